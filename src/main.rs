//! `squeal`: disc-brake squeal prediction from tetrahedral meshes to limit cycles.
//!
//! Run `squeal --help` for the commands. Every command reports errors with their context and
//! exits non-zero; output files are written atomically.

// The argument structs' doc comments are the command line's help text, which shows `<out>`,
// `[stability]` and the like literally: rustdoc must not read them as HTML or links.
#![allow(rustdoc::invalid_html_tags, rustdoc::broken_intra_doc_links)]

mod commands;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "squeal",
    version,
    about = "Disc-brake squeal: meshes -> Craig-Bampton brake -> stability -> CHBM limit cycles"
)]
struct Cli {
    /// Worker threads (default: all cores). Results are bit-identical for any count.
    #[arg(long, global = true)]
    threads: Option<usize>,
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
    /// Parametric stability studies: piston pressure, contact stiffness, modal damping
    Study(commands::study::StudyArgs),
    /// CHBM against time integration: accuracy, speed, robustness
    Compare(commands::compare::CompareArgs),
    /// The whole pipeline on a scene, with a report folder
    Run(commands::run::RunArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // Dense kernels run sequentially: their results would otherwise depend on the thread
    // count. Parallelism comes from independent tasks (rayon) and the sparse factorizations.
    faer::set_global_parallelism(faer::Par::Seq);
    if let Some(n) = cli.threads {
        // A second initialisation cannot happen here: this is the only call.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(n.max(1))
            .build_global();
    }
    let result = match cli.command {
        Command::Mesh(cmd) => commands::mesh::run(cmd),
        Command::Fe(cmd) => commands::fe::run(cmd),
        Command::Reduce(args) => commands::reduce::run(args),
        Command::Stability(args) => commands::stability::run(args),
        Command::Chbm(args) => commands::chbm::run(args),
        Command::Branch(args) => commands::branch::run(args),
        Command::Study(args) => commands::study::run(args),
        Command::Compare(args) => commands::compare::run(args),
        Command::Run(args) => commands::run::run(args),
    };
    match result {
        Ok(code) => code,
        Err(err) => {
            eprintln!("error: {err:#}");
            ExitCode::FAILURE
        }
    }
}
