//! Group scenarios (docs/design.md, Group tracking): a scenario file with a `[group]` table
//! of followers, each tracking a named aircraft (the scenario's target, an extra target, or
//! another follower: a chain), and of extra targets.
//!
//! ```toml
//! [[group.follower]]
//! name = "f1"
//! tracks = "target"                         # the scenario's [target]
//! guidance.command_ft = [32.0, 8.0, 0.0]    # any key of the scenario, but run.*
//!
//! [[group.target]]
//! name = "crosser"
//! motion = "straight"                       # any key of [target]
//! size_ft = 12.0
//! ```
//!
//! Each follower is the file's scenario with its entry's keys applied as `--set` overrides
//! (after the command line's), so every follower is a whole [`Scenario`] passed by the same
//! checks; each extra target is the file's scenario with its entry's keys set in `[target]`.
//! The run section is the group's: the followers step together. Follower `k` (0-based, in
//! the file's order) runs on its own `run.seed + k·2³²` (modulo 2⁶³): its turbulence and
//! any noise. With `gusts = "shared"` in `[group]` the followers fly one air mass instead:
//! every follower's Dryden stream is the group's `run.seed`'s (the first follower's), the
//! same white noise shaped at each one's own airspeed and altitude, as a target's with
//! `target.gusts = "shared"`. Their noise stays their own.
//!
//! ```toml
//! [group]
//! gusts = "shared"                          # default "independent"
//! ```

use super::origin::ScenarioSource;
use super::{Scenario, ScenarioError};
use std::path::Path;

/// The name of the scenario's own `[target]` in a group.
pub const BASE_TARGET: &str = "target";

/// A follower of a group.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupFollower {
    /// Its name (its outputs' folder).
    pub name: String,
    /// The aircraft it tracks: a target's name or another follower's.
    pub tracks: String,
    /// Its whole scenario (its `[target]` is what it tracks when that is a target).
    pub scenario: Scenario,
}

/// A target of a group: the scenario whose `[target]` describes it.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupTarget {
    /// Its name.
    pub name: String,
    /// The scenario of its `[target]`.
    pub scenario: Scenario,
}

/// A group scenario: its targets (the scenario's own first) and followers, leaders before
/// the followers that track them.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupScenario {
    /// The targets, the scenario's `[target]` first.
    pub targets: Vec<GroupTarget>,
    /// The followers, each after the follower it tracks.
    pub followers: Vec<GroupFollower>,
}

impl GroupScenario {
    /// The group the file at `path` describes, with the command line's `overrides` applied
    /// to every member; `None` when the file has no `[group]` (a single pair).
    pub fn load(path: &Path, overrides: &[String]) -> Result<Option<Self>, ScenarioError> {
        let Ok(text) = std::fs::read_to_string(path) else {
            return Ok(None);
        };
        let Some(group) = text
            .parse::<toml::Table>()
            .ok()
            .and_then(|mut t| t.remove("group"))
        else {
            return Ok(None);
        };
        let base = Scenario::load(path, overrides)?;
        let source = ScenarioSource {
            path: path.to_path_buf(),
            text,
            overrides: overrides.to_vec(),
        };
        let entries = GroupEntries::of(&group, &source)?;
        let mut targets = vec![GroupTarget {
            name: BASE_TARGET.to_string(),
            scenario: base.clone(),
        }];
        for (name, sets) in entries.targets {
            let sets: Vec<String> = sets.iter().map(|s| format!("target.{s}")).collect();
            let scenario = member_scenario(&source, "group.target", &name, &sets)?;
            targets.push(GroupTarget { name, scenario });
        }
        let mut followers = Vec::new();
        for (k, (name, tracks, sets)) in entries.followers.into_iter().enumerate() {
            if let Some(run_key) = sets.iter().find(|s| s.starts_with("run.")) {
                let key = format!("group.follower.{name}.{run_key}");
                return Err(source.reject(
                    "group.follower",
                    format!("{key}: the run section is the group's: set it outside [group]"),
                ));
            }
            let mut scenario = member_scenario(&source, "group.follower", &name, &sets)?;
            // Within the key's range, [0, 2⁶³ - 1].
            scenario.run.seed = base.run.seed.wrapping_add((k as u64) << 32) & (i64::MAX as u64);
            if entries.gusts_shared {
                scenario.run.shared_air_seed = Some(base.run.seed);
            }
            followers.push(GroupFollower {
                name,
                tracks,
                scenario,
            });
        }
        let followers = leaders_first(followers, &targets, &source)?;
        Ok(Some(Self { targets, followers }))
    }
}

/// The scenario of member `name` of `table` (`group.follower` or `group.target`): the
/// file's, with the command line's overrides and then the member's `sets`.
fn member_scenario(
    source: &ScenarioSource,
    table: &str,
    name: &str,
    sets: &[String],
) -> Result<Scenario, ScenarioError> {
    let overrides: Vec<String> = source.overrides.iter().chain(sets).cloned().collect();
    Scenario::load(&source.path, &overrides)
        .map_err(|e| source.reject(table, format!("{table} \"{name}\": {e}")))
}

/// The `[group]` table's members: names, what each follower tracks, and each member's keys
/// as `section.key=value` overrides; and whether the followers share one air mass.
struct GroupEntries {
    followers: Vec<(String, String, Vec<String>)>,
    targets: Vec<(String, Vec<String>)>,
    gusts_shared: bool,
}

impl GroupEntries {
    fn of(group: &toml::Value, source: &ScenarioSource) -> Result<Self, ScenarioError> {
        let reject = |key: &str, message: String| source.reject(key, message);
        let table = group.as_table().ok_or_else(|| {
            reject(
                "group",
                "group must be a table of [[group.follower]] and [[group.target]]".into(),
            )
        })?;
        if let Some(key) = table
            .keys()
            .find(|k| !["follower", "target", "gusts"].contains(&k.as_str()))
        {
            return Err(reject(
                &format!("group.{key}"),
                format!("group.{key} is not a key of [group]: allowed follower, target, gusts"),
            ));
        }
        let gusts_shared = match table.get("gusts") {
            None => false,
            Some(toml::Value::String(s)) if s == "independent" => false,
            Some(toml::Value::String(s)) if s == "shared" => true,
            Some(other) => {
                return Err(reject(
                    "group.gusts",
                    format!(
                        "group.gusts = {other} is invalid: allowed \"independent\" or \"shared\""
                    ),
                ));
            }
        };
        let members = |key: &str| member_tables(table, key, source);
        let mut names = vec![BASE_TARGET.to_string()];
        let mut take_name = |entry: &mut toml::Table, key: &str| -> Result<String, ScenarioError> {
            let name = take_string(entry, "name", key, source)?;
            if names.contains(&name) {
                return Err(reject(
                    key,
                    format!(
                        "{key}.name = \"{name}\" is taken: names must be unique and not \"{BASE_TARGET}\""
                    ),
                ));
            }
            names.push(name.clone());
            Ok(name)
        };
        let mut targets = Vec::new();
        for mut entry in members("target")? {
            let name = take_name(&mut entry, "group.target")?;
            targets.push((name, overrides_of(&entry, "")));
        }
        let mut followers = Vec::new();
        for mut entry in members("follower")? {
            let name = take_name(&mut entry, "group.follower")?;
            let tracks = take_string(&mut entry, "tracks", "group.follower", source)?;
            let sets = overrides_of(&entry, "");
            if let Some(bare) = sets
                .iter()
                .find(|s| !s.split('=').next().unwrap_or("").contains('.'))
            {
                return Err(reject(
                    "group.follower",
                    format!(
                        "group.follower \"{name}\": {bare}: expected a scenario key (section.key) besides name and tracks"
                    ),
                ));
            }
            followers.push((name, tracks, sets));
        }
        if followers.is_empty() {
            return Err(reject(
                "group",
                "a group needs at least one [[group.follower]]".into(),
            ));
        }
        Ok(Self {
            followers,
            targets,
            gusts_shared,
        })
    }
}

/// The entries of `[[group.<key>]]` (none when there is none).
fn member_tables(
    table: &toml::Table,
    key: &str,
    source: &ScenarioSource,
) -> Result<Vec<toml::Table>, ScenarioError> {
    let at = format!("group.{key}");
    match table.get(key) {
        None => Ok(Vec::new()),
        Some(toml::Value::Array(items)) => items
            .iter()
            .map(|item| {
                item.as_table().cloned().ok_or_else(|| {
                    source.reject(&at, format!("{at} entries must be tables ([[{at}]])"))
                })
            })
            .collect(),
        Some(_) => Err(source.reject(&at, format!("{at} must be written [[{at}]]"))),
    }
}

/// Removes `entry`'s string `key` (of member table `table`), which must be there.
fn take_string(
    entry: &mut toml::Table,
    key: &str,
    table: &str,
    source: &ScenarioSource,
) -> Result<String, ScenarioError> {
    match entry.remove(key) {
        Some(toml::Value::String(s)) if !s.trim().is_empty() => Ok(s),
        Some(other) => Err(source.reject(
            &format!("{table}.{key}"),
            format!("{table}.{key} = {other} is invalid: allowed a non-empty string"),
        )),
        None => Err(source.reject(table, format!("{table}: every entry needs {key} = \"...\""))),
    }
}

/// `table`'s values as `key=value` overrides, nested tables as dotted keys under `prefix`.
fn overrides_of(table: &toml::Table, prefix: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (key, value) in table {
        let path = if prefix.is_empty() {
            key.clone()
        } else {
            format!("{prefix}.{key}")
        };
        match value {
            toml::Value::Table(inner) => out.extend(overrides_of(inner, &path)),
            _ => out.push(format!("{path}={value}")),
        }
    }
    out
}

/// The followers ordered so that each comes after the follower it tracks; an unknown name
/// or a cycle in `tracks` is an error.
fn leaders_first(
    mut waiting: Vec<GroupFollower>,
    targets: &[GroupTarget],
    source: &ScenarioSource,
) -> Result<Vec<GroupFollower>, ScenarioError> {
    let known = |name: &str, waiting: &[GroupFollower]| {
        targets.iter().any(|t| t.name == name) || waiting.iter().any(|f| f.name == name)
    };
    if let Some(f) = waiting.iter().find(|f| !known(&f.tracks, &waiting)) {
        let names: Vec<&str> = (targets.iter().map(|t| t.name.as_str()))
            .chain(waiting.iter().map(|f| f.name.as_str()))
            .filter(|n| *n != f.name)
            .collect();
        return Err(source.reject(
            "group.follower",
            format!(
                "group.follower \"{}\": tracks = \"{}\" names no aircraft: allowed {}",
                f.name,
                f.tracks,
                names.join(", ")
            ),
        ));
    }
    let mut ordered: Vec<GroupFollower> = Vec::new();
    while !waiting.is_empty() {
        let ready = waiting.iter().position(|f| {
            targets.iter().any(|t| t.name == f.tracks) || ordered.iter().any(|o| o.name == f.tracks)
        });
        let Some(i) = ready else {
            let cycle: Vec<String> = waiting
                .iter()
                .map(|f| format!("{} tracks {}", f.name, f.tracks))
                .collect();
            return Err(source.reject(
                "group.follower",
                format!(
                    "group.follower: tracks form a cycle ({}): each chain must end at a target",
                    cycle.join(", ")
                ),
            ));
        };
        ordered.push(waiting.remove(i));
    }
    Ok(ordered)
}
