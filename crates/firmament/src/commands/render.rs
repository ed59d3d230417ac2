//! `firmament render`.

use anyhow::{Context, Result, bail};
use firmament_core::Frame;
use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
use firmament_core::auto_exposure::{ExposureMode, meter_image};
use firmament_core::color::{LinearRgb, linear_to_srgb};
use firmament_core::display::{DisplaySettings, Encoding, Exposure};
use firmament_core::frame::Sky;
use firmament_render::GpuContext;
use firmament_render::headless::{HeadlessRenderer, Image, Readback};

use super::scene_input::SHOWCASE_PRESET;
use crate::cli::{ExrCompression, RenderArgs};
use crate::output::{OutputFormat, write_exr, write_png, write_png16};
use rayon::prelude::*;

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
    if format == OutputFormat::Exr && args.png_bits != 8 {
        tracing::warn!(
            "--png-bits applies to .png output only: {} is an EXR",
            args.output.display()
        );
    }
    let png16 = format == OutputFormat::Png && args.png_bits == 16;

    let mut extra = super::scene_input::size_overrides(args.width, args.height);
    extra.extend(super::scene_input::time_override(args.time.as_deref()));
    let scene_args = super::scene_input::with_default_preset(&args.scene_args, args.scene.as_deref(), SHOWCASE_PRESET);
    let what = super::scene_input::describe_scene(args.scene.as_deref(), &scene_args);
    let policy = crate::untrusted::Policy::new(&args.untrusted, args.scene.as_deref())?;
    let scene = super::scene_input::load_scene(args.scene.as_deref(), &scene_args, extra, policy.confinement())
        .with_context(|| format!("cannot build {what}"))?;
    let (width, height) = (scene.render.width, scene.render.height);
    policy.check_pixels("the image", width, height)?;
    if args.reference && scene.atmosphere.model == firmament_scene::AtmosphereModelName::Physical {
        let pixels = u64::from(width) * u64::from(height);
        policy.check_paths(
            pixels.saturating_mul(args.paths),
            &format!("{} paths per pixel x {pixels} pixels", args.paths),
        )?;
    }
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
    if png16 && frame.display.bloom > 0.0 {
        bail!(
            "display.bloom = {}: --png-bits 16 writes the display model of the linear image, which has \
             no bloom (bloom is the GPU output pass's); render an 8-bit PNG, or set display.bloom = 0",
            frame.display.bloom
        );
    }

    // The f64 models' images are written as the GPU path writes its own.
    let write_radiance = |radiance: &[LinearRgb]| {
        write_reference(
            &args.output,
            (format, png16),
            compression,
            radiance,
            &reference_display(&frame, radiance, (width, height)),
            width,
            height,
        )
    };
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
        return write_radiance(&radiance);
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
        let reference = Reference::new(sky.atmosphere.clone(), &sky.suns, settings)
            .with_eclipsers(&sky.eclipsers)
            .with_rings(sky.rings.as_ref())
            .with_surface(sky.surface.as_ref());
        let conversion = sky.atmosphere.spectral_conversion();
        let radiance: Vec<LinearRgb> = reference
            .image(&frame.camera, width, height)
            .into_iter()
            .map(|s| conversion.linear_srgb(s))
            .collect();
        return write_radiance(&radiance);
    }
    let ctx = GpuContext::headless(args.backend.into())?;
    let when = scene.time.date_time.as_deref().unwrap_or(&scene.time.time_of_day);
    tracing::info!("rendering {what} at {width}x{height}, {when}");
    let mut renderer = HeadlessRenderer::new(&ctx);
    let readback = Readback {
        ldr: format == OutputFormat::Png && !png16,
        hdr: format == OutputFormat::Exr || png16,
    };
    let pixels = renderer.submit(&ctx, &frame, width, height, readback)?.collect(&ctx)?;
    let mut display = frame.display;
    if let ExposureMode::Auto(_) = display.exposure_mode {
        let state = renderer.exposure_state(&ctx)?;
        tracing::info!(
            "auto-exposure: EV100 {:.2} (metered luminance {:.4} cd/m²)",
            state.ev100,
            f64::from(state.metered_log2).exp2()
        );
        display.exposure = Exposure::from_ev100(f64::from(state.ev100));
    }
    // The EXR is written from the half floats themselves, widened as its blocks are filled.
    match (format, &pixels.ldr, &pixels.hdr) {
        (OutputFormat::Png, _, Some(hdr)) if png16 => {
            let radiance: Vec<LinearRgb> = hdr
                .pixels
                .chunks_exact(4)
                .map(|p| LinearRgb::new(p[0].to_f64(), p[1].to_f64(), p[2].to_f64()))
                .collect();
            write_png16(&args.output, &display_image(&radiance, &display, width, height, 16))?;
        }
        (OutputFormat::Png, Some(ldr), _) => write_png(&args.output, ldr)?,
        (OutputFormat::Exr, _, Some(hdr)) => write_exr(&args.output, hdr, compression)?,
        _ => bail!("the renderer returned no image to write"),
    }
    tracing::info!("wrote {}", args.output.display());
    Ok(())
}

/// Writes a reference image (linear sRGB radiance per pixel) like the GPU path writes its own
/// (`format`: the output's, and whether a PNG has 16 bits per channel).
fn write_reference(
    output: &std::path::Path,
    (format, png16): (OutputFormat, bool),
    compression: ExrCompression,
    radiance: &[LinearRgb],
    display: &DisplaySettings,
    width: u32,
    height: u32,
) -> Result<()> {
    match format {
        OutputFormat::Png if png16 => write_png16(output, &display_image(radiance, display, width, height, 16))?,
        OutputFormat::Png => {
            let image = display_image(radiance, display, width, height, 8);
            let pixels = image.pixels.iter().map(|&v| v as u8).collect();
            write_png(output, &Image { width, height, pixels })?;
        }
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

/// A reference image's display: the frame's, its exposure metered from `radiance` (the core's
/// meter, which the GPU's is tested against) when it is auto.
fn reference_display(frame: &Frame, radiance: &[LinearRgb], (width, height): (u32, u32)) -> DisplaySettings {
    let mut display = frame.display;
    if let ExposureMode::Auto(auto) = display.exposure_mode {
        let camera = firmament_core::Camera {
            aspect: f64::from(width) / f64::from(height),
            ..frame.camera
        };
        let metered = meter_image(frame, &camera, radiance, width);
        display.exposure = Exposure::from_ev100(auto.target_ev100(metered));
    }
    display
}

/// Linear radiance through `display`'s night vision, exposure, tone curve and encoding, in `f64`
/// (the core's display model, which the GPU's output pass is tested against), as RGBA of `bits`
/// (8 or 16) per channel.
fn display_image(radiance: &[LinearRgb], display: &DisplaySettings, width: u32, height: u32, bits: u32) -> Image<u16> {
    let top = f64::from((1u32 << bits) - 1);
    let encode = |v: f64| {
        let v = v.clamp(0.0, 1.0);
        let v = match display.encoding {
            Encoding::Srgb => linear_to_srgb(v),
            Encoding::None => v,
        };
        (v * top).round() as u16
    };
    Image {
        width,
        height,
        pixels: radiance
            .par_iter()
            .flat_map_iter(|c| {
                let d = display.display_linear(*c);
                [encode(d.r), encode(d.g), encode(d.b), top as u16]
            })
            .collect(),
    }
}
