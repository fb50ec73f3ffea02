//! `navigation.mode = "perfect"` is today's behaviour: `formation.toml` run for 10 s gives the
//! same telemetry, column by column, with no `[navigation]` keys, with every mode written out
//! as `perfect`, and with `perfect` modes whose error keys hold other values (they are then
//! unused). An INS/GPS run of the same scenario logs its navigation beside the truth and
//! differs (so the comparison can fail).

use crate::common;

use std::path::Path;

/// The header and the columns of a run's telemetry.
fn telemetry(overrides: &[&str]) -> (Vec<String>, Vec<Vec<String>>) {
    let mut all = vec!["run.duration_s=10", "output.frames_every=0"];
    all.extend_from_slice(overrides);
    let dir = tempfile::tempdir().expect("temp dir");
    common::run_in(&common::load("formation", &all), "formation", dir.path());
    read_columns(&dir.path().join("telemetry.csv"))
}

fn read_columns(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).expect("telemetry.csv");
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .expect("a header")
        .split(',')
        .map(String::from)
        .collect();
    let mut columns = vec![Vec::new(); header.len()];
    for line in lines {
        for (column, cell) in columns.iter_mut().zip(line.split(',')) {
            column.push(cell.to_string());
        }
    }
    (header, columns)
}

fn assert_same(
    (header_a, columns_a): &(Vec<String>, Vec<Vec<String>>),
    (header_b, columns_b): &(Vec<String>, Vec<Vec<String>>),
    what: &str,
) {
    assert_eq!(header_a, header_b, "{what}: the columns differ");
    for (name, (a, b)) in header_a.iter().zip(columns_a.iter().zip(columns_b)) {
        assert!(a.len() > 900, "{what}: {name} has {} rows", a.len());
        if let Some(row) = a.iter().zip(b).position(|(x, y)| x != y) {
            panic!(
                "{what}: column {name} differs at row {row}: {} vs {}",
                a[row], b[row]
            );
        }
    }
}

#[test]
fn perfect_navigation_reproduces_the_telemetry() {
    let plain = telemetry(&[]);
    let explicit = telemetry(&[
        "navigation.mode=perfect",
        "navigation.air_data.mode=perfect",
        "navigation.camera.mode=perfect",
    ]);
    assert_same(&plain, &explicit, "explicit perfect");
    let unused_keys = telemetry(&[
        "navigation.mode=perfect",
        "navigation.gyro_bias_deg_per_h=100",
        "navigation.camera.mount_misalignment_deg=[2.0, 2.0, 2.0]",
        "navigation.air_data.airspeed_bias_fps=5",
    ]);
    assert_same(&plain, &unused_keys, "perfect with other error keys");
    let ins_gps = telemetry(&["navigation.mode=ins_gps"]);
    assert!(ins_gps.0.iter().any(|c| c == "nav_n_ft"));
    assert!(!plain.0.iter().any(|c| c.starts_with("nav_")));
    let r_meas_x = |t: &(Vec<String>, Vec<Vec<String>>)| {
        let i = t.0.iter().position(|c| c == "r_meas_x").expect("r_meas_x");
        t.1[i].clone()
    };
    assert_ne!(
        r_meas_x(&plain),
        r_meas_x(&ins_gps),
        "the INS/GPS's errors reach the guidance"
    );
}
