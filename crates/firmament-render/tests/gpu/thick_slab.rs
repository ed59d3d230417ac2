//! A thick air's multiple scattering on the GPU against the exact solution of a plane-parallel
//! slab: uniform, isotropically scattering (conservative or absorbing), over a black or a
//! Lambertian ground, lit by one sun. Its radiance solves a Fredholm equation in optical depth
//! alone (Chandrasekhar, "Radiative Transfer", 1950, ch. I; the kernel ω·E₁/2), which
//! [`ExactSlab`] solves deterministically — no
//! Monte Carlo noise, and nothing shared with the renderer or the path tracer. The slab stands on
//! a sphere of Venus's radius, 10 km high, where curvature changes a path of zenith angle 60°
//! through it by 0.5 %.

use std::f64::consts::PI;

use firmament_core::atmosphere::medium::{Density, DensityLayer, DensityProfile, MediumTerm, Phase};
use firmament_core::atmosphere::{Planet, Spectrum, Sun, presets};
use firmament_core::frame::AtmosphereSky;
use glam::DVec3;

use crate::support::{centre_radiance, direction, gpu};

/// The slab's height, metres, and the radius of the sphere it stands on.
const HEIGHT: f64 = 10_000.0;
const RADIUS: f64 = 6_051_800.0;

/// Cells of the exact solution's grid in optical depth, in cosine steps (from 10⁻⁴ deep at the
/// faces to 0.08 in the middle at optical depth 20: its energy balance, below, holds within
/// 1.5·10⁻⁴, and as many even steps give radiances within 0.1 % of its).
const CELLS: usize = 400;

/// The exponential integral Eₙ(x) = ∫₁^∞ e^(−xt)/tⁿ dt, x ≥ 0 (n ≥ 2 at x = 0): its series for
/// x ≤ 1 and its continued fraction beyond (Press et al., "Numerical Recipes", 3rd ed., §6.3).
fn exponential_integral(n: u32, x: f64) -> f64 {
    const EULER: f64 = 0.577_215_664_901_532_9;
    let nm1 = n - 1;
    if x == 0.0 {
        return 1.0 / f64::from(nm1);
    }
    if x > 1.0 {
        let mut b = x + f64::from(n);
        let mut c = 1e300;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..500 {
            let a = -f64::from(i) * (f64::from(nm1) + f64::from(i));
            b += 2.0;
            d = 1.0 / (a * d + b);
            c = b + a / c;
            let delta = c * d;
            h *= delta;
            if (delta - 1.0).abs() < 1e-15 {
                break;
            }
        }
        return h * (-x).exp();
    }
    let mut sum = if nm1 == 0 {
        -x.ln() - EULER
    } else {
        1.0 / f64::from(nm1)
    };
    let mut factor = 1.0;
    for i in 1..500u32 {
        factor *= -x / f64::from(i);
        let delta = if i == nm1 {
            let psi = -EULER + (1..=nm1).map(|k| 1.0 / f64::from(k)).sum::<f64>();
            factor * (-x.ln() + psi)
        } else {
            -factor / (f64::from(i) - f64::from(nm1))
        };
        sum += delta;
        if delta.abs() < sum.abs() * 1e-16 {
            break;
        }
    }
    sum
}

/// The conservative isotropic slab of optical depth `depth`: the source function S(τ) (radiance
/// scattered per unit optical depth, per unit sun irradiance) of S = J₀ + Λ[S] on [`CELLS`]
/// cells, S constant in each and the kernel E₁(|τ − τ'|)/2 integrated over them exactly (a
/// Nyström method with product integration).
struct ExactSlab {
    depth: f64,
    /// The single-scattering albedo.
    albedo: f64,
    /// Cell edges, optical depth from the top.
    edges: Vec<f64>,
    /// The matrix 1 − Λ, factored in place by Gaussian elimination (rows swapped by `pivots`).
    lu: Vec<f64>,
    pivots: Vec<usize>,
}

/// The light of an [`ExactSlab`] under one sun.
struct SlabLight {
    /// The source function per cell.
    source: Vec<f64>,
    /// The radiance the ground sends up.
    ground: f64,
}

impl ExactSlab {
    fn new(depth: f64, albedo: f64) -> Self {
        let n = CELLS;
        // Crowded at both faces, where the source changes fastest: cosine steps.
        let edges: Vec<f64> = (0..=n)
            .map(|i| depth * 0.5 * (1.0 - (PI * i as f64 / n as f64).cos()))
            .collect();
        let mut lu = vec![0.0; n * n];
        for i in 0..n {
            let centre = 0.5 * (edges[i] + edges[i + 1]);
            for j in 0..n {
                let lambda = if i == j {
                    1.0 - exponential_integral(2, 0.5 * (edges[j + 1] - edges[j]))
                } else {
                    0.5 * (exponential_integral(2, (centre - edges[j]).abs())
                        - exponential_integral(2, (centre - edges[j + 1]).abs()))
                    .abs()
                };
                lu[i * n + j] = f64::from(u8::from(i == j)) - albedo * lambda;
            }
        }
        let mut pivots: Vec<usize> = (0..n).collect();
        for k in 0..n {
            let p = (k..n)
                .max_by(|&a, &b| lu[a * n + k].abs().total_cmp(&lu[b * n + k].abs()))
                .expect("a column");
            if p != k {
                for j in 0..n {
                    lu.swap(k * n + j, p * n + j);
                }
                pivots.swap(k, p);
            }
            for i in k + 1..n {
                let factor = lu[i * n + k] / lu[k * n + k];
                lu[i * n + k] = factor;
                for j in k + 1..n {
                    lu[i * n + j] -= factor * lu[k * n + j];
                }
            }
        }
        Self {
            depth,
            albedo,
            edges,
            lu,
            pivots,
        }
    }

    /// `x` with (1 − Λ)·x = `rhs`, by the factors.
    fn solve(&self, rhs: &[f64]) -> Vec<f64> {
        let n = CELLS;
        let mut x: Vec<f64> = self.pivots.iter().map(|&p| rhs[p]).collect();
        for i in 0..n {
            for j in 0..i {
                x[i] -= self.lu[i * n + j] * x[j];
            }
        }
        for i in (0..n).rev() {
            for j in i + 1..n {
                x[i] -= self.lu[i * n + j] * x[j];
            }
            x[i] /= self.lu[i * n + i];
        }
        x
    }

    /// The slab's light with the sun at cosine `mu_sun` from the zenith over a Lambertian ground
    /// of `albedo`: per unit irradiance normal to the beam, the sunlight scattered once,
    /// e^(−τ/μ₀)/4π (each cell's mean), and the ground's, I_g·E₂(τ₀ − τ)/2 for the radiance
    /// I_g = albedo·F↓/π it sends up, plus the light scattered again. F↓ (the direct beam's and
    /// the sky's) is linear in I_g, so two solves give both.
    fn light(&self, mu_sun: f64, albedo: f64) -> SlabLight {
        let cells = self.edges.windows(2);
        let sun: Vec<f64> = cells
            .clone()
            .map(|c| {
                self.albedo * mu_sun * ((-c[0] / mu_sun).exp() - (-c[1] / mu_sun).exp()) / (c[1] - c[0]) / (4.0 * PI)
            })
            .collect();
        let e3 = |x: f64| exponential_integral(3, x);
        let from_ground: Vec<f64> = cells
            .map(|c| self.albedo * 0.5 * (e3(self.depth - c[1]) - e3(self.depth - c[0])) / (c[1] - c[0]))
            .collect();
        let (by_sun, by_ground) = (self.solve(&sun), self.solve(&from_ground));
        let direct = mu_sun * (-self.depth / mu_sun).exp();
        let (sky_by_sun, sky_by_ground) = (self.fluxes(&by_sun).0, self.fluxes(&by_ground).0);
        let k = albedo / PI;
        let ground = k * (direct + sky_by_sun) / (1.0 - k * sky_by_ground);
        SlabLight {
            source: by_sun.iter().zip(&by_ground).map(|(a, b)| a + ground * b).collect(),
            ground,
        }
    }

    /// The radiance arriving at the ground from cosine `mu` from the zenith.
    fn radiance_at_ground(&self, light: &SlabLight, mu: f64) -> f64 {
        let below = |t: f64| (-(self.depth - t) / mu).exp();
        (0..CELLS)
            .map(|i| light.source[i] * (below(self.edges[i + 1]) - below(self.edges[i])))
            .sum()
    }

    /// The radiance leaving the top at cosine `mu` from the zenith, the ground's seen through.
    fn radiance_at_top(&self, light: &SlabLight, mu: f64) -> f64 {
        let below = |t: f64| (-t / mu).exp();
        let air: f64 = (0..CELLS)
            .map(|i| light.source[i] * (below(self.edges[i]) - below(self.edges[i + 1])))
            .sum();
        air + light.ground * below(self.depth)
    }

    /// The sky's irradiance on the ground and the light leaving the top, per unit area, each
    /// 2π∫S·E₂: with the direct beam's, R + T = μ₀ for a conservative slab.
    fn fluxes(&self, source: &[f64]) -> (f64, f64) {
        let e3 = |x: f64| exponential_integral(3, x);
        let (mut down, mut up) = (0.0, 0.0);
        for (s, cell) in source.iter().zip(self.edges.windows(2)) {
            let (a, b) = (cell[0], cell[1]);
            down += s * (e3(self.depth - b) - e3(self.depth - a));
            up += s * (e3(a) - e3(b));
        }
        (2.0 * PI * down, 2.0 * PI * up)
    }
}

/// The exact slab conserves energy: the light it reflects and transmits (direct and diffuse)
/// adds up to the light that falls on it, within 3·10⁻⁴ (the grid's error), and its
/// transmission matches an analog Monte Carlo count made outside the project (T = 0.0714 ±
/// 0.0006 at optical depth 20, Sun 30° from the zenith, 200 000 photons). Over a ground of albedo
/// 0.3 what leaves the top and what the ground absorbs add up to the light that falls.
#[test]
fn the_exact_slab_conserves_energy() {
    for depth in [2.0, 10.0, 20.0] {
        let slab = ExactSlab::new(depth, 1.0);
        for sun_zenith in [0.0f64, 30.0, 60.0] {
            let mu_sun = sun_zenith.to_radians().cos();
            let (down, up) = slab.fluxes(&slab.light(mu_sun, 0.0).source);
            let direct = mu_sun * (-depth / mu_sun).exp();
            let balance = (down + up + direct) / mu_sun;
            println!(
                "slab τ {depth}, sun {sun_zenith}°: R {:.5}, T {:.5}, R + T {balance:.6}",
                up / mu_sun,
                (down + direct) / mu_sun
            );
            assert!((balance - 1.0).abs() < 3e-4, "τ {depth}, sun {sun_zenith}°: {balance}");
            if depth == 20.0 && sun_zenith == 30.0 {
                let t = (down + direct) / mu_sun;
                assert!((t - 0.0714).abs() < 3.0 * 0.0006, "T {t}");
            }
            let albedo = 0.3;
            let light = slab.light(mu_sun, albedo);
            let (down, up) = slab.fluxes(&light.source);
            // The ground's own light seen through the slab: πI_g·2E₃(τ₀).
            let up = up + light.ground * 2.0 * PI * exponential_integral(3, depth);
            let balance = (up + (1.0 - albedo) * (down + direct)) / mu_sun;
            assert!(
                (balance - 1.0).abs() < 3e-4,
                "τ {depth}, sun {sun_zenith}°, albedo: {balance}"
            );
        }
    }
}

/// The slab of optical depth `depth` on the GPU: one term, uniform, isotropic, posed so the world
/// is East-North-Up at (0°, 0°), a sun of unit irradiance `sun_zenith` degrees from the zenith
/// towards north, over a ground of `albedo`.
fn slab_sky(depth: f64, single_scattering_albedo: f64, sun_zenith: f64, albedo: f64) -> AtmosphereSky {
    let mut atmosphere = presets::venus();
    atmosphere.planet = Planet::sphere(RADIUS, HEIGHT).posed_at(0.0, 0.0);
    atmosphere.medium.terms = vec![MediumTerm {
        scattering: Spectrum::splat(single_scattering_albedo * depth / HEIGHT),
        absorption: Spectrum::splat((1.0 - single_scattering_albedo) * depth / HEIGHT),
        density: Density::Profile(DensityProfile::single(DensityLayer::constant())),
        phase: Phase::HenyeyGreenstein { g: 0.0 },
    }];
    atmosphere.medium.ground_albedo = Spectrum::splat(albedo);
    let sun = Sun {
        irradiance: Spectrum::ONE,
        ..presets::earth_sun(direction(0.0, 90.0 - sun_zenith))
    };
    AtmosphereSky {
        atmosphere,
        suns: vec![sun],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
    }
}

/// The GPU's sky of uniform slabs of optical depth 2, 10 and 20 (thick airs from 2: the
/// discrete-ordinates tail) over a black ground, 10 over a ground of albedo 0.3 and 10 with a
/// single-scattering albedo of 0.9, against [`ExactSlab`]: from the ground, zenith angles 0°, 30°,
/// 60° and 85° across the sun's azimuth, and from 20 km straight down, with the Sun 30° and 60°
/// from the zenith (`cargo test --release -p firmament-render --test gpu -- --nocapture
/// thick_slab::`). Budgets and measurements: docs/ATMOSPHERE.md, "Thick airs".
#[test]
fn a_thick_uniform_slab_matches_its_exact_solution() {
    let mut gpu = gpu();
    let mut worst: f64 = 0.0;
    for (depth, omega, albedo) in [
        (2.0, 1.0, 0.0),
        (10.0, 1.0, 0.0),
        (20.0, 1.0, 0.0),
        (10.0, 1.0, 0.3),
        (10.0, 0.9, 0.0),
    ] {
        let slab = ExactSlab::new(depth, omega);
        for sun_zenith in [30.0f64, 60.0] {
            let light = slab.light(sun_zenith.to_radians().cos(), albedo);
            let sky = slab_sky(depth, omega, sun_zenith, albedo);
            let conversion = sky.atmosphere.spectral_conversion();
            let views: [(f64, f64); 5] = [(1.0, 90.0), (1.0, 60.0), (1.0, 30.0), (1.0, 5.0), (2.0 * HEIGHT, -90.0)];
            for (altitude, elevation) in views {
                let mu = elevation.to_radians().sin();
                let exact = if altitude < HEIGHT {
                    slab.radiance_at_ground(&light, mu)
                } else {
                    slab.radiance_at_top(&light, -mu)
                };
                let want = conversion.linear_srgb(Spectrum::splat(exact));
                let want = DVec3::new(want.r, want.g, want.b);
                let got = centre_radiance(
                    &mut gpu,
                    &sky,
                    DVec3::new(0.0, 0.0, altitude),
                    direction(90.0, elevation),
                );
                let error = (got - want).abs().max_element() / want.max_element();
                println!(
                    "slab τ {depth:>4}, ω {omega}, albedo {albedo}, sun {sun_zenith}° from the zenith, eye {altitude:>6} m, view {elevation:>4}° up: gpu {got:.5} exact {want:.5} error {:+.1} %",
                    100.0 * ((got.x / want.x) - 1.0)
                );
                let budget = if depth < 5.0 {
                    THIN_SLAB
                } else if omega < 1.0 {
                    ABSORBING_SLAB
                } else {
                    THICK_SLAB
                };
                assert!(
                    error < budget,
                    "τ {depth}, albedo {albedo}, sun {sun_zenith}°, {altitude} m, {elevation}°: {error}"
                );
                worst = worst.max(error);
            }
        }
    }
    println!("worst {:.1} %", 100.0 * worst);
}

/// The budget against the exact slab, as the largest channel's error over the largest channel,
/// at optical depth 2 ...
const THIN_SLAB: f64 = 0.01;
/// ... at 10 and 20 in a conservative air, where what is left (up to 2 % dark at 10, 4 % at 20,
/// everywhere alike) grows with the depth (docs/ATMOSPHERE.md, "Thick airs") ...
const THICK_SLAB: f64 = 0.05;
/// ... and at 10 in an air that absorbs a tenth of what it meets.
const ABSORBING_SLAB: f64 = 0.02;
