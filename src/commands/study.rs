//! `squeal study` (being written).

use anyhow::{Result, bail};
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
pub struct StudyArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
}

pub fn run(_args: StudyArgs) -> Result<ExitCode> {
    bail!("squeal study is not written yet")
}
