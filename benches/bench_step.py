"""Per-call cost of famcc's Python ``step()``, against its floor and alternatives.

One harness, interleaved rounds, medians and paired ratios.

Candidates (all fed recorded closed-loop errors of the paper's scenarios, variant
"code", dt = 1 ms; each famcc/reference candidate in two phases):

- ``loop``: the timing loop with an empty body (harness overhead);
- ``noop``: ``famcc._core._CallFloor().step(e)``, a ``&mut self`` method taking
  and returning a float: the floor of any Python-to-Rust method call;
- ``famcc <design>/<phase>``: ``Controller.step(e)`` for finite-time (order 2),
  variable-exponent (order 2) and rfc (order 3); ``transient`` replays samples
  0..999 (t < T_s: first-step latch, shrinking envelope) from a reset
  controller, ``settled`` replays samples 1000.. from the controller's state at
  t = 1 s (restored with ``set_state``, outside the per-call cost);
- ``famcc finite-time/settled step(e, applied)``: the same with the optional
  argument passed (its parsing cost);
- ``reference <design>/<phase>``: the pure-Python oracle's step (``tests/oracle/reference.py``);
- ``simple-pid``: ``PID(1, 0.1, 0.05, setpoint=0, sample_time=None)(x)``;
- ``ControllerBank`` throughput (order 2, finite-time) at N = 1e3, 1e5, 1e6
  from a fresh (transient) and a settled controller, per-controller inputs (the
  bank splits batches of N >= 16384 over the machine's cores, at most 8: its
  "cpu" figure is steps per CPU-second of the whole process, i.e. per core);
- ``native proxy``: a ``ControllerBank`` of 1000 identical copies per design and
  phase, fed the same samples as the Python candidates (see below).

Method: everything is built first; then R rounds; in each round the candidates
run in a shuffled order, each timing one batch of M calls (20000 compiled, 2000
pure Python) with ``time.perf_counter_ns`` and the garbage collector off, giving
ns/call. Reported: median, min and IQR over rounds; ratios are medians over
rounds of the per-round ratios (paired, so slow drifts of the machine cancel).

Native step times (for the issue's target ``Python step <= 1.3 x (no-op + native
step)``) come from ``--native-ns order2=NN,order3=NN`` (or per design:
``finite-time=NN,variable-exponent=NN,rfc=NN``), else from criterion's results
of ``cargo bench -p famcc-core --bench step`` under ``target/criterion`` if present.

Both clocks are read around every batch: ``time.perf_counter_ns`` (wall) and
``time.thread_time_ns`` (this thread's CPU time, which excludes time the thread
was descheduled and so stays meaningful on a loaded machine); ``--clock``
chooses which one the table, the ratios and the targets use.

Usage::

    python benches/bench_step.py [--rounds 21] [--clock wall|cpu] [--json out.json]
                                 [--native-ns order2=NN,order3=NN] [--quick]
"""

from __future__ import annotations

import argparse
import gc
import hashlib
import json
import os
import platform
import random
import statistics
import sys
import time
from pathlib import Path

import famcc
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
# The pure-Python oracle lives with the tests (it is not shipped in the package).
sys.path.insert(0, str(ROOT / "tests"))
from oracle.reference import ReferenceController

perf_ns = time.perf_counter_ns
thread_ns = time.thread_time_ns
process_ns = time.process_time_ns
DT = 1e-3
DESIGNS = {  # name -> (scenario, order, criterion id)
    "finite-time": ("finite-time", 2, "ex1"),
    "variable-exponent": ("variable-exponent", 2, "ex2"),
    "rfc": ("rfc", 3, "ex3"),
}
TRANSIENT = 1000  # samples with t < T_s = 1 s
TARGETS = {
    "order2_vs_floor": 1.3,  # step <= 1.3 x (noop + native)
    "order2_ns": 200.0,  # step <= 200 ns
    "vs_simple_pid": 10.0,  # >= 10x faster than simple-pid
    "vs_reference": 15.0,  # >= 15x faster than the pure-Python reference
    "bank_1e5_steps_per_s": 10e6,
    # issue 16: example 1 (finite-time, order 2), settled
    "ex1_settled_ns": 65.0,  # step() <= 65 ns median
    "ex1_settled_vs_simple_pid": 11.0,  # >= 11x simple-pid in the same process
}


# ---------------------------------------------------------------------------
# build information


def build_info() -> str:
    """Which cargo profile built the loaded extension (compares with target/)."""
    so = Path(famcc._core.__file__)

    def digest(p: Path) -> str | None:
        try:
            return hashlib.sha256(p.read_bytes()).hexdigest()
        except OSError:
            return None

    mine = digest(so)
    for profile in ("release", "debug"):
        if mine is not None and mine == digest(ROOT / "target" / profile / "lib_core.so"):
            return f"{profile} (identical to target/{profile}/lib_core.so)"
    size = so.stat().st_size / 1e6
    guess = "probably debug" if size > 10 else "probably release"
    return f"unknown profile, {guess} ({size:.1f} MB)"


# ---------------------------------------------------------------------------
# inputs


def record(design: str, t_end: float = 10.0) -> list[float]:
    """The error sequence of a closed-loop run of the design (variant "code")."""
    sc = famcc.scenarios.paper(DESIGNS[design][0], "code")
    res = sc.run(dt=DT, t_end=t_end)
    return [float(x) for x in res.y - res.y_d]


class Replay:
    """One candidate: a callable, its inputs (one chunk), and how to rewind it."""

    def __init__(self, name, fn, inputs, rewind=None, calls=20000, group="", meta=None):
        self.name, self.fn, self.inputs = name, fn, list(inputs)
        self.rewind = rewind or (lambda: None)
        self.chunks = max(1, calls // len(self.inputs))
        self.calls = self.chunks * len(self.inputs)
        self.group = group
        self.meta = meta or {}
        self.samples: list[float] = []  # wall clock (perf_counter_ns), ns/call
        self.cpu_samples: list[float] = []  # this thread's CPU time, ns/call

    def record(self, wall: int, cpu: int) -> None:
        self.samples.append(wall / self.calls)
        self.cpu_samples.append(cpu / self.calls)

    def run(self) -> None:
        fn, inputs, rewind = self.fn, self.inputs, self.rewind
        wall = cpu = 0
        for _ in range(self.chunks):
            rewind()
            c0 = thread_ns()
            t0 = perf_ns()
            for e in inputs:
                fn(e)
            t1 = perf_ns()
            cpu += thread_ns() - c0
            wall += t1 - t0
        self.record(wall, cpu)


def stepper(ctrl, errors, phase, calls, name, group, meta):
    """A famcc or reference controller replaying one phase of a recorded run."""
    ctrl.reset()
    if phase == "transient":
        inputs = errors[:TRANSIENT]
        rewind = ctrl.reset
    else:
        for e in errors[:TRANSIENT]:
            ctrl.step(e)
        state = ctrl.state()
        inputs = errors[TRANSIENT : TRANSIENT + min(calls, len(errors) - TRANSIENT)]

        def rewind(ctrl=ctrl, state=state):
            ctrl.set_state(state)

    return Replay(name, ctrl.step, inputs, rewind, calls, group, meta)


#: The floor of a Python-to-Rust method call (a private benchmark helper).
NOOP = "noop: _CallFloor.step(e)"


def build_candidates(records, calls_compiled, calls_python):
    cands = []
    e_ft = records["finite-time"]
    cands.append(Replay("loop (empty body)", lambda e: None, e_ft, None, calls_compiled, "floor"))
    # replace the lambda by a true empty loop body: time the bare for-loop
    cands[-1].run = _empty_loop_runner(cands[-1])
    cands.append(Replay(NOOP, famcc._core._CallFloor().step, e_ft, None, calls_compiled, "floor"))
    for design, (scen, order, _) in DESIGNS.items():
        for phase in ("transient", "settled"):
            ctrl = famcc.scenarios.paper(scen, "code").controller(DT)
            cands.append(
                stepper(
                    ctrl,
                    records[design],
                    phase,
                    calls_compiled,
                    f"famcc {design}/{phase}",
                    "famcc",
                    {"design": design, "phase": phase, "order": order},
                )
            )
    # the optional argument's cost: step(e, applied) with applied = the same float
    ctrl = famcc.scenarios.paper("finite-time", "code").controller(DT)
    c = stepper(
        ctrl,
        e_ft,
        "settled",
        calls_compiled,
        "famcc finite-time/settled step(e, applied)",
        "famcc-applied",
        {"design": "finite-time", "phase": "settled", "order": 2},
    )
    step = ctrl.step
    c.fn = lambda e, step=step: step(e, e)
    c.run = _applied_runner(c, step)
    cands.append(c)
    for design, (scen, order, _) in DESIGNS.items():
        for phase in ("transient", "settled"):
            kw = famcc.scenarios.paper(scen, "code").controller_kwargs
            ref = ReferenceController.from_kwargs(dt=DT, **kw)
            cands.append(
                stepper(
                    ref,
                    records[design],
                    phase,
                    calls_python,
                    f"reference {design}/{phase}",
                    "reference",
                    {"design": design, "phase": phase, "order": order},
                )
            )
    try:
        from simple_pid import PID
    except ImportError:  # pragma: no cover - optional
        print("simple-pid not installed: skipped", file=sys.stderr)
    else:
        pid = PID(1, 0.1, 0.05, setpoint=0, sample_time=None)
        cands.append(
            Replay(
                "simple-pid PID(1, 0.1, 0.05)(x)",
                pid,
                e_ft,
                pid.reset,
                calls_python * 5,
                "simple-pid",
            )
        )
    return cands


def _empty_loop_runner(c: Replay):
    def run() -> None:
        inputs = c.inputs
        wall = cpu = 0
        for _ in range(c.chunks):
            c0 = thread_ns()
            t0 = perf_ns()
            for _e in inputs:
                pass
            t1 = perf_ns()
            cpu += thread_ns() - c0
            wall += t1 - t0
        c.record(wall, cpu)

    return run


def _applied_runner(c: Replay, step):
    def run() -> None:
        inputs, rewind = c.inputs, c.rewind
        wall = cpu = 0
        for _ in range(c.chunks):
            rewind()
            c0 = thread_ns()
            t0 = perf_ns()
            for e in inputs:
                step(e, e)
            t1 = perf_ns()
            cpu += thread_ns() - c0
            wall += t1 - t0
        c.record(wall, cpu)

    return run


# ---------------------------------------------------------------------------
# ControllerBank


class BankCase:
    """``ControllerBank.step`` throughput (steps/s), order 2, finite-time by default.

    ``mode="throughput"``: N controllers with per-controller inputs (the recorded
    errors at random offsets: Monte-Carlo-like), ``max(2, 1e6/N)`` calls per batch;
    the transient bank is reset before each batch, the settled one starts at t = 1.5 s
    and keeps running. ``mode="proxy"``: N = 1000 identical copies all fed the same
    recorded samples as the Python candidates (samples 0..999 from a reset, or
    1000..1999 from the state at t = 1 s, the bank rebuilt before each batch): the
    per-step time is the native step plus the bank's per-element loop, an upper bound
    of the native step measured with the same clock in the same rounds.
    """

    def __init__(
        self,
        n: int,
        phase: str,
        errors: list[float],
        design: str = "finite-time",
        mode: str = "throughput",
        seed: int = 0,
    ):
        self.n, self.phase, self.design, self.mode = n, phase, design, mode
        ctrl = famcc.scenarios.paper(DESIGNS[design][0], "code").controller(DT)
        rec = np.asarray(errors)
        if mode == "proxy":
            start = 0
            if phase == "settled":
                for e in errors[:TRANSIENT]:
                    ctrl.step(e)
                start = TRANSIENT
            self.ctrl = ctrl
            self.calls = TRANSIENT
            self.inputs = [np.full(n, x) for x in rec[start : start + self.calls]]
            self.bank = famcc.ControllerBank(ctrl, n)
        else:
            start = 0
            if phase == "settled":
                for e in errors[:1500]:
                    ctrl.step(e)
                start = 1500
            self.bank = famcc.ControllerBank(ctrl, n)
            self.calls = max(2, 10**6 // n)
            offsets = np.random.default_rng(seed).integers(0, 500, size=n)
            span = len(rec) - start - 600
            self.inputs = [
                np.ascontiguousarray(rec[start + (k % span) + offsets])
                for k in range(min(self.calls, 8))
            ]
        self.samples: list[float] = []  # steps per second, wall clock
        # steps per CPU-second of the whole process: banks of N >= 16384 step on
        # several threads, so this is per-core efficiency, not throughput
        self.cpu_samples: list[float] = []

    @property
    def name(self) -> str:
        if self.mode == "proxy":
            return f"native proxy: bank N=1000 {self.design}/{self.phase}"
        return f"ControllerBank N=1e{round(np.log10(self.n))} ({self.phase})"

    def run(self) -> None:
        if self.mode == "proxy":
            self.bank = famcc.ControllerBank(self.ctrl, self.n)
        elif self.phase == "transient":
            self.bank.reset()
        bank, inputs, calls = self.bank, self.inputs, self.calls
        m = len(inputs)
        c0 = process_ns()
        t0 = perf_ns()
        for k in range(calls):
            bank.step(inputs[k % m])
        t1 = perf_ns()
        cpu = process_ns() - c0
        self.samples.append(self.n * calls / ((t1 - t0) * 1e-9))
        self.cpu_samples.append(self.n * calls / (cpu * 1e-9))


# ---------------------------------------------------------------------------
# native numbers


def native_from_args(spec: str | None) -> dict[str, float]:
    out: dict[str, float] = {}
    if not spec:
        return out
    for item in spec.split(","):
        key, _, val = item.partition("=")
        key = key.strip()
        ns = float(val)
        if key == "order2":
            out.setdefault("finite-time", ns)
            out.setdefault("variable-exponent", ns)
        elif key == "order3":
            out.setdefault("rfc", ns)
        elif key in DESIGNS:
            out[key] = ns
        else:
            raise SystemExit(
                f"--native-ns: unknown key {key!r} (order2, order3, {', '.join(DESIGNS)})"
            )
    return out


def native_from_criterion(root: Path) -> dict[tuple[str, str], float]:
    """ns per native step from criterion (one iteration = 1000 steps)."""
    out = {}
    for design, (_, _, cid) in DESIGNS.items():
        for phase in ("transient", "settled"):
            f = root / "step" / f"{cid}_f64_{phase}" / "new" / "estimates.json"
            try:
                est = json.loads(f.read_text())
            except (OSError, ValueError):
                continue
            out[(design, phase)] = est["median"]["point_estimate"] / 1000.0
    return out


# ---------------------------------------------------------------------------
# statistics and report


def summary(xs: list[float]) -> dict[str, float]:
    q = statistics.quantiles(xs, n=4) if len(xs) >= 2 else [xs[0]] * 3
    return {"median": statistics.median(xs), "min": min(xs), "max": max(xs), "iqr": q[2] - q[0]}


def paired_ratio(a: list[float], b: list[float]) -> float:
    return statistics.median(x / y for x, y in zip(a, b))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=21)
    ap.add_argument("--calls", type=int, default=20000, help="calls per batch, compiled")
    ap.add_argument("--calls-python", type=int, default=2000, help="calls per batch, pure Python")
    ap.add_argument(
        "--native-ns",
        default=None,
        help="native step ns: order2=NN,order3=NN or finite-time=NN,...",
    )
    ap.add_argument(
        "--native",
        choices=("proxy", "criterion"),
        default="proxy",
        help="where native step times come from without --native-ns: the "
        "in-harness ControllerBank proxy (same clock, same rounds) or "
        "criterion's estimates.json under --criterion-dir",
    )
    ap.add_argument("--criterion-dir", default=str(ROOT / "target" / "criterion"))
    ap.add_argument("--no-bank", action="store_true")
    ap.add_argument("--quick", action="store_true", help="5 rounds, smaller batches")
    ap.add_argument("--json", default=None, help="write all samples and the summary here")
    ap.add_argument("--seed", type=int, default=12345)
    ap.add_argument(
        "--clock",
        choices=("wall", "cpu"),
        default="wall",
        help="clock for the table's main columns, ratios and targets: wall "
        "(perf_counter_ns) or cpu (thread_time_ns: excludes time the "
        "thread was descheduled; use on a loaded machine)",
    )
    args = ap.parse_args(argv)
    if args.quick:
        args.rounds, args.calls, args.calls_python = 5, 5000, 500

    info = {
        "build": build_info(),
        "python": sys.version.split()[0],
        "platform": platform.platform(),
        "cpu": platform.processor() or platform.machine(),
        "cpus": os.cpu_count(),
        "famcc": famcc.__version__,
        "rounds": args.rounds,
        "calls": args.calls,
        "calls_python": args.calls_python,
    }
    print(f"famcc {info['famcc']} extension build: {info['build']}")
    if "debug" in info["build"]:
        print(
            "WARNING: debug build; numbers are meaningless. Rebuild with `pip install -e .`"
            " (maturin's PEP 517 backend builds the release profile).",
            file=sys.stderr,
        )
    print(
        f"python {info['python']} on {info['platform']}, {info['cpus']} cpus; {args.rounds} rounds",
        flush=True,
    )

    records = {d: record(d) for d in DESIGNS}
    cands = build_candidates(records, args.calls, args.calls_python)
    banks = (
        []
        if args.no_bank
        else [
            BankCase(n, ph, records["finite-time"])
            for n in (10**3, 10**5, 10**6)
            for ph in ("transient", "settled")
        ]
    )
    proxies = [
        BankCase(1000, ph, records[d], design=d, mode="proxy")
        for d in DESIGNS
        for ph in ("transient", "settled")
    ]
    native = {
        (d, ph): ns
        for d, ns in native_from_args(args.native_ns).items()
        for ph in ("transient", "settled")
    }
    native_src = "--native-ns" if native else None
    if not native and args.native == "criterion":
        native = native_from_criterion(Path(args.criterion_dir))
        native_src = f"criterion ({args.criterion_dir}, wall clock)" if native else None

    rng = random.Random(args.seed)
    for c in cands:  # warm up (and fill caches) once
        c.run()
        c.samples.clear()
        c.cpu_samples.clear()
    gc_was = gc.isenabled()
    gc.disable()
    try:
        for r in range(args.rounds):
            order = list(cands) + list(banks) + list(proxies)
            rng.shuffle(order)
            for c in order:
                c.run()
            print(f"\rround {r + 1}/{args.rounds}", end="", file=sys.stderr, flush=True)
    finally:
        if gc_was:
            gc.enable()
    print(file=sys.stderr)
    if not native:
        xs_name = "samples" if args.clock == "wall" else "cpu_samples"
        native = {
            (p.design, p.phase): 1e9 / statistics.median(getattr(p, xs_name)) for p in proxies
        }
        native_src = (
            f"in-harness proxy: ControllerBank N=1000 ns/step ({args.clock} clock; "
            "native step + bank loop, an upper bound)"
        )
    report = analyse(cands, banks + proxies, native, native_src, args.clock)
    if args.json:
        Path(args.json).write_text(json.dumps({"info": info, **report}, indent=1))
        print(f"\nwrote {args.json}")
    return 0


def analyse(cands, banks, native, native_src, clock):
    """Prints the table and the targets; returns everything for --json."""
    primary = "samples" if clock == "wall" else "cpu_samples"
    other = "cpu_samples" if clock == "wall" else "samples"
    other_name = "cpu" if clock == "wall" else "wall"

    def xs(c):
        return getattr(c, primary)

    by = {c.name: c for c in cands}
    noop = by[NOOP]
    loop = by["loop (empty body)"]
    pid = by.get("simple-pid PID(1, 0.1, 0.05)(x)")
    rows = []
    print(
        f"\nclock: {clock} (ratios: medians of per-round ratios; other clock's median "
        f"in column '{other_name}')"
    )
    print(
        f"{'candidate':46s} {'median':>8s} {'min':>8s} {'IQR':>7s} {other_name:>8s} "
        f"{'-loop':>7s} {'/noop':>6s} {'/(noop+nat)':>11s} {'pid/x':>6s} {'ref/x':>6s}"
    )
    print(f"{'':46s} {'ns/call':>8s} {'ns/call':>8s} {'ns':>7s} {'ns/call':>8s} {'ns':>7s}")
    for c in cands:
        s = summary(xs(c))
        row = {
            "name": c.name,
            "group": c.group,
            **c.meta,
            **s,
            f"median_{other_name}": statistics.median(getattr(c, other)),
            "net_of_loop": s["median"] - statistics.median(xs(loop)),
            "samples_wall": c.samples,
            "samples_cpu": c.cpu_samples,
        }
        cols = ["", "", "", ""]
        if c.group in ("famcc", "famcc-applied"):
            row["ratio_noop"] = paired_ratio(xs(c), xs(noop))
            cols[0] = f"{row['ratio_noop']:.2f}"
            nat = native.get((c.meta["design"], c.meta["phase"]))
            if nat is not None:
                row["native_ns"] = nat
                row["ratio_floor"] = statistics.median(
                    x / (y + nat) for x, y in zip(xs(c), xs(noop))
                )
                cols[1] = f"{row['ratio_floor']:.2f}"
            if pid is not None:
                row["pid_ratio"] = paired_ratio(xs(pid), xs(c))
                cols[2] = f"{row['pid_ratio']:.1f}"
            if c.group == "famcc":
                ref = by[f"reference {c.meta['design']}/{c.meta['phase']}"]
                row["ref_ratio"] = paired_ratio(xs(ref), xs(c))
                cols[3] = f"{row['ref_ratio']:.0f}"
        rows.append(row)
        print(
            f"{c.name:46s} {s['median']:8.1f} {s['min']:8.1f} {s['iqr']:7.1f} "
            f"{row[f'median_{other_name}']:8.1f} {row['net_of_loop']:7.1f} {cols[0]:>6s} "
            f"{cols[1]:>11s} {cols[2]:>6s} {cols[3]:>6s}"
        )
    bank_rows = []
    if banks:
        print()
        print(
            f"{'ControllerBank (order 2 unless named)':46s} {'median':>8s} {'min':>8s} "
            f"{'max':>8s} {other_name:>8s}  {'ns/step':>7s}   (bank cpu = all threads: "
            f"steps per CPU-second; N >= 16384 runs on {min(os.cpu_count() or 1, 8)} threads)"
        )
        print(f"{'':46s} {'M st/s':>8s} {'M st/s':>8s} {'M st/s':>8s} {'M st/s':>8s}")
        for b in banks:
            s = summary(xs(b))
            bank_rows.append(
                {
                    "name": b.name,
                    "n": b.n,
                    "phase": b.phase,
                    "mode": b.mode,
                    "calls_per_batch": b.calls,
                    **s,
                    f"median_{other_name}": statistics.median(getattr(b, other)),
                    "samples_wall": b.samples,
                    "samples_cpu": b.cpu_samples,
                }
            )
            print(
                f"{b.name:46s} {s['median'] / 1e6:8.2f} {s['min'] / 1e6:8.2f} "
                f"{s['max'] / 1e6:8.2f} {statistics.median(getattr(b, other)) / 1e6:8.2f}  "
                f"{1e9 / s['median']:7.1f}"
            )

    # -- targets -----------------------------------------------------------------
    print()
    print(
        "native step: "
        + (
            f"{native_src}: "
            + ", ".join(f"{d}/{ph}={ns:.1f} ns" for (d, ph), ns in sorted(native.items()))
            if native
            else "not given (pass --native-ns or run cargo bench); ratio skipped"
        )
    )
    print(f"targets ({clock} clock, medians):")
    verdicts = []

    def verdict(label, ok, detail):
        verdicts.append({"target": label, "met": ok, "detail": detail})
        state = "n/a " if ok is None else ("MET " if ok else "MISS")
        print(f"  [{state}] {label}: {detail}")

    fam = [r for r in rows if r["group"] == "famcc"]
    o2 = [r for r in fam if r["order"] == 2]
    if all("ratio_floor" in r for r in o2):
        verdict(
            "order-2 step <= 1.3 x (noop + native step)",
            all(r["ratio_floor"] <= TARGETS["order2_vs_floor"] for r in o2),
            ", ".join(f"{r['design']}/{r['phase']} {r['ratio_floor']:.2f}" for r in o2),
        )
    else:
        verdict("order-2 step <= 1.3 x (noop + native step)", None, "needs native numbers")
    verdict(
        "order-2 step <= 200 ns",
        all(r["median"] <= TARGETS["order2_ns"] for r in o2),
        ", ".join(f"{r['design']}/{r['phase']} {r['median']:.0f} ns" for r in o2),
    )
    if pid is not None:
        verdict(
            ">= 10x faster than simple-pid",
            all(r["pid_ratio"] >= TARGETS["vs_simple_pid"] for r in fam),
            ", ".join(f"{r['design']}/{r['phase']} {r['pid_ratio']:.1f}x" for r in fam),
        )
    ex1 = [r for r in fam if r["design"] == "finite-time" and r["phase"] == "settled"]
    if ex1:
        verdict(
            "example 1 settled step <= 65 ns (issue 16)",
            ex1[0]["median"] <= TARGETS["ex1_settled_ns"],
            f"{ex1[0]['median']:.1f} ns",
        )
        if pid is not None:
            verdict(
                "example 1 settled >= 11x simple-pid (issue 16)",
                ex1[0]["pid_ratio"] >= TARGETS["ex1_settled_vs_simple_pid"],
                f"{ex1[0]['pid_ratio']:.1f}x",
            )
    verdict(
        ">= 15x faster than the pure-Python reference",
        all(r["ref_ratio"] >= TARGETS["vs_reference"] for r in fam),
        ", ".join(f"{r['design']}/{r['phase']} {r['ref_ratio']:.0f}x" for r in fam),
    )
    b5 = [b for b in bank_rows if b["n"] == 10**5 and b["mode"] == "throughput"]
    if b5:
        verdict(
            "ControllerBank >= 10 M steps/s at N = 1e5 (order 2)",
            all(b["median"] >= TARGETS["bank_1e5_steps_per_s"] for b in b5),
            ", ".join(f"{b['phase']} {b['median'] / 1e6:.1f} M/s" for b in b5),
        )
    return {
        "clock": clock,
        "native_ns": {f"{d}/{ph}": ns for (d, ph), ns in native.items()},
        "native_source": native_src,
        "rows": rows,
        "bank": bank_rows,
        "targets": verdicts,
    }


if __name__ == "__main__":
    raise SystemExit(main())
