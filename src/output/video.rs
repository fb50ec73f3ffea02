//! `wingman export video RUN_DIR`: a finished run folder's saved frames (`frames/NNNNNN.png`,
//! docs/outputs.md) as one video per camera, played at the rate they were taken, each frame
//! captioned at its foot with its exposure time and its measurement's status as
//! `telemetry.csv` logged it (docs/viewer.md, A video). The encoders are in
//! [`super::video_encoders`]: ffmpeg (MP4) when it is on the PATH, an animated PNG otherwise.

use super::video_encoders::{EncodeError, Encoder, VideoFormat, open_sink};
use crate::render::image::CameraImage;
use crate::vision::overlay::draw_footer;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Why a video could not be made.
#[derive(Debug, thiserror::Error)]
pub enum VideoError {
    /// The folder is not a run folder with saved frames (a bad argument).
    #[error("{0}")]
    NotARun(String),
    /// A frame could not be read, or frames differ in size.
    #[error("{0}")]
    BadFrame(String),
    /// The encoder failed, or the video could not be written.
    #[error(transparent)]
    Encode(#[from] EncodeError),
}

impl VideoError {
    /// Whether the command line's argument is to blame (exit code 2) rather than the machine.
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, Self::Encode(_))
    }
}

/// A video written.
#[derive(Debug, Clone, PartialEq)]
pub struct VideoWritten {
    /// The video file.
    pub path: PathBuf,
    /// The camera it shows: `None` for the follower's `frames/`, the name of `frames/NAME/`.
    pub camera: Option<String>,
    /// What encoded it, e.g. `ffmpeg libx264 (MP4)`, `png crate (animated PNG)`.
    pub encoder: String,
    /// Frames in the video.
    pub frames: usize,
    /// Frame size, px (before any padding to even sizes).
    pub width_px: u32,
    /// Frame height, px.
    pub height_px: u32,
    /// Playback rate, frames per second: `camera.rate_hz` over the saved frames' spacing.
    pub fps: f64,
}

/// One camera's saved frames: its name and its frames by number.
#[derive(Debug)]
struct FrameSource {
    camera: Option<String>,
    frames: Vec<(u64, PathBuf)>,
}

/// The frames `NNNNNN.png` in `dir`, by number.
fn numbered_pngs(dir: &Path) -> Vec<(u64, PathBuf)> {
    let mut found: Vec<(u64, PathBuf)> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "png"))
        .filter_map(|p| Some((p.file_stem()?.to_str()?.parse::<u64>().ok()?, p)))
        .collect();
    found.sort();
    found
}

/// Every camera of a run folder: the follower's `frames/*.png`, and each `frames/NAME/`
/// holding frames (a run with several followers' cameras), by name.
fn frame_sources(run_dir: &Path) -> Vec<FrameSource> {
    let dir = run_dir.join("frames");
    let mut sources = vec![FrameSource {
        camera: None,
        frames: numbered_pngs(&dir),
    }];
    let mut named: Vec<PathBuf> = std::fs::read_dir(&dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect();
    named.sort();
    for sub in named {
        let camera = sub.file_name().map(|n| n.to_string_lossy().into_owned());
        let frames = numbered_pngs(&sub);
        sources.push(FrameSource { camera, frames });
    }
    sources.retain(|s| !s.frames.is_empty());
    sources
}

/// `camera.rate_hz` of the run's resolved `scenario.toml`.
fn camera_rate_hz(run_dir: &Path) -> Result<f64, VideoError> {
    let path = run_dir.join("scenario.toml");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| VideoError::NotARun(format!("{}: {e} (not a run folder)", path.display())))?;
    let value: toml::Value = toml::from_str(&text)
        .map_err(|e| VideoError::NotARun(format!("{}: {e}", path.display())))?;
    value
        .get("camera")
        .and_then(|c| c.get("rate_hz"))
        .and_then(|r| r.as_float().or_else(|| r.as_integer().map(|i| i as f64)))
        .filter(|r| *r > 0.0)
        .ok_or_else(|| VideoError::NotARun(format!("{}: no camera.rate_hz", path.display())))
}

/// The saved frames' spacing in camera frames (`output.frames_every`): the smallest step
/// between consecutive numbers, 1 for a single frame.
fn frame_step(frames: &[(u64, PathBuf)]) -> u64 {
    frames
        .windows(2)
        .map(|w| w[1].0 - w[0].0)
        .filter(|d| *d > 0)
        .min()
        .unwrap_or(1)
}

/// Frame number -> `meas_status` of the first telemetry row holding that frame (columns
/// `frame_t_s` and `meas_status`, prefixed `NAME_` for camera `NAME`); empty when the
/// telemetry is absent or has no camera columns.
fn frame_statuses(run_dir: &Path, camera: Option<&str>, rate_hz: f64) -> HashMap<u64, u8> {
    let prefix = camera.map(|c| format!("{c}_")).unwrap_or_default();
    let Ok(mut reader) = csv::Reader::from_path(run_dir.join("telemetry.csv")) else {
        return HashMap::new();
    };
    let Ok(header) = reader.headers().cloned() else {
        return HashMap::new();
    };
    let column = |name: String| header.iter().position(|h| h == name);
    let (Some(t_col), Some(s_col)) = (
        column(format!("{prefix}frame_t_s")),
        column(format!("{prefix}meas_status")),
    ) else {
        return HashMap::new();
    };
    let mut statuses = HashMap::new();
    for record in reader.records().flatten() {
        let (Some(t), Some(s)) = (record.get(t_col), record.get(s_col)) else {
            continue;
        };
        if let (Ok(t_s), Ok(status)) = (t.parse::<f64>(), s.parse::<u8>()) {
            let number = (t_s * rate_hz).round() as u64;
            statuses.entry(number).or_insert(status);
        }
    }
    statuses
}

/// The caption at a frame's foot: `T 12.345 S  TRACK OK` (`TRACK LOST`, `TRACK AT BORDER`,
/// `TRACK TOO SMALL`; `NO MEASUREMENT` for a frame the telemetry holds no measurement of).
pub fn video_caption(t_s: f64, meas_status: Option<u8>) -> String {
    let track = match meas_status {
        Some(0) => "TRACK OK",
        Some(1) => "TRACK LOST",
        Some(2) => "TRACK AT BORDER",
        Some(3) => "TRACK TOO SMALL",
        _ => "NO MEASUREMENT",
    };
    format!("T {t_s:.3} S  {track}")
}

/// The video file for a camera: `out` (default `RUN_DIR/video.EXT`), with `_NAME` before the
/// extension for camera `NAME`.
fn video_path(run_dir: &Path, out: Option<&Path>, camera: Option<&str>, ext: &str) -> PathBuf {
    let base = out.map_or_else(|| run_dir.join(format!("video.{ext}")), Path::to_path_buf);
    match camera {
        None => base,
        Some(name) => {
            let stem = base.file_stem().unwrap_or_default().to_string_lossy();
            let ext = base
                .extension()
                .map_or(ext.to_string(), |e| e.to_string_lossy().into());
            base.with_file_name(format!("{stem}_{name}.{ext}"))
        }
    }
}

/// Decodes a saved frame as RGBA8.
fn read_frame(path: &Path) -> Result<CameraImage, VideoError> {
    CameraImage::read_png(path).map_err(|e| VideoError::BadFrame(e.to_string()))
}

/// Writes a run folder's videos, one per camera (see the module's documentation): `out`
/// names the file (default `RUN_DIR/video.mp4` with ffmpeg, `RUN_DIR/video.apng` without),
/// `encoder` picks the encoder. A group run's folder (`group.json`) gives one video per
/// follower that saved frames, named `_NAME` as another camera's.
pub fn export_video(
    run_dir: &Path,
    out: Option<&Path>,
    encoder: Encoder,
) -> Result<Vec<VideoWritten>, VideoError> {
    if run_dir.join("group.json").is_file() {
        return export_group_videos(run_dir, out, encoder);
    }
    let rate_hz = camera_rate_hz(run_dir)?;
    let sources = frame_sources(run_dir);
    if sources.is_empty() {
        return Err(VideoError::NotARun(format!(
            "{}: no saved frames (run with --set output.frames_every=1 for every frame)",
            run_dir.join("frames").display()
        )));
    }
    let encoder = encoder.resolve();
    sources
        .iter()
        .map(|source| write_video(run_dir, out, encoder, source, rate_hz))
        .collect()
}

/// A group run's videos: each follower's folder (one holding a `scenario.toml`) with saved
/// frames, as `video_NAME.EXT` in the group's folder (or `out` with `_NAME`).
fn export_group_videos(
    run_dir: &Path,
    out: Option<&Path>,
    encoder: Encoder,
) -> Result<Vec<VideoWritten>, VideoError> {
    let mut followers: Vec<PathBuf> = std::fs::read_dir(run_dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("scenario.toml").is_file())
        .collect();
    followers.sort();
    let encoder = encoder.resolve();
    let mut written = Vec::new();
    for dir in followers {
        let name = dir.file_name().unwrap_or_default().to_string_lossy();
        if numbered_pngs(&dir.join("frames")).is_empty() {
            continue;
        }
        let path = video_path(run_dir, out, Some(&name), encoder.extension());
        for mut video in export_video(&dir, Some(&path), encoder)? {
            video.camera = Some(name.to_string());
            written.push(video);
        }
    }
    if written.is_empty() {
        return Err(VideoError::NotARun(format!(
            "{}: a group run whose followers saved no frames (run with --set \
             output.frames_every=1 for every frame)",
            run_dir.display()
        )));
    }
    Ok(written)
}

/// One camera's video.
fn write_video(
    run_dir: &Path,
    out: Option<&Path>,
    encoder: Encoder,
    source: &FrameSource,
    rate_hz: f64,
) -> Result<VideoWritten, VideoError> {
    let camera = source.camera.as_deref();
    let step = frame_step(&source.frames);
    let statuses = frame_statuses(run_dir, camera, rate_hz);
    let first = read_frame(&source.frames[0].1)?;
    let (width_px, height_px) = (first.width_px, first.height_px);
    let path = video_path(run_dir, out, camera, encoder.extension());
    let format = VideoFormat {
        width_px,
        height_px,
        frames: source.frames.len(),
        step,
        rate_hz,
    };
    let mut sink = open_sink(encoder, &path, &format)?;
    for (k, (number, png)) in source.frames.iter().enumerate() {
        let mut frame = if k == 0 {
            first.clone()
        } else {
            read_frame(png)?
        };
        if (frame.width_px, frame.height_px) != (width_px, height_px) {
            return Err(VideoError::BadFrame(format!(
                "{}: {}x{} px, the first frame {width_px}x{height_px}",
                png.display(),
                frame.width_px,
                frame.height_px
            )));
        }
        let caption = video_caption(*number as f64 / rate_hz, statuses.get(number).copied());
        draw_footer(&mut frame.rgba, width_px, height_px, &caption)
            .map_err(|e| VideoError::BadFrame(format!("{}: {e}", png.display())))?;
        sink.push(&frame.rgba)?;
    }
    let encoder_name = sink.finish()?;
    Ok(VideoWritten {
        path,
        camera: source.camera.clone(),
        encoder: encoder_name,
        frames: source.frames.len(),
        width_px,
        height_px,
        fps: format.fps(),
    })
}
