#!/usr/bin/env bash
# The test command: every check that needs no system package, in a virtual environment of
# its own. The nox sessions (noxfile.py) lint, rust, python and docs, in two lanes side by
# side on the machine's cores:
#   cargo:  lint(rust)  (fmt, clippy, rustdoc on the root, C ABI and firmware workspaces),
#           rust        (the Rust tests, the benches in test mode, the no_std build, the C ABI)
#   Python: lint(python) (ruff, mypy --strict, actionlint; after the editable install of the
#           package with the test, docs and cluster extras: the extension's build),
#           python      (pytest on every core, the docstring examples),
#           docs        (mkdocs build --strict)
# and prints the time of each step at the end. The firmware check, the mutation slices and
# the wheels are sessions of their own (they install toolchains and system packages):
#
#   ./scripts/test.sh                  the test command
#   ./scripts/test.sh -s firmware      any nox arguments: that session in the test
#                                      environment (-l lists them; .ci/run runs firmware
#                                      and mutants after the test command)
#
# Python: inside a virtual environment (activated, or python3 itself is one) everything is
# installed into and run with that environment. Otherwise the script makes its own in
# .venv-test/ (reused on later runs), so the system Python is never modified. Rust: the
# machine's cargo (rustup), with clippy and rustfmt.
set -euo pipefail
cd "$(dirname "$0")/.."
T0=$SECONDS

in_venv() { # python -> status 0 if that interpreter runs in a virtual environment
    "$1" -c 'import sys; sys.exit(0 if sys.prefix != sys.base_prefix else 1)' 2>/dev/null
}
if [ -n "${VIRTUAL_ENV:-}" ] && [ -x "$VIRTUAL_ENV/bin/python" ]; then
    PY="$VIRTUAL_ENV/bin/python"
elif in_venv python3; then
    PY=$(python3 -c 'import sys; print(sys.executable)')
    export VIRTUAL_ENV
    VIRTUAL_ENV=$("$PY" -c 'import sys; print(sys.prefix)')
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
# The task runner itself (also in the test extra, with the same bound).
if ! "$PY" -c 'import nox' 2>/dev/null; then
    "$PY" -m pip install --quiet --disable-pip-version-check 'nox>=2024.4.15'
fi
nox_() { "$PY" -m nox --no-color "$@"; }

# With arguments: nox's, in this environment.
if [ $# -gt 0 ]; then
    exec "$PY" -m nox "$@"
fi

# Where the time goes: each session's steps append `seconds<TAB>name` (noxfile.py: timed).
mkdir -p target/test
export FAMCC_TIMES="$PWD/target/test/times.tsv"
: >"$FAMCC_TIMES"

# The cargo lane in the background (its log is shown at the end), the Python lane in the
# foreground. They share no build directory: the extension builds in target/python-build.
nox_ -s "lint(rust)" rust >target/test/cargo-lane.log 2>&1 &
CARGO_LANE=$!
trap 'kill "$CARGO_LANE" 2>/dev/null || true' EXIT
T_PY=$SECONDS
py_rc=0
nox_ -s "lint(python)" python docs || py_rc=$?
T_PY=$((SECONDS - T_PY))
cargo_rc=0
wait "$CARGO_LANE" || cargo_rc=$?
T_CARGO_DONE=$((SECONDS - T0))
echo
echo "== the cargo lane (target/test/cargo-lane.log)"
grep -vE "^\s+(Compiling|Checking|Documenting|Fresh|Dirty|Downloaded|Downloading|Running|Finished|Locking|Adding|Updating|Blocking)\b" \
    target/test/cargo-lane.log | grep -vE "^test .* \.\.\. ok$|^$" || true

echo
echo "time per step (the two lanes ran side by side):"
while IFS=$'\t' read -r s name; do
    printf '  %5d s  %s\n' "$s" "$name"
done <"$FAMCC_TIMES"
echo "  the Python lane $T_PY s, the cargo lane done at $T_CARGO_DONE s; $((SECONDS - T0)) s in all"
if [ "$cargo_rc" -ne 0 ] || [ "$py_rc" -ne 0 ]; then
    [ "$cargo_rc" -eq 0 ] || echo "error: the cargo lane failed (lint(rust), rust: above)" >&2
    [ "$py_rc" -eq 0 ] || echo "error: the Python lane failed (lint(python), python, docs: above)" >&2
    exit 1
fi
echo "test command: OK"
