//! A checked view of an RGBA8 frame: row-major, top row first, `width * 4` bytes per row.

use thiserror::Error;

/// A frame buffer whose length does not match its stated size.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum ImageSizeError {
    /// `rgba.len()` is not `width * height * 4`.
    #[error(
        "RGBA frame of {width_px}x{height_px} px needs {expected_bytes} bytes, got {actual_bytes}"
    )]
    BufferSize {
        /// Stated width, px.
        width_px: u32,
        /// Stated height, px.
        height_px: u32,
        /// `width * height * 4`, or `usize::MAX` when that overflows.
        expected_bytes: usize,
        /// Length of the buffer passed in.
        actual_bytes: usize,
    },
    /// More pixels than 32-bit pixel indices can address.
    #[error("RGBA frame of {width_px}x{height_px} px has more than 2^32 - 1 pixels")]
    TooLarge {
        /// Stated width, px.
        width_px: u32,
        /// Stated height, px.
        height_px: u32,
    },
}

/// Expected byte length of a tightly packed RGBA8 frame, or an error naming the mismatch.
pub(crate) fn check_rgba_len(
    len: usize,
    width_px: u32,
    height_px: u32,
) -> Result<(), ImageSizeError> {
    let expected = (width_px as usize)
        .checked_mul(height_px as usize)
        .and_then(|n| n.checked_mul(4));
    if expected == Some(len) {
        Ok(())
    } else {
        Err(ImageSizeError::BufferSize {
            width_px,
            height_px,
            expected_bytes: expected.unwrap_or(usize::MAX),
            actual_bytes: len,
        })
    }
}

/// A read-only RGBA8 frame whose buffer length has been checked: a whole image, or a region
/// of one whose first pixel is at `origin` in the image.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RgbaView<'a> {
    rgba: &'a [u8],
    /// Width, px.
    pub width: usize,
    /// Height, px.
    pub height: usize,
    /// Image column and row of the view's first pixel (0, 0 for a whole image).
    pub origin: [usize; 2],
}

impl<'a> RgbaView<'a> {
    /// Wraps `rgba` after checking its length.
    /// Also rejects frames with more than `u32::MAX` pixels (pixel lists hold u32 indices).
    pub fn new(rgba: &'a [u8], width_px: u32, height_px: u32) -> Result<Self, ImageSizeError> {
        check_rgba_len(rgba.len(), width_px, height_px)?;
        if u64::from(width_px) * u64::from(height_px) > u64::from(u32::MAX) {
            return Err(ImageSizeError::TooLarge {
                width_px,
                height_px,
            });
        }
        Ok(Self {
            rgba,
            width: width_px as usize,
            height: height_px as usize,
            origin: [0, 0],
        })
    }

    /// The same view, as the region of an image whose first pixel is at image column
    /// `u0_px`, row `v0_px`.
    pub fn at_origin(self, u0_px: u32, v0_px: u32) -> Self {
        Self {
            origin: [u0_px as usize, v0_px as usize],
            ..self
        }
    }

    /// The bytes of row `v` (`width * 4` of them).
    pub fn row(&self, v: usize) -> &'a [u8] {
        &self.rgba[v * self.width * 4..(v + 1) * self.width * 4]
    }

    /// RGB of pixel `idx = v * width + u`, as f64 grey levels.
    pub fn rgb(&self, idx: usize) -> [f64; 3] {
        let p = &self.rgba[idx * 4..idx * 4 + 3];
        [f64::from(p[0]), f64::from(p[1]), f64::from(p[2])]
    }

    /// Number of pixels.
    pub fn pixel_count(&self) -> usize {
        self.width * self.height
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The length check accepts exactly width*height*4 bytes, including the empty 0x0 frame,
    /// and reports overflowing sizes instead of wrapping.
    #[test]
    fn length_check() {
        assert!(RgbaView::new(&[0; 24], 3, 2).is_ok());
        assert!(RgbaView::new(&[], 0, 0).is_ok());
        assert!(RgbaView::new(&[], 0, 5).is_ok());
        assert!(matches!(
            RgbaView::new(&[0; 23], 3, 2),
            Err(ImageSizeError::BufferSize {
                expected_bytes: 24,
                actual_bytes: 23,
                ..
            })
        ));
        assert!(check_rgba_len(0, u32::MAX, u32::MAX).is_err());
    }
}
