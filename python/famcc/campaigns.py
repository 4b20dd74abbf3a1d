"""Monte Carlo robustness campaigns: thousands of dispersed plants, in lockstep.

:func:`campaign` draws ``cases`` random members of a plant family
(:class:`famcc.plants.Family`), initial states, references, sensor noise and,
optionally, controller settings; it integrates them in chunks, each chunk a
:class:`famcc.ControllerBank` and a vectorised RK4 with exactly the
sample-and-hold of :func:`famcc.simulate`, on the local cores, any
:class:`concurrent.futures.Executor` or a Dask cluster. The
:class:`CampaignResult` holds one row per case and judges each case on the
claims a run can fail (docs/design.md §8): ``settled`` (within the deadline),
``bounded`` (did not diverge), ``nominal`` (no flexible expansion while the
actuator had headroom) and ``unsaturated``; it gives the success rates with
Clopper-Pearson intervals, the worst cases, figures and a report, and
:meth:`CampaignResult.case` rebuilds any case for :func:`famcc.simulate`.

Semantics, per case and sample ``t_k = k dt`` (``k = 0..K-1``, ``K = round(t_end
/ dt) + 1``), the same as :func:`famcc.simulate`: the controller reads ``e_k =
y(t_k) - y_d(t_k)`` (plus the sensor noise ``n_k``, when there is noise), returns
``v_k``; ``u_k = clip(v_k, u_limits)`` is held over ``[t_k, t_k + dt)`` while
the plant is integrated with ``substeps`` classical RK4 steps. Metrics use the
true error ``z1 = y - y_d``, never the noisy measurement.

Examples
--------
>>> import famcc
>>> from famcc.campaigns import Uniform, campaign
>>> ctrl = famcc.scenarios.paper("finite-time").controller()
>>> res = campaign("second-order", ctrl, cases=40, t_end=4.0, u_limits=(-100, 100),
...                reference=famcc.Sine(), eps=0.1, settle_by="bound",
...                dispersion={"gain": Uniform(0.7, 1.3), "x1(0)": Uniform(-1.5, 0.5)},
...                executor="serial", chunk_size=20, progress=False)
>>> res.rate("settled").tested, res.rate("bounded").held
(40, 40)
>>> row = res.row(3)
>>> sim = res.case(3).simulate()
>>> sim.settling_time(0.1) == row["settling_time"], sim.saturated_fraction == row["saturated_fraction"]
(True, True)
"""

from __future__ import annotations

import concurrent.futures as cf
import ctypes
import hashlib
import importlib
import json
import math
import os
import sys
import time
import zlib
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from famcc.families import Family, family
from famcc.simulation import Constant, Sine, _as_float, _is_number
from famcc.verdicts import STARTUP

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "CRITERIA",
    "Campaign",
    "CampaignResult",
    "Case",
    "Choice",
    "LogUniform",
    "Normal",
    "Rate",
    "Uniform",
    "beta_ppf",
    "campaign",
    "clopper_pearson",
    "load_spec",
]

#: The criteria every case is judged on, in the order reports list them.
CRITERIA = ("settled", "bounded", "nominal", "unsaturated")

#: Default state bound: a case whose ``|x_i|`` exceeds it counts as diverged.
STATE_BOUND = 1e6

_REFERENCE_KEYS = {"sine": ("amplitude", "omega", "phase"), "constant": ("value",)}
_CONTROLLER_KEYS = ("eps", "k_u", "settle_time", "k0", "rho_e")


# ---------------------------------------------------------------------------
# distributions
# ---------------------------------------------------------------------------


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


# ---------------------------------------------------------------------------
# Clopper-Pearson intervals: the beta quantile, without scipy
# ---------------------------------------------------------------------------


def _betacf(a: float, b: float, x: float) -> float:
    """Continued fraction of the incomplete beta function (modified Lentz)."""
    tiny, eps = 1e-300, 1e-16
    qab, qap, qam = a + b, a + 1.0, a - 1.0
    c, d = 1.0, 1.0 - qab * x / qap
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 10000):
        m2 = 2 * m
        aa = m * (b - m) * x / ((qam + m2) * (a + m2))
        d = 1.0 + aa * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + aa / c
        c = c if abs(c) > tiny else tiny
        h *= d * c
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2))
        d = 1.0 + aa * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + aa / c
        c = c if abs(c) > tiny else tiny
        delta = d * c
        h *= delta
        if abs(delta - 1.0) < eps:
            break
    return h


def beta_cdf(x: float, a: float, b: float) -> float:
    """The regularized incomplete beta function ``I_x(a, b)``, ``a, b > 0``.

    >>> round(beta_cdf(0.5, 2.0, 2.0), 12), round(beta_cdf(0.3, 1.0, 1.0), 12)
    (0.5, 0.3)
    """
    if not (a > 0 and b > 0):
        raise ValueError(f"a and b must be > 0, got {a!r}, {b!r}")
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    front = math.exp(
        math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log1p(-x)
    )
    if x < (a + 1.0) / (a + b + 2.0):
        return front * _betacf(a, b, x) / a
    return 1.0 - front * _betacf(b, a, 1.0 - x) / b


def beta_ppf(q: float, a: float, b: float) -> float:
    """The quantile of the Beta(a, b) distribution: ``x`` with ``I_x(a, b) = q``.

    Bisection on :func:`beta_cdf` (monotone), to about 1e-15 in ``x``.

    >>> round(beta_ppf(0.5, 2.0, 2.0), 12), round(beta_ppf(0.975, 1.0, 10.0), 6)
    (0.5, 0.308497)
    """
    if not 0.0 <= q <= 1.0:
        raise ValueError(f"q must lie in [0, 1], got {q!r}")
    if q == 0.0:
        return 0.0
    if q == 1.0:
        return 1.0
    lo, hi = 0.0, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if beta_cdf(mid, a, b) < q:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-15:
            break
    return 0.5 * (lo + hi)


def clopper_pearson(k: int, n: int, confidence: float = 0.95) -> tuple[float, float]:
    """The exact (Clopper-Pearson) interval of a binomial proportion ``k / n``.

    ``lo = B(alpha/2; k, n - k + 1)`` (0 when ``k = 0``), ``hi = B(1 - alpha/2;
    k + 1, n - k)`` (1 when ``k = n``), ``B`` the beta quantile; it covers the
    true rate with probability at least ``confidence``.

    >>> [round(v, 4) for v in clopper_pearson(5, 10)]
    [0.1871, 0.8129]
    >>> [round(v, 5) for v in clopper_pearson(0, 100)]       # 1 - 0.025**(1/100)
    [0.0, 0.03622]
    """
    if not (isinstance(n, (int, np.integer)) and isinstance(k, (int, np.integer))):
        raise ValueError(f"k and n must be integers, got {k!r}, {n!r}")  # noqa: TRY004
    if n < 1 or not 0 <= k <= n:
        raise ValueError(f"need n >= 1 and 0 <= k <= n, got k = {k}, n = {n}")
    if not 0 < confidence < 1:
        raise ValueError(f"confidence must lie in (0, 1), got {confidence!r}")
    alpha = 1.0 - confidence
    lo = 0.0 if k == 0 else beta_ppf(alpha / 2, k, n - k + 1)
    hi = 1.0 if k == n else beta_ppf(1 - alpha / 2, k + 1, n - k)
    return lo, hi


@dataclass(frozen=True)
class Rate:
    """How many cases held a criterion, with a Clopper-Pearson interval.

    Attributes
    ----------
    name : str
        The criterion.
    held, failed, untested : int
        Case counts; untested cases (the claim could not be decided, e.g. its
        deadline lies beyond the horizon) count neither way.
    lo, hi : float
        The interval of the success rate ``held / (held + failed)`` (NaN when no
        case was tested).
    confidence : float
    """

    name: str
    held: int
    failed: int
    untested: int
    lo: float
    hi: float
    confidence: float = 0.95

    @property
    def tested(self) -> int:
        """``held + failed``."""
        return self.held + self.failed

    @property
    def rate(self) -> float:
        """``held / tested`` (NaN when nothing was tested)."""
        return self.held / self.tested if self.tested else math.nan

    def text(self) -> str:
        """One line: ``"settled: 9,812 of 10,000 (98.12 %, 95 % CI 97.85-98.37 %)"``."""
        if not self.tested:
            return f"{self.name}: untested ({self.untested:,} cases could not decide it)"
        tail = f"; {self.untested:,} untested" if self.untested else ""
        return (
            f"{self.name}: {self.held:,} of {self.tested:,} ({_pct(self.rate)}, "
            f"{100 * self.confidence:g} % CI {_pct(self.lo, False)}-{_pct(self.hi)}){tail}"
        )


def _pct(v: float, unit: bool = True) -> str:
    """``0.98123 -> "98.12 %"``; tiny non-zero values keep two significant digits."""
    if not math.isfinite(v):
        return "-"
    p = 100 * v
    text = f"{p:.2f}" if p == 0 or abs(p) >= 0.01 else f"{p:.2g}"
    return text + (" %" if unit else "")


def _rate(name: str, status: np.ndarray, confidence: float) -> Rate:
    held = int(np.sum(status == 1))
    failed = int(np.sum(status == 0))
    untested = int(np.sum(status == -1))
    if held + failed:
        lo, hi = clopper_pearson(held, held + failed, confidence)
    else:
        lo = hi = math.nan
    return Rate(name, held, failed, untested, lo, hi, confidence)


# ---------------------------------------------------------------------------
# counter-based sensor noise: the same numbers for a case in any chunk
# ---------------------------------------------------------------------------

_MASK = (1 << 64) - 1
_GOLDEN = 0x9E3779B97F4A7C15


def _mix(z: np.ndarray) -> np.ndarray:
    """SplitMix64's finaliser on uint64 arrays (wrapping arithmetic)."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    out: np.ndarray = z ^ (z >> np.uint64(31))
    return out


def noise_keys(seed: int, cases: np.ndarray) -> np.ndarray:
    """One 64-bit noise key per case index, from the campaign's seed."""
    base = np.uint64((seed * _GOLDEN + 0x632BE59BD9B4E019) & _MASK)
    with np.errstate(over="ignore"):
        return _mix(np.asarray(cases, dtype=np.uint64) * np.uint64(_GOLDEN) + base)


def standard_normal(keys: np.ndarray, k: int) -> np.ndarray:
    """Standard normal draws for sample ``k``, one per key (Box-Muller on hashes).

    A pure function of the key and ``k``: a case's noise does not depend on
    the chunk it runs in, the executor or the other cases.

    >>> import numpy as np
    >>> z = standard_normal(noise_keys(1, np.arange(20000)), 7)
    >>> round(float(z.mean()), 1), round(float(z.std()), 1)
    (0.0, 1.0)
    """
    c1 = np.uint64(((2 * k + 1) * _GOLDEN) & _MASK)
    c2 = np.uint64(((2 * k + 2) * _GOLDEN) & _MASK)
    h1 = _mix(keys ^ c1)
    h2 = _mix(keys ^ c2)
    u1 = ((h1 >> np.uint64(11)).astype(np.float64) + 1.0) * 2.0**-53
    u2 = (h2 >> np.uint64(11)).astype(np.float64) * 2.0**-53
    return np.sqrt(-2.0 * np.log(u1)) * np.cos(2.0 * math.pi * u2)


class NoisySensor:
    """A controller that reads ``e + sigma n_k``: a case's sensor noise, for :func:`simulate`.

    ``n_k`` are the campaign's draws for the case (:func:`standard_normal` of its
    key and the sample index), so :func:`famcc.simulate` with this wrapper
    feeds the controller exactly what the campaign fed it. Diagnostics and
    configuration are the wrapped controller's.
    """

    def __init__(self, controller: Any, sigma: float, key: int) -> None:
        self.controller = controller
        self.sigma = float(sigma)
        self.key = int(key)
        self._keys = np.array([self.key], dtype=np.uint64)
        self._k = 0

    @property
    def dt(self) -> float:
        """The controller's sample period."""
        return float(self.controller.dt)

    @property
    def order(self) -> int:
        """The controller's order."""
        return int(self.controller.order)

    @property
    def diagnostics(self) -> Any:
        """The controller's diagnostics."""
        return self.controller.diagnostics

    def config(self) -> dict[str, Any]:
        """The controller's configuration."""
        return dict(self.controller.config())

    def step(self, e: float, applied: float | None = None) -> float:
        """Steps the controller with the noisy measurement."""
        n = float(self.sigma * standard_normal(self._keys, self._k)[0])
        self._k += 1
        return float(self.controller.step(e + n, applied=applied))

    def __repr__(self) -> str:
        return f"NoisySensor(sigma={self.sigma:g}, key={self.key}) -> {self.controller!r}"


# ---------------------------------------------------------------------------
# the work of one chunk (runs on a worker)
# ---------------------------------------------------------------------------


@dataclass
class _Chunk:
    """Everything a worker needs for cases ``start .. stop - 1``."""

    start: int
    stop: int
    family: Family
    controller: dict[str, Any]
    values: dict[str, np.ndarray]
    dt: float
    steps: int
    substeps: int
    u_limits: tuple[float, float] | None
    eps: float
    reference: str
    reference_params: dict[str, float]
    state_bound: float
    noise_seed: int


def _controller(config: Mapping[str, Any], overrides: Mapping[str, float]) -> Any:
    import famcc

    kw = dict(config)
    order, dt = kw.pop("order"), kw.pop("dt")
    kw.update(overrides)
    return famcc.Controller(order, dt, **kw)


def _stack(out: Any, shape: tuple[int, int]) -> np.ndarray:
    """A right-hand side's value as an ``(n, N)`` float64 array (entries may be scalars)."""
    if isinstance(out, np.ndarray) and out.shape == shape and out.dtype == np.float64:
        return out
    try:
        arr = np.asarray(out, dtype=np.float64)
    except ValueError:  # ragged: some entries are scalars
        arr = np.empty(0)
    if arr.shape == shape:
        return arr
    if len(out) != shape[0]:
        raise ValueError(f"the family's rhs must return {shape[0]} rows, got {len(out)}")
    return np.array([np.broadcast_to(np.asarray(c, dtype=np.float64), shape[1:]) for c in out])


_MALLOC_TUNED = False


def _roomy_malloc() -> None:
    """Undo, in a Dask worker, the nanny's ``MALLOC_TRIM_THRESHOLD_`` for this process.

    Dask's nanny starts its workers with ``MALLOC_TRIM_THRESHOLD_=65536``, which
    also fixes glibc's mmap threshold at 128 KiB: every temporary array of a
    chunk (80-320 KiB) then costs an mmap, a munmap and its page faults, and
    a chunk ran 1.3-2x slower than in a plain process (benches/README.md,
    "Campaign"). This sets the trim threshold to 64 MiB and the mmap threshold to
    16 MiB in the worker, once, on Linux with glibc; elsewhere it does nothing.
    """
    global _MALLOC_TUNED
    if _MALLOC_TUNED:
        return
    _MALLOC_TUNED = True
    if not sys.platform.startswith("linux") or "MALLOC_TRIM_THRESHOLD_" not in os.environ:
        return
    worker = sys.modules.get("distributed")
    try:
        if worker is None or worker.get_worker() is None:
            return
    except ValueError:  # not inside a Dask worker
        return
    try:
        libc = ctypes.CDLL("libc.so.6")
        libc.mallopt(-1, 64 << 20)  # M_TRIM_THRESHOLD
        libc.mallopt(-3, 16 << 20)  # M_MMAP_THRESHOLD
    except (OSError, AttributeError):
        return


def run_chunk(chunk: _Chunk) -> dict[str, np.ndarray]:
    """Integrates one chunk in lockstep; returns its raw per-case counters.

    Public for executors that need an importable function; call
    :func:`campaign` instead.
    """
    import famcc

    _roomy_malloc()
    started = time.perf_counter()
    m = chunk.stop - chunk.start
    n = chunk.family.order
    values = chunk.values
    params = chunk.family.full_params({k: v for k, v in values.items() if k in chunk.family.params})
    x = np.empty((n, m))
    nominal_x0 = chunk.family.x0
    for i in range(n):
        x[i] = values.get(f"x{i + 1}(0)", nominal_x0[i])

    # one bank per distinct controller setting in the chunk
    ckeys = [k for k in values if k.startswith("controller.")]
    groups: list[tuple[Any, np.ndarray | None]] = []
    if ckeys:
        table = np.column_stack([values[k] for k in ckeys])
        uniq, inverse = np.unique(table, axis=0, return_inverse=True)
        inverse = np.asarray(inverse).reshape(-1)
        for g, row in enumerate(uniq):
            idx = np.flatnonzero(inverse == g)
            over = {k.split(".", 1)[1]: float(v) for k, v in zip(ckeys, row)}
            ctrl = _controller(chunk.controller, over)
            groups.append((famcc.ControllerBank(ctrl, len(idx)), idx))
        if len(groups) == 1:
            groups = [(groups[0][0], None)]
    else:
        groups.append((famcc.ControllerBank(_controller(chunk.controller, {}), m), None))
    has_diag = all(hasattr(b, "xi_nominal") and hasattr(b, "expansion") for b, _ in groups)

    # reference: per-case arrays where dispersed, else the nominal object
    rkind = chunk.reference
    ref_vals: dict[str, Any] = dict(chunk.reference_params)
    ref_vals.update(
        {k.split(".", 1)[1]: v for k, v in values.items() if k.startswith("reference.")}
    )
    sigma = values.get("noise.sigma")
    keys = noise_keys(chunk.noise_seed, np.arange(chunk.start, chunk.stop))

    K = chunk.steps + 1
    dt, lims, eps = chunk.dt, chunk.u_limits, chunk.eps
    h = dt / chunk.substeps
    half = 0.5 * h
    sixth = h / 6.0
    rhs = chunk.family._rhs
    shape = (n, m)

    last_out = np.full(m, -1, dtype=np.int64)
    first_in = np.full(m, -1, dtype=np.int64)
    last_sat = np.full(m, -1, dtype=np.int64)
    sat_count = np.zeros(m, dtype=np.int64)
    sat_late = np.zeros(m, dtype=np.int64)
    exp_unsat = np.zeros(m, dtype=np.int64)
    exp_unsat_late = np.zeros(m, dtype=np.int64)
    max_xi_nom = np.zeros(m) if has_diag else np.full(m, np.nan)
    diverged_at = np.full(m, -1, dtype=np.int64)
    alive = np.ones(m, dtype=bool)
    any_dead = False
    pending_first = m
    frozen: dict[str, np.ndarray] = {}
    counters = {
        "last_out": last_out,
        "first_in": first_in,
        "last_sat": last_sat,
        "sat_count": sat_count,
        "sat_late": sat_late,
        "exp_unsat": exp_unsat,
        "exp_unsat_late": exp_unsat_late,
        "max_xi_nominal": max_xi_nom,
    }
    v = np.empty(m)
    xin = np.empty(m)
    fac = np.empty(m)
    overflows = 0
    amp: Any = ref_vals.get("amplitude")
    omega: Any = ref_vals.get("omega")
    phase: Any = ref_vals.get("phase")
    const: Any = ref_vals.get("value")

    with np.errstate(all="ignore"):
        for k in range(K):
            t = k * dt
            if rkind == "sine":
                yd: Any = amp * np.sin(omega * t + phase)
            else:
                yd = const
            e = x[0] - yd
            a = np.abs(e)
            np.copyto(last_out, k, where=~(a < eps))
            if pending_first:
                newly = (a < eps) & (first_in < 0)
                if newly.any():
                    first_in[newly] = k
                    pending_first -= int(newly.sum())
            if sigma is not None:
                e = e + sigma * standard_normal(keys, k)
            if any_dead:
                e = np.where(alive, e, 0.0)
            e = np.ascontiguousarray(e, dtype=np.float64)
            for bank, lanes in groups:
                if lanes is None:
                    v = bank.step(e)
                    overflows += bank.overflows
                    if has_diag:
                        xin = bank.xi_nominal
                        fac = bank.expansion
                else:
                    v[lanes] = bank.step(np.ascontiguousarray(e[lanes]))
                    overflows += bank.overflows
                    if has_diag:
                        xin[lanes] = bank.xi_nominal
                        fac[lanes] = bank.expansion
            if lims is not None:
                sat = (v < lims[0]) | (v > lims[1])
                u = np.minimum(np.maximum(v, lims[0]), lims[1])
                sat_count += sat
                np.copyto(last_sat, k, where=sat)
                if t >= STARTUP:
                    sat_late += sat
            else:
                sat = None
                u = v
            if has_diag:
                np.maximum(max_xi_nom, np.abs(xin), out=max_xi_nom)
                expd = fac > 1.0
                if sat is not None:
                    expd &= ~sat
                exp_unsat += expd
                if t >= STARTUP:
                    exp_unsat_late += expd
            if k == K - 1:
                break
            for j in range(chunk.substeps):
                tj = t + j * h
                k1 = _stack(rhs(tj, x, u, params), shape)
                k2 = _stack(rhs(tj + half, x + half * k1, u, params), shape)
                k3 = _stack(rhs(tj + half, x + half * k2, u, params), shape)
                k4 = _stack(rhs(tj + h, x + h * k3, u, params), shape)
                x = x + sixth * (k1 + 2.0 * (k2 + k3) + k4)
            bad = ~np.all(np.abs(x) <= chunk.state_bound, axis=0)
            if any_dead:
                bad &= alive
            if bad.any():
                idx_bad = np.flatnonzero(bad)
                for name, arr in counters.items():
                    frozen.setdefault(name, arr.copy())[idx_bad] = arr[idx_bad]
                diverged_at[idx_bad] = k + 1
                alive[idx_bad] = False
                any_dead = True
                x[:, idx_bad] = 0.0
    dead = ~alive
    out = {
        name: np.where(dead, frozen[name], arr) if name in frozen else arr
        for name, arr in counters.items()
    }
    out["diverged_at"] = diverged_at
    out["overflows"] = np.array([overflows])
    out["has_diagnostics"] = np.array([has_diag])
    out["seconds"] = np.array([time.perf_counter() - started])
    return out


# ---------------------------------------------------------------------------
# the campaign
# ---------------------------------------------------------------------------


@dataclass
class Campaign:
    """A campaign's configuration (what :func:`campaign` runs; rebuilds any case).

    Attributes are the arguments of :func:`campaign`, resolved: the family, the
    controller's configuration, the dispersions, the per-case values drawn from
    them (``values``, one array per dispersed key), and the numbers.
    """

    family: Family
    controller: dict[str, Any]
    cases: int
    t_end: float
    dt: float
    steps: int
    substeps: int
    u_limits: tuple[float, float] | None
    eps: float
    settle_by: Any
    reference: Any
    noise: float
    dispersion: dict[str, Distribution]
    seed: int
    chunk_size: int
    state_bound: float
    require: tuple[str, ...]
    confidence: float
    name: str
    values: dict[str, np.ndarray] = field(repr=False)

    @property
    def reference_kind(self) -> str:
        """``"sine"`` or ``"constant"``."""
        return "sine" if isinstance(self.reference, Sine) else "constant"

    def fingerprint(self) -> str:
        """A hash of everything that decides the per-case results (for resuming)."""
        import famcc

        cfg = {k: repr(v) for k, v in self.controller.items()}
        doc = {
            "famcc": famcc.__version__,
            "family": self.family.name,
            "order": self.family.order,
            "params": self.family.params,
            "x0": self.family.x0.tolist(),
            "controller": cfg,
            "cases": self.cases,
            "dt": self.dt,
            "steps": self.steps,
            "substeps": self.substeps,
            "u_limits": self.u_limits,
            "eps": self.eps,
            "reference": repr(self.reference),
            "noise": self.noise,
            "seed": self.seed,
            "chunk_size": self.chunk_size,
            "state_bound": self.state_bound,
            "dispersion": {k: d.describe() for k, d in self.dispersion.items()},
        }
        text = json.dumps(doc, sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    def chunks(self) -> Iterator[tuple[int, int]]:
        """``(start, stop)`` of every chunk."""
        for a in range(0, self.cases, self.chunk_size):
            yield a, min(a + self.chunk_size, self.cases)

    def chunk(self, start: int, stop: int) -> _Chunk:
        """The work of cases ``start .. stop - 1``."""
        vals = {k: np.ascontiguousarray(v[start:stop]) for k, v in self.values.items()}
        if self.noise > 0 and "noise.sigma" not in vals:
            vals["noise.sigma"] = np.full(stop - start, self.noise)
        ref = self.reference
        rpar = (
            {"amplitude": ref.amplitude, "omega": ref.omega, "phase": ref.phase}
            if isinstance(ref, Sine)
            else {"value": ref.value}
        )
        return _Chunk(
            start,
            stop,
            self.family,
            self.controller,
            vals,
            self.dt,
            self.steps,
            self.substeps,
            self.u_limits,
            self.eps,
            self.reference_kind,
            rpar,
            self.state_bound,
            self.seed,
        )


def _draw(dispersion: Mapping[str, Distribution], seed: int, cases: int) -> dict[str, np.ndarray]:
    """Per-key draws: key ``name`` uses the generator seeded by ``(seed, crc32(name))``.

    Each key's draws are independent of the other keys and of their order, and
    the first ``n`` cases are the same for every ``cases >= n``.
    """
    out = {}
    for key, dist in dispersion.items():
        rng = np.random.default_rng([seed, zlib.crc32(key.encode())])
        out[key] = np.asarray(dist.sample(rng, cases), dtype=np.float64)
        if out[key].shape != (cases,) or not np.all(np.isfinite(out[key])):
            raise ValueError(f"the dispersion of {key!r} gave non-finite or misshaped draws")
    return out


def _resolve_family(fam: Any, variant: str | None) -> Family:
    if isinstance(fam, Family):
        if variant is not None:
            raise ValueError("variant only applies to a family given by name")
        return fam
    if isinstance(fam, str):
        return family(fam, variant)
    raise ValueError(
        f"family must be a famcc.plants.Family or a name such as 'second-order', got {fam!r}"
    )


def _resolve_controller(controller: Any) -> dict[str, Any]:
    if hasattr(controller, "config") and hasattr(controller, "step"):
        ctrl = controller
    elif callable(getattr(controller, "controller", None)):
        ctrl = controller.controller()  # a famcc.Design, or anything that builds one
    else:
        raise ValueError(
            "controller must be a famcc.Controller or an object whose controller() builds "
            f"one (a famcc.Design), got {controller!r}"
        )
    cfg = ctrl.config()
    if not isinstance(cfg, dict) or "order" not in cfg or "dt" not in cfg:
        raise ValueError("controller.config() must give the famcc.Controller configuration")
    return dict(cfg)


def _check_keys(fam: Family, dispersion: Mapping[str, Any], reference: Any) -> None:
    kind = "sine" if isinstance(reference, Sine) else "constant"
    states = {f"x{i + 1}(0)" for i in range(fam.order)}
    for key in dispersion:
        if key in fam.params or key in states or key == "noise.sigma":
            continue
        head, _, tail = key.partition(".")
        if head == "reference" and tail in _REFERENCE_KEYS[kind]:
            continue
        if head == "controller" and tail in _CONTROLLER_KEYS:
            continue
        raise ValueError(
            f"unknown dispersion key {key!r}: use a parameter of {fam.name} "
            f"({', '.join(fam.params) or 'none'}), an initial state "
            f"({', '.join(sorted(states))}), reference.{' / reference.'.join(_REFERENCE_KEYS[kind])}"
            f", noise.sigma or controller.{' / controller.'.join(_CONTROLLER_KEYS)}"
        )


def campaign(
    family: Family | str,
    controller: Any,
    *,
    cases: int,
    t_end: float,
    reference: Sine | Constant,
    u_limits: Sequence[float] | None = None,
    dispersion: Mapping[str, Any] | None = None,
    eps: float | None = None,
    settle_by: float | str | None = None,
    substeps: int = 1,
    noise: float = 0.0,
    seed: int = 0,
    chunk_size: int = 2000,
    executor: Any = None,
    jobs: int | None = None,
    out: str | Path | None = None,
    progress: Any = True,
    state_bound: float = STATE_BOUND,
    require: Sequence[str] = ("settled", "bounded"),
    confidence: float = 0.95,
    variant: str | None = None,
    name: str = "campaign",
) -> CampaignResult:
    """Run a Monte Carlo robustness campaign; returns a :class:`CampaignResult`.

    Parameters
    ----------
    family : famcc.plants.Family or str
        The plant family, or the name of a ready-made one
        (:func:`famcc.families.names`).
    controller : famcc.Controller or object with ``controller()``
        The design: its configuration is used (every case starts from a fresh
        controller with it), its state is not. A ``famcc.Design`` works too.
    cases : int
        Number of random cases (>= 1).
    t_end : float
        Horizon, s (rounded to whole samples as in :func:`famcc.simulate`).
    reference : famcc.Sine or famcc.Constant
        The nominal reference; ``reference.amplitude``, ``reference.omega``,
        ``reference.phase`` (or ``reference.value``) can be dispersed.
    u_limits : (lo, hi), optional
        Actuator limits; None means none.
    dispersion : dict, optional
        Key -> :class:`Uniform`, :class:`Normal`, :class:`LogUniform`,
        :class:`Choice`, a number or a table (:func:`distribution`). Keys: the
        family's parameters (``"J"``, ``"gain"``), initial states ``"x1(0)"`` ..
        ``"xn(0)"``, ``"reference.amplitude"`` / ``"reference.omega"`` /
        ``"reference.phase"`` / ``"reference.value"``, ``"noise.sigma"`` and
        controller settings ``"controller.k_u"``, ``"controller.eps"``,
        ``"controller.settle_time"``, ``"controller.k0"``, ``"controller.rho_e"``
        (each distinct setting in a chunk is its own bank: prefer :class:`Choice`).
        Undispersed quantities stay nominal.
    eps : float, optional
        Accuracy of ``|z1|`` for the settling time. Default: the controller's
        preset output accuracy (:attr:`famcc.SimResult.accuracy`); a design
        that presets none needs it.
    settle_by : float, "bound" or None
        The ``settled`` criterion's deadline: seconds; ``"bound"`` for the
        paper's corollary bound ``max(T_e, T_s) + T'`` (``T_e`` the end of the
        case's last saturation episode, ``T'`` from the laws and, for the
        finite-time law, the case's ``z1(0)``); None for "settled by the end of
        the horizon". A deadline beyond the horizon leaves the case untested.
    substeps : int
        RK4 steps per sample, as :func:`famcc.simulate`'s ``substeps`` (that
        defaults to 10; at 1 kHz one step already integrates the paper's
        plants to about 1e-10, benches/README.md "Campaign").
    noise : float
        Standard deviation of white sensor noise added to the measured error
        (in the output's unit); each case draws its own sequence.
    seed : int
        Seeds every draw: the same seed gives the same cases and results on
        every executor and for every ``chunk_size``.
    chunk_size : int
        Cases integrated together by one worker (default 2000; 10^4 is the
        fastest per case, smaller chunks balance and resume better).
    executor : None, "serial", concurrent.futures.Executor, distributed.Client or str
        Where chunks run: None for a :class:`~concurrent.futures.ProcessPoolExecutor`
        on the local cores (``jobs`` workers), ``"serial"`` for this process,
        any executor, a Dask ``distributed.Client``, or a scheduler address
        (``"tcp://host:8786"``; needs ``pip install 'famcc[cluster]'``).
    jobs : int, optional
        Worker processes of the default pool (default: the CPU count).
    out : path, optional
        Folder for finished chunks (``out/chunks/``): a rerun with the same
        configuration skips them (resume after an interruption).
    progress : bool or object with ``step(label, seconds)``
        A progress bar on stderr (:class:`famcc.reporting.Progress`) by default.
    state_bound : float
        A case whose state leaves ``|x_i| <= state_bound`` (or turns non-finite)
        is diverged: it fails every criterion, and its metrics stop there.
    require : sequence of str
        The criteria whose conjunction is a case's success (:data:`CRITERIA`).
    confidence : float
        Of the Clopper-Pearson intervals.
    variant : str, optional
        The variant of a paper family given by name.
    name : str
        Label for reports.

    Returns
    -------
    CampaignResult

    Raises
    ------
    ValueError
        For a bad argument (the message names it), or an ``out`` folder that
        holds another campaign.

    Examples
    --------
    Ten DC motors with dispersed inertia and load under one design, in this
    process:

    >>> import famcc
    >>> ctrl = famcc.Controller(2, 1e-3, famcc.Linear(4.0), constraint="lateral",
    ...                         eps=0.02, k_u=20.0, settle_time=0.5)
    >>> res = campaign("dc-motor", ctrl, cases=10, t_end=2.0, u_limits=(-12.0, 12.0),
    ...                reference=famcc.Constant(0.5), settle_by=1.5, executor="serial",
    ...                dispersion={"J": Uniform(0.005, 0.02), "load": Uniform(0.0, 2.0)},
    ...                progress=False)
    >>> r = res.rate()
    >>> r.held + r.failed, r.lo <= r.rate <= r.hi
    (10, True)
    """
    fam = _resolve_family(family, variant)
    cfg = _resolve_controller(controller)
    if cfg["order"] != fam.order:
        raise ValueError(
            f"the controller's order ({cfg['order']}) must equal the family's ({fam.order})"
        )
    if not isinstance(cases, (int, np.integer)) or isinstance(cases, bool) or cases < 1:
        raise ValueError(f"cases must be an integer >= 1, got {cases!r}")
    dt = float(cfg["dt"])
    t_end = _finite("t_end", t_end)
    steps = round(t_end / dt)
    if not t_end > 0 or steps < 1:
        raise ValueError(f"t_end must be at least half a sample period dt ({dt}), got {t_end!r}")
    if not isinstance(reference, (Sine, Constant)):
        raise ValueError(  # noqa: TRY004 - bad arguments raise ValueError throughout
            "reference must be famcc.Sine(...) or famcc.Constant(...) (campaigns "
            f"disperse their parameters), got {reference!r}"
        )
    limits: tuple[float, float] | None = None
    if u_limits is not None:
        try:
            lo, hi = (float(v) for v in u_limits)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"u_limits must be None or a pair (lo, hi), got {u_limits!r}") from exc
        if not lo < hi:
            raise ValueError(f"u_limits must satisfy lo < hi, got {u_limits!r}")
        limits = (lo, hi)
    if not isinstance(substeps, (int, np.integer)) or isinstance(substeps, bool) or substeps < 1:
        raise ValueError(f"substeps must be an integer >= 1, got {substeps!r}")
    if not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"chunk_size must be an integer >= 1, got {chunk_size!r}")
    if not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    noise = _finite("noise", noise)
    if noise < 0:
        raise ValueError(f"noise must be >= 0, got {noise!r}")
    state_bound = _finite("state_bound", state_bound)
    if not state_bound > 0:
        raise ValueError(f"state_bound must be > 0, got {state_bound!r}")
    req = tuple(require)
    bad = [c for c in req if c not in CRITERIA]
    if bad or not req:
        raise ValueError(f"require must name some of {', '.join(CRITERIA)}, got {list(require)!r}")
    if eps is None:
        eps = _preset_accuracy(cfg)
        if eps is None:
            raise ValueError("this controller presets no output accuracy: pass eps=")
    eps = _finite("eps", eps)
    if not eps > 0:
        raise ValueError(f"eps must be > 0, got {eps!r}")
    if not (settle_by is None or settle_by == "bound" or _is_number(settle_by)):
        raise ValueError(f"settle_by must be seconds, 'bound' or None, got {settle_by!r}")
    if settle_by == "bound":
        _corollary_time(cfg, np.zeros(1))  # raises for a design without a bound
    disp = {str(k): distribution(v) for k, v in (dispersion or {}).items()}
    _check_keys(fam, disp, reference)
    spec = Campaign(
        family=fam,
        controller=cfg,
        cases=int(cases),
        t_end=t_end,
        dt=dt,
        steps=steps,
        substeps=int(substeps),
        u_limits=limits,
        eps=eps,
        settle_by=settle_by,
        reference=reference,
        noise=noise,
        dispersion=disp,
        seed=int(seed),
        chunk_size=int(chunk_size),
        state_bound=state_bound,
        require=req,
        confidence=float(confidence),
        name=name,
        values=_draw(disp, int(seed), int(cases)),
    )
    raw = _execute(spec, executor, jobs, None if out is None else Path(out), progress)
    return CampaignResult(spec, raw)


def _preset_accuracy(cfg: Mapping[str, Any]) -> float | None:
    order, kind = cfg.get("order"), cfg.get("constraint")
    if order == 1 or (order == 2 and kind == "lateral"):
        return _as_float(cfg.get("eps"))
    skews = cfg.get("skew")
    first = skews[0] if isinstance(skews, (list, tuple)) and skews else skews
    eps_z = getattr(first, "eps_z", None)
    return _as_float(eps_z)


def _corollary_time(cfg: Mapping[str, Any], z1_0: np.ndarray) -> np.ndarray:
    """``T'`` of the paper's corollaries for the design (per case for the finite-time law)."""
    from famcc import bounds

    laws = cfg.get("feedback") or []
    laws = list(laws) if isinstance(laws, (list, tuple)) else [laws]
    names = {type(law).__name__ for law in laws}
    if laws and names == {"FixedTime"}:
        stages = [(law.alpha, law.p, law.beta, law.q) for law in laws]
        return np.full(len(z1_0), bounds.fixed_time(stages))
    if len(laws) == 1 and names == {"VariableExponent"}:
        law = laws[0]
        return np.full(len(z1_0), bounds.variable_exponent(law.k, law.r_b, law.r_1, law.r_t))
    if len(laws) == 1 and names == {"FiniteTime"}:
        law = laws[0]
        return np.array([bounds.finite_time(law.k, law.p, float(z)) for z in z1_0])
    raise ValueError(
        "settle_by='bound' needs a design with a corollary bound (FixedTime stages, one "
        f"VariableExponent or one FiniteTime stage), got {sorted(names) or 'no laws'}: "
        "give settle_by in seconds"
    )


def _is_dask_client(obj: Any) -> bool:
    return type(obj).__module__.startswith("distributed") and hasattr(obj, "get_executor")


def _dask_client(address: str) -> Any:
    try:
        distributed: Any = importlib.import_module("distributed")
    except ImportError as exc:
        raise ImportError(
            "a Dask scheduler needs the distributed package: pip install 'famcc[cluster]'"
        ) from exc
    return distributed.Client(address)


def _progress(progress: Any, total: int, title: str) -> Any:
    if progress is True:
        from famcc.reporting import Progress

        return Progress(total, title)
    if progress in (False, None):
        return None
    if not callable(getattr(progress, "step", None)):
        raise ValueError("progress must be True, False or an object with step(label, seconds)")  # noqa: TRY004
    return progress


def _chunk_path(out: Path, start: int, stop: int) -> Path:
    return out / "chunks" / f"chunk-{start:09d}-{stop:09d}.npz"


def _execute(
    spec: Campaign, executor: Any, jobs: int | None, out: Path | None, progress: Any
) -> dict[str, np.ndarray]:
    finished: dict[tuple[int, int], dict[str, np.ndarray]] = {}
    fp = spec.fingerprint()
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        (out / "chunks").mkdir(exist_ok=True)
        meta = out / "campaign.json"
        if meta.exists():
            old = json.loads(meta.read_text()).get("fingerprint")
            if old != fp:
                raise ValueError(
                    f"{out} holds another campaign (fingerprint {old}, this one {fp}): use a "
                    "new folder, or delete that one to start afresh"
                )
        else:
            meta.write_text(
                json.dumps(
                    {"fingerprint": fp, "cases": spec.cases, "chunk_size": spec.chunk_size},
                    indent=1,
                )
                + "\n"
            )
        for a, b in spec.chunks():
            path = _chunk_path(out, a, b)
            if path.exists():
                with np.load(path) as z:
                    if str(z["fingerprint"]) == fp:
                        finished[(a, b)] = {k: z[k] for k in z.files if k != "fingerprint"}
    todo = [c for c in spec.chunks() if c not in finished]
    bar = _progress(
        progress,
        max(len(todo), 1),
        f"famcc campaign {spec.name}: {spec.cases:,} cases, {len(todo)} chunk(s) to run"
        + (f", {len(finished)} done before" if finished else ""),
    )

    def done(key: tuple[int, int], result: dict[str, np.ndarray], seconds: float) -> None:
        finished[key] = result
        if out is not None:
            path = _chunk_path(out, *key)
            tmp = path.with_name(path.name + ".tmp.npz")
            arrays: dict[str, Any] = {"fingerprint": np.array(fp), **result}
            np.savez(tmp, **arrays)
            os.replace(tmp, path)
        if bar is not None:
            bar.step(
                f"cases {key[0]}-{key[1] - 1} ({float(result['seconds'][0]):.1f} s of work"
                f"); elapsed",
                seconds,
            )

    if todo:
        own: Any = None
        pool: Any
        if executor == "serial":
            pool = None
        elif executor is None:
            pool = own = cf.ProcessPoolExecutor(max_workers=jobs or os.cpu_count() or 1)
        elif isinstance(executor, str):
            own = _dask_client(executor)
            pool = own.get_executor(pure=False)
        elif _is_dask_client(executor):
            pool = executor.get_executor(pure=False)
        elif isinstance(executor, cf.Executor):
            pool = executor
        else:
            raise ValueError(
                "executor must be None (local processes), 'serial', a concurrent.futures."
                f"Executor, a distributed.Client or a scheduler address, got {executor!r}"
            )
        try:
            if pool is None:
                for key in todo:
                    t0 = time.perf_counter()
                    done(key, run_chunk(spec.chunk(*key)), time.perf_counter() - t0)
            else:
                t0 = time.perf_counter()
                futures = {pool.submit(run_chunk, spec.chunk(*key)): key for key in todo}
                for fut in cf.as_completed(futures):
                    done(futures[fut], fut.result(), time.perf_counter() - t0)
        finally:
            if isinstance(own, cf.Executor):
                own.shutdown(cancel_futures=True)
            elif own is not None:
                own.close()  # the client we opened; the scheduler keeps running
    parts = [finished[c] for c in spec.chunks()]
    raw = {
        k: np.concatenate([p[k] for p in parts])
        for k in parts[0]
        if k not in ("overflows", "has_diagnostics", "seconds")
    }
    raw["seconds"] = np.array([sum(float(p["seconds"][0]) for p in parts if "seconds" in p)])
    raw["overflows"] = np.array([int(sum(int(p["overflows"][0]) for p in parts))])
    raw["has_diagnostics"] = np.array([all(bool(p["has_diagnostics"][0]) for p in parts)])
    return raw


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------


@dataclass
class Case:
    """One case of a campaign, rebuilt: run it with :meth:`simulate`.

    Attributes
    ----------
    index : int
    plant : famcc.plants.Plant
        The family's scalar plant with the case's parameters and initial state.
    controller : famcc.Controller or NoisySensor
        A fresh controller with the case's settings (wrapped in a
        :class:`NoisySensor` when the case has sensor noise).
    reference : famcc.Sine or famcc.Constant
    t_end : float
    u_limits : (float, float) or None
    substeps : int
    eps : float
    params : dict
        The case's dispersed values.
    """

    index: int
    plant: Any
    controller: Any
    reference: Any
    t_end: float
    u_limits: tuple[float, float] | None
    substeps: int
    eps: float
    params: dict[str, float]

    def simulate(self, **kwargs: Any) -> Any:
        """:func:`famcc.simulate` of this case (keywords go to it); a :class:`famcc.SimResult`."""
        from famcc.simulation import simulate

        kw = {"reference": self.reference, "u_limits": self.u_limits, "substeps": self.substeps}
        kw.update(kwargs)
        return simulate(self.plant, self.controller, self.t_end, **kw)


class CampaignResult:
    """The per-case results of a campaign, judged, with rates, worst cases and figures.

    Attributes
    ----------
    spec : Campaign
        The configuration (and the per-case draws).
    table : dict of str to ndarray
        One row per case: ``case``, the dispersed values (one column per key,
        plus ``noise_key`` when there is noise), ``settling_time`` (s, NaN:
        never settled), ``first_entry`` (s, NaN: never), ``deadline`` (s, NaN
        when ``settle_by`` is None), ``max_abs_xi_nominal``,
        ``expanded_unsaturated_fraction``, ``saturated_fraction``,
        ``last_saturation_end`` (s, 0 when never saturated), ``diverged``,
        ``diverged_at`` (s, NaN), one status column per criterion (1 held, 0
        failed, -1 untested) and ``success`` (the same for the ``require`` ed
        criteria together).
    overflows : int
        Steps at which a controller's law overflowed (it then held its output).
    """

    def __init__(self, spec: Campaign, raw: Mapping[str, np.ndarray]) -> None:
        self.spec = spec
        self.overflows = int(raw["overflows"][0])
        #: Seconds of work in the chunks, summed over workers (including earlier runs'
        #: chunks that a rerun skipped).
        self.work_seconds = float(raw["seconds"][0])
        self.has_diagnostics = bool(raw["has_diagnostics"][0])
        self.table = self._judge(raw)

    # -- per-case metrics and verdicts -----------------------------------------
    def _judge(self, raw: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        s = self.spec
        K = s.steps + 1
        dt = s.dt
        t_last = (K - 1) * dt
        div_at = raw["diverged_at"]
        diverged = div_at >= 0
        samples = np.where(diverged, div_at, K).astype(np.float64)
        last_out = raw["last_out"]
        settling = np.where(last_out < 0, 0.0, (last_out + 1) * dt)
        settling = np.where((last_out == K - 1) | diverged, np.nan, settling)
        first_in = raw["first_in"]
        first = np.where(first_in >= 0, first_in * dt, np.nan)
        last_sat = raw["last_sat"]
        t_e = np.where(last_sat >= 0, np.minimum(last_sat + 1, K - 1) * dt, 0.0)
        table: dict[str, np.ndarray] = {"case": np.arange(s.cases)}
        for key, vals in s.values.items():
            table[key] = vals
        if s.noise > 0 or "noise.sigma" in s.values:
            table["noise_key"] = noise_keys(s.seed, np.arange(s.cases))
        # deadline of the settled criterion
        if s.settle_by is None:
            deadline = np.full(s.cases, np.nan)
        elif s.settle_by == "bound":
            settle_time = s.values.get(
                "controller.settle_time", np.full(s.cases, float(s.controller["settle_time"]))
            )
            z1_0 = self._initial_error()
            deadline = np.maximum(t_e, settle_time) + _corollary_time(s.controller, z1_0)
        else:
            deadline = np.full(s.cases, float(s.settle_by))
        with np.errstate(invalid="ignore"):
            if s.settle_by is None:
                settled = np.where(np.isfinite(settling), 1, 0)
            else:
                ok = np.isfinite(settling) & (settling <= deadline)
                settled = np.where(deadline > t_last + 1e-9 * dt, -1, np.where(ok, 1, 0))
        settled = np.where(diverged, 0, settled)
        bounded = np.where(diverged, 0, 1)
        if self.has_diagnostics:
            nominal = np.where(diverged | (raw["exp_unsat_late"] > 0), 0, 1)
        else:
            nominal = np.full(s.cases, -1)
        if s.u_limits is None:
            unsat = np.full(s.cases, -1)
        else:
            unsat = np.where(diverged | (raw["sat_late"] > 0), 0, 1)
        status = {"settled": settled, "bounded": bounded, "nominal": nominal, "unsaturated": unsat}
        req = np.array([status[c] for c in s.require])
        success = np.where((req == 0).any(axis=0), 0, np.where((req == -1).any(axis=0), -1, 1))
        xi = raw["max_xi_nominal"] if self.has_diagnostics else np.full(s.cases, np.nan)
        frac_exp = raw["exp_unsat"] / samples if self.has_diagnostics else np.full(s.cases, np.nan)
        table.update(
            settling_time=settling,
            first_entry=first,
            deadline=deadline,
            max_abs_xi_nominal=xi,
            expanded_unsaturated_fraction=frac_exp,
            saturated_fraction=raw["sat_count"] / samples,
            last_saturation_end=t_e,
            diverged=diverged,
            diverged_at=np.where(diverged, div_at * dt, np.nan),
        )
        for c in CRITERIA:
            table[c] = status[c].astype(np.int8)
        table["success"] = success.astype(np.int8)
        return table

    def _initial_error(self) -> np.ndarray:
        s = self.spec
        x1 = s.values.get("x1(0)", np.full(s.cases, s.family.x0[0]))
        if isinstance(s.reference, Sine):
            amp = s.values.get("reference.amplitude", s.reference.amplitude)
            phase = s.values.get("reference.phase", s.reference.phase)
            omega = s.values.get("reference.omega", s.reference.omega)
            return np.asarray(x1 - amp * np.sin(omega * 0.0 + phase), dtype=np.float64)
        return np.asarray(x1 - s.values.get("reference.value", s.reference.value))

    # -- rates -------------------------------------------------------------
    @property
    def n(self) -> int:
        """Number of cases."""
        return self.spec.cases

    def rate(self, criterion: str = "success") -> Rate:
        """Held / failed / untested counts of a criterion (or ``"success"``), with its interval."""
        if criterion != "success" and criterion not in CRITERIA:
            raise ValueError(f"criterion must be 'success' or one of {CRITERIA}, got {criterion!r}")
        return _rate(criterion, self.table[criterion], self.spec.confidence)

    def rates(self) -> dict[str, Rate]:
        """:meth:`rate` of ``"success"`` and of every criterion."""
        return {c: self.rate(c) for c in ("success", *CRITERIA)}

    @property
    def failure_rate(self) -> tuple[float, float, float]:
        """``(rate, lo, hi)`` of failure among the tested cases (1 - success)."""
        r = self.rate("success")
        return 1.0 - r.rate, 1.0 - r.hi, 1.0 - r.lo

    # -- cases ---------------------------------------------------------------
    def row(self, i: int) -> dict[str, Any]:
        """Case ``i`` as a dict of plain Python values (NaN for unknown numbers)."""
        self._check_index(i)
        return {k: _plain(v[i]) for k, v in self.table.items()}

    def _check_index(self, i: int) -> None:
        if not isinstance(i, (int, np.integer)) or not 0 <= i < self.n:
            raise IndexError(f"case index must be in 0..{self.n - 1}, got {i!r}")

    def worst(self, k: int = 10) -> list[dict[str, Any]]:
        """The ``k`` worst cases, worst first, as rows (:meth:`row`).

        Diverged first (earliest first), then the failed ones, then the
        untested, then the rest; within each, never settled before settled,
        later settling first, then larger max nominal ``|xi|``.
        """
        t = self.table
        rank = np.select([t["diverged"], t["success"] == 0, t["success"] == -1], [0, 1, 2], 3)
        div = np.nan_to_num(t["diverged_at"], nan=np.inf)
        settle = np.nan_to_num(t["settling_time"], nan=np.inf)
        xi = np.nan_to_num(t["max_abs_xi_nominal"], nan=0.0)
        order = np.lexsort((-xi, -settle, div, rank))
        return [self.row(int(i)) for i in order[:k]]

    def case(self, i: int) -> Case:
        """Case ``i`` rebuilt: its plant, a fresh controller, reference and limits.

        ``result.case(i).simulate()`` runs :func:`famcc.simulate` on it and
        reproduces the case's settling time (to the sample) and saturated
        fraction: the ready-made families compute the scalar plant's
        arithmetic, and the controller is the same law. A diverged case may
        make :func:`famcc.simulate` raise where the campaign stopped counting.
        """
        self._check_index(i)
        s = self.spec
        vals = {k: float(v[i]) for k, v in s.values.items()}
        params = {k: v for k, v in vals.items() if k in s.family.params}
        x0 = s.family.x0
        for j in range(s.family.order):
            x0[j] = vals.get(f"x{j + 1}(0)", x0[j])
        plant = s.family.plant(x0=x0.tolist(), **params)
        over = {k.split(".", 1)[1]: v for k, v in vals.items() if k.startswith("controller.")}
        ctrl: Any = _controller(s.controller, over)
        sigma = vals.get("noise.sigma", s.noise)
        if sigma > 0:
            key = int(noise_keys(s.seed, np.array([i]))[0])
            ctrl = NoisySensor(ctrl, sigma, key)
        ref: Any
        if isinstance(s.reference, Sine):
            ref = Sine(
                vals.get("reference.amplitude", s.reference.amplitude),
                vals.get("reference.omega", s.reference.omega),
                vals.get("reference.phase", s.reference.phase),
            )
        else:
            ref = Constant(vals.get("reference.value", s.reference.value))
        return Case(i, plant, ctrl, ref, s.t_end, s.u_limits, s.substeps, s.eps, vals)

    # -- export --------------------------------------------------------------
    def to_dataframe(self) -> Any:
        """The table as a :class:`pandas.DataFrame` (one row per case, indexed by case).

        Raises
        ------
        ImportError
            When pandas is not installed (famcc does not require it: ``pip install pandas``).
        """
        try:
            pd: Any = importlib.import_module("pandas")
        except ImportError as exc:
            raise ImportError(
                "CampaignResult.to_dataframe() needs pandas, which famcc does not require: "
                "pip install pandas"
            ) from exc
        cols = {k: v for k, v in self.table.items() if k != "case"}
        df = pd.DataFrame(cols, index=pd.Index(self.table["case"], name="case"))
        df.attrs.update(self._meta())
        return df

    def to_parquet(self, path: str | Path) -> Path:
        """Writes the table to a Parquet file (needs pandas and pyarrow); returns the path.

        Raises
        ------
        ImportError
            When pyarrow (or pandas) is not installed: ``pip install pyarrow pandas``.
        """
        try:
            importlib.import_module("pyarrow")
        except ImportError as exc:
            raise ImportError(
                "CampaignResult.to_parquet() needs pyarrow, which famcc does not require: "
                "pip install pyarrow (and pandas)"
            ) from exc
        df = self.to_dataframe()
        df.attrs.clear()  # pyarrow stores attrs as JSON; keep the file plain
        path = Path(path)
        df.to_parquet(path)
        return path

    def to_csv(self, path: str | Path) -> Path:
        """Writes the table as CSV (no dependencies); returns the path."""
        path = Path(path)
        keys = list(self.table)
        with path.open("w") as fh:
            fh.write(",".join(keys) + "\n")
            cols = [self.table[k] for k in keys]
            for i in range(self.n):
                fh.write(",".join(_cell(c[i]) for c in cols) + "\n")
        return path

    def _meta(self) -> dict[str, Any]:
        s = self.spec
        return {
            "name": s.name,
            "family": s.family.name,
            "cases": s.cases,
            "seed": s.seed,
            "dt": s.dt,
            "t_end": s.t_end,
            "substeps": s.substeps,
            "u_limits": s.u_limits,
            "eps": s.eps,
            "settle_by": s.settle_by,
        }

    # -- text ----------------------------------------------------------------
    def summary(self) -> str:
        """A few lines: the success rate, each criterion, divergences."""
        lines = [self._headline()]
        for name, r in self.rates().items():
            if name != "success":
                lines.append("  " + r.text())
        return "\n".join(lines)

    def _headline(self) -> str:
        r = self.rate("success")
        s = self.spec
        what = " and ".join(s.require)
        if not r.tested:
            return f"{s.name}: {s.cases:,} cases; success ({what}) untested in every case"
        f, flo, fhi = self.failure_rate
        return (
            f"{s.name}: {s.cases:,} cases; success ({what}) {r.held:,} of {r.tested:,} = "
            f"{_pct(r.rate)} ({100 * r.confidence:g} % CI {_pct(r.lo, False)}-{_pct(r.hi)}); "
            f"failure rate {_pct(f)} (CI {_pct(flo, False)}-{_pct(fhi)})"
            + (f"; {r.untested:,} untested" if r.untested else "")
        )

    def __repr__(self) -> str:
        return f"<famcc.CampaignResult {self.summary()}>"

    # -- figures -------------------------------------------------------------
    def plot_distributions(self) -> Figure:
        """Histograms of the settling time and of the max nominal ``|xi|``."""
        import matplotlib.pyplot as plt
        from matplotlib.ticker import FormatStrFormatter, MaxNLocator, NullFormatter

        t = self.table
        s = self.spec
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
        ts = t["settling_time"][np.isfinite(t["settling_time"])]
        never = int(np.sum(~np.isfinite(t["settling_time"]) & ~t["diverged"]))
        div = int(np.sum(t["diverged"]))
        if ts.size:
            ax1.hist(ts, bins=min(60, max(10, int(np.sqrt(ts.size)))), color="tab:blue", alpha=0.85)
        ax1.axvline(
            float(s.controller["settle_time"]),
            color="0.3",
            ls=":",
            label=f"T_s = {float(s.controller['settle_time']):g} s",
        )
        if _is_number(s.settle_by):
            ax1.axvline(
                float(s.settle_by),
                color="tab:red",
                ls="--",
                label=f"deadline {float(s.settle_by):g} s",
            )
        elif s.settle_by == "bound":
            d = t["deadline"]
            ax1.axvline(
                float(np.median(d)),
                color="tab:red",
                ls="--",
                label=f"deadline max(T_e, T_s) + T' (median {float(np.median(d)):.3g} s)",
            )
        ax1.set_xlabel(f"settling time to |z1| < {s.eps:g} [s]")
        ax1.set_ylabel("cases")
        ax1.set_title(
            f"settling time ({ts.size:,} settled, {never:,} never settled, {div:,} diverged)",
            fontsize=10,
        )
        ax1.legend(fontsize=8, loc="upper right")
        xi = t["max_abs_xi_nominal"]
        xi = xi[np.isfinite(xi)]
        if xi.size:
            hi = max(1.05, float(np.max(xi)))
            bins = (
                np.linspace(0.0, hi, 60)
                if hi < 3
                else np.geomspace(max(float(np.min(xi)), 1e-3), hi, 60)
            )
            ax2.hist(xi, bins=bins, color="tab:purple", alpha=0.85)
            if hi >= 3:
                ax2.set_xscale("log")
                lo_xi = float(bins[0])
                ticks = [m * 10.0**d for d in range(-3, 7) for m in (1.0, 2.0, 5.0)]
                ax2.set_xticks([v for v in ticks if lo_xi <= v <= hi])
                ax2.xaxis.set_major_formatter(FormatStrFormatter("%g"))
                ax2.xaxis.set_minor_formatter(NullFormatter())
            over = int(np.sum(xi >= 1.0))
            ax2.axvline(
                1.0, color="tab:red", ls="--", label=f"|xi| = 1 ({over:,} cases at or above)"
            )
            ax2.legend(fontsize=8, loc="upper right")
            ax2.set_title("max nominal |xi| per case (>= 1: left the nominal set)", fontsize=10)
        else:
            ax2.text(
                0.5,
                0.5,
                "nominal xi not recorded",
                ha="center",
                va="center",
                transform=ax2.transAxes,
            )
        ax2.set_xlabel("max nominal |xi| over the run")
        ax2.set_ylabel("cases")
        for ax in (ax1, ax2):
            ax.yaxis.set_major_locator(MaxNLocator(integer=True))
            ax.grid(alpha=0.3)
        fig.suptitle(self._title(), fontsize=11)
        return fig

    def _title(self) -> str:
        s = self.spec
        return f"{s.name}: {s.cases:,} cases of {s.family.name}, {s.t_end:g} s at dt = {s.dt:g} s"

    def plot_success(self, bins: int = 10) -> Figure:
        """Success rate (with Clopper-Pearson bars) against each dispersed value."""
        import matplotlib.pyplot as plt

        keys = [k for k, d in self.spec.dispersion.items() if not isinstance(d, Fixed)]
        cols = min(3, max(1, len(keys)))
        rows = max(1, math.ceil(len(keys) / cols))
        fig, axes = plt.subplots(
            rows, cols, figsize=(4.2 * cols, 3.2 * rows), layout="constrained", squeeze=False
        )
        status = self.table["success"]
        overall = self.rate("success").rate
        for ax, key in zip(axes.flat, keys):
            x = self.spec.values[key]
            tested = status >= 0
            distinct = np.unique(x)
            if distinct.size <= bins:
                centers = distinct
                which = np.searchsorted(distinct, x)
                widths = None
            else:
                edges = np.linspace(float(x.min()), float(x.max()), bins + 1)
                which = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, bins - 1)
                centers = 0.5 * (edges[:-1] + edges[1:])
                widths = edges[1] - edges[0]
            rate, lo, hi, cnt = [], [], [], []
            for b in range(len(centers)):
                sel = (which == b) & tested
                n_b = int(sel.sum())
                k_b = int((status[sel] == 1).sum())
                cnt.append(n_b)
                if n_b:
                    lo_b, hi_b = clopper_pearson(k_b, n_b, self.spec.confidence)
                    rate.append(k_b / n_b)
                    lo.append(lo_b)
                    hi.append(hi_b)
                else:
                    rate.append(np.nan)
                    lo.append(np.nan)
                    hi.append(np.nan)
            r = np.array(rate)
            yerr = np.array([r - np.array(lo), np.array(hi) - r])
            ax.errorbar(
                centers,
                100 * r,
                yerr=100 * yerr,
                fmt="o-",
                ms=4,
                capsize=3,
                color="tab:green",
                label="per bin",
            )
            if math.isfinite(overall):
                ax.axhline(
                    100 * overall, color="0.4", ls="--", lw=1, label=f"all cases {_pct(overall)}"
                )
                ax.legend(fontsize=7, loc="lower right")
            ax.set_xlabel(key + (f"  ({self.spec.dispersion[key].describe()})"), fontsize=9)
            ax.set_ylabel("success [%]")
            low = np.nanmin(100 * np.array(lo)) if np.isfinite(lo).any() else 0.0
            ax.set_ylim(max(0.0, min(90.0, low - 5.0)), 100.5)
            ax.grid(alpha=0.3)
            if widths is None:
                ax.set_xticks(centers)
        for ax in list(axes.flat)[len(keys) :]:
            ax.set_visible(False)
        if not keys:
            axes.flat[0].set_visible(True)
            axes.flat[0].text(0.5, 0.5, "nothing dispersed", ha="center", va="center")
        what = " and ".join(self.spec.require)
        fig.suptitle(
            f"{self._title()}\nsuccess ({what}) against each dispersed value, "
            f"{100 * self.spec.confidence:g} % Clopper-Pearson bars",
            fontsize=10,
        )
        return fig

    # -- report --------------------------------------------------------------
    def write(self, out: str | Path, figures: bool = True, worst: int = 10) -> Path:
        """Writes ``report.md``, ``cases.csv`` (and ``cases.parquet`` with pyarrow), figures.

        Returns the path of ``report.md``.
        """
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        s = self.spec
        self.to_csv(out / "cases.csv")
        tables = ["`cases.csv`"]
        try:
            self.to_parquet(out / "cases.parquet")
            tables.append("`cases.parquet`")
        except ImportError:
            pass
        pngs = []
        if figures:
            import matplotlib.pyplot as plt

            for fname, fig in (
                ("distributions.png", self.plot_distributions()),
                ("success.png", self.plot_success()),
            ):
                fig.savefig(out / fname, dpi=110)
                plt.close(fig)
                pngs.append(fname)
        lines = [f"# famcc campaign: {s.name}", ""]
        lines.append(f"**{self._headline()}**")
        lines += ["", "## Setup", ""]
        lines.append(
            f"- plant family: {s.family.name} ({s.family.description or 'own family'});"
            f" nominal {', '.join(f'{k} = {v:g}' for k, v in s.family.params.items())},"
            f" x(0) = {s.family.x0.tolist()}"
        )
        lines.append(f"- controller: `{_controller(s.controller, {})!r}`")
        lines.append(f"- reference: {s.reference!r}; sensor noise sigma = {s.noise:g}")
        lim = "none" if s.u_limits is None else f"[{s.u_limits[0]:g}, {s.u_limits[1]:g}]"
        lines.append(
            f"- horizon {s.t_end:g} s, dt = {s.dt:g} s ({s.steps + 1:,} samples), "
            f"{s.substeps} RK4 step(s) per sample, u limits {lim}"
        )
        lines.append(
            f"- seed {s.seed}, chunks of {s.chunk_size:,} cases; diverged: "
            f"|x_i| > {s.state_bound:g} or not finite"
        )
        if s.dispersion:
            lines += ["", "| dispersed | distribution |", "|---|---|"]
            lines += [f"| `{k}` | {d.describe()} |" for k, d in s.dispersion.items()]
        lines += ["", "## Criteria", ""]
        if s.settle_by is None:
            deadline = "by the end of the horizon"
        elif s.settle_by == "bound":
            deadline = "by the corollary bound max(T_e, T_s) + T' of each case"
        else:
            deadline = f"by {float(s.settle_by):g} s"
        lines.append(
            f"- **settled**: |z1| < {s.eps:g} for good {deadline} "
            "(untested where that lies beyond the horizon)"
        )
        lines.append("- **bounded**: the state stayed finite and within the bound")
        lines.append(
            f"- **nominal**: no flexible expansion while the actuator had headroom "
            f"after the start-up ({STARTUP:g} s); |xi~| < 1 alone proves nothing "
            "(docs/design.md §8)"
        )
        lines.append(f"- **unsaturated**: v inside the limits after the start-up ({STARTUP:g} s)")
        lines.append(f"- success: {' and '.join(s.require)}")
        lines += [
            "",
            f"| criterion | held | failed | untested | rate | {100 * s.confidence:g} % CI |",
            "|---|---|---|---|---|---|",
        ]
        for name, r in self.rates().items():
            ci = "-" if not r.tested else f"{_pct(r.lo, False)}-{_pct(r.hi)}"
            lines.append(
                f"| {name} | {r.held:,} | {r.failed:,} | {r.untested:,} | {_pct(r.rate)} | {ci} |"
            )
        t = self.table
        ts = t["settling_time"]
        fin = ts[np.isfinite(ts)]
        xi = t["max_abs_xi_nominal"]
        lines += ["", "## Distributions", ""]
        if fin.size:
            q = np.quantile(fin, [0.5, 0.95, 0.99])
            lines.append(
                f"- settling time: median {q[0]:.3g} s, 95th percentile {q[1]:.3g} s, "
                f"99th {q[2]:.3g} s, max {float(fin.max()):.3g} s "
                f"({fin.size:,} of {self.n:,} settled)"
            )
        if np.isfinite(xi).any():
            lines.append(
                f"- max nominal |xi|: median {float(np.nanmedian(xi)):.3g}, max "
                f"{float(np.nanmax(xi)):.3g}; {int(np.sum(xi >= 1)):,} cases reached 1"
            )
        lines.append(
            f"- saturated fraction: mean {float(np.mean(t['saturated_fraction'])):.3g};"
            f" diverged: {int(np.sum(t['diverged'])):,}; law overflows: "
            f"{self.overflows:,}"
        )
        if not self.has_diagnostics:
            lines.append(
                "- nominal xi and expansion not recorded: this famcc._core's "
                "ControllerBank has no xi_nominal / expansion"
            )
        for fname in pngs:
            lines += ["", f"![{fname}]({fname})"]
        lines += ["", f"## The {worst} worst cases", ""]
        keys = list(s.values)
        head = ["case", *keys, "settling [s]", "max nom. xi", "saturated", "diverged at", "success"]
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "---|" * len(head))
        for row in self.worst(worst):
            cells = [str(row["case"])] + [f"{row[k]:.4g}" for k in keys]
            cells += [
                _fmt(row["settling_time"], "never"),
                _fmt(row["max_abs_xi_nominal"]),
                f"{100 * row['saturated_fraction']:.1f} %",
                _fmt(row["diverged_at"], "-"),
                {1: "held", 0: "FAILED", -1: "untested"}[row["success"]],
            ]
            lines.append("| " + " | ".join(cells) + " |")
        lines += [
            "",
            (
                "Rerun a case: `result.case(i).simulate()` (Python) or rebuild it from "
                "the table's values."
            ),
            "",
            f"Tables: {', '.join(tables)}.",
        ]
        path = out / "report.md"
        path.write_text("\n".join(lines) + "\n")
        return path


def _fmt(v: Any, none: str = "-") -> str:
    return none if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.4g}"


def _plain(v: Any) -> Any:
    if isinstance(v, (np.bool_, bool)):
        return bool(v)
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.floating):
        return float(v)
    return v


def _cell(v: Any) -> str:
    if isinstance(v, (np.floating, float)):
        return "" if not math.isfinite(float(v)) else repr(float(v))
    if isinstance(v, (np.bool_, bool)):
        return str(int(bool(v)))
    return str(v)


# ---------------------------------------------------------------------------
# TOML specs (famcc campaign SPEC.toml)
# ---------------------------------------------------------------------------


def _law(spec: Any, kind: str) -> Any:
    import famcc

    if not isinstance(spec, Mapping) or kind not in spec:
        raise ValueError(
            f"a {kind} must be a table with {kind} = NAME and its parameters, got {spec!r}"
        )
    rest = dict(spec)
    name = rest.pop(kind)
    allowed = {
        "law": ("Linear", "FiniteTime", "FixedTime", "VariableExponent"),
        "skew": ("Smooth", "Nonsingular"),
    }[kind]
    if name not in allowed:
        raise ValueError(f"{kind} must be one of {', '.join(allowed)}, got {name!r}")
    return getattr(famcc, name)(**rest)


def _controller_from_spec(spec: Mapping[str, Any], dt: float) -> Any:
    import famcc

    kw = dict(spec)
    scenario = kw.pop("scenario", None)
    variant = kw.pop("variant", "code")
    if "feedback" in kw:
        fb = kw["feedback"]
        kw["feedback"] = [_law(f, "law") for f in fb] if isinstance(fb, list) else _law(fb, "law")
    if "skew" in kw:
        sk = kw["skew"]
        kw["skew"] = [_law(f, "skew") for f in sk] if isinstance(sk, list) else _law(sk, "skew")
    if isinstance(kw.get("differentiator"), Mapping):
        kw["differentiator"] = famcc.HighGain(**kw["differentiator"])
    if "eps" in kw and isinstance(kw["eps"], list):
        kw["eps"] = tuple(kw["eps"])
    if scenario is not None:
        return famcc.scenarios.paper(scenario, variant).controller(dt, **kw)
    if "order" not in kw:
        raise ValueError("[controller] needs scenario = NAME or order and the design's settings")
    order = kw.pop("order")
    return famcc.Controller(order, dt, **kw)


def load_spec(path: str | Path) -> dict[str, Any]:
    """Reads a campaign spec (TOML) into the keyword arguments of :func:`campaign`.

    The format (``examples/campaigns/*.toml``; every table but ``[plant]`` and
    ``[controller]`` is optional)::

        name = "rfc-saturated"
        cases = 10000
        seed = 3
        t_end = 10.0
        dt = 0.001
        substeps = 1
        u_limits = [-7.0, 9.0]
        chunk_size = 2500

        [plant]
        family = "third-order"
        variant = "code"

        [controller]              # a paper scenario's design, with overrides,
        scenario = "rfc-saturated"  # or order = 2, feedback = {law = "FiniteTime", k = 1,
        variant = "code"            # p = 0.5}, constraint = ..., eps = ..., k_u = ...

        [criteria]
        eps = 0.1
        settle_by = "horizon"     # seconds, "bound" or "horizon"
        require = ["settled", "bounded"]

        [reference]
        kind = "sine"             # amplitude, omega, phase; or kind = "constant", value
        amplitude = 1.0

        [noise]
        sigma = 0.0

        [dispersion.plant]        # the family's parameters
        gain = {uniform = [0.8, 1.2]}
        [dispersion.x0]           # initial states x1, x2, ...
        x1 = {uniform = [0.5, 1.5]}
        [dispersion.reference]    # amplitude, omega, phase or value
        omega = {uniform = [0.8, 1.2]}
        [dispersion.controller]   # eps, k_u, settle_time, k0, rho_e
        k_u = {choice = [25.0, 30.0]}
        [dispersion.noise]
        sigma = {uniform = [0.0, 0.001]}

    Raises
    ------
    ValueError
        For an unknown key or a bad value (naming it).
    """
    import tomllib

    path = Path(path)
    try:
        doc = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML: {exc}") from exc
    top = {
        "name",
        "description",
        "cases",
        "seed",
        "t_end",
        "dt",
        "substeps",
        "u_limits",
        "chunk_size",
        "state_bound",
        "confidence",
        "plant",
        "controller",
        "criteria",
        "reference",
        "noise",
        "dispersion",
    }
    unknown = sorted(set(doc) - top)
    if unknown:
        raise ValueError(f"{path}: unknown keys {unknown}; known: {sorted(top)}")
    for need in ("cases", "t_end", "plant", "controller"):
        if need not in doc:
            raise ValueError(f"{path}: missing {need!r}")
    plant = dict(doc["plant"])
    fam = plant.pop("family", None)
    if fam is None:
        raise ValueError(f"{path}: [plant] needs family = NAME")
    variant = plant.pop("variant", None)
    if plant:
        raise ValueError(f"{path}: unknown keys {sorted(plant)} in [plant]")
    dt = float(doc.get("dt", 1e-3))
    ctrl = _controller_from_spec(doc["controller"], dt)
    crit = dict(doc.get("criteria", {}))
    settle_by = crit.pop("settle_by", "horizon")
    settle_by = None if settle_by == "horizon" else settle_by
    kw: dict[str, Any] = {
        "family": fam,
        "variant": variant,
        "controller": ctrl,
        "cases": doc["cases"],
        "t_end": doc["t_end"],
        "name": doc.get("name", path.stem),
        "eps": crit.pop("eps", None),
        "settle_by": settle_by,
        "require": tuple(crit.pop("require", ("settled", "bounded"))),
    }
    if crit:
        raise ValueError(f"{path}: unknown keys {sorted(crit)} in [criteria]")
    for key in ("seed", "substeps", "chunk_size", "state_bound", "confidence"):
        if key in doc:
            kw[key] = doc[key]
    if "u_limits" in doc:
        kw["u_limits"] = tuple(doc["u_limits"])
    ref = dict(doc.get("reference", {"kind": "sine"}))
    kind = ref.pop("kind", "sine")
    if kind == "sine":
        kw["reference"] = Sine(**ref)
    elif kind == "constant":
        kw["reference"] = Constant(**ref)
    else:
        raise ValueError(f"{path}: [reference] kind must be 'sine' or 'constant', got {kind!r}")
    noise = dict(doc.get("noise", {}))
    kw["noise"] = float(noise.pop("sigma", 0.0))
    if noise:
        raise ValueError(f"{path}: unknown keys {sorted(noise)} in [noise]")
    disp: dict[str, Any] = {}
    for group, table in dict(doc.get("dispersion", {})).items():
        if not isinstance(table, Mapping):
            raise ValueError(f"{path}: [dispersion.{group}] must be a table")  # noqa: TRY004
        for key, value in table.items():
            if group == "plant":
                disp[key] = value
            elif group == "x0":
                if not (key.startswith("x") and key[1:].isdigit()):
                    raise ValueError(f"{path}: [dispersion.x0] keys are x1, x2, ..., got {key!r}")
                disp[f"{key}(0)"] = value
            elif group in ("reference", "controller", "noise"):
                disp[f"{group}.{key}"] = value
            else:
                raise ValueError(
                    f"{path}: unknown table [dispersion.{group}] (plant, x0, "
                    "reference, controller, noise)"
                )
    kw["dispersion"] = disp
    return kw


def run_spec(
    path: str | Path,
    out: str | Path,
    *,
    executor: Any = None,
    jobs: int | None = None,
    progress: Any = True,
    figures: bool = True,
) -> tuple[CampaignResult, Path]:
    """Runs a TOML spec (:func:`load_spec`) with its chunks in ``out/``; writes the report.

    Returns the result and the path of ``out/report.md``.
    """
    kw = load_spec(path)
    res = campaign(executor=executor, jobs=jobs, out=out, progress=progress, **kw)
    return res, res.write(out, figures=figures)
