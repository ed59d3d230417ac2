//! `firmament render`.

use anyhow::{Context, Result, bail};
use firmament_core::Frame;
use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
use firmament_core::color::{LinearRgb, linear_to_srgb};
use firmament_core::display::Encoding;
use firmament_core::frame::Sky;
use firmament_render::GpuContext;
use firmament_render::headless::{HeadlessRenderer, Image, Readback};

use crate::cli::{ExrCompression, RenderArgs};
use crate::output::{OutputFormat, write_exr, write_png};

/// Renders the scene to the output file; nothing is written unless everything succeeds.
pub(crate) fn run(args: &RenderArgs) -> Result<()> {
    // Check the output before the slow parts, so a typo fails at once.
    let format = OutputFormat::from_path(&args.output)?;
    crate::output::check_parent_dir(&args.output)?;
    if format == OutputFormat::Png && args.exr_compression.is_some() {
        tracing::warn!(
            "--exr-compression applies to .exr output only: {} is a PNG",
            args.output.display()
        );
    }
    let compression = args.exr_compression.unwrap_or_default();

    let mut extra = super::scene_input::size_overrides(args.width, args.height);
    if let Some(time) = &args.time {
        // Quoted, so the scene's own validation names the rule for a bad time.
        extra.push(format!("time.time_of_day=\"{}\"", time.replace('"', "")));
    }
    let what = super::scene_input::describe_scene(args.scene.as_deref(), &args.scene_args);
    let scene = super::scene_input::load_scene(args.scene.as_deref(), &args.scene_args, extra)
        .with_context(|| format!("cannot build {what}"))?;
    let (width, height) = (scene.render.width, scene.render.height);
    if args.reference {
        crate::limits::check_reference_pixels("the image", width, height)?;
    } else {
        crate::limits::check_pixels("the image", width, height)?;
    }
    // `--time` on a scene with `time.date_time` sets the clock time on that date.
    let frame = match &args.time {
        Some(_) => scene.frame_at(Some(scene.time_of_day()?)),
        None => scene.frame_at(None),
    }
    .with_context(|| format!("cannot build {what}"))?;

    if args.reference
        && let Sky::Empirical(sky) = &frame.sky
    {
        // The seed's model is its own reference: EmpiricalAtmosphere::color per pixel centre, in
        // f64 (what the GPU pass is tested against), times the sky's luminance scale.
        tracing::info!("rendering {what} with the seed model's f64 port at {width}x{height}");
        let camera = firmament_core::Camera {
            aspect: f64::from(width) / f64::from(height),
            ..frame.camera
        };
        let radiance: Vec<LinearRgb> = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| {
                let ndc = glam::DVec2::new(
                    (f64::from(x) + 0.5) / f64::from(width) * 2.0 - 1.0,
                    1.0 - (f64::from(y) + 0.5) / f64::from(height) * 2.0,
                );
                sky.radiance(camera.position, camera.view_direction(ndc))
            })
            .collect();
        return write_reference(&args.output, format, compression, &radiance, &frame, width, height);
    }
    if args.reference {
        let Sky::Atmosphere(sky) = &frame.sky else {
            bail!("--reference renders the atmosphere: the scene needs sky.model = \"atmosphere\"");
        };
        tracing::info!(
            "rendering {what} with the f64 reference at {width}x{height}, {} paths per pixel",
            args.paths
        );
        let settings = ReferenceSettings {
            paths: args.paths as usize,
            ..ReferenceSettings::default()
        };
        let reference = Reference::new(sky.atmosphere, &sky.suns, settings);
        let conversion = sky.atmosphere.spectral_conversion();
        let radiance: Vec<LinearRgb> = reference
            .image(&frame.camera, width, height)
            .into_iter()
            .map(|s| conversion.linear_srgb(s))
            .collect();
        return write_reference(&args.output, format, compression, &radiance, &frame, width, height);
    }
    let ctx = GpuContext::headless(args.backend.into())?;
    let when = scene.time.date_time.as_deref().unwrap_or(&scene.time.time_of_day);
    tracing::info!("rendering {what} at {width}x{height}, {when}");
    let mut renderer = HeadlessRenderer::new(&ctx);
    let readback = Readback {
        ldr: format == OutputFormat::Png,
        hdr: format == OutputFormat::Exr,
    };
    let pixels = renderer.submit(&ctx, &frame, width, height, readback)?.collect(&ctx)?;
    // The EXR is written from the half floats themselves, widened as its blocks are filled.
    match (format, &pixels.ldr, &pixels.hdr) {
        (OutputFormat::Png, Some(ldr), _) => write_png(&args.output, ldr)?,
        (OutputFormat::Exr, _, Some(hdr)) => write_exr(&args.output, hdr, compression)?,
        _ => bail!("the renderer returned no image to write"),
    }
    tracing::info!("wrote {}", args.output.display());
    Ok(())
}

/// Writes a reference image (linear sRGB radiance per pixel) like the GPU path writes its own.
fn write_reference(
    output: &std::path::Path,
    format: OutputFormat,
    compression: ExrCompression,
    radiance: &[LinearRgb],
    frame: &Frame,
    width: u32,
    height: u32,
) -> Result<()> {
    match format {
        OutputFormat::Png => write_png(output, &reference_ldr(radiance, frame, width, height))?,
        OutputFormat::Exr => write_exr(output, &reference_hdr(radiance, width, height), compression)?,
    }
    tracing::info!("wrote {}", output.display());
    Ok(())
}

/// The reference's linear sRGB as the HDR image the GPU would give (RGBA f32).
fn reference_hdr(radiance: &[LinearRgb], width: u32, height: u32) -> Image<f32> {
    Image {
        width,
        height,
        pixels: radiance
            .iter()
            .flat_map(|c| [c.r as f32, c.g as f32, c.b as f32, 1.0])
            .collect(),
    }
}

/// The reference through the scene's exposure and tone curve, sRGB-encoded like the GPU's
/// tonemap pass (the core's display model is what that pass is tested against).
fn reference_ldr(radiance: &[LinearRgb], frame: &Frame, width: u32, height: u32) -> Image<u8> {
    let encode = |v: f64| {
        let v = v.clamp(0.0, 1.0);
        let v = match frame.display.encoding {
            Encoding::Srgb => linear_to_srgb(v),
            Encoding::None => v,
        };
        (v * 255.0).round() as u8
    };
    Image {
        width,
        height,
        pixels: radiance
            .iter()
            .flat_map(|c| {
                let d = frame.display.display_linear(*c);
                [encode(d.r), encode(d.g), encode(d.b), 255]
            })
            .collect(),
    }
}
