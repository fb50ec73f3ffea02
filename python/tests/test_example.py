"""The example the README's fresh-machine check runs: python/examples/fly_formation.py flies
formation.toml for 10 s and saves the frame at the end as a PNG of the camera's size."""

import struct
import subprocess
import sys


def test_fly_formation_saves_a_frame(root, tmp_path):
    out = tmp_path / "frame.png"
    done = subprocess.run(
        [sys.executable, root / "python/examples/fly_formation.py", "--out", out],
        cwd=root, capture_output=True, text=True, check=True,
    )
    assert "t = 10.0" in done.stdout, done.stdout
    png = out.read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert struct.unpack(">II", png[16:24]) == (640, 480)
