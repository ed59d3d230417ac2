//! Clouds in the reference against closed forms: a uniform layer's transmittance along the exact
//! path length through its shell, single scattering in a thin slab, a thick slab's reflectance
//! against δ-Eddington and its energy balance (of clouds, and of an air as thick as Venus's), a
//! white furnace, and the path tracer's orders against the deterministic single scattering.

use std::f64::consts::PI;

use glam::DVec3;

use super::*;
use crate::atmosphere::clouds::{CloudKind, DualHenyeyGreenstein};
use crate::atmosphere::{Planet, Sun, presets};

fn relative(a: Spectrum, b: Spectrum) -> f64 {
    ((a - b) / b).abs().max_element()
}

/// An atmosphere with no air at all on `planet`, over a black ground.
fn vacuum(planet: Planet) -> Atmosphere {
    let mut atmosphere = presets::earth();
    atmosphere.planet = planet;
    atmosphere.medium.terms[0].scattering = Spectrum::ZERO;
    atmosphere.medium.terms[1].scattering = Spectrum::ZERO;
    atmosphere.medium.terms[1].absorption = Spectrum::ZERO;
    atmosphere.medium.terms[2].absorption = Spectrum::ZERO;
    atmosphere.medium.ground_albedo = Spectrum::ZERO;
    atmosphere
}

/// A direction `zenith` degrees from +Z, turned `azimuth` degrees from +X towards +Y.
fn direction(zenith: f64, azimuth: f64) -> DVec3 {
    let (z, a) = (zenith.to_radians(), azimuth.to_radians());
    DVec3::new(z.sin() * a.cos(), z.sin() * a.sin(), z.cos())
}

/// A layer of `kind` with a single Henyey–Greenstein lobe of asymmetry `g`.
fn slab(bottom: f64, top: f64, density: f64, albedo: f64, g: f64, kind: CloudKind) -> CloudLayer {
    CloudLayer {
        albedo,
        phase: DualHenyeyGreenstein {
            g_forward: g,
            g_back: 0.0,
            blend: 1.0,
        },
        ..CloudLayer::new(bottom, top, 1.0, density, kind)
    }
}

/// The path length between two heights along a ray, found independently of the integrator:
/// bisection on the exact altitude after a 10 m march.
fn length_between(planet: &Planet, ray: &Ray, bottom: f64, top: f64) -> f64 {
    let cross = |level: f64| {
        let f = |t: f64| planet.altitude(ray.at(t)) - level;
        let mut t = 0.0;
        while f(t + 10.0) < 0.0 {
            t += 10.0;
        }
        let (mut lo, mut hi) = (t, t + 10.0);
        for _ in 0..80 {
            let m = 0.5 * (lo + hi);
            if f(m) < 0.0 {
                lo = m;
            } else {
                hi = m;
            }
        }
        0.5 * (lo + hi)
    };
    cross(top) - cross(bottom)
}

/// A uniform layer's transmittance from the ground is `exp(−density·L)` times the air's, `L` the
/// exact path length through the shell, on a sphere and on the WGS84 ellipsoid; and `L` is
/// `(top − bottom)/cos θ` within 0.5 % for view zenith angles 0–75° (the Earth's curvature
/// shortens it by 0.43 % at 75° for a layer 1.5–2.5 km up).
#[test]
fn a_uniform_layer_dims_by_its_path_length() {
    let (bottom, top, density) = (1_500.0, 2_500.0, 2e-3);
    let layer = slab(bottom, top, density, 1.0, 0.85, CloudKind::Uniform);
    let earth = presets::earth();
    let sphere = Planet::sphere(earth.planet.radii.x, earth.planet.atmosphere_height);
    let mut worst_flat: f64 = 0.0;
    for (planet, latitude) in [(sphere, 0.0f64), (earth.planet, 45.0)] {
        let atmosphere = Atmosphere {
            planet,
            ..earth.clone()
        };
        let clear = Reference::new(atmosphere.clone(), &[], ReferenceSettings::default());
        let cloudy = clear.clone().with_clouds(std::slice::from_ref(&layer));
        let ground = planet.surface_point(latitude.to_radians(), 0.3);
        let up = planet.up(ground);
        let east = DVec3::Z.cross(up).normalize();
        let north = up.cross(east);
        for zenith in [0.0f64, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0] {
            let (s, c) = zenith.to_radians().sin_cos();
            let ray = Ray::new(ground + up * 2.0, up * c + (east * 0.6 + north * 0.8) * s).unwrap();
            let length = length_between(&planet, &ray, bottom, top);
            let ratio = cloudy.transmittance_to_space(ray.origin, ray.direction)
                / clear.transmittance_to_space(ray.origin, ray.direction);
            let want = (-density * length).exp();
            assert!(
                (ratio / want - Spectrum::ONE).abs().max_element() < 1e-8,
                "{zenith}°: {ratio} vs {want}"
            );
            if zenith <= 75.0 {
                let flat = (top - bottom) / c;
                worst_flat = worst_flat.max((length / flat - 1.0).abs());
            }
        }
    }
    println!("worst |L/((top − bottom)/cos θ) − 1| for 0–75°: {worst_flat:.5}");
    assert!(worst_flat < 0.005, "{worst_flat}");
}

/// A view ray through an opaque slab: the transmittance is still exact (the quadrature stops
/// where the ray is opaque, the optical depth does not), and the ground behind adds nothing.
#[test]
fn an_opaque_slab_ends_the_view() {
    let planet = Planet::sphere(6_371_000.0, 60_000.0);
    let (bottom, top, density) = (1_000.0, 2_000.0, 0.05);
    let layer = slab(bottom, top, density, 1.0, 0.85, CloudKind::Uniform);
    let mut atmosphere = presets::earth();
    atmosphere.planet = planet;
    let settings = ReferenceSettings {
        view_steps: 256,
        paths: 1,
        ..Default::default()
    };
    let sun = presets::earth_sun(direction(30.0, 0.0));
    let clear = Reference::new(atmosphere.clone(), &[sun], settings);
    let cloudy = clear.clone().with_clouds(&[layer]);
    let eye = DVec3::new(0.0, 0.0, 6_371_000.0 + 5_000.0);
    let view = Ray::new(eye, direction(150.0, 180.0)).unwrap();
    let (_, transmittance) = cloudy.single_scattering_before(&view, f64::INFINITY);
    assert_eq!(transmittance, Spectrum::ZERO, "the view ray ends on the ground");
    let upward = Ray::new(DVec3::new(0.0, 0.0, 6_371_000.0 + 2.0), direction(20.0, 0.0)).unwrap();
    let (single, transmittance) = cloudy.single_scattering_before(&upward, f64::INFINITY);
    let (_, clear_transmittance) = clear.single_scattering_before(&upward, f64::INFINITY);
    let length = length_between(&planet, &upward, bottom, top);
    let want = clear_transmittance * (-density * length).exp();
    assert!(relative(transmittance, want) < 1e-8, "{transmittance} vs {want}");
    assert!(single.min_element() > 0.0);
}

/// Single scattering in a thin uniform slab (optical depth 0.1, albedo 0.9, the droplets'
/// dual Henyey–Greenstein) in a vacuum on a nearly flat planet, seen from below and from above,
/// against the plane-parallel closed forms (Chandrasekhar, *Radiative Transfer*, 1950):
/// below `E·ω·P(ν)·μ₀·(e^(−τ/μ) − e^(−τ/μ₀))/(μ − μ₀)`, above
/// `E·ω·P(ν)·μ₀/(μ + μ₀)·(1 − e^(−τ(1/μ + 1/μ₀)))`. Within 1e-5: the planet (R = 10¹⁰ m) is
/// flat to `h·tan²θ/R` ≈ 1e-6 at 70°; looking straight up the quadrature agrees to 1e-9.
#[test]
fn single_scattering_in_a_thin_slab_matches_the_closed_forms() {
    let radius = 1e10;
    let (bottom, top, density, albedo) = (1_000.0, 1_500.0, 2e-4, 0.9);
    let tau = density * (top - bottom);
    let layer = CloudLayer {
        albedo,
        ..CloudLayer::new(bottom, top, 1.0, density, CloudKind::Uniform)
    };
    let atmosphere = vacuum(Planet::sphere(radius, 10_000.0));
    let settings = ReferenceSettings {
        view_steps: 64,
        paths: 1,
        ..Default::default()
    };
    let ground = DVec3::new(0.0, 0.0, radius);
    for (sun_zenith, view_zenith, azimuth) in [(30.0f64, 0.0f64, 0.0f64), (60.0, 40.0, 180.0), (20.0, 70.0, 0.0)] {
        let sun = presets::earth_sun(direction(sun_zenith, 0.0));
        let reference = Reference::new(atmosphere.clone(), &[sun], settings).with_clouds(std::slice::from_ref(&layer));
        let mu0 = sun_zenith.to_radians().cos();
        let mu = view_zenith.to_radians().cos();
        // From below, looking up.
        let up = direction(view_zenith, azimuth);
        let (single, transmittance) =
            reference.single_scattering_before(&Ray::new(ground + DVec3::Z * 2.0, up).unwrap(), f64::INFINITY);
        let phase = layer.phase.eval(up.dot(sun.direction));
        let want = sun.irradiance * albedo * phase * mu0 * ((-tau / mu).exp() - (-tau / mu0).exp()) / (mu - mu0);
        assert!(
            relative(single, want) < 1e-5,
            "below {view_zenith}°: {single} vs {want}"
        );
        let t_want = Spectrum::splat((-tau / mu).exp());
        assert!(relative(transmittance, t_want) < 1e-5, "{transmittance} vs {t_want}");
        // From above, looking down.
        let down = direction(180.0 - view_zenith, azimuth);
        let (single, _) =
            reference.single_scattering_before(&Ray::new(ground + DVec3::Z * 3_000.0, down).unwrap(), f64::INFINITY);
        let phase = layer.phase.eval(down.dot(sun.direction));
        let want = sun.irradiance * albedo * phase * mu0 / (mu + mu0) * (1.0 - (-tau * (1.0 / mu + 1.0 / mu0)).exp());
        assert!(
            relative(single, want) < 1e-5,
            "above {view_zenith}°: {single} vs {want}"
        );
    }
}

/// δ-Eddington reflectance of a conservative slab of optical depth `tau` and Henyey–Greenstein
/// asymmetry `g` over a black surface, lit at `mu0` (Joseph, Wiscombe & Weinman, "The
/// Delta-Eddington Approximation for Radiative Flux Transfer", J. Atmos. Sci. 33, 1976: `f = g²`,
/// `τ' = (1 − f)τ`, `g' = g/(1 + g)`), in the closed form of the conservative Eddington
/// two-stream solution (Meador & Weaver, J. Atmos. Sci. 37, 1980, eq. for ω = 1):
/// `R = (γτ' + (γ₃ − γμ₀)(1 − e^(−τ'/μ₀)))/(1 + γτ')`, `γ = 3(1 − g')/4`, `γ₃ = (2 − 3g'μ₀)/4`.
fn delta_eddington_reflectance(tau: f64, g: f64, mu0: f64) -> f64 {
    let f = g * g;
    let tau = (1.0 - f) * tau;
    let g = (g - f) / (1.0 - f);
    let gamma = 0.75 * (1.0 - g);
    let gamma3 = (2.0 - 3.0 * g * mu0) / 4.0;
    (gamma * tau + (gamma3 - gamma * mu0) * (1.0 - (-tau / mu0).exp())) / (1.0 + gamma * tau)
}

/// A thick conservative slab (Henyey–Greenstein g = 0.85, albedo 1) in a vacuum over a black
/// ground on a nearly flat planet (R = 10¹⁰ m).
fn thick_slab(tau: f64, suns: &[Sun], paths: usize, background: Spectrum) -> Reference {
    let (bottom, top) = (1_000.0, 2_000.0);
    let layer = slab(bottom, top, tau / (top - bottom), 1.0, 0.85, CloudKind::Uniform);
    let settings = ReferenceSettings {
        paths,
        background,
        ..Default::default()
    };
    Reference::new(vacuum(Planet::sphere(1e10, 10_000.0)), suns, settings).with_clouds(&[layer])
}

/// Above and below [`thick_slab`]'s slab.
const ABOVE: f64 = 1e10 + 3_000.0;
const BELOW: f64 = 1e10 + 500.0;

/// Joseph et al. (1976, figs. 2–4) and King & Harshvardhan ("Comparative Accuracy of Selected
/// Multiple Scattering Approximations", J. Atmos. Sci. 43, 1986) find δ-Eddington's fluxes of
/// thick conservative layers within a few per cent of exact (doubling) for μ₀ ≳ 0.5: the
/// tolerance of the reflectance against it, besides the Monte Carlo noise.
const DELTA_EDDINGTON_ACCURACY: f64 = 0.04;

/// The path tracer's reflectance and transmittance of a thick slab (optical depth 10–30) by
/// reciprocity: the slab lit by a uniform sky (the reference's `background`) and seen from
/// above (below) at zenith angle θ₀ shows `R(μ₀)` (`T(μ₀)`, direct beam included) times the
/// sky's radiance — the hemispherical reflectance (transmittance) for a sun at θ₀, as the
/// slab's reflection function is symmetric. Every path's weight is exactly 1 here (grey, no
/// absorption, the phase function drawn exactly), so each estimate is a binomial share with
/// standard error `√(R(1 − R)/N)`. R + T = 1 within the noise (energy conservation, and no path
/// cut short: [`MAX_EVENTS_WITH_CLOUDS`](path_tracer)), and R is δ-Eddington's within its accuracy.
#[test]
fn a_thick_slab_reflects_as_delta_eddington_and_conserves_energy() {
    let paths = 4096;
    for (tau, sun_zenith) in [(10.0, 0.0f64), (20.0, 30.0), (30.0, 60.0)] {
        let reference = thick_slab(tau, &[], paths, Spectrum::ONE);
        let reflected = check_reflectance_by_reciprocity(&reference, ("clouds", tau, 0.85), sun_zenith, (ABOVE, BELOW));
        // Grey: every wavelength alike.
        assert!(relative(reflected, Spectrum::splat(reflected.x)) < 1e-9);
    }
}

/// An air as thick as Venus's (vertical optical depth 40 and 60, Henyey–Greenstein g = 0.3,
/// albedo 1, no clouds) over a black ground, by reciprocity as [`thick_slab`]'s test: R + T = 1
/// within the noise and R is δ-Eddington's within its accuracy. A path that leaves through the
/// ground takes about τ²(1 − g) ≈ 1100–2500 events here: with the cut at 1000 events the air's
/// paths had before, T at τ = 60 came out half as large and R + T = 0.970 (±0.006).
#[test]
fn a_thick_air_reflects_as_delta_eddington_and_conserves_energy() {
    use crate::atmosphere::medium::{Density, DensityLayer, DensityProfile, MediumTerm, Phase};
    let g = 0.3;
    for (tau, sun_zenith) in [(40.0, 0.0f64), (60.0, 60.0)] {
        let mut atmosphere = vacuum(Planet::sphere(1e10, 1_000.0));
        atmosphere.medium.terms = vec![MediumTerm {
            scattering: Spectrum::splat(tau / 1_000.0),
            absorption: Spectrum::ZERO,
            density: Density::Profile(DensityProfile::single(DensityLayer::constant())),
            phase: Phase::HenyeyGreenstein { g },
        }];
        let settings = ReferenceSettings {
            paths: 2048,
            background: Spectrum::ONE,
            ..Default::default()
        };
        let reference = Reference::new(atmosphere, &[], settings);
        check_reflectance_by_reciprocity(&reference, ("air", tau, g), sun_zenith, (1e10 + 2_000.0, 1e10 + 0.01));
    }
}

/// Checks a conservative slab of `(label, optical depth, g)` over a black ground, lit by a
/// uniform sky of radiance 1, seen from `heights` (above it, below it) at `sun_zenith` degrees:
/// R + T = 1 within four standard errors and R δ-Eddington's within its accuracy. Returns R.
fn check_reflectance_by_reciprocity(
    reference: &Reference,
    (label, tau, g): (&str, f64, f64),
    sun_zenith: f64,
    (above, below): (f64, f64),
) -> Spectrum {
    let paths = reference.settings.paths;
    let started = std::time::Instant::now();
    let seen = |height: f64, zenith: f64| {
        let ray = Ray::new(DVec3::new(0.0, 0.0, height), direction(zenith, 0.0)).unwrap();
        path_tracer::multiple_scattering(reference, &ray, 0, paths, f64::INFINITY)
    };
    let (reflected, transmitted) = (seen(above, 180.0 - sun_zenith), seen(below, sun_zenith));
    let label = format!(
        "{label} τ {tau}, θ₀ {sun_zenith}° ({paths} paths each, {:.1?})",
        started.elapsed()
    );
    let reflectance = (reflected.total.x, reflected.standard_error.x);
    let transmittance = (transmitted.total.x, transmitted.standard_error.x);
    assert_balanced(&label, (tau, g, sun_zenith), reflectance, transmittance);
    reflected.total
}

/// Asserts that a conservative slab of `(optical depth, g)` lit at `sun_zenith` degrees
/// reflects and transmits `(value, standard error)` with R + T = 1 within four standard errors
/// and R δ-Eddington's within its accuracy.
fn assert_balanced(label: &str, (tau, g, sun_zenith): (f64, f64, f64), (r, sr): (f64, f64), (t, st): (f64, f64)) {
    let want = delta_eddington_reflectance(tau, g, sun_zenith.to_radians().cos());
    println!(
        "{label}: R {r:.4} ± {sr:.4} (δ-Eddington {want:.4}, {:+.2} %), T {t:.4} ± {st:.4}, R + T {:.4}",
        100.0 * (r / want - 1.0),
        r + t
    );
    assert!(((r + t) - 1.0).abs() < 4.0 * (sr * sr + st * st).sqrt(), "energy");
    assert!(
        (r - want).abs() < DELTA_EDDINGTON_ACCURACY * want + 4.0 * sr,
        "δ-Eddington"
    );
}

/// The same slab lit by a sun: the reflected flux is the irradiance on a surface facing down
/// above the slab ([`path_tracer::sky_radiance_mean`], next-event estimation towards the sun
/// through the cloud), the transmitted one the diffuse irradiance on the ground plus the direct
/// beam. R + T = 1 within the noise, and R is δ-Eddington's within its accuracy. Far noisier
/// than reciprocity: the forward peak of the phase function towards the sun makes the sun's
/// light arrive in rare large contributions.
#[test]
#[ignore = "16 s: cargo test --release -p firmament-core sunlit_thick_slab -- --ignored"]
fn a_sunlit_thick_slab_reflects_as_delta_eddington_and_conserves_energy() {
    let paths = 32_768;
    let up = DVec3::Z;
    for (tau, sun_zenith) in [(10.0, 0.0f64), (20.0, 30.0), (30.0, 60.0)] {
        let sun = presets::earth_sun(direction(sun_zenith, 0.0));
        let reference = thick_slab(tau, &[sun], paths, Spectrum::ZERO);
        let mu0 = sun_zenith.to_radians().cos();
        let incident = sun.irradiance.x * mu0;
        let started = std::time::Instant::now();
        let reflected = path_tracer::sky_radiance_mean(&reference, DVec3::new(0.0, 0.0, ABOVE), -up, paths);
        let transmitted = path_tracer::sky_radiance_mean(&reference, DVec3::new(0.0, 0.0, BELOW), up, paths);
        let label = format!(
            "sunlit τ {tau}, θ₀ {sun_zenith}° ({paths} paths each, {:.1?})",
            started.elapsed()
        );
        let r = reflected.total.x * PI / incident;
        let t = transmitted.total.x * PI / incident + (-tau / mu0).exp();
        let (sr, st) = (
            reflected.standard_error.x * PI / incident,
            transmitted.standard_error.x * PI / incident,
        );
        assert_balanced(&label, (tau, 0.85, sun_zenith), (r, sr), (t, st));
    }
}

/// A white furnace with clouds: no absorption, a white ground, uniform light from space. Every
/// path's weight stays exactly 1 (grey air, phase functions drawn exactly), so the radiance is
/// the background's exactly, whatever the clouds — a check of the trackers' weights and of
/// paths ending only when they leave (the forced first segment is checked statistically below).
#[test]
fn a_grey_white_furnace_with_clouds_conserves_energy_exactly() {
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(6_371_000.0, 60_000.0);
    atmosphere.medium.terms[1].absorption = Spectrum::ZERO;
    atmosphere.medium.terms[2].absorption = Spectrum::ZERO;
    atmosphere.medium.ground_albedo = Spectrum::ONE;
    atmosphere.medium.terms[0].scattering = Spectrum::splat(atmosphere.medium.terms[0].scattering.y);
    atmosphere.medium.terms[1].phase = crate::atmosphere::Phase::HenyeyGreenstein { g: 0.8 };
    let background = Spectrum::new(1.0, 2.0, 3.0);
    let settings = ReferenceSettings {
        paths: 200,
        background,
        ..Default::default()
    };
    let layers = [
        CloudLayer::new(1_000.0, 1_800.0, 1.0, 0.01, CloudKind::Uniform),
        CloudLayer::new(1_500.0, 3_000.0, 0.5, 0.002, CloudKind::Stratocumulus),
    ];
    let reference = Reference::new(atmosphere.clone(), &[], settings).with_clouds(&layers);
    let ground = 6_371_000.0;
    for (origin, view) in [
        (DVec3::new(0.0, 0.0, ground + 2.0), DVec3::new(0.3, 0.0, 1.0)),
        (DVec3::new(0.0, 0.0, ground + 1_200.0), DVec3::new(1.0, 0.0, 0.0)),
        (DVec3::new(0.0, 0.0, ground + 8_000.0), DVec3::new(0.2, 0.1, -1.0)),
    ] {
        let ray = Ray::new(origin, view).unwrap();
        let radiance = path_tracer::multiple_scattering(&reference, &ray, 0, settings.paths, f64::INFINITY);
        assert!(
            relative(radiance.total, background) < 1e-9,
            "{ray:?}: {}",
            radiance.total
        );
    }
}

/// The path tracer's first order through a cloud (a uniform and a textured layer kind, over
/// Earth's air) is the deterministic single scattering plus the sunlit ground, within the noise;
/// and its orders ≥ 2 with the first segment forced through the tabulated clouds agree with its
/// unforced orders ≥ 1 less those.
#[test]
fn the_path_tracer_s_orders_agree_with_the_deterministic_single_scattering() {
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(6_371_000.0, 60_000.0);
    let sun = presets::earth_sun(direction(40.0, 0.0));
    let eye = DVec3::new(0.0, 0.0, 6_371_000.0 + 2.0);
    for kind in [CloudKind::Uniform, CloudKind::Stratus] {
        let layer = CloudLayer::new(1_000.0, 1_600.0, 1.0, 1.5e-3, kind);
        let settings = ReferenceSettings {
            view_steps: 256,
            paths: 8192,
            ..Default::default()
        };
        let view = Ray::new(eye, direction(30.0, 150.0)).unwrap();
        // Batches with their own seeds give the first order's standard error.
        let batches = 16;
        let runs: Vec<(MultipleScattering, MultipleScattering)> = (0..batches)
            .map(|b| {
                let reference = Reference::new(
                    atmosphere.clone(),
                    &[sun],
                    ReferenceSettings {
                        seed: 1000 + b,
                        paths: settings.paths / batches as usize,
                        ..settings
                    },
                )
                .with_clouds(std::slice::from_ref(&layer));
                let n = reference.settings.paths;
                (
                    path_tracer::multiple_scattering(&reference, &view, 1, n, f64::INFINITY),
                    path_tracer::multiple_scattering(&reference, &view, 2, n, f64::INFINITY),
                )
            })
            .collect();
        let mean = |f: &dyn Fn(&(MultipleScattering, MultipleScattering)) -> Spectrum| {
            let values: Vec<Spectrum> = runs.iter().map(f).collect();
            let m = values.iter().copied().sum::<Spectrum>() / batches as f64;
            let var = values.iter().map(|v| (*v - m) * (*v - m)).sum::<Spectrum>() / (batches as f64 - 1.0);
            (m, (var / batches as f64).sqrt())
        };
        let (first, first_error) = mean(&|r| r.0.per_order[1]);
        let (unforced, unforced_error) = mean(&|r| r.0.total - r.0.per_order[1]);
        let (forced, forced_error) = mean(&|r| r.1.total);
        let reference = Reference::new(atmosphere.clone(), &[sun], settings).with_clouds(std::slice::from_ref(&layer));
        let planet_view = reference.atmosphere.planet.ray_to_planet_frame(&view);
        let (single, ground, _) = reference.single_scattering(&planet_view, f64::INFINITY);
        let want = single + ground;
        println!(
            "{}: order 1 {first} ± {first_error} vs quadrature {want}; orders ≥ 2 forced {forced} ± \
             {forced_error}, unforced {unforced} ± {unforced_error}",
            kind.name()
        );
        let off = (first - want).abs() / first_error;
        assert!(off.max_element() < 4.0, "order 1: {off}");
        let noise = (forced_error * forced_error + unforced_error * unforced_error).sqrt();
        let off = (forced - unforced).abs() / noise;
        assert!(off.max_element() < 4.0, "orders ≥ 2: {off}");
        assert!((first_error / first).max_element() < 0.05, "{first_error}");
    }
}

/// The level of detail's share of rays that meet cloud ([`CloudLayer::cover_seen`]) against the
/// field itself: the mean transmittance of a broken layer along parallel rays through 9216
/// points of the ground (the field's optical depths, in `f64`) against the independent columns'
/// `1 − cover + cover·e^(−τ/cover)`, τ the columns' mean optical depth along the ray — cumulus
/// at 10, 30 and 60 %, stratocumulus at 50 and 80 %, cirrus at 50 %, up to 60° from the zenith,
/// within 0.04, where the layer is seen from orbit (docs/CLOUDS.md, "Level of detail", has the
/// table and the grazing views). The even veil of the mean optical depth, `e^(−τ)`, is far off: 0.03 against 0.73 for
/// the 30 % cumulus seen straight down.
#[test]
fn independent_columns_keep_a_broken_layers_mean_transmittance() {
    let planet = Planet::sphere(6_360_000.0, 60_000.0);
    for (kind, coverage, bottom, top, density) in [
        (CloudKind::Cumulus, 0.1, 700.0, 1_800.0, 0.05),
        (CloudKind::Cumulus, 0.3, 1_500.0, 3_000.0, 0.05),
        (CloudKind::Cumulus, 0.6, 1_500.0, 3_000.0, 0.05),
        (CloudKind::Stratocumulus, 0.5, 1_000.0, 2_000.0, 0.03),
        (CloudKind::Stratocumulus, 0.8, 1_000.0, 2_000.0, 0.03),
        (CloudKind::Cirrus, 0.5, 8_000.0, 9_000.0, 0.002),
    ] {
        let layer = CloudLayer {
            seed: 5,
            ..CloudLayer::new(bottom, top, coverage, density, kind)
        };
        let layers = [layer.clone()];
        let steps = 400;
        let tau_vertical: f64 = (0..steps)
            .map(|k| {
                let h = bottom + (top - bottom) * (f64::from(k) + 0.5) / f64::from(steps);
                layer.mean_density_with_coverage(h, coverage) * (top - bottom) / f64::from(steps)
            })
            .sum();
        for zenith in [0.0f64, 30.0, 60.0] {
            let d = direction(zenith, 90.0);
            // Feet 1.55 km apart east–west and 1.45 km north–south, over 149 × 139 km about the
            // pole (the clouds cluster on 4 km noise, and sheets vary over tens of km).
            let grid = 96i32;
            let field = (0..grid * grid)
                .map(|i| {
                    let (x, y) = (f64::from(i % grid - grid / 2), f64::from(i / grid - grid / 2));
                    let origin = DVec3::new(x * 1_550.0, y * 1_450.0, planet.surface().radii.z);
                    let ray = Ray { origin, direction: d };
                    (-cloud_media::optical_depth(&planet, &layers, &ray, 0.0, 20_000.0)).exp()
                })
                .sum::<f64>()
                / f64::from(grid * grid);
            let tau = tau_vertical / zenith.to_radians().cos();
            let cover = layer.cover_seen(coverage, (top - bottom) * zenith.to_radians().tan());
            let columns = 1.0 - cover + cover * (-tau / cover).exp();
            println!(
                "{kind:?} at {coverage} (share {:.3}), {zenith}° from the zenith: field {field:.4}, \
                 independent columns {columns:.4}, the mean optical depth {:.4}",
                layer.cover_share(),
                (-tau).exp()
            );
            assert!(
                (columns - field).abs() < 0.04,
                "{kind:?} at {coverage}, {zenith}°: independent columns {columns:.4}, the field {field:.4}"
            );
        }
    }
}
