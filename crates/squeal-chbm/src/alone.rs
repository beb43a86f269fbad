//! Independent runs side by side, each alone on one thread.
//!
//! A comparison's runs (CHBM solves, time integrations, the shooting reference) are
//! independent and each is timed: its wall time is a column of the paper's Table 2. Run on
//! rayon's pool, a thread waiting inside one run's parallel section steals another run's work,
//! and the first run's wall time then includes the second's. [`run_alone`] keeps each run on
//! its own worker: at most `rayon::current_num_threads()` scoped workers (the bound the caller
//! chose with `--threads`), each with a private one-thread rayon pool, so a run's parallel
//! sections execute sequentially on that worker and nothing else runs there meanwhile. The
//! results are the same bits for any number of workers (every run is computed as it would be
//! alone on one thread), and the wall times are each run's own one-thread cost.

use std::collections::VecDeque;
use std::sync::Mutex;

/// One run: computed once, on whichever worker takes it.
pub type Job<'a, T> = Box<dyn FnOnce() -> T + Send + 'a>;

/// Runs `jobs` in the order given (the longest first gives the shortest wall time), each
/// alone on one of at most `rayon::current_num_threads()` workers; returns their results in
/// the order of `jobs`.
pub fn run_alone<'a, T: Send>(jobs: Vec<Job<'a, T>>) -> Vec<T> {
    let n = jobs.len();
    let workers = rayon::current_num_threads().clamp(1, n.max(1));
    let queue: Mutex<VecDeque<(usize, Job<'a, T>)>> =
        Mutex::new(jobs.into_iter().enumerate().collect());
    let results: Mutex<Vec<Option<T>>> = Mutex::new((0..n).map(|_| None).collect());
    let next = || {
        queue
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .pop_front()
    };
    let work = || {
        // Without a private pool (the system refused a thread) the runs go on here, still
        // one at a time; only their parallel sections may then use the caller's pool.
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().ok();
        while let Some((i, job)) = next() {
            let out = match &pool {
                Some(p) => p.install(job),
                None => job(),
            };
            results
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)[i] = Some(out);
        }
    };
    if workers == 1 {
        work();
    } else {
        std::thread::scope(|s| {
            for _ in 0..workers {
                s.spawn(work);
            }
        });
    }
    results
        .into_inner()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
        .into_iter()
        .map(|r| r.expect("every job ran: the workers empty the queue before the scope ends"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_keep_the_jobs_order_and_no_more_run_at_once_than_workers() {
        // Exact: each job returns its index; the most jobs running at once is counted.
        use std::sync::atomic::{AtomicUsize, Ordering};
        let running = AtomicUsize::new(0);
        let most = AtomicUsize::new(0);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let out = pool.install(|| {
            let jobs: Vec<Job<'_, usize>> = (0..7)
                .map(|i| {
                    let (running, most) = (&running, &most);
                    Box::new(move || {
                        let now = running.fetch_add(1, Ordering::SeqCst) + 1;
                        most.fetch_max(now, Ordering::SeqCst);
                        // A parallel section inside a job stays on the job's worker.
                        let s: usize = rayon::iter::ParallelIterator::sum(
                            rayon::iter::IntoParallelIterator::into_par_iter(0..1000usize),
                        );
                        std::thread::sleep(std::time::Duration::from_millis(20));
                        running.fetch_sub(1, Ordering::SeqCst);
                        i + s - 499_500
                    }) as Job<'_, usize>
                })
                .collect();
            run_alone(jobs)
        });
        assert_eq!(out, (0..7).collect::<Vec<_>>());
        assert!(
            most.load(Ordering::SeqCst) <= 2,
            "at most the pool's 2 workers"
        );
    }
}
