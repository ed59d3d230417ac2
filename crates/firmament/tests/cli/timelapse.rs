//! End-to-end tests of `firmament timelapse`: real processes, real files, real GPU (software on
//! CI), tiny images. Every bad input must give one clear message, a non-zero exit and no files.

use std::path::{Path, PathBuf};
use std::process::Command;

use firmament_core::astro::spa::{SpaInput, sun_times};
use firmament_core::astro::{CivilDateTime, Instant};

use crate::support::{exr_floats, firmament, names_in, stderr};

/// Every path under `dir`, recursively, sorted.
fn files_in(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).expect("readable") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                stack.push(path.clone());
            }
            files.push(path);
        }
    }
    files.sort();
    files
}

/// A tiny time-lapse of the default scene: `frames` frames from 16:00 to 20:00 UTC.
fn tiny(out: &str, frames: &str) -> Vec<String> {
    [
        "timelapse",
        "--from",
        "2024-03-20T16:00:00Z",
        "--to",
        "2024-03-20T20:00:00Z",
        "--frames",
        frames,
        "--width",
        "48",
        "--height",
        "27",
        "-o",
        out,
    ]
    .map(str::to_owned)
    .to_vec()
}

fn args(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

/// sRGB-encoded 8 bits → linear, from IEC 61966-2-1 (not from the code under test).
fn srgb_to_linear(v: u8) -> f64 {
    let v = f64::from(v) / 255.0;
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// Rec. 709 / sRGB luminance of linear RGB.
fn luminance(r: f64, g: f64, b: f64) -> f64 {
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

fn mean_png_luminance(path: &Path) -> f64 {
    let image = image::open(path).expect("a PNG").to_rgb8();
    let sum: f64 = image
        .pixels()
        .map(|p| luminance(srgb_to_linear(p[0]), srgb_to_linear(p[1]), srgb_to_linear(p[2])))
        .sum();
    sum / f64::from(image.width() * image.height())
}

fn mean_exr_luminance(path: &Path) -> f64 {
    let image = image::open(path).expect("an EXR").to_rgba32f();
    let sum: f64 = image
        .pixels()
        .map(|p| luminance(f64::from(p[0]), f64::from(p[1]), f64::from(p[2])))
        .sum();
    sum / f64::from(image.width() * image.height())
}

#[test]
fn three_frames_make_pngs_a_gif_and_a_contact_sheet_and_a_second_run_resumes() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    let run = tiny("lapse", "3");
    let out = firmament(d, &args(&run));
    assert!(out.status.success(), "{}", stderr(&out));
    let lapse = d.join("lapse");
    assert_eq!(
        names_in(&lapse),
        [
            "contact_sheet.png",
            "frame_0001.png",
            "frame_0002.png",
            "frame_0003.png",
            "timelapse.gif",
            "timelapse.json"
        ],
        "exactly the frames, the GIF, the sheet and the manifest: no temporary files"
    );
    let frames: Vec<image::RgbImage> = (1..=3)
        .map(|k| {
            image::open(lapse.join(format!("frame_000{k}.png")))
                .expect("a PNG")
                .to_rgb8()
        })
        .collect();
    for f in &frames {
        assert_eq!(f.dimensions(), (48, 27));
    }
    // 16:00, 18:00, 20:00 UTC at 45° N, 0° E: the sky darkens from frame to frame.
    let means: Vec<f64> = (1..=3)
        .map(|k| mean_png_luminance(&lapse.join(format!("frame_000{k}.png"))))
        .collect();
    assert!(means[0] > means[1] && means[1] > means[2], "{means:?}");

    // The GIF: 3 frames of the frames' size (under 640 px), looping.
    use image::AnimationDecoder;
    let gif = std::io::BufReader::new(std::fs::File::open(lapse.join("timelapse.gif")).expect("GIF"));
    let decoded = image::codecs::gif::GifDecoder::new(gif)
        .expect("a GIF")
        .into_frames()
        .collect_frames()
        .expect("GIF frames");
    assert_eq!(decoded.len(), 3);
    for (frame, png) in decoded.iter().zip(&frames) {
        assert_eq!(frame.buffer().dimensions(), (48, 27));
        // 24 fps: 41.7 ms, stored in hundredths of a second.
        let (num, den) = frame.delay().numer_denom_ms();
        assert_eq!(num / den, 40, "{num}/{den} ms");
        // Quantised to 256 colours: close to the PNG, not equal (NeuQuant may leave a rare
        // colour, the sun's disc, further off).
        let diffs: Vec<u8> = frame
            .buffer()
            .pixels()
            .zip(png.pixels())
            .flat_map(|(a, b)| (0..3).map(move |c| a[c].abs_diff(b[c])))
            .collect();
        let mean = diffs.iter().map(|&d| f64::from(d)).sum::<f64>() / diffs.len() as f64;
        let worst = diffs.iter().max().copied().unwrap_or(0);
        assert!(
            mean < 3.0 && worst < 64,
            "GIF frame differs from its PNG: mean {mean}, worst {worst}"
        );
    }

    // The contact sheet: the three frames side by side, in order, full size (under 240 px).
    let sheet = image::open(lapse.join("contact_sheet.png")).expect("a PNG").to_rgb8();
    let gap = 4;
    assert_eq!(sheet.dimensions(), (gap + 3 * (48 + gap), gap + 27 + gap));
    for (k, frame) in frames.iter().enumerate() {
        let x0 = gap + k as u32 * (48 + gap);
        for (x, y, p) in frame.enumerate_pixels() {
            assert_eq!(sheet.get_pixel(x0 + x, gap + y), p, "frame {k} at ({x}, {y})");
        }
    }

    // The same command again renders nothing and says so.
    let modified = |p: &Path| std::fs::metadata(p).expect("exists").modified().expect("mtime");
    let before: Vec<_> = (1..=3)
        .map(|k| modified(&lapse.join(format!("frame_000{k}.png"))))
        .collect();
    let out = firmament(d, &args(&run));
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("3 of 3 frames skipped"), "{err}");
    assert!(
        !err.contains("rendered in"),
        "a resumed complete run rendered frames: {err}"
    );
    let after: Vec<_> = (1..=3)
        .map(|k| modified(&lapse.join(format!("frame_000{k}.png"))))
        .collect();
    assert_eq!(before, after, "frames were rewritten");
    assert_eq!(names_in(&lapse).len(), 6);

    // Another size in the same folder is refused rather than mixed.
    let mut other = run.clone();
    other[10] = "40".to_owned();
    let out = firmament(d, &args(&other));
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("holds another time-lapse (3 frames of 48x27")
            && stderr(&out).contains("this run renders 3 frames of 48x40"),
        "{}",
        stderr(&out)
    );

    // --overwrite renders every frame again.
    let mut again = run.clone();
    again.push("--overwrite".to_owned());
    let out = firmament(d, &args(&again));
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("3 frames rendered") && err.contains("0 skipped"), "{err}");
}

#[test]
fn one_frame_renders_from_and_may_equal_to() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = firmament(
        dir.path(),
        &[
            "timelapse",
            "--from",
            "2024-03-20T18:00:00+01:00",
            "--to",
            "2024-03-20T17:00:00Z",
            "--frames",
            "1",
            "--width",
            "48",
            "--height",
            "27",
            "-o",
            "one/two",
            "-q",
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).is_empty(), "-q printed: {}", stderr(&out));
    assert_eq!(
        names_in(&dir.path().join("one/two")),
        ["contact_sheet.png", "frame_0001.png", "timelapse.gif", "timelapse.json"]
    );
}

#[test]
fn every_bad_input_fails_cleanly_and_writes_nothing() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("a_file"), "not a folder").expect("write");
    let before = files_in(d);
    let with = |changes: &[(&str, &str)], extra: &[&str]| -> Vec<String> {
        let mut run = tiny("out", "3");
        for (flag, value) in changes {
            let i = run.iter().position(|a| a == flag).expect("flag") + 1;
            run[i] = (*value).to_owned();
        }
        run.extend(extra.iter().map(|s| (*s).to_owned()));
        run
    };
    let cases: Vec<(Vec<String>, i32, &str)> = vec![
        (
            with(&[("--from", "yesterday")], &[]),
            2,
            "invalid value 'yesterday' for '--from <ISO8601>': `yesterday` is not an ISO 8601 date and time",
        ),
        (
            with(&[("--to", "2024-02-30T00:00:00Z")], &[]),
            2,
            "for '--to <ISO8601>': `2024-02-30T00:00:00Z` is not an ISO 8601 date and time (no such date or time)",
        ),
        (
            with(
                &[("--from", "2024-03-20T20:00:00Z"), ("--to", "2024-03-20T16:00:00Z")],
                &[],
            ),
            2,
            "--from 2024-03-20T20:00:00Z is after --to 2024-03-20T16:00:00Z: --from must not be later than --to",
        ),
        (
            // The same instant on two clocks.
            with(
                &[
                    ("--from", "2024-03-20T18:00:00+02:00"),
                    ("--to", "2024-03-20T16:00:00Z"),
                ],
                &[],
            ),
            2,
            "--from and --to are the same instant (2024-03-20T18:00:00+02:00): 3 frames need --to later than --from",
        ),
        (
            with(&[("--frames", "0")], &[]),
            2,
            "invalid value '0' for '--frames <N>': must be a whole number of frames from 1 to 100000",
        ),
        (
            with(&[("--frames", "100001")], &[]),
            2,
            "invalid value '100001' for '--frames <N>': must be a whole number of frames from 1 to 100000 (a \
             fixed limit: for more, split the span over several runs",
        ),
        (with(&[], &["--fps", "0"]), 2, "invalid value '0' for '--fps <FPS>'"),
        (
            with(&[], &["--exr", "--exr-compression", "b44"]),
            2,
            "invalid value 'b44' for '--exr-compression <KIND>'\n  [possible values: none, rle, zip, zips, piz]",
        ),
        (
            with(&[], &["--exr-compression", "zip"]),
            2,
            "the following required arguments were not provided:\n  --exr",
        ),
        (
            with(&[("-o", "a_file")], &[]),
            1,
            "output a_file: exists and is not a folder",
        ),
        (
            with(&[("-o", "a_file/sub")], &[]),
            1,
            "output a_file/sub: cannot create the folder: a_file is not a folder",
        ),
        // A folder that cannot be created, even by root.
        #[cfg(target_os = "linux")]
        (
            with(&[("-o", "/proc/firmament-timelapse")], &[]),
            1,
            "output /proc/firmament-timelapse: cannot create the folder",
        ),
        (
            with(&[], &["--set", "camera.fov_y=0"]),
            1,
            "camera.fov_y = 0: must be in (0, 180) degrees",
        ),
        (
            with(&[("--width", "0")], &[]),
            1,
            "render.width = 0: must be 1 to 16384 pixels",
        ),
        (
            with(&[], &["--preset", "dwan"]),
            1,
            "unknown preset `dwan`; did you mean `dawn`?",
        ),
        (with(&[], &["missing.toml"]), 1, "cannot read scene file missing.toml"),
        (
            with(&[], &["--preset", "mars-noon"]),
            1,
            "planet.body = \"mars\": a real date places Earth's sun",
        ),
        #[cfg(target_os = "linux")]
        (
            with(&[], &["--backend", "metal"]),
            1,
            "no GPU adapter found for backend `metal`",
        ),
    ];
    for (run, code, expected) in cases {
        let out = firmament(d, &args(&run));
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(code), "{run:?}: {err}");
        assert!(
            err.contains(expected),
            "{run:?}\n  got:      {err}\n  expected: {expected}"
        );
        assert!(!err.contains("panicked"), "{run:?} panicked: {err}");
        assert_eq!(files_in(d), before, "{run:?} left files behind");
    }
    // A missing --output is clap's own error.
    let out = firmament(
        d,
        &[
            "timelapse",
            "--from",
            "2024-03-20T16:00Z",
            "--to",
            "2024-03-20T17:00Z",
            "--frames",
            "2",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--output <DIR>"), "{}", stderr(&out));
    assert_eq!(files_in(d), before);
}

/// An image's floats, RGBA rows top first.
type Floats = Vec<f32>;

/// `--exr` frames are compressed as `--exr-compression` says (zip by default), in 32-bit float,
/// and every compression holds the same floats, read by the `exr` crate and by `image` alike —
/// the floats and the PNG `render` writes for the same instant. The frames are in order (the sky
/// darkens frame by frame) although they are encoded in parallel.
#[test]
fn exr_frames_are_compressed_as_chosen_and_hold_the_same_floats() {
    use exr::compression::Compression;
    use exr::meta::attribute::SampleType;
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    let frames = 4;
    let cases = [
        (None, Compression::ZIP16),
        (Some("none"), Compression::Uncompressed),
        (Some("rle"), Compression::RLE),
        (Some("zip"), Compression::ZIP16),
        (Some("zips"), Compression::ZIP1),
        (Some("piz"), Compression::PIZ),
    ];
    // The first run's frames: each EXR's floats and each PNG's bytes.
    let mut first: Option<(Vec<Floats>, Vec<Vec<u8>>)> = None;
    for (flag, expected) in cases {
        let name = flag.unwrap_or("default");
        let mut run = tiny(name, &frames.to_string());
        let size = run.iter().position(|a| a == "--width").expect("--width");
        run.splice(size..size + 4, ["--width", "32", "--height", "18"].map(str::to_owned));
        run.push("--exr".to_owned());
        if let Some(flag) = flag {
            run.extend(["--exr-compression".to_owned(), flag.to_owned()]);
        }
        let out = firmament(d, &args(&run));
        assert!(out.status.success(), "{name}: {}", stderr(&out));
        let mut floats = Vec::new();
        let mut pngs = Vec::new();
        for k in 1..=frames {
            let path = d.join(name).join(format!("frame_000{k}.exr"));
            let meta = exr::meta::MetaData::read_from_file(&path, false).expect("an EXR header");
            let header = &meta.headers[0];
            assert_eq!(header.compression, expected, "{}", path.display());
            assert_eq!(header.layer_size.0, 32);
            let names: Vec<String> = header.channels.list.iter().map(|c| c.name.to_string()).collect();
            assert_eq!(names, ["A", "B", "G", "R"], "{}", path.display());
            assert!(header.channels.list.iter().all(|c| c.sample_type == SampleType::F32));
            let exr = exr_floats(&path);
            assert_eq!(exr.len(), 32 * 18 * 4);
            let via_image = image::open(&path).expect("image reads it").to_rgba32f().into_raw();
            assert!(exr == via_image, "{}: exr and image read other floats", path.display());
            floats.push(exr);
            pngs.push(std::fs::read(d.join(name).join(format!("frame_000{k}.png"))).expect("the PNG"));
        }
        let means: Vec<f64> = (1..=frames)
            .map(|k| mean_png_luminance(&d.join(name).join(format!("frame_000{k}.png"))))
            .collect();
        assert!(means.windows(2).all(|m| m[1] < m[0]), "{name}: out of order: {means:?}");
        match &first {
            None => first = Some((floats, pngs)),
            Some((f, p)) => {
                assert!(*f == floats, "{name}: other floats than the default compression's");
                assert!(*p == pngs, "{name}: other PNGs than the default compression's");
            }
        }
    }
    let (floats, _) = first.expect("a first run");
    assert!(floats.iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
    assert!(floats[0] != floats[1], "frames 1 and 2 are the same image");

    // `render` at frame 1's instant: the same floats (one render read back once) and PNG pixels.
    let still = |file: &str| {
        let out = firmament(
            d,
            &[
                "render",
                "--preset",
                "default",
                "--set",
                "time.date_time=\"2024-03-20T16:00:00Z\"",
                "--width",
                "32",
                "--height",
                "18",
                "-o",
                file,
            ],
        );
        assert!(out.status.success(), "{file}: {}", stderr(&out));
        d.join(file)
    };
    assert!(
        exr_floats(&still("still.exr")) == floats[0],
        "render's EXR differs from frame 1's"
    );
    let png = |path: &Path| image::open(path).expect("a PNG").to_rgb8().into_raw();
    assert_eq!(png(&still("still.png")), png(&d.join("default/frame_0001.png")));
}

/// The issue's check "Day/night: rendered sky luminance decreases monotonically through sunset
/// and twilight": Earth's atmosphere at 45° N, 0° E on the 2024 March equinox, looking north (away
/// from the setting sun and the moon's path), from 1 h before sunset to 1.5 h after (sun ≈ +10°
/// to ≈ −16°), every 30 min. The EXR frames are linear radiance (cd/m² as Y), so the check is
/// radiometric; the PNGs, through the preset's fixed exposure (EV100 11) and tone curve, may only
/// stay equal where they clip to black.
#[test]
fn sky_luminance_decreases_monotonically_through_sunset_and_twilight() {
    // Sunset from NREL's SPA in the core, on the UTC clock.
    let noon = CivilDateTime::utc(2024, 3, 20, 12, 0, 0.0);
    let instant = Instant::from_civil(&noon, None).expect("valid");
    let sunset_h = sun_times(&SpaInput::new(instant, 45.0, 0.0), 0.0)
        .sunset_h()
        .expect("the sun sets");
    assert!((18.0..18.3).contains(&sunset_h), "sunset at {sunset_h} h UTC");
    let at = |hours: f64| {
        let s = (hours * 3600.0).round() as u32;
        format!("2024-03-20T{:02}:{:02}:{:02}Z", s / 3600, s / 60 % 60, s % 60)
    };
    let (from, to) = (at(sunset_h - 1.0), at(sunset_h + 1.5));
    let dir = tempfile::tempdir().expect("temp dir");
    let out = firmament(
        dir.path(),
        &[
            "timelapse",
            "--preset",
            "earth-sunset",
            "--set",
            "camera.heading=0",
            "--set",
            "camera.pitch=10",
            "--set",
            "flare.enabled=false",
            // The sun alone: the moon (and its light in the sky) comes and goes on its own.
            "--set",
            "time.moon=false",
            "--set",
            "time.stars=false",
            "--from",
            &from,
            "--to",
            &to,
            "--frames",
            "6",
            "--width",
            "48",
            "--height",
            "27",
            "--exr",
            "-o",
            "dusk",
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let dusk = dir.path().join("dusk");
    let exr: Vec<f64> = (1..=6)
        .map(|k| mean_exr_luminance(&dusk.join(format!("frame_000{k}.exr"))))
        .collect();
    for pair in exr.windows(2) {
        assert!(pair[1] < pair[0], "EXR mean luminance (cd/m²) rose: {exr:?}");
    }
    assert!(
        exr[5] < exr[0] * 1e-2,
        "twilight should be far darker than day: {exr:?}"
    );
    assert!(exr[0] > 100.0, "an hour before sunset the sky is bright: {exr:?}");
    let png: Vec<f64> = (1..=6)
        .map(|k| mean_png_luminance(&dusk.join(format!("frame_000{k}.png"))))
        .collect();
    for pair in png.windows(2) {
        assert!(pair[1] <= pair[0], "PNG mean luminance rose: {png:?}");
    }
    assert!(png[5] < png[0], "{png:?}");
}

#[test]
fn an_auto_exposed_time_lapse_into_night_stays_exposed_and_repeats_byte_for_byte() {
    // 21 June at 52° N, looking west from 16:00 into the night (sun 10° down at 22:00).
    let run = |out: &str| {
        vec![
            "timelapse",
            "--preset",
            "earth-sunset",
            "--set",
            "display.exposure_mode=auto",
            "--set",
            "planet.latitude=52",
            "--set",
            "camera.heading=290",
            "--set",
            "camera.pitch=15",
            "--from",
            "2025-06-21T16:00:00Z",
            "--to",
            "2025-06-21T22:00:00Z",
            "--frames",
            "7",
            "--width",
            "64",
            "--height",
            "36",
            "-o",
            out,
        ]
        .into_iter()
        .map(str::to_owned)
        .collect::<Vec<_>>()
    };
    let dir = tempfile::tempdir().expect("temp dir");
    for out in ["first", "second"] {
        let ran = firmament(dir.path(), &args(&run(out)));
        assert!(ran.status.success(), "{}", stderr(&ran));
    }
    for k in 1..=7 {
        let name = format!("frame_000{k}.png");
        let first = std::fs::read(dir.path().join("first").join(&name)).expect("a frame");
        let second = std::fs::read(dir.path().join("second").join(&name)).expect("a frame");
        assert!(first == second, "{name} differs between two runs");
        let image = image::open(dir.path().join("first").join(&name))
            .expect("a PNG")
            .to_rgb8();
        let mean = image.pixels().flat_map(|p| p.0).map(f64::from).sum::<f64>()
            / (3.0 * f64::from(image.width() * image.height()) * 255.0);
        assert!((0.25..=0.65).contains(&mean), "{name}: mean display value {mean}");
    }
}

/// Starts the time-lapse `run` (its output folder `lapse`) in `dir` and returns once its first
/// frame exists.
fn start_until_the_first_frame(dir: &Path, run: &[String], stderr: std::process::Stdio) -> std::process::Child {
    let child = Command::new(env!("CARGO_BIN_EXE_firmament"))
        .args(args(run))
        .current_dir(dir)
        .env_remove("FIRMAMENT_LOG")
        .stderr(stderr)
        .stdout(std::process::Stdio::null())
        .spawn()
        .expect("spawns");
    let first = dir.join("lapse/frame_0001.png");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    while !first.exists() && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    assert!(first.exists(), "no frame within 2 minutes");
    child
}

/// Ctrl-C (SIGINT) and SIGTERM stop after the frame in flight: exit 130, only complete frames,
/// no GIF yet, a message saying how to resume; the same command then finishes the rest.
#[cfg(unix)]
#[test]
fn a_signal_stops_cleanly_and_the_same_command_resumes() {
    for signal in ["INT", "TERM"] {
        let dir = tempfile::tempdir().expect("temp dir");
        let d = dir.path();
        let run = tiny("lapse", "60");
        let child = start_until_the_first_frame(d, &run, std::process::Stdio::piped());
        let killed = Command::new("kill")
            .args([format!("-{signal}"), child.id().to_string()])
            .status()
            .expect("kill runs");
        assert!(killed.success());
        let out = child.wait_with_output().expect("waits");
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(130), "SIG{signal}: {err}");
        assert!(
            err.contains("interrupted: ") && err.contains("of 60 frames are in lapse"),
            "{err}"
        );
        assert!(err.contains("to resume, run the same command again"), "{err}");
        let mut names = names_in(&d.join("lapse"));
        names.retain(|n| n != "timelapse.json");
        assert!(
            names.iter().all(|n| n.starts_with("frame_") && n.ends_with(".png")),
            "only frames: {names:?}"
        );
        let done = names.len();
        assert!((1..60).contains(&done), "{done} frames after SIG{signal}");
        // Every frame in flight is finished: the frames kept are the first ones, without a gap.
        let first: Vec<String> = (1..=done).map(|k| format!("frame_{k:04}.png")).collect();
        assert_eq!(names, first, "SIG{signal}");
        for n in &names {
            image::open(d.join("lapse").join(n)).expect("every frame kept is a complete PNG");
        }
        let out = firmament(d, &args(&run));
        let err = stderr(&out);
        assert!(out.status.success(), "{err}");
        assert!(err.contains(&format!("{done} of 60 frames skipped")), "{err}");
        let rendered = if done == 59 {
            "1 frame rendered".to_owned()
        } else {
            format!("{} frames rendered", 60 - done)
        };
        assert!(err.contains(&rendered), "{err}");
        assert_eq!(
            names_in(&d.join("lapse")).len(),
            63,
            "60 frames, the GIF, the sheet, the manifest"
        );
    }
}

/// SIGKILL (or a crash, or power loss) mid-run: no handler runs, so the frame being written may
/// leave its temporary file, and a frame copied or cut short by a crash is not a whole PNG. The
/// same command then removes the temporary files, renders every missing or incomplete frame again,
/// and ends with exactly the files, byte for byte, of a run never interrupted.
#[cfg(unix)]
#[test]
fn a_killed_run_resumes_to_the_files_of_an_uninterrupted_one() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    let run = tiny("lapse", "24");
    let lapse = d.join("lapse");
    let mut child = start_until_the_first_frame(d, &run, std::process::Stdio::null());
    child.kill().expect("SIGKILL");
    let status = child.wait().expect("waits");
    assert!(!status.success(), "killed before it finished: {status:?}");

    // Only whole frames under their own names; a temporary file at most.
    let names = names_in(&lapse);
    let kept: Vec<&String> = names
        .iter()
        .filter(|n| !n.starts_with(".firmament-") && *n != "timelapse.json")
        .collect();
    assert!(
        kept.iter().all(|n| n.starts_with("frame_") && n.ends_with(".png")),
        "only frames: {names:?}"
    );
    assert!((1..24).contains(&kept.len()), "{} frames after SIGKILL", kept.len());
    for n in &kept {
        image::open(lapse.join(n)).expect("every frame kept is a complete PNG");
    }
    // What a kill mid-write leaves (the temporary file), and what a crash before the data reached
    // the disk, or a copy cut short, would leave (a frame that is not a whole PNG).
    std::fs::write(lapse.join(".firmament-Kx3f9a.tmp"), b"\x89PNG\r\n\x1a\npartial").expect("writes");
    let cut = lapse.join(kept[0].as_str());
    let bytes = std::fs::read(&cut).expect("reads");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).expect("cuts a frame short");

    let out = firmament(d, &args(&run));
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("is not a complete frame") && err.contains("rendering it again"),
        "{err}"
    );
    assert!(err.contains("removed"), "stale temporary files are reported: {err}");
    let skipped = kept.len() - 1;
    assert!(
        skipped == 0 || err.contains(&format!("{skipped} of 24 frames skipped")),
        "{err}"
    );
    assert!(err.contains(&format!("{} frames rendered", 24 - skipped)), "{err}");
    assert!(
        names_in(&lapse).iter().all(|n| !n.starts_with('.')),
        "temporary files left: {:?}",
        names_in(&lapse)
    );

    // The same frames, GIF and contact sheet as a run never interrupted.
    let whole = tempfile::tempdir().expect("temp dir");
    let out = firmament(whole.path(), &args(&run));
    assert!(out.status.success(), "{}", stderr(&out));
    let reference = whole.path().join("lapse");
    assert_eq!(names_in(&lapse), names_in(&reference));
    assert_eq!(names_in(&lapse).len(), 27);
    for name in names_in(&reference) {
        let a = std::fs::read(lapse.join(&name)).expect("resumed file");
        let b = std::fs::read(reference.join(&name)).expect("uninterrupted file");
        assert!(a == b, "{name} differs between the resumed and the uninterrupted run");
    }
}

/// `--shard I/N` renders a contiguous block into a shared folder; `--assemble` then writes the
/// GIF and the contact sheet; frames, GIF and sheet are byte-identical to one run's (the
/// showcase preset: auto-exposure adapting between frames, a flare).
#[test]
fn shards_and_assembly_give_the_bytes_of_one_run() {
    let dir = tempfile::tempdir().expect("temp dir");
    let dir = dir.path();
    let run = |extra: &[&str], out: &str| {
        let mut all = vec!["-q"];
        let base = tiny(out, "7");
        all.extend(args(&base));
        all.extend(["--preset", "golden-hour"]);
        all.extend(extra);
        firmament(dir, &all)
    };
    let one = run(&[], "one");
    assert!(one.status.success(), "{}", stderr(&one));
    for shard in ["2/3", "1/3", "3/3"] {
        let out = run(&["--shard", shard], "many");
        assert!(out.status.success(), "{shard}: {}", stderr(&out));
        assert!(!dir.join("many/timelapse.gif").exists(), "a shard wrote the GIF");
    }
    // Shard 2 of 3 holds frames 3 and 4 (of 7): ⌊7·1/3⌋ = 2 to ⌊7·2/3⌋ = 4.
    let out = firmament(dir, &["-q", "timelapse", "--assemble", "many"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(names_in(&dir.join("one")), names_in(&dir.join("many")));
    for name in names_in(&dir.join("one")) {
        let read = |run: &str| std::fs::read(dir.join(run).join(&name)).expect("a file");
        assert!(read("one") == read("many"), "{name} differs");
    }

    // Assembly refuses a folder with a frame missing; a shard refuses another time-lapse's folder.
    std::fs::remove_file(dir.join("many/frame_0004.png")).expect("removed");
    let out = firmament(dir, &["-q", "timelapse", "--assemble", "many"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("1 of 7 frames are missing or incomplete (the first: frame_0004.png)"),
        "{}",
        stderr(&out)
    );
    let mut five = args(&tiny("many", "5"))
        .iter()
        .map(|a| (*a).to_owned())
        .collect::<Vec<_>>();
    five.extend(["--shard".to_owned(), "1/2".to_owned()]);
    let mut all = vec!["-q"];
    all.extend(args(&five));
    let out = firmament(dir, &all);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("holds another time-lapse (7 frames"),
        "{}",
        stderr(&out)
    );
    for (shard, expect) in [("4/3", "must be I/N"), ("8/8", "more shards than the 7 frames")] {
        let mut all = vec!["-q"];
        let base = tiny("other", "7");
        all.extend(args(&base));
        all.extend(["--shard", shard]);
        let out = firmament(dir, &all);
        assert_ne!(out.status.code(), Some(0), "{shard}");
        assert!(stderr(&out).contains(expect), "{shard}: {}", stderr(&out));
        assert!(!dir.join("other").exists(), "{shard} made the folder");
    }
}
