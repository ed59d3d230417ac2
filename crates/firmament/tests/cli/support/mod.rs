//! What the CLI tests share: running the binary and reading what it said, and fixtures.

pub(crate) mod fixtures;

use std::path::Path;
use std::process::{Command, Output};

/// Runs the `firmament` binary in `dir` with `args` (no `FIRMAMENT_LOG` from the environment).
pub(crate) fn firmament(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_firmament"))
        .args(args)
        .current_dir(dir)
        .env_remove("FIRMAMENT_LOG")
        .output()
        .expect("the firmament binary runs")
}

/// What the process wrote to standard error.
pub(crate) fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The names of the entries of `dir`, sorted.
pub(crate) fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("the folder reads")
        .map(|e| e.expect("an entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}
