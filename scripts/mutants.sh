#!/usr/bin/env bash
# Mutation testing with cargo-mutants (docs/mutation.md): famcc-core against
# its own tests, and the C ABI (crates/famcc-ffi) against its unit tests.
#
#   scripts/mutants.sh               the seeded slice that nox -s mutants runs: the
#                                    round-robin shard MUTANTS_SEED % MUTANTS_SHARDS of
#                                    MUTANTS_SHARDS of famcc-core's mutants (~2;
#                                    MUTANTS_OUT names the report directory)
#   scripts/mutants.sh --diff [BASE] the famcc-core mutants in the lines changed
#                                    against BASE (default: main), as before a merge
#   scripts/mutants.sh --full        every mutant of famcc-core, then of the C ABI
#                                    (hours on 2 cores; --shard k/n splits it)
#   scripts/mutants.sh --ffi         every mutant of the C ABI's own code
#
# Arguments after the mode go to `cargo mutants` (e.g. --shard 3/8, -j 2).
# Mutants triaged as equivalent, one a line with a reason, in
# .cargo/mutants-equivalent.txt are excluded; any other surviving mutant makes
# cargo mutants (and so this script) exit non-zero (2: missed, 3: timeout).
# Reports: target/mutants/<mode>/mutants.out/ (outcomes.json, missed.txt, ...).
set -euo pipefail
cd "$(dirname "$0")/.."

# A fresh machine has no cargo-mutants: it builds from crates.io (~5 min once).
if ! cargo mutants --version >/dev/null 2>&1; then
    echo "installing cargo-mutants (cargo install --locked --debug cargo-mutants)"
    # --debug: a third of the build time; cargo-mutants only drives cargo.
    cargo install --locked --quiet --debug cargo-mutants
fi

mode=slice
case "${1:-}" in
--full | --ffi | --slice) mode=${1#--} && shift ;;
--diff)
    mode=diff && shift
    base=main
    if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then base=$1 && shift; fi
    ;;
esac

# `file: description  # reason` -> a regex on the names of `cargo mutants --list`
# (`file:line:col: description`; the line and column are left free so that the
# list survives edits elsewhere in the file).
excludes=()
while IFS= read -r line; do
    line=${line%%#*}
    line=$(printf '%s' "$line" | sed -e 's/[[:space:]]*$//')
    [ -z "$line" ] && continue
    file=${line%%: *}
    what=${line#*: }
    esc=$(printf '%s' "$what" | sed -e 's/[][\.*^$+?(){}|/]/\\&/g')
    fesc=$(printf '%s' "$file" | sed -e 's/[][\.*^$+?(){}|/]/\\&/g')
    excludes+=(--exclude-re "^${fesc}:[0-9]+:[0-9]+: ${esc}\$")
done <.cargo/mutants-equivalent.txt

# A build directory of its own, kept between runs: the dependencies are built
# once, only the mutated crates per mutant. Not the tree's own target/:
# cargo names a workspace crate's artifacts by its path relative to the
# workspace, so a mutant built there from cargo-mutants' copy would stand in
# for the real crate until the copy is gone.
export CARGO_TARGET_DIR="$PWD/target/mutants-build"
# The closed loops run several times faster optimised; the tests' debug
# assertions (and overflow checks) stay on; no debug info: faster links.
export CARGO_PROFILE_TEST_OPT_LEVEL=1 CARGO_PROFILE_DEV_OPT_LEVEL=1
export CARGO_PROFILE_TEST_DEBUG=0 CARGO_PROFILE_DEV_DEBUG=0
# famcc-core is generic: every test binary compiles the mutated code anew, so
# the test targets are what a mutant costs (--cargo-arg: built and run, the
# build step included): every unit and integration test (no doctests,
# examples or benches). The integration tests are one binary for that reason.
all_tests=(--cargo-arg=--lib --cargo-arg=--tests)
core() { # out-dir, args... -> cargo mutants on famcc-core
    local out=$1 && shift
    mkdir -p "target/mutants/$out"
    # In the source's order, unless --shuffle is given (a run that may be
    # stopped early is then still a uniform sample of its shard).
    local order=--no-shuffle
    case " $* " in *" --shuffle "*) order= ;; esac
    cargo mutants ${order:+"$order"} --output "target/mutants/$out" "${excludes[@]}" "$@"
}

case "$mode" in
slice)
    seed=${MUTANTS_SEED:-11}
    shards=${MUTANTS_SHARDS:-1440}
    out=target/mutants/${MUTANTS_OUT:-slice}/mutants.out
    echo "mutation slice: famcc-core, round-robin shard $((seed % shards)) of $shards" \
        "(MUTANTS_SEED=$seed, MUTANTS_SHARDS=$shards)"
    # The sample is taken from every mutant, triaged or not, so that it stays
    # put when the triage list grows; a triaged survivor passes below. The
    # test command (.ci/run runs it first) has just run the same tests
    # unmutated: no baseline, a fixed timeout per mutant instead (a mutant
    # whose tests hang is caught).
    rc=0
    mkdir -p "target/mutants/${MUTANTS_OUT:-slice}"
    cargo mutants --no-shuffle --output "target/mutants/${MUTANTS_OUT:-slice}" "${all_tests[@]}" \
        --shard "$((seed % shards))/$shards" --sharding round-robin \
        --baseline skip --timeout "${MUTANTS_TIMEOUT:-180}" "$@" || rc=$?
    case " $* " in *" --list "*) exit "$rc" ;; esac
    if [ "$rc" -eq 2 ]; then
        # Survivors: each must be triaged (the name without line and column).
        untriaged=$(sed -E 's/^([^:]*):[0-9]+:[0-9]+: /\1: /' "$out/missed.txt" | while IFS= read -r m; do
            sed -e 's/[[:space:]]*#.*//' -e 's/[[:space:]]*$//' .cargo/mutants-equivalent.txt | grep -qxF -- "$m" || echo "$m"
        done)
        if [ -z "$untriaged" ]; then
            echo "mutation slice: every survivor is triaged as equivalent (.cargo/mutants-equivalent.txt)"
            rc=0
        else
            printf 'mutation slice: untriaged survivor: %s\n' "$untriaged" >&2
        fi
    fi
    if [ "$rc" -eq 3 ]; then
        echo "mutation slice: a mutant timed out (caught by the timeout); none survived"
    elif [ "$rc" -ne 0 ]; then
        echo "mutation slice failed (status $rc, $out): kill each survivor with a test or" \
            "triage it in .cargo/mutants-equivalent.txt (docs/mutation.md)" >&2
        exit "$rc"
    fi
    ;;
diff)
    echo "mutation testing: famcc-core, the lines changed against $base"
    git diff "$base" -- crates/famcc-core/src >target/mutants-diff.patch
    if [ ! -s target/mutants-diff.patch ]; then
        echo "no change to crates/famcc-core/src against $base"
        exit 0
    fi
    core diff "${all_tests[@]}" --in-diff target/mutants-diff.patch "$@"
    ;;
full)
    core full "${all_tests[@]}" "$@"
    "$0" --ffi "$@"
    ;;
ffi)
    mkdir -p target/mutants/ffi
    cargo mutants --no-shuffle --dir crates/famcc-ffi --output "$PWD/target/mutants/ffi" "$@"
    ;;
esac
