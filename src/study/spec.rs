//! Study files (TOML): the base scenario, the axes and how they combine. The schema is read
//! here; the axes' values are expanded into cases in [`super::plan`].
//!
//! ```toml
//! [study]
//! scenario = "../scenarios/formation.toml"   # relative to the study file
//! kind = "sweep"                            # or "apparent_size"
//! combine = "factorial"                     # or "zip"
//! replicates = 5                            # run.seed = first_seed, first_seed + 1, ...
//! set = ["output.plots=false"]              # overrides of every case
//!
//! [[axis]]
//! key = "camera.hfov_deg"
//! range = { from = 30, to = 120, step = 15 }
//!
//! [[axis]]
//! name = "resolution"
//! keys = ["camera.width_px", "camera.height_px"]   # moving together
//! values = [[320, 240], [640, 480]]
//! ```

use serde::Deserialize;

/// What a study's cases do.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StudyKind {
    /// Each case is a `wingman run` of the base scenario with the case's overrides.
    #[default]
    Sweep,
    /// Each case renders the target once at a relative orientation and range (seed 8.2).
    ApparentSize,
}

/// How the axes' values combine into cases.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Combine {
    /// Every combination of the axes' values (the first axis varies slowest).
    #[default]
    Factorial,
    /// The k-th value of every axis together (all axes have as many values).
    Zip,
}

/// A study file as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyFile {
    /// `[study]`: what is studied and how.
    pub study: StudySection,
    /// `[[axis]]`: the keys varied, in order.
    #[serde(default, rename = "axis")]
    pub axes: Vec<AxisSpec>,
    /// `[plots]`: what the sweep draws.
    #[serde(default)]
    pub plots: PlotsSection,
}

/// `[study]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudySection {
    /// The base scenario, relative to the study file.
    pub scenario: String,
    /// What a case does.
    #[serde(default)]
    pub kind: StudyKind,
    /// How the axes combine.
    #[serde(default)]
    pub combine: Combine,
    /// Runs per combination of axis values, over `run.seed` (absent: the scenario's seed).
    pub replicates: Option<u32>,
    /// The first replicate's `run.seed`.
    #[serde(default = "default_first_seed")]
    pub first_seed: u64,
    /// Overrides applied to every case before the axes' (`section.key=value`).
    #[serde(default)]
    pub set: Vec<String>,
}

fn default_first_seed() -> u64 {
    1
}

/// `[plots]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlotsSection {
    /// The `results.csv` columns plotted against each axis (absent: the kind's defaults).
    pub outcomes: Option<Vec<String>>,
}

/// One `[[axis]]` as written: one key or several moving together, and a list or a range.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisSpec {
    /// The axis' name in messages and plots (default: its first key).
    pub name: Option<String>,
    /// The scenario key varied (`section.key`).
    pub key: Option<String>,
    /// Several keys varied together; each value is then a list with one entry per key.
    pub keys: Option<Vec<String>>,
    /// The values, in order.
    pub values: Option<Vec<toml::Value>>,
    /// Or evenly spaced numbers.
    pub range: Option<RangeSpec>,
}

/// `range = { from, to, step }` (inclusive; integers when all three are) or
/// `range = { from, to, count }` (`count` numbers from `from` to `to`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RangeSpec {
    /// First value.
    pub from: toml::Value,
    /// Last value (included when the steps land on it).
    pub to: toml::Value,
    /// Spacing.
    pub step: Option<toml::Value>,
    /// Or the number of values.
    pub count: Option<u32>,
}

/// The most values one axis may have.
pub const MAX_AXIS_VALUES: usize = 10_000;

impl RangeSpec {
    /// The range's values, or why it has none.
    pub fn values(&self) -> Result<Vec<toml::Value>, String> {
        let number = |v: &toml::Value, what: &str| match v {
            toml::Value::Integer(i) => Ok(*i as f64),
            toml::Value::Float(f) if f.is_finite() => Ok(*f),
            _ => Err(format!("range.{what} must be a number, not {v}")),
        };
        let (from, to) = (number(&self.from, "from")?, number(&self.to, "to")?);
        if to < from {
            return Err(format!("range.to = {to} is below range.from = {from}"));
        }
        match (&self.step, self.count) {
            (Some(step_value), None) => {
                let step = number(step_value, "step")?;
                if step <= 0.0 {
                    return Err(format!("range.step = {step} must be > 0"));
                }
                // Counted in floating point first: a huge range must not wrap the cast.
                let count = ((to - from) / step + 1e-9).floor() + 1.0;
                if count > MAX_AXIS_VALUES as f64 {
                    return Err(format!("{count} values; at most {MAX_AXIS_VALUES}"));
                }
                let n = count as usize;
                let integers = [&self.from, &self.to, step_value]
                    .iter()
                    .all(|v| v.is_integer());
                Ok((0..n).map(|k| spaced(from, step, k, integers)).collect())
            }
            (None, Some(count)) => {
                let n = count as usize;
                if n < 2 {
                    return Err(format!("range.count = {count} must be 2 or more"));
                }
                check_count(n)?;
                let step = (to - from) / (n - 1) as f64;
                Ok((0..n).map(|k| spaced(from, step, k, false)).collect())
            }
            _ => Err("a range has either `step` or `count`".to_string()),
        }
    }
}

fn check_count(n: usize) -> Result<(), String> {
    if n > MAX_AXIS_VALUES {
        return Err(format!("{n} values; at most {MAX_AXIS_VALUES}"));
    }
    Ok(())
}

/// `from + k step`, as an integer or rounded to 12 significant digits (so that 0.1 steps
/// read 0.3, not 0.30000000000000004).
fn spaced(from: f64, step: f64, k: usize, integer: bool) -> toml::Value {
    let x = from + step * k as f64;
    if integer {
        return toml::Value::Integer(x.round() as i64);
    }
    let rounded: f64 = format!("{x:.12e}").parse().unwrap_or(x);
    toml::Value::Float(rounded)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn range(text: &str) -> Result<Vec<toml::Value>, String> {
        let spec: RangeSpec = toml::from_str(text).map_err(|e| e.to_string())?;
        spec.values()
    }

    #[test]
    fn integer_range_is_inclusive_and_integer() {
        let v = range("from = 30\nto = 120\nstep = 15").unwrap();
        assert_eq!(v.len(), 7);
        assert_eq!(v[0], toml::Value::Integer(30));
        assert_eq!(v[6], toml::Value::Integer(120));
    }

    #[test]
    fn float_steps_are_rounded() {
        let v = range("from = 0.1\nto = 0.5\nstep = 0.1").unwrap();
        assert_eq!(v.len(), 5);
        assert_eq!(v[2], toml::Value::Float(0.3));
    }

    #[test]
    fn count_spaces_evenly() {
        let v = range("from = 0\nto = 1\ncount = 5").unwrap();
        assert_eq!(v[1], toml::Value::Float(0.25));
        assert_eq!(v.len(), 5);
    }

    #[test]
    fn bad_ranges_say_why() {
        assert!(
            range("from = 2\nto = 1\nstep = 1")
                .unwrap_err()
                .contains("below")
        );
        assert!(
            range("from = 0\nto = 1\nstep = 0")
                .unwrap_err()
                .contains("> 0")
        );
        assert!(range("from = 0\nto = 1").unwrap_err().contains("either"));
        assert!(
            range("from = 0\nto = 1e9\nstep = 1")
                .unwrap_err()
                .contains("at most")
        );
        // A count beyond usize: refused, not wrapped by the cast.
        assert!(
            range("from = 0\nto = 1e30\nstep = 1")
                .unwrap_err()
                .contains("at most")
        );
        assert!(
            range("from = \"a\"\nto = 1\nstep = 1")
                .unwrap_err()
                .contains("number")
        );
    }
}
