//! What a key holds and what it allows, found by asking the schema and the checks themselves:
//! a message about a value of the wrong kind quotes the key's own list of strings or its own
//! range, never the range of the integer type that stores it.

use super::Scenario;

/// A string no string-choice key accepts: the schema answers it with the key's list.
const NOT_A_CHOICE: &str = "\u{1}";

/// The value at the dotted `key` of `table`, as a user would write it (a number given as a
/// bare string by `--set` is shown without quotes).
pub fn value_text(table: &toml::Table, key: &str) -> Option<String> {
    let (last, sections) = split(key)?;
    let mut current = table;
    for section in sections {
        current = current.get(section)?.as_table()?;
    }
    Some(match current.get(last)? {
        toml::Value::String(s) if s.trim().parse::<f64>().is_ok() => s.trim().to_string(),
        toml::Value::Float(x) => super::check::short_number(x.to_string()),
        other => other.to_string(),
    })
}

/// What `key` allows, asked of the schema and the checks with `table` (the scenario being
/// read, overrides applied) holding a probe there: a string-choice key's list of strings, else
/// the range its checks enforce on a number, else the range of whole numbers it stores.
pub fn allowed(table: &toml::Table, key: &str) -> Option<String> {
    choices(table, key).or_else(|| range(table, key))
}

/// `one of "a", "b"` for a string-choice key.
fn choices(table: &toml::Table, key: &str) -> Option<String> {
    let probe = with_value(table, key, toml::Value::String(NOT_A_CHOICE.to_string()))?;
    let error = parse(probe).err()?;
    let rest = error.message().strip_prefix("unknown variant `")?;
    let (_, expected) = rest.split_once(", expected ")?;
    Some(expected.trim_end().replace('`', "\""))
}

/// The range the checks give for `key` (probed with 0 and with the largest whole numbers),
/// else `a whole number in [0, N]` with N the largest whole number the key stores.
fn range(table: &toml::Table, key: &str) -> Option<String> {
    let mut largest = None;
    for probe in [0, i64::from(u8::MAX), i64::from(u32::MAX), i64::MAX] {
        let Some(scenario) =
            with_value(table, key, toml::Value::Integer(probe)).and_then(|t| parse(t).ok())
        else {
            continue;
        };
        largest = Some(probe);
        if let Err(invalid) = scenario.validate()
            && invalid.key == key
        {
            return Some(invalid.allowed);
        }
    }
    largest.map(|n| format!("a whole number in [0, {n}]"))
}

/// `table` with `key` set to `value` (None where a section on its way is not a table).
fn with_value(table: &toml::Table, key: &str, value: toml::Value) -> Option<toml::Table> {
    let (last, sections) = split(key)?;
    let mut probe = table.clone();
    let mut current = &mut probe;
    for section in sections {
        current = current
            .entry(section.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()?;
    }
    current.insert(last.to_string(), value);
    Some(probe)
}

fn parse(table: toml::Table) -> Result<Scenario, toml::de::Error> {
    toml::Value::Table(table).try_into()
}

/// The key's last name and the sections before it; an `[i]` index is not a key's.
fn split(key: &str) -> Option<(&str, Vec<&str>)> {
    if key.contains('[') {
        return None;
    }
    let parts: Vec<&str> = key.split('.').collect();
    let (last, sections) = parts.split_last()?;
    Some((last, sections.to_vec()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str) -> toml::Table {
        text.parse().expect("valid TOML")
    }

    #[test]
    fn string_choices_are_listed() {
        let allowed = allowed(&table("[target]\nmotion = 1\n"), "target.motion");
        let allowed = allowed.expect("a list");
        assert!(allowed.starts_with("one of \"seed_profile\""), "{allowed}");
    }

    #[test]
    fn integer_keys_quote_their_checked_range() {
        let t = table("[camera]\nwidth_px = -640\n");
        assert_eq!(
            allowed(&t, "camera.width_px").as_deref(),
            Some("an integer in [8, 8192]")
        );
        assert_eq!(value_text(&t, "camera.width_px").as_deref(), Some("-640"));
        let t = table("[run]\nseed = -1\n");
        assert_eq!(
            allowed(&t, "run.seed").as_deref(),
            Some("a whole number in [0, 9223372036854775807]")
        );
    }
}
