//! A panic ends a run as cleanly as Ctrl-C does: the writes under way are dropped, every output
//! folder's manifest records how the run ended and its lock is released
//! ([`squeal_pipeline::folder::interrupt::stop_with`]), one line says what happened, and the exit status says
//! it too.
//!
//! The common panic is not a bug: `squeal stability scene.toml | head -1` closes the pipe
//! after one line, and the next `println!` fails with EPIPE. Rust ignores SIGPIPE at start-up,
//! so the write returns the error and `println!` panics ("failed printing to stdout: Broken
//! pipe"); before this hook the panic unwound past `main`'s clean-up and left the folder's
//! `.squeal-lock` and a manifest saying "running".
//!
//! Why a panic hook, and not SIGPIPE's default action or a fallible writer:
//! - SIGPIPE's default action kills the process at the write: nothing runs after it, so the
//!   manifest would still say "running" and the lock file would stay (as after `kill -9`).
//! - Every command prints with `println!` (hundreds of lines over the commands); making each
//!   write fallible would touch them all, and a panic elsewhere (a bug) would still need this.
//!
//! The hook runs on the panicking thread before any unwinding, so the run's state is intact:
//! the hook stops the process there ([`std::process::exit`]), other threads included. A
//! closed standard output or error exits with 141 (128 + SIGPIPE, what a shell shows for a
//! process killed by the signal), any other panic with 101 (Rust's status for a panic). With
//! `RUST_BACKTRACE` set, a bug's panic is also printed the standard way, backtrace included.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

/// The exit status when the standard output (or error) was closed: 128 + SIGPIPE.
pub const CLOSED_PIPE_STATUS: i32 = 141;
/// The exit status after an internal error (a panic that is not a closed pipe).
pub const BUG_STATUS: i32 = 101;

/// How a panic ends the run.
#[derive(Debug, PartialEq)]
pub struct Ending {
    /// The line for the user (standard error).
    pub message: String,
    /// What the output folders' manifests record.
    pub status: String,
    /// The exit status.
    pub code: i32,
}

/// The ending for a panic whose message is `text`, raised at `place` (`file:line`).
pub fn ending(text: &str, place: Option<String>) -> Ending {
    let text = text.trim();
    let closed = ["stdout", "stderr"]
        .into_iter()
        .find(|s| text.starts_with(&format!("failed printing to {s}")));
    // EPIPE is 32 on Linux, macOS and the BSDs; its text is the C locale's (Rust programs do
    // not set a locale).
    let broken = text.contains("Broken pipe") || text.contains("(os error 32)");
    if let (Some(stream), true) = (closed, broken) {
        let stream = match stream {
            "stdout" => "standard output",
            _ => "standard error",
        };
        return Ending {
            message: format!(
                "error: the {stream} was closed before the run ended (a broken pipe, as with `| head`): the run stopped; no partial file is left, and an output folder's manifest marks the run as interrupted"
            ),
            status: format!("interrupted (the {stream} was closed)"),
            code: CLOSED_PIPE_STATUS,
        };
    }
    // A panic message is one line for the user: its own line breaks would split it.
    let one_line = text.split_whitespace().collect::<Vec<_>>().join(" ");
    let at = place.map(|p| format!(" at {p}")).unwrap_or_default();
    Ending {
        message: format!(
            "error: internal error (a bug in squeal{at}: {one_line}); the run stopped: no partial file is left, and an output folder's manifest marks the run as failed; please report it with the command line (RUST_BACKTRACE=1 shows where)"
        ),
        status: format!("failed: internal error: {one_line}"),
        code: BUG_STATUS,
    }
}

/// The text of a panic's payload: `panic!` gives a `&str` or a `String`.
fn payload_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic without a message".into()
    }
}

/// Installs the hook (module docs). Called once, first thing in `main`.
pub fn install() {
    let standard = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        // A second panic (another thread) while the first stops the process waits for it.
        static ENDING: AtomicBool = AtomicBool::new(false);
        if ENDING.swap(true, Ordering::SeqCst) {
            loop {
                std::thread::park();
            }
        }
        let place = info
            .location()
            .map(|l| format!("{}:{}", l.file(), l.line()));
        let end = ending(&payload_text(info.payload()), place);
        let backtrace = std::env::var("RUST_BACKTRACE").is_ok_and(|v| !v.is_empty() && v != "0");
        if end.code == BUG_STATUS && backtrace {
            standard(info);
        }
        // Standard error may be the closed pipe: the line is then lost, not a second panic.
        let _ = writeln!(std::io::stderr().lock(), "{}", end.message);
        squeal_pipeline::folder::interrupt::stop_with(&end.status, end.code);
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The panic of `println!` on a closed pipe (its text as Rust's standard library writes
    /// it) is a closed pipe, not a bug: exit 141, the run interrupted.
    #[test]
    fn a_closed_pipe_is_an_interruption() {
        let e = ending(
            "failed printing to stdout: Broken pipe (os error 32)",
            Some("library/std/src/io/stdio.rs:1165".into()),
        );
        assert_eq!(e.code, 141);
        assert_eq!(e.status, "interrupted (the standard output was closed)");
        assert!(
            e.message
                .starts_with("error: the standard output was closed")
        );
        assert!(!e.message.contains("stdio.rs") && !e.message.contains('\n'));
        let e = ending("failed printing to stderr: Broken pipe (os error 32)", None);
        assert_eq!(e.status, "interrupted (the standard error was closed)");
    }

    /// Another failure to print (a full disk under a redirection) and any other panic are
    /// internal errors: exit 101, one line naming the place, the run failed.
    #[test]
    fn other_panics_are_bugs_said_on_one_line() {
        let e = ending(
            "failed printing to stdout: No space left on device (os error 28)",
            None,
        );
        assert_eq!(e.code, 101);
        let e = ending(
            "index out of bounds:\n the len is 3 but the index is 7",
            Some("crates/x/src/y.rs:12".into()),
        );
        assert_eq!(e.code, 101);
        assert_eq!(
            e.status,
            "failed: internal error: index out of bounds: the len is 3 but the index is 7"
        );
        assert!(
            e.message
                .starts_with("error: internal error (a bug in squeal at crates/x/src/y.rs:12: index out of bounds: the len"),
            "{}",
            e.message
        );
        assert!(!e.message.contains('\n'));
    }
}
