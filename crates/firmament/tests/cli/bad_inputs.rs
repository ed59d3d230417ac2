//! The bad-input corpus (issue 10): malformed and hostile scene files, broken meshes and textures,
//! absurd sizes, bad dates and times, unwritable outputs — across every command. Each case runs
//! the real binary in a folder of its own holding only the case's input files, and must give a
//! non-zero exit status (1 for a bad scene, output or GPU; 2 for a bad argument), exactly one
//! message on standard error that starts with `error:` and names the key, flag or rule, no panic,
//! no backtrace, no log of a GPU error, nothing on standard output, and no new file.
//!
//! The cases of `commands.rs` (`every_bad_input_fails_cleanly_and_writes_nothing`: a TOML syntax
//! error, an unknown key, a string for a number, `nan`, a missing scene file, an unknown preset, zero
//! and huge `--width`/`--height`, a camera under the ground, `--time 25:00`, a `.jpg` output, an
//! output in a missing folder or under a file, an unknown backend), of `timelapse.rs` (`yesterday`,
//! `2024-02-30`, `--from` after `--to`, `--frames 0`, an output that is a file), of `sun.rs` and of
//! `view.rs` are not repeated here; together they make the corpus. None of these needs the GPU:
//! every one fails before an adapter is asked for.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::support::fixtures::{cloud_scene, coverage_map_scene, gltf_triangle, mesh_scene, png_bytes, texture_scene};
use crate::support::{firmament, stderr};

/// An input file (or folder) a case creates in its folder before running.
enum Fixture {
    /// A file with these bytes.
    File(&'static str, Vec<u8>),
    /// An empty folder.
    Dir(&'static str),
}

/// One bad input: what to create, how to run, what must be said.
struct Case {
    name: &'static str,
    fixtures: Vec<Fixture>,
    args: Vec<String>,
    env: Vec<(&'static str, &'static str)>,
    /// The process's address-space limit (`ulimit -v`), KiB.
    address_space: Option<u64>,
    code: i32,
    expect: Vec<&'static str>,
}

/// A case running `args` (after `-q`), expecting exit status `code` and every text of `expect` in
/// the message.
fn case(name: &'static str, code: i32, args: &[&str], expect: &[&'static str]) -> Case {
    Case {
        name,
        fixtures: Vec::new(),
        args: args.iter().map(|a| (*a).to_owned()).collect(),
        env: Vec::new(),
        address_space: None,
        code,
        expect: expect.to_vec(),
    }
}

impl Case {
    fn file(mut self, name: &'static str, contents: impl Into<Vec<u8>>) -> Self {
        self.fixtures.push(Fixture::File(name, contents.into()));
        self
    }

    fn dir(mut self, name: &'static str) -> Self {
        self.fixtures.push(Fixture::Dir(name));
        self
    }

    fn with_args(mut self, args: Vec<String>) -> Self {
        self.args = args;
        self
    }

    fn env(mut self, key: &'static str, value: &'static str) -> Self {
        self.env.push((key, value));
        self
    }

    /// Runs the case under `ulimit -v kib` (through `sh`), as a machine short of memory.
    fn address_space(mut self, kib: u64) -> Self {
        self.address_space = Some(kib);
        self
    }
}

/// Every path under `dir`, sorted, relative to it.
fn tree(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(folder) = stack.pop() {
        for entry in std::fs::read_dir(&folder).expect("readable folder") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                stack.push(path.clone());
            }
            out.push(path.strip_prefix(dir).expect("under dir").to_path_buf());
        }
    }
    out.sort();
    out
}

/// What a finished case left: exit status (`None`: killed by a signal), stdout, stderr.
struct Ran {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

/// Runs `firmament -q ARGS` in `dir` with no display (so `view` can never open a window), no
/// `FIRMAMENT_LOG`, `env` and the case's address-space limit; killed after two minutes. Output
/// goes to files in `scratch`, so a flood of it cannot block the process.
fn run(dir: &Path, scratch: &Path, case: &Case) -> Ran {
    let (args, env) = (&case.args, &case.env);
    let (out_path, err_path) = (scratch.join("stdout"), scratch.join("stderr"));
    let binary = env!("CARGO_BIN_EXE_firmament");
    let mut command = match case.address_space {
        None => Command::new(binary),
        Some(kib) => {
            let mut sh = Command::new("sh");
            sh.args(["-c", &format!("ulimit -v {kib} && exec \"$0\" \"$@\""), binary]);
            sh
        }
    };
    let mut child = command
        .arg("-q")
        .args(args)
        .current_dir(dir)
        .env_remove("FIRMAMENT_LOG")
        .env_remove("FIRMAMENT_MAX_PIXELS")
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .envs(env.iter().copied())
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).expect("stdout file"))
        .stderr(std::fs::File::create(&err_path).expect("stderr file"))
        .spawn()
        .expect("the firmament binary runs");
    let deadline = Instant::now() + Duration::from_secs(120);
    let status = loop {
        if let Some(status) = child.try_wait().expect("waits") {
            break Some(status);
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let read = |p: &Path| String::from_utf8_lossy(&std::fs::read(p).expect("output file")).into_owned();
    Ran {
        code: status.and_then(|s| s.code()),
        stdout: read(&out_path),
        stderr: read(&err_path),
    }
}

/// What is wrong with how a case ended, if anything.
fn problems(case: &Case, ran: &Ran, before: &[PathBuf], after: &[PathBuf]) -> Vec<String> {
    let mut wrong = Vec::new();
    let err = &ran.stderr;
    if ran.code != Some(case.code) {
        wrong.push(format!("exit status {:?}, expected {}", ran.code, case.code));
    }
    if !err.starts_with("error: ") {
        wrong.push("the message does not start with `error: `".to_owned());
    }
    let errors = err.lines().filter(|l| l.starts_with("error")).count();
    if errors != 1 {
        wrong.push(format!("{errors} lines start with `error`, expected one"));
    }
    for bad in ["panicked", "backtrace", "RUST_BACKTRACE", "Validation Error", " ERROR "] {
        if err.contains(bad) {
            wrong.push(format!("the message contains `{bad}`"));
        }
    }
    if err.chars().count() > 2_000 {
        wrong.push(format!("the message is {} characters long", err.chars().count()));
    }
    for text in &case.expect {
        if !err.contains(text) {
            wrong.push(format!("the message lacks `{text}`"));
        }
    }
    if !ran.stdout.is_empty() {
        wrong.push(format!("printed on stdout: {}", ran.stdout));
    }
    if before != after {
        wrong.push(format!("the folder held {before:?} and now holds {after:?}"));
    }
    wrong
}

/// `n` copies of `item`, comma-separated, in brackets: a TOML array.
fn toml_array(item: &str, n: usize) -> String {
    format!("[{}]", vec![item; n].join(", "))
}

/// A time-lapse's arguments around `extra` (a small, valid run unless `extra` breaks it).
fn timelapse(extra: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = [
        "timelapse",
        "--from",
        "2024-03-20T16:00:00Z",
        "--to",
        "2024-03-20T17:00:00Z",
        "--frames",
        "2",
        "--width",
        "16",
        "--height",
        "9",
    ]
    .iter()
    .map(|a| (*a).to_owned())
    .collect();
    for pair in extra.chunks(2) {
        match args.iter().position(|a| a == pair[0]) {
            Some(i) if pair.len() == 2 => args[i + 1] = pair[1].to_owned(),
            _ => args.extend(pair.iter().map(|a| (*a).to_owned())),
        }
    }
    args
}

/// A sky-sample from the f64 reference (no GPU), valid unless what follows breaks it.
const SKY_SAMPLE: [&str; 8] = [
    "sky-sample",
    "--reference",
    "--altitude",
    "0",
    "--sun-zenith",
    "30",
    "--view-zenith",
    "60",
];

fn corpus() -> Vec<Case> {
    let nine_suns = format!(
        "preset = \"earth-noon\"\nsuns = {}\n",
        toml_array("{ elevation = 10.0 }", 9)
    );
    let nine_lights = format!("lights = {}\n", toml_array("{ diffuse = [1.0, 1.0, 1.0] }", 9));
    let nine_clouds = format!(
        "preset = \"earth-clouds\"\nclouds = {}\n",
        toml_array(
            "{ kind = \"stratus\", bottom = 500.0, top = 900.0, coverage = 1.0, density = 0.02 }",
            9
        )
    );
    let many_flare_elements = format!(
        "[flare]\nenabled = true\nelements = {}\n",
        toml_array("{ kind = \"glow\", size = 0.1 }", 65)
    );
    let too_many_objects = format!(
        "objects = {}\n",
        toml_array("{ mesh = { kind = \"cube\", size = 1.0 } }", 16_385)
    );
    let deep = format!("a = {}{}\n", "[".repeat(100_000), "]".repeat(100_000));
    let long_value = format!("[camera]\nfov_y = \"{}\"\n", "x".repeat(1_000_000));
    let png = png_bytes();
    let truncated_png = png[..png.len() / 2].to_vec();
    let (gltf, gltf_bin) = gltf_triangle(7);
    let binary: Vec<u8> = (0..=255_u8).cycle().take(4096).collect();
    let garbage_obj = "v 0 0 0\nv 1 0 0\nthis is not an OBJ line\nf 1 2 9\n";

    let mut cases = vec![
        // ---- render: malformed and hostile scene files --------------------------------------
        case(
            "render: an unterminated string",
            1,
            &["render", "s.toml"],
            &["s.toml is not valid TOML"],
        )
        .file("s.toml", "[camera]\nfov_y = \"40\n"),
        case(
            "render: a duplicate key",
            1,
            &["render", "s.toml"],
            &["s.toml is not valid TOML", "duplicate key"],
        )
        .file("s.toml", "[camera]\nfov_y = 40.0\nfov_y = 50.0\n"),
        case(
            "render: binary garbage for a scene",
            1,
            &["render", "s.toml"],
            &["cannot read scene file s.toml", "UTF-8"],
        )
        .file("s.toml", binary.clone()),
        case(
            "render: arrays nested 100000 deep (the message is cut short)",
            1,
            &["render", "s.toml"],
            &["s.toml is not valid TOML", "characters left out"],
        )
        .file("s.toml", deep),
        case(
            "render: a megabyte-long value (the message is cut short)",
            1,
            &["render", "s.toml"],
            &["camera.fov_y: invalid type: string", "characters left out"],
        )
        .file("s.toml", long_value),
        case(
            "render: a 17 MiB scene file",
            1,
            &["render", "s.toml"],
            &["cannot read scene file s.toml: 17825792 bytes, over the limit of 16 MiB"],
        )
        .file("s.toml", vec![b'#'; 17 << 20]),
        case(
            "render: a folder for the scene file",
            1,
            &["render", "s.toml"],
            &["cannot read scene file s.toml"],
        )
        .dir("s.toml"),
        case(
            "render: an unknown table",
            1,
            &["render", "s.toml"],
            &["camra: unknown key (did you mean `camera`?)"],
        )
        .file("s.toml", "[camra]\nfov_y = 40.0\n"),
        case(
            "render: an array for a number",
            1,
            &["render", "s.toml"],
            &["camera.fov_y: invalid type: sequence, expected f64"],
        )
        .file("s.toml", "[camera]\nfov_y = [1.0, 2.0]\n"),
        case(
            "render: a position of two components",
            1,
            &["render", "s.toml"],
            &["lights[0].position: invalid length 2"],
        )
        .file("s.toml", "[[lights]]\nposition = [0.0, 1.0]\n"),
        // ---- render: NaN, infinities, negatives -------------------------------------------------
        case(
            "render: fov_y = -inf",
            1,
            &["render", "s.toml"],
            &["camera.fov_y = -inf: must be in (0, 180) degrees"],
        )
        .file("s.toml", "[camera]\nfov_y = -inf\n"),
        case(
            "render: exposure = inf",
            1,
            &["render", "--set", "display.exposure=inf"],
            &["display.exposure = inf: must be a finite number > 0"],
        ),
        case(
            "render: a negative exposure",
            1,
            &["render", "s.toml"],
            &["display.exposure = -1: must be a finite number > 0"],
        )
        .file("s.toml", "[display]\nexposure = -1.0\n"),
        case(
            "render: auto-exposure bounds reversed",
            1,
            &[
                "render",
                "--set",
                "display.auto_ev_min=12",
                "--set",
                "display.auto_ev_max=3",
            ],
            &["display.auto_ev_min = 12: must be <= display.auto_ev_max (3)"],
        ),
        case(
            "render: a NaN auto-exposure bound",
            1,
            &["render", "--set", "display.auto_ev_max=nan"],
            &["display.auto_ev_max = NaN: must be in [-20, 40] (EV at ISO 100)"],
        ),
        case(
            "render: a negative adaptation speed",
            1,
            &["render", "--set", "display.auto_speed_down=-1"],
            &["display.auto_speed_down = -1: must be a finite number > 0 EV per second"],
        ),
        case(
            "completions: an unknown shell",
            2,
            &["completions", "tcsh"],
            &["invalid value 'tcsh'"],
        ),
        case(
            "manpages: no such folder",
            1,
            &["manpages", "--dir", "man/pages"],
            &["--dir man/pages: not a folder"],
        ),
        case(
            "render: a negative bloom",
            1,
            &["render", "--set", "display.bloom=-0.1"],
            &["display.bloom = -0.1: must be in [0, 1]"],
        ),
        case(
            "render: an unknown exposure mode",
            1,
            &["render", "--set", "display.exposure_mode=program"],
            &["exposure_mode", "manual", "auto"],
        ),
        case(
            "render: bloom in a 16-bit PNG",
            1,
            &["render", "--set", "display.bloom=0.1", "--png-bits", "16"],
            &["display.bloom = 0.1: --png-bits 16"],
        ),
        case(
            "render: a NaN planet radius",
            1,
            &["render", "s.toml"],
            &["planet.radius = NaN: must be a finite number > 0 metres"],
        )
        .file("s.toml", "preset = \"earth-noon\"\n[planet]\nradius = nan\n"),
        case(
            "render: a negative planet radius",
            1,
            &["render", "--preset", "earth-noon", "--set", "planet.radius=-6360000"],
            &["planet.radius = -6360000: must be a finite number > 0 metres"],
        ),
        case(
            "render: a NaN in the camera's position",
            1,
            &["render", "--set", "camera.position=[nan, 0, 1.7]"],
            &["camera.position = [NaN, 0, 1.7]: every component must be a finite number of metres"],
        ),
        case(
            "render: the camera inside Mars",
            1,
            &[
                "render",
                "--preset",
                "mars-noon",
                "--set",
                "camera.position=[0, 0, -5000]",
            ],
            &["the camera is inside the planet (mars)", "its altitude is -5000 m"],
        ),
        // ---- render: absurd sizes and counts --------------------------------------------------
        case(
            "render: --width 100000",
            1,
            &["render", "--width", "100000"],
            &["render.width = 100000: must be 1 to 16384 pixels (a fixed limit of the scene format"],
        ),
        case(
            "render: render.width = 0 in a file",
            1,
            &["render", "s.toml"],
            &["render.width = 0: must be 1 to 16384 pixels"],
        )
        .file("s.toml", "[render]\nwidth = 0\n"),
        case(
            "render: a float for the width",
            1,
            &["render", "--set", "render.width=1e9"],
            &["render.width: invalid type: floating point"],
        ),
        case(
            "render: 16384 x 16384 is over the pixel limit",
            1,
            &["render", "--width", "16384", "--height", "16384"],
            &[
                "the image is 16384x16384 = 268435456 pixels, over the limit of 67108864 pixels",
                "FIRMAMENT_MAX_PIXELS=268435456",
            ],
        ),
        case(
            "render: a lowered pixel limit",
            1,
            &["render", "--width", "64", "--height", "64"],
            &["the image is 64x64 = 4096 pixels, over the limit of 1000 pixels"],
        )
        .env("FIRMAMENT_MAX_PIXELS", "1000"),
        case(
            "render: an unreadable pixel limit",
            1,
            &["render"],
            &["FIRMAMENT_MAX_PIXELS = \"lots\": must be a whole number of pixels >= 1"],
        )
        .env("FIRMAMENT_MAX_PIXELS", "lots"),
        case(
            "render: 9 suns",
            1,
            &["render", "s.toml"],
            &["suns = 9 suns: at most 8 suns", "a fixed limit of the renderer"],
        )
        .file("s.toml", nine_suns.clone()),
        case(
            "render: 9 lights",
            1,
            &["render", "s.toml"],
            &[
                "lights = 9 lights: at most 8 lights",
                "a fixed limit of the classic lighting model",
            ],
        )
        .file("s.toml", nine_lights.clone()),
        case(
            "render: 65 flare elements",
            1,
            &["render", "s.toml"],
            &[
                "flare.elements = 65 elements: at most 64 elements",
                "a fixed limit of the flare pass",
            ],
        )
        .file("s.toml", many_flare_elements),
        case(
            "render: 100000 flare samples",
            1,
            &["render", "--set", "flare.enabled=true", "--set", "flare.samples=100000"],
            &["flare.samples = 100000: must be 1 to 256 (MAX_FLARE_SAMPLES, a fixed limit"],
        ),
        // ---- render: shadows -------------------------------------------------------------------
        case(
            "render: a shadow map of 100 texels",
            1,
            &["render", "--preset", "earth-objects", "--set", "shadows.map_size=100"],
            &["shadows.map_size = 100: must be 256 to 8192 texels"],
        ),
        case(
            "render: 9 shadow cascades in a file",
            1,
            &["render", "s.toml"],
            &["shadows.cascades = 9: must be 1 to 4"],
        )
        .file("s.toml", "preset = \"earth-objects\"\n[shadows]\ncascades = 9\n"),
        case(
            "render: shadows of no sun",
            1,
            &["render", "--preset", "earth-objects", "--set", "shadows.max_suns=0"],
            &["shadows.max_suns = 0: must be 1 to 8"],
        ),
        case(
            "render: a negative shadow depth bias",
            1,
            &["render", "--preset", "earth-objects", "--set", "shadows.depth_bias=-1"],
            &["shadows.depth_bias = -1: must be 0 to 16 texels"],
        ),
        case(
            "render: shadows of unlit objects",
            1,
            &[
                "render",
                "--preset",
                "earth-objects",
                "--set",
                "lighting.model=\"unlit\"",
                "--set",
                "shadows.enabled=true",
            ],
            &["shadows.enabled = true: shadows need lit objects"],
        ),
        case(
            "render: 16385 objects",
            1,
            &["render", "s.toml"],
            &[
                "objects = 16385 objects: at most 16384 objects",
                "a fixed limit of the scene format",
                "merge objects into one mesh file",
            ],
        )
        .file("s.toml", too_many_objects),
        case(
            "render: a 4096 x 4096 sphere is over the shapes' triangle budget",
            1,
            &[
                "render",
                "--set",
                "objects=[{ mesh = { kind = \"glt_sphere\", radius = 1.0, slices = 4096, stacks = 4096 } }]",
            ],
            &[
                "objects[0].mesh = 33554432 triangles",
                "at most 16777216 triangles together",
            ],
        ),
        case(
            "render: a quad of 100000000 subdivisions",
            1,
            &[
                "render",
                "--set",
                "objects=[{ mesh = { kind = \"quad\", size = 1.0, subdivisions = 100000000 } }]",
            ],
            &["objects[0].mesh.subdivisions = 100000000: must be in 1..=4096"],
        ),
        case(
            "render: a checkerboard of 100000000 texels",
            1,
            &[
                "render",
                "--set",
                "objects=[{ mesh = { kind = \"cube\", size = 1.0 }, texture = { checkerboard = { size = 100000000 } } }]",
            ],
            &["objects[0].texture.checkerboard.size = 100000000: must be in 1..=8192 texels"],
        ),
        case(
            "render: --paths 2000000 for the reference",
            2,
            &["render", "--preset", "earth-noon", "--reference", "--paths", "2000000"],
            &["invalid value '2000000' for '--paths <N>'"],
        ),
        case(
            "render: --exr-compression lzma",
            2,
            &["render", "-o", "x.exr", "--exr-compression", "lzma"],
            &[
                "invalid value 'lzma' for '--exr-compression <KIND>'",
                "[possible values: none, rle, zip, zips, piz]",
            ],
        ),
        // ---- render: clouds --------------------------------------------------------------------
        case(
            "render: a cloud layer's bottom above its top",
            1,
            &["render", "--preset", "earth-clouds", "--set", "clouds.0.bottom=4000"],
            &["clouds[0].top = 3000: must be a finite number of metres above clouds[0].bottom (4000 m): bottom < top"],
        ),
        case(
            "render: a negative cloud base",
            1,
            &["render", "--preset", "earth-clouds", "--set", "clouds.0.bottom=-100"],
            &["clouds[0].bottom = -100: must be a finite number of metres >= 0"],
        ),
        case(
            "render: a cloud top above the atmosphere",
            1,
            &["render", "--preset", "earth-clouds", "--set", "clouds.0.top=1e6"],
            &["clouds[0].top = 1000000: must be at most the top of the atmosphere"],
        ),
        case(
            "render: a cloud coverage of 1.5",
            1,
            &["render", "--preset", "earth-clouds", "--set", "clouds.0.coverage=1.5"],
            &["clouds[0].coverage = 1.5: must be in [0, 1]"],
        ),
        case(
            "render: a NaN cloud coverage in a file",
            1,
            &["render", "s.toml"],
            &["clouds[0].coverage = NaN: must be in [0, 1]"],
        )
        .file("s.toml", cloud_scene("coverage = nan").replace("coverage = 0.4\n", "")),
        case(
            "render: a negative cloud density",
            1,
            &["render", "--preset", "earth-clouds", "--set", "clouds.0.density=-0.05"],
            &["clouds[0].density = -0.05: must be in [0, 10] per metre"],
        ),
        case(
            "render: an infinite cloud density",
            1,
            &["render", "--preset", "earth-clouds", "--set", "clouds.0.density=inf"],
            &["clouds[0].density = inf: must be in [0, 10] per metre"],
        ),
        case(
            "render: an unknown cloud kind",
            1,
            &["render", "--preset", "earth-clouds", "--set", "clouds.0.kind=cumulous"],
            &[
                "clouds[0].kind: unknown variant `cumulous`",
                "(did you mean `cumulus`?)",
            ],
        ),
        case(
            "render: an unknown key in a cloud layer",
            1,
            &["render", "s.toml"],
            &["clouds[0].covrage: unknown key (did you mean `coverage`?)"],
        )
        .file("s.toml", cloud_scene("covrage = 0.5")),
        case(
            "render: 9 cloud layers",
            1,
            &["render", "s.toml"],
            &[
                "clouds = 9 layers: at most 8 cloud layers",
                "a fixed limit of the renderer",
            ],
        )
        .file("s.toml", nine_clouds.clone()),
        case(
            "render: a wind of 3 numbers",
            1,
            &["render", "--preset", "earth-clouds", "--set", "clouds.0.wind=[1, 2, 3]"],
            &["clouds[0].wind: must be 2 numbers, [east, north] in m/s; found 3 numbers"],
        ),
        case(
            "render: a NaN wind",
            1,
            &["render", "--preset", "earth-clouds", "--set", "clouds.0.wind=[nan, 0]"],
            &["clouds[0].wind = [NaN, 0]: [east, north] must each be a finite speed within ±1000 m/s"],
        ),
        case(
            "render: a cloud phase of 2 numbers",
            1,
            &[
                "render",
                "--preset",
                "earth-clouds",
                "--set",
                "clouds.0.phase=[0.8, -0.3]",
            ],
            &["clouds[0].phase: must be 3 numbers, [g_forward, g_back, blend]; found 2 numbers"],
        ),
        case(
            "render: a cloud phase g of 1",
            1,
            &[
                "render",
                "--preset",
                "earth-clouds",
                "--set",
                "clouds.0.phase=[1.0, -0.3, 0.8]",
            ],
            &["clouds[0].phase = [1, -0.3, 0.8]: g_forward (the first number) must be in (-1, 1)"],
        ),
        case(
            "render: a cloud albedo of 1.2",
            1,
            &["render", "--preset", "earth-clouds", "--set", "clouds.0.albedo=1.2"],
            &["clouds[0].albedo = 1.2: must be in [0, 1]"],
        ),
        case(
            "render: a missing coverage map",
            1,
            &["render", "s.toml"],
            &["clouds[0].coverage_map: cannot load", "nope.png", "does not exist"],
        )
        .file("s.toml", coverage_map_scene("nope.png")),
        case(
            "render: a folder for a coverage map",
            1,
            &["render", "s.toml"],
            &[
                "clouds[0].coverage_map: cannot load",
                "folder.png",
                "is not a regular file",
            ],
        )
        .file("s.toml", coverage_map_scene("folder.png"))
        .dir("folder.png"),
        case(
            "render: text for a PNG coverage map",
            1,
            &["render", "s.toml"],
            &[
                "clouds[0].coverage_map: cannot load",
                "text.png",
                "cannot decode the Png image",
            ],
        )
        .file("s.toml", coverage_map_scene("text.png"))
        .file("text.png", "hello"),
        case(
            "render: a coverage map that is no image",
            1,
            &["render", "s.toml"],
            &[
                "clouds[0].coverage_map: cannot load",
                "notes.txt",
                "not an image file of a known format",
            ],
        )
        .file("s.toml", coverage_map_scene("notes.txt"))
        .file("notes.txt", "hello"),
        // ---- render: broken meshes and textures ------------------------------------------------
        case(
            "render: a missing texture file",
            1,
            &["render", "s.toml"],
            &["objects[0].texture.file", "nope.png"],
        )
        .file("s.toml", texture_scene("nope.png")),
        case(
            "render: a truncated PNG texture",
            1,
            &["render", "s.toml"],
            &["objects[0].texture.file", "half.png"],
        )
        .file("s.toml", texture_scene("half.png"))
        .file("half.png", truncated_png),
        case(
            "render: text for a PNG texture",
            1,
            &["render", "s.toml"],
            &["objects[0].texture.file", "text.png"],
        )
        .file("s.toml", texture_scene("text.png"))
        .file("text.png", "hello"),
        case(
            "render: a folder for a texture",
            1,
            &["render", "s.toml"],
            &["objects[0].texture.file", "folder.png"],
        )
        .file("s.toml", texture_scene("folder.png"))
        .dir("folder.png"),
        case(
            "render: an OBJ with garbage",
            1,
            &["render", "s.toml"],
            &["objects[0].mesh.path", "garbage.obj"],
        )
        .file("s.toml", mesh_scene("garbage.obj"))
        .file("garbage.obj", garbage_obj),
        case(
            "render: binary bytes for an OBJ",
            1,
            &["render", "s.toml"],
            &["objects[0].mesh.path", "binary.obj"],
        )
        .file("s.toml", mesh_scene("binary.obj"))
        .file("binary.obj", binary.clone()),
        case(
            "render: a folder for a mesh",
            1,
            &["render", "s.toml"],
            &["objects[0].mesh.path", "model.obj"],
        )
        .file("s.toml", mesh_scene("model.obj"))
        .dir("model.obj"),
        case(
            "render: a glTF with an out-of-range index",
            1,
            &["render", "s.toml"],
            &["objects[0].mesh.path", "oob.gltf", "index 7 is out of range"],
        )
        .file("s.toml", mesh_scene("oob.gltf"))
        .file("oob.gltf", gltf.clone())
        .file("tri.bin", gltf_bin.clone()),
        case(
            "render: a glTF whose buffer file is missing",
            1,
            &["render", "s.toml"],
            &["objects[0].mesh.path", "nobin.gltf", "gone.bin"],
        )
        .file("s.toml", mesh_scene("nobin.gltf"))
        .file("nobin.gltf", gltf.replace("tri.bin", "gone.bin")),
        case(
            "render: a truncated GLB",
            1,
            &["render", "s.toml"],
            &["objects[0].mesh.path", "short.glb"],
        )
        .file("s.toml", mesh_scene("short.glb"))
        .file("short.glb", b"glTF\x02\x00\x00\x00\xff\xff\x00\x00".to_vec()),
        // ---- render: bad dates and times in the scene ----------------------------------------
        case(
            "render: 2024-02-30 in the scene",
            1,
            &["render", "--set", "time.date_time=\"2024-02-30T12:00:00Z\""],
            &["time.date_time = \"2024-02-30T12:00:00Z\"", "no such date or time"],
        ),
        case(
            "render: the year 99999 in the scene",
            1,
            &["render", "s.toml"],
            &[
                "time.date_time = \"99999-01-01T00:00:00Z\"",
                "is not an ISO 8601 date and time",
            ],
        )
        .file("s.toml", "[time]\ndate_time = \"99999-01-01T00:00:00Z\"\n"),
        case(
            "render: `yesterday` in the scene",
            1,
            &["render", "--set", "time.date_time=yesterday"],
            &["time.date_time = \"yesterday\"", "is not an ISO 8601 date and time"],
        ),
        case(
            "render: --time noon",
            1,
            &["render", "--time", "noon"],
            &["time.time_of_day = \"noon\": expected HH:MM or HH:MM:SS"],
        ),
        case(
            "render: a keyframe at 25:00",
            1,
            &["render", "--set", "sky.gradient.keyframes.0.time=\"25:00\""],
            &["sky.gradient.keyframes[0].time = \"25:00\": hours must be 0 to 24"],
        ),
        // ---- render: --set that cannot apply ---------------------------------------------------
        case(
            "render: --set past the end of an array",
            1,
            &["render", "--preset", "earth-noon", "--set", "suns.5.elevation=3"],
            &["--set suns.5.elevation=3: index 5 is past the end of an array of 1"],
        ),
        case(
            "render: --set inside a number",
            1,
            &["render", "--set", "camera.fov_y.degrees=5"],
            &["--set camera.fov_y.degrees=5: cannot set `degrees` inside a float"],
        ),
        case(
            "render: --set an empty key",
            1,
            &["render", "--set", "=1"],
            &["--set =1: the key path has an empty part"],
        ),
        // ---- render: outputs -------------------------------------------------------------------
        case(
            "render: an output without an extension",
            1,
            &["render", "-o", "image"],
            &["output image: the file name must end in .png (8-bit sRGB) or .exr (linear float)"],
        ),
        case(
            "render: an output that is a folder",
            1,
            &["render", "-o", "out.png"],
            &["output out.png: is a folder"],
        )
        .dir("out.png"),
        case(
            "render: an EXR output under a file",
            1,
            &["render", "-o", "a_file/x.exr"],
            &["output a_file/x.exr: the folder a_file does not exist"],
        )
        .file("a_file", "not a folder"),
        // ---- check -----------------------------------------------------------------------------
        case(
            "check: an unknown nested key",
            1,
            &["check", "s.toml"],
            &[
                "s.toml is not a valid scene",
                "sky.gradient.keyframez: unknown key (did you mean `keyframes`?)",
            ],
        )
        .file("s.toml", "[sky.gradient]\nkeyframez = []\n"),
        case(
            "check: no keyframes",
            1,
            &["check", "--set", "sky.gradient.keyframes=[]"],
            &["sky.gradient.keyframes = []: needs at least one keyframe"],
        ),
        case(
            "check: a table for the image size",
            1,
            &["check", "--set", "render=5"],
            &["render: invalid type: integer `5`"],
        ),
        case(
            "check: 9 lights",
            1,
            &["check", "s.toml"],
            &["s.toml is not a valid scene", "lights = 9 lights: at most 8 lights"],
        )
        .file("s.toml", nine_lights.clone()),
        case(
            "check: a glTF with an out-of-range index",
            1,
            &["check", "s.toml"],
            &["s.toml is not a valid scene", "index 7 is out of range"],
        )
        .file("s.toml", mesh_scene("oob.gltf"))
        .file("oob.gltf", gltf.clone())
        .file("tri.bin", gltf_bin),
        case(
            "check: a missing coverage map",
            1,
            &["check", "s.toml"],
            &[
                "s.toml is not a valid scene",
                "clouds[0].coverage_map: cannot load",
                "nope.png",
            ],
        )
        .file("s.toml", coverage_map_scene("nope.png")),
        // ---- sky-sample ------------------------------------------------------------------------
        case(
            "sky-sample: 9 suns",
            1,
            &[&SKY_SAMPLE[..], &["s.toml"]].concat(),
            &["suns = 9 suns: at most 8 suns", "a fixed limit of the renderer"],
        )
        .file("s.toml", nine_suns.clone()),
        case(
            "sky-sample: a malformed scene",
            1,
            &[&SKY_SAMPLE[..], &["s.toml"]].concat(),
            &["s.toml is not valid TOML"],
        )
        .file("s.toml", "[planet\n"),
        case(
            "sky-sample: --altitude 1e300",
            1,
            &[
                "sky-sample",
                "--altitude",
                "1e300",
                "--sun-zenith",
                "30",
                "--view-zenith",
                "30",
            ],
            &["--altitude = 1e300: must be at most 1e15 metres"],
        ),
        case(
            "render: a camera 1e300 m away",
            1,
            &["render", "--set", "camera.position=[0, 0, 1e300]"],
            &["camera.position = [0e0, 0e0, 1e300]: must be within 1e15 m (about 6700 AU)"],
        ),
        case(
            "sky-sample: --paths 0",
            2,
            &[&SKY_SAMPLE[..], &["--paths", "0"]].concat(),
            &["invalid value '0' for '--paths <N>'"],
        ),
        case(
            "sky-sample: an infinite view zenith",
            2,
            &[
                "sky-sample",
                "--reference",
                "--altitude",
                "0",
                "--sun-zenith",
                "30",
                "--view-zenith",
                "inf",
            ],
            &["invalid value 'inf' for '--view-zenith <DEG>': must be a finite number"],
        ),
        case(
            "sky-sample: no --altitude",
            2,
            &["sky-sample", "--sun-zenith", "30", "--view-zenith", "60"],
            &["--altitude <M>"],
        ),
        // ---- bench -----------------------------------------------------------------------------
        case(
            "bench: --width 100000",
            1,
            &["bench", "--width", "100000", "--frames", "1"],
            &["render.width = 100000: must be 1 to 16384 pixels"],
        ),
        case(
            "bench: 9000 x 9000 is over the pixel limit",
            1,
            &["bench", "--objects", "--width", "9000", "--height", "9000"],
            &["the image is 9000x9000 = 81000000 pixels, over the limit of 67108864 pixels"],
        ),
        case(
            "bench: --frames 0",
            2,
            &["bench", "--frames", "0"],
            &["invalid value '0' for '--frames <N>'"],
        ),
        case(
            "bench: --objects 100001",
            2,
            &["bench", "--objects", "100001"],
            &["invalid value '100001' for '--objects [<N>]'"],
        ),
        case(
            "bench: an OBJ with garbage",
            1,
            &["bench", "s.toml", "--frames", "1"],
            &["objects[0].mesh.path", "garbage.obj"],
        )
        .file(
            "s.toml",
            format!("preset = \"earth-objects\"\n{}", mesh_scene("garbage.obj")),
        )
        .file("garbage.obj", garbage_obj),
        // ---- sun -------------------------------------------------------------------------------
        case(
            "sun: the year 99999",
            2,
            &["sun", "--time", "99999-01-01T00:00:00Z", "--lat", "0", "--lon", "0"],
            &["invalid value '99999-01-01T00:00:00Z' for '--time <ISO8601>'"],
        ),
        case(
            "sun: 25:00",
            2,
            &["sun", "--time", "2024-06-01T25:00:00Z", "--lat", "0", "--lon", "0"],
            &["'2024-06-01T25:00:00Z' for '--time <ISO8601>'", "no such date or time"],
        ),
        case(
            "sun: an empty time",
            2,
            &["sun", "--time", "", "--lat", "0", "--lon", "0"],
            &["invalid value '' for '--time <ISO8601>'"],
        ),
        case(
            "sun: no --lat",
            2,
            &["sun", "--time", "2024-06-01T12:00:00Z", "--lon", "0"],
            &["--lat <DEG>"],
        ),
        // ---- timelapse -------------------------------------------------------------------------
        case(
            "timelapse: --to at 25:00",
            2,
            &[],
            &["'2024-03-20T25:00:00Z' for '--to <ISO8601>'", "no such date or time"],
        )
        .with_args(timelapse(&["--to", "2024-03-20T25:00:00Z", "-o", "out"])),
        case(
            "timelapse: --from in the year 99999",
            2,
            &[],
            &["invalid value '99999-03-20T16:00:00Z' for '--from <ISO8601>'"],
        )
        .with_args(timelapse(&["--from", "99999-03-20T16:00:00Z", "-o", "out"])),
        case(
            "timelapse: 9 lights",
            1,
            &[],
            &[
                "lights = 9 lights: at most 8 lights",
                "drop or merge the weakest lights",
            ],
        )
        .with_args(timelapse(&["s.toml", "-o", "out"]))
        .file("s.toml", nine_lights),
        case(
            "timelapse: a missing texture",
            1,
            &[],
            &["objects[0].texture.file", "nope.png"],
        )
        .with_args(timelapse(&["s.toml", "-o", "out"]))
        .file("s.toml", texture_scene("nope.png")),
        case(
            "timelapse: a missing coverage map",
            1,
            &[],
            &["clouds[0].coverage_map: cannot load", "nope.png", "does not exist"],
        )
        .with_args(timelapse(&["s.toml", "-o", "out"]))
        .file("s.toml", coverage_map_scene("nope.png")),
        case(
            "timelapse: a cloud layer's bottom above its top",
            1,
            &[],
            &["clouds[0].top = 3000: must be a finite number of metres above clouds[0].bottom (3500 m)"],
        )
        .with_args(timelapse(&["s.toml", "-o", "out"]))
        .file(
            "s.toml",
            cloud_scene("bottom = 3500.0").replace("bottom = 1500.0\n", ""),
        ),
        case(
            "timelapse: frames over the pixel limit",
            1,
            &[],
            &["each frame is 16384x16384 = 268435456 pixels, over the limit of 67108864 pixels"],
        )
        .with_args(timelapse(&["--width", "16384", "--height", "16384", "-o", "out"])),
        case(
            "timelapse: --fps 1000",
            2,
            &[],
            &["invalid value '1000' for '--fps <FPS>'"],
        )
        .with_args(timelapse(&["--fps", "1000", "-o", "out"])),
        // ---- view (no display: these fail before any window) -----------------------------------
        case(
            "view: a malformed scene",
            1,
            &["view", "s.toml", "--frames", "1"],
            &["s.toml is not valid TOML"],
        )
        .file("s.toml", "[camera]\nfov_y = = 3\n"),
        case(
            "view: 9 suns",
            1,
            &["view", "s.toml", "--frames", "1"],
            &["suns = 9 suns: at most 8 suns", "a fixed limit of the renderer"],
        )
        .file("s.toml", nine_suns),
        case(
            "view: --size 100000x10",
            2,
            &["view", "--size", "100000x10"],
            &["expected WxH, each 1 to 16384 pixels"],
        ),
        case(
            "view: --size 16384x16384 is over the pixel limit",
            1,
            &["view", "--size", "16384x16384", "--frames", "1"],
            &["the window (--size) is 16384x16384 = 268435456 pixels, over the limit"],
        ),
        case(
            "view: --frames 0",
            2,
            &["view", "--frames", "0"],
            &["invalid value '0' for '--frames <N>'"],
        ),
        case(
            "view: --scale nan",
            2,
            &["view", "--scale", "nan"],
            &["invalid value 'nan' for '--scale <S>': must be a number in (0, 1]"],
        ),
        case(
            "view: a screenshot in a missing folder",
            1,
            &["view", "--frames", "1", "--screenshot", "shots/a.png"],
            &["output shots/a.png: the folder shots does not exist"],
        ),
        case(
            "view: a screenshot without an extension",
            1,
            &["view", "--frames", "1", "--screenshot", "shot"],
            &["output shot: the file name must end in .png"],
        ),
        case(
            "view: save-scene to a folder",
            1,
            &["view", "--frames", "1", "--save-scene", "saved"],
            &["output saved: is a folder"],
        )
        .dir("saved"),
        case(
            "view: an unknown preset",
            1,
            &["view", "--preset", "earth-nun", "--frames", "1"],
            &["unknown preset `earth-nun`; did you mean `earth-noon`?"],
        ),
    ];

    #[cfg(target_os = "linux")]
    {
        // The pixel limit raised past any machine: the memory free now still bounds the image.
        // `ulimit -v` stands for a machine short of memory (1 GiB), so the cases fail anywhere.
        cases.push(
            case(
                "render: 16384 x 16384 with the pixel limit lifted, over the memory",
                1,
                &["render", "--width", "16384", "--height", "16384"],
                &[
                    "the image is 16384x16384 = 268435456 pixels: rendering it needs about 12.0 GiB of memory \
                     (48 bytes a pixel), more than the",
                    "address-space limit (ulimit -v); render a smaller image, or raise that limit (ulimit -v)",
                ],
            )
            .env("FIRMAMENT_MAX_PIXELS", "1000000000000")
            .address_space(1 << 20),
        );
        cases.push(
            case(
                "render --reference: f64 pixels over the memory",
                1,
                &[
                    "render",
                    "--reference",
                    "--preset",
                    "earth-noon",
                    "--width",
                    "4096",
                    "--height",
                    "4096",
                    "-o",
                    "ref.exr",
                ],
                &["rendering it needs about 1.1 GiB of memory (72 bytes a pixel)"],
            )
            .address_space(1 << 20),
        );
        cases.push(
            case(
                "timelapse: frames over the memory",
                1,
                &[],
                &["each frame is 16384x16384 = 268435456 pixels: rendering it needs about 12.0 GiB"],
            )
            .with_args(timelapse(&["--width", "16384", "--height", "16384", "-o", "out"]))
            .env("FIRMAMENT_MAX_PIXELS", "1000000000000")
            .address_space(1 << 20),
        );
        cases.push(
            case(
                "view: a window over the memory",
                1,
                &["view", "--size", "16384x16384", "--frames", "1"],
                &["the window (--size) is 16384x16384 = 268435456 pixels: rendering it needs about 12.0 GiB"],
            )
            .env("FIRMAMENT_MAX_PIXELS", "1000000000000")
            .address_space(1 << 20),
        );
        cases.push(case(
            "render: an output in a folder no file can be made in",
            1,
            &["render", "-o", "/proc/firmament.png"],
            &["output /proc/firmament.png: cannot create a file in /proc"],
        ));
        cases.push(case(
            "check: /dev/zero as the scene file",
            1,
            &["check", "/dev/zero"],
            &["cannot read scene file /dev/zero", "over the limit of 16 MiB"],
        ));
    }
    cases
}

#[test]
fn every_bad_input_fails_with_one_clear_message_and_writes_nothing() {
    let scratch = tempfile::tempdir().expect("temp dir");
    let cases = corpus();
    // The count the corpus has (docs/RELIABILITY.md), so that no case can vanish unnoticed.
    let floor = if cfg!(target_os = "linux") { 124 } else { 118 };
    assert!(cases.len() >= floor, "only {} cases", cases.len());
    let mut failures = Vec::new();
    for case in &cases {
        let dir = tempfile::tempdir().expect("temp dir");
        for fixture in &case.fixtures {
            match fixture {
                Fixture::File(name, bytes) => std::fs::write(dir.path().join(name), bytes).expect("write input"),
                Fixture::Dir(name) => std::fs::create_dir(dir.path().join(name)).expect("create folder"),
            }
        }
        let before = tree(dir.path());
        let ran = run(dir.path(), scratch.path(), case);
        let after = tree(dir.path());
        let wrong = problems(case, &ran, &before, &after);
        if !wrong.is_empty() {
            failures.push(format!(
                "{} ({:?}):\n    {}\n  stderr: {}",
                case.name,
                case.args,
                wrong.join("\n    "),
                ran.stderr.chars().take(1_000).collect::<String>()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} bad inputs misbehaved:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// "A scene file's relative paths resolve against the scene file's folder; no loader follows a
/// path outside what the user asked for without saying so in the log."
#[test]
fn relative_paths_resolve_in_the_scene_folder_and_paths_outside_it_are_logged() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    let triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::fs::create_dir_all(d.join("scenes")).expect("folder");
    std::fs::create_dir_all(d.join("shared")).expect("folder");
    std::fs::write(d.join("scenes/inside.obj"), triangle).expect("write");
    std::fs::write(d.join("shared/outside.obj"), triangle).expect("write");
    std::fs::write(d.join("shared/abs.png"), png_bytes()).expect("write");
    let absolute = d.join("shared/abs.png");
    let object =
        |mesh: &str, extra: &str| format!("[[objects]]\nmesh = {{ kind = \"file\", path = \"{mesh}\" }}\n{extra}");

    // Inside the scene's folder, relative to it (not to the working directory, `d`): no note.
    std::fs::write(d.join("scenes/inside.toml"), object("inside.obj", "")).expect("write");
    let out = firmament(d, &["check", "scenes/inside.toml"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(!stderr(&out).contains("outside"), "{}", stderr(&out));

    // A `..` escape and an absolute path: both read, both said.
    std::fs::write(
        d.join("scenes/outside.toml"),
        object(
            "../shared/outside.obj",
            &format!("texture = {{ file = \"{}\" }}\n", absolute.display()),
        ),
    )
    .expect("write");
    let out = firmament(d, &["check", "scenes/outside.toml"]);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    let scenes = d.join("scenes");
    for expected in [
        format!(
            "objects[0].mesh.path: reads {}, outside the scene's folder {}",
            d.join("shared/outside.obj").display(),
            scenes.display()
        ),
        format!(
            "objects[0].texture.file: reads {}, outside the scene's folder {}",
            absolute.display(),
            scenes.display()
        ),
    ] {
        assert!(err.contains(&expected), "`{expected}` missing from:\n{err}");
    }
    // A file outside the working directory, for a scene without a file (`--set`): said too.
    let elsewhere = tempfile::tempdir().expect("temp dir");
    let far = elsewhere.path().join("far.obj");
    std::fs::write(&far, triangle).expect("write");
    let out = firmament(
        &scenes,
        &[
            "check",
            "--set",
            &format!(
                "objects=[{{ mesh = {{ kind = \"file\", path = \"{}\" }} }}]",
                far.display()
            ),
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("outside the working directory"),
        "{}",
        stderr(&out)
    );
}
