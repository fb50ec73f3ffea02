"""A finished run folder as a Rerun recording (docs/viewer.md): its camera frames with the
measurement drawn over them, the 3-D scene (every aircraft with its trail, the slot, the
camera's frustum) and its time series (R against R_c, b̂ with its ±3σ band, the
measurement against the truth, the control surfaces), all on the timeline ``sim_time``.

    python -m wingman.rerun RUN_DIR FILE.rrd       # what `wingman export rerun` runs
    rerun FILE.rrd                                 # opens it in the viewer

It reads only the folder (``scenario.toml``, ``telemetry.csv``, ``summary.json``,
``frames/``); the run itself is not repeated. Frames are in the recording at the rate the
run saved them: ``output.frames_every = 1`` saves every camera frame.
"""

import argparse
import json
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import rerun as rr
import rerun.blueprint as rrb

try:
    import tomllib
except ImportError:  # Python < 3.11
    import tomli as tomllib

from . import load_results

TIMELINE = "sim_time"
# The overlay's colours (src/vision/overlay.rs): measured by status, the truth in cyan.
OK_RGB, TRUNCATED_RGB, LOST_RGB, TRUTH_RGB = (0, 230, 0), (255, 220, 0), (255, 40, 40), (0, 220, 255)
# telemetry.csv's meas_status: 0 ok, 1 not found, 2 touching the border, 3 too small.
STATUS_RGB = {0: OK_RGB, 1: LOST_RGB, 2: TRUNCATED_RGB, 3: LOST_RGB}
AIRCRAFT_RGB = [(40, 90, 220), (220, 60, 40), (240, 160, 0), (150, 60, 200), (0, 160, 120)]
# How often a trail is redrawn, s, and the spacing of its points, s.
TRAIL_EVERY_S, TRAIL_STEP_S = 0.5, 0.1
# Where the frustum's image plane is drawn, ft from the camera.
IMAGE_PLANE_FT = 12.0


@dataclass
class Aircraft:
    """One aircraft of the run: its name (an entity path part), times (s), NED positions (ft,
    N x 3), attitudes (roll, pitch, yaw, rad, N x 3) and, for a follower that saved frames,
    the frame folder and the telemetry columns' prefix of its camera ("" for the follower of
    a one-follower run)."""

    name: str
    t_s: np.ndarray
    position_ned_ft: np.ndarray
    attitude_rad: np.ndarray
    frames_dir: Path = None
    prefix: str = ""


def _stack(columns, names):
    """The named columns side by side, or None when one is missing."""
    if not all(n in columns for n in names):
        return None
    return np.column_stack([np.asarray(columns[n], dtype=float) for n in names])


def _axes(prefix, suffix):
    return [f"{prefix}{axis}{suffix}" for axis in ("n", "e", "d")]


def find_aircraft(run_dir, columns):
    """The aircraft a run folder holds: the follower (``fol_*``, attitude ``phi_rad``...),
    the target at R_F + R (``rel_*``, ``tgt_phi_rad``...), and every further aircraft
    ``NAME`` logged as ``NAME_rel_n_ft``... (relative to the follower) with
    ``NAME_phi_rad``... (zero attitude where absent). The follower's frames are
    ``frames/*.png``; a follower ``NAME`` with its own camera saves into ``frames/NAME/``."""
    t = np.asarray(columns["t_s"], dtype=float)
    follower = _stack(columns, _axes("fol_", "_ft"))
    euler = ("phi_rad", "theta_rad", "psi_rad")
    found = [Aircraft("follower", t, follower, _stack(columns, euler), Path(run_dir) / "frames")]
    names = sorted(
        c[: -len("_rel_n_ft")] for c in columns if c.endswith("_rel_n_ft") and c != "rel_n_ft"
    )
    for name, prefix in [("target", "")] + [(n, f"{n}_") for n in names]:
        rel = _stack(columns, _axes(f"{prefix}rel_", "_ft"))
        attitude = _stack(columns, [f"{prefix or 'tgt_'}{e}" for e in euler])
        if attitude is None:
            attitude = np.zeros_like(rel)
        frames = Path(run_dir) / "frames" / name
        found.append(Aircraft(name, t, follower + rel, attitude, frames, prefix))
    return found


def quaternion_xyzw(attitude_rad):
    """Quaternions (x, y, z, w) of roll, pitch, yaw (N x 3, rad): yaw about z, then pitch
    about the new y, then roll about the new x (the body axes from NED's)."""
    half = 0.5 * np.asarray(attitude_rad, dtype=float)
    (cr, cp, cy), (sr, sp, sy) = np.cos(half).T, np.sin(half).T
    return np.column_stack(
        [
            sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy,
        ]
    )


def _quaternion_product(a, b):
    """a b for quaternions (x, y, z, w), row by row."""
    (ax, ay, az, aw), (bx, by, bz, bw) = a.T, b.T
    return np.column_stack(
        [
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz,
        ]
    )


@dataclass
class Camera:
    """The scenario's camera: image size (px), focal length (px), frame rate (Hz) and the
    mount's pitch (rad)."""

    width_px: int
    height_px: int
    focal_px: float
    rate_hz: float
    mount_pitch_rad: float

    @classmethod
    def of(cls, scenario):
        cam = scenario["camera"]
        focal = cam.get("focal_px", 0.0) or 0.5 * cam["width_px"] / np.tan(
            0.5 * np.radians(cam["hfov_deg"])
        )
        pitch = np.radians(cam.get("mount_pitch_deg", 0.0))
        return cls(cam["width_px"], cam["height_px"], float(focal), cam["rate_hz"], pitch)

    def pixel(self, y_i_px, z_i_px):
        """(u, v) of image coordinates (yI right, zI up, from the image centre)."""
        return 0.5 * self.width_px + y_i_px, 0.5 * self.height_px - z_i_px


def _series(rec, path, t_s, values):
    """A time series at `path`, its empty cells (NaN) left out."""
    values = np.asarray(values, dtype=float)
    keep = np.isfinite(values)
    if keep.any():
        rec.send_columns(
            path,
            indexes=[rr.TimeColumn(TIMELINE, duration=t_s[keep])],
            columns=rr.Scalars.columns(scalars=values[keep]),
        )


def log_time_series(rec, columns, b_true_ft, follower=None):
    """R against R_c per axis, b̂ (and the filter's b̂ ± 3σ_b) against the true size, the
    held frame's measured centroid and length against the truth, the surfaces (°) and
    throttle: under ``series/KIND/`` (``series/KIND/FOLLOWER/`` for a follower of a group)."""
    t = np.asarray(columns["t_s"], dtype=float)
    who = f"{follower}/" if follower else ""

    def path(kind, rest):
        return f"series/{kind}/{who}{rest}"

    for axis in ("n", "e", "d"):
        _series(rec, path("relative_position", f"{axis}/R"), t, columns[f"rel_{axis}_ft"])
        _series(rec, path("relative_position", f"{axis}/R_c"), t, columns[f"cmd_{axis}_ft"])
    _series(rec, path("size", "b_hat"), t, columns["b_hat_ft"])
    _series(rec, path("size", "b_true"), t, np.full_like(t, b_true_ft))
    if "kf_b_sigma_ft" in columns:
        b, sigma = np.asarray(columns["kf_b_hat_ft"]), np.asarray(columns["kf_b_sigma_ft"])
        _series(rec, path("size", "b_hat_plus_3sigma"), t, b + 3.0 * sigma)
        _series(rec, path("size", "b_hat_minus_3sigma"), t, b - 3.0 * sigma)
    for name in ("y_i", "z_i", "b_i"):
        _series(rec, path("measurement", f"{name}/measured"), t, columns[f"{name}_px"])
        _series(rec, path("measurement", f"{name}/truth"), t, columns[f"{name}_true_px"])
    for name in ("elevator", "aileron", "rudder"):
        if f"{name}_rad" in columns:
            _series(rec, path("surfaces", f"{name}_deg"), t, np.degrees(columns[f"{name}_rad"]))
    if "throttle" in columns:
        _series(rec, path("surfaces", "throttle"), t, columns["throttle"])
    dashed = rr.SeriesLines(colors=[(150, 150, 150)], widths=[1.0])
    for name in ("b_true", "b_hat_plus_3sigma", "b_hat_minus_3sigma"):
        rec.log(path("size", name), dashed, static=True)
    for axis in ("n", "e", "d"):
        rec.log(path("relative_position", f"{axis}/R_c"), dashed, static=True)


def log_scene(rec, aircraft, mesh_path):
    """Every aircraft's pose (a transform at every telemetry row, the target's mesh on it)
    and its trail so far (redrawn every TRAIL_EVERY_S), in NED (x north, y east, z down),
    ft, under ``world/``."""
    rec.log("world", rr.ViewCoordinates.FRD, static=True)
    for k, craft in enumerate(aircraft):
        path, rgb = f"world/{craft.name}", AIRCRAFT_RGB[k % len(AIRCRAFT_RGB)]
        rec.send_columns(
            path,
            indexes=[rr.TimeColumn(TIMELINE, duration=craft.t_s)],
            columns=rr.Transform3D.columns(
                translation=craft.position_ned_ft, quaternion=quaternion_xyzw(craft.attitude_rad)
            ),
        )
        if mesh_path is not None:
            rec.log(f"{path}/mesh", rr.Asset3D(path=mesh_path, albedo_factor=rgb), static=True)
        else:
            rec.log(f"{path}/mesh", rr.Arrows3D(vectors=[[8.0, 0, 0]], colors=[rgb]), static=True)
        _log_trail(rec, f"world/trails/{craft.name}", craft, rgb)


def log_slot(rec, path, columns):
    """The slot a follower is sent to, R_F + R - R_c, from its own telemetry, at ``path``."""
    t = np.asarray(columns["t_s"], dtype=float)
    tracked = _stack(columns, _axes("fol_", "_ft")) + _stack(columns, _axes("rel_", "_ft"))
    slot = tracked - _stack(columns, _axes("cmd_", "_ft"))
    rec.send_columns(
        path,
        indexes=[rr.TimeColumn(TIMELINE, duration=t)],
        columns=rr.Points3D.columns(positions=slot),
    )
    rec.log(path, rr.Points3D.from_fields(colors=[(0, 200, 0)], radii=[1.0]), static=True)


def _log_trail(rec, path, craft, rgb):
    t = craft.t_s
    step = max(1, int(round(TRAIL_STEP_S / max(np.median(np.diff(t)), 1e-9)))) if len(t) > 1 else 1
    for t_now in np.arange(t[0], t[-1] + 1e-9, TRAIL_EVERY_S):
        upto = np.searchsorted(t, t_now, side="right")
        points = craft.position_ned_ft[:upto:step]
        rec.set_time(TIMELINE, duration=float(t_now))
        rec.log(path, rr.LineStrips3D([points], colors=[rgb], radii=[0.3]))


def frame_files(frames_dir):
    """The saved frames of a folder, ``NNNNNN.png`` by number: [(number, path)]."""
    if frames_dir is None or not Path(frames_dir).is_dir():
        return []
    found = [(int(p.stem), p) for p in Path(frames_dir).glob("*.png") if p.stem.isdigit()]
    return sorted(found)


def log_camera(rec, craft, camera, columns):
    """A follower's camera: its orientation on the body (mount pitch, then the gimbal's pan
    and tilt, as their encoders read them) at every telemetry row, the pinhole (its frustum
    in the 3-D view) and each saved frame at its exposure time, with the frame's measurement
    (centroid cross, a square of the maximal length centred on it, status colour) and the
    truth (cyan). Returns the number of frames logged."""
    frames = frame_files(craft.frames_dir)
    if not frames:
        return 0
    cam_path = f"world/{craft.name}/camera"
    pan = columns.get(f"{craft.prefix}gimbal_pan_rad", np.zeros_like(craft.t_s))
    tilt = columns.get(f"{craft.prefix}gimbal_tilt_rad", np.zeros_like(craft.t_s))
    gimbal = quaternion_xyzw(np.column_stack([np.zeros_like(craft.t_s), tilt, pan]))
    mount = quaternion_xyzw([[0.0, camera.mount_pitch_rad, 0.0]] * len(craft.t_s))
    rec.send_columns(
        cam_path,
        indexes=[rr.TimeColumn(TIMELINE, duration=craft.t_s)],
        columns=rr.Transform3D.columns(quaternion=_quaternion_product(mount, gimbal)),
    )
    pinhole = rr.Pinhole(
        focal_length=camera.focal_px,
        width=camera.width_px,
        height=camera.height_px,
        camera_xyz=rr.ViewCoordinates.FRD,
        image_plane_distance=IMAGE_PLANE_FT,
    )
    rec.log(f"{cam_path}/image", pinhole, static=True)
    held = _held_frames(columns, craft.prefix, camera.rate_hz)
    for number, png in frames:
        t_s = number / camera.rate_hz
        rec.set_time(TIMELINE, duration=t_s)
        rec.log(f"{cam_path}/image", rr.EncodedImage(path=png))
        if number in held:
            _log_measurement(rec, f"{cam_path}/image", camera, columns, craft.prefix, held[number])
        else:  # no telemetry row holds this frame: no marks rather than the last frame's
            rec.log(f"{cam_path}/image/measured", rr.Clear(recursive=True))
            rec.log(f"{cam_path}/image/truth", rr.Clear(recursive=True))
    return len(frames)


def _held_frames(columns, prefix, rate_hz):
    """Frame number -> the first telemetry row that holds that frame's measurement."""
    frame_t = np.asarray(columns.get(f"{prefix}frame_t_s", []), dtype=float)
    rows = {}
    for row, t_s in enumerate(frame_t):
        if np.isfinite(t_s):
            rows.setdefault(int(round(t_s * rate_hz)), row)
    return rows


def _log_measurement(rec, image_path, camera, columns, prefix, row):
    def value(name):
        return float(columns[f"{prefix}{name}"][row])

    status = value("meas_status")
    status = int(status) if np.isfinite(status) else 1
    marks = (("measured", "_px", STATUS_RGB[status]), ("truth", "_true_px", TRUTH_RGB))
    for kind, suffix, rgb in marks:
        y, z, b = (value(f"{n}{suffix}") for n in ("y_i", "z_i", "b_i"))
        path = f"{image_path}/{kind}"
        if not np.isfinite([y, z, b]).all():
            rec.log(path, rr.Clear(recursive=True))
            continue
        centre = camera.pixel(y, z)
        rec.log(f"{path}/centroid", rr.Points2D([centre], colors=[rgb], radii=[2.0]))
        label = f"b = {b:.1f} px" if kind == "measured" else None
        boxes = rr.Boxes2D(centers=[centre], half_sizes=[[b / 2, b / 2]], colors=[rgb], labels=label)
        rec.log(f"{path}/length", boxes)


def blueprint(cameras, follower):
    """The layout the recording opens with, at the run's end: the 3-D scene (its eye 80 ft
    behind and 40 ft above the follower there, following it) and each camera's image beside
    the time series."""
    images = [rrb.Spatial2DView(origin=f"world/{name}/camera/image", name=f"{name} camera") for name in cameras]
    series = [
        rrb.TimeSeriesView(origin=f"series/{name}", name=title)
        for name, title in (
            ("relative_position", "R against R_c, ft"),
            ("size", "b_hat with +-3 sigma, ft"),
            ("measurement", "measured against true, px"),
            ("surfaces", "surfaces, deg; throttle"),
        )
    ]
    end = follower.position_ned_ft[-1]
    heading = end - follower.position_ned_ft[max(0, len(follower.t_s) - 10)]
    heading = heading / max(np.linalg.norm(heading), 1e-9)
    eye = rrb.archetypes.EyeControls3D(
        position=end - 80.0 * heading + [0.0, 0.0, -40.0],
        look_target=end,
        eye_up=[0.0, 0.0, -1.0],
        tracking_entity=f"world/{follower.name}",
    )
    scene = rrb.Spatial3DView(origin="world", name="scene (NED, ft)", eye_controls=eye)
    layout = rrb.Horizontal(rrb.Vertical(scene, *images), rrb.Vertical(*series), column_shares=[3, 2])
    time = rrb.TimePanel(timeline=TIMELINE, play_state="following", state="collapsed")
    return rrb.Blueprint(layout, time, collapse_panels=True)


def _read_run(run_dir):
    run_dir = Path(run_dir)
    for name in ("scenario.toml", "telemetry.csv"):
        if not (run_dir / name).is_file():
            raise FileNotFoundError(f"{run_dir / name}: not a run folder (no {name})")
    scenario = tomllib.loads((run_dir / "scenario.toml").read_text())
    columns = load_results(run_dir / "telemetry.csv")
    summary_path = run_dir / "summary.json"
    summary = json.loads(summary_path.read_text()) if summary_path.is_file() else {}
    return scenario, columns, summary


def _recording(run_dir, out, name):
    rec = rr.RecordingStream("wingman", recording_id=f"wingman-{Path(run_dir).resolve().name}")
    rec.save(str(out))
    rec.set_log_time_enabled(False)
    rec.set_log_tick_enabled(False)
    rec.send_recording_name(name)
    return rec


def _mesh_of(scenario):
    mesh = scenario.get("camera", {}).get("mesh")
    return mesh if mesh and Path(mesh).is_file() else None


def _finish(rec, frames, aircraft):
    rec.send_blueprint(blueprint([name for name, n in frames.items() if n > 0], aircraft[0]))
    rec.flush()
    rec.disconnect()
    return {"aircraft": [c.name for c in aircraft], "frames": frames}


def write_recording(run_dir, out, aircraft=None):
    """Writes the run folder ``run_dir`` as the Rerun recording ``out`` (.rrd). ``aircraft``:
    the aircraft to show, a list of :class:`Aircraft` (default: :func:`find_aircraft`'s).
    A group run's folder (``group.json``) is written by :func:`write_group_recording`.
    Returns a dict: the aircraft's names and the frames logged per camera."""
    if (Path(run_dir) / "group.json").is_file() and aircraft is None:
        return write_group_recording(run_dir, out)
    scenario, columns, summary = _read_run(run_dir)
    aircraft = aircraft if aircraft is not None else find_aircraft(run_dir, columns)
    camera = Camera.of(scenario) if "camera" in scenario else None
    rec = _recording(run_dir, out, summary.get("scenario", Path(run_dir).name))
    log_scene(rec, aircraft, _mesh_of(scenario))
    log_slot(rec, "world/slot", columns)
    log_time_series(rec, columns, summary.get("b_true_ft", float("nan")))
    frames = {c.name: log_camera(rec, c, camera, columns) for c in aircraft if camera is not None}
    return _finish(rec, frames, aircraft)


def write_group_recording(run_dir, out):
    """A group run's folder (docs/outputs.md, Group runs) as one recording: every follower
    (from its own folder's ``fol_*`` and attitude) and every target a follower tracks (at
    its R_F + R), each follower's slot (``world/slots/NAME``) and its time series (under
    ``series/KIND/NAME/``), and the cameras' saved frames where there are any."""
    run_dir = Path(run_dir)
    group = json.loads((run_dir / "group.json").read_text())
    runs = {f["name"]: _read_run(run_dir / f["name"]) for f in group["followers"]}
    aircraft = []
    for member in group["followers"]:
        name, (_, columns, _) = member["name"], runs[member["name"]]
        follower, target = find_aircraft(run_dir / name, columns)[:2]
        aircraft.append(Aircraft(name, follower.t_s, follower.position_ned_ft, follower.attitude_rad, follower.frames_dir))
        seen = {a.name for a in aircraft} | set(runs)
        if member["tracks"] not in seen:
            aircraft.append(Aircraft(member["tracks"], target.t_s, target.position_ned_ft, target.attitude_rad))
    first_scenario = runs[group["followers"][0]["name"]][0]
    rec = _recording(run_dir, out, group.get("scenario", run_dir.name))
    log_scene(rec, aircraft, _mesh_of(first_scenario))
    frames = {}
    for name, (scenario, columns, summary) in runs.items():
        log_slot(rec, f"world/slots/{name}", columns)
        log_time_series(rec, columns, summary.get("b_true_ft", float("nan")), follower=name)
        camera = Camera.of(scenario) if "camera" in scenario else None
        craft = next(a for a in aircraft if a.name == name)
        frames[name] = log_camera(rec, craft, camera, columns) if camera is not None else 0
    return _finish(rec, frames, aircraft)


def main(argv=None):
    """``python -m wingman.rerun RUN_DIR FILE.rrd``: exit 0, or 2 with one line for a folder
    that is not a run's."""
    parser = argparse.ArgumentParser(prog="python -m wingman.rerun", description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir", type=Path)
    parser.add_argument("out", type=Path)
    args = parser.parse_args(argv)
    try:
        written = write_recording(args.run_dir, args.out)
    except KeyError as e:
        print(f"error: {args.run_dir}: telemetry.csv or scenario.toml has no {e}", file=sys.stderr)
        return 2
    except (FileNotFoundError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    frames = sum(written["frames"].values())
    print(f"{args.out}: {', '.join(written['aircraft'])}; {frames} frames; open it with: rerun {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
