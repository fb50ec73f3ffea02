//! What the image pipeline can be told: where the background colour comes from, the target's
//! colour, when a pixel counts as target, which blob to measure and how small is too small.

use thiserror::Error;

/// Where the background colour of each pixel comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BackgroundSource {
    /// Fit a smooth colour surface (per channel, quadratic in u and v) to the pixels within
    /// `border_px` of the image edge, rejecting outliers such as a target crossing the border.
    /// Exact for a uniform background and for linear or quadratic gradients in any direction
    /// (a sky gradient seen from a banked aircraft is tilted in the image).
    BorderFit {
        /// Width of the border ring the background is fitted to, px (≥ 1).
        border_px: u32,
    },
    /// A known uniform background colour; the border is then only used to estimate the noise.
    Fixed {
        /// Background colour, RGB 0-255.
        rgb: [u8; 3],
    },
}

/// The colour of a fully covered target pixel, which sets the full contrast against which a
/// partly covered (anti-aliased) pixel's coverage is measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TargetColour {
    /// Per-channel median of the candidate pixels whose 8 neighbours are all candidates
    /// (the silhouette's interior, free of anti-aliased edges).
    Estimated,
    /// A known target colour.
    Fixed {
        /// Target colour, RGB 0-255.
        rgb: [u8; 3],
    },
}

/// When a pixel differs enough from the background to be a target candidate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DetectionThreshold {
    /// `sigmas` times the background noise (per-channel standard deviation estimated from the
    /// border) as a Euclidean RGB distance, and at least `min_distance` grey levels.
    NoiseSigmas {
        /// Multiple of the per-channel noise σ (> 0). With 3 channels the squared distance of
        /// a background pixel is σ²·χ²(3): 6σ gives ~1e-7 false candidates per pixel.
        sigmas: f64,
        /// Lower bound on the threshold, grey levels (≥ 0): keeps noise-free images from
        /// classifying rounding differences.
        min_distance: f64,
    },
    /// A fixed Euclidean RGB distance from the background, grey levels (> 0).
    ColourDistance {
        /// Threshold distance, grey levels.
        distance: f64,
    },
}

/// How pixels are classified as target or background.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentationConfig {
    /// Background colour model.
    pub background: BackgroundSource,
    /// Colour of a fully covered target pixel.
    pub target_colour: TargetColour,
    /// Candidate threshold.
    pub detection: DetectionThreshold,
    /// A candidate pixel is in the binary mask when its coverage is at least this, in (0, 1]
    /// (0.5: more than half the pixel is target), or when its 8 neighbours are candidates too.
    pub mask_coverage: f64,
}

impl Default for SegmentationConfig {
    fn default() -> Self {
        Self {
            background: BackgroundSource::BorderFit { border_px: 2 },
            target_colour: TargetColour::Estimated,
            detection: DetectionThreshold::NoiseSigmas {
                sigmas: 6.0,
                min_distance: 8.0,
            },
            mask_coverage: 0.5,
        }
    }
}

/// Which connected blob is measured when there are several.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BlobSelection {
    /// The blob with the most mask pixels.
    Largest,
    /// The blob whose pixel-centre mean is nearest to this point (e.g. the previous centroid).
    NearestTo {
        /// Column of the point, px.
        u_px: f64,
        /// Row of the point, px.
        v_px: f64,
    },
    /// Among the blobs whose pixel-centre mean lies within `radius_px` of this point and
    /// whose box lies within the square of that half side (a gate about a prediction), the
    /// one most like the prediction: least (d / radius)² + (ln(max(e / length, φ)) / ln ρ)²,
    /// d its distance from the point, e the longer side of its box, `length_px` the expected
    /// maximal length, ρ `length_ratio` (either 0: sizes not compared, the nearest) and φ
    /// `fragment_fraction` (a blob shorter than φ of the expected length is a fragment, and
    /// fragments differ by their distance alone; 0: every size counts); none when no blob lies
    /// inside the gate, or when a joined blob is more like the prediction than every blob
    /// inside (the target joined to something else: it is there, unmeasured, and no lesser
    /// blob stands in for it). A blob is joined when it is centred within the radius and
    /// reaches beyond the square, or its box's longer side exceeds `merge_ratio` times the
    /// expected length (longer than the target alone can be; 0: not judged by length). With
    /// `merges_measured` a joined blob more like the prediction than every blob inside (or
    /// alone in the gate) is measured instead, as `BlobStatus::Merged`.
    NearestWithin {
        /// Column of the point, px.
        u_px: f64,
        /// Row of the point, px.
        v_px: f64,
        /// The gate's radius, px.
        radius_px: f64,
        /// The expected maximal length, px (0: unknown).
        length_px: f64,
        /// The ratio of a blob's extent to `length_px` that weighs as much as the gate's
        /// radius (0: sizes not compared).
        length_ratio: f64,
        /// The fraction of `length_px` below which a blob's size counts as this fraction's
        /// (0: every size counts).
        fragment_fraction: f64,
        /// The ratio of a blob's extent to `length_px` beyond which it is the target joined
        /// to another (0: merges told by the gate's square alone).
        merge_ratio: f64,
        /// Whether a merge is measured (`BlobStatus::Merged`: its bearing holds the target,
        /// its length does not) rather than measuring nothing.
        merges_measured: bool,
    },
}

impl BlobSelection {
    /// The same selection in pixels whose origin is at (`u0_px`, `v0_px`) and which are
    /// `scale` image pixels each (a region's, or binned pixels).
    pub fn in_pixels(self, u0_px: f64, v0_px: f64, scale: f64) -> Self {
        let at = |u_px: f64, v_px: f64| ((u_px - u0_px) / scale, (v_px - v0_px) / scale);
        match self {
            Self::Largest => Self::Largest,
            Self::NearestTo { u_px, v_px } => {
                let (u_px, v_px) = at(u_px, v_px);
                Self::NearestTo { u_px, v_px }
            }
            Self::NearestWithin {
                u_px,
                v_px,
                radius_px,
                length_px,
                length_ratio,
                fragment_fraction,
                merge_ratio,
                merges_measured,
            } => {
                let (u_px, v_px) = at(u_px, v_px);
                Self::NearestWithin {
                    u_px,
                    v_px,
                    radius_px: radius_px / scale,
                    length_px: length_px / scale,
                    length_ratio,
                    fragment_fraction,
                    merge_ratio,
                    merges_measured,
                }
            }
        }
    }
}

/// Everything the image pipeline is configured with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VisionConfig {
    /// Pixel classification.
    pub segmentation: SegmentationConfig,
    /// Blobs with fewer mask pixels than this are not selected; when no blob has this many the
    /// measurement is `TooSmall` (≥ 1).
    pub min_pixel_count: usize,
    /// Mask pixels up to this many pixels apart (in u and in v) belong to one blob (1:
    /// 8-connectivity; ≥ 1). Thin parts of a distant target seen edge-on rasterise as broken
    /// lines; 2 keeps them with the body they belong to.
    pub link_radius_px: usize,
    /// Measure colour distances against each pixel's own background, from the previous frame
    /// turned by the camera's rotation and the border's colours (`super::reference`), instead
    /// of a colour surface fitted to the border.
    pub motion_reference: bool,
    /// With `motion_reference`: a pixel the remembered background does not explain is
    /// target only as a mixture of a background colour around it and a shade of the target's
    /// colour, learned from the blobs measured on it, to within this angle in RGB, deg
    /// (`super::target_colour`); 0: no colour test.
    pub target_colour_tolerance_deg: f64,
}

impl Default for VisionConfig {
    fn default() -> Self {
        Self {
            segmentation: SegmentationConfig::default(),
            min_pixel_count: 4,
            link_radius_px: 1,
            motion_reference: false,
            target_colour_tolerance_deg: 0.0,
        }
    }
}

/// A configuration value outside its allowed range.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum VisionConfigError {
    /// `border_px` of `BorderFit` is 0.
    #[error("vision background border_px must be at least 1, got 0")]
    ZeroBorder,
    /// `mask_coverage` outside (0, 1].
    #[error("vision mask_coverage must be in (0, 1], got {0}")]
    MaskCoverage(f64),
    /// `sigmas` not finite and positive.
    #[error("vision detection sigmas must be finite and > 0, got {0}")]
    DetectionSigmas(f64),
    /// `min_distance` not finite and non-negative.
    #[error("vision detection min_distance must be finite and >= 0 grey levels, got {0}")]
    DetectionMinDistance(f64),
    /// `distance` not finite and positive.
    #[error("vision detection distance must be finite and > 0 grey levels, got {0}")]
    DetectionDistance(f64),
    /// `min_pixel_count` is 0.
    #[error("vision min_pixel_count must be at least 1, got 0")]
    ZeroMinPixelCount,
    /// `target_colour_tolerance_deg` outside [0, 90).
    #[error("vision target_colour_tolerance_deg must be in [0, 90) deg, got {0}")]
    TargetColourTolerance(f64),
}

impl VisionConfig {
    /// Checks every value against its allowed range.
    pub fn validate(&self) -> Result<(), VisionConfigError> {
        let seg = &self.segmentation;
        if let BackgroundSource::BorderFit { border_px: 0 } = seg.background {
            return Err(VisionConfigError::ZeroBorder);
        }
        if !(seg.mask_coverage > 0.0 && seg.mask_coverage <= 1.0) {
            return Err(VisionConfigError::MaskCoverage(seg.mask_coverage));
        }
        match seg.detection {
            DetectionThreshold::NoiseSigmas {
                sigmas,
                min_distance,
            } => {
                if !(sigmas.is_finite() && sigmas > 0.0) {
                    return Err(VisionConfigError::DetectionSigmas(sigmas));
                }
                if !(min_distance.is_finite() && min_distance >= 0.0) {
                    return Err(VisionConfigError::DetectionMinDistance(min_distance));
                }
            }
            DetectionThreshold::ColourDistance { distance } => {
                if !(distance.is_finite() && distance > 0.0) {
                    return Err(VisionConfigError::DetectionDistance(distance));
                }
            }
        }
        if self.min_pixel_count == 0 {
            return Err(VisionConfigError::ZeroMinPixelCount);
        }
        let tolerance = self.target_colour_tolerance_deg;
        if !(0.0..90.0).contains(&tolerance) {
            return Err(VisionConfigError::TargetColourTolerance(tolerance));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The defaults are valid; each out-of-range value is reported, NaN included.
    #[test]
    fn validation_names_bad_values() {
        assert_eq!(VisionConfig::default().validate(), Ok(()));
        let mut c = VisionConfig::default();
        c.segmentation.mask_coverage = f64::NAN;
        assert!(matches!(
            c.validate(),
            Err(VisionConfigError::MaskCoverage(_))
        ));
        let mut c = VisionConfig::default();
        c.segmentation.background = BackgroundSource::BorderFit { border_px: 0 };
        assert_eq!(c.validate(), Err(VisionConfigError::ZeroBorder));
        let mut c = VisionConfig::default();
        c.segmentation.detection = DetectionThreshold::ColourDistance { distance: -1.0 };
        assert_eq!(
            c.validate(),
            Err(VisionConfigError::DetectionDistance(-1.0))
        );
        let c = VisionConfig {
            min_pixel_count: 0,
            ..VisionConfig::default()
        };
        assert_eq!(c.validate(), Err(VisionConfigError::ZeroMinPixelCount));
        let c = VisionConfig {
            target_colour_tolerance_deg: 90.0,
            ..VisionConfig::default()
        };
        assert_eq!(
            c.validate(),
            Err(VisionConfigError::TargetColourTolerance(90.0))
        );
    }
}
