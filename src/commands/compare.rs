//! `squeal compare` (being written).

use anyhow::{Result, bail};
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
pub struct CompareArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
}

pub fn run(_args: CompareArgs) -> Result<ExitCode> {
    bail!("squeal compare is not written yet")
}
