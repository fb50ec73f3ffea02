//! A target trajectory given at knots (time, position, velocity, acceleration) and
//! interpolated between them by quintic Hermite polynomials (docs/equations.md, Trajectory
//! sources for the target): position, velocity and acceleration are continuous and exactly
//! the knots' at the knots, so the attitude drawn from them (nose along the velocity,
//! coordinated-turn bank from the acceleration) has no jumps.

use crate::frames::{
    EulerAngles, Vec3, attitude_along_velocity, coordinated_turn_bank_rad, wrap_angle_rad,
};
use crate::world::target::{TargetModel, TargetState};

/// The target's motion at one knot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Knot {
    /// Time from the run's start, s.
    pub t_s: f64,
    /// R_T, NED, ft.
    pub position_ned_ft: Vec3,
    /// V_T, NED, ft/s.
    pub velocity_ned_fps: Vec3,
    /// a_T, NED, ft/s².
    pub accel_ned_fps2: Vec3,
}

/// A trajectory through knots, with the attitude at each knot where it is known (a recorded
/// track's) and otherwise nose along the velocity with the coordinated-turn bank.
#[derive(Debug, Clone, PartialEq)]
pub struct SampledTrack {
    knots: Vec<Knot>,
    attitudes: Option<Vec<EulerAngles>>,
}

impl SampledTrack {
    /// A track through `knots`, at least two, their times strictly increasing, with one
    /// attitude per knot when `attitudes` is given; `None` when they are not so.
    pub fn new(knots: Vec<Knot>, attitudes: Option<Vec<EulerAngles>>) -> Option<Self> {
        let increasing = knots.windows(2).all(|w| w[0].t_s < w[1].t_s);
        let matched = attitudes.as_ref().is_none_or(|a| a.len() == knots.len());
        (knots.len() >= 2 && increasing && matched).then_some(Self { knots, attitudes })
    }

    /// A flown track: `knots` at least two, one per step of a fixed positive time step.
    pub(super) fn flown(knots: Vec<Knot>) -> Self {
        debug_assert!(knots.len() >= 2 && knots.windows(2).all(|w| w[0].t_s < w[1].t_s));
        Self {
            knots,
            attitudes: None,
        }
    }

    /// The knots.
    pub fn knots(&self) -> &[Knot] {
        &self.knots
    }

    /// Time of the last knot, s.
    pub fn end_s(&self) -> f64 {
        self.knots.last().map_or(0.0, |k| k.t_s)
    }

    /// Position, velocity and acceleration at `t_s`: quintic Hermite between knots; before
    /// the first and after the last knot the track goes on at that knot's velocity.
    fn motion(&self, t_s: f64) -> Knot {
        let after = self.knots.partition_point(|k| k.t_s <= t_s);
        let (first, last) = (self.knots[0], self.knots[self.knots.len() - 1]);
        if after == 0 || after == self.knots.len() {
            let edge = if after == 0 { first } else { last };
            return Knot {
                t_s,
                position_ned_ft: edge.position_ned_ft + edge.velocity_ned_fps * (t_s - edge.t_s),
                velocity_ned_fps: edge.velocity_ned_fps,
                accel_ned_fps2: if t_s == edge.t_s {
                    edge.accel_ned_fps2
                } else {
                    Vec3::zeros()
                },
            };
        }
        quintic_hermite(&self.knots[after - 1], &self.knots[after], t_s)
    }

    /// The recorded attitude at `t_s`, each angle interpolated linearly along the shorter
    /// way round; the first's or last's outside the knots.
    fn recorded_attitude(&self, attitudes: &[EulerAngles], t_s: f64) -> EulerAngles {
        let after = self.knots.partition_point(|k| k.t_s <= t_s);
        if after == 0 || after == self.knots.len() {
            return attitudes[after.saturating_sub(1)];
        }
        let (k0, k1) = (&self.knots[after - 1], &self.knots[after]);
        let s = (t_s - k0.t_s) / (k1.t_s - k0.t_s);
        let (a0, a1) = (attitudes[after - 1], attitudes[after]);
        let blend = |x0: f64, x1: f64| wrap_angle_rad(x0 + s * wrap_angle_rad(x1 - x0));
        EulerAngles::new(
            blend(a0.phi_rad, a1.phi_rad),
            a0.theta_rad + s * (a1.theta_rad - a0.theta_rad),
            blend(a0.psi_rad, a1.psi_rad),
        )
    }
}

/// The quintic through two knots' positions, velocities and accelerations, at `t_s` in
/// [k0.t_s, k1.t_s].
fn quintic_hermite(k0: &Knot, k1: &Knot, t_s: f64) -> Knot {
    let h = k1.t_s - k0.t_s;
    let s = (t_s - k0.t_s) / h;
    let dp = k1.position_ned_ft - k0.position_ned_ft;
    let (v0, v1) = (k0.velocity_ned_fps * h, k1.velocity_ned_fps * h);
    let (a0, a1) = (k0.accel_ned_fps2 * (h * h), k1.accel_ned_fps2 * (h * h));
    // p(s) = c0 + c1 s + ... + c5 s⁵ with p, p', p'' matching the knots at s = 0 and 1.
    let c0 = k0.position_ned_ft;
    let c1 = v0;
    let c2 = a0 * 0.5;
    let c3 = dp * 10.0 - v0 * 6.0 - v1 * 4.0 - a0 * 1.5 + a1 * 0.5;
    let c4 = dp * -15.0 + v0 * 8.0 + v1 * 7.0 + a0 * 1.5 - a1;
    let c5 = dp * 6.0 - v0 * 3.0 - v1 * 3.0 - a0 * 0.5 + a1 * 0.5;
    let p = c0 + (c1 + (c2 + (c3 + (c4 + c5 * s) * s) * s) * s) * s;
    let dp_ds = c1 + (c2 * 2.0 + (c3 * 3.0 + (c4 * 4.0 + c5 * (5.0 * s)) * s) * s) * s;
    let d2p_ds2 = c2 * 2.0 + (c3 * 6.0 + (c4 * 12.0 + c5 * (20.0 * s)) * s) * s;
    Knot {
        t_s,
        position_ned_ft: p,
        velocity_ned_fps: dp_ds / h,
        accel_ned_fps2: d2p_ds2 / (h * h),
    }
}

impl TargetModel for SampledTrack {
    fn state(&self, t_s: f64) -> TargetState {
        let m = self.motion(t_s);
        let attitude = match &self.attitudes {
            Some(attitudes) => self.recorded_attitude(attitudes, t_s),
            None => {
                let bank_rad = coordinated_turn_bank_rad(&m.velocity_ned_fps, &m.accel_ned_fps2);
                attitude_along_velocity(&m.velocity_ned_fps, bank_rad).unwrap_or_default()
            }
        };
        TargetState {
            position_ned_ft: m.position_ned_ft,
            velocity_ned_fps: m.velocity_ned_fps,
            accel_ned_fps2: m.accel_ned_fps2,
            attitude,
        }
    }

    fn position_ned_ft(&self, t_s: f64) -> Vec3 {
        self.motion(t_s).position_ned_ft
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quintic polynomial per axis and its derivatives.
    fn poly(t: f64) -> Knot {
        let c = [1.0, -2.0, 0.5, 0.3, -0.02, 0.001];
        let p: f64 = c
            .iter()
            .enumerate()
            .map(|(i, ci)| ci * t.powi(i as i32))
            .sum();
        let v: f64 = (1..6).map(|i| c[i] * i as f64 * t.powi(i as i32 - 1)).sum();
        let a: f64 = (2..6)
            .map(|i| c[i] * (i * (i - 1)) as f64 * t.powi(i as i32 - 2))
            .sum();
        Knot {
            t_s: t,
            position_ned_ft: Vec3::new(p, 2.0 * p, -p),
            velocity_ned_fps: Vec3::new(v, 2.0 * v, -v),
            accel_ned_fps2: Vec3::new(a, 2.0 * a, -a),
        }
    }

    /// The interpolant reproduces a quintic exactly, between and at the knots.
    #[test]
    fn quintic_is_reproduced() {
        let track = SampledTrack::new(vec![poly(0.0), poly(0.7), poly(2.0)], None).unwrap();
        for i in 0..=40 {
            let t = i as f64 * 0.05;
            let (got, want) = (track.motion(t), poly(t));
            assert!(
                (got.position_ned_ft - want.position_ned_ft).norm() < 1e-10,
                "t {t}"
            );
            assert!(
                (got.velocity_ned_fps - want.velocity_ned_fps).norm() < 1e-9,
                "t {t}"
            );
            assert!(
                (got.accel_ned_fps2 - want.accel_ned_fps2).norm() < 1e-8,
                "t {t}"
            );
        }
    }

    /// Past its last knot the track flies straight on at the last velocity.
    #[test]
    fn extrapolates_straight() {
        let track = SampledTrack::new(vec![poly(0.0), poly(1.0)], None).unwrap();
        let end = poly(1.0);
        let got = track.motion(3.0);
        let want = end.position_ned_ft + end.velocity_ned_fps * 2.0;
        assert!((got.position_ned_ft - want).norm() < 1e-12);
        assert_eq!(got.accel_ned_fps2, Vec3::zeros());
    }

    #[test]
    fn rejects_bad_knots() {
        assert!(SampledTrack::new(vec![poly(0.0)], None).is_none());
        assert!(SampledTrack::new(vec![poly(1.0), poly(1.0)], None).is_none());
        let one = Some(vec![EulerAngles::default()]);
        assert!(SampledTrack::new(vec![poly(0.0), poly(1.0)], one).is_none());
    }

    /// A recorded heading crossing ±180° is interpolated the short way.
    #[test]
    fn recorded_heading_wraps() {
        let a0 = EulerAngles::new(0.0, 0.0, 3.1);
        let a1 = EulerAngles::new(0.0, 0.0, -3.1);
        let track = SampledTrack::new(vec![poly(0.0), poly(1.0)], Some(vec![a0, a1])).unwrap();
        let psi = track.state(0.5).attitude.psi_rad;
        assert!((psi.abs() - std::f64::consts::PI).abs() < 1e-9, "{psi}");
    }
}
