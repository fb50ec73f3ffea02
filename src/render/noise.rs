//! Per-pixel Gaussian sensor noise, added to a frame after readback.
//!
//! The same value is added to R, G and B of every pixel (sky and target), then rounded and
//! clamped to 0-255. It is a pure function of (seed, frame index, pixel): a 64-bit hash of the
//! frame's key and the pixel's index gives four 16-bit draws (one each for four neighbouring
//! pixels), each mapped through a table of the 65 536 standard-normal quantiles
//! Φ⁻¹((k + ½) / 65 536) (so samples reach ±4.3σ). On lavapipe this is cheaper than hashing
//! and Box-Muller in the fragment shader (docs/findings.md, Rendering on lavapipe).

use crate::render::image::CameraImage;
use crate::render::region::ImageRegion;

/// Number of table entries: one per 16-bit draw.
const TABLE_LEN: usize = 1 << 16;

/// Adds seeded Gaussian noise of a fixed standard deviation to frames.
#[derive(Debug, Clone)]
pub struct NoiseGenerator {
    /// ⌊std · Φ⁻¹((k + ½) / 65 536) + ½⌋, grey levels. Adding the rounded noise to an integer
    /// grey level equals rounding their sum, so the frame is rounded exactly once.
    table: Box<[i16; TABLE_LEN]>,
    seed_hash: u64,
}

impl NoiseGenerator {
    /// Noise of standard deviation `std_grey_levels` (finite, ≥ 0) seeded by `seed`.
    pub fn new(std_grey_levels: f64, seed: u64) -> Self {
        let mut table = Box::new([0i16; TABLE_LEN]);
        for (k, t) in table.iter_mut().enumerate() {
            let p = (k as f64 + 0.5) / TABLE_LEN as f64;
            // Saturates (as casts do) far beyond the 0-255 range: clamping gives the same pixel.
            *t = (std_grey_levels * standard_normal_quantile(p) + 0.5).floor() as i16;
        }
        Self {
            table,
            seed_hash: splitmix64(seed),
        }
    }

    /// Adds this frame's noise to `frame` (a whole image) in place; `frame_index` selects
    /// the draw.
    pub fn apply(&self, frame: &mut CameraImage, frame_index: u64) {
        let region = ImageRegion {
            u0_px: 0,
            v0_px: 0,
            width_px: frame.width_px,
            height_px: frame.height_px,
        };
        self.apply_in_region(&mut frame.rgba, &region, frame.width_px, frame_index);
    }

    /// Adds this frame's noise to `rgba`, the pixels of `region` (row-major, 4 bytes a pixel)
    /// of an image `image_width_px` wide: each pixel gets the noise it gets in the whole
    /// image. The draw of image pixel i is the (i mod 4)-th 16 bits of the hash of block i / 4.
    pub fn apply_in_region(
        &self,
        rgba: &mut [u8],
        region: &ImageRegion,
        image_width_px: u32,
        frame_index: u64,
    ) {
        let key = splitmix64(self.seed_hash ^ frame_index);
        let add = |c: u8, n: i16| i16::from(c).saturating_add(n).clamp(0, 255) as u8;
        let row_bytes = 4 * region.width_px as usize;
        if row_bytes == 0 {
            return;
        }
        for (row, v) in rgba.chunks_exact_mut(row_bytes).zip(region.v0_px..) {
            let first = u64::from(v) * u64::from(image_width_px) + u64::from(region.u0_px);
            let mut h = splitmix64(key.wrapping_add(first / 4)) >> (16 * (first % 4));
            for (i, px) in (first..).zip(row.chunks_exact_mut(4)) {
                if i != first && i.is_multiple_of(4) {
                    h = splitmix64(key.wrapping_add(i / 4));
                }
                let n = self.table[(h & 0xffff) as usize];
                h >>= 16;
                px[0] = add(px[0], n);
                px[1] = add(px[1], n);
                px[2] = add(px[2], n);
            }
        }
    }
}

/// splitmix64 (Steele, Lea & Flood 2014): a well-mixed 64-bit value from a 64-bit value.
fn splitmix64(z: u64) -> u64 {
    let mut z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Φ⁻¹(p) for p in (0, 1), by Acklam's rational approximation (relative error < 1.2e-9).
pub fn standard_normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    const P_LOW: f64 = 0.024_25;
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    if p < P_LOW {
        tail((-2.0 * p.ln()).sqrt())
    } else if p <= 1.0 - P_LOW {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    } else {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_match_reference_values() {
        // Reference values of Φ⁻¹ to 10 digits.
        for (p, x) in [
            (0.5, 0.0),
            (0.975, 1.959_963_985),
            (0.001, -3.090_232_306),
            (0.8413447461, 1.0),
            (1e-6, -4.753_424_309),
        ] {
            let q = standard_normal_quantile(p);
            assert!((q - x).abs() < 1e-8, "Φ⁻¹({p}) = {q}, expected {x}");
        }
    }

    #[test]
    fn table_has_unit_variance_and_zero_mean() {
        // std 100 grey levels: rounding to whole levels adds 1/12 to the variance, 1e-5
        // relative; midpoint quantiles lose a little of the tails, 1e-4 relative.
        let g = NoiseGenerator::new(100.0, 0);
        let n = TABLE_LEN as f64;
        let mean = g.table.iter().map(|&t| f64::from(t)).sum::<f64>() / n;
        let var = g.table.iter().map(|&t| f64::from(t).powi(2)).sum::<f64>() / n;
        assert!(
            mean.abs() < 0.01 && (var / 1e4 - 1.0).abs() < 1e-3,
            "{mean} {var}"
        );
    }

    #[test]
    fn noise_is_grey_deterministic_and_keyed_by_frame() {
        let g = NoiseGenerator::new(10.0, 3);
        let base = CameraImage::filled(33, 7, [100, 120, 140, 255]);
        let (mut a, mut b, mut c) = (base.clone(), base.clone(), base.clone());
        g.apply(&mut a, 1);
        g.apply(&mut b, 1);
        g.apply(&mut c, 2);
        assert_eq!(a, b);
        assert_ne!(a, c);
        for (p, q) in a.rgba.chunks_exact(4).zip(base.rgba.chunks_exact(4)) {
            let d = i32::from(p[0]) - i32::from(q[0]);
            assert_eq!(i32::from(p[1]) - i32::from(q[1]), d);
            assert_eq!(i32::from(p[2]) - i32::from(q[2]), d);
            assert_eq!(p[3], 255);
        }
    }

    /// A region gets the noise its pixels get in the whole image, whatever its alignment to
    /// the four-pixel blocks of the hash (image width 33: blocks span rows).
    #[test]
    fn region_noise_is_the_whole_image_noise_there() {
        let g = NoiseGenerator::new(10.0, 3);
        let mut whole = CameraImage::filled(33, 7, [100, 120, 140, 255]);
        g.apply(&mut whole, 5);
        let region = ImageRegion {
            u0_px: 3,
            v0_px: 2,
            width_px: 29,
            height_px: 4,
        };
        let mut part = CameraImage::filled(29, 4, [100, 120, 140, 255]);
        g.apply_in_region(&mut part.rgba, &region, 33, 5);
        for v in 0..4 {
            for u in 0..29 {
                assert_eq!(part.pixel(u, v), whole.pixel(u + 3, v + 2), "({u}, {v})");
            }
        }
    }

    #[test]
    fn zero_noise_changes_nothing() {
        let g = NoiseGenerator::new(0.0, 9);
        let mut f = CameraImage::filled(5, 5, [0, 128, 255, 255]);
        g.apply(&mut f, 4);
        assert_eq!(f, CameraImage::filled(5, 5, [0, 128, 255, 255]));
    }
}
