"""Running a campaign's chunks: serially, on local processes, any Executor, or Dask."""

from __future__ import annotations

import concurrent.futures as cf
import importlib
import json
import os
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from famcc.campaigns.chunk import run_chunk
from famcc.progress import Progress

if TYPE_CHECKING:
    from famcc.campaigns.plan import Campaign


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
