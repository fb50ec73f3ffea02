"""Flies scenarios/formation.toml for 10 s from Python and saves the camera's frame at the end
as a PNG (docs/python.md). Run from the repository's root:

    .venv/bin/python python/examples/fly_formation.py [--seed N] [--out FRAME.png]
"""

import argparse

import wingman


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", default="runs/fly_formation_10s.png")
    args = parser.parse_args()
    # Every 30th frame (one a second) is drawn whole, to be saved; the others in their
    # tracking window only, as `wingman run` draws them.
    sim = wingman.Simulation(
        "scenarios/formation.toml",
        overrides={"run.seed": args.seed, "output.frames_every": 30},
    )
    sim.run_until(10.0)
    while sim.frame() is None:
        sim.step()
    frame = sim.frame()
    wingman.write_png(args.out, frame)
    state = sim.state()
    error = state["relative_ned_ft"] - state["slot_ned_ft"]
    print(
        f"t = {sim.time_s:.2f} s: b_hat = {state['estimate']['b_hat_ft']:.3f} ft, "
        f"slot error [{error[0]:.2f}, {error[1]:.2f}, {error[2]:.2f}] ft; "
        f"frame {frame.shape[1]}x{frame.shape[0]} of t = {sim.measurement()['t_s']:.3f} s "
        f"saved to {args.out}"
    )


if __name__ == "__main__":
    main()
