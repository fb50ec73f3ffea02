//! The apparent-size study on a box whose sizes have closed forms. A box 4 ft long (x),
//! 8 ft wide (y) and 0.5 ft thick (z) sits on the optical axis of a 640x480 camera with a 60°
//! horizontal field of view (focal length l = 320 / tan 30° px) at range R (to its centre):
//! - face-on (pitch 90°: the camera looks down its z axis) its silhouette is the near face,
//!   4 x 8 ft at R - 0.25 ft: maximal length l √(4² + 8²) / (R - 0.25), measured and projected;
//!   the four-point model (8.1)-(8.2) (face centres at R) spans the 8 ft width: l 8 / R;
//! - edge-on (yaw 90°: the camera looks down its y axis) its silhouette is 4 x 0.5 ft at
//!   R - 4 ft: l √(4² + 0.5²) / (R - 4); the model's wing tips lie on the line of sight, so it
//!   spans the 4 ft length: l 4 / R.
//!
//! Tolerances: the projected mesh and the model are exact geometry (1e-9 relative); the
//! measured maximal length comes from 4x multisampled pixels, whose edges the image
//! pipeline locates to a fraction of a pixel: within 1.5 px. The implied size is
//! R bI / √(l² + yI² + zI²) with the measured centroid on the axis within a pixel.

use crate::common;

use std::path::Path;
use wingman::study::results::{CaseRecord, read_record};
use wingman::study::run::SWEEP_THREAD_PREFIX;
use wingman::study::{Plan, run_sweep};

const LENGTH_FT: f64 = 4.0;
const WIDTH_FT: f64 = 8.0;
const THICKNESS_FT: f64 = 0.5;

/// The box as OBJ: 8 corners, 12 triangles, centred on the origin.
fn box_obj() -> String {
    let (x, y, z) = (LENGTH_FT / 2.0, WIDTH_FT / 2.0, THICKNESS_FT / 2.0);
    let mut text = String::new();
    for k in 0..8 {
        let sign = |bit: usize| if k & bit == 0 { -1.0 } else { 1.0 };
        text += &format!("v {} {} {}\n", sign(1) * x, sign(2) * y, sign(4) * z);
    }
    // Faces as quads of corner indices (1-based), each split in two triangles.
    let quads = [
        [1, 2, 4, 3],
        [5, 7, 8, 6],
        [1, 5, 6, 2],
        [3, 4, 8, 7],
        [1, 3, 7, 5],
        [2, 6, 8, 4],
    ];
    for [a, b, c, d] in quads {
        text += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
    }
    text
}

fn setup(dir: &Path) -> std::path::PathBuf {
    std::fs::write(dir.join("box.obj"), box_obj()).unwrap();
    let diagonal_ft = (LENGTH_FT.powi(2) + WIDTH_FT.powi(2) + THICKNESS_FT.powi(2)).sqrt();
    let scenario = format!(
        "[target]\nsize_ft = {diagonal_ft:?}\n\n[camera]\nwidth_px = 640\nheight_px = 480\n\
         hfov_deg = 60.0\nmsaa_samples = 4\nmesh = \"{}\"\n",
        dir.join("box.obj").display()
    );
    std::fs::write(dir.join("box_scenario.toml"), scenario).unwrap();
    let study = "[study]\nscenario = \"box_scenario.toml\"\nkind = \"apparent_size\"\n\
                 combine = \"zip\"\n\n\
                 [[axis]]\nkey = \"view.yaw_deg\"\nvalues = [0, 0, 90, 90]\n\n\
                 [[axis]]\nkey = \"view.pitch_deg\"\nvalues = [90, 90, 0, 0]\n\n\
                 [[axis]]\nkey = \"view.range_ft\"\nvalues = [20.0, 60.0, 20.0, 60.0]\n";
    let path = dir.join("box_study.toml");
    std::fs::write(&path, study).unwrap();
    path
}

fn focal_px() -> f64 {
    320.0 / 30f64.to_radians().tan()
}

fn number(record: &CaseRecord, name: &str) -> f64 {
    record
        .number(name)
        .unwrap_or_else(|| panic!("case {}: no {name}: {record:?}", record.case))
}

#[test]
fn box_face_on_and_edge_on_match_closed_forms() {
    let dir = tempfile::tempdir().unwrap();
    let study = setup(dir.path());
    let plan = Plan::load(&study).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.path().join("out");
    let mut options = common::quiet_sweep_into(&out);
    options.jobs = 2;
    let report = run_sweep(&plan, &options).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        live_sweep_threads(),
        Vec::<String>::new(),
        "the sweep returned before its workers, which used GPU devices, had exited"
    );
    assert_eq!(
        (report.cases, report.tally.counts.as_str()),
        (4, "4 completed"),
        "{report:?}"
    );
    let l = focal_px();
    for case in 0..4 {
        let record = read_record(&out.join("cases").join(format!("{case:06}"))).unwrap();
        let range_ft = [20.0, 60.0][case % 2];
        let face_on = case < 2;
        let (silhouette_ft, near_ft, model_ft) = if face_on {
            (
                LENGTH_FT.hypot(WIDTH_FT),
                range_ft - THICKNESS_FT / 2.0,
                WIDTH_FT,
            )
        } else {
            (
                LENGTH_FT.hypot(THICKNESS_FT),
                range_ft - WIDTH_FT / 2.0,
                LENGTH_FT,
            )
        };
        let silhouette_px = l * silhouette_ft / near_ft;
        let model_px = l * model_ft / range_ft;
        let what = format!("case {case} (face-on {face_on}, R = {range_ft} ft)");
        let mesh_px = number(&record, "b_i_mesh_px");
        assert!(
            (mesh_px / silhouette_px - 1.0).abs() < 1e-9,
            "{what}: mesh {mesh_px} vs {silhouette_px}"
        );
        let four_px = number(&record, "b_i_four_point_px");
        assert!(
            (four_px / model_px - 1.0).abs() < 1e-9,
            "{what}: model {four_px} vs {model_px}"
        );
        let measured_px = number(&record, "b_i_measured_px");
        assert!(
            (measured_px - silhouette_px).abs() < 1.5,
            "{what}: measured {measured_px} vs {silhouette_px}"
        );
        // The sizes implied at the true range: the model's is its flat extent exactly, the
        // measured one the silhouette's scaled by R / (R - near offset), within 1.5 px of it.
        let size_ft = number(&record, "size_four_point_ft");
        assert!(
            (size_ft - model_ft).abs() < 1e-9,
            "{what}: model size {size_ft}"
        );
        let implied_ft = number(&record, "size_measured_ft");
        let expected_ft = range_ft * silhouette_px / l;
        assert!(
            (implied_ft - expected_ft).abs() < 1.5 * range_ft / l,
            "{what}: implied {implied_ft} vs {expected_ft}"
        );
        let ratio = number(&record, "ratio_measured_true");
        assert!((ratio - implied_ft / number(&record, "size_true_ft")).abs() < 1e-12);
    }
}

/// The names of this process's threads that are a sweep's workers (Linux's /proc): a worker
/// still exiting when the process exits runs the graphics driver's thread-exit hooks after
/// the driver may have been unloaded.
fn live_sweep_threads() -> Vec<String> {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return Vec::new();
    };
    tasks
        .filter_map(|task| std::fs::read_to_string(task.ok()?.path().join("comm")).ok())
        .map(|name| name.trim().to_string())
        .filter(|name| name.starts_with(SWEEP_THREAD_PREFIX))
        .collect()
}
