//! The target's turn read from its wing line (`estimator.target_bank = "measured"`;
//! docs/equations.md, The target's bank from its wing line). An aircraft in coordinated flight
//! turns by banking its lift: its acceleration across its velocity is g cos γ tan φ, in feet
//! per second squared, whatever its size. The camera sees the bank: the silhouette's maximal
//! length, the span seen from behind, lies along the wing axis
//! ```text
//! ŵ(φ) = cos φ ŷ₀ + sin φ ẑ₀
//! ```
//! with ŷ₀ the horizontal unit vector to the right of the velocity and ẑ₀ the unit vector
//! across the velocity pointing down (the body axes of [`super::aspect::body_axes_ned`] at zero
//! acceleration). A small direction w (camera axes) at the image point (yI, zI) appears along
//! D(w) = (w_y - w_x yI/l, -(w_z + w_x zI/l)) in (yI, zI) ([`super::aspect::image_direction`]), so
//! the measured direction u of the line satisfies cos φ D(ŷ₀) × u + sin φ D(ẑ₀) × u = 0:
//! ```text
//! tan φ = -(A × u) / (B × u),   A = D(ŷ₀), B = D(ẑ₀)
//! ```
//! The velocity's direction is the filter's (scale-free: d̂ + ĝ); the line's direction noise
//! σ_θ = √2 σ_end / bI from its ends' noise across it, carried through dtan φ/dθ.

use crate::frames::{GRAVITY_FPS2, Mat3, Vec3};

use super::aspect::{body_axes_ned, image_direction};

/// The largest bank a wing line is read as, rad: beyond it the line is more likely the
/// fuselage, or the view too oblique to tell the bank.
const MAX_BANK_RAD: f64 = 1.0;

/// The silhouette's maximal length as the camera saw it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WingLine {
    /// Its midpoint, (yI right, zI up), px.
    pub point_px: (f64, f64),
    /// Its unit direction in (yI, zI) (either sense).
    pub direction: [f64; 2],
    /// Its length, px.
    pub length_px: f64,
}

/// What a wing line says of the target's acceleration across its velocity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LateralAcceleration {
    /// ŷ₀: the horizontal unit vector to the right of the target's velocity, NED.
    pub across_ned: Vec3,
    /// The acceleration along it, g cos γ tan φ, ft/s².
    pub accel_fps2: f64,
    /// Its σ from the line's direction noise, ft/s².
    pub sigma_fps2: f64,
}

/// The target's acceleration across its velocity from its wing line (module docs), for a
/// camera oriented `ned_from_camera` with focal length `focal_px`, the target flying along
/// `velocity_ned` (any scale) and the line's ends each uncertain by `end_sigma_px` across it.
/// `None` for a target without a horizontal velocity, a view along the bank's axis, or a
/// bank beyond [`MAX_BANK_RAD`].
pub fn lateral_acceleration(
    line: &WingLine,
    ned_from_camera: &Mat3,
    focal_px: f64,
    velocity_ned: &Vec3,
    end_sigma_px: f64,
) -> Option<LateralAcceleration> {
    let horizontal = velocity_ned.xy().norm();
    if horizontal <= 1e-9 * velocity_ned.norm() {
        return None;
    }
    let cos_gamma = horizontal / velocity_ned.norm();
    let axes = body_axes_ned(velocity_ned, &Vec3::zeros())?;
    let (right, down): (Vec3, Vec3) = (axes.column(1).into(), axes.column(2).into());
    let camera_from_ned = ned_from_camera.transpose();
    let (y_i_px, z_i_px) = line.point_px;
    let image_of = |w: Vec3| image_direction(&(camera_from_ned * w), y_i_px, z_i_px, focal_px);
    let (a, b, u) = (image_of(right), image_of(down), line.direction);
    let cross = |p: [f64; 2]| p[0] * u[1] - p[1] * u[0];
    let dot = |p: [f64; 2]| p[0] * u[0] + p[1] * u[1];
    let (a_cross, b_cross) = (cross(a), cross(b));
    if b_cross.abs() < 1e-6 {
        return None;
    }
    let tan_bank = -a_cross / b_cross;
    if tan_bank.abs() > MAX_BANK_RAD.tan() {
        return None;
    }
    // d tan φ / dθ for u turned by dθ: d(P × u)/dθ = P · u.
    let slope = -(dot(a) * b_cross - a_cross * dot(b)) / (b_cross * b_cross);
    let sigma_theta = std::f64::consts::SQRT_2 * end_sigma_px / line.length_px.max(1.0);
    let g_level = GRAVITY_FPS2 * cos_gamma;
    Some(LateralAcceleration {
        across_ned: right,
        accel_fps2: g_level * tan_bank,
        sigma_fps2: g_level * slope.abs() * sigma_theta,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimation::aspect::wing_axis_ned;
    use crate::frames::EulerAngles;

    const FOCAL_PX: f64 = 554.0;

    /// The wing line of a target at `rel_ned` flying `velocity` with `accel`, seen by a
    /// camera `ned_from_camera`: its tips (span 8 ft) projected exactly.
    fn wing_line(rel_ned: Vec3, velocity: Vec3, accel: Vec3, ned_from_camera: &Mat3) -> WingLine {
        let wing = wing_axis_ned(&velocity, &accel).expect("moving");
        let project = |p: Vec3| {
            let c = ned_from_camera.transpose() * p;
            (FOCAL_PX * c.y / c.x, -FOCAL_PX * c.z / c.x)
        };
        let (t1, t2) = (project(rel_ned + wing * 4.0), project(rel_ned - wing * 4.0));
        let (dy, dz) = (t1.0 - t2.0, t1.1 - t2.1);
        let length_px = dy.hypot(dz);
        WingLine {
            point_px: (0.5 * (t1.0 + t2.0), 0.5 * (t1.1 + t2.1)),
            direction: [dy / length_px, dz / length_px],
            length_px,
        }
    }

    /// From behind, above, beside and off the image centre, climbing or not, in either turn:
    /// the bank read from the projected wing gives back the coordinated turn's acceleration
    /// to round-off (a line's image is a line, so its direction at the projected tips'
    /// midpoint is D(ŵ) there exactly).
    #[test]
    fn the_wing_line_gives_back_the_turn() {
        let views = [
            (Vec3::new(32.0, 8.0, 0.0), EulerAngles::new(0.0, 0.0, 0.2)),
            (
                Vec3::new(60.0, -20.0, 15.0),
                EulerAngles::new(0.3, -0.2, -0.3),
            ),
            (
                Vec3::new(150.0, 40.0, 30.0),
                EulerAngles::new(-0.2, -0.15, 0.25),
            ),
        ];
        for (rel, camera_attitude) in views {
            let ned_from_camera = camera_attitude.body_from_ned().transpose();
            for climb in [0.0, -6.0] {
                let velocity = Vec3::new(48.0, 10.0, climb);
                let right = body_axes_ned(&velocity, &Vec3::zeros())
                    .expect("moving")
                    .column(1)
                    .into_owned();
                for turn_fps2 in [-12.0, -3.0, 0.0, 5.0, 15.0] {
                    let accel = right * turn_fps2;
                    let line = wing_line(rel, velocity, accel, &ned_from_camera);
                    let read =
                        lateral_acceleration(&line, &ned_from_camera, FOCAL_PX, &velocity, 0.5)
                            .expect("seen from behind");
                    assert!((read.across_ned - right).norm() < 1e-12);
                    assert!(
                        (read.accel_fps2 - turn_fps2).abs() < 1e-9 * turn_fps2.abs().max(1.0),
                        "{rel:?} climb {climb} turn {turn_fps2}: read {}",
                        read.accel_fps2
                    );
                    assert!(read.sigma_fps2 > 0.0 && read.sigma_fps2 < 2.0, "{read:?}");
                }
            }
        }
    }

    /// The σ follows the line's length: a wing twice as long in the image reads its bank
    /// twice as well.
    #[test]
    fn a_longer_line_reads_the_bank_better() {
        let ned_from_camera = Mat3::identity();
        let velocity = Vec3::new(50.0, 0.0, 0.0);
        let line = wing_line(
            Vec3::new(40.0, 0.0, 0.0),
            velocity,
            Vec3::zeros(),
            &ned_from_camera,
        );
        let sigma = |length_px| {
            let l = WingLine { length_px, ..line };
            lateral_acceleration(&l, &ned_from_camera, FOCAL_PX, &velocity, 0.5)
                .expect("behind")
                .sigma_fps2
        };
        assert!((sigma(50.0) / sigma(100.0) - 2.0).abs() < 1e-9);
        // Seen square from behind, level: σ = g √2 σ_end / bI.
        assert!((sigma(100.0) - GRAVITY_FPS2 * 2f64.sqrt() * 0.5 / 100.0).abs() < 1e-9);
    }

    /// A target seen from straight above (its down axis along the line of sight), one
    /// flying straight up, and a line too steep for a wing say nothing.
    #[test]
    fn views_that_cannot_tell_the_bank_say_nothing() {
        let velocity = Vec3::new(50.0, 0.0, 0.0);
        // A camera looking straight down: its optical axis is NED down.
        let looking_down = EulerAngles::new(0.0, -std::f64::consts::FRAC_PI_2, 0.0)
            .body_from_ned()
            .transpose();
        let line = wing_line(
            Vec3::new(0.0, 0.0, 40.0),
            velocity,
            Vec3::zeros(),
            &looking_down,
        );
        assert!(lateral_acceleration(&line, &looking_down, FOCAL_PX, &velocity, 0.5).is_none());
        let level = Mat3::identity();
        let behind = wing_line(Vec3::new(40.0, 0.0, 0.0), velocity, Vec3::zeros(), &level);
        let straight_up = Vec3::new(0.0, 0.0, -50.0);
        assert!(lateral_acceleration(&behind, &level, FOCAL_PX, &straight_up, 0.5).is_none());
        let vertical = WingLine {
            direction: [0.0, 1.0],
            ..behind
        };
        assert!(lateral_acceleration(&vertical, &level, FOCAL_PX, &velocity, 0.5).is_none());
    }
}
