//! The telemetry columns, declared once: each column's name, unit, meaning, the runs that have
//! it and the accessor that writes its value. `telemetry.csv`'s writer
//! ([`super::telemetry::row_of`]) and the table in `docs/outputs.md` ([`super::outputs_doc`])
//! both read [`COLUMNS`].

use crate::estimation::{TargetEstimate, TargetMotionEstimate};
use crate::follower::AircraftActuation;
use crate::frames::{EulerAngles, Vec3, wrap_angle_rad};
use crate::guidance::signals::AccelerationGuidanceOutput;
use crate::guidance::signals::FollowerCommand;
use crate::sensing::FollowerPose;
use crate::sim::{GimbalReading, Snapshot};
use crate::vision::{BlobStatus, ImageMeasurement};
use crate::world::target::TargetFlight;

/// Which runs have a column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Runs {
    /// Every run.
    Every,
    /// Runs whose d̂ is a scaled velocity (the velocity law).
    ScaledVelocity,
    /// Runs whose d̂ is a filtered acceleration bound (the acceleration law).
    AccelerationBound,
    /// Runs whose guidance commands an acceleration (the acceleration law).
    AccelerationCommand,
    /// Runs with the 6-DOF follower.
    Aircraft,
    /// Runs with a Kalman filter (flying on it or beside the adaptive law).
    Filter,
    /// Runs with a gimballed camera.
    Gimbal,
    /// Runs whose gimbal has a roll axis (`camera.gimbal.kind = "roll_pan_tilt"`).
    GimbalRoll,
    /// Runs whose target is an aircraft (`target.model = "aircraft"`).
    TargetAircraft,
    /// Runs whose follower navigates with errors (`navigation.mode` other than `perfect`).
    Navigation,
}

impl Runs {
    /// Whether the run that logged `s` has the column.
    pub fn has(self, s: &Snapshot) -> bool {
        match self {
            Self::Every => true,
            Self::ScaledVelocity => {
                matches!(s.target_motion, TargetMotionEstimate::ScaledVelocity(_))
            }
            Self::AccelerationBound => matches!(
                s.target_motion,
                TargetMotionEstimate::FilteredAccelerationBound(_)
            ),
            Self::AccelerationCommand => {
                matches!(s.guidance.command, FollowerCommand::Acceleration(_))
            }
            Self::Aircraft => s.aircraft.is_some(),
            Self::Filter => s.filter.is_present(),
            Self::Gimbal => s.gimbal.is_some(),
            Self::GimbalRoll => s.gimbal.is_some_and(|g| g.roll_axis),
            Self::TargetAircraft => s.target_flight.is_some(),
            Self::Navigation => s.navigation.is_some(),
        }
    }

    /// The runs in words, for the docs.
    pub fn describe(self) -> &'static str {
        match self {
            Self::Every => "every run",
            Self::ScaledVelocity => "velocity law",
            Self::AccelerationBound | Self::AccelerationCommand => "acceleration law",
            Self::Aircraft => "6-DOF follower",
            Self::Filter => "Kalman filter",
            Self::Gimbal => "gimballed camera",
            Self::GimbalRoll => "gimbal with a roll axis",
            Self::TargetAircraft => "aircraft target",
            Self::Navigation => "navigation with errors",
        }
    }
}

/// The cells an entry writes: one column, or the three components of a vector.
#[derive(Debug, Clone, Copy)]
pub enum Cells {
    /// One column and its value.
    One(&'static str, fn(&Snapshot) -> f64),
    /// Three columns and the vector whose components they hold.
    Three([&'static str; 3], fn(&Snapshot) -> Vec3),
}

/// One entry of the table: a column, or the three columns of a vector.
#[derive(Debug, Clone, Copy)]
pub struct Column {
    /// The column names and the accessor that gives their values (NaN: an empty cell).
    pub cells: Cells,
    /// Unit ("" for numbers without one).
    pub unit: &'static str,
    /// Which runs have it.
    pub runs: Runs,
    /// What it holds.
    pub meaning: &'static str,
}

impl Column {
    /// The column names.
    pub fn names(&self) -> &[&'static str] {
        match &self.cells {
            Cells::One(name, _) => std::slice::from_ref(name),
            Cells::Three(names, _) => names,
        }
    }

    /// Appends the named values of `s` to `row`.
    pub fn push_values(&self, s: &Snapshot, row: &mut Vec<(&'static str, f64)>) {
        match self.cells {
            Cells::One(name, value) => row.push((name, value(s))),
            Cells::Three(names, value) => {
                row.extend(names.into_iter().zip(value(s).iter().copied()))
            }
        }
    }
}

const fn one(
    name: &'static str,
    unit: &'static str,
    runs: Runs,
    meaning: &'static str,
    value: fn(&Snapshot) -> f64,
) -> Column {
    Column {
        cells: Cells::One(name, value),
        unit,
        runs,
        meaning,
    }
}

const fn three(
    names: [&'static str; 3],
    unit: &'static str,
    runs: Runs,
    meaning: &'static str,
    value: fn(&Snapshot) -> Vec3,
) -> Column {
    Column {
        cells: Cells::Three(names, value),
        unit,
        runs,
        meaning,
    }
}

const NAN3: Vec3 = Vec3::new(f64::NAN, f64::NAN, f64::NAN);

fn attitude(a: &EulerAngles) -> Vec3 {
    Vec3::new(a.phi_rad, a.theta_rad, a.psi_rad)
}

/// A pixel measurement as (y_i, z_i, b_i), NaN without one.
fn image(m: Option<ImageMeasurement>) -> Vec3 {
    m.map_or(NAN3, |m| Vec3::new(m.y_i_px, m.z_i_px, m.b_i_px))
}

fn accel(s: &Snapshot, f: fn(&AccelerationGuidanceOutput) -> Vec3) -> Vec3 {
    s.guidance.acceleration.as_ref().map_or(NAN3, f)
}

fn aircraft(s: &Snapshot, f: fn(&AircraftActuation) -> f64) -> f64 {
    s.aircraft.as_ref().map_or(f64::NAN, f)
}

fn aircraft3(s: &Snapshot, f: fn(&AircraftActuation) -> Vec3) -> Vec3 {
    s.aircraft.as_ref().map_or(NAN3, f)
}

fn target_flight(s: &Snapshot, f: fn(&TargetFlight) -> f64) -> f64 {
    s.target_flight.as_ref().map_or(f64::NAN, f)
}

fn filter(s: &Snapshot, f: fn(&TargetEstimate) -> f64) -> f64 {
    s.filter.estimate().as_ref().map_or(f64::NAN, f)
}

fn filter3(s: &Snapshot, f: fn(&TargetEstimate) -> Vec3) -> Vec3 {
    s.filter.estimate().as_ref().map_or(NAN3, f)
}

fn gimbal(s: &Snapshot, f: fn(&GimbalReading) -> f64) -> f64 {
    s.gimbal.as_ref().map_or(f64::NAN, f)
}

fn navigation(s: &Snapshot, f: fn(&FollowerPose) -> Vec3) -> Vec3 {
    s.navigation.as_ref().map_or(NAN3, f)
}

/// `meas_status` codes: 0 ok, 1 not found, 2 truncated (touches the border), 3 too small,
/// 4 merged (the tracked aircraft joined to another, measured for its bearing).
pub fn status_code(status: BlobStatus) -> f64 {
    match status {
        BlobStatus::Ok => 0.0,
        BlobStatus::NotFound => 1.0,
        BlobStatus::Truncated => 2.0,
        BlobStatus::TooSmall => 3.0,
        BlobStatus::Merged => 4.0,
    }
}

use Runs::{
    AccelerationBound, AccelerationCommand, Aircraft, Every, Filter, Gimbal, GimbalRoll,
    Navigation, ScaledVelocity, TargetAircraft,
};

/// Every telemetry column, in the order a row holds them (a run writes those its runs have).
#[rustfmt::skip]
pub static COLUMNS: &[Column] = &[
    one("t_s", "s", Every, "time", |s| s.t_s),
    three(["rel_n_ft", "rel_e_ft", "rel_d_ft"], "ft", Every, "relative position R = R_T - R_F (NED)", |s| s.relative_ned_ft),
    three(["tgt_vn_fps", "tgt_ve_fps", "tgt_vd_fps"], "ft/s", Every, "target velocity V_T (NED)", |s| s.target.velocity_ned_fps),
    three(["tgt_an_fps2", "tgt_ae_fps2", "tgt_ad_fps2"], "ft/s²", Every, "target acceleration a_T (NED)", |s| s.target.accel_ned_fps2),
    three(["tgt_phi_rad", "tgt_theta_rad", "tgt_psi_rad"], "rad", Every, "target attitude φ, θ, ψ", |s| attitude(&s.target.attitude)),
    one("tgt_airspeed_fps", "ft/s", TargetAircraft, "the target's airspeed", |s| target_flight(s, |f| f.airspeed_fps)),
    one("tgt_alpha_rad", "rad", TargetAircraft, "the target's angle of attack α", |s| target_flight(s, |f| f.alpha_rad)),
    one("tgt_beta_rad", "rad", TargetAircraft, "the target's sideslip β", |s| target_flight(s, |f| f.beta_rad)),
    three(["tgt_ref_n_ft", "tgt_ref_e_ft", "tgt_ref_d_ft"], "ft", TargetAircraft, "where the target's reference motion is, R_ref (NED); the target is at R_F + R", |s| s.target_flight.map_or(NAN3, |f| f.reference_ned_ft)),
    three(["fol_n_ft", "fol_e_ft", "fol_d_ft"], "ft", Every, "follower position R_F (NED)", |s| s.follower_position_ned_ft),
    three(["fol_vn_fps", "fol_ve_fps", "fol_vd_fps"], "ft/s", Every, "follower velocity V_F (NED)", |s| s.follower_velocity_ned_fps),
    three(["phi_rad", "theta_rad", "psi_rad"], "rad", Every, "follower attitude φ, θ, ψ", |s| attitude(&s.follower_attitude)),
    three(["cmd_n_ft", "cmd_e_ft", "cmd_d_ft"], "ft", Every, "the command R_c (NED)", |s| s.command_ned_ft),
    three(["cmd_exc_n_ft", "cmd_exc_e_ft", "cmd_exc_d_ft"], "ft", Every, "the excited command R*_c (NED)", |s| s.excited_command_ned_ft),
    one("excitation_amp", "", Every, "the excitation's amplitude a(t) w(t) within its window (`excitation.start_s`, `end_s`), in its own units", |s| s.excitation_amplitude),
    one("b_hat_ft", "ft", Every, "b̂, the size estimate the guidance flies on", |s| s.b_hat_ft),
    three(["d_hat_x_per_s", "d_hat_y_per_s", "d_hat_z_per_s"], "1/s", ScaledVelocity, "d̂, the scaled target velocity", |s| s.target_motion.vector()),
    three(["d_hat_x_fps", "d_hat_y_fps", "d_hat_z_fps"], "ft/s", AccelerationBound, "d̂, the filtered-acceleration bound", |s| s.target_motion.vector()),
    three(["r_meas_x", "r_meas_y", "r_meas_z"], "", Every, "the r the guidance was given at that instant: r* with noise, or the camera's held frame brought forward by the follower's own motion; under the Kalman filter (`estimator.kind = \"kalman\"`) the filter's r̂; empty while it has none", |s| s.r_measured.unwrap_or(NAN3)),
    three(["r_cmd_x", "r_cmd_y", "r_cmd_z"], "", Every, "the scaled command the guidance tracks", |s| s.guidance.r_command),
    one("frame_t_s", "s", Every, "the time of the camera frame the guidance holds (taken `camera.latency_frames` frames earlier; empty without a camera)", |s| s.frame.map_or(f64::NAN, |f| f.t_s)),
    three(["y_i_px", "z_i_px", "b_i_px"], "px", Every, "the held frame's measured centroid and maximal length (empty without a measurement)", |s| image(s.frame.and_then(|f| f.measured))),
    one("meas_status", "", Every, "the held frame's status: 0 ok, 1 not found, 2 touching the border, 3 too small, 4 merged (the tracked aircraft joined to another, `camera.merges = \"bearing\"`) (empty without a camera)", |s| s.frame.map_or(f64::NAN, |f| status_code(f.status))),
    one("meas_trusted", "", Every, "whether the estimator took the held frame: 1 when it was ok and (under the Kalman filter) its innovation and bearing gates did not keep it out, 0 otherwise (empty without a camera)", |s| s.frame_trusted.map_or(f64::NAN, |t| f64::from(u8::from(t)))),
    one("centroid_vs_silhouette_px", "px", Every, "the held frame's measured centroid's distance from the true centroid of the target's silhouette (empty when not ok, or without a camera)", |s| s.frame.and_then(|f| f.centroid_vs_silhouette_px).unwrap_or(f64::NAN)),
    one("meas_background", "", Every, "what lay behind the target in the held frame, by the truth: 0 sky, 1 ground, 2 horizon, 3 cloud (empty without a world scene, `scene.kind = \"world\"`)", |s| s.frame.and_then(|f| f.background).map_or(f64::NAN, |b| f64::from(b as u8))),
    three(["y_i_true_px", "z_i_true_px", "b_i_true_px"], "px", Every, "the held frame's truth: projection of the target's reference point and maximal length of the projected mesh (empty without a camera)", |s| image(s.frame.and_then(|f| f.truth))),
    three(["fol_an_fps2", "fol_ae_fps2", "fol_ad_fps2"], "ft/s²", AccelerationCommand, "the commanded acceleration a_F (5.38) (NED)", |s| accel(s, |a| a.accel_cmd_ned_fps2)),
    three(["y_model_x", "y_model_y", "y_model_z"], "", AccelerationCommand, "the reference model's output y_m", |s| accel(s, |a| a.y_model)),
    three(["y_observer_x", "y_observer_y", "y_observer_z"], "", AccelerationCommand, "the observer's output C ẑ", |s| accel(s, |a| a.y_observer)),
    three(["y_a_x", "y_a_y", "y_a_z"], "", AccelerationCommand, "the combined output y_a", |s| accel(s, |a| a.y_combined)),
    three(["w_f_x_fps", "w_f_y_fps", "w_f_z_fps"], "ft/s", AccelerationCommand, "the virtual control w_f", |s| accel(s, |a| a.virtual_control_fps)),
    one("b_hat_rate_fps", "ft/s", AccelerationCommand, "b̂'", |s| s.guidance.acceleration.as_ref().map_or(f64::NAN, |a| a.b_hat_rate_fps)),
    one("airspeed_fps", "ft/s", Aircraft, "airspeed V", |s| aircraft(s, |a| a.air_data.airspeed_fps)),
    one("alpha_rad", "rad", Aircraft, "angle of attack α", |s| aircraft(s, |a| a.air_data.alpha_rad)),
    one("beta_rad", "rad", Aircraft, "sideslip β", |s| aircraft(s, |a| a.air_data.beta_rad)),
    three(["p_rps", "q_rps", "r_rps"], "rad/s", Aircraft, "body rates p, q, r", |s| aircraft3(s, |a| a.air_data.body_rates_rps)),
    one("throttle", "", Aircraft, "throttle position δT", |s| aircraft(s, |a| a.actuators.throttle)),
    one("elevator_rad", "rad", Aircraft, "elevator position δe", |s| aircraft(s, |a| a.actuators.elevator_rad)),
    one("aileron_rad", "rad", Aircraft, "aileron position δa", |s| aircraft(s, |a| a.actuators.aileron_rad)),
    one("rudder_rad", "rad", Aircraft, "rudder position δr", |s| aircraft(s, |a| a.actuators.rudder_rad)),
    three(["vf_cmd_n_fps", "vf_cmd_e_fps", "vf_cmd_d_fps"], "ft/s", Aircraft, "the V_F the autopilot flies (NED)", |s| aircraft3(s, |a| a.velocity_cmd_ned_fps)),
    one("airspeed_cmd_fps", "ft/s", Aircraft, "the airspeed command V_c", |s| aircraft(s, |a| a.autopilot.airspeed_cmd_fps)),
    one("airspeed_ref_fps", "ft/s", Aircraft, "the airspeed reference V_m", |s| aircraft(s, |a| a.autopilot.airspeed_ref_fps)),
    one("flight_path_cmd_rad", "rad", Aircraft, "the flight-path command γ_c", |s| aircraft(s, |a| a.autopilot.flight_path_cmd_rad)),
    one("phi_cmd_rad", "rad", Aircraft, "the bank command φ_c", |s| aircraft(s, |a| a.autopilot.euler_cmd.phi_rad)),
    one("theta_cmd_rad", "rad", Aircraft, "the pitch command θ_c", |s| aircraft(s, |a| a.autopilot.euler_cmd.theta_rad)),
    one("psi_cmd_rad", "rad", Aircraft, "the heading command ψ_c (wrapped)", |s| aircraft(s, |a| wrap_angle_rad(a.autopilot.euler_cmd.psi_rad))),
    three(["p_cmd_rps", "q_cmd_rps", "r_cmd_rps"], "rad/s", Aircraft, "the filtered rate commands ω_f", |s| aircraft3(s, |a| a.autopilot.rate_cmd_filtered_rps)),
    one("throttle_cmd", "", Aircraft, "the throttle command", |s| aircraft(s, |a| a.autopilot.controls.throttle)),
    one("elevator_cmd_rad", "rad", Aircraft, "the elevator command", |s| aircraft(s, |a| a.autopilot.controls.elevator_rad)),
    one("aileron_cmd_rad", "rad", Aircraft, "the aileron command", |s| aircraft(s, |a| a.autopilot.controls.aileron_rad)),
    one("rudder_cmd_rad", "rad", Aircraft, "the rudder command", |s| aircraft(s, |a| a.autopilot.controls.rudder_rad)),
    three(["gust_u_fps", "gust_v_fps", "gust_w_fps"], "ft/s", Aircraft, "the gust (body axes)", |s| aircraft3(s, |a| a.gust_body_fps)),
    one("kf_b_hat_ft", "ft", Filter, "the filter's b̂ (empty before its first measurement)", |s| filter(s, |f| f.b_hat_ft)),
    one("kf_b_sigma_ft", "ft", Filter, "the filter's σ_b", |s| filter(s, |f| f.b_sigma_ft)),
    one("kf_nis", "", Filter, "νᵀ S⁻¹ ν of the latest measurement the filter fused, held until the next (χ² with 3 degrees of freedom where the filter's model holds: 3 on average; empty before the first)", |s| s.filter_nis.unwrap_or(f64::NAN)),
    three(["kf_r_x", "kf_r_y", "kf_r_z"], "", Filter, "the filter's r", |s| filter3(s, |f| f.r)),
    three(["kf_d_x_per_s", "kf_d_y_per_s", "kf_d_z_per_s"], "1/s", Filter, "the filter's d", |s| filter3(s, |f| f.d_per_s)),
    three(["kf_a_x_per_s2", "kf_a_y_per_s2", "kf_a_z_per_s2"], "1/s²", Filter, "the filter's a", |s| filter3(s, |f| f.a_per_s2)),
    one("gimbal_pan_rad", "rad", Gimbal, "gimbal pan, as its encoder reads it", |s| gimbal(s, |g| g.angles.pan_rad)),
    one("gimbal_tilt_rad", "rad", Gimbal, "gimbal tilt, as its encoder reads it", |s| gimbal(s, |g| g.angles.tilt_rad)),
    one("gimbal_pan_cmd_rad", "rad", Gimbal, "gimbal pan command", |s| gimbal(s, |g| g.command.pan_rad)),
    one("gimbal_tilt_cmd_rad", "rad", Gimbal, "gimbal tilt command", |s| gimbal(s, |g| g.command.tilt_rad)),
    one("gimbal_roll_rad", "rad", GimbalRoll, "gimbal roll, as its encoder reads it", |s| gimbal(s, |g| g.angles.roll_rad)),
    one("gimbal_roll_cmd_rad", "rad", GimbalRoll, "gimbal roll command (minus the navigated bank, within the limits)", |s| gimbal(s, |g| g.command.roll_rad)),
    three(["nav_n_ft", "nav_e_ft", "nav_d_ft"], "ft", Navigation, "the follower's position as its INS/GPS knows it (NED; fol_n_ft... are the truth)", |s| navigation(s, |n| n.position_ned_ft)),
    three(["nav_vn_fps", "nav_ve_fps", "nav_vd_fps"], "ft/s", Navigation, "the follower's velocity as its INS/GPS knows it (NED; the track velocity)", |s| navigation(s, |n| n.velocity_ned_fps)),
    three(["nav_phi_rad", "nav_theta_rad", "nav_psi_rad"], "rad", Navigation, "the follower's attitude φ, θ, ψ as its INS/GPS knows it", |s| navigation(s, |n| attitude(&n.attitude))),
];
