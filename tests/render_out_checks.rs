//! `render --out` is checked before the scenario is flown: a name that is not a
//! PNG file, or an existing folder, is refused at once with exit code 2 and no file is left.

use std::process::Command;
use std::time::{Duration, Instant};

#[test]
fn render_out_must_name_a_png_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let jpg = dir.path().join("x.jpg");
    for (out, what) in [
        (jpg.as_path(), "name a .png file"),
        (dir.path(), "is a folder"),
    ] {
        let started = Instant::now();
        let output = Command::new(env!("CARGO_BIN_EXE_wingman"))
            .args(["render", "scenarios/formation.toml", "--at", "130", "--out"])
            .arg(out)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .env("NODEVICE_SELECT", "1")
            .output()
            .expect("binary runs");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(what), "{stderr}");
        // Flying 130 s of the scenario takes several seconds; refusing takes none.
        assert!(
            started.elapsed() < Duration::from_secs(3),
            "flew before refusing"
        );
    }
    assert!(!jpg.exists(), "a file was left");
}
