#!/usr/bin/env bash
# Installs what the tests need and runs every test: Rust (fmt, clippy, unit,
# property, golden and closed-loop tests, the no_std build), Python (pytest),
# and the firmware check (cross-build, emulated closed loops, C ABI).
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m pip install --quiet --disable-pip-version-check -e '.[test]'
cargo fmt --all -- --check
cargo clippy --workspace --all-targets -- -D warnings
cargo test -p famcc-core
cargo build -p famcc-core --no-default-features
# The C ABI (its own workspace: a no_std staticlib with panic = "abort").
cargo test --manifest-path crates/famcc-ffi/Cargo.toml --lib
ruff check python tests benches examples
python3 -m pytest -q
# famcc-core in f32 on a Cortex-M4F under QEMU, and the C ABI (installs its
# Debian packages with apt-get when missing).
bash scripts/firmware-check.sh
