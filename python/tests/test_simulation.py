"""A Simulation stepped from Python is the run `wingman run` makes: its summary has the
numbers of the command line's summary.json for the same scenario and seed (all but the wall
times, exactly); a step advances one tick; frames come back as (H, W, 4) uint8 arrays; a bad
scenario raises ScenarioError with the command line's message; a command offset changes how
the follower flies."""

import json
import subprocess

import numpy as np
import pytest

import wingman

# A short formation run: 5 s, 150 frames.
SHORT = {"run.seed": 3, "run.duration_s": 5.0}
# The summary's keys that are wall times (and the adapter's name and figures of them).
TIMING_KEYS = {"wall_s", "realtime_factor", "per_frame_ms", "stage_wall_s"}


def test_step_advances_one_tick_and_frames_are_images(root):
    sim = wingman.Simulation(root / "scenarios/formation.toml", {**SHORT, "camera.width_px": 160,
                                                                 "camera.height_px": 120,
                                                                 "output.frames_every": 1})
    assert sim.tick == 0 and sim.frame() is None
    assert sim.step() == "running"
    assert sim.tick == 1 and sim.time_s == pytest.approx(sim.dt_s)
    sim.run_until(1.0)
    assert sim.time_s == pytest.approx(1.0)
    frame = sim.frame()
    assert frame.shape == (120, 160, 4) and frame.dtype == np.uint8
    assert sim.frame_size() == (160, 120)
    # The target is in the image: pixels of more than one colour.
    assert len(np.unique(frame.reshape(-1, 4), axis=0)) > 1
    state = sim.state()
    assert state["relative_ned_ft"].shape == (3,)
    np.testing.assert_allclose(
        state["relative_ned_ft"],
        state["target"]["position_ned_ft"] - state["follower"]["position_ned_ft"],
    )
    assert state["command"]["kind"] == "velocity"
    held = sim.measurement()
    assert held["t_s"] < sim.time_s and held["measured_px"].shape == (3,)


def test_windowed_frames_are_not_offered_as_images(root):
    sim = wingman.Simulation(root / "scenarios/formation.toml", SHORT)
    sim.run_until(2.0)
    assert sim.frame() is None, "a frame drawn in its tracking window only is no image"


def test_summary_is_the_command_lines(root, cli, tmp_path):
    sets = [f"--set={k}={v}" for k, v in SHORT.items()]
    out = tmp_path / "run"
    subprocess.run(
        [cli, "run", root / "scenarios/formation.toml", "--out", out, "--quiet",
         "--set", "output.plots=false", *sets],
        check=True,
    )
    expected = json.loads((out / "summary.json").read_text())
    sim = wingman.Simulation(root / "scenarios/formation.toml", {**SHORT, "output.plots": False})
    assert sim.run() == "completed"
    got = sim.summary()
    assert got.keys() == expected.keys()
    for key in expected.keys() - TIMING_KEYS - {"adapter"}:
        assert got[key] == expected[key], key
    assert got["b_hat_final_ft"] == expected["b_hat_final_ft"]
    assert got["rms_error_last20s_ft"] == expected["rms_error_last20s_ft"]


def test_bad_scenario_raises_the_command_lines_message(root, cli):
    with pytest.raises(wingman.ScenarioError) as raised:
        wingman.Simulation(root / "scenarios/formation.toml", {"camera.hfov_deg": 500.0})
    message = str(raised.value)
    cli_run = subprocess.run(
        [cli, "run", root / "scenarios/formation.toml", "--set", "camera.hfov_deg=500.0"],
        capture_output=True, text=True,
    )
    assert cli_run.returncode == 2
    assert cli_run.stderr.strip() == f"error: {message}"
    assert "camera.hfov_deg" in message and "500" in message
    with pytest.raises(wingman.ScenarioError, match="no_such.toml"):
        wingman.Simulation(root / "scenarios/no_such.toml")
    assert issubclass(wingman.ScenarioError, ValueError)


def test_group_scenario_is_refused_not_flown_as_a_pair(root):
    with pytest.raises(wingman.ScenarioError, match=r"group scenario"):
        wingman.Simulation(root / "scenarios/platoon.toml")


def test_command_offset_moves_the_follower(root):
    base = {**SHORT, "sensor.mode": "perfect", "run.duration_s": 4.0}
    plain = wingman.Simulation(root / "scenarios/formation.toml", base)
    pushed = wingman.Simulation(root / "scenarios/formation.toml", base)
    pushed.set_command_offset([0.0, 5.0, 0.0])
    plain.run()
    pushed.run()
    east_plain = plain.state()["follower"]["position_ned_ft"][1]
    east_pushed = pushed.state()["follower"]["position_ned_ft"][1]
    assert east_pushed - east_plain > 5.0, (east_plain, east_pushed)
    assert pushed.state()["command"]["ned"][1] > plain.state()["command"]["ned"][1]


def test_results_of_a_study_as_arrays(tmp_path):
    study = tmp_path / "study.toml"
    study.write_text(
        f'[study]\nscenario = "{wingman.scenario_path("seed_ch4_formation")}"\n'
        'set = ["output.plots=false", "run.duration_s=2.0"]\n'
        '[[axis]]\nkey = "guidance.k"\nvalues = [2.0, 3.0]\n'
    )
    results = wingman.sweep(study, tmp_path / "out")
    assert len(results["status"]) == 2
    assert list(results["status"]) == ["completed", "completed"]
    assert results["b_hat_final_ft"].dtype == np.float64
