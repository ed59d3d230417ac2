//! `firmament render`.

use anyhow::{Context, Result};
use firmament_render::GpuContext;
use firmament_render::headless::HeadlessRenderer;

use crate::cli::RenderArgs;
use crate::output::{OutputFormat, write_exr, write_png};

/// Renders the scene to the output file; nothing is written unless everything succeeds.
pub(crate) fn run(args: &RenderArgs) -> Result<()> {
    // Check the output before the slow parts, so a typo fails at once.
    let format = OutputFormat::from_path(&args.output)?;
    crate::output::check_parent_dir(&args.output)?;

    let mut extra = Vec::new();
    if let Some(w) = args.width {
        extra.push(format!("render.width={w}"));
    }
    if let Some(h) = args.height {
        extra.push(format!("render.height={h}"));
    }
    if let Some(time) = &args.time {
        // Quoted, so the scene's own validation names the rule for a bad time.
        extra.push(format!("time.time_of_day=\"{}\"", time.replace('"', "")));
    }
    let what = match (&args.scene, &args.scene_args.preset) {
        (Some(path), _) => path.display().to_string(),
        (None, Some(preset)) => format!("preset `{preset}`"),
        (None, None) => "the default scene".to_owned(),
    };
    let scene = super::load_scene(args.scene.as_deref(), &args.scene_args, extra)
        .with_context(|| format!("cannot build {what}"))?;
    let frame = scene.frame_at(None)?;
    let (width, height) = (scene.render.width, scene.render.height);

    let ctx = GpuContext::headless(args.backend.into())?;
    tracing::info!("rendering {what} at {width}x{height}, {}", scene.time.time_of_day);
    let mut renderer = HeadlessRenderer::new(&ctx);
    match format {
        OutputFormat::Png => write_png(&args.output, &renderer.render_ldr(&ctx, &frame, width, height)?)?,
        OutputFormat::Exr => write_exr(&args.output, &renderer.render_hdr(&ctx, &frame, width, height)?)?,
    }
    tracing::info!("wrote {}", args.output.display());
    Ok(())
}
