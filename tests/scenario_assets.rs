//! A scenario's assets are part of its input: the camera's mesh is found from the
//! scenario file's folder (the default one falls back to the shipped mesh, so a shipped
//! scenario copied anywhere runs); a missing, empty, corrupt, flat, endless or oversized mesh
//! is a scenario error (exit 2, naming the file, the key and what is wrong) before anything
//! is written; and loading a mesh grows nearly linearly with its vertex count.

use crate::common;

use std::path::Path;
use std::time::{Duration, Instant};

const CAMERA: &str = "[sensor]\nmode = \"camera\"\n[run]\nduration_s = 0.2\n[output]\nplots = false\n[camera]\nrate_hz = 25.0\n";

/// Runs a camera scenario whose mesh is `mesh` (written beside it when `contents` is given).
fn run_with_mesh(mesh: &str, contents: Option<&str>) -> (i32, String, bool) {
    let dir = tempfile::tempdir().expect("temp dir");
    if let Some(text) = contents {
        std::fs::write(dir.path().join(mesh), text).expect("mesh");
    }
    let scenario = dir.path().join("bad.toml");
    std::fs::write(&scenario, format!("{CAMERA}mesh = \"{mesh}\"\n")).expect("scenario");
    let out = dir.path().join("out");
    let (code, stderr) = common::wingman_cli_in(
        dir.path(),
        &[
            "run",
            "bad.toml",
            "--quiet",
            "--out",
            out.to_str().expect("utf-8"),
        ],
    );
    (code, stderr, out.exists())
}

#[test]
fn bad_meshes_are_scenario_errors_before_anything_is_written() {
    let cases = [
        ("missing.obj", None, "No such file"),
        ("empty.obj", Some(""), "no triangles"),
        ("corrupt.obj", Some("v 0 0 zero\nf 1 2 3\n"), "cannot parse"),
        (
            "flat.obj",
            Some("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"),
            "no area",
        ),
        ("/dev/zero", None, "not a regular file"),
    ];
    for (mesh, contents, what) in cases {
        let started = Instant::now();
        let (code, stderr, written) = run_with_mesh(mesh, contents);
        assert_eq!(code, 2, "{mesh}: {stderr}");
        assert!(
            stderr.contains("bad.toml:") && stderr.contains("camera.mesh"),
            "{stderr}"
        );
        assert!(stderr.contains(what), "{mesh}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
        assert!(!written, "{mesh}: outputs written");
        assert!(
            started.elapsed() < Duration::from_secs(20),
            "{mesh} took long"
        );
    }
}

/// A shipped scenario copied to another folder and run from a third runs: its default mesh
/// is the shipped one. A mesh written beside a scenario is found from its folder.
#[test]
fn scenarios_run_from_any_folder() {
    let dir = tempfile::tempdir().expect("temp dir");
    let elsewhere = dir.path().join("elsewhere");
    std::fs::create_dir_all(&elsewhere).expect("folder");
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let copy = elsewhere.join("formation.toml");
    std::fs::copy(repo.join("scenarios/formation.toml"), &copy).expect("copy");
    let (code, stderr) = common::wingman_cli_in(
        dir.path(),
        &[
            "run",
            copy.to_str().expect("utf-8"),
            "--quiet",
            "--out",
            "a",
            "--set",
            "run.duration_s=0.2",
            "--set",
            "output.plots=false",
        ],
    );
    assert_eq!(code, 0, "{stderr}");

    let mesh = std::fs::read_to_string(repo.join("assets/target_aircraft.obj")).expect("mesh");
    std::fs::write(elsewhere.join("mine.obj"), mesh).expect("mesh copy");
    let scenario = elsewhere.join("mine.toml");
    // The main scenario with its mesh named relative to its own folder (a camera scenario
    // of defaults alone would fly the seed's adaptive gains, which pixels make unstable).
    let formation = std::fs::read_to_string(&copy).expect("copied scenario");
    let own_mesh = formation.replace(
        "mesh = \"assets/target_aircraft.obj\"",
        "mesh = \"mine.obj\"",
    );
    assert_ne!(own_mesh, formation, "formation.toml names its mesh");
    std::fs::write(&scenario, own_mesh).expect("scenario");
    let (code, stderr) = common::wingman_cli_in(
        dir.path(),
        &[
            "run",
            scenario.to_str().expect("utf-8"),
            "--quiet",
            "--out",
            "b",
            "--set",
            "run.duration_s=0.2",
            "--set",
            "output.plots=false",
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    let resolved = std::fs::read_to_string(dir.path().join("b/scenario.toml")).expect("resolved");
    assert!(resolved.contains("elsewhere/mine.obj"), "{resolved}");
}

/// A UV sphere of `rings` x `segments` vertices, as OBJ text.
fn sphere_obj(rings: usize, segments: usize) -> String {
    let mut text = String::new();
    for i in 0..rings {
        let polar = std::f64::consts::PI * (i as f64 + 0.5) / rings as f64;
        for j in 0..segments {
            let azimuth = std::f64::consts::TAU * j as f64 / segments as f64;
            let (x, y, z) = (
                polar.sin() * azimuth.cos(),
                polar.sin() * azimuth.sin(),
                polar.cos(),
            );
            text.push_str(&format!("v {x} {y} {z}\n"));
        }
    }
    for i in 0..rings - 1 {
        for j in 0..segments {
            let a = i * segments + j + 1;
            let b = i * segments + (j + 1) % segments + 1;
            text.push_str(&format!("f {a} {b} {}\n", b + segments));
            text.push_str(&format!("f {a} {} {}\n", b + segments, a + segments));
        }
    }
    text
}

/// 120 000 vertices load and scale in a few seconds (all vertex pairs took 37 s).
#[test]
fn mesh_loading_grows_nearly_linearly() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("sphere.obj");
    std::fs::write(&path, sphere_obj(300, 400)).expect("mesh");
    let scenario = wingman::scenario::Scenario::from_toml_str(
        &format!("{CAMERA}mesh = \"{}\"\n", path.display()),
        Path::new("s.toml"),
        &[],
    )
    .expect("valid scenario");
    let started = Instant::now();
    let mesh =
        wingman::sensing::camera::load_target_mesh(&wingman::sensing::CameraConfig::of(&scenario))
            .expect("mesh loads");
    let elapsed = started.elapsed();
    assert_eq!(mesh.vertices_ft.len(), 120_000);
    // Scaled to the target's 8 ft: the sphere's diameter.
    assert!((mesh.max_dimension_ft() - 8.0).abs() < 1e-9);
    assert!(elapsed < Duration::from_secs(8), "{elapsed:?}");
}
