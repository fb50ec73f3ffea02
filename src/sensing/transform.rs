//! The sensing transform: from image measurements to the scaled relative position r (seed
//! Chapter 3, (3.1)-(3.12); `docs/equations.md`, What the camera measures), and back.
//!
//! The camera frame is the follower's body frame (x along the optical axis). A point at body
//! coordinates (X, Y, Z), X > 0, appears at yI = l Y / X (right), zI = -l Z / X (up), with l the
//! focal length in pixels.

use crate::frames::{Mat3, Vec3};
use crate::vision::ImageMeasurement;

/// Unit line of sight T_IB in body axes from bearing λ and elevation ϑ, (3.9).
pub fn line_of_sight_body(bearing_rad: f64, elevation_rad: f64) -> Vec3 {
    let (sl, cl) = bearing_rad.sin_cos();
    let (se, ce) = elevation_rad.sin_cos();
    Vec3::new(ce * cl, ce * sl, -se)
}

/// Bearing λ (3.3) and elevation ϑ (3.9) of an image point, rad.
pub fn bearing_elevation_rad(y_i_px: f64, z_i_px: f64, focal_px: f64) -> (f64, f64) {
    let bearing = (y_i_px / focal_px).atan();
    let elevation = (z_i_px / (focal_px * focal_px + y_i_px * y_i_px).sqrt()).atan();
    (bearing, elevation)
}

/// r = aI L_BEᵀ T_IB, the relative position divided by the target's size b, in NED
/// ((3.7), (3.12)); `body_from_ned` is the follower's L_BE.
pub fn scaled_relative_position(
    measurement: &ImageMeasurement,
    focal_px: f64,
    body_from_ned: &Mat3,
) -> Vec3 {
    let m = measurement;
    let (bearing, elevation) = bearing_elevation_rad(m.y_i_px, m.z_i_px, focal_px);
    body_from_ned.transpose() * line_of_sight_body(bearing, elevation) * m.scaled_range(focal_px)
}

/// J = ∂r/∂(yI, zI, bI) of [`scaled_relative_position`] at a measurement, columns yI, zI, bI,
/// `ned_from_camera` the camera's L_BEᵀ: since aI T_IB = [l, yI, -zI]ᵀ / bI exactly,
/// r = L_BEᵀ [l, yI, -zI]ᵀ / bI and J = L_BEᵀ [[0, 0, -l/bI²], [1/bI, 0, -yI/bI²],
/// [0, -1/bI, zI/bI²]]. It maps pixel noise to the noise of r (`docs/equations.md`, Noisy measurements).
pub fn scaled_position_jacobian(
    measurement: &ImageMeasurement,
    focal_px: f64,
    ned_from_camera: &Mat3,
) -> Mat3 {
    let m = measurement;
    let (inv, inv2) = (1.0 / m.b_i_px, 1.0 / (m.b_i_px * m.b_i_px));
    let camera = Mat3::new(
        0.0,
        0.0,
        -focal_px * inv2,
        inv,
        0.0,
        -m.y_i_px * inv2,
        0.0,
        -inv,
        m.z_i_px * inv2,
    );
    ned_from_camera * camera
}

/// The inverse of [`scaled_relative_position`]: the image coordinates of the relative position
/// `rel_ned_ft` and the maximal length bI = l b / X that (3.7) assumes, i.e. the image of a
/// segment of length b parallel to the image plane at depth X. (A real silhouette's maximal
/// length depends on the target's attitude: the renderer and vision modules measure it.)
/// Returns `None` when the target is not in front of the camera (X ≤ 0).
pub fn image_from_relative_position(
    rel_ned_ft: &Vec3,
    body_from_ned: &Mat3,
    b_ft: f64,
    focal_px: f64,
) -> Option<ImageMeasurement> {
    let p_body = body_from_ned * rel_ned_ft;
    if p_body.x <= 0.0 {
        return None;
    }
    Some(ImageMeasurement {
        y_i_px: focal_px * p_body.y / p_body.x,
        z_i_px: -focal_px * p_body.z / p_body.x,
        b_i_px: b_ft * focal_px / p_body.x,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::EulerAngles;
    use rand::{Rng, SeedableRng};

    /// The round trip (relative position, attitude, size) -> (yI, zI, bI) -> r recovers R / b
    /// to 1e-9 relative over thousands of random attitudes and in-view positions.
    #[test]
    fn measurement_round_trip_is_exact() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let focal_px = 554.256;
        let mut checked = 0;
        while checked < 5000 {
            let att = EulerAngles::new(
                rng.random_range(-3.0..3.0),
                rng.random_range(-1.5..1.5),
                rng.random_range(-3.1..3.1),
            );
            let l_be = att.body_from_ned();
            // A point in the field of view: ahead within ±60° of the axis.
            let range_ft = rng.random_range(5.0..1000.0);
            let bearing = rng.random_range(-1.0..1.0);
            let elevation = rng.random_range(-0.8..0.8);
            let p_body = line_of_sight_body(bearing, elevation) * range_ft;
            let rel_ned = l_be.transpose() * p_body;
            let b_ft = rng.random_range(1.0..30.0);
            let meas = image_from_relative_position(&rel_ned, &l_be, b_ft, focal_px)
                .expect("point is ahead");
            let r = scaled_relative_position(&meas, focal_px, &l_be);
            let expected = rel_ned / b_ft;
            assert!(
                (r - expected).norm() <= 1e-9 * expected.norm(),
                "r = {r:?}, expected {expected:?}"
            );
            checked += 1;
        }
    }

    /// The Jacobian matches central differences of the transform.
    #[test]
    fn jacobian_matches_finite_differences() {
        let attitude = EulerAngles::new(0.3, -0.2, 1.1).body_from_ned();
        let m = ImageMeasurement {
            y_i_px: 40.0,
            z_i_px: -25.0,
            b_i_px: 60.0,
        };
        let focal_px = 554.0;
        let j = scaled_position_jacobian(&m, focal_px, &attitude.transpose());
        let h = 1e-4;
        for (column, delta) in [(0, [h, 0.0, 0.0]), (1, [0.0, h, 0.0]), (2, [0.0, 0.0, h])] {
            let shifted = |sign: f64| ImageMeasurement {
                y_i_px: m.y_i_px + sign * delta[0],
                z_i_px: m.z_i_px + sign * delta[1],
                b_i_px: m.b_i_px + sign * delta[2],
            };
            let fd = (scaled_relative_position(&shifted(1.0), focal_px, &attitude)
                - scaled_relative_position(&shifted(-1.0), focal_px, &attitude))
                / (2.0 * h);
            assert!(
                (fd - j.column(column)).norm() < 1e-8,
                "{column}: {fd} vs {}",
                j.column(column)
            );
        }
    }

    #[test]
    fn point_behind_camera_has_no_image() {
        let l_be = Mat3::identity();
        assert!(
            image_from_relative_position(&Vec3::new(-10.0, 0.0, 0.0), &l_be, 8.0, 500.0).is_none()
        );
    }

    #[test]
    fn image_axes_follow_spec_signs() {
        let l_be = Mat3::identity();
        // Right and above (negative down) of the axis: yI > 0 and zI > 0.
        let m = image_from_relative_position(&Vec3::new(100.0, 10.0, -5.0), &l_be, 8.0, 500.0)
            .expect("ahead");
        assert!((m.y_i_px - 50.0).abs() < 1e-12);
        assert!((m.z_i_px - 25.0).abs() < 1e-12);
    }
}
