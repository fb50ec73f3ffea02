//! The cluster files (studies/cluster/, the Dockerfile; docs/studies.md, On a cluster) work on
//! a fresh clone. Invariants:
//! - the Slurm script logs into a folder that exists when the job is submitted (Slurm opens
//!   the log before the script runs and makes no folder);
//! - `k8s_run.sh` fills the manifests' `${STUDY}`, `${SHARDS}` and `${IMAGE}` in and nothing
//!   else; what it applies is YAML (a structural check of the subset the manifests use) with a
//!   ReadWriteMany volume claim that both Jobs mount, an Indexed Job of SHARDS completions
//!   with a retry per index, and a merge of that study and shard count;
//! - its wait ends at once when the shards' Job fails (exit 1, the failed indexes named, no
//!   merge started), and goes on to the merge when it completes;
//! - the container recipe installs the one package list (scripts/packages.txt) through
//!   scripts/setup.sh, as a workstation does (CI spells the list out, checked against it). No
//!   Docker daemon runs on the machine these tests were written on, so the image build itself
//!   is run by CI (.ci/run) only where one does.

use crate::common;

use serde_json::{Map, Value};
use std::path::Path;
use std::process::Command;

fn read(path: &str) -> String {
    std::fs::read_to_string(common::repo_root().join(path))
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn slurm_logs_into_a_folder_that_exists() {
    let script = read("studies/cluster/slurm_sweep.sh");
    let log = script
        .lines()
        .find_map(|l| l.strip_prefix("#SBATCH --output="))
        .expect("an --output directive");
    assert!(
        !log.contains('/'),
        "the log {log} goes into a folder a fresh clone may not have"
    );
}

/// A fake `kubectl` on the PATH: it logs its arguments, keeps each manifest applied from
/// standard input as `applied-N.yaml`, and answers a Job's conditions with `$FAKE_<JOB>`
/// (dashes as underscores) from its second look on (the first: no condition yet).
const FAKE_KUBECTL: &str = r#"#!/usr/bin/env bash
echo "$*" >> "$FAKE_DIR/calls"
case "$*" in
*"apply -f -"*) n=$(ls "$FAKE_DIR" | grep -c applied); cat > "$FAKE_DIR/applied-$n.yaml" ;;
*failedIndexes*) echo "1" ;;
*"get job/"*)
    job=${2#job/}; var="FAKE_${job//-/_}"
    if [ -e "$FAKE_DIR/looked-$job" ]; then echo "${!var}"; else touch "$FAKE_DIR/looked-$job"; fi ;;
esac
"#;

/// Runs `k8s_run.sh` for 3 shards of the Monte Carlo study against the fake `kubectl`, the
/// shards' Job ending `sweep_condition` and the merge's `Complete`: its exit code, standard
/// error and the manifests it applied from standard input.
fn k8s_run(fake: &Path, sweep_condition: &str) -> (Option<i32>, String, Vec<String>) {
    let kubectl = fake.join("kubectl");
    std::fs::write(&kubectl, FAKE_KUBECTL).expect("fake kubectl");
    std::fs::set_permissions(
        &kubectl,
        std::os::unix::fs::PermissionsExt::from_mode(0o755),
    )
    .expect("executable");
    let path = format!(
        "{}:{}",
        fake.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let output = Command::new("bash")
        .arg("studies/cluster/k8s_run.sh")
        .current_dir(common::repo_root())
        .env("PATH", path)
        .env("FAKE_DIR", fake)
        .env("FAKE_wingman_sweep", sweep_condition)
        .env("FAKE_wingman_merge", "Complete")
        .env("STUDY", "studies/monte_carlo.toml")
        .env("SHARDS", "3")
        .env("IMAGE", "registry.example/wingman:1")
        .env("POLL_S", "0")
        .output()
        .expect("bash runs");
    let applied = (0..)
        .map(|n| fake.join(format!("applied-{n}.yaml")))
        .take_while(|p| p.exists())
        .map(|p| std::fs::read_to_string(p).expect("manifest"))
        .collect();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    (output.status.code(), stderr, applied)
}

#[test]
fn k8s_wait_fails_fast_when_a_shard_fails() {
    let fake = tempfile::tempdir().expect("temp dir");
    let (code, stderr, applied) = k8s_run(fake.path(), "FailureTarget Failed");
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("failed indexes: 1"), "{stderr}");
    assert_eq!(applied.len(), 1, "the merge must not start: {applied:?}");
}

#[test]
fn k8s_manifests_are_parameterised_yaml() {
    let fake = tempfile::tempdir().expect("temp dir");
    let (code, stderr, applied) = k8s_run(fake.path(), "SuccessCriteriaMet Complete");
    assert_eq!(code, Some(0), "{stderr}");
    let [sweep, merge] = [&applied[0], &applied[1]].map(|text| {
        assert!(!text.contains("${"), "a parameter left unfilled:\n{text}");
        parse_yaml(text).unwrap_or_else(|e| panic!("{e}\n{text}"))
    });
    let volume = parse_yaml(&read("studies/cluster/k8s_volume.yaml")).expect("volume YAML");
    assert_eq!(volume["kind"], "PersistentVolumeClaim");
    assert!(
        volume["spec"]["accessModes"]
            .as_array()
            .is_some_and(|m| m.contains(&"ReadWriteMany".into()))
    );
    let claim = &volume["metadata"]["name"];

    let spec = &sweep["spec"];
    assert_eq!(spec["completionMode"], "Indexed");
    assert_eq!(
        (&spec["completions"], &spec["parallelism"]),
        (&3.into(), &3.into())
    );
    assert!(
        spec["backoffLimitPerIndex"]
            .as_i64()
            .is_some_and(|n| n >= 1)
    );
    for job in [&sweep, &merge] {
        let pod = &job["spec"]["template"]["spec"];
        assert_eq!(
            &pod["volumes"][0]["persistentVolumeClaim"]["claimName"],
            claim
        );
        let container = &pod["containers"][0];
        assert_eq!(container["image"], "registry.example/wingman:1");
        let env: Vec<(&Value, &Value)> = container["env"]
            .as_array()
            .expect("env")
            .iter()
            .map(|e| (&e["name"], &e["value"]))
            .collect();
        assert!(env.contains(&(&"STUDY".into(), &"studies/monte_carlo.toml".into())));
        assert!(env.contains(&(&"SHARDS".into(), &"3".into())));
        assert_eq!(container["volumeMounts"][0]["mountPath"], "/repo/runs");
    }
    let merge_command = merge["spec"]["template"]["spec"]["containers"][0]["args"][0]
        .as_str()
        .expect("merge command");
    assert!(
        merge_command.contains("wingman sweep merge"),
        "{merge_command}"
    );
}

#[test]
fn the_container_installs_the_one_package_list() {
    let listed = Command::new("sh")
        .args(["scripts/setup.sh", "--list"])
        .current_dir(common::repo_root())
        .output()
        .expect("sh runs");
    let packages: Vec<String> = String::from_utf8_lossy(&listed.stdout)
        .split_whitespace()
        .map(str::to_string)
        .collect();
    assert_eq!(packages, common::SYSTEM_PACKAGES);
    for file in [
        "Dockerfile",
        "scripts/setup.sh",
        "studies/cluster/k8s_sweep.yaml",
    ] {
        let text = read(file);
        for package in &packages {
            assert!(!text.contains(package.as_str()), "{file} copies {package}");
        }
    }
    let dockerfile = read("Dockerfile");
    let steps: Vec<&str> = dockerfile.lines().filter(|l| !l.starts_with('#')).collect();
    let has = |step: &str| steps.iter().any(|l| l.contains(step));
    assert!(
        has("COPY scripts/setup.sh scripts/packages.txt"),
        "{dockerfile}"
    );
    assert!(has("RUN sh scripts/setup.sh"), "{dockerfile}");
    assert!(
        has("cargo build --release --locked --bin wingman"),
        "{dockerfile}"
    );
    // The manifests run `wingman` from the PATH: the image links it there.
    assert!(has(
        "COPY --from=build /repo/target/release/wingman target/release/wingman"
    ));
    assert!(has(
        "ln -s /repo/target/release/wingman /usr/local/bin/wingman"
    ));
    assert!(read("studies/cluster/k8s_sweep.yaml").contains("exec wingman sweep"));
    assert!(read(".ci/run").contains("docker build --tag wingman:latest ."));
}

/// The structural check refuses what breaks a manifest: an entry indented where nothing
/// opens a block, a key twice, a tab, a line that is not `key: value`.
#[test]
fn the_yaml_check_can_fail() {
    let good = "a:\n  b: [1, \"x, y\"]\n  c:\n    - {d: 2}\n    - >-\n      e\n      f\n";
    let parsed = parse_yaml(good).expect("good");
    assert_eq!(parsed["a"]["b"], serde_json::json!([1, "x, y"]));
    assert_eq!(parsed["a"]["c"], serde_json::json!([{"d": 2}, "e f"]));
    for bad in [
        "a:\n  b: 1\n   c: 2\n",
        "a: 1\na: 2\n",
        "a:\n\tb: 1\n",
        "a:\n  just text\n",
    ] {
        assert!(parse_yaml(bad).is_err(), "{bad}");
    }
}

/// The YAML subset the manifests use, as JSON: block mappings and sequences by indentation
/// (spaces only), `>-` folded and `|` literal block scalars, flow mappings and sequences of
/// plain or quoted scalars, integers; comments on their own lines. Anything else, a duplicate
/// key or a line indented where nothing opens a block, is an error naming the line.
fn parse_yaml(text: &str) -> Result<Value, String> {
    let mut lines = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let content = line.trim_start_matches(' ');
        if content.starts_with('\t') {
            return Err(format!("line {}: a tab in the indentation", number + 1));
        }
        if !(content.is_empty() || content.starts_with('#')) {
            lines.push((line.len() - content.len(), content.trim_end().to_string()));
        }
    }
    let mut parser = Yaml { lines, next: 0 };
    let value = parser.block(0)?;
    match parser.lines.get(parser.next) {
        Some((_, line)) => Err(format!("unexpected line: {line}")),
        None => Ok(value),
    }
}

/// Lines (indentation, content) and the next one to read.
struct Yaml {
    lines: Vec<(usize, String)>,
    next: usize,
}

impl Yaml {
    fn peek(&self) -> Option<(usize, &str)> {
        self.lines.get(self.next).map(|(i, l)| (*i, l.as_str()))
    }

    fn block(&mut self, indent: usize) -> Result<Value, String> {
        match self.peek() {
            Some((i, line)) if i == indent && (line == "-" || line.starts_with("- ")) => {
                self.sequence(indent)
            }
            Some((i, _)) if i == indent => self.mapping(indent),
            other => Err(format!(
                "expected a block at indentation {indent}: {other:?}"
            )),
        }
    }

    fn sequence(&mut self, indent: usize) -> Result<Value, String> {
        let mut items = Vec::new();
        while let Some((i, line)) = self
            .peek()
            .filter(|(i, l)| *i == indent && l.starts_with("- "))
        {
            let rest = line[2..].trim_start();
            let inner = i + line.len() - rest.len();
            if key_value(rest).is_some() {
                self.lines[self.next] = (inner, rest.to_string());
                items.push(self.mapping(inner)?);
            } else {
                let rest = rest.to_string();
                self.next += 1;
                items.push(self.value(&rest, indent)?);
            }
        }
        Ok(Value::Array(items))
    }

    fn mapping(&mut self, indent: usize) -> Result<Value, String> {
        let mut map = Map::new();
        while let Some((_, line)) = self
            .peek()
            .filter(|(i, l)| *i == indent && !l.starts_with("- "))
        {
            let (key, rest) = key_value(line).ok_or_else(|| format!("not `key: value`: {line}"))?;
            let (key, rest) = (key.to_string(), rest.to_string());
            self.next += 1;
            let value = match self.peek() {
                _ if !rest.is_empty() => self.value(&rest, indent)?,
                Some((i, _)) if i > indent => self.block(i)?,
                Some((i, l)) if i == indent && l.starts_with("- ") => self.sequence(indent)?,
                _ => Value::Null,
            };
            if map.insert(key.clone(), value).is_some() {
                return Err(format!("key `{key}` twice"));
            }
        }
        match self.peek() {
            Some((i, line)) if i > indent => Err(format!("unexpected indentation: {line}")),
            _ => Ok(Value::Object(map)),
        }
    }

    /// The value written after `key:` or `-` on a line of `indent`: a block scalar takes the
    /// lines indented deeper.
    fn value(&mut self, rest: &str, indent: usize) -> Result<Value, String> {
        let join = match rest {
            ">" | ">-" => " ",
            "|" | "|-" => "\n",
            _ => return scalar(rest),
        };
        let mut parts = Vec::new();
        while let Some((_, line)) = self.peek().filter(|(i, _)| *i > indent) {
            parts.push(line.to_string());
            self.next += 1;
        }
        Ok(Value::String(parts.join(join)))
    }
}

/// `key: value` or `key:` (not a quoted or flow scalar): the key and the rest.
fn key_value(line: &str) -> Option<(&str, &str)> {
    if line.starts_with(['"', '\'', '{', '[', '>', '|']) {
        return None;
    }
    let (key, rest) = line
        .strip_suffix(':')
        .map(|k| (k, ""))
        .or_else(|| line.split_once(": "))?;
    let plain = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c));
    plain.then(|| (key, rest.trim()))
}

/// A scalar or a flow collection of scalars.
fn scalar(text: &str) -> Result<Value, String> {
    let quoted = |q: char| text.len() >= 2 && text.starts_with(q) && text.ends_with(q);
    if quoted('"') || quoted('\'') {
        return Ok(Value::String(text[1..text.len() - 1].to_string()));
    }
    if let Some(inner) = text.strip_prefix('[').and_then(|t| t.strip_suffix(']')) {
        return flow_items(inner)
            .into_iter()
            .map(scalar)
            .collect::<Result<_, _>>()
            .map(Value::Array);
    }
    if let Some(inner) = text.strip_prefix('{').and_then(|t| t.strip_suffix('}')) {
        let mut map = Map::new();
        for item in flow_items(inner) {
            let (key, value) =
                key_value(item).ok_or_else(|| format!("not `key: value`: {item}"))?;
            map.insert(key.to_string(), scalar(value)?);
        }
        return Ok(Value::Object(map));
    }
    if text.starts_with(['{', '[', '"', '\'']) || text.contains(": ") || text.contains(" #") {
        return Err(format!("not a scalar of the subset: {text}"));
    }
    Ok(text
        .parse::<i64>()
        .map_or_else(|_| Value::String(text.to_string()), Value::from))
}

/// The comma-separated items of a flow collection (commas inside quotes kept).
fn flow_items(inner: &str) -> Vec<&str> {
    let (mut items, mut start, mut quote) = (Vec::new(), 0, None);
    for (k, c) in inner.char_indices() {
        match (quote, c) {
            (None, '"' | '\'') => quote = Some(c),
            (Some(q), c) if c == q => quote = None,
            (None, ',') => {
                items.push(inner[start..k].trim());
                start = k + 1;
            }
            _ => {}
        }
    }
    items.push(inner[start..].trim());
    items.retain(|item| !item.is_empty());
    items
}
