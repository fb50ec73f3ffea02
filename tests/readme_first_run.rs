//! The README is a front page a new user can follow: its first command works as
//! root (no sudo in a container) and as a user, the Rust it asks for is the `rust-version` of
//! `Cargo.toml`, its first command installs the Python package and its second, which CI
//! runs, runs pytest after the Rust tests, every link names a file of this repository (none
//! outside it), the equations, design, findings and scenario reference it points to are in
//! `docs/`, it says how to put `wingman` on the PATH, names the dissertation in full (as
//! docs/equations.md does) and the licence, whose files and `Cargo.toml` key agree.

use crate::common;

use std::path::Path;

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &str) -> String {
    std::fs::read_to_string(repo().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn first_command_needs_no_sudo_as_root() {
    let readme = read("README.md");
    let first = readme
        .lines()
        .find(|l| l.contains("cargo run --release -- run scenarios/formation.toml"))
        .expect("command 1");
    assert!(!first.trim_start().starts_with("sudo"), "{first}");
    assert!(first.contains("sh scripts/setup.sh"), "{first}");
    let setup = read("scripts/setup.sh");
    assert!(
        setup.contains("id -u") && setup.contains("as_root=\"\""),
        "root runs apt-get"
    );
    // setup.sh installs the list of scripts/packages.txt; CI (as root, with apt-get, after
    // apt-get update) installs that same list, spelled out.
    assert!(
        setup.contains("packages.txt"),
        "setup.sh installs packages.txt"
    );
    let packages = read("scripts/packages.txt");
    let listed: Vec<&str> = packages
        .lines()
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .collect();
    assert_eq!(listed, common::SYSTEM_PACKAGES);
    let ci = read(".ci/run");
    let update = ci.find("apt-get update").expect("CI runs apt-get update");
    let install = ci
        .lines()
        .find(|l| l.starts_with("apt-get install"))
        .expect("CI installs with apt-get");
    assert!(ci.find(install).unwrap() > update, "apt-get update first");
    let installed: Vec<&str> = install
        .split_whitespace()
        .filter(|w| !w.starts_with('-') && !["apt-get", "install"].contains(w))
        .collect();
    assert_eq!(installed, listed, "CI installs packages.txt's list");
}

/// Command 1 installs the Python package too; command 2, the one CI runs, runs the Rust tests
/// and the Python package's (pytest).
#[test]
fn commands_install_and_test_the_python_package() {
    let readme = read("README.md");
    let first = readme
        .lines()
        .find(|l| l.contains("cargo run --release -- run scenarios/formation.toml"))
        .expect("command 1");
    assert!(first.contains("sh scripts/install_python.sh"), "{first}");
    let install = read("scripts/install_python.sh");
    assert!(install.contains("python3 -m venv .venv") && install.contains("./python"));
    assert!(
        readme.contains("\nsh scripts/test.sh\n"),
        "command 2 is scripts/test.sh"
    );
    let test = read("scripts/test.sh");
    assert!(
        test.contains("\ncargo test --release\n"),
        "test.sh runs the Rust tests"
    );
    assert!(
        test.contains("-m pytest -q python/tests"),
        "test.sh runs pytest"
    );
    assert!(
        read(".ci/run").contains("\nsh scripts/test.sh\n"),
        "CI runs command 2"
    );
}

#[test]
fn rust_version_is_the_one_the_readme_asks_for() {
    let manifest: toml::Table = read("Cargo.toml").parse().expect("Cargo.toml");
    let version = manifest["package"]["rust-version"]
        .as_str()
        .expect("rust-version set");
    let readme = read("README.md");
    assert!(
        readme.contains(&format!("Rust {version} or newer")),
        "README asks for another Rust"
    );
}

#[test]
fn links_stay_inside_the_repository() {
    for doc in [
        "README.md",
        "docs/equations.md",
        "docs/design.md",
        "docs/findings.md",
        "docs/outputs.md",
        "docs/scenario_reference.md",
    ] {
        let text = read(doc);
        assert!(
            !text.contains(concat!("..", "/shared")),
            "{doc} points outside the repository"
        );
        let base = repo().join(doc).parent().expect("folder").to_path_buf();
        for link in text.split("](").skip(1) {
            let target = link.split(')').next().unwrap_or("");
            let file = target.split('#').next().unwrap_or("");
            if file.is_empty() || file.starts_with("http") {
                continue;
            }
            assert!(
                base.join(file).exists(),
                "{doc}: link to {file} names no file"
            );
        }
    }
    let readme = read("README.md");
    for doc in [
        "docs/equations.md",
        "docs/design.md",
        "docs/findings.md",
        "docs/outputs.md",
        "docs/scenario_reference.md",
    ] {
        assert!(readme.contains(doc), "README does not point to {doc}");
    }
    assert!(
        readme.lines().count() < 150,
        "the front page grew into a notebook"
    );
}

/// The dissertation: title, author, institution and year.
const DISSERTATION: [&str; 4] = [
    "Vision Based Guidance and Flight Control in Problems of Aerial Tracking",
    "Vahram Stepanyan",
    "Virginia Polytechnic Institute and State University",
    "2006",
];

#[test]
fn the_dissertation_is_cited_in_full() {
    for doc in ["README.md", "docs/equations.md"] {
        // Line breaks inside the citation are spaces.
        let text = read(doc).split_whitespace().collect::<Vec<_>>().join(" ");
        for part in DISSERTATION {
            assert!(text.contains(part), "{doc} does not name {part:?}");
        }
    }
}

#[test]
fn readme_says_how_to_install_on_the_path() {
    let readme = read("README.md");
    assert!(
        readme.contains("`cargo install --path .`"),
        "no install command"
    );
    assert!(
        readme.contains("`target/release/wingman`"),
        "README does not say what `wingman` stands for"
    );
}

#[test]
fn licence_is_mit_or_apache() {
    let manifest: toml::Table = read("Cargo.toml").parse().expect("Cargo.toml");
    assert_eq!(
        manifest["package"]["license"].as_str(),
        Some("MIT OR Apache-2.0")
    );
    assert!(read("LICENSE-MIT").contains("Permission is hereby granted, free of charge"));
    assert!(
        read("LICENSE-APACHE").contains("Apache License\n                           Version 2.0")
    );
    for file in ["LICENSE-MIT", "LICENSE-APACHE"] {
        assert!(
            read(file).contains("the wingman developers"),
            "{file}: no copyright line"
        );
        assert!(
            read("README.md").contains(file),
            "README does not name {file}"
        );
    }
}
