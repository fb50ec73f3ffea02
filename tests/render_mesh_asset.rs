//! The committed target mesh `assets/target_aircraft.obj` loads, is what the generator
//! (`examples/make_target_mesh.rs`) writes, and its maximal size is the seed's b = 8 ft
//! (docs/equations.md, What the camera measures):
//! the largest vertex-to-vertex distance is the span between the two tip vertices, 8 ft to
//! 1e-6 ft (the tips are exact in f32; everything else is at least 0.1 ft shorter).

use std::path::Path;

use wingman::render::TargetMesh;
use wingman::render::aircraft_mesh::{HALF_SPAN_FT, target_aircraft_obj};
use wingman::render::mesh::TARGET_AIRCRAFT_OBJ_PATH;

fn asset_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(TARGET_AIRCRAFT_OBJ_PATH)
}

#[test]
fn asset_loads_with_an_8_ft_maximal_dimension() {
    let mesh = TargetMesh::load_obj(&asset_path(), 1.0).expect("asset loads");
    assert!(
        mesh.triangles.len() > 100,
        "{} triangles",
        mesh.triangles.len()
    );
    assert!((mesh.max_dimension_ft() - 8.0).abs() < 1e-6);
    // Tips at y = ±4 ft; the fuselage is shorter than the span.
    let y_max = mesh
        .vertices_ft
        .iter()
        .map(|v| v.y)
        .fold(f64::MIN, f64::max);
    let y_min = mesh
        .vertices_ft
        .iter()
        .map(|v| v.y)
        .fold(f64::MAX, f64::min);
    assert_eq!((y_min, y_max), (-HALF_SPAN_FT, HALF_SPAN_FT));
    let x_max = mesh
        .vertices_ft
        .iter()
        .map(|v| v.x)
        .fold(f64::MIN, f64::max);
    let x_min = mesh
        .vertices_ft
        .iter()
        .map(|v| v.x)
        .fold(f64::MAX, f64::min);
    assert!(x_max - x_min < 7.0, "length {}", x_max - x_min);
}

#[test]
fn asset_is_the_generators_output() {
    let committed = std::fs::read_to_string(asset_path()).expect("asset readable");
    assert!(
        committed == target_aircraft_obj(),
        "assets/target_aircraft.obj is stale: run `cargo run --release --example make_target_mesh`"
    );
}

#[test]
fn built_in_copy_matches_the_file_and_scales() {
    let from_file = TargetMesh::load_obj(&asset_path(), 1.0).expect("asset loads");
    assert_eq!(
        TargetMesh::target_aircraft(1.0).expect("built in"),
        from_file
    );
    let half = TargetMesh::target_aircraft(0.5).expect("built in");
    assert!((half.max_dimension_ft() - 4.0).abs() < 1e-6);
}
