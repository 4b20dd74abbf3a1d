#!/usr/bin/env bash
# Mutation testing of the Python package with cosmic-ray (docs/mutation.md,
# "Python"): the verdict and metric code of python/famcc, each mutant tested
# against its module's tests only (scripts/mutants_py.py: TARGETS), in a
# scratch copy of the package under target/mutants-py/<mode>/tree.
#
#   scripts/mutants-py.sh             the seeded slice that nox -s mutants runs:
#                                     MUTANTS_PY_COUNT (5) mutants drawn with the seed
#                                     MUTANTS_PY_SEED (11) from all the targets' mutants
#   scripts/mutants-py.sh --full      every mutant of the targets (~1,760; hours)
#   scripts/mutants-py.sh --target python/famcc/verdicts.py   one module (repeatable;
#                                     with the slice's sampling unless --full)
#   scripts/mutants-py.sh --list      the chosen mutants, none run
#   scripts/mutants-py.sh --report    the last run's outcomes again
#
# MUTANTS_PY_OUT names the report directory (target/mutants-py/<it>/:
# outcomes.txt, missed.diff, session.sqlite). A survivor that is not triaged as
# equivalent in .mutants-py-equivalent.txt makes the script exit 2.
# Needs the package installed (pip install -e '.[test]': the compiled
# extension in python/famcc) and cosmic-ray (the mutation extra), which the
# script installs when it is missing and a virtual environment is active
# (nox -s mutants installs both).
set -euo pipefail
cd "$(dirname "$0")/.."

if [ -n "${VIRTUAL_ENV:-}" ] && [ -x "$VIRTUAL_ENV/bin/python" ]; then
    PY="$VIRTUAL_ENV/bin/python"
else
    PY=python3
fi
if ! "$PY" -c 'import cosmic_ray' 2>/dev/null; then
    if "$PY" -c 'import sys; sys.exit(sys.prefix == sys.base_prefix)'; then
        # The mutation extra's requirement, as pyproject.toml states it.
        req=$("$PY" -c 'import tomllib; print(*tomllib.load(open("pyproject.toml", "rb"))["project"]["optional-dependencies"]["mutation"])')
        echo "installing the mutation extra into $("$PY" -c 'import sys; print(sys.prefix)'): $req"
        # shellcheck disable=SC2086 # one argument per requirement
        "$PY" -m pip install --quiet --disable-pip-version-check $req
    else
        echo "error: cosmic-ray is missing: pip install -e '.[test,mutation]' (in a virtual environment)" >&2
        exit 1
    fi
fi
exec "$PY" scripts/mutants_py.py "$@"
