"""A campaign's figures and its ``report.md``."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from famcc.campaigns.controller import _controller
from famcc.campaigns.dispersion import Fixed
from famcc.campaigns.stats import _fmt, _pct, clopper_pearson
from famcc.plants.base import is_real as _is_number
from famcc.verdicts import STARTUP, Status

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from famcc.campaigns.result import CampaignResult


def plot_distributions(result: CampaignResult) -> Figure:
    """Histograms of the settling time and of the max nominal ``|xi|``."""
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FormatStrFormatter, MaxNLocator, NullFormatter

    t = result.table
    s = result.spec
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
        ax2.axvline(1.0, color="tab:red", ls="--", label=f"|xi| = 1 ({over:,} cases at or above)")
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
    fig.suptitle(_title(result), fontsize=11)
    return fig


def _title(result: CampaignResult) -> str:
    s = result.spec
    return f"{s.name}: {s.cases:,} cases of {s.family.name}, {s.t_end:g} s at dt = {s.dt:g} s"


def plot_success(result: CampaignResult, bins: int = 10) -> Figure:
    """Success rate (with Clopper-Pearson bars) against each dispersed value."""
    import matplotlib.pyplot as plt

    keys = [k for k, d in result.spec.dispersion.items() if not isinstance(d, Fixed)]
    cols = min(3, max(1, len(keys)))
    rows = max(1, math.ceil(len(keys) / cols))
    fig, axes = plt.subplots(
        rows, cols, figsize=(4.2 * cols, 3.2 * rows), layout="constrained", squeeze=False
    )
    status = result.table["success"]
    overall = result.rate("success").rate
    for ax, key in zip(axes.flat, keys):
        x = result.spec.values[key]
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
                lo_b, hi_b = clopper_pearson(k_b, n_b, result.spec.confidence)
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
        ax.set_xlabel(key + (f"  ({result.spec.dispersion[key].describe()})"), fontsize=9)
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
    what = " and ".join(result.spec.require)
    fig.suptitle(
        f"{_title(result)}\nsuccess ({what}) against each dispersed value, "
        f"{100 * result.spec.confidence:g} % Clopper-Pearson bars",
        fontsize=10,
    )
    return fig


def write(result: CampaignResult, out: str | Path, figures: bool = True, worst: int = 10) -> Path:
    """Writes ``report.md``, ``cases.csv`` (and ``cases.parquet`` with pyarrow), figures.

    Returns the path of ``report.md``.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    s = result.spec
    result.to_csv(out / "cases.csv")
    tables = ["`cases.csv`"]
    try:
        result.to_parquet(out / "cases.parquet")
        tables.append("`cases.parquet`")
    except ImportError:
        pass
    pngs = []
    if figures:
        import matplotlib.pyplot as plt

        for fname, fig in (
            ("distributions.png", result.plot_distributions()),
            ("success.png", result.plot_success()),
        ):
            fig.savefig(out / fname, dpi=110)
            plt.close(fig)
            pngs.append(fname)
    lines = [f"# famcc campaign: {s.name}", ""]
    lines.append(f"**{result._headline()}**")
    lines += ["", "## Setup", ""]
    lines.append(
        f"- plant family: {s.family.name} ({s.family.description or 'own family'});"
        f" nominal {', '.join(f'{k} = {v:g}' for k, v in s.family.params.items())},"
        f" x(0) = {s.family.x0.tolist()}"
    )
    lines.append(f"- controller: `{_controller(s.spec, {})!r}`")
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
    for name, r in result.rates().items():
        ci = "-" if not r.tested else f"{_pct(r.lo, False)}-{_pct(r.hi)}"
        lines.append(
            f"| {name} | {r.held:,} | {r.failed:,} | {r.untested:,} | {_pct(r.rate)} | {ci} |"
        )
    t = result.table
    ts = t["settling_time"]
    fin = ts[np.isfinite(ts)]
    xi = t["max_abs_xi_nominal"]
    lines += ["", "## Distributions", ""]
    if fin.size:
        q = np.quantile(fin, [0.5, 0.95, 0.99])
        lines.append(
            f"- settling time: median {q[0]:.3g} s, 95th percentile {q[1]:.3g} s, "
            f"99th {q[2]:.3g} s, max {float(fin.max()):.3g} s "
            f"({fin.size:,} of {result.n:,} settled)"
        )
    if np.isfinite(xi).any():
        lines.append(
            f"- max nominal |xi|: median {float(np.nanmedian(xi)):.3g}, max "
            f"{float(np.nanmax(xi)):.3g}; {int(np.sum(xi >= 1)):,} cases reached 1"
        )
    lines.append(
        f"- saturated fraction: mean {float(np.mean(t['saturated_fraction'])):.3g};"
        f" diverged: {int(np.sum(t['diverged'])):,}; law overflows: "
        f"{result.overflows:,}"
    )
    if not result.has_diagnostics:
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
    for row in result.worst(worst):
        cells = [str(row["case"])] + [f"{row[k]:.4g}" for k in keys]
        cells += [
            _fmt(row["settling_time"], "never"),
            _fmt(row["max_abs_xi_nominal"]),
            f"{100 * row['saturated_fraction']:.1f} %",
            _fmt(row["diverged_at"], "-"),
            Status.from_code(row["success"]).shown,
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
