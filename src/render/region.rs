//! The part of the image a frame draws, reads back and measures.
//!
//! A tracking camera need not look at the whole image: the target covers a small part of it,
//! and where it will be is predicted from the last measurement (`vision::tracking`). A frame
//! may then be drawn, read back and measured only in an [`ImageRegion`]: a rectangle of whole
//! pixels inside the image, in the image's pixel coordinates (column u right, row v down,
//! pixel (i, j) covers [i, i+1) x [j, j+1), as in [`crate::render::camera`]).

use crate::render::camera::CameraIntrinsics;

/// A rectangle of whole pixels inside the image: columns `u0_px .. u0_px + width_px`, rows
/// `v0_px .. v0_px + height_px`; never empty.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ImageRegion {
    /// First column, px.
    pub u0_px: u32,
    /// First row, px.
    pub v0_px: u32,
    /// Width, px (≥ 1).
    pub width_px: u32,
    /// Height, px (≥ 1).
    pub height_px: u32,
}

impl ImageRegion {
    /// The whole image of `intrinsics`.
    pub fn whole(intrinsics: &CameraIntrinsics) -> Self {
        Self {
            u0_px: 0,
            v0_px: 0,
            width_px: intrinsics.width_px,
            height_px: intrinsics.height_px,
        }
    }

    /// The pixels that overlap the continuous box [u_min, u_max] x [v_min, v_max] (px), cut
    /// to the image of `intrinsics`; `None` when the box is not finite or misses the image.
    pub fn covering(
        u_min_px: f64,
        u_max_px: f64,
        v_min_px: f64,
        v_max_px: f64,
        intrinsics: &CameraIntrinsics,
    ) -> Option<Self> {
        let axis = |lo: f64, hi: f64, len: u32| -> Option<(u32, u32)> {
            if !(lo.is_finite() && hi.is_finite()) {
                return None;
            }
            let first = lo.floor().max(0.0);
            let end = hi.ceil().min(f64::from(len));
            (end > first).then_some((first as u32, (end - first) as u32))
        };
        let (u0_px, width_px) = axis(u_min_px, u_max_px, intrinsics.width_px)?;
        let (v0_px, height_px) = axis(v_min_px, v_max_px, intrinsics.height_px)?;
        Some(Self {
            u0_px,
            v0_px,
            width_px,
            height_px,
        })
    }

    /// Whether this is the whole image of `intrinsics`.
    pub fn is_whole(&self, intrinsics: &CameraIntrinsics) -> bool {
        *self == Self::whole(intrinsics)
    }

    /// Number of pixels.
    pub fn pixel_count(&self) -> usize {
        self.width_px as usize * self.height_px as usize
    }

    /// One past the last column, px.
    pub fn u_end_px(&self) -> u32 {
        self.u0_px + self.width_px
    }

    /// One past the last row, px.
    pub fn v_end_px(&self) -> u32 {
        self.v0_px + self.height_px
    }

    /// The region's edges that lie inside the image of `intrinsics` (not on its border):
    /// left, top, right, bottom. A measurement that reaches one of them may have missed
    /// pixels beyond it.
    pub fn inner_edges(&self, intrinsics: &CameraIntrinsics) -> [bool; 4] {
        [
            self.u0_px > 0,
            self.v0_px > 0,
            self.u_end_px() < intrinsics.width_px,
            self.v_end_px() < intrinsics.height_px,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A box is widened to whole pixels and cut to the image; boxes off the image or not
    /// finite give no region.
    #[test]
    fn covering_box_is_cut_to_the_image() {
        let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
        assert_eq!(
            ImageRegion::covering(10.5, 20.2, 30.0, 40.0, &cam),
            Some(ImageRegion {
                u0_px: 10,
                v0_px: 30,
                width_px: 11,
                height_px: 10
            })
        );
        let cut = ImageRegion::covering(-5.0, 700.0, 470.5, 490.0, &cam);
        assert_eq!(
            cut,
            Some(ImageRegion {
                u0_px: 0,
                v0_px: 470,
                width_px: 640,
                height_px: 10
            })
        );
        assert_eq!(
            cut.map(|r| r.inner_edges(&cam)),
            Some([false, true, false, false])
        );
        assert_eq!(ImageRegion::covering(650.0, 700.0, 0.0, 10.0, &cam), None);
        assert_eq!(ImageRegion::covering(f64::NAN, 7.0, 0.0, 10.0, &cam), None);
        let whole = ImageRegion::covering(-1.0, 641.0, -1.0, 481.0, &cam);
        assert!(whole.is_some_and(|r| r.is_whole(&cam) && r.pixel_count() == 640 * 480));
    }
}
