//! Untrusted mode (issue 31): a corpus of hostile scenes — absolute paths, `..` escapes, links
//! out of the folder, a glTF buffer and an OBJ material library outside it, a FIFO and
//! `/dev/zero` as textures, a huge time-lapse, a `--reference` that would take hours — each
//! refused (or stopped at the time limit) under `--untrusted` with a non-zero exit, one message
//! naming the key and the rule, no output, and no file outside the folder even looked up (the
//! system calls that take a path are traced with strace); the legitimate ones keep working
//! without the flag.

use std::os::unix::fs::symlink;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use crate::support::fixtures::{coverage_map_scene, gltf_triangle, mesh_scene, png_bytes, texture_scene};
use crate::support::{firmament, names_in, stderr};

/// A scene's folder, `job` (the allowed one), beside a folder `outside` of files it must not
/// reach, in a temporary folder of their own.
struct Folders {
    _top: tempfile::TempDir,
    job: PathBuf,
    outside: PathBuf,
}

/// Writes `bytes` to `path`.
fn write(path: &Path, bytes: impl AsRef<[u8]>) {
    std::fs::write(path, bytes).expect("a fixture file");
}

fn folders() -> Folders {
    let top = tempfile::tempdir().expect("a temporary folder");
    let job = top.path().join("job");
    let outside = top.path().join("outside");
    std::fs::create_dir_all(&job).expect("a folder");
    std::fs::create_dir_all(&outside).expect("a folder");
    let (gltf, bin) = gltf_triangle(2);
    for folder in [&job, &outside] {
        write(&folder.join("real.png"), png_bytes());
        write(&folder.join("tri.bin"), &bin);
        write(&folder.join("m.mtl"), "newmtl red\nKd 1 0 0\n");
    }
    write(&job.join("tri.gltf"), &gltf);
    write(&job.join("escape.gltf"), gltf.replace("tri.bin", "../outside/tri.bin"));
    let file_uri = format!("file://{}", outside.join("tri.bin").display());
    write(&job.join("file_uri.gltf"), gltf.replace("tri.bin", &file_uri));
    let triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    write(&job.join("escape.obj"), format!("mtllib ../outside/m.mtl\n{triangle}"));
    symlink("../outside/real.png", job.join("link.png")).expect("a link");
    symlink("../outside", job.join("shared")).expect("a link");
    let fifo = Command::new("mkfifo")
        .arg(job.join("pipe.png"))
        .status()
        .expect("mkfifo runs");
    assert!(fifo.success());
    Folders {
        _top: top,
        job,
        outside,
    }
}

/// One hostile scene: its text, what the refusal must say, and whether the scene is
/// legitimate for a trusted user (it then checks without the flag).
struct Hostile {
    name: &'static str,
    scene: String,
    expect: &'static [&'static str],
    legitimate: bool,
}

fn corpus(outside: &Path) -> Vec<Hostile> {
    let absolute = outside.join("real.png").display().to_string();
    let flare =
        "[flare]\nenabled = true\nelements = [{ kind = \"image\", file = \"../outside/real.png\", size = 0.1 }]\n";
    let hostile = |name, scene: String, expect, legitimate| Hostile {
        name,
        scene,
        expect,
        legitimate,
    };
    vec![
        hostile(
            "absolute",
            texture_scene(&absolute),
            &["objects[0].texture.file: untrusted mode refuses absolute paths"],
            true,
        ),
        hostile(
            "dot_dot",
            texture_scene("../outside/real.png"),
            &["objects[0].texture.file = \"../outside/real.png\": climbs out of the allowed folder"],
            true,
        ),
        hostile(
            "link_out",
            texture_scene("link.png"),
            &["objects[0].texture.file = \"link.png\": a symbolic link on the way leads out"],
            true,
        ),
        hostile(
            "linked_folder",
            texture_scene("shared/real.png"),
            &["\"shared/real.png\": a symbolic link on the way leads out"],
            true,
        ),
        hostile(
            "gltf_buffer",
            mesh_scene("escape.gltf"),
            &["objects[0].mesh.path", "buffer", "climbs out of the allowed folder"],
            true,
        ),
        hostile(
            "gltf_file_uri",
            mesh_scene("file_uri.gltf"),
            &["objects[0].mesh.path", "climbs out of the allowed folder"],
            true,
        ),
        hostile(
            "obj_material_library",
            mesh_scene("escape.obj"),
            &[
                "objects[0].mesh.path",
                "material library",
                "climbs out of the allowed folder",
            ],
            true,
        ),
        hostile(
            "coverage_map",
            coverage_map_scene("../outside/real.png"),
            &["clouds[0].coverage_map = \"../outside/real.png\": climbs out"],
            true,
        ),
        hostile(
            "flare_image",
            flare.to_owned(),
            &["flare.elements[0].file = \"../outside/real.png\": climbs out"],
            true,
        ),
        hostile(
            "fifo",
            texture_scene("pipe.png"),
            &["objects[0].texture.file", "not a regular file"],
            false,
        ),
        hostile(
            "dev_zero",
            texture_scene("/dev/zero"),
            &["objects[0].texture.file: untrusted mode refuses absolute paths"],
            false,
        ),
    ]
}

/// Runs `firmament -q ARGS` in `dir` under strace, recording every system call that takes a
/// path; returns the output and the path each call was given.
fn traced(dir: &Path, args: &[&str]) -> (Output, Vec<String>) {
    let log = dir.join("strace.log");
    let out = Command::new("strace")
        .args(["-f", "-qq", "-e", "trace=%file", "-o"])
        .arg(&log)
        .arg(env!("CARGO_BIN_EXE_firmament"))
        .arg("-q")
        .args(args)
        .current_dir(dir)
        .env_remove("FIRMAMENT_LOG")
        .output()
        .expect("strace runs (the untrusted-mode tests trace system calls with it)");
    let text = std::fs::read_to_string(&log).expect("strace wrote its log");
    std::fs::remove_file(&log).expect("the log is removed");
    // The first quoted string of a call is the path it was given.
    let paths = text
        .lines()
        .filter_map(|line| line.split('"').nth(1).map(str::to_owned))
        .collect();
    (out, paths)
}

/// The one `error:` line of a failed run, checked for `expect`.
fn refused(out: &Output, code: i32, expect: &[&str], case: &str) {
    let message = stderr(out);
    assert_eq!(out.status.code(), Some(code), "{case}: {message}");
    assert!(
        out.stdout.is_empty(),
        "{case}: printed {:?}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(
        message.starts_with("error: ") && message.lines().count() == 1,
        "{case}: {message}"
    );
    for part in expect {
        assert!(message.contains(part), "{case}: {message:?} lacks {part:?}");
    }
    assert!(!message.contains("panicked"), "{case}: {message}");
}

#[test]
fn hostile_scenes_are_refused_without_looking_outside_the_folder() {
    let Folders { _top, job, outside } = folders();
    let before = names_in(&job);
    for case in corpus(&outside) {
        let scene = format!("{}.toml", case.name);
        write(&job.join(&scene), &case.scene);
        let started = Instant::now();
        let (out, paths) = traced(&job, &["check", &scene, "--untrusted"]);
        refused(&out, 1, case.expect, case.name);
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "{}: took {:?}",
            case.name,
            started.elapsed()
        );
        assert!(
            paths.iter().any(|p| p.ends_with(&scene)),
            "{}: the trace holds no open of the scene: {paths:?}",
            case.name
        );
        let outside_name = outside.file_name().and_then(|n| n.to_str()).expect("a name");
        let reached: Vec<&String> = paths
            .iter()
            .filter(|p| p.contains(outside_name) || p.starts_with("/dev/zero"))
            .collect();
        assert!(reached.is_empty(), "{}: looked up {reached:?}", case.name);
        let message = stderr(&out);
        assert!(
            !message.contains(&*outside.to_string_lossy()),
            "{}: {message}",
            case.name
        );
        if case.legitimate {
            let out = firmament(&job, &["-q", "check", &scene]);
            assert!(
                out.status.success(),
                "{} without --untrusted: {}",
                case.name,
                stderr(&out)
            );
        }
        std::fs::remove_file(job.join(&scene)).expect("the scene is removed");
    }
    // A render and an environment map refuse the same way, before any output exists.
    write(&job.join("s.toml"), texture_scene("link.png"));
    for (command, output) in [("render", "out.png"), ("envmap", "out.exr")] {
        let out = firmament(&job, &["-q", command, "s.toml", "--untrusted", "-o", output]);
        refused(&out, 1, &["symbolic link on the way leads out"], command);
    }
    std::fs::remove_file(job.join("s.toml")).expect("the scene is removed");
    assert_eq!(names_in(&job), before, "files were left behind");
}

#[test]
fn files_inside_the_folder_load_under_their_limits() {
    let Folders { _top, job, .. } = folders();
    write(&job.join("tex.toml"), texture_scene("real.png"));
    write(&job.join("gltf.toml"), mesh_scene("tri.gltf"));
    for scene in ["tex.toml", "gltf.toml"] {
        let out = firmament(&job, &["-q", "check", scene, "--untrusted"]);
        assert!(out.status.success(), "{scene}: {}", stderr(&out));
    }
    // A link inside the folder is followed.
    symlink("real.png", job.join("alias.png")).expect("a link");
    write(&job.join("alias.toml"), texture_scene("alias.png"));
    let out = firmament(&job, &["-q", "check", "alias.toml", "--untrusted"]);
    assert!(out.status.success(), "{}", stderr(&out));
    // --asset-root widens the folder: the scene in `job` may then reach `../outside`.
    write(&job.join("up.toml"), texture_scene("../outside/real.png"));
    let out = firmament(&job, &["-q", "check", "up.toml", "--untrusted", "--asset-root", ".."]);
    assert!(out.status.success(), "{}", stderr(&out));

    // Each budget refuses, names its flag, and yields to it.
    let wide = image::RgbImage::new(4097, 1);
    wide.save(job.join("wide.png")).expect("a PNG");
    write(&job.join("wide.toml"), texture_scene("wide.png"));
    let quad = "[[objects]]\nmesh = { kind = \"quad\", size = 1.0, subdivisions = 1024 }\n";
    write(&job.join("quad.toml"), quad);
    // (the run, what it must say, the flag that lifts the limit, a value that does).
    let cases: [(&[&str], &[&str], &str, &str); 3] = [
        (
            &["check", "wide.toml", "--untrusted"],
            &[
                "the image width is 4097 pixels",
                "AssetLimits::max_texture_side",
                "--max-texture-side",
            ],
            "--max-texture-side",
            "8192",
        ),
        (
            &["check", "tex.toml", "--untrusted", "--max-file-bytes", "10"],
            &["untrusted mode's limit of 10 bytes", "--max-file-bytes"],
            "--max-file-bytes",
            "1000000",
        ),
        (
            &["check", "quad.toml", "--untrusted"],
            &["triangles of built-in shapes", "--max-triangles"],
            "--max-triangles",
            "4000000",
        ),
    ];
    for (args, expect, flag, raised) in cases {
        let mut all = vec!["-q"];
        all.extend(args);
        let out = firmament(&job, &all);
        refused(&out, 1, expect, flag);
        all.retain(|a| !a.starts_with("--max-"));
        all.retain(|a| *a != "10");
        all.extend([flag, raised]);
        let out = firmament(&job, &all);
        assert!(out.status.success(), "{flag} {raised}: {}", stderr(&out));
    }
}

#[test]
fn requests_over_the_budgets_are_refused_before_any_work() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let dir = dir.path();
    let cases: [(&[&str], &[&str]); 5] = [
        (
            &[
                "timelapse",
                "--untrusted",
                "--from",
                "2024-03-20T06:00Z",
                "--to",
                "2024-03-21T06:00Z",
                "--frames",
                "100000",
                "-o",
                "lapse",
            ],
            &[
                "--frames = 100000: over untrusted mode's limit of 240 frames",
                "--max-frames",
            ],
        ),
        (
            &[
                "render",
                "--untrusted",
                "--width",
                "4096",
                "--height",
                "4096",
                "-o",
                "big.png",
            ],
            &[
                "the image is 4096x4096 = 16777216 pixels, over untrusted mode's limit",
                "--max-pixels",
            ],
        ),
        (
            &[
                "render",
                "--untrusted",
                "--preset",
                "earth-noon",
                "--reference",
                "--width",
                "1920",
                "--height",
                "1080",
                "-o",
                "ref.exr",
            ],
            &[
                "the reference would trace 530841600 paths (256 paths per pixel x 2073600 pixels)",
                "--max-paths",
            ],
        ),
        (
            &[
                "sky-sample",
                "--untrusted",
                "--reference",
                "--paths",
                "10000000",
                "--altitude",
                "0",
                "--sun-zenith",
                "30",
                "--view-zenith",
                "45",
            ],
            &["the reference would trace 10000000 paths", "--max-paths"],
        ),
        (
            &["render", "--untrusted", "--asset-root", "missing", "-o", "x.png"],
            &["--asset-root: the allowed folder", "missing"],
        ),
    ];
    for (args, expect) in cases {
        let mut all = vec!["-q"];
        all.extend(args);
        let started = Instant::now();
        let out = firmament(dir, &all);
        refused(&out, 1, expect, args[0]);
        assert!(
            started.elapsed() < Duration::from_secs(30),
            "{args:?} took {:?}",
            started.elapsed()
        );
    }
    // The budgets' flags belong to untrusted mode.
    let out = firmament(dir, &["-q", "render", "--max-pixels", "5", "-o", "x.png"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("--untrusted"), "{}", stderr(&out));
    assert!(names_in(dir).is_empty(), "files were written: {:?}", names_in(dir));
}

#[test]
fn the_time_limit_stops_cleanly_with_its_own_status() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let dir = dir.path();
    // Hours of reference work on two cores.
    let started = Instant::now();
    let out = firmament(
        dir,
        &[
            "-q",
            "render",
            "--untrusted",
            "--max-paths",
            "1000000000",
            "--time-limit",
            "2",
            "--preset",
            "earth-noon",
            "--reference",
            "--paths",
            "65536",
            "--width",
            "64",
            "--height",
            "64",
            "-o",
            "ref.exr",
        ],
    );
    let elapsed = started.elapsed();
    refused(
        &out,
        124,
        &["stopped at the time limit of 2 s (--time-limit)"],
        "reference",
    );
    assert!(elapsed < Duration::from_secs(20), "stopped after {elapsed:?}");
    assert!(names_in(dir).is_empty(), "files were written: {:?}", names_in(dir));

    // A time-lapse stopped while it writes frames keeps only whole ones.
    let out = firmament(
        dir,
        &[
            "-q",
            "timelapse",
            "--untrusted",
            "--time-limit",
            "4",
            "--preset",
            "earth-sunset",
            "--from",
            "2024-03-20T06:00Z",
            "--to",
            "2024-03-20T18:00Z",
            "--frames",
            "240",
            "--width",
            "64",
            "--height",
            "36",
            "-o",
            "lapse",
        ],
    );
    refused(&out, 124, &["stopped at the time limit of 4 s"], "timelapse");
    let lapse = dir.join("lapse");
    let mut names = if lapse.is_dir() { names_in(&lapse) } else { Vec::new() };
    names.retain(|n| n != "timelapse.json");
    for name in &names {
        assert!(
            name.starts_with("frame_") && name.ends_with(".png"),
            "left {name} in {names:?}"
        );
        let frame = image::open(lapse.join(name)).unwrap_or_else(|e| panic!("{name} is not whole: {e}"));
        assert_eq!((frame.width(), frame.height()), (64, 36), "{name}");
    }
}
