//! Printing shared by the squeal-eigs benchmarks.

use squeal_eigs::FactorStats;
use std::time::Duration;

/// The factorization's times and sizes, one quantity a line.
pub fn print_factor(s: &FactorStats, total: Duration) {
    println!(
        "ordering (s)            {:8.2}",
        s.ordering_time.as_secs_f64()
    );
    println!(
        "ordering + symbolic (s) {:8.2}",
        s.symbolic_time.as_secs_f64()
    );
    println!(
        "numeric Cholesky (s)    {:8.2}",
        s.numeric_time.as_secs_f64()
    );
    println!("factorize incl. checks  {:8.2}", total.as_secs_f64());
    println!("supernodal              {:>8}", s.supernodal);
    println!("nnz(L)                  {:>12}", s.nnz_l);
    println!("factor flops            {:>12.3e}", s.flops);
    println!(
        "solve tasks / top share {:>8} / {:.2}",
        s.solve_tasks, s.solve_top_fraction
    );
    println!(
        "factor memory (MiB)     {:8.1}",
        s.factor_bytes as f64 / 1048576.0
    );
}

/// Peak resident memory of this process in MiB (VmHWM of /proc/self/status).
pub fn peak_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|kb| kb.parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}
