//! Scenario files (TOML): schema with defaults, `--set section.key=value` overrides, and
//! validation whose errors name the file, the key, the value and the allowed range.

mod acceleration;
mod atmosphere;
mod camera;
pub mod check;
mod control;
mod estimator;
mod excitation;
mod gimbal;
pub mod group;
mod navigation;
pub mod origin;
mod probe;
pub mod reference;
mod scene;
mod sections;
mod sensor;
mod target;

pub use acceleration::*;
pub use atmosphere::*;
pub use camera::*;
pub use control::*;
pub use estimator::*;
pub use excitation::*;
pub use gimbal::*;
pub use navigation::*;
pub use origin::{Origin, ScenarioSource};
pub use scene::*;
pub use sections::*;
pub use sensor::*;
pub use target::*;

use std::path::{Path, PathBuf};

/// Why a scenario could not be used. Every variant says where the offending value came
/// from: the file (with the line and column of the key), or the `--set` argument.
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
    /// The file holds no setting at all.
    #[error(
        "{}: the scenario file is empty: write at least one section (see scenarios/)",
        path.display()
    )]
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// A `--set` override that is not `section.key=value`.
    #[error("--set {text}: {reason}")]
    Override {
        /// The override as given.
        text: String,
        /// What is wrong with it.
        reason: OverrideError,
    },
    /// A TOML syntax error, a key or value the schema does not accept, a value out of its
    /// allowed range, or an asset or resource the scenario asks for that cannot be had.
    #[error("{origin}: {message}")]
    Rejected {
        /// Where the value came from.
        origin: Origin,
        /// The key, when one is to blame.
        key: Option<String>,
        /// The value, what is wrong with it and what is allowed.
        message: String,
    },
}

impl ScenarioSource {
    /// A rejection of the value of `key`, with its origin.
    pub fn reject(&self, key: &str, message: impl Into<String>) -> ScenarioError {
        ScenarioError::Rejected {
            origin: self.origin(key),
            key: Some(key.to_string()),
            message: origin::shorten(&message.into()),
        }
    }

    /// The schema's error (syntax, type, unknown key) with its origin: the `--set` that
    /// wrote the key, else the key's place in the file, else the place the parser names. A
    /// value of the wrong kind is quoted with what its key allows (probed in `table`, the
    /// scenario read so far, when there is one).
    fn schema_error(&self, error: &toml::de::Error, table: Option<&toml::Table>) -> ScenarioError {
        // An error of the text has a span (and a message without the excerpt around it); an
        // error of the overridden table names its key at the end of its message.
        let (key, mut message) = match error.span() {
            Some(_) => origin::schema_message(error.message()),
            None => origin::schema_message(&error.to_string()),
        };
        let origin = match (&key, error.span()) {
            (Some(key), _) => self.origin(key),
            (None, Some(span)) => self.at_offset(span.start),
            (None, None) => self.file(),
        };
        // A whole number is quoted with its key's range, not its type's; a string choice
        // with its strings.
        let vague = message.contains("allowed a whole number") || message.contains("string only");
        if let (Some(key), Some(table), true) = (&key, table, vague)
            && let (Some(value), Some(allowed)) =
                (probe::value_text(table, key), probe::allowed(table, key))
        {
            message = origin::shorten(&format!("{key} = {value} is invalid: allowed {allowed}"));
        }
        ScenarioError::Rejected {
            origin,
            key,
            message,
        }
    }

    /// The parser's error of the text: a key given twice, or a number too large to be
    /// written in TOML, is named with its key (and the number with what the key allows).
    fn text_error(&self, error: &toml::de::Error) -> ScenarioError {
        let (Some(span), raw) = (error.span(), error.message()) else {
            return self.schema_error(error, None);
        };
        let Some(key) = origin::key_at(&self.text, span.start) else {
            return self.schema_error(error, None);
        };
        let message = if raw.starts_with("duplicate key") {
            format!("duplicate key {key}: give each key once")
        } else if raw.contains(" as i128") || raw.contains("value was too large") {
            let value = self.text.get(span.clone()).unwrap_or("?").trim();
            let allowed = self
                .probe_table(span.clone())
                .and_then(|table| probe::allowed(&table, &key))
                .unwrap_or_else(|| format!("a number in [-{0}, {0}]", i64::MAX));
            format!("{key} = {value} is invalid: allowed {allowed}")
        } else {
            return self.schema_error(error, None);
        };
        ScenarioError::Rejected {
            origin: self.at_offset(span.start),
            key: Some(key),
            message: origin::shorten(&message),
        }
    }

    /// The scenario with the text of `span` written as 0 and the overrides applied (to ask
    /// what the key there allows).
    fn probe_table(&self, span: std::ops::Range<usize>) -> Option<toml::Table> {
        let mut text = self.text.clone();
        text.replace_range(span, "0");
        let mut table: toml::Table = text.parse().ok()?;
        for set in &self.overrides {
            apply_override(&mut table, set).ok()?;
        }
        Some(table)
    }
}

impl Scenario {
    /// Reads, overrides, parses and validates a scenario file.
    pub fn load(path: &Path, overrides: &[String]) -> Result<Scenario, ScenarioError> {
        Self::load_with_source(path, overrides).map(|(scenario, _)| scenario)
    }

    /// [`Scenario::load`], with the source that says where each value came from (for
    /// checks made after loading, e.g. of the assets).
    pub fn load_with_source(
        path: &Path,
        overrides: &[String],
    ) -> Result<(Scenario, ScenarioSource), ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Unreadable {
            path: path.to_path_buf(),
            source,
        })?;
        if text.parse::<toml::Table>().is_ok_and(|t| t.is_empty()) {
            return Err(ScenarioError::Empty {
                path: path.to_path_buf(),
            });
        }
        let source = ScenarioSource {
            path: path.to_path_buf(),
            text,
            overrides: overrides.to_vec(),
        };
        let mut scenario = Self::from_source(&source)?;
        let dir = path.parent().unwrap_or(Path::new("."));
        scenario.camera.mesh = resolve_asset_path(&scenario.camera.mesh, DEFAULT_MESH, dir);
        scenario.follower.aircraft =
            resolve_asset_path(&scenario.follower.aircraft, DEFAULT_AIRCRAFT, dir);
        if !scenario.target.track.is_empty() {
            // Any track may be one of the shipped ones (assets/tracks/).
            let track = &scenario.target.track;
            scenario.target.track = resolve_asset_path(track, track, dir);
        }
        scenario.target.aircraft =
            resolve_asset_path(&scenario.target.aircraft, DEFAULT_AIRCRAFT, dir);
        Ok((scenario, source))
    }

    /// Parses scenario text as if read from `path` (used in messages only).
    pub fn from_toml_str(
        text: &str,
        path: &Path,
        overrides: &[String],
    ) -> Result<Scenario, ScenarioError> {
        Self::from_source(&ScenarioSource {
            path: path.to_path_buf(),
            text: text.to_string(),
            overrides: overrides.to_vec(),
        })
    }

    /// Parses, overrides and validates a source.
    fn from_source(source: &ScenarioSource) -> Result<Scenario, ScenarioError> {
        let mut table: toml::Table = source.text.parse().map_err(|e| source.text_error(&e))?;
        // A group's members are read by `group::GroupScenario`; the file's own sections are
        // the pair its members start from.
        table.remove("group");
        for text in &source.overrides {
            apply_override(&mut table, text).map_err(|reason| ScenarioError::Override {
                text: text.clone(),
                reason,
            })?;
        }
        let scenario: Scenario = toml::Value::Table(table.clone())
            .try_into()
            .map_err(|e| source.schema_error(&e, Some(&table)))?;
        scenario
            .validate()
            .map_err(|invalid| source.reject(&invalid.key, invalid.to_string()))?;
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

/// Where a scenario's asset path points: a relative path is looked up from the scenario
/// file's folder `dir`; the shipped default `default`, when that folder has none, is this
/// program's own (`assets/` of its source; failing that, the caller uses the copy built into
/// the program). The path found is returned absolute, so that the resolved scenario runs from
/// anywhere; a path found nowhere is returned as it is, for the loader to report.
fn resolve_asset_path(path: &str, default: &str, dir: &Path) -> String {
    let asset = PathBuf::from(path);
    if asset.is_absolute() {
        return path.to_string();
    }
    let mut candidates = vec![dir.join(&asset)];
    if path == default {
        candidates.push(Path::new(env!("CARGO_MANIFEST_DIR")).join(&asset));
    }
    match candidates.iter().find(|p| p.exists()) {
        Some(found) => {
            let found = found.canonicalize().unwrap_or_else(|_| found.clone());
            found.to_string_lossy().into_owned()
        }
        None => path.to_string(),
    }
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
            Err(ScenarioError::Rejected {
                origin: Origin::Override(_),
                ..
            })
        ));
        let s = parse("", &["guidance.mission=intercept"]).expect("bare strings work");
        assert_eq!(s.guidance.mission, Mission::Intercept);
    }
}
