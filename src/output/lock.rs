//! The output folder's lock: a run holds an exclusive lock (flock(2)) on a file in its folder
//! from before it clears the folder until it has written its last file, so that a second run
//! into the same folder is refused instead of mixing its files with the first's. The kernel
//! releases the lock when the process ends however it ends (SIGKILL included), so a killed
//! run leaves no stale lock.

use std::fs::File;
use std::io::{Read, Seek, Write};
use std::os::fd::AsRawFd;
use std::path::{Path, PathBuf};

/// Why a folder's lock could not be taken.
#[derive(Debug, thiserror::Error)]
pub enum LockError {
    /// Another run is writing into the folder now (it holds the folder's lock).
    #[error(
        "--out {}: another wingman run{} is writing into this folder: wait for it or choose \
         another folder",
        path.display(),
        holder.map(|p| format!(" (process {p})")).unwrap_or_default()
    )]
    Busy {
        /// The folder.
        path: PathBuf,
        /// The process holding the lock, when its lock file says.
        holder: Option<u32>,
    },
    /// The lock file could not be made, read or locked.
    #[error("--out {}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
}

fn io_error(path: &Path) -> impl Fn(std::io::Error) -> LockError + '_ {
    move |source| LockError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// The lock file a run keeps in its folder (it stays after the run; only its lock goes).
pub const LOCK_FILE: &str = ".wingman-lock";

/// A held lock on an output folder; dropping it releases the lock.
#[derive(Debug)]
pub struct FolderLock {
    _file: File,
}

/// Takes the lock of `dir` (created if need be), or says which process holds it.
pub fn lock(dir: &Path) -> Result<FolderLock, LockError> {
    std::fs::create_dir_all(dir).map_err(io_error(dir))?;
    let path = dir.join(LOCK_FILE);
    let mut file = open(&path)?;
    if !try_lock(&file).map_err(io_error(&path))? {
        return Err(busy(dir, &mut file));
    }
    // The holder's process id, for the message of a run that is refused.
    let written = file
        .set_len(0)
        .and_then(|()| file.rewind())
        .and_then(|()| writeln!(file, "{}", std::process::id()));
    written.map_err(io_error(&path))?;
    Ok(FolderLock { _file: file })
}

/// Fails when a run holds the lock of `dir` now (a check before the run starts; [`lock`] is
/// what keeps a second run out).
pub fn check_free(dir: &Path) -> Result<(), LockError> {
    let path = dir.join(LOCK_FILE);
    if !path.is_file() {
        return Ok(());
    }
    let mut file = open(&path)?;
    match try_lock(&file).map_err(io_error(&path))? {
        // Taken and released again when `file` closes.
        true => Ok(()),
        false => Err(busy(dir, &mut file)),
    }
}

fn open(path: &Path) -> Result<File, LockError> {
    std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(false)
        .open(path)
        .map_err(io_error(path))
}

/// Whether the exclusive lock of `file` was taken (false: another process holds it).
fn try_lock(file: &File) -> std::io::Result<bool> {
    // SAFETY: flock(2) on a descriptor that `file` keeps open; it touches no memory.
    if unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) } == 0 {
        return Ok(true);
    }
    let error = std::io::Error::last_os_error();
    match error.raw_os_error() {
        Some(libc::EWOULDBLOCK) => Ok(false),
        _ => Err(error),
    }
}

/// The refusal, naming the holder's process id when the lock file says it.
fn busy(dir: &Path, file: &mut File) -> LockError {
    let mut text = String::new();
    let holder = file
        .read_to_string(&mut text)
        .ok()
        .and_then(|_| text.trim().parse::<u32>().ok());
    LockError::Busy {
        path: dir.to_path_buf(),
        holder,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A second lock of a held folder is refused, naming this process; once the first is
    /// dropped the folder can be locked again.
    #[test]
    fn a_held_folder_is_refused_until_released() {
        let dir = tempfile::tempdir().expect("temp dir");
        let run = dir.path().join("run");
        let held = lock(&run).expect("first lock");
        let error = lock(&run).expect_err("second lock refused");
        let pid = std::process::id();
        assert!(
            matches!(&error, LockError::Busy { holder: Some(p), .. } if *p == pid),
            "{error}"
        );
        assert!(check_free(&run).is_err());
        drop(held);
        check_free(&run).expect("released");
        lock(&run).expect("locked again");
    }
}
