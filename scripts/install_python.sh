#!/bin/sh
# Builds and installs the Python package `wingman` (python/, docs/python.md) with pytest into
# the virtual environment .venv of this clone (made here; no root needed, no system Python
# touched). maturin builds the extension into this clone's target/ with the release profile,
# so the Rust it shares with `cargo build --release` is not built twice. Run it again after
# changing the Rust (scripts/test.sh does). Then: .venv/bin/python, or `. .venv/bin/activate`.
set -eu
cd "$(dirname "$0")/.."
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check "./python[test,rerun]"
.venv/bin/python -c "import wingman, gymnasium; gymnasium.spec('wingman/Formation-v0')"
