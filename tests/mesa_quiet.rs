//! A user never sees Mesa's "XDG_RUNTIME_DIR is invalid or not set": a camera run
//! with the variable unset (and without the NODEVICE_SELECT work-around) prints nothing.

use std::process::Command;

#[test]
fn no_runtime_dir_complaint() {
    let dir = tempfile::tempdir().expect("temp dir");
    let output = Command::new(env!("CARGO_BIN_EXE_wingman"))
        .args(["run", "scenarios/formation.toml", "--quiet", "--out"])
        .arg(dir.path().join("run"))
        .args(["--set", "run.duration_s=0.2", "--set", "output.plots=false"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("NODEVICE_SELECT")
        .output()
        .expect("binary runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert!(!stderr.contains("XDG_RUNTIME_DIR"), "{stderr}");
    assert!(stderr.trim().is_empty(), "--quiet printed: {stderr}");
}
