//! Benchmark of `squeal reduce` (issue #4, item 9): time of each stage and peak memory on
//! the bundled coarse, medium and fine meshes, for each eigensolver backend, and the log-log
//! slope of time against dofs.
//!
//! ```sh
//! nice cargo bench -p squeal-reduce --bench reduce                      # Lanczos
//! nice cargo bench -p squeal-reduce --features arpack --bench reduce    # and ARPACK
//! nice cargo bench -p squeal-reduce --bench reduce -- coarse medium     # some levels
//! ```
//! Each (level, backend) runs in a fresh process (this binary with `--child`), so that its
//! peak resident memory (VmHWM of /proc/self/status) is its own.

use squeal_eigs::Backend;
use squeal_reduce::brake::{BrakeInputs, backend_name, load_part, reduce_brake_loaded};
use squeal_reduce::craig_bampton::Stage;
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

const LEVELS: [&str; 3] = ["coarse", "medium", "fine"];

fn mesh(part: &str, level: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../meshes")
        .join(format!("{part}_{level}.inp"))
}

/// One run's results, as the child prints them: `key=value` pairs on one line.
#[derive(Debug, Default, Clone)]
struct Run {
    level: String,
    backend: String,
    /// Free dofs of disc + pad.
    dofs: usize,
    /// Seconds per stage, disc + pad, in `Stage::ALL` order.
    stages: Vec<f64>,
    total: f64,
    peak_mb: f64,
    factor_mb: f64,
    /// User + system CPU seconds of the process.
    cpu: f64,
}

fn peak_mb() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// User + system CPU time of this process (fields 14 and 15 of /proc/self/stat, in
/// clock ticks of 1/100 s, Linux's USER_HZ).
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // The command name (field 2) is in parentheses and may hold spaces: count after it.
    let after = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    let fields: Vec<&str> = after.split_whitespace().collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    // Fields 14 and 15 overall are the 12th and 13th after the command name.
    (ticks(11) + ticks(12)) / 100.0
}

/// Runs one reduction and prints its line.
fn child(level: &str, backend: Backend) {
    faer::set_global_parallelism(faer::Par::Seq);
    let t0 = Instant::now();
    let inputs = BrakeInputs {
        backend,
        ..BrakeInputs::bundled(mesh("disc", level), mesh("pad", level))
    };
    let disc = load_part(&inputs.disc.mesh).expect("disc mesh");
    let pad = load_part(&inputs.pad.mesh).expect("pad mesh");
    let (model, report) =
        reduce_brake_loaded(&inputs, disc, pad, &mut |_, _| {}).expect("reduction");
    let out = std::env::temp_dir().join(format!("squeal-bench-{}.rom", std::process::id()));
    let t = Instant::now();
    model.write(&out).expect("write");
    let write = t.elapsed().as_secs_f64();
    let _ = std::fs::remove_file(&out);
    let total = t0.elapsed().as_secs_f64();
    let stages: Vec<String> = Stage::ALL
        .iter()
        .map(|&s| {
            if s == Stage::Write {
                return format!("{write}");
            }
            let secs: f64 = report.parts.iter().map(|p| p.time(s).as_secs_f64()).sum();
            format!("{secs}")
        })
        .collect();
    let dofs: usize = report.parts.iter().map(|p| p.reduce.free_dofs).sum();
    let factor: usize = report.parts.iter().map(|p| p.reduce.factor_bytes).sum();
    println!(
        "RUN level={level} backend={} dofs={dofs} stages={} total={total} peak_mb={} factor_mb={} cpu={}",
        backend_name(backend),
        stages.join(","),
        peak_mb(),
        factor as f64 / 1e6,
        cpu_seconds()
    );
}

fn parse(line: &str) -> Option<Run> {
    let mut run = Run::default();
    for kv in line.strip_prefix("RUN ")?.split_whitespace() {
        let (k, v) = kv.split_once('=')?;
        match k {
            "level" => run.level = v.into(),
            "backend" => run.backend = v.into(),
            "dofs" => run.dofs = v.parse().ok()?,
            "stages" => {
                run.stages = v
                    .split(',')
                    .map(|x| x.parse().unwrap_or(f64::NAN))
                    .collect()
            }
            "total" => run.total = v.parse().ok()?,
            "peak_mb" => run.peak_mb = v.parse().ok()?,
            "factor_mb" => run.factor_mb = v.parse().ok()?,
            "cpu" => run.cpu = v.parse().ok()?,
            _ => {}
        }
    }
    Some(run)
}

/// Least-squares slope of log(y) against log(x).
fn slope(points: &[(f64, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    if args.first().map(String::as_str) == Some("--child") {
        let backend = match args.get(2).map(String::as_str) {
            Some("arpack") => Backend::Arpack,
            _ => Backend::Lanczos,
        };
        child(&args[1], backend);
        return;
    }
    let levels: Vec<String> = if args.is_empty() {
        LEVELS.iter().map(|s| s.to_string()).collect()
    } else {
        args
    };
    let mut backends = vec!["lanczos"];
    if cfg!(feature = "arpack") {
        backends.push("arpack");
    } else {
        eprintln!("(ARPACK backend not compiled in: add --features arpack)");
    }
    let exe = std::env::current_exe().expect("own path");
    let mut runs = Vec::new();
    for backend in &backends {
        for level in &levels {
            eprintln!("running {level} / {backend} ...");
            let out = Command::new(&exe)
                .args(["--child", level, backend])
                .output()
                .expect("child process");
            let text = String::from_utf8_lossy(&out.stdout);
            match text.lines().find_map(parse) {
                Some(run) => runs.push(run),
                None => eprintln!(
                    "{level} / {backend} failed: {}",
                    String::from_utf8_lossy(&out.stderr)
                ),
            }
        }
    }
    print_table(&runs);
    for backend in &backends {
        let mine: Vec<&Run> = runs.iter().filter(|r| r.backend == *backend).collect();
        if mine.len() < 2 {
            continue;
        }
        let total = slope(
            &mine
                .iter()
                .map(|r| (r.dofs as f64, r.total))
                .collect::<Vec<_>>(),
        );
        let per_stage: Vec<String> = Stage::ALL
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let pts: Vec<(f64, f64)> =
                    mine.iter().map(|r| (r.dofs as f64, r.stages[k])).collect();
                format!("{} {:.2}", s.label(), slope(&pts))
            })
            .collect();
        println!(
            "\n{backend}: log-log slope of time against dofs: total {total:.2}; {}",
            per_stage.join(", ")
        );
    }
}

fn print_table(runs: &[Run]) {
    let mut head = "| mesh | backend | free dofs |".to_string();
    let mut rule = "|---|---|---|".to_string();
    for s in Stage::ALL {
        head += &format!(" {} |", s.label());
        rule += "---|";
    }
    head += " total (s) | CPU (s) | peak memory (MB) | factors (MB) |";
    rule += "---|---|---|---|";
    println!("{head}\n{rule}");
    for r in runs {
        let mut row = format!("| {} | {} | {} |", r.level, r.backend, r.dofs);
        for t in &r.stages {
            row += &format!(" {t:.2} |");
        }
        row += &format!(
            " {:.1} | {:.1} | {:.0} | {:.0} |",
            r.total, r.cpu, r.peak_mb, r.factor_mb
        );
        println!("{row}");
    }
}
