//! Target motion: the seed's piecewise velocity profile (Section 4.4; docs/equations.md, The
//! relative motion and the seed's scenario) integrated in closed form, or straight flight; and
//! the target's attitude for rendering.

use crate::frames::{EulerAngles, Vec3, attitude_along_velocity, coordinated_turn_bank_rad};
use crate::scenario::{TargetMotion, TargetSection};
use crate::world::atmosphere::DrydenTurbulence;
use std::f64::consts::PI;

/// One piece of a velocity component, active from `start_s` until the next piece's start.
/// Its value at τ = t - start_s is `offset + slope τ + amplitude cos(ω τ)`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Piece {
    start_s: f64,
    offset: f64,
    slope: f64,
    amplitude: f64,
    omega_rps: f64,
}

impl Piece {
    const fn constant(start_s: f64, value: f64) -> Self {
        Self {
            start_s,
            offset: value,
            slope: 0.0,
            amplitude: 0.0,
            omega_rps: 0.0,
        }
    }

    const fn linear(start_s: f64, value: f64, slope: f64) -> Self {
        Self {
            start_s,
            offset: value,
            slope,
            amplitude: 0.0,
            omega_rps: 0.0,
        }
    }

    /// `scale (1 + sign cos(ω τ))`.
    const fn raised_cosine(start_s: f64, scale: f64, sign: f64, omega_rps: f64) -> Self {
        Self {
            start_s,
            offset: scale,
            slope: 0.0,
            amplitude: scale * sign,
            omega_rps,
        }
    }

    fn value(&self, tau: f64) -> f64 {
        self.offset + self.slope * tau + self.amplitude * (self.omega_rps * tau).cos()
    }

    fn derivative(&self, tau: f64) -> f64 {
        self.slope - self.amplitude * self.omega_rps * (self.omega_rps * tau).sin()
    }

    /// ∫_0^τ value.
    fn integral(&self, tau: f64) -> f64 {
        let oscillating = if self.omega_rps == 0.0 {
            self.amplitude * tau
        } else {
            self.amplitude * (self.omega_rps * tau).sin() / self.omega_rps
        };
        self.offset * tau + 0.5 * self.slope * tau * tau + oscillating
    }
}

/// A velocity component as consecutive pieces; the first starts at t = 0.
#[derive(Debug, Clone, PartialEq)]
struct PiecewiseProfile {
    pieces: Vec<Piece>,
    /// ∫_0^{start_i} of the profile, one per piece.
    integral_at_start: Vec<f64>,
}

impl PiecewiseProfile {
    fn new(pieces: Vec<Piece>) -> Self {
        let mut integral_at_start = Vec::with_capacity(pieces.len());
        let mut total = 0.0;
        for (i, piece) in pieces.iter().enumerate() {
            integral_at_start.push(total);
            if let Some(next) = pieces.get(i + 1) {
                total += piece.integral(next.start_s - piece.start_s);
            }
        }
        Self {
            pieces,
            integral_at_start,
        }
    }

    /// Index of the piece active at t (a piece covers (start, next start]; t ≤ 0 is the first).
    fn index(&self, t_s: f64) -> usize {
        self.pieces
            .iter()
            .rposition(|p| p.start_s < t_s)
            .unwrap_or(0)
    }

    fn value(&self, t_s: f64) -> f64 {
        let i = self.index(t_s);
        self.pieces[i].value(t_s - self.pieces[i].start_s)
    }

    fn derivative(&self, t_s: f64) -> f64 {
        let i = self.index(t_s);
        self.pieces[i].derivative(t_s - self.pieces[i].start_s)
    }

    fn integral(&self, t_s: f64) -> f64 {
        let i = self.index(t_s);
        self.integral_at_start[i] + self.pieces[i].integral(t_s - self.pieces[i].start_s)
    }
}

/// The seed's profile for V_Tx, V_Ty, V_Tz in ft/s (Section 4.4; the seed's "(36,50]", a
/// typo, read as (38,50] so that the pieces join).
fn seed_profile() -> [PiecewiseProfile; 3] {
    let w30 = PI / 30.0;
    let w15 = PI / 15.0;
    let x = PiecewiseProfile::new(vec![
        Piece::constant(0.0, 50.0),
        Piece::raised_cosine(3.0, 25.0, 1.0, w30),
        Piece::constant(33.0, 0.0),
        Piece::raised_cosine(43.0, 30.0, -1.0, w30),
        Piece::linear(73.0, 60.0, -1.0),
        Piece::raised_cosine(83.0, 25.0, 1.0, w30),
        Piece::constant(113.0, 0.0),
    ]);
    let y = PiecewiseProfile::new(vec![
        Piece::constant(0.0, 0.0),
        Piece::raised_cosine(3.0, 25.0, -1.0, w30),
        Piece::linear(33.0, 50.0, 1.0),
        Piece::raised_cosine(43.0, 30.0, 1.0, w30),
        Piece::constant(73.0, 0.0),
        Piece::raised_cosine(83.0, -25.0, -1.0, w30),
        Piece::constant(113.0, -50.0),
    ]);
    let z = PiecewiseProfile::new(vec![
        Piece::constant(0.0, 0.0),
        Piece::raised_cosine(8.0, -3.0, -1.0, w15),
        Piece::constant(38.0, 0.0),
        Piece::raised_cosine(50.0, 3.0, -1.0, w15),
        Piece::constant(80.0, 0.0),
        Piece::raised_cosine(90.0, -3.0, -1.0, w15),
        Piece::constant(120.0, 0.0),
    ]);
    [x, y, z]
}

/// The target's kinematic state at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetState {
    /// R_T, NED, ft.
    pub position_ned_ft: Vec3,
    /// V_T, NED, ft/s.
    pub velocity_ned_fps: Vec3,
    /// a_T, NED, ft/s².
    pub accel_ned_fps2: Vec3,
    /// Attitude: nose along V_T, coordinated-turn bank.
    pub attitude: EulerAngles,
}

/// What a target with flight dynamics of its own reports beside its [`TargetState`] (for
/// telemetry): its air data and the reference it flies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetFlight {
    /// Airspeed V, ft/s.
    pub airspeed_fps: f64,
    /// Angle of attack α, rad.
    pub alpha_rad: f64,
    /// Sideslip β, rad.
    pub beta_rad: f64,
    /// Where its reference motion is, R_ref, NED, ft.
    pub reference_ned_ft: Vec3,
}

/// A target whose own state turned non-finite in a step; `what` names the state
/// ("target aircraft: body velocity, ft/s (w) is NaN").
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{what}")]
pub struct TargetDiverged {
    /// The element and its value.
    pub what: String,
}

/// The target as the simulation sees it: where it is and how it is oriented at any instant
/// of the step being integrated. A kinematic profile ([`TargetMotionModel`]) and a target with
/// dynamics of its own both implement it; a new one is one module implementing it plus its
/// arm in `Simulation::new`'s match on the `[target]` section.
pub trait TargetModel: std::fmt::Debug + Send {
    /// Advances the target's own dynamics over [t_s, t_s + dt_s], before the follower's step;
    /// an error when its state turns non-finite. A closed-form motion has nothing to do
    /// (the default).
    fn advance(&mut self, _t_s: f64, _dt_s: f64) -> Result<(), TargetDiverged> {
        Ok(())
    }

    /// The state at `t_s`, anywhere up to the end of the last step advanced.
    fn state(&self, t_s: f64) -> TargetState;

    /// Air data and reference of a target flown as an aircraft at `t_s`; `None` (the default)
    /// for a target without flight dynamics.
    fn flight(&self, _t_s: f64) -> Option<TargetFlight> {
        None
    }

    /// R_T(t), NED, ft.
    fn position_ned_ft(&self, t_s: f64) -> Vec3 {
        self.state(t_s).position_ned_ft
    }
}

/// The target's motion: position, velocity and acceleration as closed-form functions of time.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetMotionModel {
    initial_position_ned_ft: Vec3,
    kind: MotionKind,
}

#[derive(Debug, Clone, PartialEq)]
enum MotionKind {
    Profile(Box<[PiecewiseProfile; 3]>),
    Straight(Vec3),
}

impl TargetMotionModel {
    /// The seed's profile (Section 4.4) from R_T(0) = `initial_position_ned_ft`.
    pub fn seed_profile(initial_position_ned_ft: Vec3) -> Self {
        Self {
            initial_position_ned_ft,
            kind: MotionKind::Profile(Box::new(seed_profile())),
        }
    }

    /// Straight flight at `velocity_ned_fps` from R_T(0) = `initial_position_ned_ft`.
    pub fn straight(initial_position_ned_ft: Vec3, velocity_ned_fps: Vec3) -> Self {
        Self {
            initial_position_ned_ft,
            kind: MotionKind::Straight(velocity_ned_fps),
        }
    }

    /// The motion a scenario's `[target]` section describes, when it is one of the closed
    /// forms (the seed's profile or straight flight; the others are `world::trajectory`'s).
    pub fn from_section(section: &TargetSection) -> Option<Self> {
        let start = Vec3::from(section.initial_position_ft);
        match section.motion {
            TargetMotion::SeedProfile => Some(Self::seed_profile(start)),
            TargetMotion::Straight => Some(Self::straight(
                start,
                Vec3::from(section.straight_velocity_fps),
            )),
            TargetMotion::Waypoints | TargetMotion::Random | TargetMotion::Csv => None,
        }
    }

    /// R_T(t), NED, ft (exact integral of the velocity profile).
    pub fn position_ned_ft(&self, t_s: f64) -> Vec3 {
        let travelled = match &self.kind {
            MotionKind::Profile(p) => {
                Vec3::new(p[0].integral(t_s), p[1].integral(t_s), p[2].integral(t_s))
            }
            MotionKind::Straight(v) => v * t_s,
        };
        self.initial_position_ned_ft + travelled
    }

    /// V_T(t), NED, ft/s.
    pub fn velocity_ned_fps(&self, t_s: f64) -> Vec3 {
        match &self.kind {
            MotionKind::Profile(p) => Vec3::new(p[0].value(t_s), p[1].value(t_s), p[2].value(t_s)),
            MotionKind::Straight(v) => *v,
        }
    }

    /// a_T(t), NED, ft/s².
    pub fn accel_ned_fps2(&self, t_s: f64) -> Vec3 {
        match &self.kind {
            MotionKind::Profile(p) => Vec3::new(
                p[0].derivative(t_s),
                p[1].derivative(t_s),
                p[2].derivative(t_s),
            ),
            MotionKind::Straight(_) => Vec3::zeros(),
        }
    }

    /// Full state at t; the attitude has the nose along V_T and the coordinated-turn bank.
    pub fn state(&self, t_s: f64) -> TargetState {
        let velocity_ned_fps = self.velocity_ned_fps(t_s);
        let accel_ned_fps2 = self.accel_ned_fps2(t_s);
        let bank_rad = coordinated_turn_bank_rad(&velocity_ned_fps, &accel_ned_fps2);
        TargetState {
            position_ned_ft: self.position_ned_ft(t_s),
            velocity_ned_fps,
            accel_ned_fps2,
            attitude: attitude_along_velocity(&velocity_ned_fps, bank_rad).unwrap_or_default(),
        }
    }
}

impl TargetModel for TargetMotionModel {
    fn state(&self, t_s: f64) -> TargetState {
        TargetMotionModel::state(self, t_s)
    }

    fn position_ned_ft(&self, t_s: f64) -> Vec3 {
        TargetMotionModel::position_ned_ft(self, t_s)
    }
}

/// A motion flown through an air mass (`target.path = "in_air_mass"`): its position and
/// velocity over the ground are the motion's carried by the steady wind's north and east
/// components and, for a target without an airframe of its own, by the gusts' (the target
/// holds its height schedule, a pressure altitude); its acceleration and attitude are the
/// motion's own, the nose along the velocity through the air, crabbed into the wind
/// (docs/equations.md, The target in the air mass).
#[derive(Debug)]
pub struct CarriedByAir {
    motion: Box<dyn TargetModel>,
    wind_ned_fps: Vec3,
    gusts: Option<GustDrift>,
}

/// How far the gusts have carried a target: a Dryden stream advanced at the target's airspeed
/// and altitude, its horizontal gust held over each step and integrated.
#[derive(Debug, Clone)]
struct GustDrift {
    dryden: DrydenTurbulence,
    origin_altitude_ft: f64,
    /// The drift at `since_s`, NED, ft.
    offset_ned_ft: Vec3,
    /// The horizontal gust held over the step from `since_s`, NED, ft/s.
    gust_ned_fps: Vec3,
    since_s: f64,
}

impl GustDrift {
    /// The drift at `t_s` within the step, NED, ft.
    fn at(&self, t_s: f64) -> Vec3 {
        self.offset_ned_ft + self.gust_ned_fps * (t_s - self.since_s)
    }
}

impl CarriedByAir {
    /// `motion` flown in the air of the steady wind `wind_ned_fps` (NED, ft/s), and carried by
    /// the gusts of `turbulence` (at `origin_altitude_ft`, the altitude of NED down 0) when
    /// it is given.
    pub fn new(
        motion: Box<dyn TargetModel>,
        wind_ned_fps: [f64; 3],
        turbulence: Option<(DrydenTurbulence, f64)>,
    ) -> Self {
        let [north, east, _] = wind_ned_fps;
        Self {
            motion,
            wind_ned_fps: Vec3::new(north, east, 0.0),
            gusts: turbulence.map(|(dryden, origin_altitude_ft)| GustDrift {
                dryden,
                origin_altitude_ft,
                offset_ned_ft: Vec3::zeros(),
                gust_ned_fps: Vec3::zeros(),
                since_s: 0.0,
            }),
        }
    }

    /// The drift at `t_s`, NED, ft.
    fn drift_ned_ft(&self, t_s: f64) -> Vec3 {
        self.wind_ned_fps * t_s + self.gusts.as_ref().map_or_else(Vec3::zeros, |g| g.at(t_s))
    }
}

impl TargetModel for CarriedByAir {
    fn advance(&mut self, t_s: f64, dt_s: f64) -> Result<(), TargetDiverged> {
        self.motion.advance(t_s, dt_s)?;
        let Some(gusts) = &mut self.gusts else {
            return Ok(());
        };
        let through_air = self.motion.state(t_s);
        let airspeed_fps = through_air.velocity_ned_fps.norm();
        let altitude_ft = gusts.origin_altitude_ft - through_air.position_ned_ft.z;
        let [u, v, _] = gusts.dryden.step(dt_s, airspeed_fps, altitude_ft).into();
        // The gust's horizontal body components turned by the heading alone: u along the
        // nose, v to the right.
        let heading = EulerAngles::new(0.0, 0.0, through_air.attitude.psi_rad);
        gusts.offset_ned_ft = gusts.at(t_s);
        gusts.gust_ned_fps = heading.body_from_ned().transpose() * Vec3::new(u, v, 0.0);
        gusts.since_s = t_s;
        Ok(())
    }

    fn state(&self, t_s: f64) -> TargetState {
        let through_air = self.motion.state(t_s);
        let gust_ned_fps = self
            .gusts
            .as_ref()
            .map_or_else(Vec3::zeros, |g| g.gust_ned_fps);
        TargetState {
            position_ned_ft: through_air.position_ned_ft + self.drift_ned_ft(t_s),
            velocity_ned_fps: through_air.velocity_ned_fps + self.wind_ned_fps + gust_ned_fps,
            ..through_air
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seed() -> TargetMotionModel {
        TargetMotionModel::from_section(&TargetSection::default()).expect("closed form")
    }

    /// In the air mass the seed's target is carried by the wind's horizontal components, its
    /// nose still along its velocity through the air.
    #[test]
    fn the_air_mass_carries_the_motion_not_its_attitude() {
        let carried = CarriedByAir::new(Box::new(seed()), [3.0, -15.0, 2.0], None);
        let wind = Vec3::new(3.0, -15.0, 0.0);
        for t_s in [0.0, 20.0, 101.5] {
            let (own, moved) = (seed().state(t_s), carried.state(t_s));
            assert_eq!(moved.position_ned_ft, own.position_ned_ft + wind * t_s);
            assert_eq!(moved.velocity_ned_fps, own.velocity_ned_fps + wind);
            assert_eq!(moved.accel_ned_fps2, own.accel_ned_fps2);
            assert_eq!(moved.attitude, own.attitude);
        }
    }

    /// A target carried by gusts moves over each step by the gust it holds over that step: its
    /// drift is the integral of its velocity through the air's, horizontal only, and the
    /// gusts of moderate air move it (by more than 10 ft over 20 s on this stream).
    #[test]
    fn the_gusts_carry_a_tracer_by_what_it_holds_over_each_step() {
        use crate::world::atmosphere::TurbulenceLevel;
        let dryden = DrydenTurbulence::new(TurbulenceLevel::Moderate, 7);
        let mut carried = CarriedByAir::new(Box::new(seed()), [0.0; 3], Some((dryden, 500.0)));
        let own = seed();
        let drift = |c: &CarriedByAir, t_s: f64| {
            c.state(t_s).position_ned_ft - own.state(t_s).position_ned_ft
        };
        let dt_s = 0.01;
        for i in 0..2000 {
            let t_s = i as f64 * dt_s;
            carried.advance(t_s, dt_s).expect("a closed-form motion");
            let gust = carried.state(t_s).velocity_ned_fps - own.state(t_s).velocity_ned_fps;
            let moved = drift(&carried, t_s + dt_s) - drift(&carried, t_s);
            assert!(
                (moved - gust * dt_s).norm() < 1e-9,
                "step {i}: {moved:?} {gust:?}"
            );
            assert_eq!(gust.z, 0.0);
        }
        assert!(
            drift(&carried, 20.0).norm() > 10.0,
            "{:?}",
            drift(&carried, 20.0)
        );
    }

    /// Each piece joins the next continuously.
    #[test]
    fn profile_is_continuous() {
        for axis in seed_profile() {
            for piece in &axis.pieces[1..] {
                let t = piece.start_s;
                let before = axis.value(t - 1e-9);
                let after = axis.value(t + 1e-9);
                assert!(
                    (before - after).abs() < 1e-6,
                    "jump at {t}: {before} -> {after}"
                );
            }
        }
    }

    /// The seed's printed values at a few instants.
    #[test]
    fn profile_matches_seed_values() {
        let m = seed();
        assert_eq!(m.velocity_ned_fps(1.0), Vec3::new(50.0, 0.0, 0.0));
        let v = m.velocity_ned_fps(38.0);
        assert!((v - Vec3::new(0.0, 55.0, 0.0)).norm() < 1e-12);
        let v = m.velocity_ned_fps(78.0);
        let vz = 3.0 * (1.0 - (PI / 15.0 * 28.0).cos());
        assert!((v - Vec3::new(55.0, 0.0, vz)).norm() < 1e-12);
        assert_eq!(m.velocity_ned_fps(130.0), Vec3::new(0.0, -50.0, 0.0));
    }

    /// Speed within about 35-60 ft/s (docs/equations.md, The relative motion and the seed's
    /// scenario). Its "accelerations up to about 3.2 ft/s²" holds per axis (the largest,
    /// 30π/30 = π ft/s², on x and y in (43, 73]); the norm is up to √2 π plus the small
    /// vertical part, since x and y peak together.
    #[test]
    fn speed_and_acceleration_envelope() {
        let m = seed();
        for i in 0..=14_000 {
            let t = i as f64 * 0.01;
            let speed = m.velocity_ned_fps(t).norm();
            assert!((35.0..=60.1).contains(&speed), "speed {speed} at {t}");
            let accel = m.accel_ned_fps2(t);
            assert!(accel.amax() <= PI + 1e-12, "accel {accel:?} at {t}");
            assert!(
                accel.norm() <= (2.0 * PI * PI + 0.4).sqrt(),
                "accel {accel:?} at {t}"
            );
        }
    }

    /// The closed-form position agrees with a fine numerical quadrature of the velocity to
    /// better than 1e-6 ft over 140 s (composite Simpson, 1.4 million intervals, exact on
    /// each smooth piece to ~1e-12 except across the kinks, which are points of continuity).
    #[test]
    fn position_is_exact_integral_of_velocity() {
        let m = seed();
        let n = 1_400_000usize;
        let h = 140.0 / n as f64;
        let mut sum = m.velocity_ned_fps(0.0) + m.velocity_ned_fps(140.0);
        for i in 1..n {
            let w = if i % 2 == 1 { 4.0 } else { 2.0 };
            sum += m.velocity_ned_fps(i as f64 * h) * w;
        }
        let numeric = m.position_ned_ft(0.0) + sum * (h / 3.0);
        let closed = m.position_ned_ft(140.0);
        assert!(
            (numeric - closed).norm() < 1e-6,
            "{numeric:?} vs {closed:?}"
        );
    }

    /// The acceleration is the derivative of the velocity (central differences).
    #[test]
    fn acceleration_is_velocity_derivative() {
        let m = seed();
        for t in [5.0, 20.0, 40.0, 60.0, 78.0, 100.0, 115.0] {
            let h = 1e-5;
            let fd = (m.velocity_ned_fps(t + h) - m.velocity_ned_fps(t - h)) / (2.0 * h);
            assert!((fd - m.accel_ned_fps2(t)).norm() < 1e-6, "t = {t}");
        }
    }

    #[test]
    fn attitude_follows_velocity() {
        let m = seed();
        let s = m.state(40.0); // flying east, level
        assert!((s.attitude.psi_rad - PI / 2.0).abs() < 1e-9);
        let s = m.state(20.0); // climbing (VTz < 0): positive flight-path angle.
        assert!(s.attitude.theta_rad > 0.0);
        // At t = 20 VTx falls and VTy rises: turning from north to east, a right turn.
        assert!(s.attitude.phi_rad > 0.0);
    }
}
