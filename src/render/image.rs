//! A rendered camera frame read back to the CPU.

use std::path::{Path, PathBuf};

/// Why a frame could not be saved.
#[derive(Debug, thiserror::Error)]
#[error("cannot write frame {path}: {source}")]
pub struct ImageSaveError {
    /// The PNG file.
    pub path: PathBuf,
    /// What the encoder or the file system said.
    pub source: png::EncodingError,
}

/// Why a PNG file could not be read as an image.
#[derive(Debug, thiserror::Error)]
#[error("cannot read image {path}: {reason}")]
pub struct ImageReadError {
    /// The PNG file.
    pub path: PathBuf,
    /// What the decoder or the file system said.
    pub reason: String,
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

    /// Writes the frame as an 8-bit RGBA PNG (fast deflate, adaptive row filters).
    pub fn save_png(&self, path: &Path) -> Result<(), ImageSaveError> {
        let error = |source| ImageSaveError {
            path: path.to_path_buf(),
            source,
        };
        let file = std::fs::File::create(path).map_err(|e| error(e.into()))?;
        let mut encoder =
            png::Encoder::new(std::io::BufWriter::new(file), self.width_px, self.height_px);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        encoder.set_filter(png::Filter::Adaptive);
        let mut writer = encoder.write_header().map_err(error)?;
        writer.write_image_data(&self.rgba).map_err(error)?;
        writer.finish().map_err(error)
    }

    /// Reads a PNG file as an RGBA8 image: grey, palette, 16-bit and alpha-less images are
    /// converted (opaque where the file has no alpha).
    pub fn read_png(path: &Path) -> Result<Self, ImageReadError> {
        let error = |reason: &dyn std::fmt::Display| ImageReadError {
            path: path.to_path_buf(),
            reason: reason.to_string(),
        };
        let file = std::fs::File::open(path).map_err(|e| error(&e))?;
        let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
        decoder.set_transformations(png::Transformations::normalize_to_color8());
        let mut reader = decoder.read_info().map_err(|e| error(&e))?;
        let size = reader
            .output_buffer_size()
            .ok_or_else(|| error(&"too large"))?;
        let mut bytes = vec![0; size];
        let info = reader.next_frame(&mut bytes).map_err(|e| error(&e))?;
        bytes.truncate(info.buffer_size());
        let rgba = match info.color_type {
            png::ColorType::Rgba => bytes,
            png::ColorType::Rgb => expand(&bytes, 3, |p| [p[0], p[1], p[2], 255]),
            png::ColorType::GrayscaleAlpha => expand(&bytes, 2, |p| [p[0], p[0], p[0], p[1]]),
            png::ColorType::Grayscale => expand(&bytes, 1, |p| [p[0], p[0], p[0], 255]),
            png::ColorType::Indexed => return Err(error(&"a palette left unexpanded")),
        };
        Ok(Self {
            width_px: info.width,
            height_px: info.height,
            rgba,
        })
    }
}

/// RGBA8 pixels from pixels of `channels` bytes each.
fn expand(bytes: &[u8], channels: usize, rgba: impl Fn(&[u8]) -> [u8; 4]) -> Vec<u8> {
    bytes.chunks_exact(channels).flat_map(rgba).collect()
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

    /// A saved frame reads back pixel for pixel; an RGB and a grey PNG read as opaque RGBA;
    /// a file that is not a PNG is an error naming it.
    #[test]
    fn png_round_trip_and_conversions() {
        let dir = tempfile::tempdir().unwrap();
        let mut frame = CameraImage::filled(5, 3, [10, 20, 30, 40]);
        frame.rgba[4 * 7..4 * 8].copy_from_slice(&[250, 0, 128, 255]);
        let path = dir.path().join("f.png");
        frame.save_png(&path).unwrap();
        assert_eq!(CameraImage::read_png(&path).unwrap(), frame);

        let write = |name: &str, colour, bytes: &[u8]| {
            let path = dir.path().join(name);
            let file = std::fs::File::create(&path).unwrap();
            let mut encoder = png::Encoder::new(file, 2, 1);
            encoder.set_color(colour);
            let mut writer = encoder.write_header().unwrap();
            writer.write_image_data(bytes).unwrap();
            writer.finish().unwrap();
            CameraImage::read_png(&path).unwrap().rgba
        };
        let rgb = write("rgb.png", png::ColorType::Rgb, &[1, 2, 3, 4, 5, 6]);
        assert_eq!(rgb, [1, 2, 3, 255, 4, 5, 6, 255]);
        let grey = write("grey.png", png::ColorType::Grayscale, &[7, 9]);
        assert_eq!(grey, [7, 7, 7, 255, 9, 9, 9, 255]);

        let not_png = dir.path().join("not.png");
        std::fs::write(&not_png, b"not a png").unwrap();
        let error = CameraImage::read_png(&not_png).unwrap_err().to_string();
        assert!(error.contains("not.png"), "{error}");
    }
}
