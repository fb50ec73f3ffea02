//! Writes the seed's 8 ft target aircraft to `assets/target_aircraft.obj` (or the path given).
//!
//! `cargo run --release --example make_target_mesh [OUT.obj]`

use std::path::PathBuf;

use wingman::render::aircraft_mesh::{target_aircraft_mesh, target_aircraft_obj};
use wingman::render::mesh::TARGET_AIRCRAFT_OBJ_PATH;

fn main() -> anyhow::Result<()> {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(TARGET_AIRCRAFT_OBJ_PATH));
    std::fs::write(&out, target_aircraft_obj())?;
    let mesh = target_aircraft_mesh();
    println!(
        "{}: {} vertices, {} triangles, max dimension {} ft",
        out.display(),
        mesh.vertices_ft.len(),
        mesh.triangles.len(),
        mesh.max_dimension_ft()
    );
    Ok(())
}
