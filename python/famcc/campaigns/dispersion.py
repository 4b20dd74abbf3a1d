"""Dispersion: the distributions a campaign draws its cases from."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from famcc.plants.base import is_real as _is_number


class Distribution:
    """Base class of the dispersions: ``sample(rng, n)`` returns ``n`` floats."""

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """``n`` independent draws from ``rng``."""
        raise NotImplementedError

    def describe(self) -> str:
        """The distribution in a few words, for reports."""
        raise NotImplementedError

    def __repr__(self) -> str:
        return self.describe()


def _finite(label: str, value: Any) -> float:
    if not _is_number(value) or not math.isfinite(value):
        raise ValueError(f"{label} must be a finite number, got {value!r}")
    return float(value)


class Uniform(Distribution):
    """Uniform on ``[lo, hi)``.

    >>> import numpy as np
    >>> d = Uniform(1.0, 2.0)
    >>> x = d.sample(np.random.default_rng(0), 1000)
    >>> bool(x.min() >= 1.0 and x.max() < 2.0), d
    (True, uniform(1, 2))
    """

    def __init__(self, lo: float, hi: float) -> None:
        self.lo, self.hi = _finite("lo", lo), _finite("hi", hi)
        if not self.lo <= self.hi:
            raise ValueError(f"uniform needs lo <= hi, got ({lo!r}, {hi!r})")

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        return rng.uniform(self.lo, self.hi, size=n)

    def describe(self) -> str:
        return f"uniform({self.lo:g}, {self.hi:g})"


class LogUniform(Distribution):
    """Log-uniform on ``[lo, hi)``, ``0 < lo <= hi`` (a scale factor over decades).

    >>> import numpy as np
    >>> x = LogUniform(0.1, 10.0).sample(np.random.default_rng(0), 1000)
    >>> bool(0.1 <= x.min() and x.max() < 10.0)
    True
    """

    def __init__(self, lo: float, hi: float) -> None:
        self.lo, self.hi = _finite("lo", lo), _finite("hi", hi)
        if not 0 < self.lo <= self.hi:
            raise ValueError(f"loguniform needs 0 < lo <= hi, got ({lo!r}, {hi!r})")

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        return np.exp(rng.uniform(math.log(self.lo), math.log(self.hi), size=n))

    def describe(self) -> str:
        return f"loguniform({self.lo:g}, {self.hi:g})"


class Normal(Distribution):
    """Normal with mean and standard deviation, optionally clipped to ``[lo, hi]``.

    >>> import numpy as np
    >>> x = Normal(1.0, 0.1, lo=0.8).sample(np.random.default_rng(0), 1000)
    >>> bool(x.min() >= 0.8), round(float(np.median(x)), 1)
    (True, 1.0)
    """

    def __init__(
        self, mean: float, std: float, lo: float | None = None, hi: float | None = None
    ) -> None:
        self.mean, self.std = _finite("mean", mean), _finite("std", std)
        if self.std < 0:
            raise ValueError(f"normal needs std >= 0, got {std!r}")
        self.lo = None if lo is None else _finite("lo", lo)
        self.hi = None if hi is None else _finite("hi", hi)

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        x = rng.normal(self.mean, self.std, size=n)
        if self.lo is not None or self.hi is not None:
            x = np.clip(x, self.lo, self.hi)
        return x

    def describe(self) -> str:
        clip = ""
        if self.lo is not None or self.hi is not None:
            clip = (
                f", clipped to [{self.lo if self.lo is not None else '-inf'}, "
                f"{self.hi if self.hi is not None else 'inf'}]"
            )
        return f"normal({self.mean:g}, {self.std:g}{clip})"


class Choice(Distribution):
    """One of a few values, equally likely (or with ``weights``).

    Controller settings are best dispersed this way: a chunk steps one
    :class:`famcc.ControllerBank` per distinct setting.

    >>> import numpy as np
    >>> sorted(set(Choice([20.0, 30.0]).sample(np.random.default_rng(0), 50).tolist()))
    [20.0, 30.0]
    """

    def __init__(self, values: Sequence[float], weights: Sequence[float] | None = None) -> None:
        self.values = [_finite("choice value", v) for v in values]
        if not self.values:
            raise ValueError("choice needs at least one value")
        if weights is not None:
            w = np.array([_finite("weight", v) for v in weights])
            if w.shape != (len(self.values),) or np.any(w < 0) or not w.sum() > 0:
                raise ValueError("choice weights must be one non-negative number per value")
            self.weights: np.ndarray | None = w / w.sum()
        else:
            self.weights = None

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        return rng.choice(np.array(self.values), size=n, p=self.weights)

    def describe(self) -> str:
        return "choice(" + ", ".join(f"{v:g}" for v in self.values) + ")"


class Fixed(Distribution):
    """Always the same value."""

    def __init__(self, value: float) -> None:
        self.value = _finite("value", value)

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        return np.full(n, self.value)

    def describe(self) -> str:
        return f"{self.value:g}"


def distribution(spec: Any) -> Distribution:
    """A distribution from a number or a one-key table (as in a campaign's TOML).

    ``{uniform = [lo, hi]}``, ``{loguniform = [lo, hi]}``, ``{normal = [mean,
    std]}`` (optional ``lo``, ``hi``), ``{choice = [v1, v2, ...]}`` (optional
    ``weights``) or a plain number (fixed).

    >>> distribution({"uniform": [0.5, 1.5]}), distribution(2.0)
    (uniform(0.5, 1.5), 2)
    >>> distribution({"normal": [1.0, 0.1], "lo": 0.5})
    normal(1, 0.1, clipped to [0.5, inf])
    """
    if isinstance(spec, Distribution):
        return spec
    if _is_number(spec):
        return Fixed(spec)
    if isinstance(spec, Mapping):
        rest = dict(spec)
        kinds = [k for k in ("uniform", "loguniform", "normal", "choice") if k in rest]
        if len(kinds) == 1:
            kind = kinds[0]
            args = rest.pop(kind)
            try:
                if kind == "choice":
                    return Choice(args, rest.pop("weights", None))
                if kind == "normal":
                    mean, std = args
                    dist: Distribution = Normal(
                        mean, std, rest.pop("lo", None), rest.pop("hi", None)
                    )
                else:
                    lo, hi = args
                    dist = Uniform(lo, hi) if kind == "uniform" else LogUniform(lo, hi)
            except (TypeError, ValueError) as exc:
                raise ValueError(f"bad {kind} distribution {spec!r}: {exc}") from exc
            if rest:
                raise ValueError(f"unknown keys {sorted(rest)} in the distribution {spec!r}")
            return dist
    raise ValueError(
        f"a dispersion must be a number or a table with one of uniform, loguniform, normal, "
        f"choice (e.g. {{uniform = [0.8, 1.2]}}), got {spec!r}"
    )
