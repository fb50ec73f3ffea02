//! How each stage is built from its own section, and the pairings across stages that only
//! the simulation makes: the estimator with the guidance law that flies on it, the target
//! model, the excitation's cap from the camera's field of view, the camera's mount.

use super::SimError;
use crate::estimation::airframe::{AirframeShape, AirframeTable};
use crate::estimation::instrument::{ExcitationInstrument, InstrumentSettings};
use crate::estimation::trim_alpha::AlphaSchedule;
use crate::estimation::{AirframeModel, Estimator, KalmanTracker, MeasurementHold, TargetTracker};
use crate::follower::aircraft::DRYDEN_SEED_SALT;
use crate::follower::{AircraftSetupError, Follower, FollowerConfig};
use crate::frames::{Mat3, Vec3};
use crate::guidance::command::{CommandInput, FormationCommand};
use crate::guidance::excitation::ViewBound;
use crate::guidance::law::GuidanceLaw;
use crate::guidance::signals::CommandKind;
use crate::scenario::check::InvalidValue;
use crate::scenario::{
    AirframeAlpha, EstimatorKind, GimbalCue, GimbalKind, GuidanceLawKind, Scenario, SensorMode,
    SizeFrom, SizeModel, TargetGusts, TargetModelKind, TargetMotion, TargetPath,
};
use crate::sensing::camera::load_target_mesh;
use crate::sensing::gimbal::{Gimbal, GimbalAngles};
use crate::sensing::{CameraConfig, SensorError};
use crate::sensing::{CaptureGeometry, FollowerPose, Sensor};
use crate::target_aircraft::{TARGET_DRYDEN_SEED_SALT, TargetAircraft};
use crate::world::aircraft::{Aircraft, AircraftParams};
use crate::world::atmosphere::{Atmosphere, AtmosphereSample, DrydenTurbulence};
use crate::world::target::{CarriedByAir, TargetModel, TargetMotionModel};
use crate::world::trajectory::{
    RANDOM_TRACK_SEED_SALT, TrackError, random_track, read_track, waypoint_track,
};
use std::path::Path;

/// With `estimator.size_from = "excitation"`, the instrument that reads the size from the
/// follower's own excitation (`estimation::instrument`), one sample per camera frame.
pub(super) fn excitation_instrument(scenario: &Scenario) -> Option<ExcitationInstrument> {
    let (e, x) = (&scenario.estimator, &scenario.excitation);
    if e.size_from != SizeFrom::Excitation {
        return None;
    }
    Some(ExcitationInstrument::new(InstrumentSettings {
        omega_rps: 2.0 * std::f64::consts::PI / x.period_s,
        q: e.instrument_q,
        sample_s: 1.0 / scenario.camera.rate_hz,
        settle_s: e.instrument_settle_s,
        block_s: e.instrument_block_periods * x.period_s,
        min_blocks: e.instrument_min_blocks as usize,
        direction_time_s: e.instrument_direction_periods * x.period_s,
    }))
}

/// The bound the field of view puts on the excitation with a camera
/// (`excitation.fov_fraction`; [`ViewBound`]): the commanded range and the tangent of the
/// half field of view the excitation's direction moves the target across.
pub(super) fn excitation_view_bound(scenario: &Scenario) -> Option<ViewBound> {
    let e = &scenario.excitation;
    if scenario.sensor.mode != SensorMode::Camera || e.fov_fraction <= 0.0 {
        return None;
    }
    let camera = &scenario.camera;
    let focal_px = camera.focal_length_px();
    let direction = Vec3::from(e.direction).normalize();
    // The tangent of the half field of view the direction moves the target across: vertical
    // for its down part, horizontal for its level part (whatever the heading), the tighter.
    let tan_half_vertical = f64::from(camera.height_px) * 0.5 / focal_px;
    let tan_half_horizontal = f64::from(camera.width_px) * 0.5 / focal_px;
    let vertical = direction.z.abs();
    let level = direction.x.hypot(direction.y);
    let tan_half_fov = [(vertical, tan_half_vertical), (level, tan_half_horizontal)]
        .iter()
        .filter(|(part, _)| *part > 1e-9)
        .map(|(part, tan_half)| tan_half / part)
        .fold(f64::INFINITY, f64::min);
    Some(ViewBound {
        fraction: e.fov_fraction,
        range_ft: scenario.guidance.command_length_ft(),
        tan_half_fov,
    })
}

/// The follower `[follower]` describes, flying in `[atmosphere]` with `[autopilot]` (the
/// turbulence stream of `run.air_seed`), realising the command of `[guidance]`'s law; and its initial state.
pub(super) fn follower_of(scenario: &Scenario) -> Result<(Follower, Vec<f64>), AircraftSetupError> {
    Follower::new(&FollowerConfig {
        follower: &scenario.follower,
        autopilot: &scenario.autopilot,
        atmosphere: &scenario.atmosphere,
        turbulence_seed: scenario.run.air_seed() ^ DRYDEN_SEED_SALT,
        command_kind: match scenario.guidance.law {
            GuidanceLawKind::Velocity => CommandKind::Velocity,
            GuidanceLawKind::Acceleration => CommandKind::Acceleration,
        },
    })
}

/// Where the guidance law's filters start (the seed starts them at the first measurement): a
/// continuous sensor's r*(0); with a camera, whose first frame restarts them, the slot the
/// guidance is to hold, R_c(0)/b̂(0) (the follower's `body_rates_rps` for a command in its
/// body frame), so that no truth enters the guidance.
pub(super) fn first_r(
    sensor: &Sensor,
    geometry: &CaptureGeometry,
    command: &FormationCommand,
    body_rates_rps: Vec3,
    b0_ft: f64,
) -> Vec3 {
    sensor
        .continuous_measurement(
            &geometry.sensed_relative_ned_ft(),
            &geometry.camera_from_ned(),
        )
        .unwrap_or_else(|| {
            let attitude = geometry.navigation.attitude;
            let input = CommandInput {
                attitude,
                body_rates_rps,
                track_ned: None,
            };
            let command_x = FormationCommand::initial_state(&attitude);
            command.command(&command_x, &input).0 / b0_ft
        })
}

/// The camera's pan/tilt gimbal, when the camera rides one.
pub(super) fn gimbal_of(scenario: &Scenario, target: &dyn TargetModel) -> Option<Gimbal> {
    let section = &scenario.camera.gimbal;
    let cue_ned = match section.cue {
        GimbalCue::None => None,
        GimbalCue::Bearing => Some(Vec3::from(section.cue_bearing_ned())),
        GimbalCue::Target => {
            Some(target.position_ned_ft(0.0) - Vec3::from(scenario.follower.initial_position_ft))
        }
    };
    (scenario.sensor.mode == SensorMode::Camera && section.kind != GimbalKind::None)
        .then(|| Gimbal::new(section, cue_ned))
}

/// The estimator `[estimator] kind` asks for, fed by a continuous sensor or a camera, with
/// the guidance law that flies on it (the seed's adaptive laws on the measurement hold, with
/// the Kalman filter beside them when it is logged; or the velocity law on a filter's
/// estimate), compensating for a follower that does not realise the command when
/// `compensate`; and the notes the law's design leaves for the run's log. A new estimator is
/// one module implementing [`TargetTracker`] and its arm here.
pub(super) fn estimation_stage(
    scenario: &Scenario,
    compensate: bool,
    continuous_sensor: bool,
) -> Result<(Estimator, GuidanceLaw, Vec<String>), SimError> {
    let e = &scenario.estimator;
    let g = &scenario.guidance;
    let airframe = airframe_model(scenario)?;
    let kalman = || -> Box<dyn TargetTracker> {
        let tracker = KalmanTracker::new(
            e,
            scenario.camera.focal_length_px(),
            g.b0_ft,
            (g.b_min_ft, g.b_max_ft),
        );
        Box::new(match airframe.clone() {
            Some(model) => tracker.with_airframe(model),
            None => tracker,
        })
    };
    Ok(match e.kind {
        EstimatorKind::Adaptive => {
            let (law, notes) = GuidanceLaw::adaptive(g, &scenario.acceleration, compensate)?;
            let hold = MeasurementHold::new(continuous_sensor, scenario.camera.compensate_delay);
            let beside = e.log_kalman.then(kalman);
            (Estimator::Adaptive { hold, beside }, law, notes)
        }
        EstimatorKind::Kalman => {
            let law = GuidanceLaw::on_estimate(g, compensate);
            (Estimator::OnFilter(kalman()), law, Vec::new())
        }
    })
}

/// The airframe size model of `estimator.size_model = "airframe"`: the table and the shape
/// of the scenario's target mesh (`camera.mesh`), each over the mesh's own largest dimension
/// (b's definition), so the model knows the shape up to scale and not the target's true
/// size; `None` with the other size models.
fn airframe_model(scenario: &Scenario) -> Result<Option<AirframeModel>, SimError> {
    if scenario.estimator.size_model != SizeModel::Airframe {
        return Ok(None);
    }
    let mesh =
        load_target_mesh(&CameraConfig::of(scenario)).map_err(|e| SimError::Sensor(Box::new(e)))?;
    let shape_size_ft = mesh.max_dimension_ft();
    let table = AirframeTable::of_mesh(&mesh.vertices_ft, shape_size_ft).ok_or_else(|| {
        SimError::Sensor(Box::new(SensorError::MeshWithoutExtent(
            scenario.camera.mesh.clone().into(),
        )))
    })?;
    let shape = AirframeShape::of_mesh(
        &mesh.vertices_ft,
        &mesh.triangles,
        shape_size_ft,
        scenario.camera.bearing_point,
    );
    let model = AirframeModel::new(&scenario.estimator, table, shape);
    Ok(Some(match scenario.estimator.airframe_angle_of_attack {
        AirframeAlpha::Zero => model,
        AirframeAlpha::Trim => model.with_alpha(target_alpha_schedule(scenario)?),
    }))
}

/// The trim α over airspeed of the target's aircraft data (`target.aircraft`, the type known
/// up to scale) in the steady air of `[atmosphere]` at the follower's own starting point: the
/// air it measures, not the target's, which it does not know. (The steady wind is the
/// scenario's, what the follower's air data give on average: an assumption, stated in
/// `estimation::trim_alpha`.)
fn target_alpha_schedule(scenario: &Scenario) -> Result<AlphaSchedule, SimError> {
    let params = AircraftParams::from_scenario_path(&scenario.target.aircraft)
        .map_err(AircraftSetupError::from)?;
    let aircraft = Aircraft::new(params).map_err(AircraftSetupError::from)?;
    let start = Vec3::from(scenario.follower.initial_position_ft);
    // As the aircraft's own trims: the steady wind and density, no drag or moment bias.
    let air = AtmosphereSample {
        drag_factor: 1.0,
        moment_bias_body_lbf_ft: Vec3::zeros(),
        ..Atmosphere::new(&scenario.atmosphere, 0)
            .map_err(AircraftSetupError::from)?
            .steady_sample(&start)
    };
    AlphaSchedule::of_aircraft(&aircraft, &air, &start).ok_or_else(|| {
        SimError::Follower(AircraftSetupError::Invalid(InvalidValue {
            key: "target.aircraft".to_string(),
            value: scenario.target.aircraft.clone(),
            allowed: "an airframe that trims in level flight at 20-200 ft/s (estimator.airframe_angle_of_attack = \"trim\")".to_string(),
        }))
    })
}

/// The target `[target]` describes, flying at least the run's duration: its motion (a
/// closed-form one, or a trajectory source, the random one on its own stream of `run.seed`),
/// over the ground or carried by the air mass (`target.path`), or an aircraft flying that
/// motion in `[atmosphere]` (its own turbulence stream, or the follower's).
pub(super) fn target_of(scenario: &Scenario) -> Result<Box<dyn TargetModel>, SimError> {
    let motion = match scenario.target.path {
        TargetPath::OverGround => motion_of(scenario)?,
        TargetPath::InAirMass => Box::new(carried_by_air(scenario, motion_of(scenario)?)),
    };
    Ok(match scenario.target.model {
        TargetModelKind::Kinematic => motion,
        TargetModelKind::Aircraft => Box::new(TargetAircraft::new(
            &scenario.target,
            &scenario.atmosphere,
            target_turbulence_seed(scenario),
            motion,
        )?),
    })
}

/// `motion` flown through the air mass: carried by the steady wind, and a target without an
/// airframe by the follower's gusts as well when it shares its air (`target.gusts`).
fn carried_by_air(scenario: &Scenario, motion: Box<dyn TargetModel>) -> CarriedByAir {
    let (target, air) = (&scenario.target, &scenario.atmosphere);
    let tracer = target.model == TargetModelKind::Kinematic && target.gusts == TargetGusts::Shared;
    let gusts = tracer.then(|| {
        let dryden = DrydenTurbulence::new(air.turbulence, target_turbulence_seed(scenario));
        (dryden, air.origin_altitude_ft)
    });
    CarriedByAir::new(motion, air.wind_ned_fps, gusts)
}

/// The seed of the target's Dryden stream: its own, or the follower's when the two
/// share the air (`target.gusts`).
fn target_turbulence_seed(scenario: &Scenario) -> u64 {
    match scenario.target.gusts {
        TargetGusts::Independent => scenario.run.seed ^ TARGET_DRYDEN_SEED_SALT,
        TargetGusts::Shared => scenario.run.air_seed() ^ DRYDEN_SEED_SALT,
    }
}

/// The path `[target]` describes.
fn motion_of(scenario: &Scenario) -> Result<Box<dyn TargetModel>, TrackError> {
    let target = &scenario.target;
    let start = Vec3::from(target.initial_position_ft);
    let duration_s = scenario.run.duration_s;
    Ok(match target.motion {
        TargetMotion::SeedProfile => Box::new(TargetMotionModel::seed_profile(start)),
        TargetMotion::Straight => {
            let velocity = Vec3::from(target.straight_velocity_fps);
            Box::new(TargetMotionModel::straight(start, velocity))
        }
        TargetMotion::Waypoints => Box::new(waypoint_track(target, duration_s)),
        TargetMotion::Random => {
            let seed = scenario.run.seed ^ RANDOM_TRACK_SEED_SALT;
            Box::new(random_track(target, seed, duration_s))
        }
        TargetMotion::Csv => Box::new(read_track(Path::new(&target.track), start, duration_s)?),
    })
}

/// L_CB of a camera on its fixed mount, or on a gimbal (its angles in `gimbal_x`) over it.
pub(super) fn mounted_camera(mount: &Mat3, gimbal: Option<&Gimbal>, gimbal_x: &[f64]) -> Mat3 {
    match gimbal {
        Some(_) => GimbalAngles::of(gimbal_x).camera_from_body() * mount,
        None => *mount,
    }
}

/// Where follower and target are at `t_s` for a follower slice.
pub(super) fn capture_geometry(
    target: &dyn TargetModel,
    follower: &Follower,
    follower_x: &[f64],
    t_s: f64,
    camera_from_body: &Mat3,
) -> CaptureGeometry {
    let pose = FollowerPose {
        position_ned_ft: follower.position_ned_ft(follower_x),
        velocity_ned_fps: follower.track_ned_fps(follower_x),
        attitude: follower.attitude(follower_x),
        camera_from_body: *camera_from_body,
    };
    CaptureGeometry::exact(
        target.position_ned_ft(t_s) - pose.position_ned_ft,
        target.state(t_s).attitude,
        pose,
    )
}
