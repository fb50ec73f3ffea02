//! Writes the telemetry and summary tables of `docs/outputs.md` from the tables in code
//! (`src/output/columns.rs`, `src/output/summary.rs`); `tests/outputs_doc.rs` fails until the
//! file is regenerated after they change.
//!
//! ```text
//! cargo run --example gen_outputs_doc
//! ```

use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/outputs.md");
    let doc = std::fs::read_to_string(&path)?;
    let updated = wingman::output::outputs_doc::with_tables(&doc)?;
    if updated != doc {
        std::fs::write(&path, updated)?;
        println!("updated {}", path.display());
    }
    Ok(())
}
