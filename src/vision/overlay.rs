//! Drawing a measurement onto an RGBA8 frame: a cross at the centroid, the maximal-length
//! segment between its Feret endpoints, and a one-line status ("OK B=42.3PX") in the top-left
//! corner, coloured by status (green ok, yellow truncated, red lost or too small). The truth's
//! reference point and Feret segment can be drawn beside it in cyan.

use std::cmp::Ordering;

use crate::render::camera::CameraIntrinsics;

use super::font::{GLYPH_HEIGHT, GLYPH_WIDTH, glyph};
use super::image_view::{ImageSizeError, check_rgba_len};
use super::pipeline::{BlobMeasurement, BlobStatus};
use super::truth::ImageTruth;

/// Colour of an `Ok` measurement.
pub const OK_RGB: [u8; 3] = [0, 230, 0];
/// Colour of a `Truncated` measurement.
pub const TRUNCATED_RGB: [u8; 3] = [255, 220, 0];
/// Colour of a `NotFound` or `TooSmall` measurement.
pub const LOST_RGB: [u8; 3] = [255, 40, 40];
/// Colour of the ground-truth marks.
pub const TRUTH_RGB: [u8; 3] = [0, 220, 255];

/// Colour of captions under the status line.
pub const CAPTION_RGB: [u8; 3] = [255, 255, 255];

/// Half-length of the centroid cross's arms, px.
const CROSS_HALF_PX: f64 = 6.0;
/// Text scale (each font pixel is this many image pixels square).
const TEXT_SCALE: usize = 2;
/// Text origin (top-left), px.
const TEXT_ORIGIN_PX: usize = 4;

/// Overlay colour for `status`.
pub fn status_rgb(status: BlobStatus) -> [u8; 3] {
    match status {
        BlobStatus::Ok => OK_RGB,
        BlobStatus::Truncated | BlobStatus::Merged => TRUNCATED_RGB,
        BlobStatus::NotFound | BlobStatus::TooSmall => LOST_RGB,
    }
}

/// The status line drawn by [`draw_measurement_overlay`], e.g. `OK b=42.3px`.
pub fn status_line(measurement: &BlobMeasurement) -> String {
    match measurement.status {
        BlobStatus::NotFound => measurement.status.label().to_string(),
        BlobStatus::TooSmall => format!(
            "{} n={}",
            measurement.status.label(),
            measurement.pixel_count
        ),
        BlobStatus::Ok | BlobStatus::Truncated | BlobStatus::Merged => format!(
            "{} b={:.1}px",
            measurement.status.label(),
            measurement.max_length_px
        ),
    }
}

/// A mutable RGBA8 image with clipped drawing primitives.
struct Canvas<'a> {
    rgba: &'a mut [u8],
    width: usize,
    height: usize,
}

impl<'a> Canvas<'a> {
    fn new(rgba: &'a mut [u8], width_px: u32, height_px: u32) -> Result<Self, ImageSizeError> {
        check_rgba_len(rgba.len(), width_px, height_px)?;
        Ok(Self {
            rgba,
            width: width_px as usize,
            height: height_px as usize,
        })
    }

    fn put(&mut self, x: i64, y: i64, rgb: [u8; 3]) {
        if x < 0 || y < 0 || x as usize >= self.width || y as usize >= self.height {
            return;
        }
        let i = (y as usize * self.width + x as usize) * 4;
        self.rgba[i..i + 3].copy_from_slice(&rgb);
        self.rgba[i + 3] = 255;
    }

    /// Segment between pixel positions (u, v), clipped to the image (Liang-Barsky), drawn by
    /// stepping one pixel along the major axis.
    fn line(&mut self, (u0, v0): (f64, f64), (u1, v1): (f64, f64), rgb: [u8; 3]) {
        let (du, dv) = (u1 - u0, v1 - v0);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        let (w, h) = (self.width as f64, self.height as f64);
        for (p, q) in [(-du, u0), (du, w - u0), (-dv, v0), (dv, h - v0)] {
            if p == 0.0 {
                if q < 0.0 {
                    return;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        // Outside the image, or NaN somewhere (then the comparison is not `Less`/`Equal`).
        if !matches!(t0.partial_cmp(&t1), Some(Ordering::Less | Ordering::Equal)) {
            return;
        }
        let (a, b) = ((u0 + t0 * du, v0 + t0 * dv), (u0 + t1 * du, v0 + t1 * dv));
        let steps = (b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil().max(1.0);
        let n = steps as i64;
        for k in 0..=n {
            let t = k as f64 / steps;
            let u = a.0 + t * (b.0 - a.0);
            let v = a.1 + t * (b.1 - a.1);
            self.put(u.floor() as i64, v.floor() as i64, rgb);
        }
    }

    fn cross(&mut self, (u, v): (f64, f64), half: f64, rgb: [u8; 3]) {
        self.line((u - half, v), (u + half, v), rgb);
        self.line((u, v - half), (u, v + half), rgb);
    }

    /// `text` at (x, y) on a dark backing box.
    fn text(&mut self, x: usize, y: usize, text: &str, rgb: [u8; 3]) {
        let advance = (GLYPH_WIDTH + 1) * TEXT_SCALE;
        let box_w = text.chars().count() * advance + TEXT_SCALE;
        let box_h = (GLYPH_HEIGHT + 2) * TEXT_SCALE;
        for by in 0..box_h {
            for bx in 0..box_w {
                let (px, py) = ((x + bx) as i64, (y + by) as i64);
                self.put(px - TEXT_SCALE as i64, py - TEXT_SCALE as i64, [0, 0, 0]);
            }
        }
        for (k, c) in text.chars().enumerate() {
            let rows = glyph(c);
            for (gy, bits) in rows.iter().enumerate() {
                for gx in 0..GLYPH_WIDTH {
                    if bits & (0b100 >> gx) == 0 {
                        continue;
                    }
                    for sy in 0..TEXT_SCALE {
                        for sx in 0..TEXT_SCALE {
                            let px = x + k * advance + gx * TEXT_SCALE + sx;
                            let py = y + gy * TEXT_SCALE + sy;
                            self.put(px as i64, py as i64, rgb);
                        }
                    }
                }
            }
        }
    }
}

/// Draws `measurement` onto an RGBA8 frame (row-major, top row first, `width_px * 4` bytes per
/// row): centroid cross, maximal-length segment and status line, coloured by status. Marks
/// outside the image are clipped. Errors only when the buffer length does not match.
pub fn draw_measurement_overlay(
    rgba: &mut [u8],
    width_px: u32,
    height_px: u32,
    measurement: &BlobMeasurement,
) -> Result<(), ImageSizeError> {
    let mut canvas = Canvas::new(rgba, width_px, height_px)?;
    let rgb = status_rgb(measurement.status);
    if let Some(f) = measurement.feret {
        canvas.line((f.start.u_px, f.start.v_px), (f.end.u_px, f.end.v_px), rgb);
    }
    if measurement.status != BlobStatus::NotFound {
        canvas.cross(
            (measurement.centroid_u_px, measurement.centroid_v_px),
            CROSS_HALF_PX,
            rgb,
        );
    }
    canvas.text(
        TEXT_ORIGIN_PX,
        TEXT_ORIGIN_PX,
        &status_line(measurement),
        rgb,
    );
    Ok(())
}

/// Draws `text` in white on the given line of the overlay's text (line 0 is the status line),
/// e.g. the gimbal's angles under the measurement's status.
pub fn draw_caption(
    rgba: &mut [u8],
    width_px: u32,
    height_px: u32,
    line: usize,
    text: &str,
) -> Result<(), ImageSizeError> {
    let mut canvas = Canvas::new(rgba, width_px, height_px)?;
    let line_px = (GLYPH_HEIGHT + 3) * TEXT_SCALE;
    canvas.text(
        TEXT_ORIGIN_PX,
        TEXT_ORIGIN_PX + line * line_px,
        text,
        CAPTION_RGB,
    );
    Ok(())
}

/// Draws `text` in white on a dark box at the frame's foot, left-aligned (a video's caption:
/// time and track status).
pub fn draw_footer(
    rgba: &mut [u8],
    width_px: u32,
    height_px: u32,
    text: &str,
) -> Result<(), ImageSizeError> {
    let mut canvas = Canvas::new(rgba, width_px, height_px)?;
    let line_px = (GLYPH_HEIGHT + 1) * TEXT_SCALE;
    let y = (height_px as usize).saturating_sub(line_px + TEXT_ORIGIN_PX);
    canvas.text(TEXT_ORIGIN_PX, y, text, CAPTION_RGB);
    Ok(())
}

/// Draws the ground truth in cyan: a diagonal cross at the projected reference point and the
/// true maximal-length segment.
pub fn draw_truth_overlay(
    rgba: &mut [u8],
    camera: &CameraIntrinsics,
    truth: &ImageTruth,
) -> Result<(), ImageSizeError> {
    let mut canvas = Canvas::new(rgba, camera.width_px, camera.height_px)?;
    let f = truth.feret;
    canvas.line(
        (f.start.u_px, f.start.v_px),
        (f.end.u_px, f.end.v_px),
        TRUTH_RGB,
    );
    let (u, v) = camera.pixel_from_image(truth.y_i_px, truth.z_i_px);
    let d = CROSS_HALF_PX * std::f64::consts::FRAC_1_SQRT_2;
    canvas.line((u - d, v - d), (u + d, v + d), TRUTH_RGB);
    canvas.line((u - d, v + d), (u + d, v - d), TRUTH_RGB);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vision::feret::{FeretDiameter, PixelPoint};

    fn measurement(status: BlobStatus) -> BlobMeasurement {
        BlobMeasurement {
            status,
            centroid_u_px: 40.5,
            centroid_v_px: 30.5,
            max_length_px: 42.26,
            area_px: 100.0,
            pixel_count: 90,
            bbox: None,
            feret: Some(FeretDiameter {
                length_px: 42.26,
                start: PixelPoint::new(20.0, 30.5),
                end: PixelPoint::new(62.0, 30.5),
            }),
            blob_count: 1,
            background_noise_sigma: 1.0,
        }
    }

    fn rgb_at(rgba: &[u8], w: usize, u: usize, v: usize) -> [u8; 3] {
        let i = (v * w + u) * 4;
        [rgba[i], rgba[i + 1], rgba[i + 2]]
    }

    /// The cross and segment land on the pixels containing the centroid and the Feret ends,
    /// in the status colour; the status line reads as specified.
    #[test]
    fn marks_in_status_colour() {
        let (w, h) = (80usize, 60usize);
        let mut rgba = vec![128u8; w * h * 4];
        let m = measurement(BlobStatus::Truncated);
        draw_measurement_overlay(&mut rgba, w as u32, h as u32, &m).unwrap();
        assert_eq!(rgb_at(&rgba, w, 40, 30), TRUNCATED_RGB);
        assert_eq!(rgb_at(&rgba, w, 40, 24), TRUNCATED_RGB); // cross arm end: 30.5 − 6
        assert_eq!(rgb_at(&rgba, w, 20, 30), TRUNCATED_RGB);
        assert_eq!(rgb_at(&rgba, w, 61, 30), TRUNCATED_RGB);
        assert_eq!(rgb_at(&rgba, w, 70, 50), [128; 3]);
        assert_eq!(status_line(&m), "TRUNC b=42.3px");
        assert_eq!(
            status_line(&measurement(BlobStatus::TooSmall)),
            "SMALL n=90"
        );
    }

    /// Lines far outside, through, or with NaN ends draw nothing out of bounds and do not
    /// panic; a wrong buffer size is an error.
    #[test]
    fn clipping_and_bad_input() {
        let (w, h) = (16u32, 8u32);
        let mut rgba = vec![0u8; 16 * 8 * 4];
        let mut c = Canvas::new(&mut rgba, w, h).unwrap();
        c.line((-1e12, -1e12), (1e12, 1e12), [1, 2, 3]);
        c.line((f64::NAN, 0.0), (3.0, 3.0), [1, 2, 3]);
        c.line((100.0, 100.0), (200.0, 100.0), [9, 9, 9]);
        c.text(10, 4, "OK 123 ~", [1, 1, 1]);
        assert!(rgba.chunks_exact(4).all(|p| p[0] != 9));
        let mut m = measurement(BlobStatus::NotFound);
        m.centroid_u_px = f64::NAN;
        assert!(draw_measurement_overlay(&mut rgba, 16, 8, &m).is_ok());
        assert!(draw_measurement_overlay(&mut rgba, 17, 8, &m).is_err());
    }
}
