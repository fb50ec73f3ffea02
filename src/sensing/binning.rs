//! Measuring a large target at the resolution it needs (`camera.measure_max_length_px`).
//!
//! Drawing and measuring a silhouette costs in proportion to the pixels it covers: at 1920x1080
//! the main scenario's target, 32 ft ahead, is about 415 px long and covers nine times the
//! pixels it covers at 640x480, for a maximal length that is already known to a few tenths of
//! a percent. A tracker measures such a target on binned pixels instead: k x k pixels summed
//! into one, as camera sensors bin in hardware, so that the silhouette's maximal length is at
//! most `measure_max_length_px` binned pixels. The frame is then drawn as the camera of 1/k
//! the resolution on the same optics sees it (same field of view, focal length l/k, the same
//! multisampling per binned pixel, pixel noise σ/k: the mean of k² independent draws), read
//! back, measured there, and the measurement is carried back to the image's pixels (binned
//! pixel i' covers image pixels [k i', k i' + k), so a coordinate u' is u = k u').
//!
//! What it costs in accuracy: the measurement of a 1/k-resolution camera, i.e. about k times
//! the error of the full-resolution one in image pixels, the same in proportion to the
//! target's size as a target `measure_max_length_px` long at full resolution. Small and
//! distant targets (shorter than the limit) are measured at full resolution, and saved
//! frames, acquisition and a target at the window's edge always are.

use crate::render::camera::CameraIntrinsics;
use crate::render::region::ImageRegion;
use crate::vision::{BlobMeasurement, BlobSelection, FeretDiameter, PixelBox, PixelPoint};

/// The largest binning factor (an 8x8 bin: a 1920-px wide image measured at 240 px).
pub const MAX_FACTOR: u32 = 8;

/// Chooses the binning of each frame and carries regions and measurements between scales.
#[derive(Debug, Clone, PartialEq)]
pub struct Binning {
    /// Targets predicted longer than this (px) are binned; `None`: never.
    max_length_px: Option<f64>,
    /// Factors that divide the image's width and height, ascending (1 first).
    factors: Vec<u32>,
}

impl Binning {
    /// The binning of a camera of `intrinsics` with `camera.measure_max_length_px` =
    /// `max_length_px` (0: none).
    pub fn new(intrinsics: &CameraIntrinsics, max_length_px: f64) -> Self {
        let factors = (1..=MAX_FACTOR)
            .filter(|k| binned_intrinsics(intrinsics, *k).is_some())
            .collect();
        Self {
            max_length_px: (max_length_px > 0.0).then_some(max_length_px),
            factors,
        }
    }

    /// The factor k for a target whose maximal length is predicted at `length_px` (image
    /// pixels): the largest available k with length / k no more than the limit would need
    /// (k ≤ ⌈length / limit⌉), 1 for a short target or without binning.
    pub fn factor_for(&self, length_px: f64) -> u32 {
        let Some(limit) = self.max_length_px else {
            return 1;
        };
        let wanted = (length_px / limit).ceil();
        self.factors
            .iter()
            .copied()
            .filter(|&k| f64::from(k) <= wanted)
            .max()
            .unwrap_or(1)
    }
}

/// The camera of 1/k the resolution on the same optics: width / k, height / k, focal
/// length / k; `None` unless k ≥ 1 divides both sides.
pub fn binned_intrinsics(intrinsics: &CameraIntrinsics, k: u32) -> Option<CameraIntrinsics> {
    (k >= 1 && intrinsics.width_px.is_multiple_of(k) && intrinsics.height_px.is_multiple_of(k))
        .then(|| CameraIntrinsics {
            width_px: intrinsics.width_px / k,
            height_px: intrinsics.height_px / k,
            focal_px: intrinsics.focal_px / f64::from(k),
        })
}

/// The binned pixels that cover `region` (image pixels) at factor k.
pub fn binned_region(region: &ImageRegion, k: u32) -> ImageRegion {
    let u0_px = region.u0_px / k;
    let v0_px = region.v0_px / k;
    ImageRegion {
        u0_px,
        v0_px,
        width_px: region.u_end_px().div_ceil(k) - u0_px,
        height_px: region.v_end_px().div_ceil(k) - v0_px,
    }
}

/// A blob selection in image pixels, in binned pixels of factor k.
pub fn binned_selection(selection: BlobSelection, k: u32) -> BlobSelection {
    selection.in_pixels(0.0, 0.0, f64::from(k))
}

/// A measurement in binned pixels of factor k, in image pixels: coordinates and lengths times
/// k, areas and pixel counts times k², the box the binned box's image pixels.
pub fn unbinned_measurement(blob: &BlobMeasurement, k: u32) -> BlobMeasurement {
    let scale = f64::from(k);
    let point = |p: PixelPoint| PixelPoint {
        u_px: scale * p.u_px,
        v_px: scale * p.v_px,
    };
    BlobMeasurement {
        centroid_u_px: scale * blob.centroid_u_px,
        centroid_v_px: scale * blob.centroid_v_px,
        max_length_px: scale * blob.max_length_px,
        area_px: scale * scale * blob.area_px,
        pixel_count: blob.pixel_count * (k * k) as usize,
        bbox: blob.bbox.map(|b| PixelBox {
            min_u: b.min_u * k,
            min_v: b.min_v * k,
            max_u: b.max_u * k + k - 1,
            max_v: b.max_v * k + k - 1,
        }),
        feret: blob.feret.map(|f| FeretDiameter {
            length_px: scale * f.length_px,
            start: point(f.start),
            end: point(f.end),
        }),
        ..*blob
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vision::BlobStatus;

    fn full_hd() -> CameraIntrinsics {
        CameraIntrinsics::from_hfov(1920, 1080, 60.0)
    }

    /// 1920x1080 bins by every factor to 8 but 7 (1080 = 2³ 3³ 5); 640x480 by all but 7.
    #[test]
    fn factors_divide_the_image() {
        let b = Binning::new(&full_hd(), 160.0);
        assert_eq!(b.factors, vec![1, 2, 3, 4, 5, 6, 8]);
        let coarse = binned_intrinsics(&full_hd(), 3).expect("3 divides");
        assert_eq!((coarse.width_px, coarse.height_px), (640, 360));
        assert!((coarse.focal_px - full_hd().focal_px / 3.0).abs() < 1e-12);
        assert!(binned_intrinsics(&full_hd(), 7).is_none());
    }

    /// The main scenario's target at 32 ft (415 px at 1080p) is binned by 3 (138 px); a
    /// target under the limit, or any target without binning, is not.
    #[test]
    fn factor_keeps_the_length_under_the_limit() {
        let b = Binning::new(&full_hd(), 160.0);
        assert_eq!(b.factor_for(415.0), 3);
        assert_eq!(b.factor_for(160.0), 1);
        assert_eq!(b.factor_for(161.0), 2);
        assert_eq!(b.factor_for(1100.0), 6, "7 does not divide: the next below");
        assert_eq!(b.factor_for(f64::NAN), 1);
        assert_eq!(Binning::new(&full_hd(), 0.0).factor_for(415.0), 1);
    }

    /// The binned region covers the image region; a measurement's coordinates scale back.
    #[test]
    fn regions_and_measurements_map_between_scales() {
        let r = ImageRegion {
            u0_px: 100,
            v0_px: 50,
            width_px: 301,
            height_px: 20,
        };
        let b = binned_region(&r, 3);
        assert_eq!(
            (b.u0_px, b.v0_px, b.u_end_px(), b.v_end_px()),
            (33, 16, 134, 24)
        );
        let blob = BlobMeasurement {
            status: BlobStatus::Ok,
            centroid_u_px: 50.25,
            centroid_v_px: 20.5,
            max_length_px: 40.0,
            area_px: 10.0,
            pixel_count: 12,
            bbox: Some(PixelBox {
                min_u: 30,
                min_v: 18,
                max_u: 70,
                max_v: 22,
            }),
            feret: None,
            blob_count: 1,
            background_noise_sigma: 0.0,
        };
        let full = unbinned_measurement(&blob, 3);
        assert_eq!((full.centroid_u_px, full.centroid_v_px), (150.75, 61.5));
        assert_eq!((full.max_length_px, full.area_px), (120.0, 90.0));
        let bbox = full.bbox.expect("box");
        assert_eq!(
            (bbox.min_u, bbox.max_u, bbox.min_v, bbox.max_v),
            (90, 212, 54, 68)
        );
        assert_eq!(
            binned_selection(
                BlobSelection::NearestTo {
                    u_px: 150.0,
                    v_px: 60.0,
                },
                3,
            ),
            BlobSelection::NearestTo {
                u_px: 50.0,
                v_px: 20.0,
            }
        );
        assert_eq!(
            binned_selection(
                BlobSelection::NearestWithin {
                    u_px: 150.0,
                    v_px: 60.0,
                    radius_px: 30.0,
                    length_px: 60.0,
                    length_ratio: 1.5,
                    fragment_fraction: 0.5,
                    merge_ratio: 0.0,
                    merges_measured: false,
                },
                3,
            ),
            BlobSelection::NearestWithin {
                u_px: 50.0,
                v_px: 20.0,
                radius_px: 10.0,
                length_px: 20.0,
                length_ratio: 1.5,
                fragment_fraction: 0.5,
                merge_ratio: 0.0,
                merges_measured: false,
            }
        );
    }
}
