//! Centroid, area and maximal length of one labelled blob, from coverage weights.
//!
//! Weights: a blob pixel whose 8 neighbours are all in the blob is fully covered (1); a blob
//! pixel on the blob's boundary and an unlabelled pixel touching the blob (the ring, where
//! anti-aliased edge pixels below the mask threshold are) get their coverage α. The centroid is
//! the first moment of these weights, so partly covered pixels count by the area they hold.
//!
//! Maximal length: each boundary or ring pixel with coverage above the noise gives one
//! sub-pixel edge point, its centre moved along the edge normal (the coverage gradient) by the
//! offset at which a straight edge covers that fraction of the pixel
//! ([`super::subpixel_edge::edge_offset_px`]). The maximum Feret diameter of these points
//! estimates the silhouette's, where pixel centres of the mask would fall short by about a pixel
//! (half a pixel at each end). Pixels with coverage ≈ 0 are left out: their offset says only
//! that the edge lies beyond the pixel, which would overshoot by up to half a pixel.

use super::components::PixelBox;
use super::feret::{FeretDiameter, FeretFinder, PixelPoint};
use super::frame::RgbaFrame;
use super::segment::CoverageModel;
use super::subpixel_edge::edge_offset_px;

/// Ring pixels on the image border with at least this coverage mean the target crosses the
/// border (0.25: far above the noise of a 1-px gap, which is debiased to ≈ 0).
const TRUNCATION_COVERAGE: f64 = 0.25;

const OUTSIDE: u8 = 0;
const RING: u8 = 1;
const BOUNDARY: u8 = 2;
const INTERIOR: u8 = 3;

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
    pub coverage: &'a CoverageModel,
    /// Edge points need at least this coverage (above the noise).
    pub edge_min_coverage: f64,
}

/// Measures blobs; owns its weight and point buffers between frames.
#[derive(Debug, Default, Clone)]
pub(crate) struct BlobMeasurer {
    weights: Vec<f32>,
    kinds: Vec<u8>,
    edge_points: Vec<PixelPoint>,
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
    /// Measures `blob` in `frame`.
    pub fn measure(&mut self, frame: &RgbaFrame<'_>, blob: &BlobToMeasure<'_>) -> BlobGeometry {
        let (w, h) = (frame.width, frame.height);
        // Weights live on the bbox + 2 (ring + one more for the gradient stencil).
        let region = Region::around(blob.bbox, 2, w, h);
        self.weights.clear();
        self.weights.resize(region.width * region.height, 0.0);
        self.kinds.clear();
        self.kinds.resize(region.width * region.height, OUTSIDE);
        let labels = blob.labels;
        let label_at = |u: isize, v: isize| -> u32 {
            if u < 0 || v < 0 || u >= w as isize || v >= h as isize {
                0
            } else {
                labels[v as usize * w + u as usize]
            }
        };
        let inner = Region::around(blob.bbox, 1, w, h);
        let (mut sum_w, mut sum_wu, mut sum_wv) = (0.0, 0.0, 0.0);
        let mut truncated = false;
        for v in inner.v0..inner.v0 + inner.height {
            for u in inner.u0..inner.u0 + inner.width {
                let idx = v * w + u;
                let own = labels[idx];
                let (ui, vi) = (u as isize, v as isize);
                let mut blob_neighbours = 0;
                for dv in -1..=1 {
                    for du in -1..=1 {
                        if (du, dv) != (0, 0) && label_at(ui + du, vi + dv) == blob.label {
                            blob_neighbours += 1;
                        }
                    }
                }
                let kind = if own == blob.label {
                    if blob_neighbours == 8 {
                        INTERIOR
                    } else {
                        BOUNDARY
                    }
                } else if own == 0 && blob_neighbours > 0 {
                    RING
                } else {
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
                self.weights[local] = weight as f32;
                self.kinds[local] = kind;
                sum_w += weight;
                sum_wu += weight * (u as f64 + 0.5);
                sum_wv += weight * (v as f64 + 0.5);
            }
        }
        let (centroid_u_px, centroid_v_px) = if sum_w > 0.0 {
            (sum_wu / sum_w, sum_wv / sum_w)
        } else {
            (
                0.5 * f64::from(blob.bbox.min_u + blob.bbox.max_u + 1),
                0.5 * f64::from(blob.bbox.min_v + blob.bbox.max_v + 1),
            )
        };
        self.collect_edge_points(region, blob.edge_min_coverage);
        BlobGeometry {
            centroid_u_px,
            centroid_v_px,
            area_px: sum_w,
            feret: self.feret.diameter(&mut self.edge_points),
            truncated,
        }
    }

    /// One sub-pixel edge point per boundary or ring pixel covered at least `min_coverage`;
    /// normals from a Sobel gradient of the weights (replicated at the region's edge).
    fn collect_edge_points(&mut self, region: Region, min_coverage: f64) {
        self.edge_points.clear();
        let (rw, rh) = (region.width as isize, region.height as isize);
        let weight = |x: isize, y: isize| -> f64 {
            let x = x.clamp(0, rw - 1) as usize;
            let y = y.clamp(0, rh - 1) as usize;
            f64::from(self.weights[y * region.width + x])
        };
        for y in 0..rh {
            for x in 0..rw {
                let local = y as usize * region.width + x as usize;
                let kind = self.kinds[local];
                let alpha = f64::from(self.weights[local]);
                if !(kind == BOUNDARY || kind == RING) || alpha < min_coverage {
                    continue;
                }
                let gx = weight(x + 1, y - 1) + 2.0 * weight(x + 1, y) + weight(x + 1, y + 1)
                    - weight(x - 1, y - 1)
                    - 2.0 * weight(x - 1, y)
                    - weight(x - 1, y + 1);
                let gy = weight(x - 1, y + 1) + 2.0 * weight(x, y + 1) + weight(x + 1, y + 1)
                    - weight(x - 1, y - 1)
                    - 2.0 * weight(x, y - 1)
                    - weight(x + 1, y - 1);
                // Outward normal: coverage decreases outward.
                let norm = gx.hypot(gy);
                let (nx, ny) = if norm > 1e-9 {
                    (-gx / norm, -gy / norm)
                } else {
                    (0.0, 0.0)
                };
                let s = edge_offset_px(alpha, nx, ny);
                let cu = (region.u0 + x as usize) as f64 + 0.5;
                let cv = (region.v0 + y as usize) as f64 + 0.5;
                self.edge_points
                    .push(PixelPoint::new(cu + s * nx, cv + s * ny));
            }
        }
    }
}
