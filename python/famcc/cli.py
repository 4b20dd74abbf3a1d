"""The ``famcc`` console command.

``famcc reproduce`` runs the paper's six simulations (variant ``code`` by
default), writes one figure per scenario, ``report.md`` and ``summary.json``, and
exits with status 1 when any claim of a scenario fails (``Scenario.check``), 0
otherwise; untested claims (bound beyond the horizon) are reported as untested
and do not change the status. ``famcc sweep`` (or ``famcc reproduce
--sweep-dt``, which runs both) sweeps the sample rate for the three
differentiator discretizations with and without estimate limits and writes
``sweep.md``, ``sweep.json`` and ``sweep.png``.

Examples::

    famcc --version
    famcc reproduce --out out/
    famcc reproduce --variant paper --scenario rfc rfc-saturated --out out-paper/
    famcc sweep --out out/ --jobs 2
    famcc campaign examples/campaigns/rfc-saturated.toml --out out/rfc-saturated
    famcc compare --out out/compare --quick
    python -m famcc.cli reproduce --t-end 2 --scenario finite-time --out /tmp/x

Exit status: 0 no guarantee failed (some may be untested: see the report's headline),
1 some guarantee failed, 2 usage error. ``famcc campaign`` (a Monte Carlo robustness
campaign from a TOML spec, :mod:`famcc.campaigns`) exits 0 once its report is written,
whatever the success rate (the rate is the result), 2 for a bad spec. ``famcc compare``
(:mod:`famcc.compare`) exits 0 once its report is written, 2 for an unknown plant or a
missing peer package.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from pathlib import Path

__all__ = ["main"]


def _positive(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not (v > 0 and v < float("inf")):
        raise argparse.ArgumentTypeError(f"must be a finite number > 0, got {text!r}")
    return v


def _parser() -> argparse.ArgumentParser:
    from famcc import __version__, scenarios
    from famcc import sweep as sw
    from famcc.scenarios import OBSERVER_MU

    names = scenarios.names()
    p = argparse.ArgumentParser(
        prog="famcc", description="famcc: fully actuated manifold constraint control."
    )
    p.add_argument("--version", action="version", version=f"famcc {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True

    def common(sp: argparse.ArgumentParser) -> None:
        sp.add_argument(
            "--out", default="famcc-out", type=Path, help="output directory (default: ./famcc-out)"
        )
        sp.add_argument(
            "--variant",
            choices=scenarios.VARIANTS,
            default="code",
            help="scenario numbers: the authors' code (default) or the printed "
            "paper (docs/design.md §6)",
        )
        sp.add_argument(
            "--scenario",
            dest="scenarios",
            nargs="+",
            action="extend",
            choices=names,
            metavar="NAME",
            help=f"scenario(s) to run (default: all): {', '.join(names)}",
        )
        sp.add_argument(
            "--t-end",
            type=_positive,
            default=None,
            help="horizon in s (default: the scenario's, 10 s)",
        )
        sp.add_argument("--quiet", action="store_true", help="no progress output")

    def sweep_opts(sp: argparse.ArgumentParser) -> None:
        sp.add_argument(
            "--rates",
            type=_positive,
            nargs="+",
            default=None,
            metavar="HZ",
            help="sample rates of the sweep in Hz (default: "
            f"{' '.join(str(r) for r in sw.RATES_HZ)})",
        )
        sp.add_argument(
            "--discretization",
            dest="discretizations",
            nargs="+",
            choices=sw.DISCRETIZATIONS,
            default=None,
            help=f"differentiator discretizations (default: all {len(sw.DISCRETIZATIONS)})",
        )
        sp.add_argument(
            "--jobs",
            type=int,
            default=None,
            help="worker processes for the sweep (default: CPU count)",
        )
        sp.add_argument(
            "--limit-factor",
            type=_positive,
            default=sw.LIMIT_FACTOR,
            help=f"estimate limits = this x max(|z_i(0)|, 1) (default: {sw.LIMIT_FACTOR:g})",
        )

    rp = sub.add_parser(
        "reproduce",
        help="run the paper's simulations; figures and report",
        description="Run the paper's six scenarios, write one PNG per "
        "scenario, report.md and summary.json. Exit status 1 when "
        "a guarantee is violated.",
    )
    common(rp)
    rp.add_argument(
        "--dt", type=_positive, default=1e-3, help="controller sample period in s (default: 0.001)"
    )
    rp.add_argument("--no-figures", action="store_true", help="skip the PNGs (numbers only)")
    rp.add_argument(
        "--observer",
        nargs="?",
        type=_positive,
        const=OBSERVER_MU,
        default=None,
        metavar="MU",
        help="the extended observer (mu in s, default "
        f"{OBSERVER_MU:g}) in the differentiator's place; the claims are the paper's",
    )
    rp.add_argument(
        "--sweep-dt",
        action="store_true",
        help="also run the sample-rate sweep (minutes; writes sweep.md)",
    )
    sweep_opts(rp)

    sp = sub.add_parser(
        "sweep",
        help="settling time and max |xi~| against the sample rate",
        description="Sweep the sample rate (50 Hz - 10 kHz) for the four "
        "differentiator discretizations, with and without "
        "estimate limits; writes sweep.md, sweep.json, sweep.png.",
    )
    common(sp)
    sweep_opts(sp)

    cp = sub.add_parser(
        "campaign",
        help="Monte Carlo robustness campaign from a TOML spec; report, figures, table",
        description="Run the campaign of SPEC.toml (examples/campaigns/*.toml) on the local "
        "cores or a Dask scheduler; write report.md, the figures and cases.csv "
        "(cases.parquet with pyarrow). Finished chunks in DIR/chunks are skipped on a rerun.",
    )
    cp.add_argument("spec", type=Path, metavar="SPEC.toml", help="the campaign spec")
    cp.add_argument("--out", required=True, type=Path, metavar="DIR", help="output directory")
    cp.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        default=None,
        help="a Dask scheduler (tcp://host:8786; pip install 'famcc[cluster]')",
    )
    cp.add_argument(
        "--jobs", type=int, default=None, help="local worker processes (default: CPU count)"
    )
    cp.add_argument("--no-figures", action="store_true", help="skip the PNGs")
    cp.add_argument("--quiet", action="store_true", help="no progress output")

    mp = sub.add_parser(
        "compare",
        help="famcc against PID, ADRC and LMCC on every plant under real conditions",
        description="Tune famcc, LMCC, PID (simple-pid) and ADRC (pyadrc) by one procedure on "
        "every plant, run them under nominal, saturated, noisy, dispersed and 200 Hz "
        "conditions and write report.md (tables, radar charts, time series, where famcc "
        "loses), results.json and figures/ (pip install 'famcc[compare]').",
    )
    mp.add_argument("--out", required=True, type=Path, metavar="DIR", help="output directory")
    mp.add_argument(
        "--quick", action="store_true", help="2 plants, 5 conditions, budget 8 (under 2 minutes)"
    )
    mp.add_argument("--jobs", type=int, default=None, help="worker processes (default: CPU count)")
    mp.add_argument("--seed", type=int, default=2026, help="seed of tuning, noise and dispersion")
    mp.add_argument(
        "--plant",
        dest="plants",
        nargs="+",
        default=None,
        metavar="NAME",
        help="only these plants (example-1, ..., two-link-arm)",
    )
    mp.add_argument("--no-figures", action="store_true", help="skip the PNGs")
    mp.add_argument("--quiet", action="store_true", help="no progress output")
    return p


def _run_compare(args: argparse.Namespace) -> int:
    from famcc import compare as cmp
    from famcc import reporting as report

    names = {c.name for c in cmp.cases(args.quick)}
    unknown = sorted(set(args.plants or ()) - names)
    if unknown:
        print(
            f"famcc compare: error: unknown plant(s) {', '.join(unknown)}; choose from "
            f"{', '.join(sorted(names))}",
            file=sys.stderr,
        )
        return 2
    n_cases = len(args.plants) if args.plants else len(names)
    total = cmp.total_runs(args.quick, n_cases=n_cases)
    bar = (
        None
        if args.quiet
        else report.Progress(
            total,
            f"famcc compare: {total} closed-loop runs ({n_cases} plants x 4 controllers; "
            f"{'quick' if args.quick else 'full'}) -> {args.out}",
        )
    )
    try:
        res = cmp.compare(
            quick=args.quick, jobs=args.jobs, progress=bar, seed=args.seed, case_names=args.plants
        )
    except ImportError as exc:
        print(f"famcc compare: error: {exc}", file=sys.stderr)
        return 2
    md = cmp.write_report(res, args.out, figures=not args.no_figures)
    if not args.quiet:
        print(f"report: {md} ({res['meta']['runtime_s']:.0f} s)", file=sys.stderr)
    return 0


def _run_campaign(args: argparse.Namespace) -> int:
    from famcc import campaigns

    t0 = time.perf_counter()
    try:
        res, md = campaigns.run_spec(
            args.spec,
            args.out,
            executor=args.scheduler,
            jobs=args.jobs,
            progress=not args.quiet,
            figures=not args.no_figures,
        )
    except (ValueError, OSError) as exc:
        print(f"famcc campaign: error: {exc}", file=sys.stderr)
        return 2
    if not args.quiet:
        print(f"report: {md} ({time.perf_counter() - t0:.1f} s)", file=sys.stderr)
        print(res.summary(), file=sys.stderr)
    return 0


def _run_sweep(args: argparse.Namespace) -> None:
    from famcc import reporting as report
    from famcc import sweep as sw

    rates = args.rates or sw.RATES_HZ
    discs = args.discretizations or sw.DISCRETIZATIONS
    names = args.scenarios or None
    from famcc import scenarios

    n = len(names or scenarios.names()) * len(rates) * len(discs) * 2
    bar = (
        None
        if args.quiet
        else report.Progress(
            n,
            f"famcc sweep: {n} runs ({len(rates)} rates x {len(discs)} discretizations x "
            f"2 limit settings), variant {args.variant!r} -> {args.out}",
        )
    )
    t0 = time.perf_counter()
    records = sw.sweep(
        names,
        variant=args.variant,
        rates=rates,
        discretizations=discs,
        t_end=args.t_end,
        jobs=args.jobs,
        progress=bar,
        limit_factor=args.limit_factor,
    )
    meta = {
        "variant": args.variant,
        "t_end": args.t_end,
        "limit_factor": args.limit_factor,
        "runtime_s": time.perf_counter() - t0,
        "jobs": args.jobs or _cpus(),
    }
    md = sw.write_sweep_report(records, args.out, meta)
    if not args.quiet:
        print(f"sweep: {md} ({meta['runtime_s']:.0f} s)", file=sys.stderr)


def _cpus() -> int:
    import os

    return os.cpu_count() or 1


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``famcc``; returns the exit status."""
    args = _parser().parse_args(None if argv is None else list(argv))
    if args.command == "sweep":
        _run_sweep(args)
        return 0
    if args.command == "campaign":
        return _run_campaign(args)
    if args.command == "compare":
        return _run_compare(args)

    from famcc import reporting as report

    t0 = time.perf_counter()
    try:
        records = report.reproduce(
            args.out,
            names=args.scenarios,
            variant=args.variant,
            dt=args.dt,
            t_end=args.t_end,
            figures=not args.no_figures,
            progress=None if args.quiet else "stderr",
            observer=args.observer,
        )
    except ValueError as exc:
        print(f"famcc reproduce: error: {exc}", file=sys.stderr)
        return 2
    bad = [r for r in records if r["violations"]]
    if not args.quiet:
        print(
            f"report: {Path(args.out) / 'report.md'} ({time.perf_counter() - t0:.1f} s)",
            file=sys.stderr,
        )
        print(report.headline(records).replace("**", ""), file=sys.stderr)
        for r in bad:
            for line in r["violations"]:
                print(f"FAILED {r['scenario']}: {line}", file=sys.stderr)
    if args.sweep_dt:
        _run_sweep(args)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
