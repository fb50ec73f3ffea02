//! Ctrl-C (SIGINT) asks a run to stop: the first one sets a flag that the run reads at every
//! tick (it then flushes its telemetry, writes its summary with status `interrupted` and its
//! plots); a second one ends the program at once, as if no handler were installed.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Whether a stop was asked for.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// Asks the run to stop (what the signal handler does).
pub fn request() {
    REQUESTED.store(true, Ordering::Relaxed);
}

extern "C" fn on_sigint(_signal: libc::c_int) {
    // Only an atomic store: nothing else is safe in a signal handler.
    request();
}

/// Installs the SIGINT handler (once per process). libc's `sigaction` directly: the one call
/// needs no crate of its own, and `SA_RESETHAND` gives a second Ctrl-C its default action.
pub fn install_sigint_handler() -> std::io::Result<()> {
    // SAFETY: the handler only stores to an atomic (async-signal-safe); the sigaction struct
    // is zero-initialised and then filled in as sigaction(2) describes.
    let result = unsafe {
        let mut action: libc::sigaction = std::mem::zeroed();
        action.sa_sigaction = on_sigint as *const () as libc::sighandler_t;
        action.sa_flags = libc::SA_RESETHAND | libc::SA_RESTART;
        libc::sigemptyset(&mut action.sa_mask);
        libc::sigaction(libc::SIGINT, &action, std::ptr::null_mut())
    };
    if result == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}
