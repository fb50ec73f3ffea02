//! A snapshot and a frame's record as Python dicts: vectors as float64 numpy arrays of 3,
//! scalars as floats, absent parts as None (keys and units in docs/python.md, States).

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wingman::frames::{EulerAngles, Vec3};
use wingman::guidance::signals::FollowerCommand;
use wingman::sensing::{FollowerPose, FrameRecord};
use wingman::sim::Snapshot;
use wingman::vision::ImageMeasurement;
use wingman::world::target::TargetState;

/// A vector as a numpy array of 3.
fn vector<'py>(py: Python<'py>, v: &Vec3) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v.as_slice())
}

/// Roll, pitch and yaw, rad, as a numpy array of 3.
fn angles<'py>(py: Python<'py>, a: &EulerAngles) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, &[a.phi_rad, a.theta_rad, a.psi_rad])
}

/// The follower as the truth has it, or as its navigation knows itself.
fn pose_dict<'py>(
    py: Python<'py>,
    position: &Vec3,
    velocity: &Vec3,
    attitude: &EulerAngles,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("position_ned_ft", vector(py, position))?;
    d.set_item("velocity_ned_fps", vector(py, velocity))?;
    d.set_item("attitude_rad", angles(py, attitude))?;
    Ok(d)
}

fn navigation_dict<'py>(py: Python<'py>, pose: &FollowerPose) -> PyResult<Bound<'py, PyDict>> {
    pose_dict(
        py,
        &pose.position_ned_ft,
        &pose.velocity_ned_fps,
        &pose.attitude,
    )
}

fn target_dict<'py>(py: Python<'py>, target: &TargetState) -> PyResult<Bound<'py, PyDict>> {
    let d = pose_dict(
        py,
        &target.position_ned_ft,
        &target.velocity_ned_fps,
        &target.attitude,
    )?;
    d.set_item("accel_ned_fps2", vector(py, &target.accel_ned_fps2))?;
    Ok(d)
}

/// The command the follower flies: its kind and NED vector (ft/s or ft/s²).
fn command_dict<'py>(py: Python<'py>, command: &FollowerCommand) -> PyResult<Bound<'py, PyDict>> {
    let (kind, v) = match command {
        FollowerCommand::Velocity(v) => ("velocity", v),
        FollowerCommand::Acceleration(a) => ("acceleration", a),
    };
    let d = PyDict::new(py);
    d.set_item("kind", kind)?;
    d.set_item("ned", vector(py, v))?;
    Ok(d)
}

/// The estimate the guidance flies on, and the Kalman filter's when the run has one.
fn estimate_dict<'py>(py: Python<'py>, s: &Snapshot) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("b_hat_ft", s.b_hat_ft)?;
    d.set_item("d_hat", vector(py, &s.target_motion.vector()))?;
    let filter = s
        .filter
        .estimate()
        .map(|e| -> PyResult<Bound<'py, PyDict>> {
            let f = PyDict::new(py);
            f.set_item("r", vector(py, &e.r))?;
            f.set_item("d_per_s", vector(py, &e.d_per_s))?;
            f.set_item("a_per_s2", vector(py, &e.a_per_s2))?;
            f.set_item("b_hat_ft", e.b_hat_ft)?;
            f.set_item("b_sigma_ft", e.b_sigma_ft)?;
            Ok(f)
        })
        .transpose()?;
    d.set_item("filter", filter)?;
    Ok(d)
}

/// (yI, zI, bI), px, as a numpy array of 3.
fn image_point<'py>(
    py: Python<'py>,
    m: &Option<ImageMeasurement>,
) -> Option<Bound<'py, PyArray1<f64>>> {
    m.map(|m| PyArray1::from_slice(py, &[m.y_i_px, m.z_i_px, m.b_i_px]))
}

/// A camera frame's record: its time, status, measured and true (yI, zI, bI) and r*.
pub fn frame_dict<'py>(py: Python<'py>, record: &FrameRecord) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("index", record.index)?;
    d.set_item("t_s", record.t_s)?;
    d.set_item("status", record.status.label())?;
    d.set_item("measured_px", image_point(py, &record.measured))?;
    d.set_item("truth_px", image_point(py, &record.truth))?;
    d.set_item("r_measured", record.r_measured.map(|r| vector(py, &r)))?;
    d.set_item("range_ft", record.range_ft)?;
    Ok(d)
}

/// Every stage's state at one instant.
pub fn snapshot_dict<'py>(py: Python<'py>, s: &Snapshot) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("t_s", s.t_s)?;
    let follower = pose_dict(
        py,
        &s.follower_position_ned_ft,
        &s.follower_velocity_ned_fps,
        &s.follower_attitude,
    )?;
    d.set_item("follower", follower)?;
    let navigation = s.navigation.map(|n| navigation_dict(py, &n)).transpose()?;
    d.set_item("navigation", navigation)?;
    d.set_item("target", target_dict(py, &s.target)?)?;
    d.set_item("relative_ned_ft", vector(py, &s.relative_ned_ft))?;
    d.set_item("slot_ned_ft", vector(py, &s.command_ned_ft))?;
    d.set_item("excited_slot_ned_ft", vector(py, &s.excited_command_ned_ft))?;
    d.set_item("r_measured", s.r_measured.map(|r| vector(py, &r)))?;
    d.set_item("estimate", estimate_dict(py, s)?)?;
    d.set_item("command", command_dict(py, &s.guidance.command)?)?;
    let frame = s.frame.map(|f| frame_dict(py, &f)).transpose()?;
    d.set_item("frame", frame)?;
    Ok(d)
}
