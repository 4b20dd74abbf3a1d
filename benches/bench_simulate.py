"""``famcc.simulate`` against another commit of famcc, in the same run.

Times the README's quick-start simulation (the paper's example 1: 10 s at
1 kHz, the default substeps, the diagnostics recorded, ``y_d = sin t``, limits
``[-2.5, 3]``) and more workloads -- example 3 saturated, the DC motor (a plant
written in Python), a 200-case campaign of example 1, example 1's 10^4 bare
``step`` calls (``steps``: what ``ex1`` costs over them), a paper scenario's
``run()``, ``famcc.tune`` of example 1 and ``famcc reproduce`` -- with the
working tree's famcc and with a baseline commit's, alternating A and B runs
so that the machine's load drifts out of the ratios. Also counts the calls
into the compiled extension per simulated sample (the loop's crossings).

The baseline is built once, as a wheel from ``git worktree`` of ``--baseline``
(default ``931cf83``, the commit before the simulator was rebuilt), into
``target/bench-baseline/`` (a venv of its own; reused while the commit matches).

Usage::

    python benches/bench_simulate.py [--baseline REV] [--rounds 7] [--json out.json]

Prints per workload: min and median seconds of each side and the ratio
baseline / current of the medians of the paired rounds.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import venv
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WORK = ROOT / "target" / "bench-baseline"

#: The child: one workload, timed ``--repeat`` times, prints JSON.
CHILD = r"""
import json, sys, time, warnings, cProfile, pstats
warnings.simplefilter("ignore")
import famcc

def ex1():
    ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5), constraint="lateral",
                            eps=0.1, k_u=5.0)
    return famcc.simulate(famcc.plants.second_order("code"), ctrl, 10.0,
                          reference=famcc.Sine(), u_limits=(-2.5, 3.0))

def ex3():
    return famcc.scenarios.paper("rfc-saturated").run(dt=1e-3)

def motor():
    ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=2.0, p=0.7), constraint="lateral",
                            eps=0.02, k_u=20.0)
    return famcc.simulate(famcc.plants.dc_motor(), ctrl, 5.0, reference=famcc.Constant(1.0),
                          u_limits=(-12, 12))

def campaign():
    from famcc.campaigns import Uniform
    ctrl = famcc.scenarios.paper("finite-time-saturated").controller(1e-3)
    return famcc.campaign("second-order", ctrl, cases=200, t_end=10.0, reference=famcc.Sine(),
                          u_limits=(-2.5, 3.0), dispersion={"gain": Uniform(0.8, 1.2)},
                          executor="serial", progress=False)

def steps():
    # the bare cost of ex1's 10^4 samples: the controller alone, no plant, no recording
    ctrl = famcc.Controller(2, 1e-3, famcc.FiniteTime(k=1.0, p=0.5), constraint="lateral",
                            eps=0.1, k_u=5.0)
    step = ctrl.step
    for k in range(10001):
        step(0.01 * (k % 7) - 0.03)

def scenario():
    return famcc.scenarios.paper("finite-time").run()

def tune():
    return famcc.tune(famcc.plants.second_order("code"), dt=1e-3, u_limits=(-2.5, 3.0),
                      eps=0.1, settle_time=3.0, reference=famcc.Sine(), progress=False)

def reproduce():
    import contextlib, io, tempfile
    from famcc.cli import main
    with tempfile.TemporaryDirectory() as d, contextlib.redirect_stdout(io.StringIO()):
        main(["reproduce", "--out", d])

name, repeat = sys.argv[1], int(sys.argv[2])
fn = globals()[name]
fn()  # warm up
times = []
for _ in range(repeat):
    t0 = time.perf_counter()
    fn()
    times.append(time.perf_counter() - t0)
crossings = None
if name == "ex1":
    prof = cProfile.Profile()
    prof.enable(); res = fn(); prof.disable()
    calls = sum(st[1] for key, st in pstats.Stats(prof).stats.items()
                if "famcc._core" in str(key[2]) or "of 'famcc._core" in str(key[2]))
    crossings = calls / len(res.t)
print(json.dumps({"times": times, "crossings_per_sample": crossings,
                  "version": famcc.__file__}))
"""

WORKLOADS = ("ex1", "ex3", "motor", "campaign", "steps", "scenario", "tune", "reproduce")


def baseline_python(rev: str) -> Path:
    """The baseline's interpreter, building it when missing or for another commit."""
    src, env = WORK / "src", WORK / "venv"
    stamp = WORK / "rev"
    full = subprocess.check_output(["git", "rev-parse", rev], cwd=ROOT, text=True).strip()
    py = env / ("Scripts/python.exe" if os.name == "nt" else "bin/python")
    if stamp.exists() and stamp.read_text() == full and py.exists():
        return py
    print(f"building the baseline {full[:10]} into {WORK} (once; a few minutes)", flush=True)
    WORK.mkdir(parents=True, exist_ok=True)
    subprocess.run(
        ["git", "worktree", "remove", "--force", str(src)],
        cwd=ROOT,
        check=False,
        capture_output=True,
    )
    subprocess.run(
        ["git", "worktree", "add", "--force", "--detach", str(src), full], cwd=ROOT, check=True
    )
    venv.create(env, with_pip=True)
    env_vars = dict(os.environ, CARGO_TARGET_DIR=str(WORK / "cargo"))
    subprocess.run([str(py), "-m", "pip", "install", "-q", str(src)], check=True, env=env_vars)
    stamp.write_text(full)
    return py


def run(py: str, name: str, repeat: int) -> dict:
    out = subprocess.run(
        [py, "-c", CHILD, name, str(repeat)],
        capture_output=True,
        text=True,
        cwd=str(WORK),
        check=True,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", default="931cf83")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json")
    ap.add_argument("--only", nargs="+", choices=WORKLOADS, help="these workloads only")
    args = ap.parse_args()
    base = str(baseline_python(args.baseline))
    here = sys.executable
    report = {}
    for name in args.only or WORKLOADS:
        a, b, ratios, cross = [], [], [], None
        for _ in range(args.rounds):
            ra = run(base, name, args.repeat)
            rb = run(here, name, args.repeat)
            a.append(min(ra["times"]))
            b.append(min(rb["times"]))
            ratios.append(a[-1] / b[-1])
            cross = (ra["crossings_per_sample"], rb["crossings_per_sample"])
        report[name] = {
            "baseline_s": a,
            "current_s": b,
            "ratio_median": statistics.median(ratios),
            "crossings_per_sample": cross,
        }
        line = (
            f"{name:9s} baseline {min(a):8.4f} s (median {statistics.median(a):.4f})  "
            f"current {min(b):8.4f} s (median {statistics.median(b):.4f})  "
            f"speed-up {statistics.median(ratios):6.1f}x"
        )
        if cross and cross[0] is not None:
            line += f"  calls into famcc._core per sample: {cross[0]:.2f} -> {cross[1]:.4f}"
        print(line, flush=True)
    if args.json:
        Path(args.json).write_text(json.dumps(report, indent=1))


if __name__ == "__main__":
    main()
