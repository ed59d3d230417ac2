//! Determinism (issue 10): the same scene, size and adapter give byte-identical PNG and EXR files
//! from one run to the next, and the f64 reference gives byte-identical files on 1 and 2 rayon
//! threads (each pixel's Monte Carlo paths are seeded by its ray and summed in a fixed order, so
//! neither how rayon splits the work nor the order threads finish changes a bit). Sizes are tiny:
//! CI renders on llvmpipe.

use std::path::Path;
use std::process::Command;

use crate::support::{firmament, stderr};

/// The bytes of `file` in `dir` after `firmament ARGS -o FILE` (with `env`) succeeds.
fn render(dir: &Path, args: &[&str], file: &str, env: &[(&str, &str)]) -> Vec<u8> {
    let _ = std::fs::remove_file(dir.join(file));
    let out = if env.is_empty() {
        firmament(dir, &[args, &["-q", "-o", file]].concat())
    } else {
        Command::new(env!("CARGO_BIN_EXE_firmament"))
            .args(args)
            .args(["-q", "-o", file])
            .current_dir(dir)
            .env_remove("FIRMAMENT_LOG")
            .envs(env.iter().copied())
            .output()
            .expect("the firmament binary runs")
    };
    assert!(out.status.success(), "{args:?} -o {file}: {}", stderr(&out));
    let bytes = std::fs::read(dir.join(file)).expect("the output file");
    assert!(!bytes.is_empty(), "{file} is empty");
    bytes
}

/// Whether two files' bytes are the same; the first difference otherwise, for the message.
fn first_difference(a: &[u8], b: &[u8]) -> Option<String> {
    if a == b {
        return None;
    }
    let at = a
        .iter()
        .zip(b)
        .position(|(x, y)| x != y)
        .unwrap_or(a.len().min(b.len()));
    Some(format!(
        "{} vs {} bytes, first difference at byte {at}",
        a.len(),
        b.len()
    ))
}

#[test]
fn gpu_renders_are_byte_identical_from_run_to_run() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scenes: [(&str, &[&str]); 2] = [
        // The gradient sky with its sun.
        (
            "dusk",
            &["render", "--preset", "dusk", "--width", "48", "--height", "27"],
        ),
        // The physical atmosphere with objects (aerial perspective, sky lighting) and lens flares
        // (occlusion sampled on the GPU).
        (
            "earth-objects",
            &[
                "render",
                "--preset",
                "earth-objects",
                "--set",
                "flare.enabled=true",
                "--width",
                "48",
                "--height",
                "27",
            ],
        ),
    ];
    for (name, args) in scenes {
        for extension in ["png", "exr"] {
            let first = render(dir.path(), args, &format!("a.{extension}"), &[]);
            let second = render(dir.path(), args, &format!("b.{extension}"), &[]);
            if let Some(difference) = first_difference(&first, &second) {
                panic!("{name}: two {extension} renders differ: {difference}");
            }
        }
    }
}

#[test]
fn the_reference_is_byte_identical_on_one_and_two_threads() {
    let dir = tempfile::tempdir().expect("temp dir");
    let args = |width: &'static str, height: &'static str| {
        [
            "render",
            "--preset",
            "earth-noon",
            "--set",
            "camera.pitch=10",
            "--reference",
            "--paths",
            "4",
            "--width",
            width,
            "--height",
            height,
        ]
    };
    // EXR holds the radiance itself (f32): the strictest comparison. The PNG goes through the
    // exposure and tone curve after it, so a smaller one suffices.
    for (extension, (width, height)) in [("exr", ("8", "6")), ("png", ("4", "3"))] {
        let file = format!("reference.{extension}");
        let one = render(dir.path(), &args(width, height), &file, &[("RAYON_NUM_THREADS", "1")]);
        let two = render(dir.path(), &args(width, height), &file, &[("RAYON_NUM_THREADS", "2")]);
        if let Some(difference) = first_difference(&one, &two) {
            panic!("the reference's {extension} differs on 1 and 2 threads: {difference}");
        }
    }
}
