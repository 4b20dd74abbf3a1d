"""A campaign's plan: its resolved configuration, the per-case draws, and its chunks."""

from __future__ import annotations

import hashlib
import json
import zlib
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from famcc import _core
from famcc.campaigns.chunk import _Chunk
from famcc.campaigns.dispersion import Distribution
from famcc.plants import Family
from famcc.signals import Sine


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
    #: The controller's configuration as famcc-core's spec, from which every chunk
    #: builds its controllers (given: the campaign's own controller's; else parsed
    #: once from ``controller``).
    controller_spec: _core.ControllerSpec | None = field(default=None, repr=False, compare=False)

    @property
    def spec(self) -> _core.ControllerSpec:
        """The controller's configuration, parsed (:attr:`controller_spec`)."""
        if self.controller_spec is None:
            self.controller_spec = _core.ControllerSpec.from_config(dict(self.controller))
        return self.controller_spec

    @property
    def reference_kind(self) -> str:
        """``"sine"`` or ``"constant"``."""
        return "sine" if isinstance(self.reference, Sine) else "constant"

    def fingerprint(self) -> str:
        """A hash of everything that decides the per-case results (for resuming)."""
        cfg = {k: repr(v) for k, v in self.controller.items()}
        doc = {
            "famcc": _core.__version__,
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
            self.spec,
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
