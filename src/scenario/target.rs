//! `[target]`: the unknown aircraft being tracked and the path it flies: the seed's profile or
//! a straight line in closed form (`world::target`), or a trajectory source
//! (`world::trajectory`; docs/equations.md, Trajectory sources for the target): waypoints,
//! seeded random manoeuvres, or a recorded track played back from a CSV file.

use super::check::{self, Check};
use serde::{Deserialize, Serialize};

/// How the target moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TargetMotion {
    /// The seed's piecewise velocity profile (Section 4.4).
    SeedProfile,
    /// Constant velocity `straight_velocity_fps`.
    Straight,
    /// Through `[[target.waypoints]]` in order, with coordinated turns at `bank_limit_deg`,
    /// then straight and level on.
    Waypoints,
    /// Seeded manoeuvres drawn within `[target.random]`.
    Random,
    /// Playback of the recorded track `track`.
    Csv,
}

/// One waypoint of `motion = "waypoints"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Waypoint {
    /// Where, NED, ft.
    pub position_ft: [f64; 3],
    /// Airspeed flown on the leg to this waypoint, ft/s: the target changes speed toward it
    /// from the leg's start, at most `target.accel_max_fps2`.
    pub speed_fps: f64,
}

/// `[target.random]`: the envelope the seeded manoeuvres of `motion = "random"` are drawn in.
/// The defaults are a small aircraft's gentle manoeuvres: the seed's target flies 35-60 ft/s
/// and climbs and descends at up to 6 ft/s (Section 4.4); 30° is the bank of a light
/// aircraft's ordinary turns (steeper is a steep turn); segments of 5-15 s are the seed's pieces' 10-30 s
/// halved, for more manoeuvres per run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RandomManoeuvreSection {
    /// Largest bank a segment draws, deg, in [0, 60].
    pub bank_max_deg: f64,
    /// Largest climb or descent rate a segment draws, ft/s, in [0, 100] and at most half
    /// `speed_min_fps` (a flight path within 30°).
    pub climb_rate_max_fps: f64,
    /// Slowest airspeed a segment draws, ft/s, in [1, 1000].
    pub speed_min_fps: f64,
    /// Fastest airspeed a segment draws, ft/s, in [speed_min_fps, 1000].
    pub speed_max_fps: f64,
    /// Shortest segment, s, in [0.1, 10⁴].
    pub segment_min_s: f64,
    /// Longest segment, s, in [segment_min_s, 10⁴].
    pub segment_max_s: f64,
    /// Heading at t = 0, deg from north (the target starts level at the middle of its speed
    /// range), in [-360, 360]. Default north, the seed's start.
    pub initial_heading_deg: f64,
}

impl Default for RandomManoeuvreSection {
    fn default() -> Self {
        Self {
            bank_max_deg: 30.0,
            climb_rate_max_fps: 5.0,
            speed_min_fps: 40.0,
            speed_max_fps: 60.0,
            segment_min_s: 5.0,
            segment_max_s: 15.0,
            initial_heading_deg: 0.0,
        }
    }
}

impl RandomManoeuvreSection {
    fn validate(&self) -> Check {
        check::in_closed("target.random.bank_max_deg", self.bank_max_deg, 0.0, 60.0)?;
        check::in_closed(
            "target.random.speed_min_fps",
            self.speed_min_fps,
            1.0,
            1000.0,
        )?;
        let (lo, hi) = (self.speed_min_fps, 1000.0);
        check::in_closed("target.random.speed_max_fps", self.speed_max_fps, lo, hi)?;
        let climb_max = (0.5 * self.speed_min_fps).min(100.0);
        let key = "target.random.climb_rate_max_fps";
        check::in_closed(key, self.climb_rate_max_fps, 0.0, climb_max)?;
        check::in_closed("target.random.segment_min_s", self.segment_min_s, 0.1, 1e4)?;
        let (lo, hi) = (self.segment_min_s, 1e4);
        check::in_closed("target.random.segment_max_s", self.segment_max_s, lo, hi)?;
        let key = "target.random.initial_heading_deg";
        check::in_closed(key, self.initial_heading_deg, -360.0, 360.0)
    }
}

/// What moves the target along its motion (`target.model`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TargetModelKind {
    /// The motion itself: position, velocity and acceleration, the attitude along the
    /// velocity with the coordinated-turn bank (the seed's target).
    Kinematic,
    /// A second 6-DOF aircraft (`target.aircraft`) flown by its own Chapter 7 flight
    /// controller (`[target.autopilot]`) along the motion, which is then its reference
    /// (docs/equations.md, The target as an aircraft).
    Aircraft,
}

/// Which gusts the target flies through (`target.gusts`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TargetGusts {
    /// A target aircraft's airframe feels a Dryden stream of its own, independent of the
    /// follower's; a kinematic target, which has no airframe, none.
    Independent,
    /// The follower's stream (in a group, the first follower's: `run.seed`'s): the same
    /// white noise, shaped by the Dryden filters at the target's own airspeed and altitude.
    /// Two aircraft tens of feet apart fly through the same air: the gusts' scale lengths are
    /// hundreds of feet. A target aircraft's airframe feels it; a kinematic target in the air
    /// mass is carried by it (docs/equations.md, The target in the air mass).
    Shared,
}

/// What the target's motion is flown relative to (`target.path`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TargetPath {
    /// The ground: the motion is a path over the ground, held against the wind (the seed's).
    OverGround,
    /// The air mass: the motion drifts with the steady wind's north and east components, so
    /// its horizontal velocities are flown through the air, as by a pilot holding a schedule
    /// of airspeed and heading (and of height over the ground). A kinematic target drifts
    /// with the follower's gusts as well when it shares them (`target.gusts = "shared"`); a
    /// target aircraft flies the drifting motion as its reference, and gusts act on its
    /// airframe as on any aircraft (docs/equations.md, The target in the air mass).
    InAirMass,
}

/// `[target]`: the unknown aircraft being tracked.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TargetSection {
    /// Motion model.
    pub motion: TargetMotion,
    /// R_T(0) in NED, ft. A CSV track is moved so that its first row is here.
    pub initial_position_ft: [f64; 3],
    /// Velocity for `motion = "straight"`, NED, ft/s.
    pub straight_velocity_fps: [f64; 3],
    /// The target's true maximal size b, ft (its wingspan): unknown to the guidance.
    pub size_ft: f64,
    /// Waypoints: the bank of the coordinated turns, deg, in [1, 60]. Default 30°, a light
    /// aircraft's ordinary turn (turn radius V²/(g tan φ), 134 ft at 50 ft/s).
    pub bank_limit_deg: f64,
    /// Waypoints: the fastest climb or descent, ft/s, in [0, 100] and at most half of every
    /// waypoint's speed. Default 5 ft/s, the seed target's steepest (6 ft/s) rounded down.
    pub climb_rate_max_fps: f64,
    /// Waypoints and random: the largest along-track acceleration, ft/s², in (0, 32.174].
    /// Default 3.2 ft/s² (0.1 g), the seed target's largest per axis (Section 4.4).
    pub accel_max_fps2: f64,
    /// Waypoints and random: the largest vertical acceleration, ft/s², in (0, 32.174].
    /// Default 3.2 ft/s² (0.1 g), as `accel_max_fps2`: gentle, for a passenger-free target.
    pub vertical_accel_max_fps2: f64,
    /// Waypoints and random: the largest roll rate, deg/s, in (0, 360]. Default 30°/s: a
    /// light aircraft rolls at 60-90°/s at full aileron; half of that is a gentle entry,
    /// which reaches a 30° bank in about a second.
    pub roll_rate_max_dps: f64,
    /// Waypoints and random: the time constant of the target's speed, climb-rate and heading
    /// responses to their commands inside the limits above, s, in [0.1, 60]; its along-track
    /// and vertical accelerations and its bank follow four times faster, which damps each
    /// response critically. Default 2 s: a small aircraft settles on a new speed or course
    /// in several seconds.
    pub response_time_s: f64,
    /// `motion = "waypoints"`: the waypoints, flown in order from `initial_position_ft`
    /// (heading for the first, at its speed, level).
    pub waypoints: Vec<Waypoint>,
    /// `motion = "random"`: the envelope of the manoeuvres.
    pub random: RandomManoeuvreSection,
    /// `motion = "csv"`: the recorded track, a CSV file (columns t_s, n_ft, e_ft, d_ft;
    /// optionally vn_fps, ve_fps, vd_fps and phi_deg, theta_deg, psi_deg; docs/equations.md,
    /// Trajectory sources for the target). A relative path is looked up from the scenario
    /// file's folder, then from this program's own folder (whose `assets/tracks/` holds the
    /// shipped tracks).
    pub track: String,
    /// What moves the target: `"kinematic"` (default, the seed's) or `"aircraft"`. The
    /// aircraft starts trimmed in straight and level flight at the motion's horizontal speed
    /// through the air at t = 0 (35-100 ft/s) on its course; a motion that starts climbing is
    /// joined by the track feedback.
    pub model: TargetModelKind,
    /// The target aircraft's data file (`model = "aircraft"`), in the schema of
    /// `follower.aircraft` and looked up like it; default the shipped
    /// `assets/aircraft/follower.toml` (the seed's airframe).
    pub aircraft: String,
    /// k of the target aircraft's command V_c = V_ref + k (R_ref - R), 1/s, in [0, 2]
    /// (0: the motion's velocity alone, which lets the track drift). Choice: 0.3. The
    /// aircraft's velocity follows V_c with a lag τ of 1-2 s, so the track error obeys
    /// τ ë + ė + k e ≈ 0, damped by 1/(2√(kτ)): 0.65-0.9 at 0.3. Measured on the seed's
    /// profile in still air (distance from the reference, RMS / largest): k = 0 15.1 / 22.4
    /// ft, 0.1 6.0 / 18.5, 0.3 4.8 / 18.5, 0.5 4.6 / 18.5, 0.8 6.6 / 18.2, 1.2 oscillates
    /// (48 / 238 ft); 0.3 keeps four times the margin to that.
    pub track_gain_per_s: f64,
    /// The target's turbulence (a target aircraft's, or a kinematic target's in the air mass;
    /// with `[atmosphere]` turbulence): `"independent"` (default) or `"shared"` with the
    /// follower (see [`TargetGusts`]).
    pub gusts: TargetGusts,
    /// What the target flies its motion relative to: `"over_ground"` (default) or
    /// `"in_air_mass"` (see [`TargetPath`]).
    pub path: TargetPath,
    /// The target aircraft's flight controller (`model = "aircraft"`): the keys of
    /// `[autopilot]`, with their defaults (not the follower's choices in a scenario).
    pub autopilot: super::AutopilotSection,
}

impl Default for TargetSection {
    fn default() -> Self {
        Self {
            motion: TargetMotion::SeedProfile,
            initial_position_ft: [200.0, 50.0, 30.0],
            straight_velocity_fps: [50.0, 0.0, 0.0],
            size_ft: 8.0,
            bank_limit_deg: 30.0,
            climb_rate_max_fps: 5.0,
            accel_max_fps2: 3.2,
            vertical_accel_max_fps2: 3.2,
            roll_rate_max_dps: 30.0,
            response_time_s: 2.0,
            waypoints: Vec::new(),
            random: RandomManoeuvreSection::default(),
            track: String::new(),
            model: TargetModelKind::Kinematic,
            aircraft: super::DEFAULT_AIRCRAFT.to_string(),
            track_gain_per_s: 0.3,
            gusts: TargetGusts::Independent,
            path: TargetPath::OverGround,
            autopilot: super::AutopilotSection::default(),
        }
    }
}

/// The largest along-track or vertical acceleration a target may be given, ft/s² (1 g).
const ACCEL_LIMIT_FPS2: f64 = crate::frames::GRAVITY_FPS2;
/// Most waypoints a scenario may list.
const MAX_WAYPOINTS: usize = 10_000;

impl TargetSection {
    /// Checks every value and the keys the chosen motion needs.
    pub(super) fn validate(&self) -> Check {
        check::position_ft("target.initial_position_ft", &self.initial_position_ft)?;
        check::finite_vec("target.straight_velocity_fps", &self.straight_velocity_fps)?;
        check::in_closed("target.size_ft", self.size_ft, 0.01, 1000.0)?;
        check::in_closed("target.bank_limit_deg", self.bank_limit_deg, 1.0, 60.0)?;
        check::in_closed(
            "target.climb_rate_max_fps",
            self.climb_rate_max_fps,
            0.0,
            100.0,
        )?;
        for (key, value, hi) in [
            (
                "target.accel_max_fps2",
                self.accel_max_fps2,
                ACCEL_LIMIT_FPS2,
            ),
            (
                "target.vertical_accel_max_fps2",
                self.vertical_accel_max_fps2,
                ACCEL_LIMIT_FPS2,
            ),
            ("target.roll_rate_max_dps", self.roll_rate_max_dps, 360.0),
        ] {
            check::require(value > 0.0 && value <= hi, key, value, format!("(0, {hi}]"))?;
        }
        check::in_closed("target.response_time_s", self.response_time_s, 0.1, 60.0)?;
        self.random.validate()?;
        self.validate_aircraft()?;
        // Every waypoint listed is checked whatever the motion; only "waypoints" needs some.
        self.validate_waypoints()?;
        match self.motion {
            TargetMotion::Waypoints => check::require(
                (1..=MAX_WAYPOINTS).contains(&self.waypoints.len()),
                "target.waypoints",
                format!("{} waypoints", self.waypoints.len()),
                format!(
                    "1 to {MAX_WAYPOINTS} [[target.waypoints]] with target.motion = \"waypoints\""
                ),
            ),
            TargetMotion::Csv => check::require(
                !self.track.is_empty(),
                "target.track",
                "\"\"",
                "the path of a CSV track with target.motion = \"csv\"",
            ),
            TargetMotion::SeedProfile | TargetMotion::Straight | TargetMotion::Random => Ok(()),
        }
    }

    fn validate_aircraft(&self) -> Check {
        check::require(
            !self.aircraft.is_empty(),
            "target.aircraft",
            "\"\"",
            "the path of an aircraft data file",
        )?;
        check::in_closed("target.track_gain_per_s", self.track_gain_per_s, 0.0, 2.0)?;
        check::require(
            self.gusts == TargetGusts::Independent
                || self.model == TargetModelKind::Aircraft
                || self.path == TargetPath::InAirMass,
            "target.gusts",
            "\"shared\"",
            "\"independent\" unless target.model = \"aircraft\" or target.path = \"in_air_mass\"",
        )?;
        self.autopilot.validate().map_err(|mut invalid| {
            invalid.key = format!("target.{}", invalid.key);
            invalid
        })
    }

    fn validate_waypoints(&self) -> Check {
        for (i, waypoint) in self.waypoints.iter().enumerate() {
            check::position_ft(
                &format!("target.waypoints[{i}].position_ft"),
                &waypoint.position_ft,
            )?;
            let key = format!("target.waypoints[{i}].speed_fps");
            let slowest = (2.0 * self.climb_rate_max_fps).max(1.0);
            check::require(
                waypoint.speed_fps.is_finite() && (slowest..=1000.0).contains(&waypoint.speed_fps),
                &key,
                waypoint.speed_fps,
                format!(
                    "[{slowest}, 1000] (at least twice target.climb_rate_max_fps = {}: a \
                     flight path within 30°)",
                    self.climb_rate_max_fps
                ),
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn waypoints(speed_fps: f64) -> TargetSection {
        TargetSection {
            motion: TargetMotion::Waypoints,
            waypoints: vec![Waypoint {
                position_ft: [500.0, 0.0, 0.0],
                speed_fps,
            }],
            ..TargetSection::default()
        }
    }

    #[test]
    fn defaults_are_valid() {
        assert_eq!(TargetSection::default().validate(), Ok(()));
        assert_eq!(waypoints(50.0).validate(), Ok(()));
    }

    /// A motion that needs keys of its own says which.
    #[test]
    fn motion_needs_its_keys() {
        let none = TargetSection {
            motion: TargetMotion::Waypoints,
            ..TargetSection::default()
        };
        assert_eq!(none.validate().unwrap_err().key, "target.waypoints");
        let csv = TargetSection {
            motion: TargetMotion::Csv,
            ..TargetSection::default()
        };
        assert_eq!(csv.validate().unwrap_err().key, "target.track");
    }

    /// A waypoint slower than twice the climb limit is refused by index.
    #[test]
    fn slow_waypoint_is_named() {
        let err = waypoints(8.0).validate().unwrap_err();
        assert_eq!(err.key, "target.waypoints[0].speed_fps");
        assert!(err.allowed.contains("[10, 1000]"), "{err}");
    }

    /// Waypoints and the random envelope are written into the resolved scenario, which
    /// reads back the same.
    #[test]
    fn resolved_waypoints_round_trip() {
        let text = "[target]\nmotion = \"waypoints\"\ntrack = \"t.csv\"\n\
                    [[target.waypoints]]\nposition_ft = [500.0, 10.0, -5.0]\nspeed_fps = 45.0\n\
                    [[target.waypoints]]\nposition_ft = [0.0, 900.0, 0.0]\nspeed_fps = 55.0\n\
                    [target.random]\nbank_max_deg = 20.0\n";
        let path = std::path::Path::new("w.toml");
        let s = super::super::Scenario::from_toml_str(text, path, &[]).expect("valid");
        assert_eq!(s.target.waypoints.len(), 2);
        assert_eq!(s.target.random.bank_max_deg, 20.0);
        let again = super::super::Scenario::from_toml_str(&s.to_toml_string(), path, &[]);
        assert_eq!(again.expect("resolved is valid"), s);
    }

    #[test]
    fn random_envelope_is_ordered() {
        let mut s = TargetSection::default();
        s.random.speed_max_fps = 30.0;
        assert_eq!(s.validate().unwrap_err().key, "target.random.speed_max_fps");
        let mut s = TargetSection::default();
        s.random.segment_max_s = 1.0;
        assert_eq!(s.validate().unwrap_err().key, "target.random.segment_max_s");
        let mut s = TargetSection::default();
        s.random.climb_rate_max_fps = 25.0;
        assert_eq!(
            s.validate().unwrap_err().key,
            "target.random.climb_rate_max_fps"
        );
    }
}
