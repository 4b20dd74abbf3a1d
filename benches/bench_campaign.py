"""Throughput of famcc.campaigns: plant-steps per second, locally and on Dask.

A plant-step is one sample period of one case: a controller step in the bank
plus the plant's RK4 integration over the period. The workload is the paper's
example 1 (LaMC finite-time, ``famcc.scenarios.paper("finite-time")``) on the
second-order family (``--family``) with dispersed gain, disturbance, initial
state and reference, ``--chunk`` cases per chunk (10^4 by default), 1 kHz.

Measured in one run, interleaved over ``--rounds`` rounds; the rates use each
candidate's best round (on a shared machine the least disturbed one) and the
medians are printed beside them:

- ``serial``: one chunk in this process (one core; the baseline);
- ``local``: ``--chunks`` chunks on a ProcessPoolExecutor with ``--jobs`` workers;
- ``dask-1`` / ``dask-2``: the same chunks on a ``distributed.LocalCluster`` of one
  and of two single-threaded worker processes (cluster start-up not timed).

It prints M plant-steps/s and the ratios local / serial and dask-2 / dask-1, and
the load average before and after (the machine is shared). Needs
``pip install -e '.[cluster]'``.

Run: ``python benches/bench_campaign.py [--family dc-motor] [--json out.json]``
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time

import famcc
from famcc.campaigns import Uniform, campaign

DISPERSIONS = {
    "second-order": {
        "gain": Uniform(0.7, 1.3),
        "amp": Uniform(2.0, 4.0),
        "x1(0)": Uniform(-1.5, -0.5),
        "reference.omega": Uniform(0.8, 1.2),
    },
    "dc-motor": {
        "J": Uniform(0.005, 0.02),
        "K": Uniform(0.2, 0.3),
        "R": Uniform(0.8, 1.2),
        "load": Uniform(0.0, 1.0),
    },
}


def _run(args: argparse.Namespace, cases: int, executor: object, chunk: int) -> float:
    """Seconds of one campaign."""
    ctrl = famcc.scenarios.paper("finite-time").controller()
    ref = famcc.Sine() if args.family == "second-order" else famcc.Constant(0.5)
    t0 = time.perf_counter()
    campaign(
        args.family,
        ctrl,
        cases=cases,
        t_end=args.t_end,
        u_limits=(-100.0, 100.0),
        reference=ref,
        eps=0.1,
        dispersion=DISPERSIONS[args.family],
        substeps=args.substeps,
        chunk_size=chunk,
        executor=executor,
        jobs=args.jobs,
        progress=False,
        seed=1,
    )
    return time.perf_counter() - t0


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--family", choices=sorted(DISPERSIONS), default="second-order")
    p.add_argument("--chunk", type=int, default=10_000, help="cases per chunk")
    p.add_argument("--chunks", type=int, default=4, help="chunks of the parallel runs")
    p.add_argument("--t-end", type=float, default=1.0, help="horizon, s")
    p.add_argument("--substeps", type=int, default=1)
    p.add_argument("--jobs", type=int, default=2, help="local worker processes")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--no-dask", action="store_true")
    p.add_argument("--json", default=None, help="write the numbers here")
    args = p.parse_args()

    steps = round(args.t_end / 1e-3)
    load0 = os.getloadavg()
    times: dict[str, list[float]] = {"serial": [], "local": [], "dask-1": [], "dask-2": []}
    clusters = {}
    if not args.no_dask:
        import distributed

        for w in (1, 2):
            cluster = distributed.LocalCluster(
                n_workers=w, threads_per_worker=1, processes=True, dashboard_address=":0"
            )
            clusters[f"dask-{w}"] = (cluster, distributed.Client(cluster))
    try:
        _run(args, args.chunk, "serial", args.chunk)  # warm-up: imports, first bank
        for _ in range(args.rounds):
            times["serial"].append(_run(args, args.chunk, "serial", args.chunk))
            times["local"].append(_run(args, args.chunk * args.chunks, None, args.chunk))
            for name, (_, client) in clusters.items():
                times[name].append(_run(args, args.chunk * args.chunks, client, args.chunk))
    finally:
        for cluster, client in clusters.values():
            client.close()
            cluster.close()
    load1 = os.getloadavg()
    rate, median = {}, {}
    for name, ts in times.items():
        if ts:
            cases = args.chunk if name == "serial" else args.chunk * args.chunks
            rate[name] = cases * steps / min(ts) / 1e6
            median[name] = cases * steps / statistics.median(ts) / 1e6
    print(
        f"family {args.family}, {args.chunk:,} cases per chunk, {steps} steps, substeps "
        f"{args.substeps}, {args.rounds} rounds; load average before "
        f"{load0[0]:.2f} / after {load1[0]:.2f} (1 min), {os.cpu_count()} CPUs"
    )
    for name, r in rate.items():
        print(
            f"  {name:>7}: {r:6.2f} M plant-steps/s best, {median[name]:5.2f} median ("
            f"{', '.join(f'{t:.2f}' for t in times[name])} s)"
        )
    ratios = {}
    if "local" in rate:
        ratios["local/serial"] = rate["local"] / rate["serial"]
    if "dask-2" in rate:
        ratios["dask-2/dask-1"] = rate["dask-2"] / rate["dask-1"]
        ratios["dask-2/serial"] = rate["dask-2"] / rate["serial"]
    for name, r in ratios.items():
        print(f"  {name}: {r:.2f}x")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(
                {
                    "args": vars(args),
                    "load_before": load0,
                    "load_after": load1,
                    "times": times,
                    "M_plant_steps_per_s": rate,
                    "M_plant_steps_per_s_median": median,
                    "ratios": ratios,
                },
                fh,
                indent=1,
            )


if __name__ == "__main__":
    main()
