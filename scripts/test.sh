#!/usr/bin/env bash
# Installs what the tests need and runs every test: Rust (fmt, clippy and
# rustdoc on every workspace; unit, property, golden and closed-loop tests;
# the no_std build; a seeded slice of cargo-mutants' mutants), Python (ruff,
# mypy --strict, pytest, the docstring examples, a seeded slice of cosmic-ray's
# mutants), the documentation site
# (mkdocs build --strict), the release workflows (actionlint), and the
# firmware check (cross-build, emulated closed loops, C ABI).
#
# Python: inside a virtual environment (activated, or python3 itself is one)
# everything is installed into and run with that environment. Otherwise the
# script makes its own in .venv-test/ (reused on later runs), so the system
# Python is never modified.
set -euo pipefail
cd "$(dirname "$0")/.."

in_venv() { # python -> status 0 if that interpreter runs in a virtual environment
    "$1" -c 'import sys; sys.exit(0 if sys.prefix != sys.base_prefix else 1)' 2>/dev/null
}
if [ -n "${VIRTUAL_ENV:-}" ] && [ -x "$VIRTUAL_ENV/bin/python" ]; then
    PY="$VIRTUAL_ENV/bin/python"
elif in_venv python3; then
    PY=$(python3 -c 'import sys; print(sys.executable)')
else
    VENV="$PWD/.venv-test"
    if ! in_venv "$VENV/bin/python"; then
        echo "creating the test environment $VENV (python3 -m venv)"
        rm -rf "$VENV"
        python3 -m venv "$VENV" || {
            echo "error: python3 -m venv failed (on Debian/Ubuntu: apt-get install python3-venv)" >&2
            exit 1
        }
        "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check --upgrade pip
    fi
    PY="$VENV/bin/python"
    # As if activated: whatever the steps below start finds this environment first.
    export VIRTUAL_ENV="$VENV"
    export PATH="$VENV/bin:$PATH"
fi
echo "python: $PY ($("$PY" -c 'import sys; print(sys.version.split()[0])'))"

# Where the time goes: `mark NAME` closes a phase; the table is printed at the end.
TIMES=()
T_LAST=0
mark() {
    TIMES+=("$(printf '%5d s  %s' $((SECONDS - T_LAST)) "$1")")
    T_LAST=$SECONDS
}

# The Python install runs beside the Rust checks and tests: pip's downloads
# and the extension's fat-LTO link keep one core busy, cargo's jobs the other.
# The extension builds in a build directory of its own (target/python-build),
# so that neither build waits for the other's lock.
mkdir -p target
CARGO_TARGET_DIR="$PWD/target/python-build" "$PY" -m pip install --quiet --disable-pip-version-check \
    -e '.[test,docs,cluster]' >target/pip-install.log 2>&1 &
PIP_INSTALL=$!
BACKGROUND=("$PIP_INSTALL")
trap 'kill "${BACKGROUND[@]}" 2>/dev/null || true' EXIT
# fmt, clippy and rustdoc over the three workspaces: the root (core, paper,
# binding), the C ABI and the firmware keep workspaces of their own
# (docs/design.md §9.1: their panic = "abort" profiles and features).
# The firmware's workspace with --all-features: its size probes (features
# ex1, ex3) are linted too.
for manifest in Cargo.toml crates/famcc-ffi/Cargo.toml embedded/Cargo.toml; do
    all=()
    [ "$manifest" = embedded/Cargo.toml ] && all=(--all-features)
    cargo fmt --all --manifest-path "$manifest" -- --check
    cargo clippy --manifest-path "$manifest" --workspace --all-targets "${all[@]}" -- -D warnings
    RUSTDOCFLAGS="-D warnings" cargo doc --manifest-path "$manifest" --workspace --no-deps --quiet
done
# famcc-core with every optional design and option compiled out (src/compiled.rs).
cargo clippy -p famcc-core --no-default-features --lib --test compiled_out -- -D warnings
mark "fmt, clippy, rustdoc (3 workspaces)"
cargo test -p famcc-core -p famcc-paper
# Every benchmark workload builds its controller and steps once (criterion's
# test mode): a design the validation rules reject fails here, not in a bench run.
cargo test -q -p famcc-core --benches
# A design compiled out is rejected, naming its feature; the rest runs.
cargo test -q -p famcc-core --no-default-features --test compiled_out
# no_std: both build without the standard library.
cargo build -p famcc-core -p famcc-paper
# The C ABI (its own workspace: a no_std staticlib with panic = "abort").
cargo test --manifest-path crates/famcc-ffi/Cargo.toml --lib
mark "Rust tests (core, paper, benches, no_std, C ABI)"
if ! wait "$PIP_INSTALL"; then
    cat target/pip-install.log
    echo "error: pip install -e '.[test,docs,cluster]' failed (above)" >&2
    exit 1
fi
cat target/pip-install.log
mark "venv, install (pip, the extension's release build; beside the Rust phases, the wait after them)"
"$PY" -m ruff check python tests benches examples
"$PY" -m ruff format --check python tests benches examples
"$PY" -m mypy --strict python/famcc
# Two workers (pytest-xdist), whole files each: a module's fixtures run once.
# Measured 2026-12-03 on the 2-core machine: 317 s against 473 s in one process.
"$PY" -m pytest -q -n 2 --dist loadfile
# The examples in the package's docstrings.
"$PY" -m pytest -q --doctest-modules python/famcc
mark "ruff, mypy, pytest, doctests"
# Mutation testing, the two slices side by side (cosmic-ray runs one pytest at
# a time, so cargo-mutants' builds take the other core):
#  - famcc-core: a fixed, seeded slice of cargo-mutants' mutants (~2, ~3 minutes;
#    docs/mutation.md). `scripts/mutants.sh --full` runs all.
#  - the Python package: a fixed, seeded slice of cosmic-ray's mutants of the
#    verdict and metric code (5, 1-2 minutes; docs/mutation.md, "Python"), each
#    against its module's tests. `scripts/mutants-py.sh --full` runs all.
# A mutant that survives and is not triaged (.cargo/mutants-equivalent.txt,
# .mutants-py-equivalent.txt) fails here.
mkdir -p target/mutants
bash scripts/mutants.sh >target/mutants/slice.log 2>&1 &
MUTANTS_RS=$!
BACKGROUND+=("$MUTANTS_RS")
bash scripts/mutants-py.sh
mutants_rc=0
wait "$MUTANTS_RS" || mutants_rc=$?
grep -vE "^\s+(Compiling|Finished|Running|Fresh|Dirty)" target/mutants/slice.log
if [ "$mutants_rc" -ne 0 ]; then
    echo "error: the famcc-core mutation slice failed (above; target/mutants/slice.log)" >&2
    exit "$mutants_rc"
fi
mark "mutation slices (cargo-mutants beside cosmic-ray)"
# The documentation site (mkdocs.yml): any warning, a broken link among them, fails.
NO_MKDOCS_2_WARNING=1 "$PY" -m mkdocs build --strict --site-dir target/docs-site
echo "mkdocs build --strict: OK (target/docs-site)"
# The release workflows, and the release scripts' syntax.
"$("$PY" -c 'import sysconfig; print(sysconfig.get_path("scripts"))')/actionlint" -no-color
echo "actionlint: OK ($(ls .github/workflows/*.yml | tr '\n' ' '))"
bash -n scripts/build-wheels.sh scripts/test-wheel.sh
mark "mkdocs, actionlint"
# famcc-core in f32 on a Cortex-M4F under QEMU, and the C ABI (installs its
# Debian packages with apt-get when missing).
FAMCC_FFI_TESTED=1 bash scripts/firmware-check.sh
mark "firmware check"
echo "time per phase:"
printf '  %s\n' "${TIMES[@]}"
echo "  $SECONDS s in all"
