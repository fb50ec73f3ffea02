//! A disk that fills up during a run degrades its outputs in order: the summary (small, its
//! space taken first) is always written, whole, and names what was not written; the telemetry
//! keeps whole rows; a plot that cannot be written leaves no cut-off file and is named in the
//! summary; the run exits 1 with one plain line (no Rust debug dump). Shown on a small tmpfs
//! where this machine may mount one, and everywhere with a file-size limit (RLIMIT_FSIZE) that
//! makes the writes fail the same way.

use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::Command;
use wingman::render::CameraImage;

/// `wingman run formation.toml` for 20 s into `out`, with `limit_bytes` as the largest file
/// it may write (none: no limit); its exit code and standard error.
fn run_formation(out: &Path, limit_bytes: Option<u64>) -> (i32, String) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_wingman"));
    command
        .args(["run", "scenarios/formation.toml", "--quiet", "--out"])
        .arg(out)
        .args(["--set", "run.duration_s=20"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("NODEVICE_SELECT", "1");
    if let Some(limit) = limit_bytes {
        // SAFETY: only async-signal-safe calls between fork and exec.
        unsafe {
            command.pre_exec(move || {
                let rlimit = libc::rlimit {
                    rlim_cur: limit,
                    rlim_max: limit,
                };
                // A write past the limit then fails with EFBIG instead of a signal.
                libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
                match libc::setrlimit(libc::RLIMIT_FSIZE, &rlimit) {
                    0 => Ok(()),
                    _ => Err(std::io::Error::last_os_error()),
                }
            });
        }
    }
    let output = command.output().expect("binary runs");
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// The folder's invariants after a failed write; returns the summary's `unwritten` list.
fn assert_degraded_in_order(out: &Path, code: i32, stderr: &str) -> Vec<String> {
    assert_eq!(code, 1, "{stderr}");
    let error_lines: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error")).collect();
    assert_eq!(error_lines.len(), 1, "{stderr}");
    for dump in ["Custom {", "Os {", "kind:", "ImageError", "IoError"] {
        assert!(!stderr.contains(dump), "a debug dump: {stderr}");
    }
    let text = std::fs::read_to_string(out.join("summary.json")).expect("summary written");
    let summary: serde_json::Value = serde_json::from_str(&text).expect("summary whole");
    assert_eq!(summary["status"], "completed", "{text}");
    assert!(!out.join("summary.json.partial").exists());
    let telemetry = std::fs::read_to_string(out.join("telemetry.csv")).expect("telemetry");
    assert!(telemetry.ends_with('\n'), "a cut-off last row");
    let columns = telemetry.lines().next().expect("header").split(',').count();
    assert!(
        telemetry.lines().all(|l| l.split(',').count() == columns),
        "a row that is not whole"
    );
    if let Ok(entries) = std::fs::read_dir(out.join("plots")) {
        for entry in entries {
            let path = entry.expect("entry").path();
            CameraImage::read_png(&path).unwrap_or_else(|e| panic!("{e}"));
        }
    }
    let unwritten: Vec<String> = summary["unwritten"]
        .as_array()
        .expect("unwritten")
        .iter()
        .map(|v| v.as_str().expect("text").to_string())
        .collect();
    assert!(stderr.contains("not written: "), "{stderr}");
    unwritten
}

/// Files may not grow past 90 KB: the telemetry stops at its last whole row, the first plot
/// (about 100 KB) is not written and is named, the summary is whole.
#[test]
fn a_write_limit_degrades_in_order() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("run");
    let (code, stderr) = run_formation(&out, Some(90 * 1024));
    let unwritten = assert_degraded_in_order(&out, code, &stderr);
    assert!(unwritten[0].starts_with("telemetry.csv: "), "{unwritten:?}");
    assert!(unwritten[0].contains("File too large"), "{unwritten:?}");
    assert!(
        unwritten[1].starts_with("plots (none after this one): cannot write")
            && unwritten[1].contains("relative_position.png"),
        "{unwritten:?}"
    );
}

/// A tmpfs mounted on a folder, unmounted when dropped.
struct Tmpfs<'a>(&'a Path);

impl Drop for Tmpfs<'_> {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(self.0).status();
    }
}

/// Mounts a tmpfs of `size` on `dir`, or says why not.
fn mount_tmpfs<'a>(dir: &'a Path, size: &str) -> Result<Tmpfs<'a>, String> {
    std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    let output = Command::new("mount")
        .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
        .arg(dir)
        .output()
        .map_err(|e| format!("cannot run mount: {e}"))?;
    if output.status.success() {
        Ok(Tmpfs(dir))
    } else {
        Err(String::from_utf8_lossy(&output.stderr).trim().to_string())
    }
}

/// Bytes a tmpfs needs for the files under `dir` (each rounded up to its 4 KiB pages).
fn tmpfs_bytes(dir: &Path) -> u64 {
    std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .map(|e| e.expect("entry").path())
                .map(|p| match p.is_dir() {
                    true => tmpfs_bytes(&p) + 4096,
                    false => p.metadata().expect("size").len().div_ceil(4096) * 4096,
                })
                .sum()
        })
        .unwrap_or(0)
}

/// A disk half the size of a run's outputs before its plots fills during the telemetry; one
/// that takes them and half of the plots fills during the plots: the summary is written in
/// both, and what the disk did not take is named. The sizes come from a run on a roomy disk.
#[test]
fn a_full_disk_degrades_in_order() {
    let dir = tempfile::tempdir().expect("temp dir");
    let reference = dir.path().join("reference");
    assert_eq!(run_formation(&reference, None).0, 0);
    let plots = tmpfs_bytes(&reference.join("plots"));
    let before_plots = tmpfs_bytes(&reference) - plots + 64 * 1024;
    let sizes_kib = [before_plots / 2048, (before_plots + plots / 2) / 1024];
    for (kib, plots_written) in sizes_kib.into_iter().zip([false, true]) {
        let disk = dir.path().join(format!("disk-{kib}k"));
        let _mounted = match mount_tmpfs(&disk, &format!("{kib}k")) {
            Ok(mounted) => mounted,
            Err(why) => {
                println!("skipped: no tmpfs can be mounted here ({why})");
                return;
            }
        };
        let out = disk.join("run");
        let (code, stderr) = run_formation(&out, None);
        let unwritten = assert_degraded_in_order(&out, code, &stderr);
        assert!(
            unwritten
                .iter()
                .all(|u| u.contains("no space left on device")),
            "{unwritten:?}"
        );
        let telemetry_first = unwritten[0].starts_with("telemetry.csv: ");
        assert_eq!(telemetry_first, !plots_written, "{kib} KiB: {unwritten:?}");
        let pngs = std::fs::read_dir(out.join("plots")).map_or(0, |d| d.count());
        assert_eq!(pngs > 0, plots_written, "{kib} KiB: {pngs} plots");
    }
}
