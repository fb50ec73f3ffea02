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
    let mut files = Vec::new();
    rust_files(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        &mut files,
    );
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
