//! The target's aspect (seed 8.2, beyond the seed's constant apparent size): with
//! `estimator.size_model = "span"`, b is the target's wing span, and the maximal length a frame
//! measures is that span as the camera sees it, foreshortened by the target's attitude
//! relative to the line of sight.
//!
//! The attitude is not measured; it is inferred from the filter's own estimates, as a pilot
//! would: an aircraft in coordinated flight points its nose along its velocity and its lift,
//! the body's -z axis, along the part of its specific force f = â_T - g (NED, g = [0, 0, g];
//! what an accelerometer reads, -g in level flight) across that velocity. The wing (body y)
//! axis is then ŵ = ẑ × x̂ with x̂ = V̂_T/‖V̂_T‖ and ẑ the unit vector of -(f - (f·x̂)x̂).
//!
//! A segment of length b along ŵ, at the image position (yI, zI) and depth x_c, projects to
//! the length f b s / x_c to first order in b / x_c, with the aspect factor
//! s = ‖(w_y - w_x yI/f, w_z + w_x zI/f)‖ (ŵ in camera axes, z down; zI up, (3.1)): s = 1 for a span across the
//! optical axis, as the sensing transform (3.3)-(3.12) assumes. So r* computed from the frame
//! is R / (b s), and R / b = s r*. The span is the silhouette's maximal length only while it
//! is the longest of its dimensions in view: seen near the wing axis the fuselage is, and
//! the frame's length then says nothing about the span (the tracker keeps only its bearing).

use crate::frames::{GRAVITY_FPS2, Mat3, Vec3};

/// The body axes of an aircraft flying at `velocity_ned_fps` with acceleration
/// `accel_ned_fps2` in coordinated flight, as the columns x̂ (nose), ŷ (right wing), ẑ (down)
/// of NED from body; `None` when it is not moving or its specific force lies along its
/// velocity.
pub fn body_axes_ned(velocity_ned_fps: &Vec3, accel_ned_fps2: &Vec3) -> Option<Mat3> {
    let forward = velocity_ned_fps.try_normalize(1e-9)?;
    let specific_force = accel_ned_fps2 - Vec3::new(0.0, 0.0, GRAVITY_FPS2);
    let lift = specific_force - forward * specific_force.dot(&forward);
    let down = -lift.try_normalize(1e-9)?;
    // ŷ = ẑ × x̂ completes the right-handed triad.
    Some(Mat3::from_columns(&[forward, down.cross(&forward), down]))
}

/// The body axes `ned_from_wind` (as [`body_axes_ned`] gives them: the nose along the
/// velocity) pitched nose up by the angle of attack `alpha_rad` about the wing axis: the nose
/// x̂ cos α - ẑ sin α, the down axis x̂ sin α + ẑ cos α, so that the velocity has body
/// components (V cos α, 0, V sin α).
pub fn pitched_by_alpha(ned_from_wind: &Mat3, alpha_rad: f64) -> Mat3 {
    let (forward, wing, down) = (
        ned_from_wind.column(0),
        ned_from_wind.column(1),
        ned_from_wind.column(2),
    );
    let (sin, cos) = alpha_rad.sin_cos();
    Mat3::from_columns(&[
        forward * cos - down * sin,
        wing.into_owned(),
        forward * sin + down * cos,
    ])
}

/// The wing axis ŵ (unit, NED) of an aircraft flying at `velocity_ned_fps` with acceleration
/// `accel_ned_fps2`, in coordinated flight; `None` when it is not moving.
pub fn wing_axis_ned(velocity_ned_fps: &Vec3, accel_ned_fps2: &Vec3) -> Option<Vec3> {
    body_axes_ned(velocity_ned_fps, accel_ned_fps2).map(|axes| axes.column(1).into())
}

/// The image of a small displacement along `direction_camera` (camera axes, z down) at the
/// image position (`y_i_px`, `z_i_px`) of a camera of focal length `focal_px`, in (yI right,
/// zI up), per unit of focal length over depth: (w_y - w_x yI/f, -(w_z + w_x zI/f)), the
/// derivative of (3.3)-(3.9).
pub fn image_direction(
    direction_camera: &Vec3,
    y_i_px: f64,
    z_i_px: f64,
    focal_px: f64,
) -> [f64; 2] {
    let (ty, tz) = (y_i_px / focal_px, z_i_px / focal_px);
    let w = direction_camera;
    [w.y - w.x * ty, -(w.z + w.x * tz)]
}

/// The aspect factor s of a span along `wing_camera` (unit, camera axes) seen at the image
/// position (`y_i_px`, `z_i_px`) of a camera of focal length `focal_px`: the length of its
/// [`image_direction`].
pub fn span_aspect(wing_camera: &Vec3, y_i_px: f64, z_i_px: f64, focal_px: f64) -> f64 {
    let [dy, dz] = image_direction(wing_camera, y_i_px, z_i_px, focal_px);
    dy.hypot(dz)
}

/// The aspect factor of a target flying at `velocity_ned_fps` with `accel_ned_fps2`, seen at
/// (`y_i_px`, `z_i_px`) by a camera whose orientation is `ned_from_camera`.
pub fn target_span_aspect(
    velocity_ned_fps: &Vec3,
    accel_ned_fps2: &Vec3,
    ned_from_camera: &Mat3,
    (y_i_px, z_i_px): (f64, f64),
    focal_px: f64,
) -> Option<f64> {
    let wing = wing_axis_ned(velocity_ned_fps, accel_ned_fps2)?;
    Some(span_aspect(
        &(ned_from_camera.transpose() * wing),
        y_i_px,
        z_i_px,
        focal_px,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::EulerAngles;

    /// Level flight north: the right wing points east; in a right turn (acceleration east)
    /// it dips, as the coordinated bank atan(a/g) says.
    #[test]
    fn wing_axis_banks_with_the_turn() {
        let v = Vec3::new(50.0, 0.0, 0.0);
        let level = wing_axis_ned(&v, &Vec3::zeros()).expect("moving");
        assert!((level - Vec3::new(0.0, 1.0, 0.0)).norm() < 1e-12);
        let a = 10.0;
        let turning = wing_axis_ned(&v, &Vec3::new(0.0, a, 0.0)).expect("moving");
        let bank = (a / GRAVITY_FPS2).atan();
        assert!((turning - Vec3::new(0.0, bank.cos(), bank.sin())).norm() < 1e-12);
        assert!(wing_axis_ned(&Vec3::zeros(), &Vec3::zeros()).is_none());
    }

    /// Level flight north at the shipped airframe's 50 ft/s trim (α = 4.48°): the nose is
    /// 4.48° above the horizon, the wing still east, and the velocity lies at α below the
    /// nose in the body's x-z plane.
    #[test]
    fn alpha_pitches_the_nose_above_the_velocity() {
        let v = Vec3::new(50.0, 0.0, 0.0);
        let alpha = 4.48f64.to_radians();
        let axes = pitched_by_alpha(&body_axes_ned(&v, &Vec3::zeros()).expect("moving"), alpha);
        let nose: Vec3 = axes.column(0).into();
        assert!((nose - Vec3::new(alpha.cos(), 0.0, -alpha.sin())).norm() < 1e-12);
        assert!((Vec3::from(axes.column(1)) - Vec3::y()).norm() < 1e-12);
        let v_body = axes.transpose() * v;
        assert!((v_body.z.atan2(v_body.x) - alpha).abs() < 1e-12, "{v_body}");
        assert!(v_body.y.abs() < 1e-12);
        let euler = crate::frames::EulerAngles::from_body_from_ned(&axes.transpose());
        assert!((euler.theta_rad - alpha).abs() < 1e-12, "{euler:?}");
    }

    /// Seen from behind on the optical axis the span is whole (s = 1); seen ψ off the tail
    /// it is foreshortened to cos ψ; the first-order factor matches the projection of the
    /// two wing tips off the axis.
    #[test]
    fn aspect_factor_is_the_projected_span() {
        let behind = Mat3::identity();
        let s = |ned_from_camera: &Mat3, px: (f64, f64)| {
            let v = Vec3::new(50.0, 0.0, 0.0);
            target_span_aspect(&v, &Vec3::zeros(), ned_from_camera, px, 554.0).expect("moving")
        };
        assert!((s(&behind, (0.0, 0.0)) - 1.0).abs() < 1e-12);
        let psi = 14f64.to_radians();
        let off_tail = EulerAngles::new(0.0, 0.0, psi).body_from_ned().transpose();
        assert!((s(&off_tail, (0.0, 0.0)) - psi.cos()).abs() < 1e-12);
        // Off the image centre: project the tips of an 8 ft span 300 ft ahead and 25 ft
        // above the optical axis through the sensing transform's image axes (yI right, zI
        // up), the wing with a component along the line of sight.
        let (f, depth, b) = (554.0, 300.0, 8.0);
        let centre = Vec3::new(depth, 40.0, -25.0);
        let wing = Vec3::new(0.3, 0.9, 0.1).normalize();
        let project = |p: Vec3| Vec3::new(0.0, f * p.y / p.x, -f * p.z / p.x);
        let exact = (project(centre + wing * b / 2.0) - project(centre - wing * b / 2.0)).norm();
        let model =
            f * b * span_aspect(&wing, f * centre.y / depth, -f * centre.z / depth, f) / depth;
        assert!((exact - model).abs() < 1e-3 * exact, "{exact} {model}");
    }
}
