//! `firmament envmap`: the full sphere of directions around the scene's camera as a linear HDR
//! environment map — an equirectangular EXR, six cube-face EXRs or one horizontal-cross EXR —
//! once, or at N instants into
//! a folder (`--time-lapse`). With `--no-sun` the discs are left out and the suns are written
//! beside the map as JSON (`sun_json.rs`). Layouts and units: docs/ENVMAP.md.

/// `<stem>.sun.json`: each sun's direction and irradiance after the air.
mod sun_json;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use firmament_core::Frame;
use firmament_core::envmap::CubeFace;
use firmament_core::frame::Sky;
use firmament_render::GpuContext;
use firmament_render::envmap::SunDiscs;
use firmament_render::headless::HeadlessRenderer;

use crate::cli::{CubeLayout, EnvmapArgs, ExrCompression};
use crate::output::{OutputFormat, check_parent_dir, write_exr};

use super::timelapse::{argument_error, check_output_dir, create_output_dir, frame_instant, frame_name, time_span};

/// The preset drawn without a scene or `--preset`.
const DEFAULT_PRESET: &str = "earth-noon";

/// What one map is written as.
#[derive(Debug, Clone, Copy)]
struct Layout {
    /// `Some(face side)` for six cube faces, `None` for the equirectangular map.
    cube: Option<u32>,
    /// Whether the faces go into one horizontal-cross image rather than six files.
    cross: bool,
    /// The equirectangular map's width, pixels.
    width: u32,
    discs: SunDiscs,
    compression: ExrCompression,
}

/// The files one map is written to, named after `output` (`<stem>.exr`): the map itself (or the
/// faces' cross) or its six faces `<stem>_px.exr` …, and with `--no-sun` `<stem>.sun.json`.
struct MapFiles {
    images: Vec<PathBuf>,
    sun_json: Option<PathBuf>,
}

impl MapFiles {
    fn new(output: &Path, layout: &Layout) -> Self {
        let stem = output.with_extension("");
        let beside = |suffix: &str| {
            let mut name = stem.clone().into_os_string();
            name.push(suffix);
            PathBuf::from(name)
        };
        let images = match layout.cube {
            Some(_) if !layout.cross => CubeFace::ALL
                .iter()
                .map(|face| beside(&format!("_{}.exr", face.suffix())))
                .collect(),
            _ => vec![output.to_path_buf()],
        };
        let sun_json = (layout.discs == SunDiscs::Omitted).then(|| beside(".sun.json"));
        Self { images, sun_json }
    }

    /// Every file, the images first.
    fn all(&self) -> impl Iterator<Item = &PathBuf> {
        self.images.iter().chain(&self.sun_json)
    }
}

/// Renders the map (or the time-lapse of maps); nothing is written unless its render succeeds.
pub(crate) fn run(args: &EnvmapArgs) -> Result<()> {
    // clap waives `requires = "cubemap"` when --width (which --cubemap conflicts with) is given.
    if args.cube_layout.is_some() && !args.cubemap {
        argument_error(
            "envmap",
            "--cube-layout arranges the faces of --cubemap: give --cubemap (and --face-size, not --width)".into(),
        );
    }
    let layout = Layout {
        cube: args.cubemap.then_some(args.face_size),
        cross: args.cube_layout.unwrap_or_default() == CubeLayout::Cross,
        width: args.width,
        discs: if args.no_sun {
            SunDiscs::Omitted
        } else {
            SunDiscs::Included
        },
        compression: args.exr_compression.unwrap_or_default(),
    };
    // Checked before the scene and the GPU, so a typo fails at once and leaves nothing.
    if !args.time_lapse && OutputFormat::from_path(&args.output)? != OutputFormat::Exr {
        bail!(
            "output {}: an environment map is linear float radiance: the file name must end in .exr",
            args.output.display()
        );
    }
    let policy = crate::untrusted::Policy::new(&args.untrusted, args.scene.as_deref())?;
    if args.time_lapse {
        policy.check_frames(args.frames.unwrap_or(1))?;
    }
    let (what_pixels, width, height) = match layout.cube {
        // The cross is twelve faces' pixels, half of them blank.
        Some(side) if layout.cross => ("the cube's cross (4 x 3 faces)", 4 * side, 3 * side),
        // The six faces are held together: counted as one strip of six.
        Some(side) => ("the cube (six faces side by side)", side, 6 * side),
        None => ("the map", layout.width, layout.width / 2),
    };
    policy.check_pixels(what_pixels, width, height)?;
    crate::limits::check_pixels(what_pixels, width, height)?;
    let extra = super::scene_input::time_override(args.time.as_deref())
        .into_iter()
        .collect();
    let scene_args = super::scene_input::with_default_preset(&args.scene_args, args.scene.as_deref(), DEFAULT_PRESET);
    let what = super::scene_input::describe_scene(args.scene.as_deref(), &scene_args);
    let scene = super::scene_input::load_scene(args.scene.as_deref(), &scene_args, extra, policy.confinement())
        .with_context(|| format!("cannot build {what}"))?;

    if args.time_lapse {
        let (Some(from), Some(to), Some(frames)) = (&args.from, &args.to, args.frames) else {
            bail!("--time-lapse needs --from, --to and --frames");
        };
        let span = time_span(from, to, frames).unwrap_or_else(|message| argument_error("envmap", message));
        let dir = args.output.as_path();
        check_output_dir(dir)?;
        let instants: Vec<_> = (0..frames).map(|k| frame_instant(from, span, k, frames)).collect();
        let build = |k: usize| {
            let civil = &instants[k];
            scene
                .frame_at_date_time(civil)
                .with_context(|| format!("cannot build {what} at {civil}"))
        };
        // The first and last instants up front: a scene without a real date fails at once.
        check_frame(&build(0)?, &layout)?;
        check_frame(&build(instants.len() - 1)?, &layout)?;
        let ctx = GpuContext::headless(args.backend.into())?;
        create_output_dir(dir)?;
        let mut renderer = HeadlessRenderer::new(&ctx);
        tracing::info!(
            "environment maps of {what}: {frames} from {from} to {to} → {}",
            dir.display()
        );
        for k in 0..instants.len() {
            let files = MapFiles::new(&dir.join(frame_name(k as u32, frames, "exr")), &layout);
            render_map(&ctx, &mut renderer, &build(k)?, &layout, &files)?;
        }
        return Ok(());
    }

    let files = MapFiles::new(&args.output, &layout);
    for path in files.all() {
        check_parent_dir(path)?;
    }
    let frame = match &args.time {
        Some(_) => scene.frame_at(Some(scene.time_of_day()?)),
        None => scene.frame_at(None),
    }
    .with_context(|| format!("cannot build {what}"))?;
    check_frame(&frame, &layout)?;
    let ctx = GpuContext::headless(args.backend.into())?;
    let mut renderer = HeadlessRenderer::new(&ctx);
    tracing::info!("environment map of {what} → {}", args.output.display());
    render_map(&ctx, &mut renderer, &frame, &layout, &files)
}

/// Fails unless `frame` can be drawn as `layout` asks: `--no-sun` needs suns to leave out.
fn check_frame(frame: &Frame, layout: &Layout) -> Result<()> {
    if layout.discs == SunDiscs::Omitted && !matches!(frame.sky, Sky::Atmosphere(_)) {
        bail!(
            "--no-sun leaves out the physical atmosphere's suns and writes them as JSON: the scene \
             needs sky.model = \"atmosphere\" (other skies draw their suns within the map)"
        );
    }
    Ok(())
}

/// Renders `frame` as `layout` says and writes `files`.
fn render_map(
    ctx: &GpuContext,
    renderer: &mut HeadlessRenderer,
    frame: &Frame,
    layout: &Layout,
    files: &MapFiles,
) -> Result<()> {
    match layout.cube {
        Some(side) => {
            let cube = renderer.render_cube_faces(ctx, frame, side, layout.discs)?;
            if layout.cross {
                write_exr(&files.images[0], &cube.to_horizontal_cross(), layout.compression)?;
            } else {
                for (face, path) in CubeFace::ALL.iter().zip(&files.images) {
                    write_exr(path, cube.face(*face), layout.compression)?;
                }
            }
        }
        None => {
            let map = renderer.render_equirect(ctx, frame, layout.width, layout.discs)?;
            write_exr(&files.images[0], &map, layout.compression)?;
        }
    }
    if let Some(path) = &files.sun_json {
        sun_json::write(path, frame)?;
    }
    for path in files.all() {
        tracing::info!("wrote {}", path.display());
    }
    Ok(())
}
