"""The judged results of a campaign: rates, worst cases, tables and rebuilt cases."""

from __future__ import annotations

import importlib
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from famcc.campaigns.controller import _controller, _corollary_time
from famcc.campaigns.noise import NoisySensor, noise_keys
from famcc.campaigns.report import plot_distributions, plot_success, write
from famcc.campaigns.stats import Rate, _pct, _rate
from famcc.signals import Constant, Sine
from famcc.sim.simulate import simulate
from famcc.verdicts import Status, combine_codes

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from famcc.campaigns.plan import Campaign

#: The criteria every case is judged on, in the order reports list them.
CRITERIA = ("settled", "bounded", "nominal", "unsaturated")


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
        ``diverged_at`` (s, NaN), one status column per criterion (int8
        :attr:`famcc.verdicts.Status.code`: 1 held, 0 failed, -1 untested) and
        ``success`` (the ``require`` d criteria combined by
        :func:`famcc.verdicts.combine`).
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
            deadline = np.maximum(t_e, settle_time) + _corollary_time(s.spec, z1_0)
        else:
            deadline = np.full(s.cases, float(s.settle_by))
        held, failed, untested = (st.code for st in (Status.HELD, Status.FAILED, Status.UNTESTED))
        with np.errstate(invalid="ignore"):
            if s.settle_by is None:
                settled = np.where(np.isfinite(settling), held, failed)
            else:
                ok = np.isfinite(settling) & (settling <= deadline)
                beyond = deadline > t_last + 1e-9 * dt
                settled = np.where(beyond, untested, np.where(ok, held, failed))
        settled = np.where(diverged, failed, settled)
        bounded = np.where(diverged, failed, held)
        if self.has_diagnostics:
            nominal = np.where(diverged | (raw["exp_unsat_late"] > 0), failed, held)
        else:
            nominal = np.full(s.cases, untested)
        if s.u_limits is None:
            unsat = np.full(s.cases, untested)
        else:
            unsat = np.where(diverged | (raw["sat_late"] > 0), failed, held)
        status = {"settled": settled, "bounded": bounded, "nominal": nominal, "unsaturated": unsat}
        success = combine_codes(np.array([status[c] for c in s.require]))
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
        table["success"] = success
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
        success = t["success"]
        worse = [t["diverged"], success == Status.FAILED.code, success == Status.UNTESTED.code]
        rank = np.select(worse, [0, 1, 2], 3)
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
        ctrl: Any = _controller(s.spec, over)
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
        return plot_distributions(self)

    def plot_success(self, bins: int = 10) -> Figure:
        """The success rate against each dispersed value, with Clopper-Pearson bars."""
        return plot_success(self, bins)

    def write(self, out: str | Path, figures: bool = True, worst: int = 10) -> Path:
        """Writes ``report.md``, ``cases.csv`` (and ``cases.parquet`` with pyarrow), figures.

        Returns the path of ``report.md``.
        """
        return write(self, out, figures, worst)


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
