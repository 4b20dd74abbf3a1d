#!/usr/bin/env bash
# Interleaved criterion A/B of famcc-core's step bench: two checkouts' bench
# binaries run alternately (a, b, b, a, ...), pinned to one core, and each
# row's per-step median is printed per pass. benches/README.md pools them.
#
#   benches/criterion_ab.sh A_CHECKOUT B_CHECKOUT ROUNDS [FILTER] > passes.txt
#
# Each checkout's bench is built first into its own target directory
# (CARGO_TARGET_DIR=<checkout>/target/ab), so the two never share one.
set -euo pipefail
A=$(cd "$1" && pwd); B=$(cd "$2" && pwd); ROUNDS=$3
FILTER=${4:-'^step/(baseline|ex[123]|linear[48])/'}
CPU=${AB_CPU:-1}
bin() { # checkout -> bench binary (built on demand; cargo prints it relative)
    local p
    p=$(cd "$1" && CARGO_TARGET_DIR="$1/target/ab" cargo bench -p famcc-core --bench step --no-run 2>&1 |
        sed -n 's/.*(\(.*deps\/step-[0-9a-f]*\)).*/\1/p' | tail -1)
    case $p in /*) echo "$p" ;; *) echo "$1/$p" ;; esac
}
BIN_A=$(bin "$A"); BIN_B=$(bin "$B")
pass() { # tag checkout binary
    local home="$2/target/ab/criterion"
    rm -rf "$home"
    (cd "$2/crates/famcc-core" && CRITERION_HOME="$home" taskset -c "$CPU" "$3" --bench "$FILTER" >/dev/null 2>&1)
    python3 - "$1" "$home" <<'PY'
import glob, json, sys
tag, home = sys.argv[1:]
for p in sorted(glob.glob(f"{home}/step/*/new/estimates.json")):
    meta = json.load(open(p.replace("estimates.json", "benchmark.json")))
    n = (meta.get("throughput") or {}).get("Elements", 1)
    print(tag, meta["full_id"], round(json.load(open(p))["median"]["point_estimate"] / n, 2))
PY
}
for _ in $(seq "$ROUNDS"); do
    pass a "$A" "$BIN_A"; pass b "$B" "$BIN_B"; pass b "$B" "$BIN_B"; pass a "$A" "$BIN_A"
done
