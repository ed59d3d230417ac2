//! A thick uniform cloud slab's reflectance (`shaders/clouds/march.wgsl`): against the
//! δ-Eddington source function the march integrates, evaluated here by quadrature in f64 (a
//! check of the march, its δ-scaled transmittance and its lighting), and, as a survey, against
//! the path-traced reference (a check of the model: issue 26's 3 %, not yet met).

use firmament_core::atmosphere::clouds::{CloudKind, CloudLayer, DualHenyeyGreenstein};
use firmament_core::atmosphere::{Spectrum, presets};
use firmament_core::frame::{AtmosphereSky, Frame, Sky};
use firmament_render::envmap::SunDiscs;
use glam::DVec3;
use std::f64::consts::PI;

use crate::clouds::{airless, camera_at};
use crate::support::{Gpu, direction, gpu};

/// The slab: 1–2 km up, Henyey–Greenstein g = 0.85, albedo 1, optical depth `tau`.
const G: f64 = 0.85;
const EYE: DVec3 = DVec3::new(0.0, 0.0, 3_000.0);
/// (optical depth, sun zenith angle in degrees) of the three cases.
const CASES: [(f64, f64); 3] = [(10.0, 0.0), (20.0, 30.0), (30.0, 60.0)];

fn slab(tau: f64) -> CloudLayer {
    CloudLayer {
        phase: DualHenyeyGreenstein {
            g_forward: G,
            g_back: 0.0,
            blend: 1.0,
        },
        ..CloudLayer::new(1_000.0, 2_000.0, 1.0, tau / 1_000.0, CloudKind::Uniform)
    }
}

/// The GPU's reflectance of the slab in a vacuum over a black ground, the sun `sun_zenith`
/// degrees from the zenith: its upward flux from a 256 × 128 map 3 km up over a white ground's
/// without the slab (`μ₀·E`).
fn gpu_reflectance(gpu: &mut Gpu, tau: f64, sun_zenith: f64) -> f64 {
    let mut black = airless();
    black.medium.ground_albedo = Spectrum::ZERO;
    let mut white = airless();
    white.medium.ground_albedo = Spectrum::ONE;
    let sun = presets::earth_sun(direction(0.0, 90.0 - sun_zenith));
    let mut flux = |atmosphere, clouds| {
        let sky = AtmosphereSky {
            atmosphere,
            suns: vec![sun],
            clouds,
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        };
        let frame = Frame::new(camera_at(EYE, DVec3::X, 60.0), Sky::Atmosphere(sky));
        let Gpu { ctx, renderer } = &mut *gpu;
        let map = renderer
            .render_equirect(ctx, &frame, 256, SunDiscs::Omitted)
            .expect("render");
        crate::support::hemisphere_flux(&map, false).y
    };
    let reflected = flux(black, vec![slab(tau)]);
    reflected / flux(white, Vec::new())
}

/// The reflectance the march's model gives, by quadrature: the radiance leaving the top of a
/// conservative slab of optical depth `tau` at each direction is the source function integrated
/// along it in δ-scaled optical depth (f = g², τ' = (1 − f)·τ, g' = g/(1 + g)) — the
/// Eddington diffuse field scattered once more, I₀ + g'·μ·I₁ (Shettle & Weinman 1970, with
/// Marshak's conditions and a black ground), and the beam e^(−τ'/μ₀) scattered by the whole
/// Henyey–Greenstein phase function over 1 − f (Nakajima & Tanaka 1988) — and its flux over μ₀.
fn model_reflectance(tau: f64, mu0: f64) -> f64 {
    let f = G * G;
    let (total, g) = ((1.0 - f) * tau, G / (1.0 + G));
    let e0 = 1.0 / PI;
    let bottom = (-total / mu0).exp();
    let c1 = -e0 * (0.5 * mu0 + 0.75 * mu0 * mu0 + bottom * (0.5 * mu0 - 0.75 * mu0 * mu0))
        / (4.0 / 3.0 + (1.0 - g) * total);
    let c2 = 2.0 / 3.0 * c1 + 0.75 * e0 * mu0 * mu0 + 0.5 * e0 * mu0;
    let henyey_greenstein = |c: f64| (1.0 - G * G) / (4.0 * PI * (1.0 + G * G - 2.0 * G * c).powf(1.5));
    let (cosines, azimuths, depths) = (40, 36, 400);
    let mut flux = 0.0;
    for a in 0..cosines {
        let mu = (f64::from(a) + 0.5) / f64::from(cosines);
        for b in 0..azimuths {
            let phi = (f64::from(b) + 0.5) / f64::from(azimuths) * 2.0 * PI;
            // The cosine between the sunlight (going down) and the way out (going up).
            let nu = (1.0 - mu0 * mu0).sqrt() * (1.0 - mu * mu).sqrt() * phi.cos() - mu0 * mu;
            let single = henyey_greenstein(nu) / (1.0 - f);
            let dt = total / f64::from(depths);
            let radiance: f64 = (0..depths)
                .map(|k| {
                    let t = (f64::from(k) + 0.5) * dt;
                    let beam = (-t / mu0).exp();
                    let i1 = c1 + 0.75 * e0 * mu0 * beam;
                    let i0 = c2 + (1.0 - g) * c1 * t - 0.75 * e0 * mu0 * mu0 * beam;
                    ((i0 + g * mu * i1).max(0.0) + single * beam) * (-t / mu).exp() * dt / mu
                })
                .sum();
            flux += radiance * mu / f64::from(cosines) * 2.0 * PI / f64::from(azimuths);
        }
    }
    flux / mu0
}

/// The march integrates its model: the GPU's reflectance of a thick slab (optical depth 10, 20,
/// 30; sun 0°, 30°, 60° from the zenith) is the quadrature's within 1 %.
#[test]
fn a_thick_slab_reflects_what_the_marchs_model_gives() {
    let mut gpu = gpu();
    for (tau, sun_zenith) in CASES {
        let got = gpu_reflectance(&mut gpu, tau, sun_zenith);
        let want = model_reflectance(tau, sun_zenith.to_radians().cos());
        assert!(
            (got / want - 1.0).abs() < 0.01,
            "τ {tau}, sun {sun_zenith}° from the zenith: the GPU reflects {got:.4}, the model {want:.4}"
        );
    }
}

/// Prints issue 26's check of the total reflectance of a thick uniform slab against the
/// path-traced reference by reciprocity (lit by a uniform sky of radiance 1 and seen from above
/// at θ₀ the slab shows `R(μ₀)`; 16 384 paths, binomial noise ±0.4–0.6 %) and the δ-Eddington
/// closed form. Not yet within the issue's 3 % (docs/CLOUDS.md, "Against closed forms and the
/// reference"): `cargo test -p firmament-render --test gpu -- --ignored --nocapture
/// thick_slab_reflectance_survey`, a minute.
#[test]
#[ignore = "a survey: the cloud model's reflectance is not yet within the issue's budget"]
fn thick_slab_reflectance_survey() {
    use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
    use firmament_core::geometry::Ray;
    let mut gpu = gpu();
    for (tau, sun_zenith) in CASES {
        let got = gpu_reflectance(&mut gpu, tau, sun_zenith);
        let mut black = airless();
        black.medium.ground_albedo = Spectrum::ZERO;
        let reference = Reference::new(
            black,
            &[],
            ReferenceSettings {
                paths: 16_384,
                background: Spectrum::ONE,
                ..Default::default()
            },
        )
        .with_clouds(&[slab(tau)]);
        let want = reference
            .radiance(&Ray {
                origin: EYE,
                direction: -direction(0.0, 90.0 - sun_zenith),
            })
            .total()
            .y;
        let noise = (want * (1.0 - want) / 16_384.0).sqrt();
        let f = G * G;
        let (tau_scaled, g_scaled, mu0) = ((1.0 - f) * tau, (G - f) / (1.0 - f), sun_zenith.to_radians().cos());
        let gamma = 0.75 * (1.0 - g_scaled);
        let gamma3 = (2.0 - 3.0 * g_scaled * mu0) / 4.0;
        let eddington = (gamma * tau_scaled + (gamma3 - gamma * mu0) * (1.0 - (-tau_scaled / mu0).exp()))
            / (1.0 + gamma * tau_scaled);
        println!(
            "tau {tau}, sun {sun_zenith}° from the zenith: GPU R {got:.4}, path tracer {want:.4} ± {noise:.4}, \
             δ-Eddington {eddington:.4}: {:+.1} %",
            100.0 * (got / want - 1.0)
        );
    }
}
