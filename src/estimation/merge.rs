//! A merged frame's bearing (`camera.merges = "bearing"`; docs/equations.md, A merge's
//! bearing): the tracked aircraft's blob joined to another's. The joined blob holds the
//! aircraft, so its centroid says where the aircraft is to within how much longer the blob is
//! than the aircraft; its length says nothing of the aircraft's range.

use crate::frames::{Mat3, Vec3};
use crate::sensing::{scaled_position_jacobian, scaled_relative_position};
use crate::vision::ImageMeasurement;

/// A merged frame as a measurement r* and its covariance, for a camera of focal length
/// `focal_px` whose L_BEᵀ is `ned_from_camera`:
/// - r* lies along the joined blob's bearing, `joined`'s (yI, zI), at the range the filter
///   predicts (`predicted`, the pixels of its r̂ at the frame's capture);
/// - the centroid's σ² is the pixel noise's (`pixel_covariance_px2`) plus the square of half
///   the joined blob's excess length over the predicted one, (½ (bI − b̂I)⁺)²: the aircraft
///   may lie at either end of the joined blob;
/// - the length's σ is `length_sigmas` predicted lengths: the frame counts for its bearing
///   only.
pub fn merged_measurement(
    joined: &ImageMeasurement,
    predicted: &ImageMeasurement,
    pixel_covariance_px2: &Mat3,
    focal_px: f64,
    ned_from_camera: &Mat3,
    length_sigmas: f64,
) -> (Vec3, Mat3) {
    let at = ImageMeasurement {
        b_i_px: predicted.b_i_px,
        ..*joined
    };
    let r_star = scaled_relative_position(&at, focal_px, &ned_from_camera.transpose());
    let spread_px2 = (0.5 * (joined.b_i_px - predicted.b_i_px).max(0.0)).powi(2);
    let mut pixel_covariance = *pixel_covariance_px2;
    pixel_covariance[(0, 0)] += spread_px2;
    pixel_covariance[(1, 1)] += spread_px2;
    pixel_covariance[(2, 2)] = (length_sigmas * at.b_i_px).powi(2);
    let jacobian = scaled_position_jacobian(&at, focal_px, ned_from_camera);
    (r_star, jacobian * pixel_covariance * jacobian.transpose())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A joined blob 60 px long where 40 px are predicted, 10 px right of the axis: r* lies
    /// along its bearing at the predicted range (|r*| = l / 40 on the axis's scale), its
    /// lateral σ is √(1 + 10²) px at that range, and its range is left free.
    #[test]
    fn a_merge_counts_for_its_bearing_at_the_predicted_range() {
        let focal_px = 500.0;
        let pixels = |y_i_px, b_i_px| ImageMeasurement {
            y_i_px,
            z_i_px: 0.0,
            b_i_px,
        };
        let predicted = pixels(0.0, 40.0);
        let noise = Mat3::identity();
        let merge = |joined: &ImageMeasurement| {
            merged_measurement(
                joined,
                &predicted,
                &noise,
                focal_px,
                &Mat3::identity(),
                10.0,
            )
        };
        let (r, covariance) = merge(&pixels(10.0, 60.0));
        let range = (focal_px.powi(2) + 100.0).sqrt() / 40.0;
        assert!((r.norm() - range).abs() < 1e-9, "{r}");
        assert!((r.y / r.x - 10.0 / focal_px).abs() < 1e-12, "{r}");
        // Across the ray a pixel moves r by f / (b̂I √(f² + yI²)).
        let across_px = |covariance: &Mat3| {
            let across = Vec3::new(-r.y, r.x, 0.0).normalize();
            let per_px = focal_px / (40.0 * (focal_px.powi(2) + 100.0).sqrt());
            (across.transpose() * covariance * across)[(0, 0)].sqrt() / per_px
        };
        let lateral_sigma_px = across_px(&covariance);
        assert!(
            (lateral_sigma_px - 101f64.sqrt()).abs() < 0.01,
            "{lateral_sigma_px}"
        );
        let along = r.normalize();
        let range_sigma = (along.transpose() * covariance * along)[(0, 0)].sqrt();
        assert!(range_sigma > 5.0 * range, "{range_sigma}");
        // No longer than predicted: the pixel noise alone across the ray.
        let (_, covariance) = merge(&pixels(10.0, 40.0));
        assert!((across_px(&covariance) - 1.0).abs() < 1e-6);
    }
}
