"""Shared for the package's tests: the repository's root (the shipped scenarios) and the
command line built from it (target/release/wingman, built by `cargo build --release`)."""

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def cli():
    path = ROOT / "target" / "release" / "wingman"
    assert path.exists(), f"{path}: build it first (cargo build --release)"
    return path


os.environ.setdefault("NODEVICE_SELECT", "1")
