//! `frames/NNNNNN.png`: camera frames as the follower saw them, with an optional overlay of
//! the measurement (centroid cross, maximal-length segment, status line).

use crate::render::image::{CameraImage, ImageSaveError};
use crate::sensing::gimbal::GimbalAngles;
use crate::sensing::{CameraConfig, CameraSensor};
use crate::sim::GimbalReading;
use crate::vision::overlay::{draw_caption, draw_measurement_overlay};
use crate::vision::{BlobMeasurement, ImageSizeError};
use std::path::{Path, PathBuf};

/// Why a frame could not be written.
#[derive(Debug, thiserror::Error)]
pub enum FrameWriteError {
    /// The folder could not be created.
    #[error("cannot create {}: {source}", path.display())]
    CreateDir {
        /// The folder.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The overlay could not be drawn on the frame.
    #[error("cannot draw the overlay: {0}")]
    Overlay(#[from] ImageSizeError),
    /// The PNG could not be written.
    #[error(transparent)]
    Save(#[from] ImageSaveError),
}

/// Creates a folder and its parents.
fn create_dir(path: &Path) -> Result<(), FrameWriteError> {
    std::fs::create_dir_all(path).map_err(|source| FrameWriteError::CreateDir {
        path: path.to_path_buf(),
        source,
    })
}

/// Saves every N-th frame of a camera into a directory.
///
/// A frame is measured, and so saved, after it was exposed: in the same tick without
/// latency, one frame period later when measuring overlaps the next exposure. Its captions
/// (the gimbal's angles) are therefore taken at the tick the frame was exposed and kept
/// until it is saved, so that they show the same instant as the image.
#[derive(Debug)]
pub struct FrameSaver {
    dir: PathBuf,
    every: u64,
    overlay: bool,
    last_index: Option<u64>,
    /// Frames the camera had taken at the previous offer (None before the first).
    frames_seen: Option<u64>,
    /// The captions of the frames to keep that were exposed but not yet saved, by index.
    exposed: Vec<(u64, Vec<String>)>,
}

impl FrameSaver {
    /// A saver writing into `dir` (created on the first frame).
    pub fn new(dir: &Path, every: u32, overlay: bool) -> Self {
        Self {
            dir: dir.to_path_buf(),
            every: u64::from(every.max(1)),
            overlay,
            last_index: None,
            frames_seen: None,
            exposed: Vec::new(),
        }
    }

    /// Called after every step: keeps `captions()` (the state now) when a frame to save was
    /// exposed at this step, and saves the camera's last measured frame if it is new and its
    /// index is a multiple of N, with its time and the captions of its exposure under the
    /// overlay's status line (when the overlay is on). A frame exposed before the first
    /// offer (frame 0, at the simulation's start) carries its time only.
    pub fn offer(
        &mut self,
        camera: &CameraSensor,
        captions: impl FnOnce() -> Vec<String>,
    ) -> Result<(), FrameWriteError> {
        let taken = camera.frames();
        let newly_exposed = self.frames_seen.is_some_and(|seen| taken > seen);
        self.frames_seen = Some(taken);
        if let Some(index) = taken.checked_sub(1)
            && newly_exposed
            && self.overlay
            && index.is_multiple_of(self.every)
        {
            self.exposed.push((index, captions()));
        }
        let Some((frame, record, blob)) = camera.last_frame() else {
            return Ok(());
        };
        if self.last_index == Some(record.index) || !record.index.is_multiple_of(self.every) {
            return Ok(());
        }
        self.last_index = Some(record.index);
        create_dir(&self.dir)?;
        let path = self.dir.join(format!("{:06}.png", record.index));
        let at_exposure = self
            .exposed
            .iter()
            .position(|(index, _)| *index == record.index)
            .map(|k| self.exposed.swap_remove(k).1)
            .unwrap_or_default();
        self.exposed.retain(|(index, _)| *index > record.index);
        let overlay = self.overlay.then(|| Overlay {
            measurement: blob,
            captions: [frame_caption(record.index, record.t_s)]
                .into_iter()
                .chain(at_exposure)
                .collect(),
        });
        write_frame(&path, frame, overlay.as_ref())
    }
}

/// The overlay's line for a frame's number and the time it was exposed:
/// `FRAME 30 T 1.000 S`.
pub fn frame_caption(index: u64, t_s: f64) -> String {
    format!("FRAME {index} T {t_s:.3} S")
}

/// What is drawn over a saved frame: its measurement and lines of text under the status.
#[derive(Debug)]
pub struct Overlay<'a> {
    /// The frame's measurement.
    pub measurement: &'a BlobMeasurement,
    /// Lines under the status line (e.g. the gimbal's angles).
    pub captions: Vec<String>,
}

/// The overlay's line for a gimbal, in degrees: `GIMBAL PAN 23.4 TILT -5.1 CMD 24.0 -5.0`,
/// with `ROLL -30.2` after the tilt where it has a roll axis.
pub fn gimbal_captions(reading: Option<GimbalReading>) -> Vec<String> {
    reading
        .map(|g| {
            let deg = |a: &GimbalAngles| (a.pan_rad.to_degrees(), a.tilt_rad.to_degrees());
            let ((pan, tilt), (pan_c, tilt_c)) = (deg(&g.angles), deg(&g.command));
            let roll = if g.roll_axis {
                format!(" ROLL {:.1}", g.angles.roll_rad.to_degrees())
            } else {
                String::new()
            };
            format!("GIMBAL PAN {pan:.1} TILT {tilt:.1}{roll} CMD {pan_c:.1} {tilt_c:.1}")
        })
        .into_iter()
        .collect()
}

/// Writes a frame as PNG, with the overlay drawn on a copy when given.
pub fn write_frame(
    path: &Path,
    frame: &CameraImage,
    overlay: Option<&Overlay>,
) -> Result<(), FrameWriteError> {
    let Some(overlay) = overlay else {
        return Ok(frame.save_png(path)?);
    };
    let mut copy = frame.clone();
    let (w, h) = (copy.width_px, copy.height_px);
    draw_measurement_overlay(&mut copy.rgba, w, h, overlay.measurement)?;
    for (k, caption) in overlay.captions.iter().enumerate() {
        draw_caption(&mut copy.rgba, w, h, k + 1, caption)?;
    }
    Ok(copy.save_png(path)?)
}

/// Why `wingman render` could not write its frame.
#[derive(Debug, thiserror::Error)]
pub enum RenderImageSizeError {
    /// The simulation stopped before the requested time.
    #[error("{0}")]
    Sim(#[from] crate::sim::SimError),
    /// The camera could not be set up or the frame not taken.
    #[error("{0}")]
    Camera(#[from] crate::sensing::SensorError),
    /// The camera took no frame (cannot happen once a frame was captured).
    #[error("no frame was taken")]
    NoFrame,
    /// The PNG could not be written.
    #[error("{0}")]
    Write(#[from] FrameWriteError),
}

/// Runs `scenario` to `t_s` (no outputs), takes one camera frame of the geometry there with the
/// scenario's `[camera]` (whatever its sensor mode), and writes it to `path` with the measured
/// (status colour) and true (projected mesh) maximal-length segments and centroids drawn on it.
pub fn render_frame_at(
    scenario: &crate::scenario::Scenario,
    t_s: f64,
    path: &Path,
) -> Result<crate::sensing::FrameRecord, RenderImageSizeError> {
    let mut sim = crate::sim::Simulation::new(scenario)?;
    let target_tick = (t_s / scenario.run.dt_s).round() as u64;
    while sim.tick() < target_tick.min(sim.total_ticks()) {
        match sim.step()? {
            crate::sim::StepOutcome::Running => {}
            _ => break,
        }
    }
    let mut camera = CameraSensor::new(&CameraConfig::of(scenario))?;
    let geometry = sim.capture_geometry();
    camera.capture_now(sim.time_s(), &geometry)?;
    let Some((frame, record, blob)) = camera.last_frame() else {
        return Err(RenderImageSizeError::NoFrame);
    };
    let mut copy = frame.clone();
    let intrinsics = *camera.intrinsics();
    if let Some(truth) = camera.last_truth() {
        crate::vision::overlay::draw_truth_overlay(&mut copy.rgba, &intrinsics, &truth)
            .map_err(FrameWriteError::from)?;
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        create_dir(dir)?;
    }
    let overlay = Overlay {
        measurement: blob,
        captions: [frame_caption(record.index, record.t_s)]
            .into_iter()
            .chain(gimbal_captions(sim.gimbal_reading()))
            .collect(),
    };
    write_frame(path, &copy, Some(&overlay))?;
    Ok(*record)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The overlay's gimbal line gives the roll only where the gimbal has a roll axis.
    #[test]
    fn the_gimbal_caption_gives_the_roll_of_a_roll_axis() {
        let angles = GimbalAngles {
            pan_rad: 0.5,
            tilt_rad: -0.25,
            roll_rad: -0.5,
        };
        let reading = |roll_axis| GimbalReading {
            angles,
            command: angles,
            roll_axis,
        };
        assert_eq!(
            gimbal_captions(Some(reading(true))),
            ["GIMBAL PAN 28.6 TILT -14.3 ROLL -28.6 CMD 28.6 -14.3"]
        );
        assert_eq!(
            gimbal_captions(Some(reading(false))),
            ["GIMBAL PAN 28.6 TILT -14.3 CMD 28.6 -14.3"]
        );
    }
}
