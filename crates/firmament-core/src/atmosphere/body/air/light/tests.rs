use super::*;
use crate::atmosphere::body::tests::sun;
use crate::atmosphere::medium::{Absorber, Constituents, DensityLayer, DensityProfile, Mie, Phase, Rayleigh};
use crate::atmosphere::reference::{Reference, ReferenceSettings};
use crate::atmosphere::{Planet, presets};

const EARTH_RADIUS: f64 = 6_371_000.0;

/// A shell `top` metres thick of constant density: molecules of `beta` m⁻¹ and nothing else.
fn constant_air(beta: f64, top: f64) -> BodyAir {
    let constant = DensityProfile::single(DensityLayer::constant());
    BodyAir {
        constituents: Constituents {
            rayleigh: Rayleigh {
                scattering: Spectrum::splat(beta),
                density: constant,
            },
            mie: Mie {
                scattering: Spectrum::ZERO,
                extinction: Spectrum::ZERO,
                density: constant,
                phase: Phase::CornetteShanks { g: 0.8 },
            },
            absorber: Absorber {
                absorption: Spectrum::ZERO,
                density: constant,
            },
        },
        top_altitude_m: top,
    }
}

fn relative(got: Spectrum, want: Spectrum) -> f64 {
    ((got - want).abs() / want).max_element()
}

/// An optically thin layer scatters the light crossing it, `E·τ` per unit of ground, half of it
/// downwards whatever the sun's height (the phase is even in the scattering angle's cosine), so
/// the sky's irradiance on the ground is `τ/2` of the sun's (on a ball so large that its
/// curvature shortens only the paths within 0.1° of the horizon).
#[test]
fn a_thin_air_sends_half_its_scattered_light_down() {
    let (beta, top) = (1e-8, 1_000.0);
    let light = AirLight::new(&constant_air(beta, top), 1e9, Spectrum::ZERO);
    for mu_s in [1.0, 0.5, 0.2] {
        let want = Spectrum::splat(beta * top / 2.0);
        let got = light.sky_irradiance(mu_s);
        assert!(relative(got, want) < 0.01, "μ_s {mu_s}: {got} vs {want}");
    }
    assert_eq!(light.sky_irradiance(-0.5), Spectrum::ZERO);
}

/// Light leaving the ground of an optically thin layer: `L = 1/π` up, of which the layer
/// scatters `∫ L·μ·(τ/μ) dω = 2τ` per unit exitance, half of it back down: the sky's albedo
/// from below is `τ`.
#[test]
fn a_thin_air_sends_back_down_as_much_ground_light_as_its_depth() {
    let (beta, top) = (1e-8, 1_000.0);
    let air = constant_air(beta, top);
    let got = Shell::new(&air, 1e9).sky_albedo_from_below();
    let want = Spectrum::splat(beta * top);
    assert!(relative(got, want) < 0.02, "{got} vs {want}");
}

/// On the ground of an air too thin to matter, the light gathered twice is the ground's own:
/// radiance `A·μ_s/π` over the lower half of the sphere, `Ψ = A·μ_s/(2π)`.
#[test]
fn on_the_ground_of_a_clear_air_the_ground_is_what_is_gathered() {
    let albedo = Spectrum::new(0.3, 0.2, 0.1);
    let light = AirLight::new(&constant_air(1e-12, 1_000.0), EARTH_RADIUS, albedo);
    for mu_s in [1.0, 0.6, 0.1] {
        let want = albedo * mu_s / (2.0 * PI);
        let got = light.multiple_scattering(0.0, mu_s);
        assert!(relative(got, want) < 0.01, "μ_s {mu_s}: {got} vs {want}");
    }
}

/// The tables read between nodes linearly, clamped at the ends.
#[test]
fn the_tables_interpolate_between_nodes() {
    let light = AirLight::new(&constant_air(1e-5, 10_000.0), 1e6, Spectrum::splat(0.2));
    let (a, b) = (light.sky[20], light.sky[21]);
    let mu = |k: f64| 2.0 * k / (SUN_NODES - 1) as f64 - 1.0;
    assert!(relative(light.sky_irradiance(mu(20.25)), a * 0.75 + b * 0.25) < 1e-12);
    let row = |r: usize| &light.multiple[r * SUN_NODES..(r + 1) * SUN_NODES];
    let h = 0.5 * 10_000.0 / (ALTITUDE_NODES - 1) as f64;
    let want = (row(0)[31] + row(1)[31]) * 0.5;
    assert!(relative(light.multiple_scattering(h, 2.0), want) < 1e-12);
}

/// Earth's air on an Earth-sized ball over ground of albedo 0.3: the sky's irradiance on the
/// ground by the tables (every order by Hillaire's approximation) against the independent path
/// tracer of the planet's sky (every order and every bounce between ground and sky:
/// docs/ATMOSPHERE.md, "Bodies").
#[test]
fn an_earth_sized_ball_s_sky_light_matches_the_path_tracer() {
    let albedo = Spectrum::splat(0.3);
    let air = BodyAir::from_atmosphere(&presets::earth()).expect("Earth's air is made of constituents");
    let light = AirLight::new(&air, EARTH_RADIUS, albedo);
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(EARTH_RADIUS, air.top_altitude_m);
    atmosphere.medium.ground_albedo = albedo;
    for zenith_deg in [0.0f64, 45.0, 75.0] {
        let (sin, cos) = zenith_deg.to_radians().sin_cos();
        let sun = sun(DVec3::new(sin, 0.0, cos));
        let settings = ReferenceSettings {
            paths: 16_384,
            ..ReferenceSettings::default()
        };
        let reference = Reference::new(atmosphere.clone(), std::slice::from_ref(&sun), settings);
        let want = reference.ground_irradiance(DVec3::new(0.0, 0.0, EARTH_RADIUS)).sky;
        let got = sun.irradiance * light.sky_irradiance(cos);
        let error = relative(got, want);
        println!(
            "sun {zenith_deg}° from the zenith: tables {got:.5} path tracer {want:.5} ({:.1} %)",
            100.0 * error
        );
        assert!(error < 0.05, "sun {zenith_deg}°: {got} vs {want}");
    }
}
