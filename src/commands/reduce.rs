//! `squeal reduce`: Craig–Bampton reduction of a disc and a pad to the reduced brake.

use anyhow::{Result, bail};
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
pub struct ReduceArgs {
    /// Disc mesh (.inp or .msh)
    pub disc: PathBuf,
    /// Pad mesh (.inp or .msh)
    pub pad: PathBuf,
    /// Output reduced model (.rom)
    #[arg(short, long, default_value = "brake.rom")]
    pub output: PathBuf,
}

pub fn run(_args: ReduceArgs) -> Result<ExitCode> {
    bail!("squeal reduce is not written yet")
}
