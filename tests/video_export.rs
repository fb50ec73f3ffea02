//! `wingman export video` turns a run folder's saved frames into one video per camera with
//! every frame in it, in order, at the camera's rate over the frames' spacing, at the frames'
//! size (ffmpeg pads odd sizes to even), each captioned at its foot with its time and the
//! track status its telemetry row gives; the animated PNG always, the MP4 where ffmpeg is on
//! the PATH (CI installs it). A group run's folder gives one video per follower that saved
//! frames. A folder without frames, or an `export rerun` without the Python package, is
//! refused in one line with exit codes 2 and 1.

use std::io::Cursor;
use std::path::Path;
use std::process::Command;
use wingman::output::video::{export_video, video_caption};
use wingman::output::video_encoders::{Encoder, ffmpeg_codec};
use wingman::render::CameraImage;

const WIDTH: u32 = 41;
const HEIGHT: u32 = 31;
/// Saved frames: every second camera frame of a 30 Hz camera.
const NUMBERS: [u64; 6] = [0, 2, 4, 6, 8, 10];

/// The grey level of saved frame `number` (so that the order can be read back).
fn grey(number: u64) -> u8 {
    20 + 20 * number as u8
}

/// A run folder with a 30 Hz camera, six frames saved every second frame into `frames/` (and
/// `frames/wing2/` when `second_camera`), and telemetry holding their statuses: frame 4 lost.
fn run_folder(dir: &Path, second_camera: bool) {
    std::fs::write(dir.join("scenario.toml"), "[camera]\nrate_hz = 30.0\n").unwrap();
    let mut csv = String::from("t_s,frame_t_s,meas_status\n");
    for n in NUMBERS {
        let status = if n == 4 { 1 } else { 0 };
        csv += &format!("{},{},{status}\n", n as f64 / 30.0 + 0.01, n as f64 / 30.0);
    }
    std::fs::write(dir.join("telemetry.csv"), csv).unwrap();
    let mut folders = vec![dir.join("frames")];
    if second_camera {
        folders.push(dir.join("frames").join("wing2"));
    }
    for folder in folders {
        std::fs::create_dir_all(&folder).unwrap();
        for n in NUMBERS {
            let g = grey(n);
            let img = CameraImage::filled(WIDTH, HEIGHT, [g, g, g, 255]);
            img.save_png(&folder.join(format!("{n:06}.png"))).unwrap();
        }
    }
}

/// Every frame of an animated PNG: (delay numerator, denominator, RGBA).
fn apng_frames(path: &Path) -> Vec<(u16, u16, Vec<u8>)> {
    let bytes = std::fs::read(path).unwrap();
    let mut reader = png::Decoder::new(Cursor::new(bytes)).read_info().unwrap();
    let info = reader.info();
    assert_eq!((info.width, info.height), (WIDTH, HEIGHT));
    let count = info.animation_control.expect("an animated PNG").num_frames;
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    (0..count)
        .map(|_| {
            reader.next_frame(&mut buf).unwrap();
            let fc = reader.info().frame_control.expect("a frame control chunk");
            (fc.delay_num, fc.delay_den, buf.clone())
        })
        .collect()
}

#[test]
fn animated_png_holds_every_frame_in_order_with_its_caption() {
    let dir = tempfile::tempdir().unwrap();
    run_folder(dir.path(), false);
    let videos = export_video(dir.path(), None, Encoder::Apng).unwrap();
    assert_eq!(videos.len(), 1);
    let v = &videos[0];
    assert_eq!(v.path, dir.path().join("video.apng"));
    assert_eq!(
        (v.frames, v.width_px, v.height_px, v.fps),
        (6, WIDTH, HEIGHT, 15.0)
    );
    let frames = apng_frames(&v.path);
    assert_eq!(frames.len(), NUMBERS.len());
    for ((num, den, rgba), n) in frames.iter().zip(NUMBERS) {
        assert_eq!((*num, *den), (2, 30), "frame {n}: each lasts 2/30 s");
        assert_eq!(
            rgba[..3],
            [grey(n); 3],
            "frame {n}: top-left pixel, in order"
        );
        // The caption's dark box and white text sit in the bottom rows.
        let bottom = &rgba[(HEIGHT as usize - 12) * WIDTH as usize * 4..];
        assert!(bottom.chunks(4).any(|p| p[..3] == [0, 0, 0]), "frame {n}");
        assert!(
            bottom.chunks(4).any(|p| p[..3] == [255, 255, 255]),
            "frame {n}"
        );
    }
}

#[test]
fn captions_say_time_and_track_status() {
    assert_eq!(video_caption(4.0 / 30.0, Some(1)), "T 0.133 S  TRACK LOST");
    assert_eq!(video_caption(2.0, Some(0)), "T 2.000 S  TRACK OK");
    assert_eq!(video_caption(2.0, Some(2)), "T 2.000 S  TRACK AT BORDER");
    assert_eq!(video_caption(0.0, None), "T 0.000 S  NO MEASUREMENT");
}

#[test]
fn each_camera_has_its_own_video() {
    let dir = tempfile::tempdir().unwrap();
    run_folder(dir.path(), true);
    let out = dir.path().join("out").join("clip.apng");
    let videos = export_video(dir.path(), Some(&out), Encoder::Apng).unwrap();
    let names: Vec<_> = videos.iter().map(|v| v.path.clone()).collect();
    assert_eq!(
        names,
        [out.clone(), dir.path().join("out").join("clip_wing2.apng")]
    );
    assert_eq!(videos[1].camera.as_deref(), Some("wing2"));
    for v in &videos {
        assert_eq!(apng_frames(&v.path).len(), NUMBERS.len());
    }
}

#[test]
fn a_group_run_has_a_video_per_follower_with_frames() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("group.json"), "{}\n").unwrap();
    for name in ["f1", "f2", "f3"] {
        std::fs::create_dir(dir.path().join(name)).unwrap();
        run_folder(&dir.path().join(name), false);
    }
    std::fs::remove_dir_all(dir.path().join("f3").join("frames")).unwrap();
    let videos = export_video(dir.path(), None, Encoder::Apng).unwrap();
    let cameras: Vec<_> = videos.iter().map(|v| v.camera.as_deref()).collect();
    assert_eq!(cameras, [Some("f1"), Some("f2")]);
    for (v, name) in videos.iter().zip(["f1", "f2"]) {
        assert_eq!(v.path, dir.path().join(format!("video_{name}.apng")));
        assert_eq!(apng_frames(&v.path).len(), NUMBERS.len());
    }
    std::fs::remove_dir_all(dir.path().join("f1").join("frames")).unwrap();
    std::fs::remove_dir_all(dir.path().join("f2").join("frames")).unwrap();
    let refused = export_video(dir.path(), None, Encoder::Apng).unwrap_err();
    assert!(refused.is_bad_input(), "{refused}");
}

/// ffprobe's count of decoded frames, width, height and frame rate of an MP4.
fn probe(path: &Path) -> String {
    let out = Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0"])
        .args([
            "-show_entries",
            "stream=nb_read_frames,width,height,r_frame_rate",
        ])
        .args(["-of", "default=noprint_wrappers=1"])
        .arg(path)
        .output()
        .expect("ffprobe comes with ffmpeg");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn mp4_through_ffmpeg_holds_every_frame() {
    let Some(codec) = ffmpeg_codec() else {
        eprintln!("skipped: no ffmpeg on the PATH (the animated PNG is tested above)");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    run_folder(dir.path(), false);
    let v = &export_video(dir.path(), None, Encoder::Auto).unwrap()[0];
    assert_eq!(v.path, dir.path().join("video.mp4"));
    assert_eq!(v.encoder, format!("ffmpeg {codec} (MP4)"));
    let probed = probe(&v.path);
    // Padded to even sizes for yuv420p.
    for line in [
        "width=42",
        "height=32",
        "r_frame_rate=15/1",
        "nb_read_frames=6",
    ] {
        assert!(probed.lines().any(|l| l == line), "{line} in {probed}");
    }
}

fn wingman(args: &[&str], envs: &[(&str, &str)]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_wingman"))
        .args(args)
        .envs(envs.iter().copied())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    (out.status.code().unwrap_or(-1), stderr)
}

#[test]
fn refusals_are_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let run = dir.path().to_str().unwrap();
    let (code, said) = wingman(&["export", "video", run], &[]);
    assert_eq!((code, said.lines().count()), (2, 1), "{said}");
    assert!(said.contains("scenario.toml"), "{said}");
    run_folder(dir.path(), false);
    std::fs::remove_dir_all(dir.path().join("frames")).unwrap();
    let (code, said) = wingman(&["export", "video", run], &[]);
    assert_eq!((code, said.lines().count()), (2, 1), "{said}");
    assert!(said.contains("output.frames_every"), "{said}");
    let out = dir.path().join("run.rrd");
    let args = ["export", "rerun", run, "--out", out.to_str().unwrap()];
    let (code, said) = wingman(&args, &[("WINGMAN_PYTHON", "/nonexistent/python")]);
    assert_eq!((code, said.lines().count()), (1, 1), "{said}");
    assert!(said.contains("scripts/install_python.sh"), "{said}");
    let args = ["export", "rerun", run, "--out", run];
    let (code, said) = wingman(&args, &[]);
    assert_eq!((code, said.lines().count()), (2, 1), "{said}");
    assert!(!out.exists());
}
