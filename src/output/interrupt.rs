//! A signal asks a run to stop: Ctrl-C (SIGINT), or SIGTERM, with which batch schedulers
//! (Slurm, Kubernetes) pre-empt a job before they kill it. The first one sets a flag that the
//! run reads at every tick (it then flushes its telemetry, writes its summary with status
//! `interrupted` and its plots); a second one ends the program at once, as if no handler were
//! installed.

use std::sync::atomic::{AtomicI32, Ordering};

/// The signal that asked for the stop (0: none).
static SIGNAL: AtomicI32 = AtomicI32::new(0);

/// Whether a stop was asked for.
pub fn requested() -> bool {
    SIGNAL.load(Ordering::Relaxed) != 0
}

/// The signal that asked for the stop, when one did.
pub fn signal() -> Option<i32> {
    Some(SIGNAL.load(Ordering::Relaxed)).filter(|s| *s != 0)
}

/// Asks the run to stop as `signal` does (what the signal handler does).
pub fn request(signal: i32) {
    SIGNAL.store(signal, Ordering::Relaxed);
}

extern "C" fn on_signal(signal: libc::c_int) {
    // Only an atomic store: nothing else is safe in a signal handler.
    request(signal);
}

/// Installs the handler of SIGINT and SIGTERM (once per process). libc's `sigaction`
/// directly: the one call needs no crate of its own, and `SA_RESETHAND` gives a second signal
/// its default action.
pub fn install_stop_handlers() -> std::io::Result<()> {
    [libc::SIGINT, libc::SIGTERM]
        .into_iter()
        .try_for_each(install_handler)
}

fn install_handler(signal: libc::c_int) -> std::io::Result<()> {
    // SAFETY: the handler only stores to an atomic (async-signal-safe); the sigaction struct
    // is zero-initialised and then filled in as sigaction(2) describes.
    let result = unsafe {
        let mut action: libc::sigaction = std::mem::zeroed();
        action.sa_sigaction = on_signal as *const () as libc::sighandler_t;
        action.sa_flags = libc::SA_RESETHAND | libc::SA_RESTART;
        libc::sigemptyset(&mut action.sa_mask);
        libc::sigaction(signal, &action, std::ptr::null_mut())
    };
    if result == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}
