//! A rendered camera frame read back to the CPU.

use std::path::{Path, PathBuf};

/// Why a frame could not be saved.
#[derive(Debug, thiserror::Error)]
#[error("cannot write frame {path}: {source}")]
pub struct ImageSaveError {
    /// The PNG file.
    pub path: PathBuf,
    /// What the encoder or the file system said.
    pub source: image::ImageError,
}

/// An RGBA8 image, tightly packed (4 bytes a pixel, no row padding), top row first.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct CameraImage {
    /// Width, px.
    pub width_px: u32,
    /// Height, px.
    pub height_px: u32,
    /// Pixels: row v, column u at byte 4 (v width + u), channels R, G, B, A.
    pub rgba: Vec<u8>,
}

impl CameraImage {
    /// A frame of the given size filled with one colour.
    pub fn filled(width_px: u32, height_px: u32, rgba: [u8; 4]) -> Self {
        let n = width_px as usize * height_px as usize;
        Self {
            width_px,
            height_px,
            rgba: rgba.repeat(n),
        }
    }

    /// Writes `part`'s pixels over this image's from column and row `at_px` (`part` lies
    /// inside the image).
    pub fn paste(&mut self, part: &CameraImage, [u0, v0]: [u32; 2]) {
        let row_bytes = 4 * part.width_px as usize;
        let stride = 4 * self.width_px as usize;
        for (v, row) in (v0 as usize..).zip(part.rgba.chunks_exact(row_bytes)) {
            let start = v * stride + 4 * u0 as usize;
            self.rgba[start..start + row_bytes].copy_from_slice(row);
        }
    }

    /// The RGBA of pixel column u, row v, or `None` outside the frame.
    pub fn pixel(&self, u_px: u32, v_px: u32) -> Option<[u8; 4]> {
        if u_px >= self.width_px || v_px >= self.height_px {
            return None;
        }
        let i = 4 * (v_px as usize * self.width_px as usize + u_px as usize);
        let p = self.rgba.get(i..i + 4)?;
        Some([p[0], p[1], p[2], p[3]])
    }

    /// Grey level (Rec. 601 luma, 0-255) of every pixel, top row first.
    pub fn grey_levels(&self) -> Vec<u8> {
        self.rgba
            .chunks_exact(4)
            .map(|p| {
                let y = 299 * u32::from(p[0]) + 587 * u32::from(p[1]) + 114 * u32::from(p[2]);
                ((y + 500) / 1000) as u8
            })
            .collect()
    }

    /// Writes the frame as an 8-bit RGBA PNG.
    pub fn save_png(&self, path: &Path) -> Result<(), ImageSaveError> {
        image::save_buffer(
            path,
            &self.rgba,
            self.width_px,
            self.height_px,
            image::ExtendedColorType::Rgba8,
        )
        .map_err(|source| ImageSaveError {
            path: path.to_path_buf(),
            source,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_indexing_is_row_major_top_first() {
        let mut f = CameraImage::filled(3, 2, [1, 2, 3, 255]);
        f.rgba[4 * (3 + 2)] = 9;
        assert_eq!(f.pixel(2, 1), Some([9, 2, 3, 255]));
        assert_eq!(f.pixel(3, 0), None);
        assert_eq!(f.grey_levels().len(), 6);
        assert_eq!(
            CameraImage::filled(1, 1, [200, 200, 200, 255]).grey_levels(),
            vec![200]
        );
    }
}
