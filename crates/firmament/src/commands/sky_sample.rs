//! `firmament sky-sample`: one view ray through the atmosphere, by the reference and the GPU.

/// The GPU path's answer for one view ray, read from the atmosphere pass's LUTs.
mod probe;

use anyhow::{Context, Result, bail};
use firmament_core::atmosphere::reference::{Reference, ReferenceSettings, SecondOrderSettings, TALLIED_ORDERS};
use firmament_core::atmosphere::{Spectrum, presets};
use firmament_core::frame::{AtmosphereSky, Sky};
use firmament_core::geometry::Ray;
use firmament_render::GpuContext;
use glam::DVec3;
use probe::sample_sky;

use crate::cli::SkySampleArgs;

/// Everything sky-sample reports, for one method.
struct Sample {
    radiance: Spectrum,
    /// `radiance` by the number of times its light was scattered or reflected, [`ORDER_BANDS`].
    by_order: [Spectrum; 4],
    /// The part of `radiance` reflected by the ground at least once.
    via_ground: Spectrum,
    /// Order 2 by the reference's deterministic quadrature (`--second-order`).
    second_order: Option<Spectrum>,
    /// Standard error of `radiance` (the reference's Monte Carlo multiple scattering; zero for
    /// the GPU, whose error is bias, not noise).
    radiance_standard_error: Spectrum,
    transmittance: Spectrum,
    sky_irradiance: Spectrum,
    sun_irradiance: Spectrum,
}

/// The bands of scattering orders reported, by name: once (with any sun disc in view), twice,
/// three or four times, five times or more.
const ORDER_BANDS: [&str; 4] = ["1", "2", "3-4", "5+"];

/// A unit ENU direction at `zenith` degrees from up and `azimuth` degrees from north, clockwise.
fn enu(zenith: f64, azimuth: f64) -> DVec3 {
    let (z, a) = (zenith.to_radians(), azimuth.to_radians());
    DVec3::new(z.sin() * a.sin(), z.sin() * a.cos(), z.cos())
}

/// The samples of one run: the sky sampled, and each method's answer.
struct Samples {
    sky: AtmosphereSky,
    reference: Option<Sample>,
    gpu: Option<Sample>,
}

/// Builds the single-sun sky and samples it by the requested methods, then prints the result.
pub(crate) fn run(args: &SkySampleArgs) -> Result<()> {
    if args.json {
        println!("{}", report_json(args)?);
        return Ok(());
    }
    print_table(args, &samples(args)?);
    Ok(())
}

/// What `firmament sky-sample --json` prints.
pub(crate) fn report_json(args: &SkySampleArgs) -> Result<serde_json::Value> {
    let Samples { sky, reference, gpu } = samples(args)?;
    let conversion = sky.atmosphere.spectral_conversion();
    let describe = |s: &Sample| {
        let rgb = conversion.linear_srgb(s.radiance);
        let by_order: serde_json::Map<_, _> = ORDER_BANDS
            .iter()
            .zip(s.by_order)
            .map(|(band, radiance)| ((*band).to_owned(), radiance.to_array().into()))
            .collect();
        serde_json::json!({
            "radiance": s.radiance.to_array(),
            "radiance_by_order": by_order,
            "radiance_via_ground": s.via_ground.to_array(),
            "radiance_order_2_quadrature": s.second_order.map(|o| o.to_array()),
            "radiance_standard_error": s.radiance_standard_error.to_array(),
            "luminance": conversion.luminance(s.radiance),
            "linear_srgb": [rgb.r, rgb.g, rgb.b],
            "transmittance": s.transmittance.to_array(),
            "sky_irradiance": s.sky_irradiance.to_array(),
            "sun_irradiance": s.sun_irradiance.to_array(),
        })
    };
    Ok(serde_json::json!({
        "wavelengths_nm": sky.atmosphere.wavelengths.0,
        "units": {"radiance": "W/(m^2 sr nm)", "luminance": "cd/m^2", "irradiance": "W/(m^2 nm)"},
        "altitude_m": args.altitude,
        "sun_zenith_deg": args.sun_zenith,
        "view_zenith_deg": args.view_zenith,
        "view_azimuth_deg": args.view_azimuth,
        "reference": reference.as_ref().map(describe),
        "gpu": gpu.as_ref().map(describe),
    }))
}

/// Checks the arguments, builds the single-sun sky and samples it by the requested methods.
fn samples(args: &SkySampleArgs) -> Result<Samples> {
    if args.altitude < 0.0 {
        bail!(
            "--altitude = {}: must be >= 0 metres (above the surface)",
            args.altitude
        );
    }
    if args.altitude > firmament_scene::MAX_CAMERA_DISTANCE {
        bail!(
            "--altitude = {:e}: must be at most {:e} metres (about 6700 AU)",
            args.altitude,
            firmament_scene::MAX_CAMERA_DISTANCE
        );
    }
    for (name, value) in [("--sun-zenith", args.sun_zenith), ("--view-zenith", args.view_zenith)] {
        if !(0.0..=180.0).contains(&value) {
            bail!("{name} = {value}: must lie in [0, 180] degrees");
        }
    }
    let scene_args = super::scene_input::with_default_preset(&args.scene_args, args.scene.as_deref(), "earth-noon");
    let policy = crate::untrusted::Policy::new(&args.untrusted, args.scene.as_deref())?;
    if !args.gpu {
        let per_path = args.line_samples + 1;
        policy.check_paths(
            args.paths.saturating_mul(per_path),
            &format!("--paths {} x {per_path}, one more than --line-samples", args.paths),
        )?;
    }
    let scene = super::scene_input::load_scene(args.scene.as_deref(), &scene_args, Vec::new(), policy.confinement())
        .context("cannot build the scene")?;
    let frame = scene.frame_at(None)?;
    let Sky::Atmosphere(scene_sky) = frame.sky else {
        bail!("sky-sample samples the atmosphere: the scene needs sky.model = \"atmosphere\"");
    };
    // The sun stands north of the eye; the view azimuth is measured from it.
    let template = scene_sky
        .suns
        .first()
        .copied()
        .unwrap_or_else(|| presets::earth_sun(DVec3::Z));
    let sun = firmament_core::atmosphere::Sun {
        direction: enu(args.sun_zenith, 0.0),
        ..template
    };
    let sky = AtmosphereSky {
        atmosphere: scene_sky.atmosphere,
        suns: vec![sun],
        clouds: scene_sky.clouds,
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    };
    if !sky.clouds.is_empty() && !args.reference {
        bail!(
            "the scene has {} cloud layers ([[clouds]]): sky-sample's GPU probe reads the atmosphere's LUTs, which hold no clouds; add --reference for the reference alone",
            sky.clouds.len()
        );
    }
    let eye = DVec3::new(0.0, 0.0, args.altitude);
    let view = enu(args.view_zenith, args.view_azimuth);

    let settings = ReferenceSettings {
        paths: args.paths as usize,
        line_samples: args.line_samples as usize,
        ..ReferenceSettings::default()
    };
    let reference = (!args.gpu).then(|| reference_sample(&sky, eye, view, settings, args.second_order));
    let gpu = if args.reference {
        None
    } else {
        let ctx = GpuContext::headless(args.backend.into())?;
        let s = sample_sky(&ctx, &sky, eye, view, DVec3::ZERO)?;
        Some(Sample {
            radiance: s.radiance,
            by_order: s.by_order,
            via_ground: s.via_ground,
            second_order: None,
            radiance_standard_error: Spectrum::ZERO,
            transmittance: s.transmittance,
            sky_irradiance: s.sky_irradiance,
            sun_irradiance: s.sun_irradiance,
        })
    };
    Ok(Samples { sky, reference, gpu })
}

/// Prints the samples as a table, the reference beside the GPU.
fn print_table(args: &SkySampleArgs, samples: &Samples) {
    let Samples { sky, reference, gpu } = samples;
    let conversion = sky.atmosphere.spectral_conversion();
    let wavelengths = sky.atmosphere.wavelengths.0;
    println!(
        "altitude {} m, sun zenith {}°, view zenith {}°, view azimuth {}° from the sun",
        args.altitude, args.sun_zenith, args.view_zenith, args.view_azimuth
    );
    println!("{:<34} {:>14} {:>14} {:>10}", "", "reference", "gpu", "gpu/ref−1");
    let row = |name: String, r: Option<f64>, g: Option<f64>| {
        let cell = |v: Option<f64>| v.map_or("—".to_owned(), |v| format!("{v:.6e}"));
        let diff = match (r, g) {
            (Some(r), Some(g)) if r != 0.0 => format!("{:+.2} %", (g / r - 1.0) * 100.0),
            _ => String::new(),
        };
        println!("{name:<34} {:>14} {:>14} {diff:>10}", cell(r), cell(g));
    };
    let pick = |f: &dyn Fn(&Sample) -> Spectrum, i: usize| {
        (reference.as_ref().map(|s| f(s)[i]), gpu.as_ref().map(|s| f(s)[i]))
    };
    for (i, nm) in wavelengths.iter().enumerate() {
        let (r, g) = pick(&|s| s.radiance, i);
        row(format!("radiance {nm} nm, W/(m² sr nm)"), r, g);
    }
    for (band, name) in ORDER_BANDS.iter().enumerate() {
        for (i, nm) in wavelengths.iter().enumerate() {
            let (r, g) = pick(&|s| s.by_order[band], i);
            row(format!("  scattered {name} times, {nm} nm"), r, g);
        }
    }
    if let Some(second_order) = reference.as_ref().and_then(|r| r.second_order) {
        for (i, nm) in wavelengths.iter().enumerate() {
            let g = gpu.as_ref().map(|s| s.by_order[1][i]);
            row(format!("  order 2 by quadrature, {nm} nm"), Some(second_order[i]), g);
        }
    }
    for (i, nm) in wavelengths.iter().enumerate() {
        let (r, g) = pick(&|s| s.via_ground, i);
        row(format!("  reflected by the ground, {nm} nm"), r, g);
    }
    let luminance = |s: &Sample| conversion.luminance(s.radiance);
    row(
        "luminance, cd/m²".to_owned(),
        reference.as_ref().map(luminance),
        gpu.as_ref().map(luminance),
    );
    // Whether a difference is the reference's noise: more --paths shrink it as 1/√paths.
    if let Some(r) = &reference {
        row(
            "  reference's standard error, cd/m²".to_owned(),
            Some(conversion.luminance(r.radiance_standard_error)),
            None,
        );
    }
    for (i, channel) in ["r", "g", "b"].iter().enumerate() {
        let srgb = |s: &Sample| conversion.linear_srgb(s.radiance).to_array()[i];
        row(
            format!("linear sRGB {channel}, cd/m² scale"),
            reference.as_ref().map(srgb),
            gpu.as_ref().map(srgb),
        );
    }
    for (label, f) in [
        (
            "transmittance to space",
            (|s: &Sample| s.transmittance) as fn(&Sample) -> Spectrum,
        ),
        ("sky irradiance on the ground", |s: &Sample| s.sky_irradiance),
        ("sun irradiance on the ground", |s: &Sample| s.sun_irradiance),
    ] {
        for (i, nm) in wavelengths.iter().enumerate() {
            let (r, g) = pick(&f, i);
            row(format!("{label} {nm} nm"), r, g);
        }
    }
}

fn reference_sample(
    sky: &AtmosphereSky,
    eye: DVec3,
    view: DVec3,
    settings: ReferenceSettings,
    second_order: bool,
) -> Sample {
    let reference = Reference::new(sky.atmosphere.clone(), &sky.suns, settings)
        .with_clouds(&sky.clouds)
        .with_eclipsers(&sky.eclipsers)
        .with_rings(sky.rings.as_ref())
        .with_surface(sky.surface.as_ref());
    let planet = &sky.atmosphere.planet;
    let ray = Ray {
        origin: eye,
        direction: view,
    };
    let parts = reference.radiance(&ray);
    let second_order = second_order.then(|| reference.second_order(&ray, &SecondOrderSettings::default()));
    let ground = reference.ground_irradiance(DVec3::ZERO);
    let order = |range: std::ops::Range<usize>| -> Spectrum {
        parts.multiple.per_order.get(range).into_iter().flatten().copied().sum()
    };
    let by_order = [
        parts.single + parts.ground + parts.sun_discs,
        order(2..3),
        order(3..5),
        order(5..TALLIED_ORDERS),
    ];
    Sample {
        radiance: parts.total(),
        by_order,
        via_ground: parts.ground + parts.multiple.via_ground,
        second_order,
        radiance_standard_error: parts.multiple.standard_error,
        transmittance: reference
            .transmittance_to_space(planet.to_planet_frame(eye), planet.direction_to_planet_frame(view)),
        sky_irradiance: ground.sky,
        sun_irradiance: ground.direct,
    }
}
