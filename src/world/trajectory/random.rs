//! `target.motion = "random"` (docs/equations.md, Trajectory sources for the target): seeded
//! manoeuvres within the envelope of `[target.random]`. The run is cut into segments of
//! durations drawn uniformly in [segment_min_s, segment_max_s]; each segment draws a turn
//! (left, straight or right, each a third of the time; a turn's bank uniform in
//! (0, bank_max_deg]), a climb rate uniform in ±climb_rate_max_fps and an airspeed uniform
//! in [speed_min_fps, speed_max_fps], and the point mass flies them inside the `[target]`
//! rate limits, so the track's velocity and acceleration stay continuous.

use super::point_mass::{Command, Limits, PointMass, fly};
use super::sampled::SampledTrack;
use crate::frames::Vec3;
use crate::scenario::{RandomManoeuvreSection, TargetSection};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Mixed into `[run] seed` for the random target's own stream, so that it is not the
/// turbulence's or the sensor's, and each run seed flies a new path ("tgtpath" in ASCII).
pub const RANDOM_TRACK_SEED_SALT: u64 = 0x0074_6774_7061_7468;

/// Draws the segments' commands.
struct Manoeuvres {
    rng: ChaCha8Rng,
    envelope: RandomManoeuvreSection,
    /// When the current segment ends, s.
    segment_end_s: f64,
    command: Command,
}

impl Manoeuvres {
    /// The command at `t_s`, drawing a new segment when the current one has ended.
    fn command(&mut self, t_s: f64) -> Command {
        while t_s >= self.segment_end_s {
            self.draw_segment();
        }
        self.command
    }

    /// Five draws, always in this order, whatever they give: duration, turn direction,
    /// bank, climb rate and speed.
    fn draw_segment(&mut self) {
        let e = &self.envelope;
        let rng = &mut self.rng;
        self.segment_end_s += rng.random_range(e.segment_min_s..=e.segment_max_s);
        let direction = f64::from(rng.random_range(-1i8..=1));
        let bank_rad = direction * rng.random_range(0.0..=e.bank_max_deg).to_radians();
        let climb = e.climb_rate_max_fps;
        let climb_rate_fps = rng.random_range(-climb..=climb);
        let speed_fps = rng.random_range(e.speed_min_fps..=e.speed_max_fps);
        self.command = Command {
            speed_fps,
            bank_rad,
            climb_rate_fps,
        };
    }
}

/// The track `[target]` describes with `motion = "random"`, flown to at least `duration_s`
/// on the stream seeded by `seed` (the run's seed with [`RANDOM_TRACK_SEED_SALT`] mixed in).
/// The target starts level at the middle of the speed range, on `initial_heading_deg`.
pub fn random_track(target: &TargetSection, seed: u64, duration_s: f64) -> SampledTrack {
    let envelope = target.random.clone();
    let limits = Limits::of(target, envelope.bank_max_deg, envelope.climb_rate_max_fps);
    let speed_fps = 0.5 * (envelope.speed_min_fps + envelope.speed_max_fps);
    let start = PointMass::level(
        Vec3::from(target.initial_position_ft),
        speed_fps,
        envelope.initial_heading_deg.to_radians(),
    );
    let mut manoeuvres = Manoeuvres {
        rng: ChaCha8Rng::seed_from_u64(seed),
        envelope,
        segment_end_s: 0.0,
        command: Command {
            speed_fps,
            bank_rad: 0.0,
            climb_rate_fps: 0.0,
        },
    };
    fly(start, &limits, duration_s, |t_s, _| manoeuvres.command(t_s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::target::TargetModel;

    /// The same seed flies the same path; another seed another.
    #[test]
    fn seeded() {
        let target = TargetSection::default();
        let a = random_track(&target, 1, 60.0);
        let b = random_track(&target, 1, 60.0);
        let c = random_track(&target, 2, 60.0);
        assert_eq!(a, b);
        let apart = (a.state(60.0).position_ned_ft - c.state(60.0).position_ned_ft).norm();
        assert!(apart > 50.0, "{apart}");
    }

    /// With a zero-width envelope the target flies straight and level at the one speed.
    #[test]
    fn zero_envelope_is_straight() {
        let mut target = TargetSection::default();
        target.random.bank_max_deg = 0.0;
        target.random.climb_rate_max_fps = 0.0;
        target.random.speed_min_fps = 45.0;
        target.random.speed_max_fps = 45.0;
        target.random.initial_heading_deg = 90.0;
        let track = random_track(&target, 7, 30.0);
        let moved = track.state(30.0).position_ned_ft - Vec3::from(target.initial_position_ft);
        assert!(
            (moved - Vec3::new(0.0, 45.0 * 30.0, 0.0)).norm() < 1e-6,
            "{moved:?}"
        );
    }
}
