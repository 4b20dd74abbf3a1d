"""Re-inject issue 11's bugs, one at a time, and show which tests catch each.

Each bug of the issue's table is a one-line textual edit of the source (the
anchor must occur exactly once, so an edit that no longer applies fails here
instead of testing nothing). It is applied alone to a scratch copy of the
tracked tree (``target/reinject/tree``, never the checkout itself), the tests
that concern it run there, and the bug counts as caught when at least one of
them fails. Rust bugs run the whole famcc-core suite (or the C ABI's unit
tests); Python bugs run the named test files against the scratch copy's
package, with the extension rebuilt from the mutated core when the bug is in
Rust code behind the binding.

    python scripts/reinject.py            # every bug (about 15 minutes on 2 cores)
    python scripts/reinject.py --only set_state

Exit status 1 when a bug is caught by no test, or an edit does not apply.
Results: docs/mutation.md, "Re-injected bugs".
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCRATCH = ROOT / "target" / "reinject"
TREE = SCRATCH / "tree"
# A build directory of its own, kept between runs: only the edited crates rebuild.
BUILD = SCRATCH / "build"


@dataclass(frozen=True)
class Bug:
    name: str
    what: str
    path: str
    old: str
    new: str
    # "core": the famcc-core suite; "ffi": the C ABI's unit tests;
    # "py": pytest on `pytests` (the extension rebuilt when `rebuild`).
    runs: tuple[str, ...]
    pytests: tuple[str, ...] = ()
    rebuild: bool = False


BUGS = (
    Bug(
        "tustin_gamma",
        "Tustin Gamma scaled by 1.1 (the differentiator's DC gain off by 10 %)",
        "crates/famcc-core/src/differentiator/discretize.rs",
        "                *gi *= tau;\n            }\n            lu_solve",
        "                *gi *= tau * 1.1;\n            }\n            lu_solve",
        ("core",),
    ),
    Bug(
        "lateral_xi",
        "lateral-constraint xi halved",
        "crates/famcc-core/src/constraint/mod.rs",
        "finish(sigma, x_u, x_u, (x_u, T::zero()), flexible)",
        "finish(sigma * T::from_f64(0.5), x_u, x_u, (x_u, T::zero()), flexible)",
        ("core",),
    ),
    Bug(
        "oblique_slope",
        "oblique-constraint slope inverted (m = x_U / y_U)",
        "crates/famcc-core/src/constraint/offset.rs",
        "let m = y_u / x_u;",
        "let m = x_u / y_u;",
        ("core",),
    ),
    Bug(
        "half_output",
        "output -0.5 k_u Gamma(xi)",
        "crates/famcc-core/src/controller/advance.rs",
        "let v = -c.k_u() * c.gamma().eval(eval.xi);",
        "let v = -(T::from_f64(0.5) * c.k_u()) * c.gamma().eval(eval.xi);",
        ("core",),
    ),
    Bug(
        "ffi_gamma",
        "C ABI maps GAMMA_RATIONAL to Log",
        "crates/famcc-ffi/src/convert.rs",
        "(FamccGamma::Rational as u32, Gamma::Rational),",
        "(FamccGamma::Rational as u32, Gamma::Log),",
        ("ffi",),
    ),
    Bug(
        "check_empty",
        "Scenario.check always returns []",
        "python/famcc/scenarios.py",
        "        return [v.text() for v in self.verdicts(result) if v.failed]",
        "        return []",
        ("py",),
        ("tests/test_verdicts.py", "tests/test_invariants.py"),
    ),
    Bug(
        "performance_ok",
        "the sweep's performance_ok replaced by True",
        "python/famcc/sweep/run.py",
        '        r["performance_ok"] = ok',
        '        r["performance_ok"] = True',
        ("py",),
        ("tests/test_reproduce.py",),
    ),
    Bug(
        "set_state",
        "set_state drops clamp_count (Controller::restore)",
        "crates/famcc-core/src/controller/snapshot.rs",
        "        st.diag.clamp_count = snap.clamp_count;\n",
        "",
        ("core", "py"),
        ("tests/test_api.py", "tests/test_bad_input.py"),
        rebuild=True,
    ),
)


def sh(args: list[str], cwd: Path, log: Path, env: dict[str, str] | None = None) -> int:
    with log.open("w") as f:
        return subprocess.run(
            args, cwd=cwd, env=env, stdout=f, stderr=subprocess.STDOUT, check=False
        ).returncode


def fresh_tree() -> None:
    """The tracked files of the checkout, as they are in the work tree."""
    files = subprocess.run(
        ["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True
    ).stdout.split(b"\0")
    if TREE.exists():
        shutil.rmtree(TREE)
    for rel in filter(None, files):
        src = ROOT / rel.decode()
        if src.is_file():
            dst = TREE / rel.decode()
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst)


def failed_tests(log: Path) -> list[str]:
    """The failing tests a cargo test or pytest log names."""
    text = log.read_text(errors="replace")
    rust = re.findall(r"^test (\S+) \.\.\. FAILED", text, re.MULTILINE)
    py = re.findall(r"^FAILED (\S+)", text, re.MULTILINE)
    return rust + py


def extension(env: dict[str, str], log: Path) -> Path | None:
    """Builds the scratch tree's extension module; its path, or None."""
    rc = sh(
        ["cargo", "build", "--release", "-p", "famcc-py", "--features", "extension-module"],
        TREE,
        log,
        env,
    )
    built = BUILD / "release" / "lib_core.so"
    return built if rc == 0 and built.is_file() else None


def run(bug: Bug) -> tuple[bool, list[str], str]:
    """(caught, the failing tests, a note) for one bug."""
    fresh_tree()
    path = TREE / bug.path
    text = path.read_text()
    if text.count(bug.old) != 1:
        return (
            False,
            [],
            f"the edit no longer applies ({text.count(bug.old)} anchors in {bug.path})",
        )
    path.write_text(text.replace(bug.old, bug.new))
    env = dict(os.environ, CARGO_TARGET_DIR=str(BUILD), CARGO_PROFILE_TEST_DEBUG="0")
    logs = SCRATCH / "logs"
    logs.mkdir(parents=True, exist_ok=True)
    failing: list[str] = []
    notes: list[str] = []
    for what in bug.runs:
        log = logs / f"{bug.name}-{what}.log"
        if what == "core":
            rc = sh(["cargo", "test", "-p", "famcc-core", "--lib", "--tests"], TREE, log, env)
        elif what == "ffi":
            ffi_env = dict(env, CARGO_TARGET_DIR=str(BUILD / "ffi"))
            rc = sh(
                ["cargo", "test", "--manifest-path", "crates/famcc-ffi/Cargo.toml", "--lib"],
                TREE,
                log,
                ffi_env,
            )
        else:
            so = ROOT / "python" / "famcc" / "_core.abi3.so"
            if bug.rebuild:
                built = extension(env, logs / f"{bug.name}-extension.log")
                if built is None:
                    return False, [], "the extension did not build"
                so = built
            shutil.copy2(so, TREE / "python" / "famcc" / "_core.abi3.so")
            py_env = dict(env, PYTHONPATH=str(TREE / "python"), MPLBACKEND="Agg")
            # The package under test must be the scratch copy's.
            probe = subprocess.run(
                [sys.executable, "-c", "import famcc; print(famcc.__file__)"],
                cwd=TREE,
                env=py_env,
                capture_output=True,
                text=True,
                check=False,
            ).stdout.strip()
            if not probe.startswith(str(TREE)):
                return False, [], f"famcc imports from {probe}, not the scratch copy"
            rc = sh(
                [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *bug.pytests],
                TREE,
                log,
                py_env,
            )
        found = failed_tests(log)
        if rc != 0 and not found:
            notes.append(f"{what}: exit {rc} without a failing test (see {log})")
        failing += [f"{what}: {t}" for t in found]
    return bool(failing), failing, "; ".join(notes)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", action="append", choices=[b.name for b in BUGS])
    args = ap.parse_args()
    bugs = [b for b in BUGS if not args.only or b.name in args.only]
    missed = 0
    for i, bug in enumerate(bugs, 1):
        t0 = time.monotonic()
        print(f"[{i}/{len(bugs)}] {bug.what} ...", flush=True)
        caught, failing, note = run(bug)
        status = "caught" if caught else "NOT CAUGHT"
        print(
            f"  {status} by {len(failing)} tests ({time.monotonic() - t0:.0f} s){': ' + note if note else ''}"
        )
        for t in failing[:12]:
            print(f"    {t}")
        if len(failing) > 12:
            print(f"    ... and {len(failing) - 12} more")
        missed += not caught
    print(f"{len(bugs) - missed} of {len(bugs)} bugs caught")
    return 1 if missed else 0


if __name__ == "__main__":
    sys.exit(main())
