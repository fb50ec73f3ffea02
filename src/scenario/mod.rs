//! Scenario files (TOML): schema with defaults, `--set section.key=value` overrides, and
//! validation whose errors name the file, the key, the value and the allowed range.

mod acceleration;
mod atmosphere;
mod camera;
pub mod check;
mod control;
mod estimator;
mod gimbal;
mod sections;
mod sensor;

pub use acceleration::*;
pub use atmosphere::*;
pub use camera::*;
pub use control::*;
pub use estimator::*;
pub use gimbal::*;
pub use sections::*;
pub use sensor::*;

use std::path::{Path, PathBuf};

/// Why a scenario could not be used. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("{}: cannot read scenario file: {source}", path.display())]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// TOML syntax error or a key/value the schema does not accept.
    #[error("{}: {}", path.display(), check::one_line(source))]
    Schema {
        /// The file.
        path: PathBuf,
        /// The parser's error (key and line included).
        source: toml::de::Error,
    },
    /// A `--set` override that is not `section.key=value`, or names an unknown key.
    #[error("{}: bad override `{text}`: {reason}", path.display())]
    Override {
        /// The file being overridden.
        path: PathBuf,
        /// The override as given.
        text: String,
        /// What is wrong with it.
        reason: OverrideError,
    },
    /// A value out of its allowed range.
    #[error("{path}: {invalid}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// The key, value and allowed range.
        invalid: check::InvalidValue,
    },
}

impl Scenario {
    /// Reads, overrides, parses and validates a scenario file.
    pub fn load(path: &Path, overrides: &[String]) -> Result<Scenario, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Unreadable {
            path: path.to_path_buf(),
            source,
        })?;
        let mut scenario = Self::from_toml_str(&text, path, overrides)?;
        scenario.resolve_mesh_path(path);
        Ok(scenario)
    }

    /// A relative mesh path not found from the working directory is looked up from the
    /// scenario file's directory and its parent; the path found is written back so that the
    /// resolved scenario runs from anywhere.
    fn resolve_mesh_path(&mut self, scenario_path: &Path) {
        let mesh = PathBuf::from(&self.camera.mesh);
        if mesh.is_absolute() || mesh.exists() {
            return;
        }
        let dir = scenario_path.parent().unwrap_or(Path::new("."));
        let candidates = [dir.join(&mesh), dir.join("..").join(&mesh)];
        if let Some(found) = candidates.iter().find(|p| p.exists()) {
            let found = found.canonicalize().unwrap_or_else(|_| found.clone());
            self.camera.mesh = found.to_string_lossy().into_owned();
        }
    }

    /// Parses scenario text as if read from `path` (used in messages only).
    pub fn from_toml_str(
        text: &str,
        path: &Path,
        overrides: &[String],
    ) -> Result<Scenario, ScenarioError> {
        let schema_error = |source| ScenarioError::Schema {
            path: path.to_path_buf(),
            source,
        };
        let mut table: toml::Table = text.parse().map_err(schema_error)?;
        for text in overrides {
            apply_override(&mut table, text).map_err(|reason| ScenarioError::Override {
                path: path.to_path_buf(),
                text: text.clone(),
                reason,
            })?;
        }
        let scenario: Scenario = toml::Value::Table(table).try_into().map_err(schema_error)?;
        scenario
            .validate()
            .map_err(|invalid| ScenarioError::Invalid {
                path: path.to_path_buf(),
                invalid,
            })?;
        Ok(scenario)
    }

    /// The resolved scenario as TOML, every default filled in.
    pub fn to_toml_string(&self) -> String {
        toml::to_string(self).unwrap_or_else(|e| format!("# cannot serialise scenario: {e}\n"))
    }
}

/// Why a `--set` override could not be applied.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum OverrideError {
    /// Not of the form `section.key=value`.
    #[error("expected section.key=value")]
    Form,
    /// The section named is a value in the file, not a section.
    #[error("`{0}` is not a section")]
    NotASection(String),
}

/// Applies `section.key=value` (or `section.sub.key=value` for a section inside a section);
/// the value is read as a TOML value (number, boolean, array, quoted
/// string) and, failing that, as a bare string.
fn apply_override(table: &mut toml::Table, text: &str) -> Result<(), OverrideError> {
    let (key, value_text) = text.split_once('=').ok_or(OverrideError::Form)?;
    let path: Vec<&str> = key.trim().split('.').collect();
    let Some((field, sections)) = path.split_last() else {
        return Err(OverrideError::Form);
    };
    if sections.is_empty() || path.iter().any(|p| p.is_empty()) {
        return Err(OverrideError::Form);
    }
    let value_text = value_text.trim();
    let value = format!("v = {value_text}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(value_text.to_string()));
    let mut current = table;
    for section in sections {
        current = current
            .entry(section.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .ok_or_else(|| OverrideError::NotASection(section.to_string()))?;
    }
    current.insert(field.to_string(), value);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str, overrides: &[&str]) -> Result<Scenario, ScenarioError> {
        let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        Scenario::from_toml_str(text, Path::new("test.toml"), &overrides)
    }

    #[test]
    fn empty_file_is_the_seed_defaults() {
        let s = parse("", &[]).expect("defaults are valid");
        assert_eq!(s, Scenario::default());
        assert_eq!(s.guidance.k, 3.5);
        assert_eq!(s.target.initial_position_ft, [200.0, 50.0, 30.0]);
    }

    #[test]
    fn resolved_scenario_round_trips() {
        let s = parse("[guidance]\nk = 2.0\n", &["run.dt_s=0.002"]).expect("valid");
        let again = parse(&s.to_toml_string(), &[]).expect("resolved is valid");
        assert_eq!(s, again);
        assert_eq!(again.run.dt_s, 0.002);
    }

    #[test]
    fn unknown_key_is_named() {
        let err = parse("[guidance]\nkk = 2.0\n", &[])
            .unwrap_err()
            .to_string();
        assert!(err.contains("test.toml") && err.contains("kk"), "{err}");
    }

    #[test]
    fn out_of_range_names_key_value_and_range() {
        let err = parse("[guidance]\nb0_ft = 40.0\n", &[])
            .unwrap_err()
            .to_string();
        assert!(err.contains("guidance.b0_ft = 40"), "{err}");
        assert!(err.contains("b_max_ft = 30"), "{err}");
    }

    /// A key of a section inside a section can be set too.
    #[test]
    fn nested_keys_can_be_set() {
        let s = parse(
            "",
            &[
                "camera.gimbal.kind=pan_tilt",
                "atmosphere.disturbances.drag_factor=1.5",
            ],
        )
        .expect("valid");
        assert_eq!(s.camera.gimbal.kind, GimbalKind::PanTilt);
        assert_eq!(s.atmosphere.disturbances.drag_factor, 1.5);
    }

    #[test]
    fn override_must_have_section_and_key() {
        assert!(matches!(
            parse("", &["dt_s=1"]),
            Err(ScenarioError::Override { .. })
        ));
        assert!(matches!(
            parse("", &["run.nope=1"]),
            Err(ScenarioError::Schema { .. })
        ));
        let s = parse("", &["guidance.mission=intercept"]).expect("bare strings work");
        assert_eq!(s.guidance.mission, Mission::Intercept);
    }
}
