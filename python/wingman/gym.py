"""Gymnasium environments on wingman (docs/python.md, The Gymnasium environment).

``wingman/Formation-v0`` (:class:`FormationEnv`): the follower of ``formation.toml`` keeps its
slot beside the target. One environment step is one camera frame period. The observation is
the camera's image (RGB, small by default), with ``measurement=True`` a Dict of the image and
the frame's measurement. The action is a velocity offset, NED, added to the guidance's
command, which the 6-DOF follower's flight controller flies. The reward is for holding the
slot, with a penalty for each frame that does not measure the target; the episode ends
(terminated) when the run does (target lost for ``run.stop_after_lost_s``, a false lock, or
a diverged state), and is truncated at ``episode_s``.
"""

import math

import gymnasium
import numpy as np
from gymnasium import spaces

from . import Simulation, SimulationError, scenario_path

# Measurement vector: the held frame's (yI, zI, bI), px, and 1 when it measured the target;
# zeros when it did not.
MEASUREMENT_LEN = 4


class FormationEnv(gymnasium.Env):
    """The formation slot from the follower's camera, as a Gymnasium environment.

    Parameters: ``scenario`` (default the shipped ``formation.toml``); ``overrides``, a dict
    of scenario keys (as :class:`wingman.Simulation` takes); ``width_px``/``height_px``, the
    camera's image (64x48 by default, the field of view kept); ``measurement``, whether the
    observation is a Dict with the measurement vector; ``episode_s``, the episode's length,
    s; ``max_offset_fps``, the largest velocity offset per axis an action of 1 asks for,
    ft/s; ``slot_scale_ft``, the slot error at which the reward per step has fallen to 1/e;
    ``lost_penalty``, what a frame that did not measure the target costs.
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 30}

    def __init__(
        self,
        scenario=None,
        overrides=None,
        width_px=64,
        height_px=48,
        measurement=False,
        episode_s=20.0,
        max_offset_fps=10.0,
        slot_scale_ft=10.0,
        lost_penalty=1.0,
        render_mode=None,
    ):
        self.scenario = scenario or scenario_path("formation")
        self.overrides = {
            # The target starts at the slot (32 ft ahead, 8 ft right), in view.
            "target.initial_position_ft": [32.0, 8.0, 0.0],
            **(overrides or {}),
            "camera.width_px": int(width_px),
            "camera.height_px": int(height_px),
            "output.frames_every": 1,
            "run.duration_s": float(episode_s),
        }
        self.with_measurement = measurement
        self.episode_s = float(episode_s)
        self.max_offset_fps = float(max_offset_fps)
        self.slot_scale_ft = float(slot_scale_ft)
        self.lost_penalty = float(lost_penalty)
        self.render_mode = render_mode
        image = spaces.Box(0, 255, shape=(int(height_px), int(width_px), 3), dtype=np.uint8)
        if measurement:
            half_w, half_h = 0.5 * width_px, 0.5 * height_px
            vector = spaces.Box(
                np.array([-half_w, -half_h, 0.0, 0.0], dtype=np.float32),
                np.array([half_w, half_h, math.hypot(width_px, height_px), 1.0], dtype=np.float32),
            )
            self.observation_space = spaces.Dict({"image": image, "measurement": vector})
        else:
            self.observation_space = image
        self.action_space = spaces.Box(-1.0, 1.0, shape=(3,), dtype=np.float32)
        self._sim = None
        self._image = np.zeros(image.shape, dtype=np.uint8)
        self._ticks_per_step = 1

    def _start(self, seed):
        overrides = dict(self.overrides)
        overrides["run.seed"] = int(seed)
        sim = Simulation(self.scenario, overrides)
        self._ticks_per_step = sim.frame_period_ticks or 1
        self._sim = sim

    def _observation(self):
        frame = self._sim.frame()
        if frame is not None:
            self._image = np.ascontiguousarray(frame[:, :, :3])
        if not self.with_measurement:
            return self._image.copy()
        return {"image": self._image.copy(), "measurement": self._measurement_vector()}

    def _measurement_vector(self):
        held = self._sim.measurement()
        vector = np.zeros(MEASUREMENT_LEN, dtype=np.float32)
        if held is not None and held["status"] == "OK" and held["measured_px"] is not None:
            space = self.observation_space["measurement"]
            vector[:3] = np.clip(held["measured_px"], space.low[:3], space.high[:3])
            vector[3] = 1.0
        return vector

    def _slot_error_ft(self):
        state = self._sim.state()
        return float(np.linalg.norm(state["relative_ned_ft"] - state["slot_ned_ft"]))

    def _target_measured(self):
        held = self._sim.measurement()
        return held is not None and held["status"] == "OK"

    def reset(self, *, seed=None, options=None):
        """Starts an episode: ``seed`` is the run's ``run.seed`` (its turbulence; without
        one, drawn from the environment's generator)."""
        super().reset(seed=seed)
        run_seed = seed if seed is not None else int(self.np_random.integers(0, 2**31 - 1))
        self._start(run_seed)
        self._image = np.zeros_like(self._image)
        return self._observation(), {"t_s": self._sim.time_s, "run_seed": run_seed}

    def step(self, action):
        """Flies ``action`` (each axis in [-1, 1] of ``max_offset_fps``, NED) for one camera
        frame period."""
        offset = np.clip(np.asarray(action, dtype=float), -1.0, 1.0) * self.max_offset_fps
        self._sim.set_command_offset(offset)
        status = "running"
        diverged = False
        try:
            for _ in range(self._ticks_per_step):
                status = self._sim.step()
                if status != "running":
                    break
        except SimulationError:
            diverged = True
            status = "diverged"
        error_ft = math.inf if diverged else self._slot_error_ft()
        measured = not diverged and self._target_measured()
        reward = math.exp(-error_ft / self.slot_scale_ft) - (0.0 if measured else self.lost_penalty)
        terminated = status in ("lost", "false_lock", "diverged", "intercepted")
        truncated = not terminated and (
            status == "completed" or self._sim.time_s >= self.episode_s - 1e-9
        )
        info = {"t_s": self._sim.time_s, "slot_error_ft": error_ft, "status": status}
        return self._observation(), float(reward), terminated, truncated, info

    def render(self):
        """The camera's last frame (RGB, H x W x 3 uint8)."""
        return self._image.copy()
