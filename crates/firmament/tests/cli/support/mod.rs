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

/// The file names in `dir`, sorted.
pub(crate) fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("readable")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// What the process wrote to standard error.
pub(crate) fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Every float of `path`'s first RGBA layer, read by the `exr` crate, rows top first, and the
/// image's width.
pub(crate) fn exr_image(path: &Path) -> (usize, Vec<f32>) {
    let image = exr::prelude::read_first_rgba_layer_from_file(
        path,
        |size, _| (size.width(), vec![0.0_f32; size.width() * size.height() * 4]),
        |(width, floats), at, (r, g, b, a): (f32, f32, f32, f32)| {
            let i = (at.y() * *width + at.x()) * 4;
            floats[i..i + 4].copy_from_slice(&[r, g, b, a]);
        },
    )
    .unwrap_or_else(|e| panic!("{}: not an EXR the exr crate reads: {e}", path.display()));
    image.layer_data.channel_data.pixels
}

/// Every float of `path`'s first RGBA layer ([`exr_image`] without the width).
pub(crate) fn exr_floats(path: &Path) -> Vec<f32> {
    exr_image(path).1
}
