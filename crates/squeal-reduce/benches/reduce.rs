//! Benchmark of `squeal reduce` (issue #4 item 9, issue #13): time and peak memory of each
//! stage on the bundled coarse, medium and fine meshes, the eigensolver's work (solves per
//! mode, fill and flops of the factors), and the log-log slopes of time and memory against
//! dofs. A larger disc (the ~1M-dof scaling level, made by `tools/mesh/brake_meshes.py
//! --levels huge`) is reduced with the fine pad when its path is given.
//!
//! ```sh
//! nice cargo bench -p squeal-reduce --bench reduce                      # coarse, medium, fine
//! nice cargo bench -p squeal-reduce --bench reduce -- coarse medium     # some levels
//! nice cargo bench -p squeal-reduce --bench reduce -- fine /tmp/squeal-huge/disc_huge.inp
//! nice cargo bench -p squeal-reduce --features arpack --bench reduce    # and ARPACK
//! options: --interface=patch|node (patch)  --threads=N (all cores)
//! ```
//! Each (level, backend) runs in a fresh process (this binary with `--child`), so that its
//! peak resident memory (VmHWM of /proc/self/status) is its own. The peak of each stage is
//! the process's while the disc is in that stage (the pad runs at the same time), measured by
//! resetting VmHWM (`/proc/self/clear_refs`) whenever a part changes stage.

use squeal_eigs::Backend;
use squeal_reduce::brake::{BrakeInputs, backend_name, load_part, reduce_brake_loaded};
use squeal_reduce::craig_bampton::Stage;
use squeal_reduce::rom::InterfaceKind;
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

const LEVELS: [&str; 3] = ["coarse", "medium", "fine"];

fn mesh(part: &str, level: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../meshes")
        .join(format!("{part}_{level}.inp"))
}

/// The disc and pad meshes of a level: a bundled level, or a disc mesh path with the fine pad.
fn meshes(level: &str) -> (PathBuf, PathBuf) {
    if LEVELS.contains(&level) {
        (mesh("disc", level), mesh("pad", level))
    } else {
        (PathBuf::from(level), mesh("pad", "fine"))
    }
}

/// A short name for a level (the file stem of a disc mesh path).
fn level_name(level: &str) -> String {
    PathBuf::from(level)
        .file_stem()
        .map_or(level.to_string(), |s| s.to_string_lossy().into_owned())
}

/// One run's results, as the child prints them: `key=value` pairs on one line.
#[derive(Debug, Default, Clone)]
struct Run {
    level: String,
    backend: String,
    /// Free dofs of disc + pad.
    dofs: usize,
    /// Seconds per stage in `Stage::ALL` order, disc and pad.
    disc: Vec<f64>,
    pad: Vec<f64>,
    /// Peak resident MB of the process while the disc was in each stage.
    stage_peaks: Vec<f64>,
    total: f64,
    peak_mb: f64,
    factor_mb: f64,
    /// User + system CPU seconds of the process.
    cpu: f64,
    /// 1-minute load average before and after.
    load: (f64, f64),
    /// Eigensolver work per part: `name:n:nnz_l:flops:solves:modes:block:ncv:solve_s:mass_s:ritz_s:sturm_s:beside`.
    work: Vec<String>,
}

fn status_mb(key: &str) -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix(key))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn peak_mb() -> f64 {
    status_mb("VmHWM:")
}

/// Resets VmHWM to the current resident size (Linux: "5" to /proc/self/clear_refs).
fn reset_peak() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

fn load_average() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|v| v.parse().ok()))
        .unwrap_or(f64::NAN)
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

fn list(values: impl IntoIterator<Item = f64>) -> String {
    values
        .into_iter()
        .map(|v| format!("{v}"))
        .collect::<Vec<_>>()
        .join(",")
}

/// Runs one reduction and prints its line.
fn child(level: &str, backend: Backend, interface: InterfaceKind) {
    faer::set_global_parallelism(faer::Par::Seq);
    let load0 = load_average();
    let t0 = Instant::now();
    let (disc_mesh, pad_mesh) = meshes(level);
    let inputs = BrakeInputs {
        backend,
        interface,
        ..BrakeInputs::bundled(disc_mesh, pad_mesh)
    };
    reset_peak();
    let disc = load_part(&inputs.disc.mesh).expect("disc mesh");
    let pad = load_part(&inputs.pad().mesh).expect("pad mesh");
    let mut stage_peaks = vec![0.0f64; Stage::ALL.len()];
    stage_peaks[0] = peak_mb();
    let mut current = [Stage::Read; 2];
    let (model, report) = reduce_brake_loaded(&inputs, disc, vec![pad], &mut |part, stage| {
        let peak = peak_mb();
        reset_peak();
        let k = Stage::ALL
            .iter()
            .position(|s| *s == current[0])
            .unwrap_or(0);
        stage_peaks[k] = stage_peaks[k].max(peak);
        current[usize::from(part == "pad")] = stage;
    })
    .expect("reduction");
    let k = Stage::ALL
        .iter()
        .position(|s| *s == current[0])
        .unwrap_or(0);
    stage_peaks[k] = stage_peaks[k].max(peak_mb());
    reset_peak();
    let out = std::env::temp_dir().join(format!("squeal-bench-{}.rom", std::process::id()));
    let t = Instant::now();
    model.write(&out).expect("write");
    let write = t.elapsed().as_secs_f64();
    let _ = std::fs::remove_file(&out);
    let w = Stage::ALL.len() - 1;
    stage_peaks[w] = peak_mb();
    let total = t0.elapsed().as_secs_f64();
    let stages = |p: usize| {
        list(Stage::ALL.iter().map(|&s| match s {
            Stage::Write if p == 0 => write,
            Stage::Write => 0.0,
            _ => report.parts[p].time(s).as_secs_f64(),
        }))
    };
    let dofs: usize = report.parts.iter().map(|p| p.reduce.free_dofs).sum();
    let factor: usize = report.parts.iter().map(|p| p.reduce.factor_bytes).sum();
    let work: Vec<String> = report
        .parts
        .iter()
        .map(|p| {
            let (r, e) = (&p.reduce, &p.reduce.eig);
            format!(
                "{}:{}:{}:{}:{}:{}:{}:{}:{}:{}:{}:{}:{}",
                p.name,
                r.interior_dofs,
                r.factor.nnz_l,
                r.factor.flops,
                e.operator_applications,
                r.modes,
                e.block,
                e.ncv,
                e.operator_time.as_secs_f64(),
                e.mass_time.as_secs_f64(),
                e.ritz_time.as_secs_f64(),
                e.sturm_time.as_secs_f64(),
                e.sturm_beside
            )
        })
        .collect();
    println!(
        "RUN level={} backend={} dofs={dofs} disc={} pad={} peaks={} total={total} peak_mb={} \
         factor_mb={} cpu={} load={load0},{} work={}",
        level_name(level),
        backend_name(backend),
        stages(0),
        stages(1),
        list(stage_peaks.iter().copied()),
        stage_peaks.iter().copied().fold(0.0, f64::max),
        factor as f64 / 1e6,
        cpu_seconds(),
        load_average(),
        work.join(";")
    );
}

fn parse(line: &str) -> Option<Run> {
    let mut run = Run::default();
    let floats = |v: &str| -> Vec<f64> {
        v.split(',')
            .map(|x| x.parse().unwrap_or(f64::NAN))
            .collect()
    };
    for kv in line.strip_prefix("RUN ")?.split_whitespace() {
        let (k, v) = kv.split_once('=')?;
        match k {
            "level" => run.level = v.into(),
            "backend" => run.backend = v.into(),
            "dofs" => run.dofs = v.parse().ok()?,
            "disc" => run.disc = floats(v),
            "pad" => run.pad = floats(v),
            "peaks" => run.stage_peaks = floats(v),
            "total" => run.total = v.parse().ok()?,
            "peak_mb" => run.peak_mb = v.parse().ok()?,
            "factor_mb" => run.factor_mb = v.parse().ok()?,
            "cpu" => run.cpu = v.parse().ok()?,
            "load" => {
                let l = floats(v);
                run.load = (l[0], l.get(1).copied().unwrap_or(f64::NAN));
            }
            "work" => run.work = v.split(';').map(str::to_string).collect(),
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

fn option<'a>(args: &'a [String], key: &str) -> Option<&'a str> {
    args.iter().find_map(|a| a.strip_prefix(key))
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    let interface = match option(&args, "--interface=") {
        Some("node") => InterfaceKind::Node,
        _ => InterfaceKind::Patch,
    };
    let threads = option(&args, "--threads=").and_then(|t| t.parse::<usize>().ok());
    if let Some(n) = threads {
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global();
    }
    if args.first().map(String::as_str) == Some("--child") {
        let backend = match args.get(2).map(String::as_str) {
            Some("arpack") => Backend::Arpack,
            _ => Backend::Lanczos,
        };
        child(&args[1], backend, interface);
        return;
    }
    let positional: Vec<String> = args
        .iter()
        .filter(|a| !a.starts_with("--"))
        .cloned()
        .collect();
    let flags: Vec<String> = args
        .iter()
        .filter(|a| a.starts_with("--"))
        .cloned()
        .collect();
    let levels: Vec<String> = if positional.is_empty() {
        LEVELS.iter().map(|s| s.to_string()).collect()
    } else {
        positional
    };
    let mut backends = vec!["lanczos"];
    if cfg!(feature = "arpack") {
        backends.push("arpack");
    } else {
        eprintln!("(ARPACK backend not compiled in: add --features arpack)");
    }
    println!(
        "# {} interface, {} threads",
        if interface == InterfaceKind::Node {
            "node"
        } else {
            "patch"
        },
        threads.unwrap_or_else(rayon::current_num_threads)
    );
    let exe = std::env::current_exe().expect("own path");
    let mut runs = Vec::new();
    for backend in &backends {
        for level in &levels {
            eprintln!("running {level} / {backend} ...");
            let out = Command::new(&exe)
                .args(["--child", level, backend])
                .args(&flags)
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
    print_tables(&runs);
    for backend in &backends {
        let mine: Vec<&Run> = runs.iter().filter(|r| r.backend == *backend).collect();
        if mine.len() < 2 {
            continue;
        }
        let against = |y: &dyn Fn(&Run) -> f64| {
            slope(
                &mine
                    .iter()
                    .map(|r| (r.dofs as f64, y(r)))
                    .collect::<Vec<_>>(),
            )
        };
        let per_stage: Vec<String> = Stage::ALL
            .iter()
            .enumerate()
            .map(|(k, s)| format!("{} {:.2}", s.label(), against(&|r| r.disc[k] + r.pad[k])))
            .collect();
        println!(
            "\n{backend}: log-log slope against dofs: wall time {:.2}, CPU time {:.2}, peak \
             memory {:.2}, factors {:.2}; stage times (disc + pad) {}",
            against(&|r| r.total),
            against(&|r| r.cpu),
            against(&|r| r.peak_mb),
            against(&|r| r.factor_mb),
            per_stage.join(", ")
        );
    }
}

fn print_tables(runs: &[Run]) {
    let mut head = "| mesh | backend | free dofs |".to_string();
    let mut rule = "|---|---|---|".to_string();
    for s in Stage::ALL {
        head += &format!(" {} |", s.label());
        rule += "---|";
    }
    head += " wall (s) | CPU (s) | CPU / wall | peak (MB) | factors (MB) | load |";
    rule += "---|---|---|---|---|---|";
    println!("\nStage times, disc / pad (s), the two parts at the same time:\n\n{head}\n{rule}");
    for r in runs {
        let mut row = format!("| {} | {} | {} |", r.level, r.backend, r.dofs);
        for (d, p) in r.disc.iter().zip(&r.pad) {
            row += &format!(" {d:.2} / {p:.2} |");
        }
        row += &format!(
            " {:.1} | {:.1} | {:.2} | {:.0} | {:.0} | {:.1}-{:.1} |",
            r.total,
            r.cpu,
            r.cpu / r.total,
            r.peak_mb,
            r.factor_mb,
            r.load.0,
            r.load.1
        );
        println!("{row}");
    }
    let mut head = "| mesh | backend |".to_string();
    let mut rule = "|---|---|".to_string();
    for s in Stage::ALL {
        head += &format!(" {} |", s.label());
        rule += "---|";
    }
    println!("\nPeak resident memory while the disc is in each stage (MB):\n\n{head}\n{rule}");
    for r in runs {
        let mut row = format!("| {} | {} |", r.level, r.backend);
        for p in &r.stage_peaks {
            row += &format!(" {p:.0} |");
        }
        println!("{row}");
    }
    println!(
        "\nEigensolver work (fixed-interface modes):\n\n| mesh | part | interior dofs | nnz(L) | \
         factor flops | solves | solves per mode | block / basis | solves (s) | M products (s) \
         | Ritz, restarts (s) | Sturm (s) |\n|---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for r in runs {
        for w in &r.work {
            let f: Vec<&str> = w.split(':').collect();
            if f.len() < 13 {
                continue;
            }
            let num = |i: usize| f[i].parse::<f64>().unwrap_or(f64::NAN);
            let beside = if f[12] == "true" { ", beside" } else { "" };
            println!(
                "| {} | {} | {} | {:.1}M | {:.2e} | {} | {:.2} | {} / {} | {:.2} | {:.2} | {:.2} | {:.2}{beside} |",
                r.level,
                f[0],
                f[1],
                num(2) / 1e6,
                num(3),
                f[4],
                num(4) / num(5).max(1.0),
                f[6],
                f[7],
                num(8),
                num(9),
                num(10),
                num(11)
            );
        }
    }
}
