"""The worker processes: one task's run and metrics, and the pool that maps task lists.

:func:`_work` is what the pool submits, so it stays a module-level function.
"""

from __future__ import annotations

import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from typing import Any

from famcc.compare.plants import _case
from famcc.compare.runs import metrics, run


def _work(task: dict[str, Any]) -> dict[str, Any]:
    """The worker: one run of a task, its metrics (never raises for a failed loop)."""
    t0 = time.perf_counter()
    own = task.pop("own_case", None)  # a case of the user's own travels with its task
    case = own if own is not None else _case(task["case"])
    horizon = task.get("t_end") or case.t_end
    try:
        res = run(
            case,
            task["kind"],
            task["params"],
            task["condition"],
            factors=task.get("factors"),
            t_end=horizon,
            seed=task.get("seed", 0),
        )
        m = metrics(case, res, horizon)
    except (ValueError, FloatingPointError, ArithmeticError) as exc:
        m = {"diverged": True, "never_settled": True, "objective": 1e6, "error": str(exc)}
    m["runtime_s"] = time.perf_counter() - t0
    return {**task, "metrics": m}


class _Pool:
    """Runs task lists in parallel (or in-process for ``jobs == 1``) with a progress bar."""

    def __init__(self, jobs: int, progress: Any, own: dict[str, Any] | None = None) -> None:
        self.jobs, self.progress = jobs, progress
        self.own = own or {}
        self.ex = ProcessPoolExecutor(max_workers=jobs) if jobs > 1 else None

    def map(self, tasks: list[dict[str, Any]]) -> list[dict[str, Any]]:
        out: list[dict[str, Any]] = [{} for _ in tasks]
        tasks = [
            {**t, "own_case": self.own[t["case"]]} if t["case"] in self.own else t for t in tasks
        ]
        if self.ex is None:
            for i, t in enumerate(tasks):
                out[i] = _work(t)
                self._tick(out[i])
            return out
        futures = {self.ex.submit(_work, t): i for i, t in enumerate(tasks)}
        for fut in as_completed(futures):
            out[futures[fut]] = fut.result()
            self._tick(out[futures[fut]])
        return out

    def _tick(self, r: dict[str, Any]) -> None:
        if self.progress is not None:
            tag = "diverged" if r["metrics"].get("diverged") else "ok"
            label = f"{r['stage']} {r['case']} {r['kind']} {r['condition']} ({tag})"
            self.progress.step(label, r["metrics"]["runtime_s"])

    def close(self) -> None:
        if self.ex is not None:
            self.ex.shutdown()
