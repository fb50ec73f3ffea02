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
