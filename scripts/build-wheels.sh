#!/usr/bin/env bash
# Builds famcc's release artefacts into dist/ (issue 16) and checks them:
#
#  1. manylinux2014 (glibc 2.17) abi3 wheels (CPython >= 3.11) for x86_64 and aarch64,
#     stripped: maturin with zig as the linker (`--zig`, zig from the ziglang package),
#     so one x86_64 machine builds both and links against glibc 2.17's symbol versions
#  2. `auditwheel show` on every wheel: the tag must be manylinux_2_17 or lower
#  3. the sdist, which must carry LICENSE-MIT and LICENSE-APACHE (as must the wheels)
#  4. smoke test: the wheel of this machine's architecture in a fresh venv runs
#     `famcc --version` and `famcc reproduce` (about 40 s; --no-smoke skips it)
#
# Tools come from PyPI into their own venv, .venv-wheels/ (reused by later runs); the
# Rust standard library of each target from rustup (`rustup target add`).
#
# Usage: scripts/build-wheels.sh [--arch x86_64|aarch64]... [--out DIR] [--no-smoke]
# Exit status: non-zero when a build or a check fails.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD

# Versions the script was proven with (maturin embeds cargo-zigbuild, which supports
# a range of zig releases; a new zig can break it).
MATURIN="maturin==1.16.0"
ZIGLANG="ziglang==0.17.1"
AUDITWHEEL="auditwheel==6.8.2"
MAX_GLIBC_MINOR=17 # manylinux2014 = manylinux_2_17

OUT="$ROOT/dist"
ARCHES=()
SMOKE=1
while (($#)); do
    case $1 in
        --arch) ARCHES+=("$2"); shift 2 ;;
        --out) OUT=$(realpath -m "$2"); shift 2 ;;
        --no-smoke) SMOKE=0; shift ;;
        -h | --help) sed -n '2,17p' "$0"; exit 0 ;;
        *) echo "unknown argument: $1 (see --help)" >&2; exit 2 ;;
    esac
done
((${#ARCHES[@]})) || ARCHES=(x86_64 aarch64)
for a in "${ARCHES[@]}"; do
    case $a in x86_64 | aarch64) ;; *) echo "unsupported --arch $a (x86_64, aarch64)" >&2; exit 2 ;; esac
done

T0=$(date +%s)
FAILURES=()
fail() { FAILURES+=("$1"); echo "FAIL: $1"; }
phase() { echo; echo "== $* ($(($(date +%s) - T0)) s)"; }

# ---------------------------------------------------------------- tools
phase "tools (.venv-wheels: $MATURIN $ZIGLANG $AUDITWHEEL)"
VENV="$ROOT/.venv-wheels"
if ! "$VENV/bin/python" -c 'import sys; sys.exit(sys.prefix == sys.base_prefix)' 2>/dev/null; then
    rm -rf "$VENV"
    python3 -m venv "$VENV"
    "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check --upgrade pip
fi
"$VENV/bin/python" -m pip install --quiet --disable-pip-version-check "$MATURIN" "$ZIGLANG" "$AUDITWHEEL"
export PATH="$VENV/bin:$PATH" # maturin finds zig as `python -m ziglang` of this venv
echo "maturin $(maturin --version | awk '{print $2}'), zig $(python -m ziglang version), auditwheel $(auditwheel --version | head -1 | awk '{print $2}')"

VERSION=$(python - <<'EOF'
import tomllib
print(tomllib.load(open("pyproject.toml", "rb"))["project"]["version"])
EOF
)
LOG="$ROOT/target/build-wheels" # build logs
mkdir -p "$OUT" "$LOG"
rm -f "$OUT"/famcc-"$VERSION"-*.whl "$OUT"/famcc-"$VERSION".tar.gz

# ---------------------------------------------------------------- wheels
wheel_of() { # arch -> path of the cp311-abi3 wheel for it in $OUT, or nothing
    local w
    for w in "$OUT"/famcc-"$VERSION"-cp311-abi3-*_"$1".whl; do
        [ -f "$w" ] && echo "$w" && return
    done
    return 0
}
so_report() { # wheel -> "size bytes, stripped|NOT stripped"
    python - "$1" <<'EOF'
import sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as z:
    (name,) = [n for n in z.namelist() if n.endswith(".so")]
    data = z.read(name)
# ELF64 little-endian: section headers at e_shoff, names in the section e_shstrndx.
import struct
shoff, = struct.unpack_from("<Q", data, 0x28)
shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x3A)
def sh(i):
    return struct.unpack_from("<IIQQQQIIQQ", data, shoff + i * shentsize)
strtab = sh(shstrndx)
names = set()
for i in range(shnum):
    off = strtab[4] + sh(i)[0]
    names.add(data[off:data.index(b"\0", off)].decode())
stripped = ".symtab" not in names and not any(n.startswith(".debug") for n in names)
print(f"{name} {len(data)} bytes, {'stripped' if stripped else 'NOT stripped (.symtab/.debug present)'}")
sys.exit(0 if stripped else 1)
EOF
}

for arch in "${ARCHES[@]}"; do
    target="$arch-unknown-linux-gnu"
    phase "wheel $target (manylinux2014)"
    if ! rustup target list --installed 2>/dev/null | grep -qx "$target"; then
        echo "rustup target add $target"
        if ! rustup target add "$target"; then
            fail "Rust standard library for $target: rustup target add failed (no rustup, or its" \
                "download server is unreachable); install that target's std, or build on an $arch machine"
            continue
        fi
    fi
    if ! maturin build --release --zig --compatibility manylinux2014 --target "$target" --strip \
        --out "$OUT" 2>&1 | tee "$LOG/build-$arch.log" | grep -vE "^\s+(Compiling|Downloaded|Downloading)"; then
        fail "maturin build $target (log: $LOG/build-$arch.log)"
        continue
    fi
    whl=$(wheel_of "$arch")
    if [ -z "$whl" ]; then
        fail "no cp311-abi3 $arch wheel in $OUT"
        continue
    fi
    echo "-- $(basename "$whl") ($(stat -c %s "$whl") bytes)"
    so_report "$whl" || fail "$(basename "$whl"): the extension is not stripped"
    for lic in LICENSE-MIT LICENSE-APACHE; do
        python -c 'import sys, zipfile; n = zipfile.ZipFile(sys.argv[1]).namelist(); sys.exit(not any(x.endswith("/licenses/" + sys.argv[2]) for x in n))' \
            "$whl" "$lic" || fail "$(basename "$whl") lacks $lic"
    done
    echo "-- auditwheel show"
    if ! aw=$(auditwheel show "$whl" 2>&1); then
        echo "$aw"
        fail "auditwheel show $(basename "$whl")"
        continue
    fi
    echo "$aw" | sed 's/^/   /'
    tag=$(tr -d '\n' <<<"$aw" | grep -oE 'consistent with the following platform tag: *"[^"]+"' | grep -oE 'manylinux_[0-9]+_[0-9]+_[a-z0-9_]+' || true)
    minor=$(sed -nE 's/^manylinux_2_([0-9]+)_.*/\1/p' <<<"$tag")
    if [ -z "$minor" ] || [ "$minor" -gt $MAX_GLIBC_MINOR ] || [[ $tag != *_"$arch" ]]; then
        fail "$(basename "$whl"): auditwheel says ${tag:-no manylinux tag}, need manylinux_2_$MAX_GLIBC_MINOR or lower for $arch"
    else
        echo "ok: $tag (glibc >= 2.$minor)"
    fi
done

# ---------------------------------------------------------------- sdist
phase "sdist"
if maturin sdist --out "$OUT" >"$LOG/sdist.log" 2>&1; then
    grep -E "Built source distribution" "$LOG/sdist.log" || true
    sdist="$OUT/famcc-$VERSION.tar.gz"
    listing=$(tar tzf "$sdist")
    for lic in LICENSE-MIT LICENSE-APACHE; do
        if grep -qx "famcc-$VERSION/$lic" <<<"$listing"; then
            echo "ok: $(basename "$sdist") carries $lic"
        else
            fail "$(basename "$sdist") lacks $lic"
        fi
    done
    if tar xzf "$sdist" -O "famcc-$VERSION/PKG-INFO" | grep -q "^License-Expression: MIT OR Apache-2.0"; then
        echo "ok: PKG-INFO License-Expression: MIT OR Apache-2.0"
    else
        fail "$(basename "$sdist"): PKG-INFO has no License-Expression"
    fi
else
    cat "$LOG/sdist.log"
    fail "maturin sdist"
fi

# ---------------------------------------------------------------- smoke test
HOST=$(uname -m)
if ((SMOKE)) && [[ " ${ARCHES[*]} " == *" $HOST "* ]]; then
    phase "smoke test: the $HOST wheel in a fresh venv"
    whl=$(wheel_of "$HOST")
    if [ -n "$whl" ]; then
        SM=$(mktemp -d "${TMPDIR:-/tmp}/famcc-smoke.XXXXXX")
        python3 -m venv "$SM/venv"
        "$SM/venv/bin/python" -m pip install --quiet --disable-pip-version-check "$whl"
        # Outside the source tree, so that only the installed wheel can be imported.
        if (cd "$SM" && "$SM/venv/bin/famcc" --version &&
            "$SM/venv/bin/python" -c 'import famcc, sys; print(famcc.__file__); sys.exit("site-packages" not in famcc.__file__)' &&
            time "$SM/venv/bin/famcc" reproduce --out "$SM/out" &&
            test -s "$SM/out/report.md"); then
            echo "ok: famcc reproduce exited 0 from the installed wheel ($SM/out/report.md)"
        else
            fail "smoke test of $(basename "$whl") (in $SM)"
        fi
    else
        fail "smoke test: no $HOST wheel"
    fi
fi

# ---------------------------------------------------------------- summary
phase "summary"
ls -l "$OUT"/famcc-"$VERSION"* 2>/dev/null | awk '{print "  " $5 "  " $9}'
if ((${#FAILURES[@]})); then
    echo "FAILED (${#FAILURES[@]}):"
    printf '  %s\n' "${FAILURES[@]}"
    exit 1
fi
echo "build-wheels: OK ($(($(date +%s) - T0)) s)"
