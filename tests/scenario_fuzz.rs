//! Malformed scenarios never hurt: mutations of the shipped scenarios (wrong
//! types, out-of-range, NaN, infinite and huge values, wrong array lengths, missing, unknown
//! and duplicate keys, truncation, garbage, bad `--set` arguments and bad mesh files) go
//! through the loader, the pre-run checks and the set-up of the simulation without a panic;
//! every rejection is one line under 200 characters that says where (the file with the line
//! and column or the key, or the `--set` argument), names no Rust type, and, for a value, what
//! is allowed. A handful of rejections go through the binary too: exit code 2, nothing
//! written. CI runs a fixed-seed set of 400; `cargo test --release -- --ignored` runs 2,000.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};
use std::process::Command;
use wingman::output::preflight;
use wingman::scenario::{Scenario, ScenarioError, SensorMode};
use wingman::sim::Simulation;

/// One malformed case: the scenario text and the `--set` arguments.
struct Case {
    text: String,
    overrides: Vec<String>,
    what: &'static str,
}

/// Values that are wrong somewhere: wrong types, non-finite, huge, tiny, negative.
const BAD_VALUES: &[&str] = &[
    "\"text\"",
    "true",
    "[1.0, 2.0]",
    "{ a = 1 }",
    "nan",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "1e-320",
    "0",
    "-1",
    "18446744073709551616",
    "99999999999",
    "[]",
    "[1, 2, 3, 4]",
    "1979-05-27",
    "\"\"",
    "[\"a\", \"b\", \"c\"]",
    "2.5",
];

/// The shipped scenarios' texts.
fn shipped() -> Vec<(String, String)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("scenarios/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| {
            let name = p.file_name().expect("name").to_string_lossy().into_owned();
            (name, std::fs::read_to_string(p).expect("scenario text"))
        })
        .collect()
}

/// Lines of the form `key = value` (not comments, not section headers).
fn value_lines(text: &str) -> Vec<usize> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| {
            let l = l.trim_start();
            !l.starts_with('#') && !l.starts_with('[') && l.contains('=')
        })
        .map(|(i, _)| i)
        .collect()
}

/// `text` with line `i` replaced by `line` (or removed when None, or doubled).
fn with_line(text: &str, i: usize, line: Option<String>) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    match line {
        Some(l) => lines[i] = l,
        None => {
            lines.remove(i);
        }
    }
    lines.join("\n") + "\n"
}

/// The key of a `key = value` line.
fn key_of(line: &str) -> String {
    line.split('=').next().unwrap_or("").trim().to_string()
}

/// A malformed mesh file for `camera.mesh` (written into `dir`), or a path that is bad.
fn bad_mesh(rng: &mut ChaCha8Rng, dir: &Path, n: usize) -> String {
    let contents = [
        "",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
        "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "v 0 0 0\nf 1 2 9\n",
        "garbage \u{0}\u{1} not an obj",
        "v 1e39 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n",
    ];
    match rng.random_range(0..contents.len() + 3) {
        k if k < contents.len() => {
            let path = dir.join(format!("mesh{n}.obj"));
            std::fs::write(&path, contents[k]).expect("mesh file");
            path.display().to_string()
        }
        k if k == contents.len() => "/dev/zero".to_string(),
        k if k == contents.len() + 1 => dir.display().to_string(),
        _ => "no/such/mesh.obj".to_string(),
    }
}

/// One mutation of `text`.
fn mutate(rng: &mut ChaCha8Rng, text: &str, dir: &Path, n: usize) -> Case {
    let lines = value_lines(text);
    let pick = |rng: &mut ChaCha8Rng| lines[rng.random_range(0..lines.len())];
    let all: Vec<&str> = text.lines().collect();
    let case = |text: String, what| Case {
        text,
        overrides: vec![],
        what,
    };
    match rng.random_range(0..9) {
        0 => {
            let i = pick(rng);
            let value = BAD_VALUES[rng.random_range(0..BAD_VALUES.len())];
            case(
                with_line(text, i, Some(format!("{} = {value}", key_of(all[i])))),
                "bad value",
            )
        }
        1 => case(with_line(text, pick(rng), None), "missing key"),
        2 => {
            let i = pick(rng);
            case(
                with_line(text, i, Some(format!("{}\n{}", all[i], all[i]))),
                "duplicate key",
            )
        }
        3 => {
            let mut cut = rng.random_range(0..text.len());
            while !text.is_char_boundary(cut) {
                cut -= 1;
            }
            case(text[..cut].to_string(), "truncation")
        }
        4 => {
            let garbage: String = (0..rng.random_range(1..12))
                .map(|_| char::from(rng.random_range(b' '..=b'~')))
                .collect();
            let i = pick(rng);
            case(
                with_line(text, i, Some(format!("{}{garbage}", all[i]))),
                "garbage",
            )
        }
        5 => case(
            with_line(text, pick(rng), Some("bogus_key = 1".into())),
            "unknown key",
        ),
        6 => {
            let mesh = bad_mesh(rng, dir, n);
            Case {
                text: text.to_string(),
                overrides: vec![
                    "sensor.mode=camera".into(),
                    "camera.rate_hz=25".into(),
                    format!("camera.mesh=\"{mesh}\""),
                ],
                what: "bad mesh",
            }
        }
        7 => {
            let i = pick(rng);
            let value = BAD_VALUES[rng.random_range(0..BAD_VALUES.len())];
            let section = section_of(&all, i);
            Case {
                text: text.to_string(),
                overrides: vec![format!("{section}{}={value}", key_of(all[i]))],
                what: "bad --set",
            }
        }
        _ => {
            let forms = ["nodot=1", "=", "run.=1", ".x=1", "run.dt_s", "run.seed.x=1"];
            Case {
                text: text.to_string(),
                overrides: vec![forms[rng.random_range(0..forms.len())].to_string()],
                what: "malformed --set",
            }
        }
    }
}

/// The dotted section (`camera.gimbal.`) line `i` is in.
fn section_of(lines: &[&str], i: usize) -> String {
    lines[..i]
        .iter()
        .rev()
        .find_map(|l| {
            let l = l.trim();
            (l.starts_with('[') && l.ends_with(']'))
                .then(|| format!("{}.", l.trim_matches(['[', ']'])))
        })
        .unwrap_or_default()
}

/// What a rejection must say: one line under 200 characters, where the value came from, no
/// Rust type names, and what is allowed when it names a value.
fn check_message(case: &Case, error: &ScenarioError, file: &str) {
    let message = error.to_string();
    let context = format!(
        "{}: {:?} --set {:?}: {message}",
        case.what,
        case.text.len(),
        case.overrides
    );
    assert!(!message.contains('\n'), "{context}");
    assert!(message.chars().count() < 200, "{context}");
    assert!(
        message.contains(file) || message.starts_with("--set "),
        "no origin: {context}"
    );
    // The file's temporary folder may hold "u8" or "f64" in its random name.
    let without_file = message.replace(file, "scenario.toml");
    for rust_name in ["f64", "u32", "u64", "u8", "usize", "struct ", "Option<"] {
        assert!(
            !without_file.contains(rust_name),
            "Rust name {rust_name}: {context}"
        );
    }
    if let ScenarioError::Rejected {
        key: Some(key),
        message: text,
        ..
    } = error
    {
        assert!(
            text.contains(key.split('[').next().unwrap_or(key)),
            "key: {context}"
        );
        if text.contains(" = ") && text.contains(" is invalid") {
            assert!(text.contains("allowed"), "no allowed range: {context}");
        }
    }
}

/// Loads, checks and sets up one case; returns the rejection, if any. Panics fail the test.
fn try_case(case: &Case, path: &Path) -> Option<ScenarioError> {
    std::fs::write(path, &case.text).expect("scenario file");
    let (scenario, source) = match Scenario::load_with_source(path, &case.overrides) {
        Ok(loaded) => loaded,
        Err(e) => return Some(e),
    };
    if let Err(e) = preflight::check(&scenario, &source) {
        return Some(e);
    }
    // Camera set-ups render a first frame: the mesh and resources were checked above.
    if scenario.sensor.mode != SensorMode::Camera
        && let Err(e) = Simulation::new(&scenario)
    {
        let setup = wingman::output::RunError::Setup(Box::new(e));
        assert!(
            setup.is_input_error(),
            "{}: set-up error not an input error: {setup}",
            case.what
        );
    }
    None
}

/// Runs `count` cases from `seed`; returns the rejections' (text, overrides) for the binary.
fn fuzz(seed: u64, count: usize) -> Vec<Case> {
    let bases = shipped();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("case.toml");
    let mut rejected = Vec::new();
    for n in 0..count {
        let (_, text) = &bases[rng.random_range(0..bases.len())];
        let case = mutate(&mut rng, text, dir.path(), n);
        let outcome =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| try_case(&case, &path)));
        match outcome {
            Ok(Some(error)) => {
                check_message(&case, &error, "case.toml");
                rejected.push(case);
            }
            Ok(None) => {}
            Err(_) => panic!(
                "case {n} ({}) panicked; overrides {:?}",
                case.what, case.overrides
            ),
        }
    }
    assert!(
        rejected.len() > count / 2,
        "only {} of {count} rejected",
        rejected.len()
    );
    rejected
}

/// Rejections through the binary: exit code 2, one line, no outputs.
fn through_binary(cases: &[Case]) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("case.toml");
    for case in cases {
        std::fs::write(&path, &case.text).expect("scenario");
        let out = dir.path().join("out");
        let mut command = Command::new(env!("CARGO_BIN_EXE_wingman"));
        command
            .args(["run", "--quiet", "--out"])
            .arg(&out)
            .arg(&path);
        for set in &case.overrides {
            command.args(["--set", set]);
        }
        let output = command
            .env("NODEVICE_SELECT", "1")
            .output()
            .expect("binary runs");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{}: {stderr}", case.what);
        assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
        assert!(!out.exists(), "outputs written: {stderr}");
    }
}

#[test]
fn malformed_scenarios_are_rejected_cleanly() {
    let rejected = fuzz(12, 400);
    through_binary(&rejected[..12]);
}

#[test]
#[ignore = "2,000 cases: cargo test --release --test behaviour scenario_fuzz:: -- --ignored"]
fn two_thousand_malformed_scenarios() {
    fuzz(2026, 2000);
}
