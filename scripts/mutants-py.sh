#!/usr/bin/env bash
# Mutation testing of the Python package with cosmic-ray (docs/mutation.md,
# "Python"): the verdict and metric code of python/famcc, each mutant tested
# against its module's tests only (scripts/mutants_py.py: TARGETS), in a
# scratch copy of the package under target/mutants-py/<mode>/tree.
#
#   scripts/mutants-py.sh             the seeded slice that ./scripts/test.sh runs:
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
# extension in python/famcc and cosmic-ray).
set -euo pipefail
cd "$(dirname "$0")/.."

if [ -n "${VIRTUAL_ENV:-}" ] && [ -x "$VIRTUAL_ENV/bin/python" ]; then
    PY="$VIRTUAL_ENV/bin/python"
else
    PY=python3
fi
if ! "$PY" -c 'import cosmic_ray' 2>/dev/null; then
    echo "error: cosmic-ray is missing: pip install -e '.[test]'" >&2
    exit 1
fi
exec "$PY" scripts/mutants_py.py "$@"
