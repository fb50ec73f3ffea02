//! Writes the key tables of `docs/scenario_reference.md` from the scenario schema (the structs,
//! their doc comments and defaults in `src/scenario/`, and the validator's ranges);
//! `tests/scenario_reference.rs` fails until the file is regenerated after they change.
//!
//! ```text
//! cargo run --release --example gen_scenario_reference
//! ```

use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = repo.join("docs/scenario_reference.md");
    let doc = std::fs::read_to_string(&path)?;
    let updated = wingman::scenario::reference::with_tables(&doc, repo)?;
    if updated != doc {
        std::fs::write(&path, updated)?;
        println!("updated {}", path.display());
    }
    Ok(())
}
