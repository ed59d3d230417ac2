//! `firmament completions` and `firmament manpages`: the shell completion scripts and the man
//! pages, generated from the command line's own clap definitions so they cannot drift from it.

use std::path::Path;

use anyhow::{Context, Result};
use clap::CommandFactory;

use crate::cli::{Cli, CompletionsArgs, ManpagesArgs};

/// Prints the completion script for the shell to standard output.
pub(crate) fn run_completions(args: &CompletionsArgs) -> Result<()> {
    let mut command = Cli::command();
    clap_complete::generate(args.shell, &mut command, "firmament", &mut std::io::stdout());
    Ok(())
}

/// Writes `firmament.1` and a page per command (`firmament-render.1`, …) into the folder.
pub(crate) fn run_manpages(args: &ManpagesArgs) -> Result<()> {
    let dir: &Path = &args.dir;
    if !dir.is_dir() {
        anyhow::bail!(
            "--dir {}: not a folder (create it first, e.g. mkdir -p {})",
            dir.display(),
            dir.display()
        );
    }
    clap_mangen::generate_to(Cli::command(), dir)
        .with_context(|| format!("cannot write the man pages into {}", dir.display()))?;
    tracing::info!("wrote the man pages into {}", dir.display());
    Ok(())
}
