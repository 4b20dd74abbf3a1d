#!/usr/bin/env bash
# Tests a built famcc artefact the way a user gets it: installs it into a fresh venv
# of the given interpreter and runs the test suite (tests/) and the installed
# package's docstring examples against the installed copy, never the source tree.
# The release workflow (.github/workflows/release.yml) runs it on every wheel and
# on the sdist; it works the same here:
#
#   scripts/test-wheel.sh python3.11 dist/     # the best artefact in dist/ for this machine
#   scripts/test-wheel.sh python3 dist/famcc-0.1.0-cp311-abi3-manylinux2014_x86_64.manylinux_2_17_x86_64.whl
#
# Linux, macOS and Windows (Git Bash). Exit status: pytest's.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
[ $# -eq 2 ] || { echo "usage: $0 PYTHON DIST_DIR_OR_FILE" >&2; exit 2; }
PYTHON=$1
ART=$2

VERSION=$("$PYTHON" -c 'import tomllib; print(tomllib.load(open("pyproject.toml", "rb"))["project"]["version"])')
BASE=${RUNNER_TEMP:-${TMPDIR:-/tmp}}
if command -v cygpath >/dev/null; then BASE=$(cygpath -u "$BASE"); fi # Windows (Git Bash)
TMP=$(mktemp -d "$BASE/famcc-wheel-test.XXXXXX")
"$PYTHON" -m venv "$TMP/venv"
if [ -x "$TMP/venv/Scripts/python.exe" ]; then VPY="$TMP/venv/Scripts/python.exe"; else VPY="$TMP/venv/bin/python"; fi
pip_() { "$VPY" -m pip --disable-pip-version-check "$@"; }
pip_ install --quiet --upgrade pip

# The artefact itself, then the test extra's packages from the index, famcc pinned
# to what is installed. From a directory of wheels: the best match for this
# interpreter and platform (pip refuses an incompatible one); from a directory with
# only the sdist: that sdist, built from source (its build requirements come from
# the index).
if [ -d "$ART" ]; then
    DIR=$ART
    if compgen -G "$ART/famcc-$VERSION-*.whl" >/dev/null; then
        pip_ install --no-index --no-deps --find-links "$ART" "famcc==$VERSION"
    else
        pip_ install --no-deps "$ART/famcc-$VERSION.tar.gz"
    fi
else
    DIR=$(dirname "$ART")
    pip_ install --no-deps "$ART"
fi
pip_ install "famcc[test]==$VERSION" --find-links "$DIR"

cd "$ROOT"
"$VPY" - <<'EOF'
import sys, sysconfig
from pathlib import Path

import famcc

where = Path(famcc.__file__).resolve()
site = Path(sysconfig.get_paths()["purelib"]).resolve()
print(f"famcc {famcc.__version__} from {where.parent}")
sys.exit(0 if site in where.parents else f"famcc was imported from {where}, not the venv")
EOF
"$VPY" -m famcc.cli --version
"$VPY" -m pytest -q -p no:cacheprovider tests
"$VPY" -m pytest -q -p no:cacheprovider --doctest-modules --pyargs famcc
