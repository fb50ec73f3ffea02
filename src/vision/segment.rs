//! Pixel classification: candidates (colour distance to the background above a threshold),
//! the silhouette's core (candidates whose 8 neighbours are candidates), the target colour,
//! each pixel's coverage and the binary mask that connected components run on.
//!
//! Coverage of a pixel whose colour is p, background B and full target colour T:
//! α = sqrt(max(|p − B|² − 3σ², 0)) / |T − B|, clamped to [0, 1]. For an anti-aliased pixel
//! p = αT + (1 − α)B + n, so |p − B|² = α²|T − B|² + 2α(T − B)·n + |n|², whose mean is
//! α²|T − B|² + 3σ²: subtracting 3σ² removes the noise's bias on average, and the distance
//! (unlike a projection on T − B) still sees shaded target pixels of another hue.

use super::background::BackgroundModel;
use super::config::{DetectionThreshold, SegmentationConfig, TargetColour};
use super::image_view::RgbaView;

/// Without core pixels, the target colour is the median of this fraction of the candidates,
/// those farthest from the background.
const FULL_CONTRAST_FRACTION: f64 = 0.1;
/// The least coverage of a core pixel by the learned target colour, as a mixture with its
/// own background, that keeps it in the mask: above the 0.1-0.22 that a background whose
/// brightness changed by 7-12 grey levels since the memory saw it reads (formation_scene.toml,
/// a field beside the target at the slot; docs/findings.md, A changed background inside the
/// blob).
const MIN_CORE_COVERAGE: f64 = 0.3;

/// Flag: colour distance to the background is at least the detection threshold.
pub(crate) const CANDIDATE: u8 = 1;
/// Flag: candidate whose 8 neighbours are all candidates (fully covered interior).
pub(crate) const CORE: u8 = 2;
/// Flag: in the binary mask (core, or candidate with coverage ≥ `mask_coverage`).
pub(crate) const MASK: u8 = 4;

/// Turns a pixel's colour into the fraction of it covered by the target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CoverageModel<'a> {
    /// Background colour model of the frame.
    pub background: BackgroundModel,
    /// Each pixel's own background colour, row-major (`camera.segmentation = "motion"`,
    /// `super::reference`); the model's surface when None.
    pub reference: Option<&'a [[f32; 3]]>,
    /// Width of the frame, px (to index `reference`).
    pub width: usize,
    /// Colour of a fully covered target pixel, grey levels.
    pub target_rgb: [f64; 3],
    /// Candidate threshold (Euclidean RGB distance), grey levels.
    pub threshold: f64,
    /// Whether `target_rgb` was learned from earlier frames and each pixel has its own
    /// background (`reference`): a core pixel's coverage is then its mixture of the two
    /// ([`CoverageModel::core_is_target`]).
    pub learned_over_reference: bool,
}

impl CoverageModel<'_> {
    /// The background colour of pixel (u, v) = index `idx`.
    pub fn background_at(&self, idx: usize, u: usize, v: usize) -> [f64; 3] {
        match self.reference {
            Some(reference) => reference[idx].map(f64::from),
            None => self.background.colour_at(u as f64 + 0.5, v as f64 + 0.5),
        }
    }

    /// The background colour at pixel position (u, v) (the pixel holding it).
    pub fn background_near(&self, u_px: f64, v_px: f64) -> [f64; 3] {
        match self.reference {
            Some(reference) if self.width > 0 && !reference.is_empty() => {
                let height = reference.len() / self.width;
                let u = (u_px.max(0.0) as usize).min(self.width - 1);
                let v = (v_px.max(0.0) as usize).min(height.max(1) - 1);
                self.background_at(v * self.width + u, u, v)
            }
            _ => self.background.colour_at(u_px, v_px),
        }
    }

    /// Coverage α in [0, 1] of pixel (u, v) = index `idx` of `frame`.
    pub fn coverage(&self, frame: &RgbaView<'_>, idx: usize, u: usize, v: usize) -> f64 {
        let p = frame.rgb(idx);
        let b = self.background_at(idx, u, v);
        let mut d2 = 0.0;
        let mut contrast2 = 0.0;
        for c in 0..3 {
            d2 += (p[c] - b[c]) * (p[c] - b[c]);
            contrast2 += (self.target_rgb[c] - b[c]) * (self.target_rgb[c] - b[c]);
        }
        // A target colour close to the background would make every difference "full": the
        // contrast is never taken below the detection threshold.
        let contrast2 = contrast2.max(self.threshold * self.threshold);
        let sigma = self.background.noise_sigma;
        let excess = (d2 - 3.0 * sigma * sigma).max(0.0);
        (excess / contrast2).sqrt().min(1.0)
    }

    /// Whether a core pixel (a candidate among candidates) at index `idx` belongs in the
    /// mask: always, but where the target's colour was learned over a per-pixel background,
    /// only when it is a mixture covered at least [`MIN_CORE_COVERAGE`] ([`mixture_coverage`]),
    /// whatever its distance coverage. A background that changed since the memory saw it (a
    /// field 7-12 grey levels darker) is a mixture of 0.1-0.22, and a region of it beside the
    /// target made a blob's interior, each pixel weighing 1 in the centroid.
    pub fn core_is_target(&self, frame: &RgbaView<'_>, idx: usize, u: usize, v: usize) -> bool {
        if !self.learned_over_reference {
            return true;
        }
        let background = self.background_at(idx, u, v);
        mixture_coverage(self.target_rgb, background, frame.rgb(idx))
            .is_none_or(|coverage| coverage >= MIN_CORE_COVERAGE)
    }
}

/// x · y of two RGB colours.
pub(crate) fn dot(x: [f32; 3], y: [f32; 3]) -> f32 {
    x[0] * y[0] + x[1] * y[1] + x[2] * y[2]
}

/// The background's share b of `pixel` = a T + b B + residual, the least-squares mixture of
/// the target's colour T (`target_rgb`, any shade a) and `background` B; None where T and B
/// span no plane (a background of the target's own hue).
pub(crate) fn background_share(
    target_rgb: [f32; 3],
    background: [f32; 3],
    pixel: [f32; 3],
) -> Option<f32> {
    let t = target_rgb;
    let (tt, tb, bb) = (dot(t, t), dot(t, background), dot(background, background));
    let det = tt * bb - tb * tb;
    (det > 1e-6 * tt * bb).then(|| (dot(background, pixel) * tt - dot(t, pixel) * tb) / det)
}

/// The coverage 1 − b of `pixel` by a shade of the target's colour `target_rgb` over
/// `background` (the least-squares mixture, [`background_share`]), within [0, 1]; None where
/// the two colours span no plane. Unlike the distance from the background against the
/// target's contrast, it reads a lit or shaded face whole and a background that changed
/// brightness (a field's haze since the memory saw it) as barely covered.
fn mixture_coverage(target_rgb: [f64; 3], background: [f64; 3], pixel: [f64; 3]) -> Option<f64> {
    let f = |x: [f64; 3]| x.map(|c| c as f32);
    background_share(f(target_rgb), f(background), f(pixel))
        .map(|b| f64::from(1.0 - b).clamp(0.0, 1.0))
}

/// Classifies the pixels of a frame; owns the per-pixel flags and pixel lists between frames.
#[derive(Debug, Clone)]
pub(crate) struct Segmenter {
    /// Per-pixel flags ([`CANDIDATE`], [`CORE`], [`MASK`]), row-major.
    pub class: Vec<u8>,
    /// Indices of candidate pixels, in raster order.
    pub candidates: Vec<u32>,
    /// Indices of mask pixels, in raster order.
    pub mask: Vec<u32>,
    row_words: Vec<u32>,
    distances: Vec<f64>,
    scratch: Vec<f64>,
    histogram: [[u32; 256]; 3],
}

impl Default for Segmenter {
    fn default() -> Self {
        Self {
            class: Vec::new(),
            candidates: Vec::new(),
            mask: Vec::new(),
            row_words: Vec::new(),
            distances: Vec::new(),
            scratch: Vec::new(),
            histogram: [[0; 256]; 3],
        }
    }
}

/// Candidate threshold for a background whose per-channel noise is `noise_sigma`.
fn detection_threshold(detection: DetectionThreshold, noise_sigma: f64) -> f64 {
    match detection {
        DetectionThreshold::NoiseSigmas {
            sigmas,
            min_distance,
        } => (sigmas * noise_sigma).max(min_distance),
        DetectionThreshold::ColourDistance { distance } => distance,
    }
}

/// Per-channel median colour of the pixels `indices` of `frame` (0 when there are none).
fn median_colour(
    frame: &RgbaView<'_>,
    indices: impl Iterator<Item = usize>,
    histogram: &mut [[u32; 256]; 3],
) -> [f64; 3] {
    *histogram = [[0; 256]; 3];
    let mut total = 0u32;
    for i in indices {
        let p = frame.rgb(i);
        for (counts, value) in histogram.iter_mut().zip(p) {
            counts[value as usize] += 1;
        }
        total += 1;
    }
    let half = total.div_ceil(2).max(1);
    histogram.map(|counts| {
        let mut seen = 0;
        for (level, &n) in counts.iter().enumerate() {
            seen += n;
            if seen >= half {
                return level as f64;
            }
        }
        0.0
    })
}

impl Segmenter {
    /// Fills `class`, `candidates` and `mask` for `frame`; returns the coverage model, or
    /// `None` when no pixel is a candidate. A `learned_target_rgb` (the target's colour as
    /// learned from earlier frames) is the full target colour where the configuration
    /// estimates it.
    pub fn segment<'a>(
        &mut self,
        frame: &RgbaView<'_>,
        background: BackgroundModel,
        reference: Option<&'a [[f32; 3]]>,
        config: &SegmentationConfig,
        learned_target_rgb: Option<[f64; 3]>,
    ) -> Option<CoverageModel<'a>> {
        let threshold = detection_threshold(config.detection, background.noise_sigma);
        let mut model = CoverageModel {
            background,
            reference,
            width: frame.width,
            target_rgb: [0.0; 3],
            threshold,
            learned_over_reference: reference.is_some() && learned_target_rgb.is_some(),
        };
        match reference {
            Some(reference) => self.find_candidates_in(frame, reference, threshold),
            None => self.find_candidates(frame, &background, threshold),
        }
        if self.candidates.is_empty() {
            self.mask.clear();
            return None;
        }
        let core_count = self.mark_core(frame.width, frame.height);
        model.target_rgb = match (config.target_colour, learned_target_rgb) {
            (TargetColour::Fixed { rgb }, _) => rgb.map(f64::from),
            (TargetColour::Estimated, Some(rgb)) => rgb,
            (TargetColour::Estimated, None) => {
                self.estimate_target_colour(frame, &model, core_count)
            }
        };
        self.mark_mask(frame, &model, config.mask_coverage);
        Some(model)
    }

    /// Flags and lists the candidates against each pixel's own background colour.
    fn find_candidates_in(&mut self, frame: &RgbaView<'_>, reference: &[[f32; 3]], threshold: f64) {
        self.class.clear();
        self.candidates.clear();
        let threshold2 = (threshold * threshold) as f32;
        for (i, b) in reference.iter().enumerate() {
            let p = frame.rgb(i);
            let d2: f32 = (0..3).map(|c| (p[c] as f32 - b[c]).powi(2)).sum();
            let candidate = d2 >= threshold2;
            self.class.push(u8::from(candidate));
            if candidate {
                self.candidates.push(i as u32);
            }
        }
    }

    /// Pass over every pixel: flags and lists the candidates.
    fn find_candidates(&mut self, frame: &RgbaView<'_>, bg: &BackgroundModel, threshold: f64) {
        let (w, h) = (frame.width, frame.height);
        // Every flag is overwritten below: no need to clear.
        self.class.resize(w * h, 0);
        self.candidates.clear();
        let threshold2 = (threshold * threshold) as f32;
        for v in 0..h {
            let row_background = bg.row_background(v);
            let class_row = &mut self.class[v * w..(v + 1) * w];
            // The row as little-endian RGBA words (R in the low byte), copied into an aligned
            // buffer so that the loop below loads whole pixels and vectorises.
            self.row_words.clear();
            self.row_words.resize(w, 0);
            bytemuck::cast_slice_mut::<u32, u8>(&mut self.row_words).copy_from_slice(frame.row(v));
            let mut any = 0u8;
            for (u, (flag, &word)) in class_row.iter_mut().zip(self.row_words.iter()).enumerate() {
                let rgba = u32::from_le(word);
                let [br, bg, bb] = row_background.rgb_at(u);
                let dr = (rgba & 0xff) as f32 - br;
                let dg = ((rgba >> 8) & 0xff) as f32 - bg;
                let db = ((rgba >> 16) & 0xff) as f32 - bb;
                *flag = u8::from(dr * dr + dg * dg + db * db >= threshold2);
                any |= *flag;
            }
            if any == 0 {
                continue;
            }
            let base = v * w;
            for (u, flag) in class_row.iter().enumerate() {
                if *flag != 0 {
                    self.candidates.push((base + u) as u32);
                }
            }
        }
    }

    /// Flags candidates whose 8 neighbours are candidates as core; returns how many.
    fn mark_core(&mut self, w: usize, h: usize) -> usize {
        let mut count = 0;
        for &i in &self.candidates {
            let i = i as usize;
            let (u, v) = (i % w, i / w);
            if u == 0 || v == 0 || u + 1 == w || v + 1 == h {
                continue;
            }
            let c = &self.class;
            let all = c[i - w - 1]
                & c[i - w]
                & c[i - w + 1]
                & c[i - 1]
                & c[i + 1]
                & c[i + w - 1]
                & c[i + w]
                & c[i + w + 1]
                & CANDIDATE;
            if all != 0 {
                self.class[i] |= CORE;
                count += 1;
            }
        }
        count
    }

    /// The colour of a fully covered target pixel: the per-channel median of the core pixels;
    /// without core pixels (a target thinner than 3 px), of the candidates farthest from the
    /// background (top [`FULL_CONTRAST_FRACTION`] by distance), which are the most covered.
    /// The median of all candidates would be a mix of target and background there, making
    /// every edge pixel look fully covered.
    fn estimate_target_colour(
        &mut self,
        frame: &RgbaView<'_>,
        model: &CoverageModel<'_>,
        core_count: usize,
    ) -> [f64; 3] {
        if core_count > 0 {
            let class = &self.class;
            let core = self
                .candidates
                .iter()
                .map(|&i| i as usize)
                .filter(|&i| class[i] & CORE != 0);
            return median_colour(frame, core, &mut self.histogram);
        }
        let w = frame.width;
        self.distances.clear();
        self.distances.extend(self.candidates.iter().map(|&i| {
            let i = i as usize;
            let p = frame.rgb(i);
            let b = model.background_at(i, i % w, i / w);
            (0..3).map(|c| (p[c] - b[c]).powi(2)).sum::<f64>()
        }));
        self.scratch.clear();
        self.scratch.extend_from_slice(&self.distances);
        let n = self.scratch.len();
        let keep = ((n as f64 * FULL_CONTRAST_FRACTION).ceil() as usize).clamp(1, n);
        let (_, cut, _) = self
            .scratch
            .select_nth_unstable_by(n - keep, f64::total_cmp);
        let cut = *cut;
        let most_different = self
            .candidates
            .iter()
            .zip(self.distances.iter())
            .filter(|(_, d)| **d >= cut)
            .map(|(&i, _)| i as usize);
        median_colour(frame, most_different, &mut self.histogram)
    }

    /// Flags and lists the mask pixels: core ([`CoverageModel::core_is_target`]), or other
    /// candidates covered at least `mask_coverage`.
    fn mark_mask(&mut self, frame: &RgbaView<'_>, model: &CoverageModel, mask_coverage: f64) {
        self.mask.clear();
        let w = frame.width;
        for &i in &self.candidates {
            let idx = i as usize;
            let (u, v) = (idx % w, idx / w);
            let in_mask = if self.class[idx] & CORE != 0 {
                model.core_is_target(frame, idx, u, v)
            } else {
                model.coverage(frame, idx, u, v) >= mask_coverage
            };
            if in_mask {
                self.class[idx] |= MASK;
                self.mask.push(i);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vision::background::BackgroundFitter;
    use crate::vision::config::BackgroundSource;
    use crate::vision::synthetic::{Background, SyntheticScene};

    /// Coverage of a noise-free anti-aliased edge equals the rendered area fraction to within
    /// 8-bit rounding (0.5 grey level over a contrast of 150 ≈ 0.004, allow 0.01).
    #[test]
    fn coverage_matches_area_fraction() {
        let mut scene = SyntheticScene::new(64, 48, Background::Uniform([200.0, 210.0, 230.0]));
        // A rectangle's right edge at u = 30.25 (on the 1/16 supersampling grid): pixel 30 is
        // 25% covered.
        scene.add_rectangle((20.125, 24.0), (20.25, 20.0), 0.0, [50.0, 60.0, 80.0]);
        let rgba = scene.render();
        let frame = RgbaView::new(&rgba, 64, 48).unwrap();
        let bg =
            BackgroundFitter::default().fit(&frame, BackgroundSource::BorderFit { border_px: 2 });
        let mut seg = Segmenter::default();
        let model = seg
            .segment(&frame, bg, None, &SegmentationConfig::default(), None)
            .unwrap();
        let cov = |u: usize, v: usize| model.coverage(&frame, v * 64 + u, u, v);
        assert!((cov(30, 24) - 0.25).abs() < 0.01, "{}", cov(30, 24));
        assert!((cov(29, 24) - 1.0).abs() < 0.01);
        assert!(cov(31, 24) < 0.01);
        // Interior is core and in the mask; the 25% pixel is a candidate but not in the mask.
        assert_eq!(seg.class[24 * 64 + 20] & (CORE | MASK), CORE | MASK);
        assert_eq!(seg.class[24 * 64 + 30] & (CANDIDATE | MASK), CANDIDATE);
        for c in 0..3 {
            assert!((model.target_rgb[c] - [50.0, 60.0, 80.0][c]).abs() < 0.6);
        }
    }

    /// A block of field 11 grey levels darker than the memory's (its brightness changed since
    /// the memory saw it) beside a dark grey target with a lit face: with the target's grey
    /// learned, the block's core pixels (a mixture of 0.22 with the grey) leave the mask and
    /// the target's, lit face included, stay; without it, the block is in the mask whole.
    #[test]
    fn a_background_that_changed_brightness_is_not_the_targets_core() {
        let (w, h) = (40, 30);
        let remembered = [134.0f32, 111.0, 89.0];
        let colour_at = |u: usize, v: usize| match (u, v) {
            (5..=34, 4..=12) => [123u8, 105, 88],
            (5..=19, 16..=24) => [53, 53, 53],
            (20..=34, 16..=24) => [106, 106, 106],
            _ => remembered.map(|c| c as u8),
        };
        let rgba: Vec<u8> = (0..w * h)
            .flat_map(|i| {
                let [r, g, b] = colour_at(i % w, i / w);
                [r, g, b, 255]
            })
            .collect();
        let frame = RgbaView::new(&rgba, w as u32, h as u32).unwrap();
        let reference = vec![remembered; w * h];
        let in_mask = |learned: Option<[f64; 3]>| {
            let mut seg = Segmenter::default();
            let mut background = BackgroundModel::constant(w, h, [0.0; 3]);
            background.noise_sigma = 1.0;
            // formation_scene.toml's: thin wing pixels down to a tenth covered.
            let config = SegmentationConfig {
                mask_coverage: 0.1,
                ..SegmentationConfig::default()
            };
            seg.segment(&frame, background, Some(&reference), &config, learned)
                .unwrap();
            move |u: usize, v: usize| seg.class[v * w + u] & MASK != 0
        };
        let learned = in_mask(Some([53.0; 3]));
        assert!(!learned(20, 8), "the changed field is not target");
        assert!(
            learned(12, 20) && learned(27, 20),
            "the target's dark and lit faces are"
        );
        let unlearned = in_mask(None);
        assert!(unlearned(20, 8) && unlearned(12, 20));
    }
}
