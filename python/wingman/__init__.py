"""wingman from Python: a scenario's simulation stepped tick by tick, its camera frames as
numpy arrays, its summary as `wingman run` writes it, studies' results as arrays, and the
Gymnasium environment ``wingman/Formation-v0`` (registered on import). See docs/python.md.

    import wingman
    sim = wingman.Simulation("scenarios/formation.toml", overrides={"run.seed": 3})
    sim.run_until(10.0)
    sim.state()["relative_ned_ft"], sim.summary()["b_hat_final_ft"]
"""

import csv
import json
import os
from pathlib import Path

import numpy as np

from . import _wingman
from ._wingman import ScenarioError, SimulationError

__all__ = [
    "Simulation",
    "ScenarioError",
    "SimulationError",
    "sweep",
    "load_results",
    "scenario_path",
    "write_png",
]

# Mesa's Vulkan layers warn when XDG_RUNTIME_DIR names no folder: give them a private one,
# as the command line does.
_runtime_dir = _wingman.runtime_dir_to_set()
if _runtime_dir is not None:
    os.environ["XDG_RUNTIME_DIR"] = str(_runtime_dir)


def scenario_path(name):
    """The path of a shipped scenario (``"formation"``) of the clone this package was built
    from."""
    return str(Path(_wingman.SCENARIOS_DIR).resolve() / f"{name}.toml")


def _override(key, value):
    """One ``--set`` argument: booleans as TOML writes them, numbers in full precision,
    lists as TOML arrays, text as it is (as on the command line)."""
    if isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, (list, tuple, np.ndarray)):
        text = "[" + ", ".join(_override("", v).split("=", 1)[1] for v in value) + "]"
    elif isinstance(value, (int, float, np.integer, np.floating)):
        text = repr(value.item() if isinstance(value, np.generic) else value)
    else:
        text = str(value)
    return f"{key}={text}"


class Simulation:
    """A scenario's simulation, stepped from Python.

    ``scenario`` is a scenario file; ``overrides`` a dict of ``"section.key": value`` (what
    ``wingman run --set section.key=value`` takes). A bad scenario or override raises
    :class:`ScenarioError` with the command line's message (file, key, value, what is
    allowed); a machine without a graphics adapter, or a run that diverges,
    :class:`SimulationError`.
    """

    def __init__(self, scenario, overrides=None):
        args = [_override(k, v) for k, v in (overrides or {}).items()]
        self._sim = _wingman.Simulation(str(scenario), args)

    def step(self):
        """One tick (``run.dt_s``); the status after it: ``"running"`` or how the run ended
        (``"completed"``, ``"intercepted"``, ``"lost"``, ``"false_lock"``). After its end no
        more ticks are taken."""
        return self._sim.step()

    def run_until(self, t_s):
        """Steps until the time reaches ``t_s`` s or the run ends; the status."""
        return self._sim.run_until(float(t_s))

    def run(self):
        """Steps to the run's end; the status."""
        return self._sim.run_until(float("inf"))

    @property
    def status(self):
        """``"running"``, or how the run ended."""
        return self._sim.status

    @property
    def time_s(self):
        """Simulated time, s."""
        return self._sim.time_s

    @property
    def tick(self):
        """Ticks taken."""
        return self._sim.tick

    @property
    def total_ticks(self):
        """Ticks of the whole run."""
        return self._sim.total_ticks

    @property
    def frame_period_ticks(self):
        """Ticks per camera frame; None without a camera."""
        return self._sim.frame_period_ticks

    @property
    def dt_s(self):
        """The tick, s."""
        return self._sim.dt_s

    def frame(self):
        """The last camera frame measured: an (H, W, 4) uint8 RGBA array (a copy), or None
        (no camera, no frame yet, or a frame drawn only in its tracking window: set
        ``output.frames_every`` to 1 to have every frame drawn whole)."""
        return self._sim.frame()

    def frame_size(self):
        """(width, height) of the camera's image, px; None without a camera."""
        return self._sim.frame_size()

    def state(self):
        """Every stage's state now: follower (truth and navigation), target, the slot, the
        estimate, the command and the frame the guidance holds (docs/python.md, States)."""
        return self._sim.state()

    def measurement(self):
        """The camera frame the guidance holds: time, status, measured and true (yI, zI, bI)
        in px, r*; None before the first."""
        return self._sim.measurement()

    def summary(self):
        """The run's summary as a dict: at its end the numbers of ``summary.json`` for the
        same scenario and overrides (but the wall times)."""
        return json.loads(self._sim.summary_json())

    def scenario_toml(self):
        """The resolved scenario, every default filled in, as TOML text."""
        return self._sim.scenario_toml()

    def set_command_offset(self, offset_ned):
        """Adds ``offset_ned`` (3 floats, NED: ft/s to the velocity law's command, ft/s² to
        the acceleration law's) to the guidance's command from the next tick on; None
        removes it. The follower flies the sum."""
        if offset_ned is not None:
            offset_ned = [float(v) for v in np.asarray(offset_ned, dtype=float).reshape(3)]
        self._sim.set_command_offset(offset_ned)


def write_png(path, rgba):
    """Writes an (H, W, 4) uint8 RGBA array (a frame) as a PNG file, making its folder."""
    import struct
    import zlib

    rgba = np.ascontiguousarray(rgba, dtype=np.uint8)
    height, width, _ = rgba.shape
    rows = np.concatenate([np.zeros((height, 1), np.uint8), rgba.reshape(height, -1)], axis=1)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
    png += chunk(b"IDAT", zlib.compress(rows.tobytes())) + chunk(b"IEND", b"")
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_bytes(png)


def load_results(path):
    """A study's ``results.csv`` as a dict of column name to numpy array: float64 where
    every value is a number (empty cells NaN), text otherwise."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    columns = rows[0].keys() if rows else []
    out = {}
    for name in columns:
        values = [r[name] for r in rows]
        try:
            out[name] = np.array([float(v) if v != "" else np.nan for v in values])
        except ValueError:
            out[name] = np.array(values)
    return out


def sweep(study, out, jobs=1):
    """Runs a study as ``wingman sweep STUDY --out OUT --jobs JOBS`` does (resuming cases
    already complete) and returns its results as :func:`load_results` reads them."""
    return load_results(_wingman.sweep(str(study), str(out), int(jobs)))


def _register_environments():
    import gymnasium

    if "wingman/Formation-v0" not in gymnasium.registry:
        gymnasium.register(id="wingman/Formation-v0", entry_point="wingman.gym:FormationEnv")


_register_environments()
