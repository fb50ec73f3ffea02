//! From a study file to its cases: the axes' values, their combination (factorial or zipped),
//! the replicates over `run.seed`, every case's overrides checked against the scenario loader
//! before anything runs, and the deterministic partition into shards.

use super::StudyError;
use super::layout::{AxisLayout, StudyLayout};
use super::setting::{SEED_KEY, Setting, value_cell};
use super::spec::{AxisSpec, Combine, MAX_AXIS_VALUES, StudyFile, StudyKind};
use super::view::{VIEW_SECTION, View};
use crate::scenario::Scenario;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The most cases one study may have.
pub const MAX_CASES: usize = 1_000_000;

/// One axis: the keys it sets and its values (one entry per key in each).
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Name in messages and plots.
    pub name: String,
    /// The keys set together, `section.key`.
    pub keys: Vec<String>,
    /// The values; each holds one value per key.
    pub values: Vec<Vec<toml::Value>>,
}

impl Axis {
    /// The axis as `results.csv` shows it.
    pub fn layout(&self) -> AxisLayout {
        AxisLayout {
            name: self.name.clone(),
            keys: self.keys.clone(),
            values: self
                .values
                .iter()
                .map(|v| v.iter().map(value_cell).collect())
                .collect(),
        }
    }
}

/// One run of a study.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Position in the study, from 0: names its folder and orders `results.csv`.
    pub index: usize,
    /// Which combination of axis values (from 0).
    pub point: usize,
    /// Which replicate of that combination (from 0).
    pub replicate: u32,
    /// The axes' settings, then `run.seed` for replicates.
    pub settings: Vec<Setting>,
}

impl Case {
    /// The scenario overrides of this case after the study's `set` (view keys excluded).
    pub fn scenario_overrides(&self, set: &[String]) -> Vec<String> {
        set.iter()
            .cloned()
            .chain(
                self.settings
                    .iter()
                    .filter(|s| !is_view_key(&s.key))
                    .map(Setting::override_text),
            )
            .collect()
    }

    /// The settings as `results.csv` cells (key, value).
    pub fn cells(&self) -> Vec<(String, String)> {
        self.settings
            .iter()
            .map(|s| (s.key.clone(), s.cell()))
            .collect()
    }
}

fn is_view_key(key: &str) -> bool {
    key.split_once('.').is_some_and(|(s, _)| s == VIEW_SECTION)
}

/// A study ready to run: every case, validated.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The study file.
    pub study_path: PathBuf,
    /// What a case does.
    pub kind: StudyKind,
    /// The base scenario.
    pub scenario_path: PathBuf,
    /// Overrides of every case.
    pub set: Vec<String>,
    /// The axes, in order.
    pub axes: Vec<Axis>,
    /// Every case, by index.
    pub cases: Vec<Case>,
    /// What the results are made of (`plan.json`).
    pub layout: StudyLayout,
}

/// A fixed part of a study's cases: those whose index is `index` modulo `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, from 0.
    pub index: usize,
    /// Shards in all.
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;

    /// `I/N` with 0 ≤ I < N.
    fn from_str(text: &str) -> Result<Self, String> {
        let bad = || format!("--shard {text}: expected I/N with 0 <= I < N (e.g. 0/3)");
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let index: usize = i.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }
}

impl Shard {
    /// Whether case `index` belongs to this shard. Cases are dealt out in turn, so that
    /// each shard gets its share of every stretch of an axis (cheap and dear cases alike).
    pub fn holds(&self, index: usize) -> bool {
        index % self.count == self.index
    }
}

impl Plan {
    /// Reads a study file, expands its cases and checks each against the scenario loader.
    pub fn load(study_path: &Path) -> Result<Plan, StudyError> {
        let text =
            std::fs::read_to_string(study_path).map_err(|source| StudyError::Unreadable {
                path: study_path.to_path_buf(),
                source,
            })?;
        let invalid = |reason: String| StudyError::Invalid {
            path: study_path.to_path_buf(),
            reason,
        };
        let file: StudyFile =
            toml::from_str(&text).map_err(|e| invalid(crate::scenario::check::one_line(&e)))?;
        let dir = study_path.parent().unwrap_or(Path::new(""));
        let scenario_path = dir.join(&file.study.scenario);
        let scenario_text = std::fs::read_to_string(&scenario_path).map_err(|e| {
            invalid(format!(
                "study.scenario: cannot read {}: {e}",
                scenario_path.display()
            ))
        })?;
        let axes = file
            .axes
            .iter()
            .enumerate()
            .map(|(k, spec)| axis_from_spec(k, spec).map_err(&invalid))
            .collect::<Result<Vec<_>, _>>()?;
        check_axes(&axes, file.study.replicates.is_some(), file.study.kind).map_err(&invalid)?;
        let cases = expand_cases(&axes, &file).map_err(&invalid)?;
        let name = study_path
            .file_stem()
            .map_or_else(|| "study".into(), |s| s.to_string_lossy().into_owned());
        let layout = StudyLayout {
            study: name,
            kind: file.study.kind,
            axes: axes.iter().map(Axis::layout).collect(),
            replicated: file.study.replicates.is_some(),
            outcomes: file.plots.outcomes.clone(),
            cases: cases.iter().map(Case::cells).collect(),
            study_file: text,
            scenario_file: scenario_text,
        };
        let plan = Plan {
            study_path: study_path.to_path_buf(),
            kind: file.study.kind,
            scenario_path,
            set: file.study.set.clone(),
            axes,
            cases,
            layout,
        };
        plan.validate()?;
        Ok(plan)
    }

    /// The cases of `shard` (every case without one).
    pub fn cases_of(&self, shard: Option<Shard>) -> impl Iterator<Item = &Case> {
        self.cases
            .iter()
            .filter(move |c| shard.is_none_or(|s| s.holds(c.index)))
    }

    /// Every case's overrides go through the scenario loader (and a view's through
    /// [`View::from_settings`]) before anything runs: first the study's `set` alone, then
    /// each axis value alone (so that a bad value is named with its axis), then each distinct
    /// combination.
    fn validate(&self) -> Result<(), StudyError> {
        let load = |overrides: &[String]| Scenario::load(&self.scenario_path, overrides);
        load(&self.set).map_err(|e| StudyError::Invalid {
            path: self.study_path.clone(),
            reason: format!("study.set: {e}"),
        })?;
        for axis in &self.axes {
            for value in &axis.values {
                let settings = settings_of(axis, value);
                let case = Case {
                    index: 0,
                    point: 0,
                    replicate: 0,
                    settings,
                };
                self.check_case(&case, &load)
                    .map_err(|reason| StudyError::BadValue {
                        path: self.study_path.clone(),
                        axis: axis.name.clone(),
                        value: value_text(value),
                        reason,
                    })?;
            }
        }
        let mut seen = BTreeSet::new();
        for case in &self.cases {
            if seen.insert(case.scenario_overrides(&self.set)) {
                self.check_case(case, &load)
                    .map_err(|reason| StudyError::BadCase {
                        path: self.study_path.clone(),
                        case: case.index,
                        settings: describe(&case.settings),
                        reason,
                    })?;
            }
        }
        Ok(())
    }

    /// Why `case`'s overrides are not a valid scenario (or view), if they are not.
    fn check_case(
        &self,
        case: &Case,
        load: &impl Fn(&[String]) -> Result<Scenario, crate::scenario::ScenarioError>,
    ) -> Result<(), String> {
        load(&case.scenario_overrides(&self.set)).map_err(|e| e.to_string())?;
        if self.kind == StudyKind::ApparentSize {
            View::from_settings(&case.settings)?;
        }
        Ok(())
    }
}

/// `a = 1, b = x` for messages.
fn describe(settings: &[Setting]) -> String {
    settings
        .iter()
        .map(|s| format!("{} = {}", s.key, s.value))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A value of an axis as written: one value, or `[a, b]` for several keys.
fn value_text(value: &[toml::Value]) -> String {
    match value {
        [one] => one.to_string(),
        many => toml::Value::Array(many.to_vec()).to_string(),
    }
}

fn settings_of(axis: &Axis, value: &[toml::Value]) -> Vec<Setting> {
    axis.keys
        .iter()
        .zip(value)
        .map(|(key, value)| Setting {
            key: key.clone(),
            value: value.clone(),
        })
        .collect()
}

/// The `k`-th `[[axis]]` (from 0) as keys and values, or what is wrong with it.
fn axis_from_spec(k: usize, spec: &AxisSpec) -> Result<Axis, String> {
    let keys = match (&spec.key, &spec.keys) {
        (Some(key), None) => vec![key.clone()],
        (None, Some(keys)) if !keys.is_empty() => keys.clone(),
        _ => return Err(format!("axis {}: give either `key` or `keys`", k + 1)),
    };
    let name = spec.name.clone().unwrap_or_else(|| keys.join("+"));
    let at = |reason: String| format!("axis `{name}`: {reason}");
    if let Some(bad) = keys.iter().find(|key| !key.contains('.')) {
        return Err(at(format!("key `{bad}` is not section.key")));
    }
    let raw = match (&spec.values, &spec.range) {
        (Some(values), None) => values.clone(),
        (None, Some(range)) => range.values().map_err(&at)?,
        _ => return Err(at("give either `values` or `range`".into())),
    };
    if raw.is_empty() || raw.len() > MAX_AXIS_VALUES {
        return Err(at(format!(
            "1 to {MAX_AXIS_VALUES} values, not {}",
            raw.len()
        )));
    }
    let values = raw
        .into_iter()
        .map(|v| match (keys.len(), v) {
            (1, v) => Ok(vec![v]),
            (n, toml::Value::Array(parts)) if parts.len() == n => Ok(parts),
            (n, other) => Err(at(format!(
                "value {other} is not a list of {n} values, one per key"
            ))),
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Axis { name, keys, values })
}

/// Axes may not share a key, nor set `run.seed` while the study replicates over it; view
/// keys belong to the apparent-size kind.
fn check_axes(axes: &[Axis], replicated: bool, kind: StudyKind) -> Result<(), String> {
    let mut seen = BTreeSet::new();
    for axis in axes {
        for key in &axis.keys {
            if !seen.insert(key.as_str()) {
                return Err(format!(
                    "axis `{}`: key `{key}` is set by two axes",
                    axis.name
                ));
            }
            if replicated && key == SEED_KEY {
                return Err(format!(
                    "axis `{}`: `{SEED_KEY}` is set by the replicates (study.replicates)",
                    axis.name
                ));
            }
            if is_view_key(key) && kind != StudyKind::ApparentSize {
                return Err(format!(
                    "axis `{}`: `{key}` needs study.kind = \"apparent_size\"",
                    axis.name
                ));
            }
        }
    }
    Ok(())
}

/// Every combination of axis values (factorial or zipped), each repeated over the seeds.
fn expand_cases(axes: &[Axis], file: &StudyFile) -> Result<Vec<Case>, String> {
    let points = match file.study.combine {
        Combine::Factorial => factorial_points(axes)?,
        Combine::Zip => zipped_points(axes)?,
    };
    let replicates = file.study.replicates.unwrap_or(1);
    if replicates == 0 {
        return Err("study.replicates must be 1 or more".into());
    }
    let count = points.len().saturating_mul(replicates as usize);
    if count > MAX_CASES {
        return Err(format!("{count} cases; at most {MAX_CASES}"));
    }
    let mut cases = Vec::with_capacity(count);
    for (point, choice) in points.iter().enumerate() {
        for replicate in 0..replicates {
            let mut settings: Vec<Setting> = axes
                .iter()
                .zip(choice)
                .flat_map(|(axis, &k)| settings_of(axis, &axis.values[k]))
                .collect();
            if file.study.replicates.is_some() {
                let seed = file.study.first_seed.saturating_add(u64::from(replicate));
                settings.push(Setting {
                    key: SEED_KEY.into(),
                    value: toml::Value::Integer(i64::try_from(seed).map_err(|_| {
                        format!("study.first_seed: seed {seed} is above {}", i64::MAX)
                    })?),
                });
            }
            cases.push(Case {
                index: cases.len(),
                point,
                replicate,
                settings,
            });
        }
    }
    Ok(cases)
}

/// Indices into each axis' values, the first axis varying slowest.
fn factorial_points(axes: &[Axis]) -> Result<Vec<Vec<usize>>, String> {
    let total = axes
        .iter()
        .try_fold(1usize, |n, a| n.checked_mul(a.values.len()))
        .filter(|n| *n <= MAX_CASES)
        .ok_or_else(|| format!("more than {MAX_CASES} combinations"))?;
    Ok((0..total)
        .map(|mut k| {
            let mut choice = vec![0; axes.len()];
            for (slot, axis) in choice.iter_mut().zip(axes).rev() {
                *slot = k % axis.values.len();
                k /= axis.values.len();
            }
            choice
        })
        .collect())
}

/// The k-th value of every axis together.
fn zipped_points(axes: &[Axis]) -> Result<Vec<Vec<usize>>, String> {
    let n = axes.first().map_or(1, |a| a.values.len());
    if let Some(other) = axes.iter().find(|a| a.values.len() != n) {
        return Err(format!(
            "combine = \"zip\" needs axes of equal length: `{}` has {} values, `{}` {}",
            axes[0].name,
            n,
            other.name,
            other.values.len()
        ));
    }
    Ok((0..n).map(|k| vec![k; axes.len()]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(name: &str, n: i64) -> Axis {
        Axis {
            name: name.into(),
            keys: vec![format!("s.{name}")],
            values: (0..n).map(|k| vec![toml::Value::Integer(k)]).collect(),
        }
    }

    #[test]
    fn factorial_varies_the_first_axis_slowest() {
        let points = factorial_points(&[axis("a", 2), axis("b", 3)]).unwrap();
        assert_eq!(points.len(), 6);
        assert_eq!(points[0], vec![0, 0]);
        assert_eq!(points[1], vec![0, 1]);
        assert_eq!(points[3], vec![1, 0]);
        assert_eq!(factorial_points(&[]).unwrap(), vec![Vec::<usize>::new()]);
    }

    #[test]
    fn zip_needs_equal_lengths() {
        assert_eq!(
            zipped_points(&[axis("a", 2), axis("b", 2)]).unwrap().len(),
            2
        );
        assert!(zipped_points(&[axis("a", 2), axis("b", 3)]).is_err());
    }

    #[test]
    fn shards_partition_the_cases() {
        let shards: Vec<Shard> = (0..3).map(|i| format!("{i}/3").parse().unwrap()).collect();
        for index in 0..20 {
            assert_eq!(shards.iter().filter(|s| s.holds(index)).count(), 1);
        }
        for bad in ["3/3", "1/0", "a/2", "1", "-1/2"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }

    #[test]
    fn multi_key_values_need_one_entry_per_key() {
        let spec: AxisSpec = toml::from_str(
            "keys = [\"camera.width_px\", \"camera.height_px\"]\nvalues = [[320, 240], [640]]",
        )
        .unwrap();
        let err = axis_from_spec(0, &spec).unwrap_err();
        assert!(err.contains("[640]") && err.contains("2 values"), "{err}");
    }
}
