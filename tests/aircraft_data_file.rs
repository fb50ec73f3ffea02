//! Aircraft data files are checked: every error names the file and the offending key (unknown,
//! missing, wrongly typed or out of range, the last with its value and the allowed range); the
//! shipped file loads from disk with the seed's numbers.

use std::path::Path;

use wingman::world::aircraft::{AircraftFileError, AircraftParams};

const SHIPPED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/aircraft/follower.toml");

fn shipped_text() -> String {
    std::fs::read_to_string(SHIPPED).expect("the shipped aircraft file is readable")
}

fn error_for(text: &str) -> String {
    AircraftParams::from_toml_str(text, Path::new("planes/bad.toml"))
        .expect_err("the edited file must be refused")
        .to_string()
}

#[test]
fn shipped_file_loads_from_disk() {
    let params = AircraftParams::load(Path::new(SHIPPED)).expect("valid");
    assert_eq!(params.mass.mass_slug, 0.6293);
    assert_eq!(params.mass.jzz_slug_ft2, 0.2553);
    assert_eq!(params.geometry.wing_area_ft2, 11.5);
    assert_eq!(params.geometry.chord_ft, 1.2547);
    assert_eq!(params, AircraftParams::seed_follower().expect("valid"));
}

#[test]
fn unknown_key_is_named_with_the_file() {
    let text = shipped_text().replace("span_ft = 9.1", "span_ft = 9.1\nwingspan_ft = 9.1");
    let err = error_for(&text);
    assert!(
        err.contains("planes/bad.toml") && err.contains("wingspan_ft"),
        "{err}"
    );
}

#[test]
fn missing_key_is_named_with_the_file() {
    let text = shipped_text().replace("c_roll_p = -0.26", "");
    let err = error_for(&text);
    assert!(
        err.contains("planes/bad.toml") && err.contains("c_roll_p"),
        "{err}"
    );
}

#[test]
fn wrong_type_is_named_with_the_file() {
    let text = shipped_text().replace("mass_slug = 0.6293", "mass_slug = \"heavy\"");
    let err = error_for(&text);
    assert!(
        err.contains("planes/bad.toml") && err.contains("mass_slug"),
        "{err}"
    );
}

#[test]
fn out_of_range_names_key_value_and_range() {
    let text = shipped_text().replace("mass_slug = 0.6293", "mass_slug = -1.0");
    let err = error_for(&text);
    assert!(err.contains("planes/bad.toml"), "{err}");
    assert!(err.contains("mass.mass_slug = -1"), "{err}");
    assert!(err.contains("> 0"), "{err}");

    let text = shipped_text().replace("limit_deg = 20.0", "limit_deg = 120.0");
    let err = error_for(&text);
    assert!(
        err.contains("actuators.rudder.limit_deg = 120") && err.contains("[0.1, 90]"),
        "{err}"
    );
}

#[test]
fn unreadable_file_is_named() {
    match AircraftParams::load(Path::new("/nonexistent/plane.toml")) {
        Err(e @ AircraftFileError::Unreadable { .. }) => {
            assert!(e.to_string().contains("/nonexistent/plane.toml"))
        }
        other => panic!("expected Unreadable, got {other:?}"),
    }
}

/// `follower.aircraft` selects the 6-DOF follower's data file: a copy of the shipped file
/// beside the scenario flies exactly as the default; a heavier copy flies differently; a file
/// that is not there is refused with exit code 2, naming the file.
mod selected_from_the_scenario {
    use std::path::Path;
    use wingman::scenario::Scenario;
    use wingman::sim::Simulation;

    const SCENARIO: &str = "[follower]\nmodel = \"aircraft\"\naircraft = \"plane.toml\"\n\
                            [run]\nduration_s = 2.0\n";

    /// The follower's position after 2 s, flying the scenario `text` from `dir`.
    fn position_after_run(dir: &Path, text: &str) -> [f64; 3] {
        let path = dir.join("s.toml");
        std::fs::write(&path, text).expect("write scenario");
        let scenario = Scenario::load(&path, &[]).expect("valid scenario");
        let mut sim = Simulation::new(&scenario).expect("set-up");
        while sim.step().expect("runs") == wingman::sim::StepOutcome::Running {}
        sim.snapshot().follower_position_ned_ft.into()
    }

    #[test]
    fn a_data_file_beside_the_scenario_is_flown() {
        let dir = tempfile::tempdir().expect("temp dir");
        let shipped = super::shipped_text();
        std::fs::write(dir.path().join("plane.toml"), &shipped).expect("write aircraft");
        let with_copy = position_after_run(dir.path(), SCENARIO);
        let default = position_after_run(
            dir.path(),
            &SCENARIO.replace("plane.toml", "assets/aircraft/follower.toml"),
        );
        assert_eq!(
            with_copy, default,
            "the shipped file's copy flies as the default"
        );
        let heavier = shipped.replace("mass_slug = 0.6293", "mass_slug = 0.7");
        assert_ne!(heavier, shipped, "the mass line is in the shipped file");
        std::fs::write(dir.path().join("plane.toml"), heavier).expect("write aircraft");
        let with_heavier = position_after_run(dir.path(), SCENARIO);
        assert_ne!(
            with_heavier, default,
            "a heavier aircraft flies differently"
        );
    }

    #[test]
    fn a_missing_data_file_is_refused_with_its_name() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("s.toml");
        std::fs::write(&path, SCENARIO).expect("write scenario");
        let out = dir.path().join("out");
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_wingman"))
            .args(["run", path.to_str().expect("utf-8"), "--quiet", "--out"])
            .arg(&out)
            .env("NODEVICE_SELECT", "1")
            .output()
            .expect("binary runs");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains("plane.toml"), "{stderr}");
    }
}
