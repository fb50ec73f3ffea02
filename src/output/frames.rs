//! `frames/NNNNNN.png`: camera frames as the follower saw them, with an optional overlay of
//! the measurement (centroid cross, maximal-length segment, status line).

use crate::render::frame::Frame;
use crate::sensor::CameraSensor;
use crate::vision::BlobMeasurement;
use crate::vision::overlay::draw_measurement_overlay;
use std::path::{Path, PathBuf};

/// Saves every N-th frame of a camera into a directory.
#[derive(Debug)]
pub struct FrameSaver {
    dir: PathBuf,
    every: u64,
    overlay: bool,
    last_index: Option<u64>,
}

impl FrameSaver {
    /// A saver writing into `dir` (created on the first frame).
    pub fn new(dir: &Path, every: u32, overlay: bool) -> Self {
        Self {
            dir: dir.to_path_buf(),
            every: u64::from(every.max(1)),
            overlay,
            last_index: None,
        }
    }

    /// Saves the camera's last frame if it is new and its index is a multiple of N.
    pub fn offer(&mut self, camera: &CameraSensor) -> Result<(), String> {
        let Some((frame, record, blob)) = camera.last_frame() else {
            return Ok(());
        };
        if self.last_index == Some(record.index) || !record.index.is_multiple_of(self.every) {
            return Ok(());
        }
        self.last_index = Some(record.index);
        std::fs::create_dir_all(&self.dir)
            .map_err(|e| format!("cannot create {}: {e}", self.dir.display()))?;
        let path = self.dir.join(format!("{:06}.png", record.index));
        write_frame(&path, frame, self.overlay.then_some(blob))
    }
}

/// Writes a frame as PNG, with the measurement drawn on a copy when given.
pub fn write_frame(
    path: &Path,
    frame: &Frame,
    overlay: Option<&BlobMeasurement>,
) -> Result<(), String> {
    match overlay {
        None => frame.save_png(path).map_err(|e| e.to_string()),
        Some(blob) => {
            let mut copy = frame.clone();
            draw_measurement_overlay(&mut copy.rgba, copy.width_px, copy.height_px, blob)
                .map_err(|e| e.to_string())?;
            copy.save_png(path).map_err(|e| e.to_string())
        }
    }
}
