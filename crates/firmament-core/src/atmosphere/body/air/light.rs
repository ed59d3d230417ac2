//! The light a body's air scatters more than once, and the sky's light on its ground: two tables
//! per air, made once for its constituents, the body's size and its albedo.
//!
//! # Model
//! **Multiple scattering** follows Hillaire, "A Scalable and Production Ready Sky and Atmosphere
//! Rendering Technique" (EGSR 2020, §5.5): at altitude `h` under a sun at zenith cosine `μ_s`,
//! the light scattered twice is gathered over the sphere of directions with an isotropic phase
//! (`L₂ = ∫ L'(ω) dω/4π`, `L'` the once-scattered light and the lit ground along `ω`), the share
//! of light the air around scatters back to the point is `f = ∫∫ σ_s·T dt dω/4π`, and every
//! higher order is taken as the same fraction of the one before: `Ψ = L₂/(1 − f)`. A view ray's
//! march adds `σ_s(h)·Ψ(h, μ_s)·E` per sun of irradiance `E` ([`super::Body::air_along`]).
//! The air is taken as a spherical shell of the body's volumetric mean radius; `μ_s` is the
//! sun's cosine to the body's normal at the point.
//!
//! **The sky's light on the ground** is the irradiance a horizontal patch of ground receives from
//! the whole sky (once-scattered light by the constituents' own phase functions, plus `Ψ`) under
//! a sun at zenith cosine `μ_s`, per unit irradiance of that sun, with the light the ground and
//! the sky send back and forth: the sky returns the share `s̄` of the light leaving the ground
//! (its spherical albedo from below, gathered as `Ψ` is, from ground of unit exitance), so each
//! bounce is `A·s̄` of the one before and the sky's light is `E_sky/(1 − A·s̄)` — with the first
//! bounce of the direct light already in `E_sky` (Ψ's lit ground), that is
//! `(E_air + E_direct·A·s̄)/(1 − A·s̄)`, every bounce of both.
//!
//! # Tables
//! Both are sampled at nodes even in `μ_s ∈ [−1, 1]` ([`SUN_NODES`]) and, for `Ψ`, in altitude
//! from the ground to the air's top ([`ALTITUDE_NODES`]), and read by linear interpolation
//! between nodes — the GPU reads the same nodes as texel centres with its bilinear filter.
//! Transmittance towards a sun comes from a finer table of optical depth by altitude and zenith
//! cosine (the one the reference's order-2 quadrature uses: Bruneton's parametrisation, read by
//! cubic interpolation), zero where the ground is in the way.

use std::f64::consts::PI;

use glam::DVec3;
use rayon::prelude::*;

use super::BodyAir;
use crate::atmosphere::depth_table::DepthTable;
use crate::atmosphere::spectrum::Spectrum;
use crate::geometry::Ray;

/// Nodes in the sun's zenith cosine, −1 to 1, of both tables.
pub const SUN_NODES: usize = 32;

/// Nodes in altitude, ground to top, of the multiple-scattering table.
pub const ALTITUDE_NODES: usize = 32;

/// Directions over the sphere of each multiple-scattering node (a Fibonacci lattice).
const SPHERE_DIRECTIONS: usize = 128;

/// Directions over the sphere of which the sky's light on the ground takes the upper half.
const SKY_DIRECTIONS: usize = 2048;

/// Midpoint steps along each direction.
const STEPS: usize = 32;

/// Nodes of the optical-depth table: radius and zenith cosine.
const DEPTH_RADIUS_NODES: usize = 64;
const DEPTH_MU_NODES: usize = 256;

/// Midpoint steps of each optical depth.
const DEPTH_STEPS: usize = 128;

/// The two tables of one air (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct AirLight {
    /// `Ψ` per unit irradiance of a sun, sr⁻¹: [`ALTITUDE_NODES`] rows (ground first) of
    /// [`SUN_NODES`] values (`μ_s = −1` first).
    pub multiple: Vec<Spectrum>,
    /// The sky's irradiance on horizontal ground per unit irradiance of a sun: [`SUN_NODES`]
    /// values, `μ_s = −1` first.
    pub sky: Vec<Spectrum>,
    /// Height of the air's top, metres: the last row's altitude.
    pub top_altitude_m: f64,
}

impl AirLight {
    /// The tables of `air` around a ball of radius `radius_m` whose ground reflects
    /// `ground_albedo` (Lambert).
    pub fn new(air: &BodyAir, radius_m: f64, ground_albedo: Spectrum) -> Self {
        let shell = Shell::new(air, radius_m);
        let multiple: Vec<Spectrum> = (0..ALTITUDE_NODES * SUN_NODES)
            .into_par_iter()
            .map(|k| {
                let h = node(k / SUN_NODES, ALTITUDE_NODES) * air.top_altitude_m;
                let mu_s = 2.0 * node(k % SUN_NODES, SUN_NODES) - 1.0;
                shell.multiple_scattering(h, mu_s, ground_albedo)
            })
            .collect();
        let partial = Self {
            multiple,
            sky: Vec::new(),
            top_altitude_m: air.top_altitude_m,
        };
        // The light going back and forth between the ground and the sky: each bounce the share
        // A·s̄ of the one before, which Ψ's lit ground holds once for the direct light.
        let bounces = Spectrum::ONE / (Spectrum::ONE - ground_albedo * shell.sky_albedo_from_below());
        let sky = (0..SUN_NODES)
            .into_par_iter()
            .map(|k| shell.sky_irradiance(2.0 * node(k, SUN_NODES) - 1.0, &partial) * bounces)
            .collect();
        Self { sky, ..partial }
    }

    /// `Ψ` at altitude `h` metres under a sun at zenith cosine `mu_s`, per unit irradiance,
    /// sr⁻¹ (module docs); clamped to the table.
    pub fn multiple_scattering(&self, h: f64, mu_s: f64) -> Spectrum {
        let (row, t) = between(h / self.top_altitude_m, ALTITUDE_NODES);
        let at_row = |r: usize| {
            let values = &self.multiple[r * SUN_NODES..(r + 1) * SUN_NODES];
            interpolate(values, 0.5 * (mu_s + 1.0))
        };
        at_row(row) * (1.0 - t) + at_row(row + 1) * t
    }

    /// The sky's irradiance on horizontal ground under a sun at zenith cosine `mu_s`, per unit
    /// irradiance of that sun (module docs).
    pub fn sky_irradiance(&self, mu_s: f64) -> Spectrum {
        interpolate(&self.sky, 0.5 * (mu_s + 1.0))
    }
}

/// Node `k` of `n` even over [0, 1], ends included.
fn node(k: usize, n: usize) -> f64 {
    k as f64 / (n - 1) as f64
}

/// The node before `x` (clamped to [0, 1]) among `n` and the fraction of the way to the next.
fn between(x: f64, n: usize) -> (usize, f64) {
    let position = x.clamp(0.0, 1.0) * (n - 1) as f64;
    let k = (position.floor() as usize).min(n - 2);
    (k, position - k as f64)
}

/// `values` at nodes even over [0, 1] read at `x`, linearly.
fn interpolate(values: &[Spectrum], x: f64) -> Spectrum {
    let (k, t) = between(x, values.len());
    values[k] * (1.0 - t) + values[k + 1] * t
}

/// The air as a spherical shell, with its optical depth to the top tabulated.
struct Shell<'a> {
    air: &'a BodyAir,
    radius: f64,
    top: f64,
    depth: DepthTable,
}

impl<'a> Shell<'a> {
    fn new(air: &'a BodyAir, radius: f64) -> Self {
        let top = radius + air.top_altitude_m;
        let depth_along = |ray: &Ray, length: f64| {
            let dt = length / DEPTH_STEPS as f64;
            (0..DEPTH_STEPS)
                .map(|k| air.extinction_at(ray.at((k as f64 + 0.5) * dt).length() - radius))
                .sum::<Spectrum>()
                * dt
        };
        let depth = DepthTable::new(radius, top, [DEPTH_MU_NODES, DEPTH_RADIUS_NODES], depth_along);
        Self {
            air,
            radius,
            top,
            depth,
        }
    }

    /// Transmittance from point `p` (from the centre) towards the unit `to_sun` to the top: 0
    /// where the ground is in the way.
    fn transmittance(&self, p: DVec3, to_sun: DVec3) -> Spectrum {
        self.depth
            .depth(p, to_sun)
            .map_or(Spectrum::ZERO, |depth| (-depth).exp())
    }

    /// Where a path from `x` along unit `d` leaves the shell: its length and whether it ends
    /// on the ground.
    fn path(&self, x: DVec3, d: DVec3) -> (f64, bool) {
        let b = x.dot(d);
        let c_ground = x.length_squared() - self.radius * self.radius;
        let ground = b * b - c_ground;
        if b < 0.0 && ground >= 0.0 {
            return (-b - ground.sqrt(), true);
        }
        let c_top = x.length_squared() - self.top * self.top;
        ((b * b - c_top).max(0.0).sqrt() - b, false)
    }

    /// Marches from `x` along the unit `d` to where the path leaves the shell, calling
    /// `step(y, h, to_y, dt)` at each midpoint `y` (altitude `h`, `to_y` the transmittance from
    /// `x` to it, `dt` the step's length); returns the transmittance of the whole path and the
    /// point of the ground where it ends, if it does.
    fn march(&self, x: DVec3, d: DVec3, mut step: impl FnMut(DVec3, f64, Spectrum, f64)) -> (Spectrum, Option<DVec3>) {
        let (length, ground) = self.path(x, d);
        let dt = length / STEPS as f64;
        let mut depth = Spectrum::ZERO;
        for k in 0..STEPS {
            let y = x + d * ((k as f64 + 0.5) * dt);
            let h = y.length() - self.radius;
            let extinction = self.air.extinction_at(h);
            step(y, h, (-(depth + extinction * (0.5 * dt))).exp(), dt);
            depth += extinction * dt;
        }
        ((-depth).exp(), ground.then(|| x + d * length))
    }

    /// The share of the light at altitude `h` the air around scatters back to it (Hillaire's
    /// `f`, the same under every sun): `∫∫ σ_s·T dt dω/4π`, and, summed the same way, what the
    /// ground along each direction sends there per unit of its exitance: `∫ T/π dω/4π`.
    fn gathered(&self, h: f64) -> (Spectrum, Spectrum) {
        let x = DVec3::new(0.0, 0.0, self.radius + h);
        let (mut share, mut ground) = (Spectrum::ZERO, Spectrum::ZERO);
        for d in fibonacci_sphere(SPHERE_DIRECTIONS) {
            let (through, end) = self.march(x, d, |_, h, to_y, dt| share += to_y * self.air.scattering_at(h) * dt);
            if end.is_some() {
                ground += through / PI;
            }
        }
        let n = SPHERE_DIRECTIONS as f64;
        (share / n, ground / n)
    }

    /// `Ψ` at altitude `h` under a sun at zenith cosine `mu_s` over ground of `albedo`.
    fn multiple_scattering(&self, h: f64, mu_s: f64, albedo: Spectrum) -> Spectrum {
        let x = DVec3::new(0.0, 0.0, self.radius + h);
        let sun = DVec3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), 0.0, mu_s);
        let (mut second, mut share) = (Spectrum::ZERO, Spectrum::ZERO);
        for d in fibonacci_sphere(SPHERE_DIRECTIONS) {
            let (through, end) = self.march(x, d, |y, h, to_y, dt| {
                let scattering = to_y * self.air.scattering_at(h) * dt;
                second += scattering * self.transmittance(y, sun) / (4.0 * PI);
                share += scattering;
            });
            if let Some(g) = end {
                let mu = g.normalize().dot(sun);
                second += through * self.transmittance(g, sun) * mu.max(0.0) * albedo / PI;
            }
        }
        let n = SPHERE_DIRECTIONS as f64;
        (second / n) / (Spectrum::ONE - share / n)
    }

    /// The irradiance on the ground of the light the air sends down: `source(y, h, d)` is what
    /// it scatters per unit length at `y` (altitude `h`) back along the direction `d` up from
    /// the ground.
    fn gather_on_ground(&self, source: impl Fn(DVec3, f64, DVec3) -> Spectrum) -> Spectrum {
        let x = DVec3::new(0.0, 0.0, self.radius);
        let mut irradiance = Spectrum::ZERO;
        for d in fibonacci_sphere(SKY_DIRECTIONS).filter(|d| d.z > 0.0) {
            let mut radiance = Spectrum::ZERO;
            self.march(x, d, |y, h, to_y, dt| radiance += to_y * source(y, h, d) * dt);
            irradiance += radiance * d.z;
        }
        irradiance * (4.0 * PI / SKY_DIRECTIONS as f64)
    }

    /// The sky's irradiance on the ground under a sun at zenith cosine `mu_s`, `table` giving Ψ:
    /// the light the air scatters down, once (by the constituents' phases) and more.
    fn sky_irradiance(&self, mu_s: f64, table: &AirLight) -> Spectrum {
        let sun = DVec3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), 0.0, mu_s);
        self.gather_on_ground(|y, h, d| {
            let mu = y.dot(sun) / y.length();
            let once = self.air.scattering_phase(h, d.dot(sun)) * self.transmittance(y, sun);
            once + self.air.scattering_at(h) * table.multiple_scattering(h, mu)
        })
    }

    /// The share of the light leaving the ground (Lambertian) that the air sends back down to
    /// it, every order (the sky's spherical albedo from below): the ground's light gathered at
    /// each altitude, each higher order the share `f` of the one before (as for Ψ), scattered
    /// down.
    fn sky_albedo_from_below(&self) -> Spectrum {
        let lit: Vec<Spectrum> = (0..ALTITUDE_NODES)
            .into_par_iter()
            .map(|j| {
                let (share, ground) = self.gathered(node(j, ALTITUDE_NODES) * self.air.top_altitude_m);
                ground / (Spectrum::ONE - share)
            })
            .collect();
        self.gather_on_ground(|_, h, _| self.air.scattering_at(h) * interpolate(&lit, h / self.air.top_altitude_m))
    }
}

/// `n` unit vectors spread evenly over the sphere (a Fibonacci lattice, z even in (−1, 1)).
fn fibonacci_sphere(n: usize) -> impl Iterator<Item = DVec3> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..n).map(move |k| {
        let z = 1.0 - (2.0 * k as f64 + 1.0) / n as f64;
        let s = (1.0 - z * z).sqrt();
        let phi = golden * k as f64;
        DVec3::new(s * phi.cos(), s * phi.sin(), z)
    })
}

#[cfg(test)]
mod tests;
