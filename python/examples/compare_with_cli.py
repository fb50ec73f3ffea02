"""Runs a scenario with the command line and from Python for each seed and prints, per seed,
the frames per second of each, by wall time and by CPU time (of the whole run, set-up
included; CPU time is steadier on a shared machine), and whether the
Python summary's b_hat and RMS error are the command line's exactly (docs/findings.md,
wingman from Python). From the repository's root, after `cargo build --release`:

    .venv/bin/python python/examples/compare_with_cli.py --seeds 1 2 3 [--duration-s 140] \
        [--set camera.width_px=160 --set camera.height_px=120]

Python runs: `steps`, sim.step() once per tick, no image; `images`, every frame drawn whole
(output.frames_every = 1) and read as a numpy array after each frame tick.
"""

import argparse
import json
import resource
import subprocess
import tempfile
import time
from pathlib import Path

import wingman


def cli_run(scenario, sets, out):
    args = ["target/release/wingman", "run", scenario, "--out", str(out), "--quiet"]
    for key, value in sets.items():
        args += ["--set", f"{key}={value}"]
    started, cpu = time.perf_counter(), cpu_s(resource.RUSAGE_CHILDREN)
    subprocess.run(args, check=True)
    wall_s = time.perf_counter() - started
    used_s = cpu_s(resource.RUSAGE_CHILDREN) - cpu
    return json.loads((out / "summary.json").read_text()), wall_s, used_s


def cpu_s(who):
    usage = resource.getrusage(who)
    return usage.ru_utime + usage.ru_stime


def python_run(scenario, sets, images):
    started, cpu = time.perf_counter(), cpu_s(resource.RUSAGE_SELF)
    sim = wingman.Simulation(scenario, {**sets, "output.frames_every": 1 if images else 0})
    period = sim.frame_period_ticks
    status = "running"
    while status == "running":
        status = sim.step()
        if images and sim.tick % period == 0:
            frame = sim.frame()
            assert frame is None or frame.dtype.name == "uint8"
    wall_s = time.perf_counter() - started
    return sim.summary(), wall_s, cpu_s(resource.RUSAGE_SELF) - cpu


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="scenarios/formation.toml")
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--duration-s", type=float, default=None)
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a scenario override for every run (repeatable)")
    args = parser.parse_args()
    print("seed | frames | frames/s by wall: CLI, Python steps, Python images | by CPU: CLI, "
          "Python steps, Python images | b_hat CLI | b_hat Python | RMS identical")
    for seed in args.seeds:
        sets = {"run.seed": seed, "output.plots": "false", "output.frames_every": 0}
        sets.update(dict(kv.split("=", 1) for kv in args.set))
        if args.duration_s is not None:
            sets["run.duration_s"] = args.duration_s
        with tempfile.TemporaryDirectory() as tmp:
            cli, *cli_s = cli_run(args.scenario, sets, Path(tmp) / "run")
        steps, *steps_s = python_run(args.scenario, sets, images=False)
        images, *images_s = python_run(args.scenario, sets, images=True)
        frames = cli["frames"]
        rates = [
            f"{frames / times[k]:.0f}" for k in (0, 1) for times in (cli_s, steps_s, images_s)
        ]
        same = all(
            s["b_hat_final_ft"] == cli["b_hat_final_ft"]
            and s["rms_error_last20s_ft"] == cli["rms_error_last20s_ft"]
            for s in (steps, images)
        )
        print(f"{seed} | {frames} | {', '.join(rates[:3])} | {', '.join(rates[3:])} | "
              f"{cli['b_hat_final_ft']!r} | "
              f"{steps['b_hat_final_ft']!r} | {same} (CLI {cli['rms_error_last20s_ft']})")


if __name__ == "__main__":
    main()
