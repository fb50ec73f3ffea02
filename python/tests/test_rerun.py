"""A run folder written as a Rerun recording reads back with Rerun's own reader: the 3-D
scene (each aircraft, its trail, the slot, the camera), the time series and one image per
saved frame at its exposure time (frame number / camera.rate_hz), with the measurement drawn
over it, all on the timeline sim_time over the run's time range; a further aircraft in the
telemetry is one more entity; `wingman export rerun` writes the same through the package."""

import collections
import csv
import os
import subprocess
import sys
from pathlib import Path

import pyarrow as pa
import pytest
from rerun.chunk import RrdReader

from wingman.rerun import find_aircraft, write_recording
from wingman import load_results

ROOT = Path(__file__).resolve().parents[2]
DURATION_S = 5.0
RATE_HZ = 30.0


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    """A 5 s run of formation.toml saving every camera frame."""
    out = tmp_path_factory.mktemp("rerun") / "run"
    cli = ROOT / "target" / "release" / "wingman"
    overrides = [f"run.duration_s={DURATION_S}", "output.frames_every=1", "output.plots=false"]
    args = [str(cli), "run", str(ROOT / "scenarios" / "formation.toml"), "--out", str(out), "--quiet"]
    for o in overrides:
        args += ["--set", o]
    subprocess.run(args, check=True, env={**os.environ, "NODEVICE_SELECT": "1"})
    return out


def read_back(path):
    """Per entity path: rows, the sim_time values (s) and the columns' names."""
    rows, times, columns = collections.Counter(), collections.defaultdict(list), collections.defaultdict(set)
    for chunk in RrdReader(str(path)).stream().to_chunks():
        batch = chunk.to_record_batch()
        names = set(batch.schema.names)
        columns[chunk.entity_path] |= names
        if "EncodedImage:blob" in names:
            rows[chunk.entity_path + "#images"] += chunk.num_rows
        rows[chunk.entity_path] += chunk.num_rows
        if "sim_time" in names:
            ns = batch.column("sim_time").cast(pa.int64()).to_pylist()
            times[chunk.entity_path] += [t / 1e9 for t in ns if t is not None]
    return rows, times, columns


def test_recording_reads_back(run_dir, tmp_path):
    out = tmp_path / "run.rrd"
    written = write_recording(run_dir, out)
    frames = sorted((run_dir / "frames").glob("*.png"))
    assert len(frames) >= DURATION_S * RATE_HZ - 2
    assert written == {"aircraft": ["follower", "target"], "frames": {"follower": len(frames), "target": 0}}
    rows, times, columns = read_back(out)
    image = "/world/follower/camera/image"
    expected = [
        "/world/follower", "/world/target", "/world/follower/mesh", "/world/target/mesh",
        "/world/trails/follower", "/world/trails/target", "/world/slot", "/world/follower/camera",
        image, f"{image}/measured/centroid", f"{image}/measured/length", f"{image}/truth/centroid",
        "/series/relative_position/n/R", "/series/relative_position/n/R_c", "/series/size/b_hat",
        "/series/size/b_hat_plus_3sigma", "/series/size/b_true", "/series/measurement/y_i/measured",
        "/series/measurement/b_i/truth", "/series/surfaces/elevator_deg", "/series/surfaces/throttle",
    ]
    for path in expected:
        assert path in rows, f"{path} not in {sorted(rows)}"
    assert "Pinhole:image_from_camera" in columns[image]
    # One image per saved frame, at its exposure time.
    assert rows[f"{image}#images"] == len(frames)
    numbers = [int(p.stem) for p in frames]
    assert sorted(times[image]) == pytest.approx([n / RATE_HZ for n in numbers], abs=1e-6)
    # The time series and the scene span the run: every telemetry row.
    telemetry = load_results(run_dir / "telemetry.csv")
    for path in ("/series/relative_position/n/R", "/world/follower", "/world/target"):
        assert rows[path] == len(telemetry["t_s"])
        assert (min(times[path]), max(times[path])) == pytest.approx((0.0, DURATION_S))


def test_more_aircraft_are_more_entities(run_dir, tmp_path):
    """A telemetry with a third aircraft (wing2_rel_n_ft...) gets its pose and its trail."""
    with open(run_dir / "telemetry.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    folder = tmp_path / "group"
    folder.mkdir()
    (folder / "scenario.toml").write_text((run_dir / "scenario.toml").read_text())
    names = list(rows[0]) + [f"wing2_rel_{a}_ft" for a in "ned"]
    with open(folder / "telemetry.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, names)
        writer.writeheader()
        for row in rows:
            writer.writerow({**row, **{f"wing2_rel_{a}_ft": float(row[f"rel_{a}_ft"]) + 20 for a in "ned"}})
    columns = load_results(folder / "telemetry.csv")
    aircraft = find_aircraft(folder, columns)
    assert [a.name for a in aircraft] == ["follower", "target", "wing2"]
    assert aircraft[2].position_ned_ft[0] == pytest.approx(aircraft[1].position_ned_ft[0] + 20)
    write_recording(folder, tmp_path / "group.rrd")
    rows_read, times, _ = read_back(tmp_path / "group.rrd")
    assert rows_read["/world/wing2"] == len(rows) and "/world/trails/wing2" in rows_read


def test_cli_export_runs_the_module(run_dir, tmp_path, cli):
    out = tmp_path / "cli.rrd"
    env = {**os.environ, "WINGMAN_PYTHON": sys.executable}
    done = subprocess.run(
        [str(cli), "export", "rerun", str(run_dir), "--out", str(out)], env=env, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    assert f"rerun {out}" in done.stdout
    rows, _, _ = read_back(out)
    assert rows["/world/follower/camera/image#images"] == len(list((run_dir / "frames").glob("*.png")))
    # A folder that is not a run's: one line, exit code 2.
    bad = subprocess.run(
        [sys.executable, "-m", "wingman.rerun", str(tmp_path), str(tmp_path / "x.rrd")], capture_output=True, text=True
    )
    assert bad.returncode == 2 and len(bad.stderr.strip().splitlines()) == 1, bad.stderr


def test_group_run_shows_every_aircraft(cli, tmp_path):
    """A group run's folder (a 3 s platoon): every follower and the target, each follower's
    slot, its own time series over the run's rows and its camera's saved frames."""
    run = tmp_path / "platoon"
    args = [str(cli), "run", str(ROOT / "scenarios" / "platoon.toml"), "--out", str(run), "--quiet"]
    for o in ("run.duration_s=3", "output.plots=false", "output.frames_every=10"):
        args += ["--set", o]
    subprocess.run(args, check=True, env={**os.environ, "NODEVICE_SELECT": "1"})
    written = write_recording(run, tmp_path / "platoon.rrd")
    assert written["aircraft"] == ["f1", "target", "f2", "f3"]
    rows, times, _ = read_back(tmp_path / "platoon.rrd")
    n_rows = len(load_results(run / "f2" / "telemetry.csv")["t_s"])
    for name in ("f1", "f2", "f3", "target"):
        assert rows[f"/world/{name}"] == n_rows and f"/world/trails/{name}" in rows
    for name in ("f1", "f2", "f3"):
        assert rows[f"/world/slots/{name}"] == n_rows + 1  # and its static colour
        assert rows[f"/series/size/{name}/b_hat"] == n_rows
        assert max(times[f"/series/relative_position/{name}/n/R"]) == pytest.approx(3.0)
        saved = sorted((run / name / "frames").glob("*.png"))
        assert len(saved) >= 8 and written["frames"][name] == len(saved)
        assert rows[f"/world/{name}/camera/image#images"] == len(saved)
