//! The reference against closed forms, published numbers and its own symmetries.

use glam::DVec3;

use super::*;
use crate::atmosphere::medium::{DensityLayer, DensityProfile, rayleigh_phase};
use crate::atmosphere::{Planet, presets};

fn relative(a: Spectrum, b: Spectrum) -> f64 {
    ((a - b) / b).abs().max_element()
}

fn rayleigh_only(planet: Planet) -> Atmosphere {
    let mut atmosphere = presets::earth();
    atmosphere.planet = planet;
    atmosphere.medium.terms[1].scattering = Spectrum::ZERO;
    atmosphere.medium.terms[1].absorption = Spectrum::ZERO;
    atmosphere.medium.terms[2].absorption = Spectrum::ZERO;
    atmosphere.medium.ground_albedo = Spectrum::ZERO;
    atmosphere
}

/// A pure absorber of tabulated density: the transmittance straight up is `exp(−σ_a·∫d)`, the
/// integral the trapezoids of the table by hand (1 at the ground, ½ at 10 km, 0 from 30 km:
/// 7.5 km + 5 km = 12.5 km), and 30° from the zenith on a flat Earth's `1/cos` within the
/// curvature's share (below 0.2 % at 30 km).
#[test]
fn a_tabulated_absorber_transmits_exp_of_its_integral() {
    use crate::atmosphere::medium::{DensityTable, MediumTerm, Phase};
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(6_360_000.0, 60_000.0);
    let absorption = Spectrum::new(1e-5, 2e-5, 3e-5);
    atmosphere.medium.terms = vec![MediumTerm {
        scattering: Spectrum::ZERO,
        absorption,
        density: crate::atmosphere::medium::Density::Table(
            DensityTable::new("test", &[(0.0, 1.0), (10_000.0, 0.5), (30_000.0, 0.0)]).unwrap(),
        ),
        phase: Phase::Rayleigh,
    }];
    atmosphere.validate().unwrap();
    let reference = Reference::new(atmosphere, &[], ReferenceSettings::default());
    let ground = DVec3::new(0.0, 0.0, 6_360_000.0);
    let want = (-absorption * 12_500.0).exp();
    let got = reference.transmittance_to_space(ground, DVec3::Z);
    assert!(relative(got, want) < 1e-6, "{got} vs {want}");
    let slant = DVec3::new(0.5, 0.0, 3f64.sqrt() / 2.0);
    let flat = (-absorption * 12_500.0 / slant.z).exp();
    let got = reference.transmittance_to_space(ground, slant);
    assert!(relative(got.ln(), flat.ln()) < 2e-3, "{got} vs {flat}");
}

#[test]
fn sea_level_vertical_optical_depths_of_the_earth_preset() {
    let earth = presets::earth();
    let pole = DVec3::new(0.0, 0.0, earth.planet.radii.z);
    let top = pole + DVec3::Z * earth.planet.atmosphere_height;
    let fraction = |scale_height: f64| 1.0 - (-60_000.0 / scale_height).exp();
    // Each constituent alone: β·H·(1 − e^(−60 km/H)); ozone: β × the tent's area, 15 km.
    let cases = [
        (
            "rayleigh",
            Spectrum::new(5.802e-6, 13.558e-6, 33.1e-6) * 8_000.0 * fraction(8_000.0),
        ),
        ("mie", Spectrum::splat(4.44e-6 * 1_200.0 * fraction(1_200.0))),
        ("ozone", Spectrum::new(0.650e-6, 1.881e-6, 0.085e-6) * 15_000.0),
    ];
    for (name, want) in cases {
        let mut atmosphere = earth.clone();
        if name != "rayleigh" {
            atmosphere.medium.terms[0].scattering = Spectrum::ZERO;
        }
        if name != "mie" {
            atmosphere.medium.terms[1].scattering = Spectrum::ZERO;
            atmosphere.medium.terms[1].absorption = Spectrum::ZERO;
        }
        if name != "ozone" {
            atmosphere.medium.terms[2].absorption = Spectrum::ZERO;
        }
        let reference = Reference::new(atmosphere.clone(), &[], ReferenceSettings::default());
        let got = reference.optical_depth(pole, top);
        assert!(relative(got, want) < 1e-7, "{name}: {got} vs {want}");
    }
    // The sums quoted in the literature for this preset: τ_R(550 nm) ≈ 0.1084, τ_M ≈ 0.00533.
    let reference = Reference::new(earth.clone(), &[], ReferenceSettings::default());
    let total = reference.optical_depth(pole, top);
    assert!((total.y - (0.10846 + 0.005328 + 0.028215)).abs() < 1e-4, "{total}");
}

#[test]
fn beer_lambert_in_a_constant_medium() {
    let mut atmosphere = rayleigh_only(Planet::sphere(1_000_000.0, 100_000.0));
    atmosphere.medium.terms[0].density = DensityProfile::single(DensityLayer::constant()).into();
    let reference = Reference::new(atmosphere.clone(), &[], ReferenceSettings::default());
    let beta = atmosphere.medium.terms[0].scattering;
    // A horizontal chord 50 km up: length 2·√((R+H)² − (R+50 km)²).
    let p = DVec3::new(0.0, 0.0, 1_050_000.0);
    let half_chord = (1_100_000.0_f64.powi(2) - 1_050_000.0_f64.powi(2)).sqrt();
    let t = reference.transmittance_to_space(p, DVec3::X);
    let want = (-beta * half_chord).exp();
    assert!(relative(t, want) < 1e-9, "{t} vs {want}");
    let a = p - DVec3::X * half_chord;
    let b = p + DVec3::X * half_chord;
    assert!(relative((-reference.optical_depth(a, b)).exp(), want * want) < 1e-9);
}

#[test]
fn transmittance_is_reciprocal_and_zero_through_the_ground() {
    let reference = Reference::new(presets::earth(), &[], ReferenceSettings::default());
    let a = DVec3::new(6_400_000.0, 1000.0, 20_000.0);
    let b = DVec3::new(6_300_000.0, 900_000.0, 40_000.0);
    let (ab, ba) = (reference.optical_depth(a, b), reference.optical_depth(b, a));
    assert!(relative(ab, ba) < 1e-9, "{ab} {ba}");
    let ground = DVec3::new(6_378_137.0 + 10.0, 0.0, 0.0);
    assert_eq!(reference.transmittance_to_space(ground, -DVec3::X), Spectrum::ZERO);
}

/// A nearly flat planet (R = 10⁷ km) with Rayleigh scattering only: single scattering seen
/// from the ground has the plane-parallel closed form
/// `L = E·P(ν)·μ₀·(e^(−τ/μ) − e^(−τ/μ₀))/(μ − μ₀)` (Chandrasekhar, *Radiative Transfer*, 1950).
#[test]
fn single_scattering_matches_the_plane_parallel_closed_form() {
    let radius = 1e10;
    let atmosphere = rayleigh_only(Planet::sphere(radius, 60_000.0));
    let beta = atmosphere.medium.terms[0].scattering;
    let tau = beta * 8_000.0 * (1.0 - (-7.5_f64).exp());
    for (view_zenith, sun_zenith, azimuth) in [(0.0_f64, 30.0_f64, 0.0_f64), (60.0, 20.0, 90.0), (45.0, 70.0, 180.0)] {
        let (vz, sz, az) = (view_zenith.to_radians(), sun_zenith.to_radians(), azimuth.to_radians());
        let view = DVec3::new(vz.sin(), 0.0, vz.cos());
        let sun_direction = DVec3::new(sz.sin() * az.cos(), sz.sin() * az.sin(), sz.cos());
        let sun = presets::earth_sun(sun_direction);
        let reference = Reference::new(
            atmosphere.clone(),
            &[sun],
            ReferenceSettings {
                paths: 1,
                ..Default::default()
            },
        );
        let eye = DVec3::new(0.0, 0.0, radius + 1.0);
        let (single, _, _) = reference.single_scattering(&Ray::new(eye, view).unwrap(), f64::INFINITY);
        let (mu, mu0) = (vz.cos(), sz.cos());
        let want =
            sun.irradiance * rayleigh_phase(view.dot(sun_direction)) * mu0 * ((-tau / mu).exp() - (-tau / mu0).exp())
                / (mu - mu0);
        assert!(
            relative(single, want) < 2e-4,
            "{view_zenith}/{sun_zenith}: {single} vs {want}"
        );
    }
}

#[test]
fn single_scattering_is_mirror_symmetric_and_reciprocal() {
    let atmosphere = presets::earth();
    let settings = ReferenceSettings {
        paths: 1,
        ..Default::default()
    };
    let eye = DVec3::new(0.0, 0.0, atmosphere.planet.radii.z + 2.0);
    let direction = |zenith: f64, azimuth: f64| {
        let (z, a) = (zenith.to_radians(), azimuth.to_radians());
        DVec3::new(z.sin() * a.cos(), z.sin() * a.sin(), z.cos())
    };
    let single = |view: DVec3, sun: DVec3| {
        let reference = Reference::new(atmosphere.clone(), &[presets::earth_sun(sun)], settings);
        reference
            .single_scattering(&Ray::new(eye, view).unwrap(), f64::INFINITY)
            .0
    };
    // Mirror: the sun at azimuth ±40° relative to the view.
    let a = single(direction(50.0, 0.0), direction(30.0, 40.0));
    let b = single(direction(50.0, 0.0), direction(30.0, -40.0));
    assert!(relative(a, b) < 1e-9, "{a} {b}");
    // Reciprocity (exact for a flat atmosphere with a single-scattering albedo that does not
    // change with height, see the closed form above): swapping the view and sun zenith angles
    // scales radiance by μ₀'/μ₀. Rayleigh alone on the curved WGS84 Earth.
    let rayleigh = rayleigh_only(atmosphere.planet);
    let single = |view: DVec3, sun: DVec3| {
        let reference = Reference::new(rayleigh.clone(), &[presets::earth_sun(sun)], settings);
        reference
            .single_scattering(&Ray::new(eye, view).unwrap(), f64::INFINITY)
            .0
    };
    let (z1, z2) = (20.0_f64, 55.0_f64);
    let l12 = single(direction(z1, 0.0), direction(z2, 120.0));
    let l21 = single(direction(z2, 0.0), direction(z1, 120.0));
    let ratio = (l12 / z2.to_radians().cos()) / (l21 / z1.to_radians().cos());
    assert!((ratio - Spectrum::ONE).abs().max_element() < 4e-3, "{ratio}");
}

/// A white furnace: no absorption anywhere, a white ground, uniform light from space and no sun.
/// Every path eventually leaves, so the radiance everywhere must equal the background.
fn furnace(grey: bool) -> (Atmosphere, Spectrum) {
    let mut atmosphere = presets::earth();
    atmosphere.medium.terms[1].absorption = Spectrum::ZERO;
    atmosphere.medium.terms[2].absorption = Spectrum::ZERO;
    atmosphere.medium.ground_albedo = Spectrum::ONE;
    if grey {
        // Equal coefficients at every wavelength and a phase function the sampler draws exactly:
        // every path's weight is exactly 1, so the estimate has no variance at all.
        atmosphere.medium.terms[0].scattering = Spectrum::splat(atmosphere.medium.terms[0].scattering.y);
        atmosphere.medium.terms[1].phase = crate::atmosphere::Phase::HenyeyGreenstein { g: 0.8 };
    }
    (atmosphere, Spectrum::new(1.0, 2.0, 3.0))
}

fn furnace_rays(atmosphere: &Atmosphere) -> Vec<Ray> {
    let ground = atmosphere.planet.radii.z;
    [
        (DVec3::new(0.0, 0.0, ground + 2.0), DVec3::new(0.3, 0.0, 1.0)),
        (DVec3::new(0.0, 0.0, ground + 2.0), DVec3::new(1.0, 0.0, 0.0)),
        (DVec3::new(0.0, 0.0, ground + 8_000.0), DVec3::new(0.2, 0.1, -1.0)),
        (DVec3::new(0.0, 0.0, 3.0 * ground), DVec3::new(0.1, 0.0, -1.0)),
    ]
    .into_iter()
    .map(|(origin, direction)| Ray::new(origin, direction).unwrap())
    .collect()
}

#[test]
fn grey_white_furnace_conserves_energy_exactly() {
    let (atmosphere, background) = furnace(true);
    let settings = ReferenceSettings {
        paths: 2000,
        background,
        ..Default::default()
    };
    let reference = Reference::new(atmosphere.clone(), &[], settings);
    for ray in furnace_rays(&atmosphere) {
        let radiance = path_tracer::multiple_scattering(&reference, &ray, 0, settings.paths, f64::INFINITY);
        assert!(
            relative(radiance.total, background) < 1e-9,
            "{ray:?}: {:?}",
            radiance.total
        );
    }
}

#[test]
fn spectral_white_furnace_conserves_energy_within_noise() {
    // Earth's spectral coefficients: the spectral-MIS weights now vary from path to path, so the
    // check is statistical — within 4 standard errors, each below 1 % of the background.
    let (atmosphere, background) = furnace(false);
    let settings = ReferenceSettings {
        paths: 20_000,
        background,
        ..Default::default()
    };
    let reference = Reference::new(atmosphere.clone(), &[], settings);
    for ray in furnace_rays(&atmosphere) {
        let radiance = path_tracer::multiple_scattering(&reference, &ray, 0, settings.paths, f64::INFINITY);
        let deviation = (radiance.total - background).abs();
        let error = radiance.standard_error;
        assert!(
            deviation.cmple(4.0 * error + 1e-9).all(),
            "{ray:?}: {:?} ± {error}",
            radiance.total
        );
        assert!((error / background).max_element() < 0.01, "{ray:?}: ± {error}");
    }
}

#[test]
fn multiple_scattering_converges_with_order() {
    let atmosphere = presets::earth();
    let sun = presets::earth_sun(DVec3::new(0.5, 0.0, 0.8));
    let settings = ReferenceSettings {
        paths: 8_000,
        ..Default::default()
    };
    let reference = Reference::new(atmosphere.clone(), &[sun], settings);
    let eye = DVec3::new(0.0, 0.0, atmosphere.planet.radii.z + 2.0);
    let parts = reference.radiance(&Ray::new(eye, DVec3::new(-0.3, 0.2, 0.5)).unwrap());
    let orders = &parts.multiple.per_order;
    let green = |k: usize| orders[k].y;
    assert_eq!(
        green(0) + green(1),
        0.0,
        "orders 0 and 1 belong to the deterministic parts"
    );
    // Each order adds less than the one before, and everything past order 10 < 0.1 % of the sky.
    for k in 2..6 {
        assert!(green(k + 1) < green(k), "order {k}: {orders:?}");
    }
    let tail: f64 = (11..orders.len()).map(green).sum();
    assert!(
        tail < 1e-3 * parts.scattered().y,
        "tail {tail} of {}",
        parts.scattered().y
    );
    // Multiple scattering is a modest share of a clear noon sky (Bruneton 2008 fig. 9: ~10–30 %).
    let share = parts.multiple.total.y / parts.scattered().y;
    assert!((0.05..0.5).contains(&share), "{share}");
    assert!(parts.multiple.standard_error.y < 0.02 * parts.multiple.total.y);
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let atmosphere = presets::earth();
    let sun = presets::earth_sun(DVec3::new(0.0, 0.6, 0.8));
    let reference = Reference::new(
        atmosphere.clone(),
        &[sun],
        ReferenceSettings {
            paths: 64,
            ..Default::default()
        },
    );
    let ray = Ray::new(
        DVec3::new(0.0, 0.0, atmosphere.planet.radii.z + 2.0),
        DVec3::new(0.0, 1.0, 0.3),
    )
    .unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| reference.radiance(&ray))
    };
    assert_eq!(run(1).multiple.total, run(2).multiple.total);
}

#[test]
fn ground_irradiance_is_plausible_at_noon() {
    let atmosphere = presets::earth();
    let sun_zenith = 30.0_f64.to_radians();
    let sun = presets::earth_sun(DVec3::new(sun_zenith.sin(), 0.0, sun_zenith.cos()));
    let reference = Reference::new(
        atmosphere.clone(),
        &[sun],
        ReferenceSettings {
            paths: 2000,
            ..Default::default()
        },
    );
    let irradiance = reference.ground_irradiance(DVec3::new(0.0, 0.0, atmosphere.planet.radii.z));
    // Direct: E·T·cos θ with the vertical optical depth stretched by 1/cos θ (flat-Earth check).
    let vertical = Spectrum::new(
        0.0464 + 0.00533 + 0.00975,
        0.10846 + 0.00533 + 0.02822,
        0.26477 + 0.00533 + 0.00128,
    );
    let want = sun.irradiance * (-vertical / sun_zenith.cos()).exp() * sun_zenith.cos();
    assert!(
        relative(irradiance.direct, want) < 2e-3,
        "{} vs {want}",
        irradiance.direct
    );
    // Diffuse-to-direct ratio of a clear sky, higher in blue (e.g. Bird & Riordan 1986: ~0.1 at
    // 550 nm, ~0.25 at 440 nm for this sun height).
    let ratio = irradiance.sky / irradiance.direct;
    assert!(ratio.z > ratio.y && ratio.y > ratio.x, "{ratio}");
    assert!((0.05..0.3).contains(&ratio.y), "{ratio}");
}

/// An opaque surface on the view ray splits the radiance exactly: what the air scatters in front
/// of it, plus the transmittance to it times the radiance arriving from beyond it.
#[test]
fn radiance_before_a_surface_splits_the_ray() {
    let atmosphere = presets::earth();
    let sun = presets::earth_sun(DVec3::new(0.6, 0.0, 0.8).normalize());
    let settings = ReferenceSettings {
        view_steps: 2048,
        paths: 1,
        ..Default::default()
    };
    let reference = Reference::new(atmosphere.clone(), &[sun], settings);
    let eye = atmosphere.planet.surface_point(0.0, 0.0) + DVec3::Z * 100.0;
    let view = Ray::new(eye, DVec3::new(0.0, 1.0, 0.05)).unwrap();
    let distance = 20_000.0;
    let near = reference.radiance_before(&view, distance);
    let far = reference.radiance(&Ray::new(view.at(distance), view.direction).unwrap());
    let whole = reference.radiance(&view);
    let split = near.single + near.transmittance * (far.single + far.ground);
    assert!(
        relative(split, whole.single + whole.ground) < 1e-4,
        "{split} vs {}",
        whole.single
    );
    let depth = reference.optical_depth(
        atmosphere.planet.to_planet_frame(eye),
        atmosphere.planet.to_planet_frame(view.at(distance)),
    );
    assert!(relative(near.transmittance, (-depth).exp()) < 1e-9);
    assert_eq!(near.sun_discs, Spectrum::ZERO);
    assert_eq!(near.ground, Spectrum::ZERO);
    // Beyond the end of the atmosphere the surface changes nothing.
    let beyond = reference.radiance_before(&view, 1e9);
    assert!(relative(beyond.single, whole.single) < 1e-12);
}
