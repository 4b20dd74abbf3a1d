#!/usr/bin/env bash
# Firmware check (issue 7): famcc-core in f32 on a Cortex-M4F under QEMU, and
# the C ABI (crates/famcc-ffi).
#
#  1. installs the Debian packages it needs (apt-get; skipped when present)
#  2. builds the host twin (embedded/host), the bare-metal firmware
#     (embedded/fw, thumbv7em-none-eabihf, -Zbuild-std), the C ABI for the
#     host and the target, and checks the committed C header
#  3. runs the firmware's closed loops and test vectors in QEMU mps2-an386
#     and compares them bit for bit with the host
#  4. counts instructions per controller step (QEMU plugin, -icount) and the
#     controller's flash (.text + .rodata) against the targets
#  5. runs the C ABI checks (crates/famcc-ffi/tests/c) and builds and runs
#     the C example on the host and, linked against the
#     thumbv7em staticlib, in QEMU
#
# Exit status: non-zero on any failure: a build, a check, a comparison, or a
# target (instructions per step, flash) missed or not measured.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT="$ROOT/target/firmware"
LOG="$OUT/check"
mkdir -p "$LOG" "$OUT/tools"
T_START=$(date +%s)

# Targets (f32, thumbv7em-none-eabihf).
TARGET_INSN_O2=1500
TARGET_INSN_O3=3000
TARGET_TEXT=16384    # order 2, and step-only at both orders
TARGET_TEXT_O3=24576 # order 3 (issue 16)

FAILURES=()
WARNINGS=()
fail() { FAILURES+=("$1"); echo "FAIL: $1"; }
warn() { WARNINGS+=("$1"); echo "WARNING: $1"; }
phase() { echo; echo "== $* ($(( $(date +%s) - T_START )) s)"; }

# ---------------------------------------------------------------- packages
phase "packages"
PKGS=(rustc-web cargo-web rust-web-src gcc gcc-arm-none-eabi binutils-arm-none-eabi
      libnewlib-arm-none-eabi qemu-system-arm cbindgen)
missing=()
for p in "${PKGS[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done
if ((${#missing[@]})); then
    SUDO=""
    if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
    echo "installing: ${missing[*]}"
    $SUDO apt-get update -q >"$LOG/apt-update.log" 2>&1
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}" \
        >"$LOG/apt-install.log" 2>&1 || { tail -20 "$LOG/apt-install.log"; echo "FAIL: apt-get install"; exit 1; }
else
    echo "all present: ${PKGS[*]}"
fi
T_PKGS=$(date +%s)

# ---------------------------------------------------------------- toolchain
# Debian's Rust (rustup's cargo may come first on PATH: call /usr/bin/cargo).
# RUSTC_BOOTSTRAP=1 is needed for -Zbuild-std (Debian ships no thumbv7em core).
export RUSTC=/usr/bin/rustc
export RUSTDOC=/usr/bin/rustdoc
export RUSTC_BOOTSTRAP=1
export CARGO_TARGET_DIR="$OUT"
export CARGO_TARGET_THUMBV7EM_NONE_EABIHF_LINKER=arm-none-eabi-ld
export CARGO_TARGET_THUMBV7EM_NONE_EABIHF_RUSTFLAGS="-C target-cpu=cortex-m4"
CARGO=/usr/bin/cargo
TGT=thumbv7em-none-eabihf
BUILD_STD=(-Zbuild-std=core,compiler_builtins -Zbuild-std-features=compiler-builtins-mem)
FW="$OUT/$TGT/release"
"$RUSTC" --version
QEMU=(qemu-system-arm -M mps2-an386 -display none -serial none -monitor none -chardev stdio,id=con)

build() { # name, dir, cargo args...
    local name=$1 dir=$2
    shift 2
    echo "-- $name"
    if ! (cd "$dir" && "$CARGO" "$@") >"$LOG/build-$name.log" 2>&1; then
        tail -30 "$LOG/build-$name.log"
        fail "build $name"
        return 1
    fi
    grep -E "^warning" "$LOG/build-$name.log" | sort -u | head -5 || true
}

# ---------------------------------------------------------------- builds
phase "build"
# Two lanes, each in a build directory of its own (so that neither waits for
# the other's lock). The target's lane builds what is measured: the check
# program (instructions per step) and the size probes (flash), with the
# release profile (opt-level 3, fat LTO). The other lane builds what is only
# run: the host twin, whose outputs must be bit-identical to the target's,
# and the C ABI for x86_64 and for the target. Those take the lighter
# profile below (opt-level 1, no LTO, 16 codegen units, no debug info): Rust neither
# reorders nor contracts floating-point arithmetic at any optimisation
# level, so their outputs are the same; they build in a third of the time.
HOST_OUT="$OUT/host"
LIGHT=(CARGO_PROFILE_RELEASE_OPT_LEVEL=1 CARGO_PROFILE_RELEASE_LTO=false CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 CARGO_PROFILE_RELEASE_DEBUG=false)
(
    export CARGO_TARGET_DIR="$HOST_OUT"
    export "${LIGHT[@]}"
    build host "$ROOT/embedded" build --release -p famcc-fw-host || true
    build ffi-host "$ROOT/crates/famcc-ffi" build --release || true
    build ffi-$TGT "$ROOT/crates/famcc-ffi" build --release --target $TGT "${BUILD_STD[@]}" || true
) >"$LOG/host-builds.txt" 2>&1 &
HOST_BUILDS=$!
build firmware "$ROOT/embedded/fw" build --release --target $TGT "${BUILD_STD[@]}" --bin famcc-fw || true
# The size probes: each compiles famcc-core's features for its own design
# alone (embedded/fw/Cargo.toml), as a firmware that configures that design.
build size-o2 "$ROOT/embedded/fw" build --release --target $TGT "${BUILD_STD[@]}" --no-default-features \
    --features ex1 --bin size-base --bin size-o2-built --bin size-o2-stepped || true
build size-o3 "$ROOT/embedded/fw" build --release --target $TGT "${BUILD_STD[@]}" --no-default-features \
    --features ex3 --bin size-o3-built --bin size-o3-stepped || true
gcc -shared -fPIC -O2 -Wall -Wextra -o "$OUT/tools/icount.so" "$ROOT/embedded/tools/icount.c" \
    || fail "build QEMU plugin"
wait "$HOST_BUILDS" || true
cat "$LOG/host-builds.txt"
mapfile -t host_failures < <(sed -n 's/^FAIL: //p' "$LOG/host-builds.txt")
FAILURES+=("${host_failures[@]}")
T_BUILD=$(date +%s)

# ---------------------------------------------------------------- C ABI tests and header
phase "C ABI: Rust tests, header"
# scripts/test.sh has run these tests already (FAMCC_FFI_TESTED=1): not twice.
if [ "${FAMCC_FFI_TESTED:-0}" = 1 ]; then
    echo "famcc-ffi tests: run by scripts/test.sh"
elif (cd "$ROOT/crates/famcc-ffi" && "$CARGO" test --lib) >"$LOG/ffi-test.log" 2>&1; then
    grep -E "^test result" "$LOG/ffi-test.log"
else
    tail -30 "$LOG/ffi-test.log"
    fail "famcc-ffi tests"
fi
HEADER="$ROOT/crates/famcc-ffi/include/famcc.h"
PINNED_CBINDGEN=0.24.3 # Debian bookworm's cbindgen: the committed header's generator
if command -v cbindgen >/dev/null; then
    (cd "$ROOT/crates/famcc-ffi" && cbindgen --config cbindgen.toml --crate famcc-ffi --output "$LOG/famcc.h") \
        >"$LOG/cbindgen.log" 2>&1 || fail "cbindgen"
    CBV=$(cbindgen --version | awk '{print $2}')
    if cmp -s "$HEADER" "$LOG/famcc.h"; then
        echo "include/famcc.h is up to date (cbindgen $CBV)"
    elif [ "$CBV" = "$PINNED_CBINDGEN" ]; then
        diff -u "$HEADER" "$LOG/famcc.h" | head -20 || true
        fail "include/famcc.h is stale: regenerate it (crates/famcc-ffi/README.md)"
    else
        warn "cbindgen $CBV is not the header's generator ($PINNED_CBINDGEN): text not compared; checking that the C example compiles against the fresh header"
        gcc -std=c11 -fsyntax-only -Wall -Wextra -Werror -I"$LOG" "$ROOT/crates/famcc-ffi/examples/c/main.c" ||
            fail "C example against the regenerated header"
    fi
else
    warn "cbindgen not installed: using the committed include/famcc.h unchecked"
fi

# ---------------------------------------------------------------- firmware: loops, vectors
phase "firmware in QEMU: closed loops, replay, test vectors"
if [ -x "$FW/famcc-fw" ] && [ -x "$HOST_OUT/release/famcc-fw-host" ]; then
    set +e
    timeout 300 "${QEMU[@]}" -semihosting-config enable=on,target=native,chardev=con,arg=famcc-fw,arg=check \
        -kernel "$FW/famcc-fw" >"$LOG/target.txt" 2>"$LOG/target.err"
    rc_fw=$?
    "$HOST_OUT/release/famcc-fw-host" run >"$LOG/host.txt" 2>"$LOG/host.err"
    rc_host=$?
    set -e
    grep -vE "^vec " "$LOG/target.txt" || true
    [ $rc_fw -eq 0 ] || { cat "$LOG/target.err"; fail "firmware checks (QEMU exit status $rc_fw)"; }
    [ $rc_host -eq 0 ] || fail "host twin checks (exit status $rc_host; see $LOG/host.txt)"
    echo "-- host vs target (test vectors, loop digests)"
    if ! "$HOST_OUT/release/famcc-fw-host" compare "$LOG/host.txt" "$LOG/target.txt" | tee "$LOG/compare.txt"; then
        fail "host and target outputs differ"
    fi
else
    fail "firmware or host twin missing"
fi

# ---------------------------------------------------------------- instructions per step
phase "instructions per controller step (QEMU -icount, plugin totals: K steps vs 0)"
K=10001
icount_total() { # mode, steps -> total instructions
    "${QEMU[@]}" -icount shift=0 \
        -semihosting-config "enable=on,target=native,chardev=con,arg=famcc-fw,arg=$1,arg=$2" \
        -plugin "$OUT/tools/icount.so" -d plugin -kernel "$FW/famcc-fw" 2>&1 >/dev/null |
        sed -n 's/^icount: total=\([0-9]*\).*/\1/p'
}
declare -A INSN WORST
if [ -x "$FW/famcc-fw" ] && [ -f "$OUT/tools/icount.so" ]; then
    for o in 2 3; do
        icount_total bench$o $K >"$LOG/icount-o$o-K" &
        icount_total bench$o 0 >"$LOG/icount-o$o-0" &
        wait
        tk=$(cat "$LOG/icount-o$o-K")
        t0=$(cat "$LOG/icount-o$o-0")
        if [ -z "$tk" ] || [ -z "$t0" ]; then
            fail "instruction count order $o (no plugin output)"
            continue
        fi
        INSN[$o]=$(awk -v a="$tk" -v b="$t0" -v k=$K 'BEGIN { printf "%.1f", (a - b) / k }')
        # Worst single step: SysTick under -icount (1 tick = 40 instructions at 25 MHz), calibrated
        # by the exact mean above.
        w=$("${QEMU[@]}" -icount shift=0 \
            -semihosting-config "enable=on,target=native,chardev=con,arg=famcc-fw,arg=worst$o" \
            -kernel "$FW/famcc-fw" 2>/dev/null | grep "^worst" || true)
        maxt=$(sed -n 's/.*max_ticks=\([0-9]*\).*/\1/p' <<<"$w")
        sumt=$(sed -n 's/.*sum_ticks=\([0-9]*\).*/\1/p' <<<"$w")
        atk=$(sed -n 's/.*at_k=\([0-9]*\).*/\1/p' <<<"$w")
        if [ -n "$maxt" ] && [ -n "$sumt" ] && [ "$sumt" -gt 0 ]; then
            # instructions per tick from the exact totals; the worst step is known to +- 1 tick
            WORST[$o]=$(awk -v m="$maxt" -v s="$sumt" -v d="$((tk - t0))" -v at="$atk" \
                'BEGIN { ipt = d / s; printf "%.0f (+-%.0f) at sample %s", m * ipt, ipt, at }')
        else
            WORST[$o]="n/a"
        fi
        echo "order $o: total(K=$K)=$tk total(0)=$t0 -> ${INSN[$o]} instructions/step (mean over the 10 s closed-loop error signal); worst step ~${WORST[$o]}"
    done
fi

# ---------------------------------------------------------------- worst case under adversarial input
phase "worst step over adversarial input (issue 15: within 20x the median step)"
WORST_RATIO=20
ADVERSARIAL=()
if [ -x "$FW/famcc-fw" ]; then
    for o in 2 3; do
        timeout 300 "${QEMU[@]}" -icount shift=0 \
            -semihosting-config "enable=on,target=native,chardev=con,arg=famcc-fw,arg=adversarial$o" \
            -kernel "$FW/famcc-fw" 2>/dev/null | grep "^adversarial" >"$LOG/adversarial-o$o.txt" || true
        [ -s "$LOG/adversarial-o$o.txt" ] || fail "adversarial order $o (no output)"
        while read -r _ ord name rest; do
            maxt=$(sed -n 's/.*max_ticks=\([0-9]*\).*/\1/p' <<<"$rest")
            medt=$(sed -n 's/.*median_ticks=\([0-9]*\).*/\1/p' <<<"$rest")
            if [ -z "$maxt" ] || [ -z "$medt" ] || [ "$medt" -eq 0 ]; then
                fail "adversarial $ord $name: $rest"
                continue
            fi
            # SysTick under -icount shift=0: 40 instructions per tick (+-1 tick).
            line=$(awk -v m="$maxt" -v d="$medt" -v o="$ord" -v n="$name" -v r=$WORST_RATIO 'BEGIN {
                printf "%s %-11s worst %6d instructions, median %6d (+-40): %.1fx (limit %dx)", o, n, 40 * m, 40 * d, m / d, r }')
            echo "$line"
            ADVERSARIAL+=("$line")
            if [ "$maxt" -gt $((WORST_RATIO * medt)) ]; then
                fail "worst step of $ord $name over $WORST_RATIO x the median"
            fi
        done <"$LOG/adversarial-o$o.txt"
    done
fi

# ---------------------------------------------------------------- flash
phase "controller flash (.text + .rodata, thumbv7em, opt-level 3, LTO; famcc-core with the design's features alone)"
textsz() { arm-none-eabi-size -B "$1" | awk 'NR == 2 { print $1 }'; }
declare -A TEXT TEXT_STEP TEXT_NEW
if [ -f "$FW/size-base" ]; then
    base=$(textsz "$FW/size-base")
    for o in 2 3; do
        full=$(textsz "$FW/size-o$o-stepped")
        new=$(textsz "$FW/size-o$o-built")
        TEXT[$o]=$((full - base))
        TEXT_NEW[$o]=$((new - base))
        TEXT_STEP[$o]=$((full - new))
        echo "order $o: controller ${TEXT[$o]} bytes = built ${TEXT_NEW[$o]} + step-only ${TEXT_STEP[$o]} (runtime alone: $base)"
    done
    echo "-- largest symbols of the order-3 controller (size-o3-stepped)"
    arm-none-eabi-nm -S --size-sort -C "$FW/size-o3-stepped" | tail -12 | while read -r _ sz _ name; do
        printf "  %6d  %s\n" "$((16#$sz))" "$name"
    done
    arm-none-eabi-nm -S "$FW/famcc-fw" | while read -r _ sz _ name; do
        case $name in famcc_fw_step_o2 | famcc_fw_step_o3)
            echo "  $name (famcc-fw): $((16#$sz)) bytes, step inlined" ;;
        esac
    done
else
    fail "size probes missing"
fi

# ---------------------------------------------------------------- C example
phase "C example (host gcc, and arm-none-eabi-gcc in QEMU)"
CEX="$ROOT/crates/famcc-ffi/examples/c"
if gcc -std=c11 -O2 -Wall -Wextra -Werror -pedantic -I"$ROOT/crates/famcc-ffi/include" "$CEX/main.c" \
    "$HOST_OUT/release/libfamcc_ffi.a" -lm -o "$OUT/famcc-c-example" 2>"$LOG/c-host.log"; then
    if "$OUT/famcc-c-example" >"$LOG/c-host.txt" 2>&1; then
        head -8 "$LOG/c-host.txt"
        echo "  ..."
        tail -3 "$LOG/c-host.txt"
    else
        cat "$LOG/c-host.txt"
        fail "C example (host) reported failures"
    fi
else
    cat "$LOG/c-host.log"
    fail "C example (host) does not build"
fi
# The storage checks from C: NULL, misaligned, undersized storage, the wrong type.
if gcc -std=c11 -O2 -Wall -Wextra -Werror -pedantic -I"$ROOT/crates/famcc-ffi/include" \
    "$ROOT/crates/famcc-ffi/tests/c/abi_checks.c" "$HOST_OUT/release/libfamcc_ffi.a" -lm \
    -o "$OUT/famcc-c-abi-checks" 2>"$LOG/c-abi-checks.log"; then
    "$OUT/famcc-c-abi-checks" || fail "C ABI checks (crates/famcc-ffi/tests/c/abi_checks.c)"
else
    cat "$LOG/c-abi-checks.log"
    fail "C ABI checks do not build"
fi
ARMCC=(arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -std=c11 -O2
       -Wall -Wextra -Werror -ffunction-sections -fdata-sections)
if "${ARMCC[@]}" -I"$ROOT/crates/famcc-ffi/include" --specs=rdimon.specs \
    -Wl,--gc-sections -Wl,--undefined=famcc_example_vectors -Wl,--no-warn-execstack \
    -Wl,--section-start=.vectors=0 -Wl,--defsym=__stack_top=0x20400000 \
    "$CEX/main.c" "$CEX/cortex-m/startup.c" "$HOST_OUT/$TGT/release/libfamcc_ffi.a" -lm \
    -o "$OUT/famcc-c-example-m4" 2>"$LOG/c-arm.log"; then
    echo "arm-none-eabi-gcc: built against $TGT/release/libfamcc_ffi.a ($(textsz "$OUT/famcc-c-example-m4") bytes text incl. newlib printf)"
    set +e
    timeout 120 "${QEMU[@]}" -semihosting-config enable=on,target=native,chardev=con \
        -kernel "$OUT/famcc-c-example-m4" >"$LOG/c-arm.txt" 2>&1
    rc=$?
    set -e
    tail -2 "$LOG/c-arm.txt"
    [ $rc -eq 0 ] || fail "C example in QEMU (exit status $rc)"
else
    cat "$LOG/c-arm.log"
    fail "C example (arm-none-eabi-gcc) does not build"
fi

# ---------------------------------------------------------------- summary
phase "summary"
# target NAME VALUE LIMIT: met, or a failure (missed, or not measured).
source "$ROOT/scripts/fw_target.sh"
target "instructions/step, order 2" "${INSN[2]:-}" $TARGET_INSN_O2
target "instructions/step, order 3" "${INSN[3]:-}" $TARGET_INSN_O3
target "controller flash, order 2 (new + step), bytes" "${TEXT[2]:-}" $TARGET_TEXT
target "controller flash, order 3 (new + step), bytes" "${TEXT[3]:-}" $TARGET_TEXT_O3
target "step-only flash, order 2, bytes" "${TEXT_STEP[2]:-}" $TARGET_TEXT
target "step-only flash, order 3, bytes" "${TEXT_STEP[3]:-}" $TARGET_TEXT
if ((${#ADVERSARIAL[@]})); then
    echo "  worst step over adversarial input (checked: <= ${WORST_RATIO}x the median):"
    printf '    %s\n' "${ADVERSARIAL[@]}"
fi
T_END=$(date +%s)
echo "time: packages $((T_PKGS - T_START)) s, builds $((T_BUILD - T_PKGS)) s, total $((T_END - T_START)) s (logs in $LOG)"
if ((${#WARNINGS[@]})); then
    echo "warnings:"
    printf '  %s\n' "${WARNINGS[@]}"
fi
if ((${#FAILURES[@]})); then
    echo "FAILED (${#FAILURES[@]}):"
    printf '  %s\n' "${FAILURES[@]}"
    exit 1
fi
echo "firmware check: OK"
