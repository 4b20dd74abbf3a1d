"""Mutation testing of python/famcc with cosmic-ray (docs/mutation.md, "Python").

Run through scripts/mutants-py.sh. The mutants are cosmic-ray's, restricted to
the plausible operators (OPERATORS) and to the verdict and metric code
(TARGETS); each is tested against its module's tests only, in a scratch copy
of the package (target/mutants-py/<mode>/tree), so the work tree is never
mutated, even when a run is killed.

    mutants_py.py [--slice] [--full] [--list] [--target PATH]

--slice (the default): MUTANTS_PY_COUNT (default 5) mutants drawn with the
seed MUTANTS_PY_SEED (default 11) from all the targets' mutants; --full: all of
them; --target PATH (repeatable): only those modules'. --list prints the
mutants and runs none; MUTANTS_PY_OUT names the report directory.
A survivor not triaged in .mutants-py-equivalent.txt makes the run exit 2.
"""

from __future__ import annotations

import argparse
import ast
import os
import random
import shutil
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from mutants_py_targets import OPERATORS, TARGETS, Target

ROOT = Path(__file__).resolve().parent.parent
TRIAGE = ROOT / ".mutants-py-equivalent.txt"
#: What the test command prints when it could not test a mutant.
SETUP_ERROR = "mutants-py: setup error"


#: Seconds a mutant's tests may take; a mutant that hangs is caught.
TIMEOUT = float(os.environ.get("MUTANTS_PY_TIMEOUT", "300"))


# -- where a mutant is ---------------------------------------------------------


def _spans(tree: ast.Module) -> tuple[list[tuple[str, int, int]], list[tuple[int, int, int, int]]]:
    """The definitions ``(qualname, first, last line)`` and the annotations' spans."""
    defs: list[tuple[str, int, int]] = []
    notes: list[tuple[int, int, int, int]] = []

    def note(n: ast.expr | None) -> None:
        if n is not None:
            notes.append((n.lineno, n.col_offset, n.end_lineno or n.lineno, n.end_col_offset or 0))

    def visit(node: ast.AST, prefix: str) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
                name = prefix + child.name
                defs.append((name, child.lineno, child.end_lineno or child.lineno))
                if not isinstance(child, ast.ClassDef):
                    a = child.args
                    for arg in [*a.posonlyargs, *a.args, *a.kwonlyargs, a.vararg, a.kwarg]:
                        note(arg.annotation if arg is not None else None)
                    note(child.returns)
                visit(child, name + ".")
            else:
                if isinstance(child, ast.AnnAssign):
                    note(child.annotation)
                visit(child, prefix)

    visit(tree, "")
    return defs, notes


def _qualname(defs: list[tuple[str, int, int]], line: int) -> str:
    """The innermost definition holding ``line`` ("<module>" outside all)."""
    best = ("<module>", 0, 10**9)
    for name, first, last in defs:
        if first <= line <= last and last - first <= best[2] - best[1]:
            best = (name, first, last)
    return best[0]


def _in_annotation(notes: list[tuple[int, int, int, int]], pos: tuple[int, int]) -> bool:
    # With `from __future__ import annotations` an annotation is never evaluated:
    # mutating one changes nothing (a `float | None` turned into `float + None`).
    return any((l0, c0) <= pos < (l1, c1) for l0, c0, l1, c1 in notes)


def _strip_comment(line: str) -> str:
    return line.split("  #", 1)[0].strip()


# -- the run -------------------------------------------------------------------


def _copy_tree(tree: Path) -> None:
    """A scratch copy of the package (the compiled extension with it) and the tests."""
    if tree.exists():
        shutil.rmtree(tree)
    ignore = shutil.ignore_patterns("__pycache__", ".pytest_cache", ".hypothesis")
    shutil.copytree(ROOT / "python", tree / "python", ignore=ignore)
    shutil.copytree(ROOT / "tests", tree / "tests", ignore=ignore)
    shutil.copy2(ROOT / "pyproject.toml", tree / "pyproject.toml")
    if not any((tree / "python" / "famcc").glob("_core*")):
        sys.exit("mutants-py: famcc._core is not built in python/famcc (pip install -e .)")


def _cosmic_ray(*args: str, cwd: Path, env: dict[str, str]) -> None:
    subprocess.run([sys.executable, "-m", "cosmic_ray.cli", *args], cwd=cwd, env=env, check=True)


def _triaged() -> list[str]:
    """The names in the triage file; one ending in ``*`` stands for all that start so."""
    out = []
    if TRIAGE.exists():
        for line in TRIAGE.read_text().splitlines():
            if line.strip() and not line.startswith("#"):
                out.append(line.rsplit("  # ", 1)[0].strip())
    return out


def _is_triaged(name: str, triaged: list[str]) -> bool:
    return any(name.startswith(t[:-1]) if t.endswith("*") else name == t for t in triaged)


def _name(path: str, operator: str, qual: str, diff: str) -> str:
    """``file: qualname: operator: old line -> new line``, free of line numbers."""
    old = [ln[1:] for ln in diff.splitlines() if ln.startswith("-") and not ln.startswith("---")]
    new = [ln[1:] for ln in diff.splitlines() if ln.startswith("+") and not ln.startswith("+++")]
    change = f"{' / '.join(map(_strip_comment, old))} -> {' / '.join(map(_strip_comment, new))}"
    return f"{path}: {qual}: {operator.removeprefix('core/')}: {change}"


def _where(targets: list[Target], tree: Path) -> dict[str, tuple[Target, list[Any], list[Any]]]:
    out = {}
    for t in targets:
        defs, notes = _spans(ast.parse((tree / t.path).read_text()))
        out[str(tree / t.path)] = (t, defs, notes)
    return out


def _listed(path: str, operator: str, occurrence: int) -> str:
    """How --list and missed.txt name a mutant (with its occurrence: for --only)."""
    return f"{path}: {operator} #{occurrence}"


def _select(
    session: Path,
    targets: list[Target],
    tree: Path,
    sample: tuple[int, int] | None,
    only: set[str] | None = None,
) -> tuple[list[tuple[str, str, int]], int]:
    """Marks every mutant but the chosen ones skipped; returns the chosen and the total.

    The mutants are those of OPERATORS in the targets' scopes, outside annotations;
    ``sample = (seed, count)`` draws ``count`` of them, sorted by module, operator
    and occurrence, with ``random.Random(seed)``; ``only`` keeps those it lists.
    """
    from cosmic_ray.work_db import WorkDB, use_db  # type: ignore[import-untyped]
    from cosmic_ray.work_item import WorkerOutcome, WorkResult  # type: ignore[import-untyped]

    where = _where(targets, tree)
    keep: list[tuple[str, str, int, str]] = []  # (target path, operator, occurrence, job id)
    with use_db(str(session), WorkDB.Mode.open) as db:
        drop = []
        for item in db.pending_work_items:
            (m,) = item.mutations
            t, defs, notes = where[str(m.module_path)]
            qual = _qualname(defs, m.start_pos[0])
            in_scope = not t.scope or any(qual == s or qual.startswith(s + ".") for s in t.scope)
            if (
                OPERATORS.match(m.operator_name)
                and in_scope
                and not _in_annotation(notes, m.start_pos)
            ):
                keep.append((t.path, m.operator_name, m.occurrence, item.job_id))
            else:
                drop.append(item.job_id)
        keep.sort()
        chosen = keep
        if only is not None:
            chosen = [k for k in keep if _listed(*k[:3]) in only]
        elif sample is not None:
            seed, count = sample
            chosen = sorted(random.Random(seed).sample(keep, min(count, len(keep))))
        ids = {k[3] for k in chosen}
        drop += [k[3] for k in keep if k[3] not in ids]
        db.set_multiple_results(drop, WorkResult(worker_outcome=WorkerOutcome.SKIPPED))
    return [k[:3] for k in chosen], len(keep)


def _report(out: Path, session: Path, targets: list[Target], tree: Path, took: float | None) -> int:
    """Prints and writes (outcomes.txt, missed.diff, triaged.diff) the session's outcomes.

    Returns 2 when a survivor is not triaged (or a mutant could not be tested).
    """
    from cosmic_ray.work_db import WorkDB, use_db
    from cosmic_ray.work_item import WorkerOutcome

    for old in ("missed.diff", "triaged.diff", "outcomes.txt", "missed.txt"):
        (out / old).unlink(missing_ok=True)
    missed = []
    where = _where(targets, tree)
    triaged = _triaged()
    lines, untriaged = [], []
    counts = {"caught": 0, "missed": 0, "triaged": 0, "error": 0, "pending": 0}
    with use_db(str(session), WorkDB.Mode.open) as db:
        done = {item.job_id for item, _ in db.completed_work_items}
        counts["pending"] = sum(1 for item in db.work_items if item.job_id not in done)
        for item, result in db.completed_work_items:
            if result.worker_outcome == WorkerOutcome.SKIPPED:
                continue
            (m,) = item.mutations
            t, defs, _ = where[str(m.module_path)]
            qual = _qualname(defs, m.start_pos[0])
            name = _name(t.path, m.operator_name, qual, result.diff or "")
            if (
                result.worker_outcome != WorkerOutcome.NORMAL
                or result.test_outcome == "incompetent"
                or SETUP_ERROR in (result.output or "")
            ):
                status = "error"
                untriaged.append(f"{name} (could not test: {result.worker_outcome})")
            elif result.test_outcome == "killed":
                status = "caught"
            elif _is_triaged(name, triaged):
                status = "triaged"
            else:
                status = "missed"
                untriaged.append(name)
            counts[status] += 1
            lines.append(f"{status}: {name}")
            if status == "missed":
                missed.append(_listed(t.path, m.operator_name, m.occurrence))
            if status in ("missed", "triaged"):
                with (out / f"{status}.diff").open("a") as f:
                    f.write(f"# {name}\n{result.diff}\n")
    lines.sort()
    (out / "outcomes.txt").write_text("\n".join(lines) + "\n")
    (out / "missed.txt").write_text("".join(f"{m}\n" for m in sorted(missed)))
    print("\n".join(lines))
    pending = f", {counts['pending']} not run" if counts["pending"] else ""
    print(
        f"python mutation testing: {counts['caught']} caught, {counts['missed']} missed, "
        f"{counts['triaged']} survived as triaged equivalent, {counts['error']} errors{pending}"
        + ("" if took is None else f" in {took:.0f} s")
        + f" (report: {out.relative_to(ROOT)}/outcomes.txt)"
    )
    if untriaged:
        print(
            "python mutation testing failed: kill each survivor with a test or triage it in "
            ".mutants-py-equivalent.txt (docs/mutation.md):\n  " + "\n  ".join(untriaged),
            file=sys.stderr,
        )
        return 2
    return 0


def test_command(tree: Path) -> int:
    """The test command cosmic-ray runs per mutant: the mutated module's tests.

    pytest's status passes through (1: a test failed, 2: the mutant broke the
    collection; both catch it), but a run that could not test (usage error, no
    tests, no mutated module) prints SETUP_ERROR, which the report counts as an
    error, not as a caught mutant.
    """
    mutated = [t for t in TARGETS if (tree / t.path).read_bytes() != (ROOT / t.path).read_bytes()]
    if len(mutated) != 1:
        print(f"{SETUP_ERROR}: {len(mutated)} targets differ from the work tree's", flush=True)
        return 1
    (t,) = mutated
    os.chdir(tree)
    import pytest

    rc = int(
        pytest.main(["-x", "-q", "-p", "no:cacheprovider", *t.tests, "--doctest-modules", t.path])
    )
    if rc in (pytest.ExitCode.USAGE_ERROR, pytest.ExitCode.NO_TESTS_COLLECTED):
        print(f"{SETUP_ERROR}: pytest exited with {rc}", flush=True)
    return rc


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--full", action="store_true", help="every mutant of the targets")
    p.add_argument("--slice", action="store_true", help="the seeded slice (the default)")
    p.add_argument("--target", action="append", help="only this module (repeatable)")
    p.add_argument("--list", action="store_true", help="print the mutants, run none")
    p.add_argument("--report", action="store_true", help="report the last run's results again")
    p.add_argument(
        "--only",
        metavar="FILE",
        help="only the mutants listed in FILE, as --list prints them (e.g. a run's missed.txt)",
    )
    p.add_argument("--test-tree", help=argparse.SUPPRESS)
    a = p.parse_args()
    if a.test_tree:
        return test_command(Path(a.test_tree))
    targets = [t for t in TARGETS if a.target is None or t.path in a.target]
    unknown = set(a.target or ()) - {t.path for t in TARGETS}
    if unknown or not targets:
        sys.exit(f"mutants-py: not a target: {unknown} ({', '.join(t.path for t in TARGETS)})")
    seed = int(os.environ.get("MUTANTS_PY_SEED", "11"))
    count = int(os.environ.get("MUTANTS_PY_COUNT", "5"))
    mode = "full" if a.full else "slice"
    out = ROOT / "target" / "mutants-py" / os.environ.get("MUTANTS_PY_OUT", mode)
    tree = out / "tree"
    config = out / "cosmic-ray.toml"
    session = out / "session.sqlite"
    if a.report:
        return _report(out, session, targets, tree, None)
    out.mkdir(parents=True, exist_ok=True)
    _copy_tree(tree)
    start = time.monotonic()

    env = dict(os.environ, PYTHONPATH=str(tree / "python"))
    session.unlink(missing_ok=True)
    command = f"{sys.executable} {Path(__file__).resolve()} --test-tree {tree}"
    config.write_text(
        "[cosmic-ray]\n"
        f"module-path = {[str(tree / t.path) for t in targets]!r}\n"
        f"timeout = {TIMEOUT}\n"
        "excluded-modules = []\n"
        f"test-command = {command!r}\n\n"
        '[cosmic-ray.distributor]\nname = "local"\n'
    )
    _cosmic_ray("init", str(config), str(session), cwd=tree, env=env)

    only = None if a.only is None else set(Path(a.only).read_text().split("\n")) - {""}
    sample = None if mode == "full" or only is not None else (seed, count)
    chosen, total = _select(session, targets, tree, sample, only)
    what = (
        f"{len(chosen)} of {total} mutants listed in {a.only}"
        if only is not None
        else f"seeded slice: {len(chosen)} of {total} mutants (MUTANTS_PY_SEED={seed}, "
        f"MUTANTS_PY_COUNT={count})"
        if mode == "slice"
        else f"all {total} mutants"
    )
    print(f"python mutation testing (cosmic-ray): {what} of {', '.join(t.path for t in targets)}")
    if a.list:
        for path, op, occ in chosen:
            print(_listed(path, op, occ))
        return 0

    _cosmic_ray("exec", str(config), str(session), cwd=tree, env=env)

    return _report(out, session, targets, tree, time.monotonic() - start)


if __name__ == "__main__":
    sys.exit(main())
