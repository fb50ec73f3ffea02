//! One key a study case sets to one value, as a `--set` override and as a `results.csv` cell.

/// One key set to one value by a case.
#[derive(Debug, Clone, PartialEq)]
pub struct Setting {
    /// `section.key`.
    pub key: String,
    /// The value.
    pub value: toml::Value,
}

impl Setting {
    /// The `--set` text: `section.key=value`, the value as TOML.
    pub fn override_text(&self) -> String {
        format!("{}={}", self.key, self.value)
    }

    /// The value as a `results.csv` cell: strings bare, everything else as TOML.
    pub fn cell(&self) -> String {
        value_cell(&self.value)
    }
}

/// A value as a `results.csv` cell: strings bare, everything else as TOML.
pub fn value_cell(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// The key replicates set.
pub const SEED_KEY: &str = "run.seed";
