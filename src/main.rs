//! `squeal`: disc-brake squeal prediction from tetrahedral meshes to limit cycles.
//!
//! Run `squeal --help` for the commands. Every command reports errors with their context and
//! exits non-zero; output files are written atomically.

// The argument structs' doc comments are the command line's help text, which shows `<out>`,
// `[stability]` and the like literally: rustdoc must not read them as HTML or links.
#![allow(rustdoc::invalid_html_tags, rustdoc::broken_intra_doc_links)]

mod commands;
mod ending;
mod progress;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// The exit codes, as `squeal --help` lists them.
const EXIT_CODES: &str = "Exit codes:
  0  success
  1  an error (the message names the file, and the line where there is one)
  2  a usage error: an unknown option or a missing argument (the message shows the usage)
  3  chbm, run: no limit cycle converged (the outputs are written and say why)
  4  mesh info: a mesh has errors (inverted elements, ...), listed in the output
  101  an internal error (a bug): the run stopped, the message says where
  130  interrupted (Ctrl-C): the run stopped, no partial file is left
  141  the standard output was closed (`| head`): the run stopped, no partial file is left";

#[derive(Parser)]
#[command(
    name = "squeal",
    version,
    about = "Disc-brake squeal: meshes -> Craig-Bampton brake -> stability -> CHBM limit cycles",
    after_help = EXIT_CODES
)]
struct Cli {
    /// Worker threads (default, or 0: all cores; at most 4 per core). Results are
    /// bit-identical for any count.
    #[arg(long, global = true, value_parser = thread_count)]
    threads: Option<usize>,
    /// stability, chbm, branch, compare, run: write into an output folder that holds files no
    /// squeal run wrote (they may be replaced), or whose manifest does not read
    #[arg(long, global = true)]
    force: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Inspect and convert tet10 meshes (Abaqus .inp, Gmsh .msh)
    #[command(subcommand)]
    Mesh(commands::mesh::MeshCommand),
    /// Finite-element matrices of a mesh
    #[command(subcommand)]
    Fe(commands::fe::FeCommand),
    /// Craig-Bampton reduction of a disc and a pad to the reduced brake (.rom)
    Reduce(commands::reduce::ReduceArgs),
    /// Static equilibrium, complex eigenvalues against friction and the Hopf point mu0
    Stability(commands::stability::StabilityArgs),
    /// Limit cycle by the Constrained Harmonic Balance Method
    Chbm(commands::chbm::ChbmArgs),
    /// The branch of limit cycles from the Hopf point, with their stability: where and how
    /// loud the brake squeals
    Branch(commands::branch::BranchArgs),
    /// The squeal mode's complex nonlinear mode: frequency and modal damping against amplitude,
    /// the limit cycles where the damping vanishes
    Nlmode(commands::nlmode::NlModeArgs),
    /// Parametric stability studies: piston pressure, contact stiffness, modal damping
    Study(commands::study::StudyArgs),
    /// CHBM against time integration: accuracy, speed, robustness
    Compare(commands::compare::CompareArgs),
    /// The whole pipeline on a scene, with a report folder
    Run(commands::run::RunArgs),
}

/// `--threads N`: 0 (all cores) up to 4 threads per core (at least 4, at most 1024). More
/// threads than that only add memory and switching, and a mistyped count (100000) would start
/// them all.
fn thread_count(s: &str) -> Result<usize, String> {
    let n: usize = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a thread count (a whole number, 0 for all cores)"))?;
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    let most = (4 * cores).clamp(4, 1024);
    if n > most {
        return Err(format!(
            "{n} threads on {cores} core(s): at most {most} (4 per core); 0 or leaving --threads out uses all cores"
        ));
    }
    Ok(n)
}

fn main() -> ExitCode {
    // A panic (a closed output pipe, a bug) ends the run as cleanly as Ctrl-C (ending.rs).
    ending::install();
    // Ctrl-C (SIGINT): the writes under way are dropped, the output folder's manifest says the
    // run was interrupted and its lock is released, then exit 130 (squeal_pipeline::folder::interrupt).
    let _ = ctrlc::set_handler(|| {
        eprintln!(
            "\ninterrupted (Ctrl-C): no partial file is left; the output folder's manifest marks this run as interrupted"
        );
        squeal_pipeline::folder::interrupt::stop("interrupted (Ctrl-C)");
    });
    let cli = Cli::parse();
    // Dense kernels run sequentially: their results would otherwise depend on the thread
    // count. Parallelism comes from independent tasks (rayon) and the sparse factorizations.
    faer::set_global_parallelism(faer::Par::Seq);
    if let Some(n) = cli.threads {
        // A second initialisation cannot happen here: this is the only call.
        // 0 is rayon's default: one thread per core.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global();
    }
    commands::FORCE.store(cli.force, std::sync::atomic::Ordering::Relaxed);
    let result = match cli.command {
        Command::Mesh(cmd) => commands::mesh::run(cmd),
        Command::Fe(cmd) => commands::fe::run(cmd),
        Command::Reduce(args) => commands::reduce::run(args),
        Command::Stability(args) => commands::stability::run(args),
        Command::Chbm(args) => commands::chbm::run(args),
        Command::Branch(args) => commands::branch::run(args),
        Command::Nlmode(args) => commands::nlmode::run(args),
        Command::Study(args) => commands::study::run(args),
        Command::Compare(args) => commands::compare::run(args),
        Command::Run(args) => commands::run::run(args),
    };
    // The output folder's manifest records how the run ended, and its lock is released.
    let status = match &result {
        Ok(_) => "finished".to_string(),
        Err(err) => format!("failed: {}", message(err)),
    };
    squeal_pipeline::folder::release_all(&status);
    match result {
        Ok(code) => code,
        Err(err) => {
            eprintln!("error: {}", message(&err));
            ExitCode::FAILURE
        }
    }
}

/// The error and its causes joined by ": ", each piece once: a cause whose text its parent's
/// message already contains (an error that shows its source in its own message) is skipped.
fn message(err: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in err.chain() {
        let text = cause.to_string();
        if out.contains(&text) {
            continue;
        }
        if !out.is_empty() {
            out.push_str(": ");
        }
        out.push_str(&text);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, thiserror::Error)]
    #[error("reading x.toml: {source}")]
    struct Repeats {
        source: std::io::Error,
    }

    /// An error that shows its source in its own message (and `source()` returns it) prints
    /// the reason once; context added by the command stays.
    #[test]
    fn each_piece_of_an_error_chain_is_printed_once() {
        let os = std::io::Error::from(std::io::ErrorKind::NotFound);
        let reason = os.to_string();
        let err = anyhow::Error::from(Repeats { source: os }).context("the scene");
        let shown = message(&err);
        assert_eq!(shown.matches(&reason).count(), 1, "{shown}");
        assert!(shown.starts_with("the scene: reading x.toml: "), "{shown}");
    }
}
