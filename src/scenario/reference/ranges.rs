//! What each key allows, as the validator itself says it: the key is set to values no check
//! lets through (NaN, ±10³⁰⁰, 0, an empty path) in a valid scenario, and the allowed range of
//! the message that names the key is read back. A check that applies only in some runs (the
//! camera's keys with `sensor.mode = "camera"`) is found in the first of the given scenarios
//! where it applies.

use super::schema_docs::KeyDoc;
use crate::scenario::Scenario;

/// The values a key of this default value is probed with: an array of floats with one
/// element changed at a time.
fn probes(default: &toml::Value) -> Vec<toml::Value> {
    use toml::Value;
    let floats = [f64::NAN, -1e300, 1e300];
    let one_changed = |items: &Vec<Value>, i: usize, x: f64| {
        let mut items = items.clone();
        items[i] = Value::Float(x);
        Value::Array(items)
    };
    match default {
        Value::Float(_) => floats.map(Value::Float).to_vec(),
        Value::Integer(_) => [0, -1, i64::from(u32::MAX), i64::MAX]
            .map(Value::Integer)
            .to_vec(),
        Value::String(_) => vec![Value::String(String::new())],
        Value::Array(items) if items.is_empty() => vec![Value::Array(Vec::new())],
        Value::Array(items) if matches!(items.first(), Some(Value::Float(_))) => (0..items.len())
            .flat_map(|i| floats.map(|x| one_changed(items, i, x)))
            .collect(),
        _ => Vec::new(),
    }
}

/// `table` with the dotted `key` set to `value` (its sections exist: the table is a whole
/// resolved scenario); a section `name[]` is the first table of the array `name`.
fn with_value(table: &toml::Table, key: &str, value: toml::Value) -> Option<toml::Table> {
    let mut changed = table.clone();
    let path: Vec<&str> = key.split('.').collect();
    let (field, sections) = path.split_last()?;
    let mut current = &mut changed;
    for section in sections {
        current = match section.strip_suffix("[]") {
            Some(array) => current
                .get_mut(array)?
                .as_array_mut()?
                .first_mut()?
                .as_table_mut()?,
            None => current.get_mut(*section)?.as_table_mut()?,
        };
    }
    current.insert(field.to_string(), value);
    Some(changed)
}

/// The validator's allowed range for `key` when the scenario `table` holds `value` there: its
/// message when it names the key (or an element of it, `key[1]`), else nothing.
fn refusal(table: &toml::Table, key: &str, value: toml::Value) -> Option<String> {
    let scenario: Scenario = toml::Value::Table(with_value(table, key, value)?)
        .try_into()
        .ok()?;
    let invalid = scenario.validate().err()?;
    // The validator names the first table of an array by its index.
    let named = key.replace("[]", "[0]");
    if invalid.key == named {
        Some(invalid.allowed)
    } else {
        let element = invalid.key.strip_prefix(&named)?;
        element
            .starts_with('[')
            .then(|| format!("{element}: {}", invalid.allowed))
    }
}

/// What the validator allows for `key` (default value `default`): the distinct refusals of
/// its probes in the first scenario of `contexts` that refuses any, joined by "; "; `None`
/// when none refuses one.
pub fn validated_range(
    key: &str,
    default: &toml::Value,
    contexts: &[toml::Table],
) -> Option<String> {
    contexts.iter().find_map(|table| {
        let mut found: Vec<String> = Vec::new();
        for value in probes(default) {
            if let Some(allowed) = refusal(table, key, value)
                && !found.contains(&allowed)
            {
                found.push(allowed);
            }
        }
        (!found.is_empty()).then(|| same_for_each_element(found).join("; "))
    })
}

/// Refusals `[0]: X`, `[1]: X`, ... of every element of an array, with the same X, as one
/// `each element: X`.
fn same_for_each_element(found: Vec<String>) -> Vec<String> {
    let Some(first) = found.iter().find_map(|f| f.strip_prefix("[0]: ")) else {
        return found;
    };
    let elements = found
        .iter()
        .filter(|f| f.starts_with('[') && f.contains("]: "));
    let count = elements.clone().count();
    let all_same = (0..count).all(|i| found.contains(&format!("[{i}]: {first}")));
    if count < 2 || !all_same {
        return found;
    }
    let mut collapsed: Vec<String> = found
        .iter()
        .filter(|f| !(f.starts_with('[') && f.contains("]: ")))
        .cloned()
        .collect();
    collapsed.push(format!("each element: {first}"));
    collapsed
}

/// The range of a key no probe found a check for: what its type admits.
pub fn type_range(key: &KeyDoc) -> String {
    if !key.variants.is_empty() {
        let names: Vec<String> = key
            .variants
            .iter()
            .map(|v| format!("`{}`", v.name))
            .collect();
        return format!("one of {}", names.join(", "));
    }
    match key.rust_type.as_str() {
        "bool" => "`true` or `false`".to_string(),
        "u8" => "an integer in [0, 255]".to_string(),
        "u32" => format!("an integer in [0, {}]", u32::MAX),
        "u64" => format!("an integer in [0, {}]", i64::MAX),
        t if t.starts_with("[u8;") => "integers in [0, 255]".to_string(),
        "String" => "any text".to_string(),
        t if t.starts_with("Vec<") => "any number of tables".to_string(),
        _ => "any value of its type (no check)".to_string(),
    }
}

/// An error naming the first variant of an enum key that a scenario cannot hold (its name
/// in the sources is not the one serde reads).
pub fn check_variants(key: &KeyDoc, table: &toml::Table) -> Result<(), String> {
    for variant in &key.variants {
        let value = toml::Value::String(variant.name.clone());
        let parsed = with_value(table, &key.dotted(), value)
            .and_then(|t| toml::Value::Table(t).try_into::<Scenario>().ok());
        if parsed.is_none() {
            return Err(format!(
                "{} = \"{}\" is not read",
                key.dotted(),
                variant.name
            ));
        }
    }
    Ok(())
}

/// The default scenario as a TOML table.
pub fn table_of(scenario: &Scenario) -> Result<toml::Table, String> {
    match toml::Value::try_from(scenario) {
        Ok(toml::Value::Table(table)) => Ok(table),
        Ok(_) => Err("a scenario serialises to a table".to_string()),
        Err(e) => Err(format!("cannot serialise a scenario: {e}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn default_table() -> toml::Table {
        table_of(&Scenario::default()).expect("serialisable")
    }

    /// The probes read the validator's own range back, also for an element of an array.
    #[test]
    fn ranges_come_from_the_validator() {
        let contexts = [default_table()];
        let float = toml::Value::Float(1.0);
        let range = validated_range("run.duration_s", &float, &contexts);
        assert_eq!(range.as_deref(), Some("[0.001, 100000]"));
        let vec = toml::Value::Array(vec![toml::Value::Float(0.0); 3]);
        let range = validated_range("follower.initial_attitude_deg", &vec, &contexts);
        assert_eq!(
            range.as_deref(),
            Some("three finite numbers; [1]: [-89, 89]")
        );
        let int = toml::Value::Integer(10);
        let range = validated_range("run.log_every", &int, &contexts);
        assert_eq!(range.as_deref(), Some("an integer in [1, 1000000]"));
        let range = validated_range("sensor.pixel_noise_px", &vec, &contexts);
        assert_eq!(range.as_deref(), Some("each element: [0, 1000]"));
    }
}
