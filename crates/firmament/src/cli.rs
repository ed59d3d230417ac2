//! The command line, declared with clap's derive API.

pub(crate) mod untrusted;
pub(crate) mod values;

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use firmament_core::astro::CivilDateTime;

/// firmament renders skies — physically based atmospheres around ellipsoid planets lit by several
/// suns, the sky at a real date and place, a keyframed gradient sky, classic lit objects, lens
/// flares — headless to PNG (display-referred sRGB) or EXR (linear, scene-referred float), as
/// time-lapses, or in a window.
#[derive(Debug, Parser)]
#[command(name = "firmament", version, about, long_about = None, after_help = EXAMPLES)]
pub(crate) struct Cli {
    /// Print only errors.
    #[arg(short, long, global = true)]
    pub(crate) quiet: bool,
    #[command(subcommand)]
    pub(crate) command: Command,
}

const EXAMPLES: &str = "\
Examples:
  firmament render                              # the showcase (golden-hour) → firmament.png
  firmament render --preset dawn -o dawn.png
  firmament render scene.toml --time 06:30 -o morning.exr
  firmament render --set camera.fov_y=90 --set display.tone_curve=aces_fitted
  firmament check scene.toml
  firmament render upload/scene.toml --untrusted -o out.png   # a stranger's scene: docs/RELIABILITY.md
  firmament check --preset earth-noon --set planet.radius=6360000
  firmament presets
  firmament sky-sample --altitude 0 --sun-zenith 60 --view-zenith 80 --view-azimuth 90
  firmament bench --preset earth-sunset --width 1280 --height 720 --frames 5
  firmament sun --time 2003-10-17T12:30:30-07:00 --lat 39.742476 --lon -105.1786
  firmament view --preset earth-sunset          # fly around; F1 panel, F12 screenshot
  firmament timelapse --from 2024-03-20T16:00Z --to 2024-03-20T20:00Z --frames 120 -o lapse
  firmament timelapse … --shard 3/8 -o /shared/lapse   # then: firmament timelapse --assemble /shared/lapse
  firmament envmap --preset earth-sunset --width 4096 -o sky.exr   # HDRI for Blender, Unreal…
  firmament envmap --preset earth-noon --cubemap --no-sun -o sky.exr  # 6 faces + sky.sun.json
  firmament completions bash > ~/.local/share/bash-completion/completions/firmament
  firmament manpages --dir ~/.local/share/man/man1

Exit status: 0 on success, 1 when the scene, the output or the GPU fails, 2 for bad arguments,
124 at --time-limit, 130 when interrupted.
Set FIRMAMENT_LOG (e.g. FIRMAMENT_LOG=debug) for more logging.";

#[derive(Debug, Subcommand)]
pub(crate) enum Command {
    /// Render a scene to a PNG or EXR file.
    Render(RenderArgs),
    /// Validate a scene file or preset and report the first problem.
    Check(CheckArgs),
    /// List the built-in presets.
    Presets,
    /// Print the atmosphere's radiance, transmittance and ground irradiance for one view and sun
    /// direction, from the f64 reference and the GPU path.
    SkySample(SkySampleArgs),
    /// Time the atmosphere's GPU passes, and the LUT path against the brute-force ray march.
    Bench(BenchArgs),
    /// Print the sun's position (NREL's SPA) at a date, time and place, and that day's sunrise,
    /// solar noon and sunset.
    Sun(SunArgs),
    /// Render a scene at N real instants from --from to --to into a folder of PNG frames, then an
    /// animated GIF and a contact sheet; Ctrl-C keeps the frames done, and a second run resumes.
    Timelapse(TimelapseArgs),
    /// Render the full sphere of directions around the scene's camera as a linear HDR
    /// environment map (an equirectangular EXR, or six cube faces) for image-based lighting, the
    /// suns' discs at their true radiance or given apart as JSON (--no-sun).
    Envmap(EnvmapArgs),
    /// Open a window on a scene: fly around (mouse and WASD/QE, or NeHe's keys), run and scrub
    /// the time, edit every scene value live in the panel, save the scene and screenshots.
    View(ViewArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell) to standard output.
    Completions(CompletionsArgs),
    /// Write the man pages, `firmament.1` and one per command, into a folder.
    Manpages(ManpagesArgs),
}

impl Command {
    /// The untrusted-mode flags of a command that reads a scene a stranger may have written.
    pub(crate) fn untrusted(&self) -> Option<&untrusted::UntrustedArgs> {
        match self {
            Self::Render(args) => Some(&args.untrusted),
            Self::Check(args) => Some(&args.untrusted),
            Self::SkySample(args) => Some(&args.untrusted),
            Self::Timelapse(args) => Some(&args.untrusted),
            Self::Envmap(args) => Some(&args.untrusted),
            Self::Presets
            | Self::Bench(_)
            | Self::Sun(_)
            | Self::View(_)
            | Self::Completions(_)
            | Self::Manpages(_) => None,
        }
    }
}

#[derive(Debug, Args)]
pub(crate) struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_enum)]
    pub(crate) shell: clap_complete::Shell,
}

#[derive(Debug, Args)]
pub(crate) struct ManpagesArgs {
    /// The folder to write them into (it must exist), e.g. `~/.local/share/man/man1`.
    #[arg(long, value_name = "DIR")]
    pub(crate) dir: PathBuf,
}

/// Where a scene comes from and what overrides it.
#[derive(Debug, Args)]
pub(crate) struct SceneArgs {
    /// Start from this built-in preset (see `firmament presets`); with a scene file it replaces
    /// the file's own `preset` key.
    #[arg(long, value_name = "NAME")]
    pub(crate) preset: Option<String>,
    /// Override a scene value, e.g. `--set camera.fov_y=75` or
    /// `--set sky.gradient.keyframes.0.zenith="#102040"` (repeatable; applied in order).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub(crate) overrides: Vec<String>,
}

#[derive(Debug, Args)]
pub(crate) struct RenderArgs {
    /// A scene file (TOML). Without one, the preset (default `golden-hour`, the showcase) is
    /// rendered.
    pub(crate) scene: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) scene_args: SceneArgs,
    /// Output file: `.png` (8-bit sRGB after exposure and tone curve) or `.exr` (linear float).
    #[arg(short, long, value_name = "FILE", default_value = "firmament.png")]
    pub(crate) output: PathBuf,
    /// Bits per channel of a `.png` output: 8, or 16 for grading (the display values computed
    /// from the linear image by the same exposure, tone curve and encoding, in `f64`).
    #[arg(long, value_name = "BITS", default_value_t = 8, value_parser = png_bits)]
    pub(crate) png_bits: u8,
    /// Image width in pixels (overrides `render.width`).
    #[arg(long, value_name = "W")]
    pub(crate) width: Option<u32>,
    /// Image height in pixels (overrides `render.height`).
    #[arg(long, value_name = "H")]
    pub(crate) height: Option<u32>,
    /// Local solar time of day, `HH:MM` or `HH:MM:SS` (overrides `time.time_of_day`).
    #[arg(long, value_name = "HH:MM")]
    pub(crate) time: Option<String>,
    /// Graphics API to render with.
    #[arg(long, value_enum, default_value_t = BackendArg::Auto)]
    pub(crate) backend: BackendArg,
    /// Render an atmosphere scene with the f64 reference integrator instead of the GPU: slow
    /// (seconds per pixel at high path counts) but the truth the GPU is checked against. With
    /// `atmosphere.model = "seed"`, the seed model's own f64 port, per pixel (fast).
    #[arg(long)]
    pub(crate) reference: bool,
    /// Monte Carlo paths per pixel for `--reference`'s multiple scattering, 1 to 1000000.
    #[arg(long, value_name = "N", default_value_t = 256, value_parser = clap::value_parser!(u64).range(1..=1_000_000))]
    pub(crate) paths: u64,
    /// How an `.exr` output is compressed, always lossless (default: zip).
    #[arg(long, value_enum, value_name = "KIND")]
    pub(crate) exr_compression: Option<ExrCompression>,
    #[command(flatten)]
    pub(crate) untrusted: untrusted::UntrustedArgs,
}

#[derive(Debug, Args)]
pub(crate) struct CheckArgs {
    /// The scene file to validate. Without one, the preset (or the built-in default scene) is
    /// checked.
    pub(crate) scene: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) scene_args: SceneArgs,
    #[command(flatten)]
    pub(crate) untrusted: untrusted::UntrustedArgs,
}

#[derive(Debug, Args)]
pub(crate) struct BenchArgs {
    /// An atmosphere scene file (TOML). Without one, the preset (default `earth-noon`) is used.
    pub(crate) scene: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) scene_args: SceneArgs,
    /// Image width in pixels.
    #[arg(long, value_name = "W", default_value_t = 1280)]
    pub(crate) width: u32,
    /// Image height in pixels.
    #[arg(long, value_name = "H", default_value_t = 720)]
    pub(crate) height: u32,
    /// Frames timed per figure (the median is reported), 1 to 1000.
    #[arg(long, value_name = "N", default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub(crate) frames: u32,
    /// Time the object pass instead: Gouraud against Phong on the scene's objects, or, for a
    /// scene without objects, N spheres of 1000 triangles lit by 8 lights.
    #[arg(long, value_name = "N", num_args = 0..=1, default_missing_value = "1000",
          value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub(crate) objects: Option<u32>,
    /// Time the lens-flare passes instead: occlusion and elements with 1, 8 and 64 sources
    /// (the `classic` flare, 32 depth samples each).
    #[arg(long, conflicts_with = "objects")]
    pub(crate) flares: bool,
    /// Time the scene's whole frame on the CLI's path (`Renderer::record`) against the embedded
    /// path (`Renderer::record_into` into a caller's HDR target, with and without firmament's
    /// output pass).
    #[arg(long, conflicts_with_all = ["objects", "flares"])]
    pub(crate) embedded: bool,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub(crate) json: bool,
    /// Graphics API to run on.
    #[arg(long, value_enum, default_value_t = BackendArg::Auto)]
    pub(crate) backend: BackendArg,
}

#[derive(Debug, Args)]
pub(crate) struct SkySampleArgs {
    /// An atmosphere scene file (TOML): its planet, medium and first sun (whose direction is
    /// replaced). Without one, the preset (default `earth-noon`) is used.
    pub(crate) scene: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) scene_args: SceneArgs,
    /// Eye altitude above the surface, metres (>= 0).
    #[arg(long, value_name = "M", value_parser = finite, allow_negative_numbers = true)]
    pub(crate) altitude: f64,
    /// Sun zenith angle, degrees, [0, 180].
    #[arg(long, value_name = "DEG", value_parser = finite, allow_negative_numbers = true)]
    pub(crate) sun_zenith: f64,
    /// View zenith angle, degrees, [0, 180].
    #[arg(long, value_name = "DEG", value_parser = finite, allow_negative_numbers = true)]
    pub(crate) view_zenith: f64,
    /// View azimuth measured from the sun's azimuth, degrees.
    #[arg(long, value_name = "DEG", value_parser = finite, default_value_t = 0.0, allow_negative_numbers = true)]
    pub(crate) view_azimuth: f64,
    /// Only the f64 reference.
    #[arg(long, conflicts_with = "gpu")]
    pub(crate) reference: bool,
    /// Only the GPU path.
    #[arg(long)]
    pub(crate) gpu: bool,
    /// Monte Carlo paths for the reference's multiple scattering, 1 to 10000000.
    #[arg(long, value_name = "N", default_value_t = 4096, value_parser = clap::value_parser!(u64).range(1..=10_000_000))]
    pub(crate) paths: u64,
    /// Points per path segment at which the reference gathers once-scattered sunlight along the
    /// whole segment, 0 to 1024 (0: only where paths collide). About 8 cut the noise at twilight
    /// several-fold, at several times the cost per path.
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = clap::value_parser!(u64).range(0..=1024))]
    pub(crate) line_samples: u64,
    /// Also compute the reference's light scattered exactly twice by deterministic quadrature
    /// (no Monte Carlo; about a second on a sphere, tens of seconds on an ellipsoid), beside the
    /// path tracer's tally of order 2.
    #[arg(long, conflicts_with = "gpu")]
    pub(crate) second_order: bool,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub(crate) json: bool,
    /// Graphics API for the GPU path.
    #[arg(long, value_enum, default_value_t = BackendArg::Auto)]
    pub(crate) backend: BackendArg,
    #[command(flatten)]
    pub(crate) untrusted: untrusted::UntrustedArgs,
}

#[derive(Debug, Args)]
pub(crate) struct SunArgs {
    /// Date and time, ISO 8601: `2003-10-17T12:30:30-07:00`, `2003-10-17T19:30:30Z`, or without an
    /// offset for UTC. Sunrise, solar noon and sunset are given on the same clock.
    #[arg(long, value_name = "ISO8601", value_parser = values::spa_time)]
    pub(crate) time: CivilDateTime,
    /// Latitude, degrees north, [-90, 90].
    #[arg(long, value_name = "DEG", value_parser = values::latitude, allow_negative_numbers = true)]
    pub(crate) lat: f64,
    /// Longitude, degrees east (west negative), [-180, 180].
    #[arg(long, value_name = "DEG", value_parser = values::longitude, allow_negative_numbers = true)]
    pub(crate) lon: f64,
    /// Elevation above sea level, metres.
    #[arg(long, value_name = "M", default_value_t = 0.0, value_parser = values::elevation, allow_negative_numbers = true)]
    pub(crate) elevation: f64,
    /// Annual mean local pressure for refraction, millibars, (0, 5000].
    #[arg(long, value_name = "MBAR", default_value_t = 1010.0, value_parser = values::pressure, allow_negative_numbers = true)]
    pub(crate) pressure: f64,
    /// Annual mean local temperature for refraction, °C.
    #[arg(long, value_name = "C", default_value_t = 10.0, value_parser = values::temperature, allow_negative_numbers = true)]
    pub(crate) temperature: f64,
    /// ΔT = TT − UT, seconds (default: Espenak & Meeus's estimate for the date).
    #[arg(long, value_name = "S", value_parser = values::delta_t, allow_negative_numbers = true)]
    pub(crate) delta_t: Option<f64>,
    /// Print JSON instead of text.
    #[arg(long)]
    pub(crate) json: bool,
}

#[derive(Debug, Args)]
pub(crate) struct TimelapseArgs {
    /// A scene file (TOML). Without one, the preset (or the built-in default scene) is rendered.
    pub(crate) scene: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) scene_args: SceneArgs,
    /// The first frame's instant, ISO 8601 (`2024-03-20T16:00:00Z`, `...+01:00`, or no offset
    /// for UTC); every frame is on its clock.
    #[arg(long, value_name = "ISO8601", value_parser = values::date_time, required_unless_present = "assemble")]
    pub(crate) from: Option<CivilDateTime>,
    /// The last frame's instant, ISO 8601; not before --from.
    #[arg(long, value_name = "ISO8601", value_parser = values::date_time, required_unless_present = "assemble")]
    pub(crate) to: Option<CivilDateTime>,
    /// Frames, 1 to 100000, evenly spaced from --from to --to, both included (1: --from only).
    #[arg(long, value_name = "N", value_parser = values::frame_count, required_unless_present = "assemble")]
    pub(crate) frames: Option<u32>,
    /// Output folder (created if missing): frame_0001.png …, timelapse.json (what the frames
    /// are), timelapse.gif, contact_sheet.png.
    #[arg(short, long, value_name = "DIR", required_unless_present = "assemble")]
    pub(crate) output: Option<PathBuf>,
    /// Render only shard I of N: the I-th of N contiguous blocks of the frames, into the same
    /// folder as the other shards (a Slurm array's or a Kubernetes indexed Job's index); then
    /// --assemble writes the GIF and the contact sheet.
    #[arg(long, value_name = "I/N", value_parser = values::shard)]
    pub(crate) shard: Option<(u32, u32)>,
    /// Write the GIF and the contact sheet of the sharded time-lapse in DIR, once every shard's
    /// frames are there (its timelapse.json says what they are).
    #[arg(long, value_name = "DIR", conflicts_with_all = [
        "from", "to", "frames", "output", "shard", "scene", "preset", "overrides", "width", "height", "fps",
        "exr", "overwrite", "untrusted",
    ])]
    pub(crate) assemble: Option<PathBuf>,
    /// Image width in pixels (overrides `render.width`).
    #[arg(long, value_name = "W")]
    pub(crate) width: Option<u32>,
    /// Image height in pixels (overrides `render.height`).
    #[arg(long, value_name = "H")]
    pub(crate) height: Option<u32>,
    /// The GIF's frame rate, 1 to 100 frames per second.
    #[arg(long, value_name = "FPS", default_value_t = 24, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub(crate) fps: u32,
    /// Also write each frame as linear, scene-referred EXR (frame_0001.exr …) beside its PNG.
    #[arg(long)]
    pub(crate) exr: bool,
    /// How the --exr frames are compressed, always lossless (default: zip).
    #[arg(long, value_enum, value_name = "KIND", requires = "exr")]
    pub(crate) exr_compression: Option<ExrCompression>,
    /// Render every frame again, even those already in the folder (default: resume, skipping them).
    #[arg(long)]
    pub(crate) overwrite: bool,
    /// Graphics API to render with.
    #[arg(long, value_enum, default_value_t = BackendArg::Auto)]
    pub(crate) backend: BackendArg,
    #[command(flatten)]
    pub(crate) untrusted: untrusted::UntrustedArgs,
}

#[derive(Debug, Args)]
pub(crate) struct EnvmapArgs {
    /// A scene file (TOML): the map is taken at its camera's position. Without one, the preset
    /// (default `earth-noon`) is used.
    pub(crate) scene: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) scene_args: SceneArgs,
    /// Output `.exr` file (linear float, the units of `render`'s EXR). With --cubemap, the six
    /// faces are `<stem>_px.exr` … `<stem>_nz.exr` beside it; with --time-lapse, a folder.
    #[arg(short, long, value_name = "FILE", default_value = "envmap.exr")]
    pub(crate) output: PathBuf,
    /// The equirectangular map's width, pixels: even, 4 to 16384 (the height is half of it).
    #[arg(long, value_name = "W", default_value_t = 2048, value_parser = values::equirect_width)]
    pub(crate) width: u32,
    /// Write six cube faces (OpenGL's convention in the Y-up frame: x east, y up, z south)
    /// instead of the equirectangular map.
    #[arg(long, conflicts_with = "width")]
    pub(crate) cubemap: bool,
    /// Each cube face's side with --cubemap, pixels, 1 to 16384.
    #[arg(long, value_name = "N", default_value_t = 512, requires = "cubemap",
          value_parser = clap::value_parser!(u32).range(1..=16_384))]
    pub(crate) face_size: u32,
    /// How --cubemap writes the faces: six files `<stem>_px.exr` … (faces), or one EXR of
    /// 4·N × 3·N holding them as a horizontal cross (cross: +Y above the second column, then
    /// −X +Z +X −Z, −Y below; the unused cells black with alpha 0). Default: faces.
    #[arg(long, value_enum, value_name = "LAYOUT", requires = "cubemap")]
    pub(crate) cube_layout: Option<CubeLayout>,
    /// Leave the suns' discs out of the map and write each sun's direction and irradiance after
    /// the air to `<stem>.sun.json`, for engines that light with a separate directional light.
    #[arg(long)]
    pub(crate) no_sun: bool,
    /// Local solar time of day, `HH:MM` or `HH:MM:SS` (overrides `time.time_of_day`).
    #[arg(long, value_name = "HH:MM", conflicts_with = "time_lapse")]
    pub(crate) time: Option<String>,
    /// One map per instant, --frames of them from --from to --to (both included), into the
    /// folder -o: `frame_0001.exr` … (with --cubemap `frame_0001_px.exr` …).
    #[arg(long, requires_all = ["from", "to", "frames"])]
    pub(crate) time_lapse: bool,
    /// The first map's instant with --time-lapse, ISO 8601 (`2024-03-20T16:00:00Z`).
    #[arg(long, value_name = "ISO8601", value_parser = values::date_time, requires = "time_lapse")]
    pub(crate) from: Option<CivilDateTime>,
    /// The last map's instant with --time-lapse, ISO 8601; not before --from.
    #[arg(long, value_name = "ISO8601", value_parser = values::date_time, requires = "time_lapse")]
    pub(crate) to: Option<CivilDateTime>,
    /// Maps with --time-lapse, evenly spaced from --from to --to.
    #[arg(long, value_name = "N", value_parser = values::frame_count, requires = "time_lapse")]
    pub(crate) frames: Option<u32>,
    /// How the EXR files are compressed, always lossless (default: zip).
    #[arg(long, value_enum, value_name = "KIND")]
    pub(crate) exr_compression: Option<ExrCompression>,
    /// Graphics API to render with.
    #[arg(long, value_enum, default_value_t = BackendArg::Auto)]
    pub(crate) backend: BackendArg,
    #[command(flatten)]
    pub(crate) untrusted: untrusted::UntrustedArgs,
}

#[derive(Debug, Args)]
pub(crate) struct ViewArgs {
    /// A scene file (TOML). Without one, the preset (default `golden-hour`, the showcase) is
    /// shown.
    pub(crate) scene: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) scene_args: SceneArgs,
    /// Window size in pixels, `WxH` (1 to 16384 each).
    #[arg(long, value_name = "WxH", default_value = "1280x720", value_parser = window_size)]
    pub(crate) size: (u32, u32),
    /// Draw N frames, then close (for scripts and tests).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=100_000_000))]
    pub(crate) frames: Option<u64>,
    /// After the last frame (with --frames, or on closing), write the scene as drawn to this PNG
    /// or EXR file (the panel not included).
    #[arg(long, value_name = "FILE")]
    pub(crate) screenshot: Option<PathBuf>,
    /// How EXR screenshots (Shift+F12, an `.exr` --screenshot) are compressed, always lossless
    /// (default: zip).
    #[arg(long, value_enum, value_name = "KIND")]
    pub(crate) exr_compression: Option<ExrCompression>,
    /// Where the panel's "save scene" writes (it can be changed in the panel); with --frames, the
    /// scene on screen is also saved there after the last frame, as that button does.
    #[arg(long, value_name = "FILE")]
    pub(crate) save_scene: Option<PathBuf>,
    /// Start with the clock stopped.
    #[arg(long)]
    pub(crate) paused: bool,
    /// Start with NeHe lesson 44's controls (W/S/A/D heading and pitch, Z/C/X speed).
    #[arg(long)]
    pub(crate) nehe: bool,
    /// Share of the window's pixels the scene is drawn at, (0, 1]: lower is faster on a slow
    /// adapter (the panel stays sharp).
    #[arg(long, value_name = "S", default_value_t = 1.0, value_parser = render_scale)]
    pub(crate) scale: f32,
    /// Graphics API to draw with.
    #[arg(long, value_enum, default_value_t = BackendArg::Auto)]
    pub(crate) backend: BackendArg,
}

/// `WxH`, each side 1 to 16384 pixels.
fn window_size(text: &str) -> Result<(u32, u32), String> {
    let rule = "expected WxH, each 1 to 16384 pixels (e.g. 1280x720)";
    let (w, h) = text.split_once(['x', 'X']).ok_or(rule)?;
    let side = |s: &str| match s.trim().parse::<u32>() {
        Ok(v) if (1..=16_384).contains(&v) => Ok(v),
        _ => Err(rule.to_owned()),
    };
    Ok((side(w)?, side(h)?))
}

/// A render scale in (0, 1].
fn render_scale(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(v) if v > 0.0 && v <= 1.0 => Ok(v),
        _ => Err("must be a number in (0, 1]".to_owned()),
    }
}

/// A finite number (clap's own f64 parser accepts `NaN` and `inf`).
fn finite(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err("must be a finite number".to_owned()),
        Err(e) => Err(e.to_string()),
    }
}

/// `--exr-compression` values: OpenEXR's lossless compressions. Files are 32-bit float RGBA in
/// scan lines; every one reads back the same floats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub(crate) enum ExrCompression {
    /// Uncompressed: the largest files, the least CPU.
    None,
    /// Run-length encoding: fast, but smooth float images hardly shrink.
    Rle,
    /// Deflate, 16 rows a block: small files, fast to write on every core.
    #[default]
    Zip,
    /// Deflate, one row a block: a little larger than zip.
    Zips,
    /// Wavelet and Huffman, 32 rows a block: best on noisy images (grain, stars).
    Piz,
}

/// `--cube-layout` values: how `envmap --cubemap` writes the six faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub(crate) enum CubeLayout {
    /// Six files, `<stem>_px.exr` … `<stem>_nz.exr`.
    #[default]
    Faces,
    /// One file, the faces as a horizontal cross (4·N × 3·N).
    Cross,
}

/// `--backend` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum BackendArg {
    /// Vulkan, Metal or DX12 if present, else OpenGL.
    Auto,
    /// Vulkan only.
    Vulkan,
    /// OpenGL (ES) only.
    Gl,
    /// Metal only.
    Metal,
    /// DirectX 12 only.
    Dx12,
}

impl From<BackendArg> for firmament_render::Backend {
    fn from(arg: BackendArg) -> Self {
        match arg {
            BackendArg::Auto => Self::Auto,
            BackendArg::Vulkan => Self::Vulkan,
            BackendArg::Gl => Self::Gl,
            BackendArg::Metal => Self::Metal,
            BackendArg::Dx12 => Self::Dx12,
        }
    }
}

/// `--png-bits`: 8 or 16.
fn png_bits(value: &str) -> Result<u8, String> {
    match value {
        "8" => Ok(8),
        "16" => Ok(16),
        _ => Err(format!("`{value}`: PNG channels are 8 or 16 bits")),
    }
}
