//! The scenario schema as its source states it: every `pub struct` and `pub enum` of
//! `src/scenario/*.rs` with the doc comments of its fields and variants, and the walk from
//! [`Scenario`](crate::scenario::Scenario) down to every key a scenario file may set.

use std::collections::BTreeMap;

/// One field of a struct or one variant of an enum, with its doc comment on one line.
#[derive(Debug, Clone, PartialEq)]
pub struct Member {
    /// The field's name, or the variant's name as written in a scenario (snake case).
    pub name: String,
    /// The field's Rust type (empty for a variant), without `super::`.
    pub rust_type: String,
    /// Its doc comment, lines joined by spaces.
    pub doc: String,
}

/// A struct (its fields) or an enum (its variants), with its own doc comment.
#[derive(Debug, Clone, PartialEq)]
pub struct TypeDoc {
    /// Whether it is an enum (members are variants) rather than a struct (members are fields).
    pub is_enum: bool,
    /// The type's doc comment.
    pub doc: String,
    /// Fields or variants, in source order.
    pub members: Vec<Member>,
}

/// Every documented type of the sources, by name.
pub type Schema = BTreeMap<String, TypeDoc>;

/// One key a scenario may set, as the walk from `Scenario` finds it.
#[derive(Debug, Clone, PartialEq)]
pub struct KeyDoc {
    /// The section's dotted path (`target.random`; `target.waypoints[]` for an array of tables).
    pub section: String,
    /// The key inside its section.
    pub name: String,
    /// The field's Rust type.
    pub rust_type: String,
    /// The field's doc comment.
    pub doc: String,
    /// The variants (name and doc) when the type is an enum.
    pub variants: Vec<Member>,
}

impl KeyDoc {
    /// The dotted key, as `--set` takes it.
    pub fn dotted(&self) -> String {
        join(&self.section, &self.name)
    }
}

/// `CamelCase` as serde's `rename_all = "snake_case"` writes it.
fn snake_case(name: &str) -> String {
    let mut out = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_uppercase() && i > 0 {
            out.push('_');
        }
        out.extend(c.to_lowercase());
    }
    out
}

/// The type's last path segment (`super::TargetSection` → `TargetSection`).
fn bare_type(rust_type: &str) -> String {
    rust_type
        .rsplit("::")
        .next()
        .unwrap_or(rust_type)
        .to_string()
}

/// Adds the `pub struct` and `pub enum` items of one source file to `schema`.
pub fn parse_source(text: &str, schema: &mut Schema) {
    let mut pending: Vec<String> = Vec::new();
    let mut open: Option<(String, TypeDoc)> = None;
    // A field serde skips is not a key a file may set.
    let mut skipped = false;
    for line in text.lines() {
        let trimmed = line.trim();
        if let Some(doc) = trimmed.strip_prefix("///") {
            pending.push(doc.trim().to_string());
            continue;
        }
        if trimmed.starts_with("#[") {
            skipped |= trimmed == "#[serde(skip)]";
            continue;
        }
        let doc = pending.join(" ");
        pending.clear();
        if let Some((name, item)) = open.as_mut() {
            if line.starts_with('}') {
                schema.insert(std::mem::take(name), item.clone());
                open = None;
            } else if !std::mem::take(&mut skipped)
                && let Some(member) = parse_member(trimmed, item.is_enum, doc)
            {
                item.members.push(member);
            }
            continue;
        }
        for (prefix, is_enum) in [("pub struct ", false), ("pub enum ", true)] {
            if let Some(rest) = line.strip_prefix(prefix)
                && let Some(name) = rest.strip_suffix(" {")
            {
                let item = TypeDoc {
                    is_enum,
                    doc: doc.clone(),
                    members: Vec::new(),
                };
                open = Some((name.to_string(), item));
            }
        }
    }
}

/// A field line `pub name: Type,` or a variant line `Name,`.
fn parse_member(line: &str, is_enum: bool, doc: String) -> Option<Member> {
    if is_enum {
        let name = line.strip_suffix(',')?;
        let simple = !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric());
        return simple.then(|| Member {
            name: snake_case(name),
            rust_type: String::new(),
            doc,
        });
    }
    let (name, rust_type) = line.strip_prefix("pub ")?.split_once(": ")?;
    Some(Member {
        name: name.to_string(),
        rust_type: rust_type.trim_end_matches(',').replace("super::", ""),
        doc,
    })
}

/// Every key under the struct `type_name` at `section`, depth first in source order; an error
/// names a type the sources do not document.
pub fn keys(schema: &Schema, type_name: &str, section: &str) -> Result<Vec<KeyDoc>, String> {
    let item = schema
        .get(type_name)
        .filter(|t| !t.is_enum)
        .ok_or_else(|| format!("no documented struct {type_name} (section [{section}])"))?;
    // The section's own keys first, then its sections.
    let mut found = Vec::new();
    let mut nested = Vec::new();
    for field in &item.members {
        let path = join(section, &field.name);
        let ty = bare_type(&field.rust_type);
        let element = ty.strip_prefix("Vec<").and_then(|t| t.strip_suffix('>'));
        match (schema.get(&ty), element.and_then(|e| schema.get(e))) {
            (Some(inner), _) if !inner.is_enum => nested.extend(keys(schema, &ty, &path)?),
            (_, Some(inner)) if !inner.is_enum => {
                found.push(leaf(section, field, Vec::new()));
                let element = element.unwrap_or_default();
                nested.extend(keys(schema, element, &format!("{path}[]"))?);
            }
            (Some(variants), _) => found.push(leaf(section, field, variants.members.clone())),
            _ => found.push(leaf(section, field, Vec::new())),
        }
    }
    found.extend(nested);
    Ok(found)
}

fn join(section: &str, name: &str) -> String {
    if section.is_empty() {
        name.to_string()
    } else {
        format!("{section}.{name}")
    }
}

fn leaf(section: &str, field: &Member, variants: Vec<Member>) -> KeyDoc {
    KeyDoc {
        section: section.to_string(),
        name: field.name.clone(),
        rust_type: field.rust_type.clone(),
        doc: field.doc.clone(),
        variants,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SOURCE: &str = "
/// Top.
#[derive(Debug)]
pub struct Top {
    /// A number,
    /// ft.
    pub a_ft: f64,
    /// The inner section.
    pub inner: super::Inner,
    /// Points.
    pub points: Vec<Point>,
    /// Set by the program, not a file key.
    #[serde(skip)]
    pub hidden: u64,
}

/// Inner.
pub struct Inner {
    /// Which.
    pub kind: Kind,
}

/// One point.
pub struct Point {
    /// Where.
    pub at: [f64; 3],
}

/// Kinds.
pub enum Kind {
    /// The first.
    #[default]
    FirstOne,
    /// The second.
    Second,
}
";

    /// Fields, nested sections, arrays of tables and enum variants are found with their docs;
    /// a field serde skips is not a key.
    #[test]
    fn walks_sections_arrays_and_enums() {
        let mut schema = Schema::new();
        parse_source(SOURCE, &mut schema);
        let found = keys(&schema, "Top", "").expect("documented");
        let dotted: Vec<String> = found.iter().map(KeyDoc::dotted).collect();
        assert_eq!(dotted, ["a_ft", "points", "inner.kind", "points[].at"]);
        assert_eq!(found[0].doc, "A number, ft.");
        let variants: Vec<&str> = found[2].variants.iter().map(|v| v.name.as_str()).collect();
        assert_eq!(variants, ["first_one", "second"]);
        assert_eq!(found[2].variants[0].doc, "The first.");
        assert!(keys(&schema, "Missing", "x").is_err());
    }
}
