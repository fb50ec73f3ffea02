//! The encoders of `wingman export video` (docs/viewer.md, A video): ffmpeg when `ffmpeg` is
//! on the PATH, fed the RGBA frames through a pipe and writing an MP4 (H.264 through libx264,
//! or MPEG-4 part 2 where this ffmpeg has no libx264); otherwise an animated PNG (APNG)
//! written by the `png` crate, which `image` already builds: no new dependency, no system
//! package. Browsers and most image viewers play an APNG.

use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};

/// Why the encoder failed or the video could not be written: the file and what was said.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct EncodeError(pub String);

/// Which encoder writes the video.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoder {
    /// ffmpeg when it is on the PATH, the animated PNG otherwise.
    Auto,
    /// ffmpeg (MP4).
    Ffmpeg,
    /// The animated PNG (APNG).
    Apng,
}

impl Encoder {
    /// `Auto` decided: `Ffmpeg` when `ffmpeg -version` runs, `Apng` otherwise.
    pub fn resolve(self) -> Self {
        match self {
            Self::Auto if ffmpeg_codec().is_some() => Self::Ffmpeg,
            Self::Auto => Self::Apng,
            chosen => chosen,
        }
    }

    /// The video file's extension.
    pub fn extension(self) -> &'static str {
        match self {
            Self::Apng => "apng",
            _ => "mp4",
        }
    }
}

/// The codec ffmpeg encodes with, `libx264` or `mpeg4`; `None` when there is no ffmpeg.
pub fn ffmpeg_codec() -> Option<&'static str> {
    let listed = Command::new("ffmpeg")
        .args(["-hide_banner", "-encoders"])
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .output()
        .ok()
        .filter(|o| o.status.success())?;
    let text = String::from_utf8_lossy(&listed.stdout);
    let has = |codec: &str| {
        text.lines()
            .any(|l| l.split_whitespace().nth(1) == Some(codec))
    };
    if has("libx264") {
        Some("libx264")
    } else {
        Some("mpeg4")
    }
}

/// What a video holds: frame size (px), frame count, and the saved frames' spacing in camera
/// frames over the camera's rate (their playback period is `step / rate_hz` s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VideoFormat {
    /// Frame width, px.
    pub width_px: u32,
    /// Frame height, px.
    pub height_px: u32,
    /// Frames to come.
    pub frames: usize,
    /// Camera frames between saved frames.
    pub step: u64,
    /// The camera's frame rate, Hz.
    pub rate_hz: f64,
}

impl VideoFormat {
    /// Frames per second of playback (real time).
    pub fn fps(&self) -> f64 {
        self.rate_hz / self.step as f64
    }

    /// An APNG frame's delay as the fraction (numerator, denominator) of a second: exactly
    /// `step / rate_hz` when both fit 16 bits and the rate is whole, in ms otherwise.
    fn delay_fraction(&self) -> (u16, u16) {
        let whole = self.rate_hz.fract() == 0.0 && self.rate_hz <= f64::from(u16::MAX);
        match u16::try_from(self.step) {
            Ok(step) if whole => (step, self.rate_hz as u16),
            _ => (
                (1000.0 / self.fps()).round().clamp(1.0, 65535.0) as u16,
                1000,
            ),
        }
    }
}

/// Takes RGBA8 frames one by one and writes the video.
pub trait FrameSink {
    /// One frame, `width * height * 4` bytes, top row first.
    fn push(&mut self, rgba: &[u8]) -> Result<(), EncodeError>;
    /// Ends the video; what encoded it (e.g. `ffmpeg libx264 (MP4)`).
    fn finish(self: Box<Self>) -> Result<String, EncodeError>;
}

fn encode_error(path: &Path, what: impl std::fmt::Display) -> EncodeError {
    EncodeError(format!("{}: {what}", path.display()))
}

/// The encoder's sink writing `path` (its folder made).
pub fn open_sink(
    encoder: Encoder,
    path: &Path,
    format: &VideoFormat,
) -> Result<Box<dyn FrameSink>, EncodeError> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| encode_error(dir, e))?;
    }
    match encoder.resolve() {
        Encoder::Apng => Ok(Box::new(ApngSink::new(path, format)?)),
        _ => Ok(Box::new(FfmpegSink::spawn(path, format)?)),
    }
}

/// The animated PNG, written as the frames come.
struct ApngSink {
    path: PathBuf,
    writer: png::Writer<BufWriter<std::fs::File>>,
}

impl ApngSink {
    fn new(path: &Path, format: &VideoFormat) -> Result<Self, EncodeError> {
        let file = std::fs::File::create(path).map_err(|e| encode_error(path, e))?;
        let mut encoder =
            png::Encoder::new(BufWriter::new(file), format.width_px, format.height_px);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        let frames = u32::try_from(format.frames).map_err(|e| encode_error(path, e))?;
        let (numerator, denominator) = format.delay_fraction();
        let writer = encoder
            .set_animated(frames, 0)
            .and_then(|()| encoder.set_frame_delay(numerator, denominator))
            .and_then(|()| encoder.write_header())
            .map_err(|e| encode_error(path, e))?;
        Ok(Self {
            path: path.to_path_buf(),
            writer,
        })
    }
}

impl FrameSink for ApngSink {
    fn push(&mut self, rgba: &[u8]) -> Result<(), EncodeError> {
        self.writer
            .write_image_data(rgba)
            .map_err(|e| encode_error(&self.path, e))
    }

    fn finish(self: Box<Self>) -> Result<String, EncodeError> {
        let path = self.path.clone();
        self.writer.finish().map_err(|e| encode_error(&path, e))?;
        Ok("png crate (animated PNG)".to_string())
    }
}

/// ffmpeg reading raw RGBA frames on its standard input.
struct FfmpegSink {
    path: PathBuf,
    codec: &'static str,
    child: Child,
    stdin: Option<BufWriter<ChildStdin>>,
}

impl FfmpegSink {
    fn spawn(path: &Path, format: &VideoFormat) -> Result<Self, EncodeError> {
        let codec =
            ffmpeg_codec().ok_or_else(|| encode_error(path, "ffmpeg is not on the PATH"))?;
        let size = format!("{}x{}", format.width_px, format.height_px);
        let rate = format!("{}", format.fps());
        let mut command = Command::new("ffmpeg");
        command
            .args(["-hide_banner", "-loglevel", "error", "-y", "-f", "rawvideo"])
            .args([
                "-pix_fmt",
                "rgba",
                "-s",
                &size,
                "-framerate",
                &rate,
                "-i",
                "-",
            ])
            // yuv420p, which most players need, wants an even width and height.
            .args(["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", codec])
            .args(["-pix_fmt", "yuv420p", "-movflags", "+faststart"]);
        if codec == "mpeg4" {
            command.args(["-q:v", "3"]);
        }
        let mut child = command
            .arg(path)
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| encode_error(path, format!("cannot start ffmpeg: {e}")))?;
        let stdin = child.stdin.take().map(BufWriter::new);
        Ok(Self {
            path: path.to_path_buf(),
            codec,
            child,
            stdin,
        })
    }

    /// Closes ffmpeg's input and waits for it; its error output when it failed.
    fn close(&mut self) -> Result<(), EncodeError> {
        let flushed = self.stdin.take().map_or(Ok(()), |mut s| s.flush());
        let status = self.child.wait().map_err(|e| encode_error(&self.path, e))?;
        if status.success() && flushed.is_ok() {
            return Ok(());
        }
        let mut said = String::new();
        if let Some(mut stderr) = self.child.stderr.take() {
            let _ = stderr.read_to_string(&mut said);
        }
        let said = said.trim();
        Err(encode_error(
            &self.path,
            format!("ffmpeg failed ({status}): {said}"),
        ))
    }
}

impl FrameSink for FfmpegSink {
    fn push(&mut self, rgba: &[u8]) -> Result<(), EncodeError> {
        let written = match self.stdin.as_mut() {
            Some(stdin) => stdin.write_all(rgba),
            None => Err(std::io::ErrorKind::BrokenPipe.into()),
        };
        match written {
            Ok(()) => Ok(()),
            Err(e) => Err(self
                .close()
                .err()
                .unwrap_or_else(|| encode_error(&self.path, e))),
        }
    }

    fn finish(mut self: Box<Self>) -> Result<String, EncodeError> {
        self.close()?;
        Ok(format!("ffmpeg {} (MP4)", self.codec))
    }
}
