#!/bin/sh
# The README's test command: every Rust test of the workspace (the simulator and the Python
# package's crate), then the Python package, rebuilt into .venv (scripts/install_python.sh),
# and its tests (python/tests, pytest). Arguments go to pytest.
set -eu
cd "$(dirname "$0")/.."
cargo test --release
sh scripts/install_python.sh
.venv/bin/python -m pytest -q python/tests "$@"
