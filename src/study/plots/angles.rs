//! Pixel outcomes as angles: a pixel is a smaller angle in a narrow field of view than in a
//! wide one, so errors in px cannot be compared across fields of view or resolutions. Each
//! case's `*_px` outcome is also given as `*_deg`, atan(px / f) with the focal length f (px)
//! of the case's own camera (its scenario with the study's `set` and the case's settings).

use super::super::layout::StudyLayout;
use super::super::results::CaseRecord;
use super::super::spec::StudyFile;
use crate::scenario::Scenario;
use serde_json::Value;
use std::path::Path;

/// The focal length, px, of each case's camera (None where the scenario does not load).
fn focal_lengths_px(layout: &StudyLayout, records: &[CaseRecord]) -> Vec<Option<f64>> {
    let set = toml::from_str::<StudyFile>(&layout.study_file)
        .map(|f| f.study.set)
        .unwrap_or_default();
    records
        .iter()
        .map(|record| {
            let overrides: Vec<String> = set
                .iter()
                .cloned()
                .chain(
                    record
                        .settings
                        .iter()
                        .filter(|(key, _)| key.starts_with("camera."))
                        .map(|(key, cell)| format!("{key}={cell}")),
                )
                .collect();
            Scenario::from_toml_str(&layout.scenario_file, Path::new(&layout.study), &overrides)
                .ok()
                .map(|s| s.camera.focal_length_px())
        })
        .collect()
}

/// The name of a pixel outcome's angle (`centroid_rms_px` → `centroid_rms_deg`).
pub fn angle_name(pixel_name: &str) -> Option<String> {
    pixel_name
        .strip_suffix("_px")
        .map(|stem| format!("{stem}_deg"))
}

/// The records with each of `pixel_outcomes` also as an angle, deg, where the case's camera
/// is known.
pub fn with_angles(
    layout: &StudyLayout,
    records: &[CaseRecord],
    pixel_outcomes: &[String],
) -> Vec<CaseRecord> {
    let focal = focal_lengths_px(layout, records);
    records
        .iter()
        .zip(focal)
        .map(|(record, focal_px)| {
            let mut record = record.clone();
            for name in pixel_outcomes {
                let (Some(px), Some(f), Some(angle)) =
                    (record.number(name), focal_px, angle_name(name))
                else {
                    continue;
                };
                let deg = (px / f).atan().to_degrees();
                record.columns.push((angle, Value::from(deg)));
            }
            record
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::spec::StudyKind;

    /// At 90° over 640 px the focal length is 320 px: 3.2 px is atan(0.01) = 0.573°; at
    /// 30° (f = 1194 px) the same 3.2 px is 0.154°.
    #[test]
    fn pixels_become_degrees_of_each_cases_camera() {
        let layout = StudyLayout {
            study: "fov".into(),
            kind: StudyKind::Sweep,
            axes: vec![],
            replicated: false,
            outcomes: None,
            cases: vec![],
            study_file: "[study]\nscenario = \"s.toml\"\nset = [\"camera.width_px=640\"]\n".into(),
            scenario_file: "[camera]\nrate_hz = 30\n".into(),
        };
        let record = |hfov: &str| CaseRecord {
            case: 0,
            point: 0,
            replicate: 0,
            settings: vec![("camera.hfov_deg".into(), hfov.into())],
            status: "completed".into(),
            message: None,
            columns: vec![("centroid_rms_px".into(), Value::from(3.2))],
        };
        let out = with_angles(
            &layout,
            &[record("90"), record("30")],
            &["centroid_rms_px".to_string()],
        );
        let deg = |k: usize| out[k].number("centroid_rms_deg").unwrap();
        assert!(
            (deg(0) - 0.01f64.atan().to_degrees()).abs() < 1e-9,
            "{}",
            deg(0)
        );
        let f30 = 320.0 / 15f64.to_radians().tan();
        assert!((deg(1) - (3.2 / f30).atan().to_degrees()).abs() < 1e-9);
    }
}
