//! The output folder of a run: a new or empty folder, or the folder of an earlier run (known
//! by its marker, written before anything else, or by its own `summary.json`), whose files
//! are cleared first so that two runs never mix. The marker makes the folder of a run that
//! was killed (SIGKILL, a full disk) before it wrote its summary reusable too.
//! Any other folder with files in it is refused: a run does not write among files it did not
//! write.

use std::path::{Path, PathBuf};

/// The marker a run writes into its folder before anything else.
pub const MARKER: &str = ".wingman-run";
/// The files a run writes at the top of its folder.
const RUN_FILES: [&str; 5] = [
    MARKER,
    "scenario.toml",
    "telemetry.csv",
    "summary.json",
    "summary.json.partial",
];
/// The folders a run writes its images into.
const RUN_FOLDERS: [&str; 2] = ["frames", "plots"];

/// Why an output folder cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum FolderError {
    /// The path names a file.
    #[error("--out {}: is a file, not a folder", .0.display())]
    NotAFolder(PathBuf),
    /// A folder with files in it that are not an earlier run's.
    #[error(
        "--out {}: the folder is not empty and holds no wingman run (no summary.json of one): \
         choose an empty or new folder",
        .0.display()
    )]
    NotARun(PathBuf),
    /// Another run is writing into the folder now, or its lock cannot be taken.
    #[error(transparent)]
    Lock(#[from] super::lock::LockError),
    /// The folder could not be read or cleared.
    #[error("--out {}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
}

fn io_error(path: &Path) -> impl Fn(std::io::Error) -> FolderError + '_ {
    move |source| FolderError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Whether `dir` may receive a run: it does not exist and can be made (its nearest existing
/// ancestor is a folder we may write in), or it is a folder we may write in that is empty or
/// holds an earlier run, and no run is writing into it now.
pub fn check(dir: &Path) -> Result<(), FolderError> {
    check_for(dir, holds_a_run)
}

/// [`check`] for a folder of outputs that `ours` recognises (a sweep's, by its `plan.json`):
/// [`FolderError::NotARun`] for a folder with files in it that `ours` does not recognise.
/// A run's folder is also refused while another run holds its lock.
pub fn check_for(dir: &Path, ours: impl Fn(&Path) -> bool) -> Result<(), FolderError> {
    usable(dir, ours)?;
    if dir.is_dir() {
        super::lock::check_free(dir)?;
    }
    Ok(())
}

/// [`check_for`] but for the lock (which the run preparing the folder holds itself).
fn usable(dir: &Path, ours: impl Fn(&Path) -> bool) -> Result<(), FolderError> {
    if !dir.exists() {
        let ancestor = dir
            .ancestors()
            .skip(1)
            .find(|a| a.exists())
            .unwrap_or(Path::new("."));
        if !ancestor.is_dir() {
            return Err(FolderError::NotAFolder(ancestor.to_path_buf()));
        }
        return writable(ancestor);
    }
    if !dir.is_dir() {
        return Err(FolderError::NotAFolder(dir.to_path_buf()));
    }
    let empty = std::fs::read_dir(dir)
        .map_err(io_error(dir))?
        .next()
        .is_none();
    if empty || ours(dir) {
        writable(dir)
    } else {
        Err(FolderError::NotARun(dir.to_path_buf()))
    }
}

/// Whether this process may create files in the folder `dir` (a read-only file system or
/// folder says no before the run, not in the middle of it).
fn writable(dir: &Path) -> Result<(), FolderError> {
    use std::os::unix::ffi::OsStrExt;
    let path = std::ffi::CString::new(dir.as_os_str().as_bytes()).map_err(|e| FolderError::Io {
        path: dir.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, e),
    })?;
    // SAFETY: access(2) reads the NUL-terminated path and nothing else.
    if unsafe { libc::access(path.as_ptr(), libc::W_OK | libc::X_OK) } == 0 {
        Ok(())
    } else {
        Err(FolderError::Io {
            path: dir.to_path_buf(),
            source: std::io::Error::last_os_error(),
        })
    }
}

/// Checks `dir` as [`check`] does (but for the lock, which the caller holds) and removes
/// what an earlier run wrote there: its three
/// files and the PNG images of its `frames/` and `plots/` (the folders too, once empty).
pub fn prepare(dir: &Path) -> Result<(), FolderError> {
    usable(dir, holds_a_run)?;
    if !dir.exists() {
        return Ok(());
    }
    for folder in RUN_FOLDERS.map(|f| dir.join(f)) {
        if !folder.is_dir() {
            continue;
        }
        for entry in std::fs::read_dir(&folder).map_err(io_error(&folder))? {
            let path = entry.map_err(io_error(&folder))?.path();
            if path.extension().is_some_and(|e| e == "png") && path.is_file() {
                std::fs::remove_file(&path).map_err(io_error(&path))?;
            }
        }
        // Files of the user's own stay, and with them the folder.
        let _ = std::fs::remove_dir(&folder);
    }
    for file in RUN_FILES.map(|f| dir.join(f)) {
        if file.is_file() {
            std::fs::remove_file(&file).map_err(io_error(&file))?;
        }
    }
    Ok(())
}

/// Marks `dir` (created if need be) as a run's folder, before the run writes anything else.
pub fn mark(dir: &Path) -> Result<(), FolderError> {
    std::fs::create_dir_all(dir).map_err(io_error(dir))?;
    let marker = dir.join(MARKER);
    std::fs::write(&marker, "a wingman run writes this folder\n").map_err(io_error(&marker))
}

/// Whether `dir` holds a run: its marker or its lock file, or a `summary.json` (a JSON object with the keys
/// every summary has) of a run from before the marker.
fn holds_a_run(dir: &Path) -> bool {
    if dir.join(MARKER).is_file() || dir.join(super::lock::LOCK_FILE).is_file() {
        return true;
    }
    let Ok(text) = std::fs::read_to_string(dir.join("summary.json")) else {
        return false;
    };
    serde_json::from_str::<serde_json::Value>(&text).is_ok_and(|v| {
        ["scenario", "status", "steps", "duration_s"]
            .iter()
            .all(|k| v.get(k).is_some())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SUMMARY: &str =
        r#"{"scenario": "s", "status": "completed", "steps": 1, "duration_s": 1.0}"#;

    /// The folder of a run killed before its summary (its marker and part of its telemetry)
    /// is a run's: accepted and cleared.
    #[test]
    fn a_killed_runs_folder_is_a_runs() {
        let dir = tempfile::tempdir().expect("temp dir");
        let run = dir.path().join("run");
        mark(&run).expect("marked");
        std::fs::write(run.join("telemetry.csv"), "t_s\n0\n").expect("telemetry");
        prepare(&run).expect("a killed run's folder is cleared");
        assert!(!run.join("telemetry.csv").exists() && !run.join(MARKER).exists());
        std::fs::write(run.join("notes.txt"), "mine").expect("notes");
        assert!(matches!(check(&run), Err(FolderError::NotARun(_))));
    }

    /// A folder under a regular file cannot be made: refused before the run, naming the
    /// file.
    #[test]
    fn a_folder_under_a_file_is_refused() {
        let dir = tempfile::tempdir().expect("temp dir");
        let file = dir.path().join("plain");
        std::fs::write(&file, "x").expect("file");
        let error = check(&file.join("run").join("deeper")).expect_err("refused");
        assert!(
            matches!(&error, FolderError::NotAFolder(p) if *p == file),
            "{error}"
        );
        assert!(check(&dir.path().join("new").join("run")).is_ok());
    }

    /// An earlier run's files go, a user's file stays; a folder of other files is refused.
    #[test]
    fn earlier_runs_are_cleared_and_other_folders_refused() {
        let dir = tempfile::tempdir().expect("temp dir");
        let run = dir.path().join("run");
        std::fs::create_dir_all(run.join("frames")).expect("frames");
        std::fs::write(run.join("summary.json"), SUMMARY).expect("summary");
        std::fs::write(run.join("telemetry.csv"), "t_s\n0\n").expect("telemetry");
        std::fs::write(run.join("frames/000007.png"), "png").expect("frame");
        std::fs::write(run.join("notes.txt"), "mine").expect("notes");
        prepare(&run).expect("an earlier run is cleared");
        assert!(!run.join("summary.json").exists() && !run.join("frames").exists());
        assert!(!run.join("telemetry.csv").exists());
        assert!(run.join("notes.txt").exists(), "the user's file stays");

        let other = dir.path().join("other");
        std::fs::create_dir_all(&other).expect("other");
        std::fs::write(other.join("thesis.tex"), "x").expect("file");
        let err = prepare(&other).unwrap_err();
        assert!(matches!(err, FolderError::NotARun(_)), "{err}");
        assert!(err.to_string().contains("other"), "{err}");
        assert!(other.join("thesis.tex").exists());

        let file = dir.path().join("file");
        std::fs::write(&file, "x").expect("file");
        let err = check(&file).unwrap_err();
        assert!(err.to_string().contains("not a folder"), "{err}");
    }
}
