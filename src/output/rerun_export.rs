//! `wingman export rerun RUN_DIR --out FILE.rrd`: a finished run folder as a Rerun recording.
//! The Python package writes it (`python -m wingman.rerun`, with the pinned `rerun-sdk`);
//! this finds a Python that has both and runs it (docs/viewer.md, A Rerun recording, says
//! why the recording is not written from Rust).

use std::path::{Path, PathBuf};
use std::process::Command;

/// Why the recording was not written.
#[derive(Debug, thiserror::Error)]
pub enum RerunExportError {
    /// The folder or the output file named is not usable (a bad argument).
    #[error("{0}")]
    BadArgument(String),
    /// No Python with the package `wingman` and `rerun-sdk` was found.
    #[error(
        "`wingman export rerun` writes the recording with the Python package wingman and rerun-sdk, which {} cannot import ({said}): run `sh scripts/install_python.sh` in the clone (it installs both into .venv), or set WINGMAN_PYTHON to a Python that has them",
        python.display()
    )]
    NotInstalled {
        /// The interpreter tried.
        python: PathBuf,
        /// What it said (its last line of error output).
        said: String,
    },
    /// The Python module failed; it printed why.
    #[error("python -m wingman.rerun failed ({0})")]
    Failed(std::process::ExitStatus),
}

impl RerunExportError {
    /// Whether the command line's argument is to blame (exit code 2).
    pub fn is_bad_input(&self) -> bool {
        match self {
            Self::BadArgument(_) => true,
            Self::Failed(status) => status.code() == Some(2),
            Self::NotInstalled { .. } => false,
        }
    }
}

/// The Python to run: `$WINGMAN_PYTHON`, else the virtual environment `.venv` of the clone
/// this program was built from (where `scripts/install_python.sh` puts the package) when it
/// exists, else `python3` on the PATH.
pub fn python_interpreter() -> PathBuf {
    if let Some(python) = std::env::var_os("WINGMAN_PYTHON").filter(|p| !p.is_empty()) {
        return PathBuf::from(python);
    }
    let venv = Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv/bin/python");
    if venv.is_file() {
        venv
    } else {
        PathBuf::from("python3")
    }
}

/// Checks the arguments: a run folder (its `scenario.toml` and `telemetry.csv`) and an
/// `.rrd` file that is not a folder.
fn check_arguments(run_dir: &Path, out: &Path) -> Result<(), RerunExportError> {
    for name in ["scenario.toml", "telemetry.csv"] {
        if !run_dir.join(name).is_file() {
            return Err(RerunExportError::BadArgument(format!(
                "{}: not a run folder (no {name})",
                run_dir.display()
            )));
        }
    }
    if out.is_dir() || out.extension().is_none_or(|e| e != "rrd") {
        return Err(RerunExportError::BadArgument(format!(
            "--out {}: name a .rrd file",
            out.display()
        )));
    }
    Ok(())
}

/// Writes `run_dir` as the recording `out`, through `python -m wingman.rerun` (its output
/// goes to this program's).
pub fn export_rerun(run_dir: &Path, out: &Path) -> Result<(), RerunExportError> {
    check_arguments(run_dir, out)?;
    let python = python_interpreter();
    let probe = Command::new(&python)
        .args(["-c", "import wingman.rerun"])
        .output();
    let said = match probe {
        Ok(o) if o.status.success() => None,
        Ok(o) => Some(last_line(&String::from_utf8_lossy(&o.stderr))),
        Err(e) => Some(e.to_string()),
    };
    if let Some(said) = said {
        return Err(RerunExportError::NotInstalled { python, said });
    }
    let status = Command::new(&python)
        .args(["-m", "wingman.rerun"])
        .arg(run_dir)
        .arg(out)
        .status()
        .map_err(|e| RerunExportError::NotInstalled {
            python: python.clone(),
            said: e.to_string(),
        })?;
    if status.success() {
        Ok(())
    } else {
        Err(RerunExportError::Failed(status))
    }
}

/// The last non-empty line of a program's error output (a Python traceback's verdict).
fn last_line(text: &str) -> String {
    text.lines()
        .rev()
        .find(|l| !l.trim().is_empty())
        .unwrap_or("no output")
        .trim()
        .to_string()
}
