//! Interrupts during a long run (`verify`, `impact sweep --out`): SIGINT or SIGTERM prints what
//! happened and exits with 128 + the signal, never leaving a half-written output. The reports and
//! a sweep's output file are written through a temporary beside them and renamed at the end, so
//! before that point an interrupt leaves the previous ones as they were (the temporary file is
//! removed); while the final renames run, the signal waits for them to finish.
//!
//! Written by hand on `libc::signal`: the handler may only do async-signal-safe work (store to an
//! atomic, write(2), unlink(2), _exit(2)), which a crate would wrap in a thread and a channel that
//! this needs no more than it needs the dependency.

use std::sync::atomic::{AtomicBool, AtomicI32, AtomicPtr, AtomicUsize, Ordering};

static WRITING: AtomicBool = AtomicBool::new(false);
static PENDING: AtomicI32 = AtomicI32::new(0);
static MSG: AtomicPtr<u8> = AtomicPtr::new(std::ptr::null_mut());
static MSG_LEN: AtomicUsize = AtomicUsize::new(0);
static TEMP: AtomicPtr<libc::c_char> = AtomicPtr::new(std::ptr::null_mut());
static OUT_MSG: AtomicPtr<u8> = AtomicPtr::new(std::ptr::null_mut());
static OUT_LEN: AtomicUsize = AtomicUsize::new(0);

#[cfg(unix)]
extern "C" fn on_signal(sig: libc::c_int) {
    if WRITING.load(Ordering::SeqCst) {
        PENDING.store(sig, Ordering::SeqCst);
        return;
    }
    let msg = MSG.load(Ordering::SeqCst);
    let len = MSG_LEN.load(Ordering::SeqCst);
    let temp = TEMP.load(Ordering::SeqCst);
    let out = OUT_MSG.load(Ordering::SeqCst);
    let out_len = OUT_LEN.load(Ordering::SeqCst);
    // SAFETY: write(2), unlink(2) and _exit(2) are async-signal-safe; `msg` points to `len` bytes,
    // `out` to `out_len` and `temp` to a NUL-terminated path, all leaked by `install` (and
    // `end_stdout_with`) and never freed.
    unsafe {
        if !temp.is_null() {
            libc::unlink(temp);
        }
        if !out.is_null() {
            libc::write(1, out.cast(), out_len);
        }
        if !msg.is_null() {
            libc::write(2, msg.cast(), len);
        }
        libc::_exit(128 + sig);
    }
}

/// Installs the handler for SIGINT and SIGTERM with the message it prints, and the temporary file
/// (if any) it removes.
pub fn install(message: &str, temp: Option<&std::path::Path>) {
    let msg: &'static mut [u8] = Box::leak(message.as_bytes().to_vec().into_boxed_slice());
    MSG_LEN.store(msg.len(), Ordering::SeqCst);
    MSG.store(msg.as_mut_ptr(), Ordering::SeqCst);
    if let Some(p) = temp {
        use std::os::unix::ffi::OsStrExt;
        if let Ok(c) = std::ffi::CString::new(p.as_os_str().as_bytes()) {
            TEMP.store(c.into_raw(), Ordering::SeqCst);
        }
    }
    #[cfg(unix)]
    // SAFETY: `on_signal` is an `extern "C" fn(c_int)` that does only async-signal-safe work.
    unsafe {
        let h = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
        libc::signal(libc::SIGINT, h);
        libc::signal(libc::SIGTERM, h);
    }
}

/// Output streamed to stdout cannot be taken back: an interrupt then also writes `line` to
/// stdout (after a newline, as the signal may cut a row), so that a script reading the stream
/// sees it ended early. Call after [`install`].
pub fn end_stdout_with(line: &str) {
    let text = format!("\n{}\n", line.trim_end());
    let bytes: &'static mut [u8] = Box::leak(text.into_bytes().into_boxed_slice());
    OUT_LEN.store(bytes.len(), Ordering::SeqCst);
    OUT_MSG.store(bytes.as_mut_ptr(), Ordering::SeqCst);
}

/// Runs the final writes with signals held back; a signal that arrived meanwhile then ends the
/// process, saying that the output was completed.
pub fn while_writing<T>(what: &str, f: impl FnOnce() -> T) -> T {
    WRITING.store(true, Ordering::SeqCst);
    let out = f();
    WRITING.store(false, Ordering::SeqCst);
    let sig = PENDING.load(Ordering::SeqCst);
    if sig != 0 {
        eprintln!(
            "{what}: interrupted by signal {sig} while writing; the writing was finished first"
        );
        std::process::exit(128 + sig);
    }
    out
}
