//! The parts' progress messages relayed to the caller's thread while they are reduced side by
//! side (moved from `brake.rs`, not changed).

use super::*;

/// Hands the parts' progress messages to `progress` on this thread, in the order each part
/// sent them, until every part has finished. A thread of the rayon pool (a caller inside
/// `ThreadPool::install`) runs pending work between messages instead of blocking the pool.
pub(super) fn relay(rx: &mpsc::Receiver<(usize, Stage)>, progress: &mut dyn FnMut(usize, Stage)) {
    let worker = rayon::current_thread_index().is_some();
    loop {
        let next = if worker {
            next_helping(rx)
        } else {
            rx.recv().ok()
        };
        match next {
            Some((name, stage)) => progress(name, stage),
            None => return,
        }
    }
}

/// The next message, running pending pool work while there is none (None: every sender is
/// gone).
fn next_helping(rx: &mpsc::Receiver<(usize, Stage)>) -> Option<(usize, Stage)> {
    loop {
        match rx.try_recv() {
            Ok(m) => return Some(m),
            Err(mpsc::TryRecvError::Disconnected) => return None,
            Err(mpsc::TryRecvError::Empty) => {}
        }
        if rayon::yield_now() != Some(rayon::Yield::Executed) {
            match rx.recv_timeout(Duration::from_millis(2)) {
                Ok(m) => return Some(m),
                Err(mpsc::RecvTimeoutError::Disconnected) => return None,
                Err(mpsc::RecvTimeoutError::Timeout) => {}
            }
        }
    }
}
