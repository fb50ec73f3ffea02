//! Centroid, area and maximal length of one labelled blob, from coverage weights.
//!
//! Weights: a blob pixel whose 8 neighbours are all in the blob is fully covered (1); a blob
//! pixel on the blob's boundary and an unlabelled pixel touching the blob (the ring, where
//! anti-aliased edge pixels below the mask threshold are) get their coverage α. The centroid is
//! the first moment of these weights, so partly covered pixels count by the area they hold.
//!
//! Maximal length: the maximum Feret diameter of the blob's sub-pixel outline points
//! (`super::edge_points`), where pixel centres of the mask would fall short by about a pixel
//! (half a pixel at each end).

use super::components::PixelBox;
use super::edge_points::{CoverageGrid, EdgePointFinder};
use super::feret::{FeretDiameter, FeretFinder, PixelPoint};
use super::image_view::RgbaView;
use super::segment::CoverageModel;

/// Ring pixels on the image border with at least this coverage mean the target crosses the
/// border (0.25: far above the noise of a 1-px gap, which is debiased to ≈ 0).
const TRUNCATION_COVERAGE: f64 = 0.25;

const RING: u8 = 1;
const BOUNDARY: u8 = 2;
const INTERIOR: u8 = 3;

/// The 8 neighbours of a pixel, (du, dv).
const NEIGHBOURS: [(isize, isize); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// What pixel (u, v) of a `w` x `h` frame is to the blob `label`: [`INTERIOR`] (in the blob,
/// with its 8 neighbours), [`BOUNDARY`] (in the blob, not all its neighbours), [`RING`] (in no
/// blob, beside this one), or `None` (in another blob, or not beside this one).
fn pixel_kind(labels: &[u32], w: usize, h: usize, u: usize, v: usize, label: u32) -> Option<u8> {
    let idx = v * w + u;
    let own = labels[idx];
    if own != label && own != 0 {
        return None;
    }
    let inside_frame = u > 0 && v > 0 && u + 1 < w && v + 1 < h;
    let in_blob = |&(du, dv): &(isize, isize)| {
        if inside_frame {
            // All 8 neighbours are in the frame: no bounds to check.
            labels[(idx as isize + dv * w as isize + du) as usize] == label
        } else {
            let (x, y) = (u as isize + du, v as isize + dv);
            x >= 0
                && y >= 0
                && x < w as isize
                && y < h as isize
                && labels[y as usize * w + x as usize] == label
        }
    };
    if own == label {
        Some(if NEIGHBOURS.iter().all(in_blob) {
            INTERIOR
        } else {
            BOUNDARY
        })
    } else {
        NEIGHBOURS.iter().any(in_blob).then_some(RING)
    }
}

/// What the moments and the edge points say about one blob.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BlobGeometry {
    /// Weighted centroid, column, px.
    pub centroid_u_px: f64,
    /// Weighted centroid, row, px.
    pub centroid_v_px: f64,
    /// Sum of the coverage weights, px².
    pub area_px: f64,
    /// Maximum Feret diameter of the sub-pixel edge points.
    pub feret: Option<FeretDiameter>,
    /// The blob or its covered ring touches the image border.
    pub truncated: bool,
}

/// The blob to measure and what its pixels are measured with.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BlobToMeasure<'a> {
    /// Final labels of the frame (blob index + 1, 0 outside the mask).
    pub labels: &'a [u32],
    /// Label of the blob.
    pub label: u32,
    /// Bounding box of the blob's mask pixels.
    pub bbox: PixelBox,
    /// Coverage of any pixel.
    pub coverage: &'a CoverageModel<'a>,
    /// Edge points need at least this coverage (above the noise).
    pub edge_min_coverage: f64,
    /// How far a corner model's predicted coverage may be from a measured one.
    pub corner_tolerance: f64,
}

/// Measures blobs; owns its weight and point buffers between frames.
#[derive(Debug, Default, Clone)]
pub(crate) struct BlobMeasurer {
    grid: CoverageGrid,
    edge_points: Vec<PixelPoint>,
    finder: EdgePointFinder,
    feret: FeretFinder,
}

/// Inclusive rectangle of pixels.
#[derive(Debug, Clone, Copy)]
struct Region {
    u0: usize,
    v0: usize,
    width: usize,
    height: usize,
}

impl Region {
    /// `bbox` grown by `margin` on every side, clipped to a `w` x `h` image.
    fn around(bbox: PixelBox, margin: usize, w: usize, h: usize) -> Self {
        let u0 = (bbox.min_u as usize).saturating_sub(margin);
        let v0 = (bbox.min_v as usize).saturating_sub(margin);
        let u1 = (bbox.max_u as usize + margin).min(w.saturating_sub(1));
        let v1 = (bbox.max_v as usize + margin).min(h.saturating_sub(1));
        Self {
            u0,
            v0,
            width: u1 + 1 - u0,
            height: v1 + 1 - v0,
        }
    }
}

impl BlobMeasurer {
    /// Measures `blob` (its box in the frame's own pixels) in `frame`; the centroid and the
    /// outline points are in image coordinates (the frame's origin added before any
    /// arithmetic, so that a region of an image gives the image's numbers to the bit).
    pub fn measure(&mut self, frame: &RgbaView<'_>, blob: &BlobToMeasure<'_>) -> BlobGeometry {
        let (w, h) = (frame.width, frame.height);
        let [ou, ov] = frame.origin;
        // Weights live on the bbox + 2 (ring + one more for the gradient stencil).
        let region = Region::around(blob.bbox, 2, w, h);
        self.grid
            .reset(ou + region.u0, ov + region.v0, region.width, region.height);
        let inner = Region::around(blob.bbox, 1, w, h);
        let (mut sum_w, mut sum_wu, mut sum_wv) = (0.0, 0.0, 0.0);
        let mut truncated = false;
        for v in inner.v0..inner.v0 + inner.height {
            for u in inner.u0..inner.u0 + inner.width {
                let idx = v * w + u;
                let Some(kind) = pixel_kind(blob.labels, w, h, u, v, blob.label) else {
                    continue;
                };
                let weight = if kind == INTERIOR {
                    1.0
                } else {
                    blob.coverage.coverage(frame, idx, u, v)
                };
                let on_border = u == 0 || v == 0 || u + 1 == w || v + 1 == h;
                if on_border && (kind != RING || weight >= TRUNCATION_COVERAGE) {
                    truncated = true;
                }
                let local = (v - region.v0) * region.width + (u - region.u0);
                self.grid.weights[local] = weight as f32;
                self.grid.is_edge[local] = kind != INTERIOR;
                sum_w += weight;
                sum_wu += weight * ((ou + u) as f64 + 0.5);
                sum_wv += weight * ((ov + v) as f64 + 0.5);
            }
        }
        let (centroid_u_px, centroid_v_px) = if sum_w > 0.0 {
            (sum_wu / sum_w, sum_wv / sum_w)
        } else {
            (
                (ou as f64) + 0.5 * f64::from(blob.bbox.min_u + blob.bbox.max_u + 1),
                (ov as f64) + 0.5 * f64::from(blob.bbox.min_v + blob.bbox.max_v + 1),
            )
        };
        self.finder.find(
            &self.grid,
            blob.edge_min_coverage,
            blob.corner_tolerance,
            &mut self.edge_points,
        );
        BlobGeometry {
            centroid_u_px,
            centroid_v_px,
            area_px: sum_w,
            feret: self.feret.diameter(&mut self.edge_points),
            truncated,
        }
    }
}
