#!/usr/bin/env bash
# Installs what the tests need and runs every test: Rust (fmt, clippy, unit,
# property and golden tests, the no_std build) and Python (pytest).
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m pip install --quiet --disable-pip-version-check -e '.[test]'
cargo fmt --all -- --check
cargo clippy --workspace --all-targets -- -D warnings
cargo test -p famcc-core
cargo build -p famcc-core --no-default-features
python3 -m pytest -q
