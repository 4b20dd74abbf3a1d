"""famcc's task runner (https://nox.thea.codes): one session per kind of check.

    nox -l                  the sessions
    nox -s lint             one session (or several: nox -s rust python)
    nox                     the test command's sessions, one after the other

The sessions (README.md, "Quick start"):

    lint      cargo fmt --check, clippy -D warnings and rustdoc (warnings denied) on the root,
              C ABI and firmware workspaces (host builds: no cross toolchain needed), ruff
              check and format, mypy --strict, actionlint, bash -n on the scripts;
              `lint(rust)` and `lint(python)` run one half
    rust      the Rust tests: famcc-core and the other library crates of the root workspace
              (unit, property, golden, closed-loop, doctests), the benchmarks in criterion's
              test mode, famcc-core with every option compiled out, the no_std build, the C
              ABI's own tests
    python    installs the package (editable) with the test, docs and cluster extras, then
              pytest on every core and the docstring examples
    docs      the documentation site: mkdocs build --strict
    firmware  scripts/firmware-check.sh: QEMU, an ARM gcc and Debian's Rust, which it
              installs with apt-get (sudo) when missing
    mutants   the seeded mutation slices side by side: scripts/mutants.sh (installs
              cargo-mutants) and scripts/mutants-py.sh (cosmic-ray: the mutation extra)
    wheels    scripts/build-wheels.sh (manylinux wheels and the sdist; tools in
              .venv-wheels/, rustup targets) and scripts/test-wheel.sh on this machine's wheel

The test command, ./scripts/test.sh, runs lint, rust, python and docs in two lanes side by
side (cargo's, and the Python package's); `./scripts/test.sh -s NAME` runs a named session
in the test environment. .ci/run is the test command, then firmware, then mutants.

Every session runs in the current virtual environment (venv_backend "none": nothing is
installed twice): ./scripts/test.sh makes .venv-test/ and activates it; run by hand, activate
a virtual environment first (a session that installs refuses to run outside one). With
FAMCC_TIMES set to a file, each step appends `seconds<TAB>name` to it (the test command's
table of phases).
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import nox

ROOT = Path(__file__).resolve().parent
nox.options.default_venv_backend = "none"
nox.options.sessions = ["lint", "rust", "python", "docs"]  # the test command's
nox.options.error_on_missing_interpreters = True

#: The three Cargo workspaces (docs/design.md §9.1) and the extra flags of their clippy run
#: (the firmware's size probes, features ex1 and ex3, are linted too).
WORKSPACES = {
    "Cargo.toml": (),
    "crates/famcc-ffi/Cargo.toml": (),
    "embedded/Cargo.toml": ("--all-features",),
}
#: The extras the test command's sessions need together: one install serves them all.
EXTRAS = ("test", "docs", "cluster")
#: What ruff checks and formats.
PY_SOURCES = ("python", "tests", "benches", "examples", "noxfile.py")
#: The extension's profile for the tests (Cargo.toml): release without fat LTO, 16 codegen
#: units; a quarter less build time, the same numbers (no float reassociation at any
#: level). The wheels keep the release profile.
EXT_PROFILE = "quick-release"


@contextmanager
def timed(session: nox.Session, name: str) -> Iterator[None]:
    """Times a step: logged, and appended to $FAMCC_TIMES when set."""
    t0 = time.monotonic()
    try:
        yield
    finally:
        dt = time.monotonic() - t0
        session.log(f"{name}: {dt:.0f} s")
        if out := os.environ.get("FAMCC_TIMES"):
            with open(out, "a", encoding="utf-8") as f:
                f.write(f"{dt:.0f}\t{name}\n")


def python() -> str:
    """The interpreter of the active virtual environment; an error outside one."""
    venv = os.environ.get("VIRTUAL_ENV")
    if venv and (Path(venv) / "bin" / "python").exists():
        return str(Path(venv) / "bin" / "python")
    if sys.prefix != sys.base_prefix:
        return sys.executable
    raise RuntimeError(
        "not in a virtual environment: run ./scripts/test.sh -s NAME (the test environment "
        ".venv-test/), or activate one first; a session never installs into the system Python"
    )


_installed: set[str] = set()


def install(session: nox.Session, *extras: str) -> None:
    """pip install -e '.[EXTRAS + extras]', once per nox run (the sessions of one run share it).

    The extension builds with the profile EXT_PROFILE in target/python-build, a build
    directory of its own, so that it never waits for the lock of a cargo run beside it.
    """
    want = set(EXTRAS) | set(extras)
    if want <= _installed:
        return
    try:
        py = python()
    except RuntimeError as e:
        session.error(str(e))
    with timed(session, f"install (pip install -e '.[{','.join(sorted(want))}]')"):
        session.run(
            py, "-m", "pip", "install", "--quiet", "--disable-pip-version-check",
            "-e", f".[{','.join(sorted(want))}]",
            env={
                "CARGO_TARGET_DIR": str(ROOT / "target" / "python-build"),
                "MATURIN_PEP517_ARGS": f"--profile {EXT_PROFILE}",
            },
            external=True,
        )  # fmt: skip
    _installed.update(want)


def cargo(session: nox.Session, *args: str, env: dict[str, str] | None = None) -> None:
    session.run("cargo", *args, env=env, external=True)


@nox.session
@nox.parametrize("part", ["rust", "python"], ids=["rust", "python"])
def lint(session: nox.Session, part: str) -> None:
    """Lints: cargo fmt, clippy, rustdoc (3 workspaces); ruff, mypy --strict, actionlint."""
    if part == "rust":
        with timed(session, "lint(rust): fmt, clippy, rustdoc (3 workspaces)"):
            for manifest, flags in WORKSPACES.items():
                cargo(session, "fmt", "--all", "--manifest-path", manifest, "--", "--check")
                cargo(session, "clippy", "--manifest-path", manifest, "--workspace",
                      "--all-targets", *flags, "--", "-D", "warnings")  # fmt: skip
                cargo(session, "doc", "--manifest-path", manifest, "--workspace", "--no-deps",
                      "--quiet", env={"RUSTDOCFLAGS": "-D warnings"})  # fmt: skip
            # famcc-core with every optional design and option compiled out (src/compiled.rs).
            cargo(session, "clippy", "-p", "famcc-core", "--no-default-features", "--lib",
                  "--test", "compiled_out", "--", "-D", "warnings")  # fmt: skip
        return
    install(session)
    py = python()
    with timed(session, "lint(python): ruff, mypy --strict, actionlint"):
        session.run(py, "-m", "ruff", "check", *PY_SOURCES, external=True)
        session.run(py, "-m", "ruff", "format", "--check", *PY_SOURCES, external=True)
        session.run(py, "-m", "mypy", "--strict", "python/famcc", external=True)
        # The release workflows, and the scripts' syntax.
        scripts = Path(py).parent
        session.run(str(scripts / "actionlint"), "-no-color", external=True)
        shell = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "scripts").glob("*.sh"))
        session.run("bash", "-n", *shell, ".ci/run", external=True)


@nox.session
def rust(session: nox.Session) -> None:
    """The Rust tests, the benches in test mode, the no_std build, the C ABI's tests.

    famcc-py (the extension) is tested through Python: the python session.
    """
    with timed(session, "rust: cargo tests (libraries, benches, compiled out, no_std, C ABI)"):
        cargo(session, "test", "--workspace", "--exclude", "famcc-py")
        # Every benchmark workload builds its controller and steps once (criterion's test
        # mode): a design the validation rules reject fails here, not in a bench run.
        cargo(session, "test", "-q", "-p", "famcc-core", "--benches")
        # A design compiled out is rejected, naming its feature; the rest runs.
        cargo(session, "test", "-q", "-p", "famcc-core", "--no-default-features",
              "--test", "compiled_out")  # fmt: skip
        # no_std: both build without the standard library.
        cargo(session, "build", "-p", "famcc-core", "-p", "famcc-paper")
        # The C ABI (its own workspace: a no_std staticlib with panic = "abort").
        cargo(session, "test", "--manifest-path", "crates/famcc-ffi/Cargo.toml", "--lib")


@nox.session(name="python")
def python_(session: nox.Session) -> None:
    """The editable install, pytest on every core, the docstring examples.

    Arguments after -- go to pytest (nox -s python -- -k campaign).
    """
    install(session)
    py = python()
    workers = str(max(2, os.cpu_count() or 2))
    with timed(session, f"python: pytest -n {workers}"):
        # Whole files per worker (a module's fixtures run once). The test command installs
        # the cluster extra, so its tests must run: a missing dask is an error, not a skip.
        session.run(py, "-m", "pytest", "-q", "-n", workers, "--dist", "loadfile",
                    "--require-extra", "cluster", *session.posargs, external=True)  # fmt: skip
    with timed(session, "python: doctests"):
        session.run(py, "-m", "pytest", "-q", "--doctest-modules", "python/famcc", external=True)


@nox.session
def docs(session: nox.Session) -> None:
    """The documentation site: mkdocs build --strict (a warning or a broken link fails)."""
    install(session)
    with timed(session, "docs: mkdocs build --strict"):
        session.run(python(), "-m", "mkdocs", "build", "--strict", "--quiet",
                    "--site-dir", "target/docs-site", env={"NO_MKDOCS_2_WARNING": "1"},
                    external=True)  # fmt: skip
        session.log("mkdocs build --strict: OK (target/docs-site)")


@nox.session
def firmware(session: nox.Session) -> None:
    """The firmware check: famcc-core on a Cortex-M4F in QEMU, the C ABI (apt-get packages).

    scripts/firmware-check.sh installs its Debian packages with apt-get when missing;
    FAMCC_FFI_TESTED=1 skips the C ABI's Rust tests that the rust session ran.
    """
    with timed(session, "firmware: scripts/firmware-check.sh"):
        session.run("bash", "scripts/firmware-check.sh", external=True)


@nox.session
def mutants(session: nox.Session) -> None:
    """The seeded mutation slices: cargo-mutants beside cosmic-ray (installs both).

    cosmic-ray runs one pytest at a time, so cargo-mutants' builds take the other core. A
    survivor not triaged fails.

    Both skip the unmutated baseline: run the rust and python sessions first (.ci/run does).
    """
    install(session, "mutation")
    log = ROOT / "target" / "mutants" / "slice.log"
    log.parent.mkdir(parents=True, exist_ok=True)
    with timed(session, "mutants: cargo-mutants beside cosmic-ray"):
        # scripts/mutants.sh in the background; its log is shown when it is done.
        session.run(
            "bash", "-c",
            f'bash scripts/mutants.sh >"{log}" 2>&1 & rs=$!; '
            "bash scripts/mutants-py.sh; py=$?; "
            "wait $rs; rc=$?; "
            f'grep -vE "^\\s+(Compiling|Finished|Running|Fresh|Dirty)" "{log}"; '
            f'[ $rc -eq 0 ] || echo "error: the famcc-core mutation slice failed (above; {log})" >&2; '
            '[ $py -eq 0 ] || echo "error: the Python mutation slice failed (above)" >&2; '
            "[ $rc -eq 0 ] && [ $py -eq 0 ]",
            external=True,
        )  # fmt: skip


@nox.session
def wheels(session: nox.Session) -> None:
    """The wheels and the sdist (scripts/build-wheels.sh), then the tests against one.

    scripts/build-wheels.sh: both Linux wheels, the sdist, their checks and a smoke run;
    scripts/test-wheel.sh: the test suite against this machine's wheel in a fresh venv with
    only the test extra (the cluster tests are reported skipped). Arguments after -- go to
    build-wheels.sh (nox -s wheels -- --arch x86_64).
    """
    with timed(session, "wheels: scripts/build-wheels.sh"):
        session.run("bash", "scripts/build-wheels.sh", *session.posargs, external=True)
    with timed(session, "wheels: scripts/test-wheel.sh"):
        session.run("bash", "scripts/test-wheel.sh", sys.executable, "dist", external=True)
