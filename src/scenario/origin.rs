//! Where a scenario value came from (a line and column of the file, or a `--set` argument),
//! and the schema's complaints in a user's words: the value, what is allowed, no Rust type
//! names, one short line.

use std::fmt::Display;
use std::path::PathBuf;

use super::check::short_number;

/// Longest message kept after the origin, in characters (the whole line stays under 200 with
/// a short file name).
const MAX_MESSAGE_CHARS: usize = 150;

/// Where an offending value came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Origin {
    /// The scenario file: the line and column (1-based) where the key is written, or none
    /// when the key is not in the file (its default, or a whole-file problem).
    File {
        /// The scenario file.
        path: PathBuf,
        /// Line and column of the key's value.
        line_column: Option<(usize, usize)>,
    },
    /// A `--set` argument, as given.
    Override(String),
}

impl Display for Origin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::File {
                path,
                line_column: Some((line, column)),
            } => write!(f, "{}:{line}:{column}", path.display()),
            Self::File { path, .. } => write!(f, "{}", path.display()),
            Self::Override(text) => write!(f, "--set {text}"),
        }
    }
}

/// A scenario's text and overrides, to say where a key's value came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ScenarioSource {
    /// The scenario file.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// The `--set` arguments, in order.
    pub overrides: Vec<String>,
}

impl ScenarioSource {
    /// Where the value of `key` (dotted; an `[i]` index is ignored) came from: the last
    /// `--set` that wrote it or a section around it, else where the file writes it.
    pub fn origin(&self, key: &str) -> Origin {
        let bare = key.split('[').next().unwrap_or(key);
        let covers = |set: &str| {
            set.split_once('=').is_some_and(|(k, _)| {
                let k = k.trim();
                k == bare
                    || bare.starts_with(&format!("{k}."))
                    || k.starts_with(&format!("{bare}."))
            })
        };
        match self.overrides.iter().rev().find(|o| covers(o)) {
            Some(set) => Origin::Override(set.clone()),
            None => Origin::File {
                path: self.path.clone(),
                line_column: locate_key(&self.text, bare),
            },
        }
    }

    /// Where the file itself is (no line).
    pub fn file(&self) -> Origin {
        Origin::File {
            path: self.path.clone(),
            line_column: None,
        }
    }

    /// Where the file is, at a byte offset of its text.
    pub fn at_offset(&self, offset: usize) -> Origin {
        Origin::File {
            path: self.path.clone(),
            line_column: Some(line_column(&self.text, offset)),
        }
    }
}

/// The 1-based line and column of byte `offset` of `text`.
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut end = offset.min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    let before = &text[..end];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// Where the value of the dotted `key` is written in the TOML `text` (None when it is not, or
/// the text does not parse).
pub fn locate_key(text: &str, key: &str) -> Option<(usize, usize)> {
    let document = toml::de::DeTable::parse(text).ok()?;
    let mut table = document.get_ref();
    let mut parts = key.split('.').peekable();
    while let Some(part) = parts.next() {
        let (_, value) = table.iter().find(|(k, _)| k.get_ref().as_ref() == part)?;
        if parts.peek().is_none() {
            return Some(line_column(text, value.span().start));
        }
        table = value.get_ref().as_table()?;
    }
    None
}

/// The dotted key written on the line of byte `offset` of `text` (its section from the last
/// `[section]` header above it): for the parser's errors, which carry a place but no key.
pub fn key_at(text: &str, offset: usize) -> Option<String> {
    let (line, _) = line_column(text, offset);
    let lines: Vec<&str> = text.lines().collect();
    let name = lines
        .get(line - 1)?
        .split_once('=')?
        .0
        .trim()
        .trim_matches('"');
    let section = lines[..line - 1].iter().rev().find_map(|l| {
        let header = l.trim().split('#').next()?.trim();
        let inner = header.strip_prefix('[')?.trim_start_matches('[');
        Some(inner.trim_end_matches(']').trim().to_string())
    });
    match section {
        Some(section) if !name.is_empty() => Some(format!("{section}.{name}")),
        _ if !name.is_empty() => Some(name.to_string()),
        _ => None,
    }
}

/// A message of the schema (serde through toml), split into the key it ends with (`... in
/// \`run.dt_s\``) and its text in a user's words.
pub fn schema_message(raw: &str) -> (Option<String>, String) {
    let raw = raw.trim_end().replace('\n', " ");
    let (text, key) = match raw.rsplit_once(" in `") {
        Some((text, key)) if key.ends_with('`') => (
            text.to_string(),
            Some(key.trim_end_matches('`').to_string()),
        ),
        _ => (raw.clone(), None),
    };
    let words = plain_words(&text, key.as_deref().unwrap_or("value"));
    // An unknown key is found where it is written, not at its section (a top-level one,
    // a section or key outside every section, at its own place).
    let key = match (text.strip_prefix("unknown field `"), key) {
        (Some(rest), section) => rest.split('`').next().map(|unknown| match section {
            Some(section) => format!("{section}.{unknown}"),
            None => unknown.to_string(),
        }),
        (None, key) => key,
    };
    (key, shorten(&words))
}

/// Cuts a message to [`MAX_MESSAGE_CHARS`].
pub fn shorten(message: &str) -> String {
    if message.chars().count() <= MAX_MESSAGE_CHARS {
        return message.to_string();
    }
    let cut: String = message.chars().take(MAX_MESSAGE_CHARS - 3).collect();
    format!("{cut}...")
}

/// The schema's complaint about `key` without Rust's names for types.
fn plain_words(text: &str, key: &str) -> String {
    if let Some(rest) = text.strip_prefix("unknown field ") {
        return unknown_key(rest, key);
    }
    if let Some(rest) = text.strip_prefix("unknown variant ") {
        let (value, expected) = rest.split_once(", expected ").unwrap_or((rest, "?"));
        return format!(
            "{key} = {} is invalid: allowed {}",
            value.replace('`', "\""),
            expected.replace('`', "\"")
        );
    }
    for prefix in ["invalid type: ", "invalid value: "] {
        if let Some(rest) = text.strip_prefix(prefix) {
            let (found, expected) = rest.split_once(", expected ").unwrap_or((rest, "?"));
            return format!(
                "{key} = {} is invalid: allowed {}",
                found_value(found),
                plain_type(expected)
            );
        }
    }
    if let Some(rest) = text.strip_prefix("invalid length ") {
        let (found, expected) = rest.split_once(", expected ").unwrap_or((rest, "?"));
        return format!("{key} has {found} values: allowed {}", plain_type(expected));
    }
    text.to_string()
}

/// `unknown field \`kk\`, expected one of \`a\`, \`b\`` as a key and its nearest allowed name.
fn unknown_key(rest: &str, section: &str) -> String {
    let mut names = rest.split('`').skip(1).step_by(2);
    let unknown = names.next().unwrap_or("?");
    let allowed: Vec<&str> = names.collect();
    let key = if section == "value" {
        unknown.to_string()
    } else {
        format!("{section}.{unknown}")
    };
    let nearest = allowed
        .iter()
        .min_by_key(|name| edit_distance(name, unknown))
        .filter(|name| edit_distance(name, unknown) <= name.len().max(unknown.len()) / 2);
    match nearest {
        Some(name) => format!("unknown key {key}: did you mean {name}?"),
        None if allowed.is_empty() => format!("unknown key {key}: the section takes no keys"),
        None => {
            let list = allowed.join(", ");
            if list.chars().count() <= ALLOWED_LIST_MAX_CHARS {
                format!("unknown key {key}: allowed {list}")
            } else {
                format!("unknown key {key}: docs/scenario_reference.md lists the keys")
            }
        }
    }
}

/// The longest list of allowed keys a message spells out: a message stays one line under
/// 200 characters with the file's path and the key before it (the scenario's own sections
/// alone list 120 characters).
const ALLOWED_LIST_MAX_CHARS: usize = 80;

/// The value serde found, from its description (`integer \`-1\``, `string "x"`, `map`).
fn found_value(found: &str) -> String {
    if let Some((_, quoted)) = found.split_once('`') {
        return short_number(quoted.trim_end_matches('`').to_string());
    }
    if let Some(string) = found.strip_prefix("string ") {
        return string.to_string();
    }
    match found {
        "sequence" => "an array".to_string(),
        "map" => "a table".to_string(),
        other => other.to_string(),
    }
}

/// A serde/Rust type name in a user's words.
fn plain_type(expected: &str) -> String {
    let unsigned = |bits: u32| format!("a whole number in [0, {}]", short_bound(bits));
    match expected {
        "f64" | "f32" => "a number".to_string(),
        "u8" => unsigned(8),
        "u16" => unsigned(16),
        "u32" => unsigned(32),
        "u64" | "usize" => unsigned(64),
        "i64" | "i32" | "isize" => "a whole number".to_string(),
        "a boolean" => "true or false".to_string(),
        "a sequence" => "an array".to_string(),
        other if other.starts_with("struct ") => "a table of keys".to_string(),
        other => other.replace('`', "\""),
    }
}

/// 2^bits - 1, short.
fn short_bound(bits: u32) -> String {
    match bits {
        // TOML's integers are 64-bit signed: no larger whole number can be written.
        64 => i64::MAX.to_string(),
        _ => ((1u64 << bits) - 1).to_string(),
    }
}

/// Levenshtein distance between two names.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substitute = diagonal + usize::from(ca != *cb);
            diagonal = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(row[j + 1] + 1);
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_are_found_at_their_line_and_column() {
        let text = "# c\n[run]\ndt_s = 0.5\n[camera.gimbal]\nkind = \"x\"\n";
        assert_eq!(locate_key(text, "run.dt_s"), Some((3, 8)));
        assert_eq!(locate_key(text, "camera.gimbal.kind"), Some((5, 8)));
        assert_eq!(locate_key(text, "run.seed"), None);
    }

    #[test]
    fn messages_name_no_rust_types() {
        let (key, m) = schema_message("invalid type: string \"abc\", expected f64 in `run.dt_s`");
        assert_eq!(key.as_deref(), Some("run.dt_s"));
        assert_eq!(m, "run.dt_s = \"abc\" is invalid: allowed a number");
        let (_, m) = schema_message("invalid value: integer `-1`, expected u32 in `run.log_every`");
        assert_eq!(
            m,
            "run.log_every = -1 is invalid: allowed a whole number in [0, 4294967295]"
        );
        let (_, m) =
            schema_message("unknown field `sigmaa`, expected `k` or `sigma` in `guidance`");
        assert_eq!(m, "unknown key guidance.sigmaa: did you mean sigma?");
        let sections = [
            "run",
            "target",
            "follower",
            "sensor",
            "guidance",
            "acceleration",
        ]
        .iter()
        .chain(&[
            "estimator",
            "excitation",
            "camera",
            "scene",
            "atmosphere",
            "output",
        ])
        .map(|name| format!("`{name}`"))
        .collect::<Vec<_>>()
        .join(", ");
        let m = unknown_key(&format!("`group`, expected one of {sections}"), "value");
        assert_eq!(
            m,
            "unknown key group: docs/scenario_reference.md lists the keys"
        );
    }

    #[test]
    fn parser_places_are_given_their_key() {
        let text = "[run]\nseed = 1\n[camera.gimbal] # c\nkind = 1\n";
        assert_eq!(key_at(text, 8).as_deref(), Some("run.seed"));
        assert_eq!(key_at(text, 40).as_deref(), Some("camera.gimbal.kind"));
        assert_eq!(key_at("x = 1\n", 2).as_deref(), Some("x"));
    }

    #[test]
    fn overrides_are_named_before_the_file() {
        let source = ScenarioSource {
            path: PathBuf::from("s.toml"),
            text: "[run]\ndt_s = 0.5\n".to_string(),
            overrides: vec!["run.dt_s=0".to_string()],
        };
        assert_eq!(
            source.origin("run.dt_s").to_string(),
            "--set run.dt_s=0".to_string()
        );
        assert_eq!(source.origin("run.seed").to_string(), "s.toml");
    }
}
