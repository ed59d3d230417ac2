#!/usr/bin/env bash
# Builds the Python package from this checkout into a virtual environment (target/python-venv)
# and runs its tests. `pip install .` is what a user runs; here maturin builds the dev profile,
# reusing the debug build `cargo test` left in target/ (a release build would take minutes more).
set -euo pipefail
cd "$(dirname "$0")/.."

venv=target/python-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install -q --upgrade pip
"$venv/bin/python" -m pip install -q "numpy>=1.21" "pytest>=7"
MATURIN_PEP517_ARGS="--profile dev" "$venv/bin/python" -m pip install -q --force-reinstall --no-deps .
# The tests compare against the command line's own PNG: its binary, as `cargo test --workspace`
# built it (a no-op after it; `cargo build -p firmament` would resolve features anew).
cargo test -q --workspace --no-run
"$venv/bin/python" -m pytest -q crates/firmament-py/tests
