//! House rule: no function in `src/` is longer than 80 lines (from its `fn` line to its closing
//! brace), so that each reads on one screen. The scan blanks out comments, string and char
//! literals before matching braces.

use std::path::{Path, PathBuf};

const MAX_FUNCTION_LINES: usize = 80;

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable source folder") {
        let path = entry.expect("readable entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The source with comments and string, raw-string and char literals replaced by spaces
/// (newlines kept, so line numbers stay).
fn blank_comments_and_literals(src: &str) -> Vec<u8> {
    let s = src.as_bytes();
    let mut out = s.to_vec();
    let blank = |out: &mut Vec<u8>, from: usize, to: usize| {
        for b in &mut out[from..to.min(s.len())] {
            if *b != b'\n' {
                *b = b' ';
            }
        }
    };
    let mut i = 0;
    while i < s.len() {
        let rest = &s[i..];
        let end = if rest.starts_with(b"//") {
            i + rest.iter().position(|b| *b == b'\n').unwrap_or(rest.len())
        } else if rest.starts_with(b"/*") {
            i + 2 + find(&rest[2..], b"*/").map_or(rest.len(), |p| p + 2)
        } else if let Some(hashes) = raw_string_start(s, i) {
            let close: Vec<u8> = std::iter::once(b'"')
                .chain(std::iter::repeat_n(b'#', hashes))
                .collect();
            let open = 2 + hashes;
            i + open + find(&rest[open..], &close).map_or(rest.len(), |p| p + close.len())
        } else if rest[0] == b'"' {
            let mut j = 1;
            while j < rest.len() && rest[j] != b'"' {
                j += if rest[j] == b'\\' { 2 } else { 1 };
            }
            i + j + 1
        } else if let Some(len) = char_literal_len(rest) {
            i + len
        } else {
            i += 1;
            continue;
        };
        blank(&mut out, i, end);
        i = end;
    }
    out
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}

/// `r"`, `r#"`, ... at `i` (not inside an identifier): the number of `#`.
fn raw_string_start(s: &[u8], i: usize) -> Option<usize> {
    if s[i] != b'r' || (i > 0 && (s[i - 1].is_ascii_alphanumeric() || s[i - 1] == b'_')) {
        return None;
    }
    let hashes = s[i + 1..].iter().take_while(|b| **b == b'#').count();
    (s.get(i + 1 + hashes) == Some(&b'"')).then_some(hashes)
}

/// The length of a char literal at the start of `rest` ('a', '\n', '\u{..}'), not a lifetime.
fn char_literal_len(rest: &[u8]) -> Option<usize> {
    if rest[0] != b'\'' {
        return None;
    }
    if rest.get(1) == Some(&b'\\') {
        let close = rest[2..].iter().position(|b| *b == b'\'')?;
        return Some(close + 3);
    }
    // One UTF-8 character, its length from its first byte, then the closing quote.
    let len = match rest.get(1)? {
        b if *b < 0x80 => 1,
        b if *b >= 0xf0 => 4,
        b if *b >= 0xe0 => 3,
        _ => 2,
    };
    (rest.get(1 + len) == Some(&b'\'')).then_some(len + 2)
}

/// (name, first line, length in lines) of every function with a body.
fn functions(src: &[u8]) -> Vec<(String, usize, usize)> {
    let line_of = |at: usize| src[..at].iter().filter(|b| **b == b'\n').count() + 1;
    let mut found = Vec::new();
    let mut i = 0;
    while let Some(p) = find(&src[i..], b"fn ") {
        let at = i + p;
        i = at + 3;
        if at > 0 && (src[at - 1].is_ascii_alphanumeric() || src[at - 1] == b'_') {
            continue;
        }
        let name: String = src[i..]
            .iter()
            .take_while(|b| b.is_ascii_alphanumeric() || **b == b'_')
            .map(|b| *b as char)
            .collect();
        // The body opens at the first `{` outside parentheses and brackets; a `;` first means
        // a declaration without a body.
        let (mut depth, mut j) = (0i32, i);
        while j < src.len() && !(depth == 0 && (src[j] == b'{' || src[j] == b';')) {
            match src[j] {
                b'(' | b'[' => depth += 1,
                b')' | b']' => depth -= 1,
                _ => {}
            }
            j += 1;
        }
        if j >= src.len() || src[j] == b';' {
            continue;
        }
        let mut braces = 0;
        let mut end = j;
        for (k, b) in src[j..].iter().enumerate() {
            match b {
                b'{' => braces += 1,
                b'}' => braces -= 1,
                _ => {}
            }
            if braces == 0 {
                end = j + k;
                break;
            }
        }
        found.push((name, line_of(at), line_of(end) - line_of(at) + 1));
    }
    found
}

#[test]
fn no_function_in_src_is_longer_than_80_lines() {
    let files = source_files();
    assert!(
        files.len() > 50,
        "the scan found too few files: {}",
        files.len()
    );
    let mut long = Vec::new();
    let mut counted = 0;
    for file in &files {
        let src = std::fs::read_to_string(file).expect("readable source");
        for (name, line, len) in functions(&blank_comments_and_literals(&src)) {
            counted += 1;
            if len > MAX_FUNCTION_LINES {
                long.push(format!("{}:{line} {name} ({len} lines)", file.display()));
            }
        }
    }
    assert!(counted > 500, "the scan found too few functions: {counted}");
    assert!(
        long.is_empty(),
        "functions over {MAX_FUNCTION_LINES} lines:\n{}",
        long.join("\n")
    );
}

/// The scanner itself: comments, strings and chars with braces do not count, a declaration
/// without a body is skipped, and a function's length runs from `fn` to its closing brace.
#[test]
fn scanner_measures_functions() {
    let src = r##"
fn a() {
    let s = "}}{";
    let c = '}';
    // }
    let r = r#"}"#;
}
trait T { fn b(&self); }
fn c(x: [u8; 2]) -> u8 { x[0] }
"##;
    let found = functions(&blank_comments_and_literals(src));
    assert_eq!(
        found,
        vec![("a".to_string(), 2, 6), ("c".to_string(), 9, 1)]
    );
}

const MAX_FILE_LINES: usize = 800;

/// Every `.rs` file under `src/` and the Python package's `python/src/`.
fn source_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    rust_files(&repo().join("src"), &mut files);
    rust_files(&repo().join("python").join("src"), &mut files);
    files.sort();
    files
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// House rule: no source file is over 800 lines; a longer one holds more than one concept.
#[test]
fn no_file_in_src_is_longer_than_800_lines() {
    let long: Vec<String> = source_files()
        .iter()
        .filter_map(|file| {
            let lines = std::fs::read_to_string(file)
                .expect("readable")
                .lines()
                .count();
            (lines > MAX_FILE_LINES).then(|| format!("{} ({lines} lines)", file.display()))
        })
        .collect();
    assert!(
        long.is_empty(),
        "files over {MAX_FILE_LINES} lines:\n{}",
        long.join("\n")
    );
}

/// What the repository ships as text for its users to read: its sources, tests, scenarios,
/// studies, scripts, shaders and documents.
fn shipped_text_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut stack: Vec<PathBuf> = [
        "src",
        "tests",
        "benches",
        "examples",
        "scenarios",
        "studies",
        "scripts",
        "shaders",
        "docs",
        ".ci",
        "assets",
        "python",
    ]
    .iter()
    .map(|d| repo().join(d))
    .collect();
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("readable folder") {
            let path = entry.expect("readable entry").path();
            let text_like = path.extension().is_some_and(|e| {
                ["rs", "toml", "md", "sh", "wgsl", "yaml", "py", "obj"]
                    .contains(&e.to_str().unwrap_or(""))
            });
            let generated = path
                .file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with('.') || n == "__pycache__");
            if path.is_dir() && !generated {
                stack.push(path);
            } else if text_like || path.file_name().is_some_and(|n| n == "run") {
                files.push(path);
            }
        }
    }
    files.push(repo().join("README.md"));
    files
}

/// The documents a citation may not name: they are not in the repository, so a user cannot
/// read them (the model is `docs/equations.md`, the program `docs/design.md`).
const ABSENT_DOCUMENTS: [&str; 5] = ["SPEC §", "SPEC.md", "DESIGN §", "DESIGN.md", "../shared"];

/// The place of a citation of an issue in `text` ("issue 12", "issues 5, 10", "Issue #3",
/// also with the number on the next line after a comment marker): its 0-based line.
fn issue_citations(text: &str) -> Vec<usize> {
    // The text as one line per file, comment markers dropped, with each word's line kept.
    let mut words: Vec<(String, usize)> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let body = line.trim_start().trim_start_matches(['/', '!', '#', '*']);
        words.extend(body.split_whitespace().map(|w| (w.to_lowercase(), i)));
    }
    let mut found = Vec::new();
    for pair in words.windows(2) {
        let (word, next) = (&pair[0].0, pair[1].0.trim_start_matches('#'));
        let word = word.trim_start_matches(|c: char| !c.is_alphanumeric());
        let cites =
            (word == "issue" || word == "issues") && next.starts_with(|c: char| c.is_ascii_digit());
        if cites {
            found.push(pair[0].1);
        }
    }
    found
}

#[test]
fn no_shipped_file_cites_a_document_outside_the_repository() {
    let this_file = repo().join("tests").join("code_health.rs");
    let mut found = Vec::new();
    for file in shipped_text_files().iter().filter(|f| **f != this_file) {
        let text = std::fs::read_to_string(file).expect("readable");
        for (i, line) in text.lines().enumerate() {
            if let Some(name) = ABSENT_DOCUMENTS.iter().find(|d| line.contains(*d)) {
                found.push(format!("{}:{}: cites {name}", file.display(), i + 1));
            }
        }
        for i in issue_citations(&text) {
            found.push(format!("{}:{}: cites an issue", file.display(), i + 1));
        }
    }
    assert!(
        found.is_empty(),
        "citations of absent documents (cite docs/*.md headings or the seed's equation \
         numbers instead):\n{}",
        found.join("\n")
    );
}

/// The issue matcher finds a number after "issue" on its line or the next, and nothing else.
#[test]
fn issue_citations_are_found() {
    assert_eq!(issue_citations("//! works (issue 12): yes"), [0]);
    assert_eq!(issue_citations("a\n/// Issues 5, 10"), [1]);
    assert_eq!(issue_citations("# see (issue\n# #13)"), [0]);
    assert!(issue_citations("an issue with 3 frames; tissue 4; issue bounds").is_empty());
}

/// The source with everything from its first `#[cfg(test)]` on removed: the unit tests at a
/// file's end may import what the module itself must not.
fn without_tests(src: &[u8]) -> &[u8] {
    find(src, b"#[cfg(test)]").map_or(src, |at| &src[..at])
}

/// The module names `text` reaches by the path prefix `prefix` (`crate::`, `super::`), as
/// written in code (comments and literals blanked).
fn reached(text: &[u8], prefix: &[u8]) -> Vec<String> {
    let mut names = Vec::new();
    let mut i = 0;
    while let Some(p) = find(&text[i..], prefix) {
        let at = i + p;
        i = at + prefix.len();
        if at > 0 && (text[at - 1].is_ascii_alphanumeric() || text[at - 1] == b'_') {
            continue;
        }
        let name: String = text[i..]
            .iter()
            .take_while(|b| b.is_ascii_alphanumeric() || **b == b'_')
            .map(|b| *b as char)
            .collect();
        if !name.is_empty() {
            names.push(name);
        }
    }
    names
}

/// A cycle in the graph `edges` (node to the nodes it imports), as the path around it.
fn cycle(
    edges: &std::collections::BTreeMap<String, std::collections::BTreeSet<String>>,
) -> Option<Vec<String>> {
    fn visit(
        node: &str,
        edges: &std::collections::BTreeMap<String, std::collections::BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut std::collections::BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(start) = path.iter().position(|n| n == node) {
            let mut around = path[start..].to_vec();
            around.push(node.to_string());
            return Some(around);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node.to_string());
        for next in edges.get(node).into_iter().flatten() {
            if let Some(found) = visit(next, edges, path, done) {
                return Some(found);
            }
        }
        path.pop();
        done.insert(node.to_string());
        None
    }
    let mut done = std::collections::BTreeSet::new();
    edges
        .keys()
        .find_map(|node| visit(node, edges, &mut Vec::new(), &mut done))
}

/// The top-level modules in the order `src/lib.rs` lists them ("each imports only those before
/// it").
fn module_order() -> Vec<String> {
    let lib = std::fs::read_to_string(repo().join("src").join("lib.rs")).expect("lib.rs");
    let from = lib
        .find("Modules, in the order")
        .expect("lib.rs lists the module order");
    let list = &lib[from..];
    let list = &list[..list.find("\n//!\n").unwrap_or(list.len())];
    list.split("[`")
        .skip(1)
        .filter_map(|s| s.split('`').next())
        .map(str::to_string)
        .collect()
}

/// The files of a top-level module: `src/NAME.rs` or everything under `src/NAME/`.
fn module_files(name: &str) -> Vec<PathBuf> {
    let dir = repo().join("src").join(name);
    let mut files = Vec::new();
    if dir.is_dir() {
        rust_files(&dir, &mut files);
    } else {
        files.push(repo().join("src").join(format!("{name}.rs")));
    }
    files
}

fn code_of(file: &Path) -> Vec<u8> {
    let src = std::fs::read_to_string(file).expect("readable source");
    without_tests(&blank_comments_and_literals(&src)).to_vec()
}

/// Each top-level module imports only the modules `src/lib.rs` lists before it (so the
/// modules form no cycle).
#[test]
fn modules_import_only_those_before_them() {
    let order = module_order();
    assert!(order.len() > 10, "module order not found: {order:?}");
    let mut late = Vec::new();
    for (i, module) in order.iter().enumerate() {
        for file in module_files(module) {
            for used in reached(&code_of(&file), b"crate::") {
                if order[i + 1..].contains(&used) {
                    late.push(format!("{} uses {used}", file.display()));
                }
            }
        }
    }
    late.sort();
    late.dedup();
    assert!(
        late.is_empty(),
        "imports of later modules:\n{}",
        late.join("\n")
    );
}

/// Inside each module with submodules, the submodules import one another without a cycle.
#[test]
fn submodules_form_no_cycle() {
    use std::collections::{BTreeMap, BTreeSet};
    let mut checked = 0;
    for module in module_order() {
        let dir = repo().join("src").join(&module);
        if !dir.is_dir() {
            continue;
        }
        let siblings: BTreeSet<String> = std::fs::read_dir(&dir)
            .expect("readable")
            .map(|e| e.expect("entry").path())
            .filter_map(|p| Some(p.file_stem()?.to_str()?.to_string()))
            .filter(|n| n != "mod")
            .collect();
        let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for name in &siblings {
            let mut files = Vec::new();
            let sub = dir.join(name);
            if sub.is_dir() {
                rust_files(&sub, &mut files);
            } else {
                files.push(dir.join(format!("{name}.rs")));
            }
            let own_prefix = format!("crate::{module}::");
            for file in files {
                let code = code_of(&file);
                let used = reached(&code, b"super::")
                    .into_iter()
                    .chain(reached(&code, own_prefix.as_bytes()));
                let entry = edges.entry(name.clone()).or_default();
                entry.extend(used.filter(|u| u != name && siblings.contains(u)));
            }
        }
        checked += 1;
        assert_eq!(
            cycle(&edges),
            None,
            "an import cycle inside {module}: {edges:?}"
        );
    }
    assert!(checked > 8, "too few modules with submodules: {checked}");
}

/// The cycle finder itself.
#[test]
fn cycle_finder_finds_cycles() {
    use std::collections::{BTreeMap, BTreeSet};
    let graph = |pairs: &[(&str, &str)]| {
        let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (a, b) in pairs {
            edges
                .entry(a.to_string())
                .or_default()
                .insert(b.to_string());
        }
        edges
    };
    assert_eq!(cycle(&graph(&[("a", "b"), ("b", "c"), ("a", "c")])), None);
    let around = cycle(&graph(&[("a", "b"), ("b", "c"), ("c", "a")])).expect("a cycle");
    assert_eq!(around.len(), 4, "{around:?}");
}

/// The behaviour tests are one test binary (Cargo.toml's `autotests = false`): a file in
/// tests/ that tests/main.rs does not name as a module would never be built or run.
#[test]
fn every_test_file_is_a_module_of_the_test_binary() {
    let tests = repo().join("tests");
    let main = std::fs::read_to_string(tests.join("main.rs")).expect("tests/main.rs");
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(&tests).expect("tests/") {
        let path = entry.expect("entry").path();
        let name = match path.extension() {
            Some(ext) if ext == "rs" => path.file_stem(),
            None if path.join("mod.rs").is_file() => path.file_name(),
            _ => None,
        };
        let Some(name) = name.and_then(|n| n.to_str()) else {
            continue;
        };
        if name != "main" && !main.contains(&format!("\nmod {name};\n")) {
            missing.push(name.to_string());
        }
    }
    assert!(missing.is_empty(), "not in tests/main.rs: {missing:?}");
}
