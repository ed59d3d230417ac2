//! The rings' light on the globe ("ringshine"): the irradiance the sunlit rings put on the ground,
//! by day and on the night side, per unit of the sun's irradiance.
//!
//! # Model
//! A ground point `p` with outward normal `n` sees the ring plane above its horizon; each element
//! `dA` of the rings at `x` sends it `L·cos θ_p·cos θ_x/|x − p|²·dA`, `L` the rings' single-
//! scattered radiance towards `p` ([`Rings::radiance`]), θ_p the angle from `n`, θ_x from the
//! plane's normal. The integral runs over each band in radius (Gauss–Legendre) and, at each radius,
//! over the arcs of azimuth that lie above `p`'s horizon and outside the globe's shadow — both arcs
//! in closed form (the shadow's for a spheroid, scaled to a unit sphere), so the integrand is smooth
//! on every arc and a few Gauss–Legendre nodes are enough. The ellipsoid being convex, every
//! point above the tangent plane is in sight. Each element's light is dimmed by the air on its
//! way down (a caller's transmittance along the direction; [`GroundTransmittance`] is the air's
//! from the ground of the mean-radius sphere the GPU's LUTs use).
//!
//! # The table
//! For a spheroid the light depends on the point's geodetic latitude and its azimuth from the
//! sun's, and on the sun only through its elevation over the ring plane: [`Rings::light_table`]
//! samples it at [`RING_LIGHT_TABLE_SIZE`] texel centres, which the GPU reads bilinearly (how
//! closely: docs/ATMOSPHERE.md, "Rings").

use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::sync::OnceLock;

use glam::DVec3;
use rayon::prelude::*;

use super::Rings;
use crate::atmosphere::planet::geodetic_normal;
use crate::atmosphere::reference::quadrature::GaussRule;
use crate::atmosphere::reference::{Reference, ReferenceSettings};
use crate::atmosphere::{Atmosphere, Planet, Spectrum};

/// The ring-light table's size, texels: azimuth from the sun's, 0 to π, across; geodetic latitude,
/// −90° to 90°, down.
pub const RING_LIGHT_TABLE_SIZE: (usize, usize) = (48, 64);

/// Gauss–Legendre nodes per band in radius and per arc of azimuth.
const RADIUS_NODES: usize = 5;
const AZIMUTH_NODES: usize = 10;

/// Nodes of [`GroundTransmittance`].
const TRANSMITTANCE_NODES: usize = 65;

impl Rings {
    /// The irradiance the rings scatter from a sun towards unit `sun` (planet frame) onto the
    /// ground at planet-frame `p` with outward unit normal `n`, on a planet of semi-axes `radii`
    /// (m), per unit of the sun's irradiance and per model wavelength (W m⁻² per W m⁻²); `air`
    /// gives the air's transmittance from `p` along a unit planet-frame direction. See the module
    /// docs.
    pub fn light_on_ground(
        &self,
        radii: DVec3,
        p: DVec3,
        n: DVec3,
        sun: DVec3,
        air: impl Fn(DVec3) -> Spectrum,
    ) -> Spectrum {
        let bands: Vec<(f64, f64)> = self.bands.iter().map(|b| (b.inner_m, b.outer_m)).collect();
        let shadow = GlobeShadow::new(radii, sun);
        integrate_over_annuli(
            &bands,
            p,
            n,
            |r| shadow.arc(r),
            |r, view| self.radiance(r, view, sun, Spectrum::ONE, true) * air(view),
        )
    }

    /// The table of [`light_on_ground`](Self::light_on_ground) over a spheroid of semi-axes
    /// `radii` (m) for a sun towards unit `sun` (planet frame), through `air`, row by row from the
    /// south pole: texel `(i, j)` at azimuth `(i + ½)·π/W` from the sun's and geodetic latitude
    /// `sign(t)·t²·π/2`, `t = 2(j + ½)/H − 1` ([`RING_LIGHT_TABLE_SIZE`]; rows crowd at the
    /// equator, where the light climbs from nothing within a few degrees and changes face).
    pub fn light_table(&self, radii: DVec3, sun: DVec3, air: &GroundTransmittance) -> Vec<Spectrum> {
        let (width, height) = RING_LIGHT_TABLE_SIZE;
        let sun_azimuth = sun.y.atan2(sun.x);
        (0..width * height)
            .into_par_iter()
            .map(|k| {
                let (i, j) = (k % width, k / width);
                let azimuth = (i as f64 + 0.5) * PI / width as f64;
                let latitude = row_latitude((j as f64 + 0.5) / height as f64);
                let n = geodetic_normal(latitude, sun_azimuth + azimuth);
                let p = radii * radii * n / (radii * n).length();
                self.light_on_ground(radii, p, n, sun, |view| air.at(n.dot(view)))
            })
            .collect()
    }
}

/// The air's transmittance from the ground to space against the cosine of the direction from the
/// zenith, on a sphere of the planet's mean radius (as the GPU's LUTs have it): the core's
/// [`Reference::transmittance_to_space`] at 65 cosines, `cos θ = x²` for `x` evenly spaced in
/// [0, 1] (crowded at the horizon, where the air's depth grows fastest), linear between them in
/// `x`.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundTransmittance {
    nodes: Vec<Spectrum>,
}

impl GroundTransmittance {
    /// The table for `atmosphere`'s air.
    pub fn new(atmosphere: &Atmosphere) -> Self {
        let planet = &atmosphere.planet;
        let sphere = Atmosphere {
            planet: Planet::sphere(planet.mean_radius(), planet.atmosphere_height),
            ..atmosphere.clone()
        };
        let radius = sphere.planet.radii.z;
        let reference = Reference::new(sphere, &[], ReferenceSettings::default());
        // A millimetre up: a point a rounding inside the ground would see no sky.
        let ground = DVec3::new(0.0, 0.0, radius + 1e-3);
        let nodes = (0..TRANSMITTANCE_NODES)
            .map(|k| {
                let x = k as f64 / (TRANSMITTANCE_NODES - 1) as f64;
                let cos = x * x;
                let direction = DVec3::new((1.0 - cos * cos).max(0.0).sqrt(), 0.0, cos);
                reference.transmittance_to_space(ground, direction)
            })
            .collect();
        Self { nodes }
    }

    /// The transmittance towards a direction `cos_zenith` from the zenith (0 below the horizon).
    pub fn at(&self, cos_zenith: f64) -> Spectrum {
        if cos_zenith <= 0.0 {
            return Spectrum::ZERO;
        }
        let x = cos_zenith.min(1.0).sqrt() * (TRANSMITTANCE_NODES - 1) as f64;
        let k = (x as usize).min(TRANSMITTANCE_NODES - 2);
        self.nodes[k].lerp(self.nodes[k + 1], x - k as f64)
    }
}

/// The geodetic latitude (radians) of the table's row at `v` (0 south, 1 north): `v − ½` goes as
/// the square root of the latitude ([`Rings::light_table`]).
fn row_latitude(v: f64) -> f64 {
    let t = 2.0 * v - 1.0;
    t.signum() * t * t * FRAC_PI_2
}

/// Where the globe hides the sun from the ring plane, for a spheroid: scaled by its radii it is a
/// unit sphere, the ring plane stays `z = 0` and a ring point at scaled radius ρ is dark where
/// `x'·ŝ' < 0` and `ρ²(1 − h'² cos²(φ − φ_s)) < 1` (`h'` the scaled sun's horizontal length).
struct GlobeShadow {
    equator_m: f64,
    sun_azimuth: f64,
    horizontal: f64,
}

impl GlobeShadow {
    fn new(radii: DVec3, sun: DVec3) -> Self {
        let equator_m = 0.5 * (radii.x + radii.y);
        let scaled = DVec3::new(sun.x / equator_m, sun.y / equator_m, sun.z / radii.z).normalize_or_zero();
        Self {
            equator_m,
            sun_azimuth: sun.y.atan2(sun.x),
            horizontal: scaled.truncate().length(),
        }
    }

    /// The arc of azimuths (start, length) in shadow at radius `r` m, if any.
    fn arc(&self, r: f64) -> Option<(f64, f64)> {
        let rho = r / self.equator_m;
        if rho <= 1.0 || self.horizontal <= 0.0 {
            return None;
        }
        let k = (1.0 - 1.0 / (rho * rho)).sqrt() / self.horizontal;
        (k < 1.0).then(|| {
            let half = k.acos();
            (self.sun_azimuth + PI - half, 2.0 * half)
        })
    }
}

/// `∫ f(r, view)·cos θ_p·cos θ_x/d² dA` over the annuli `bands` (inner, outer radius, m) in the
/// plane `z = 0`, seen from `p` with normal `n` above its horizon, leaving out at each radius the arc
/// `dark(r)` (start, length). `view` is the unit direction from `p` to the ring point.
fn integrate_over_annuli(
    bands: &[(f64, f64)],
    p: DVec3,
    n: DVec3,
    dark: impl Fn(f64) -> Option<(f64, f64)>,
    f: impl Fn(f64, DVec3) -> Spectrum,
) -> Spectrum {
    // Made once: a rule's construction costs as much as a few hundred of the integrand's values.
    static RADIAL: OnceLock<GaussRule> = OnceLock::new();
    static ANGULAR: OnceLock<GaussRule> = OnceLock::new();
    let radial = RADIAL.get_or_init(|| GaussRule::new(RADIUS_NODES));
    let angular = ANGULAR.get_or_init(|| GaussRule::new(AZIMUTH_NODES));
    let horizontal = n.truncate().length();
    let normal_azimuth = n.y.atan2(n.x);
    let height = n.dot(p);
    let mut irradiance = Spectrum::ZERO;
    for &(inner, outer) in bands {
        let (mid, half) = (0.5 * (inner + outer), 0.5 * (outer - inner));
        for (x, w) in radial.nodes.iter().zip(&radial.weights) {
            let r = mid + half * x;
            // Above the horizon: r·h·cos(φ − φ_n) > n·p.
            let visible = if r * horizontal <= height {
                continue;
            } else if -r * horizontal >= height {
                (0.0, TAU)
            } else {
                let half_arc = (height / (r * horizontal)).acos();
                (normal_azimuth - half_arc, 2.0 * half_arc)
            };
            for (start, length) in arcs_outside(visible, dark(r)) {
                for (y, v) in angular.nodes.iter().zip(&angular.weights) {
                    let phi = start + 0.5 * length * (y + 1.0);
                    let to_ring = DVec3::new(r * phi.cos(), r * phi.sin(), 0.0) - p;
                    let d2 = to_ring.length_squared();
                    let d = d2.sqrt();
                    let view = to_ring / d;
                    let cos_p = n.dot(view);
                    if cos_p <= 0.0 {
                        continue;
                    }
                    let cos_x = p.z.abs() / d;
                    let area = w * half * r * v * 0.5 * length;
                    irradiance += f(r, view) * (cos_p * cos_x / d2 * area);
                }
            }
        }
    }
    irradiance
}

/// The parts of arc `arc` (start, length ≤ 2π) outside `dark` (start, length), as (start, length).
fn arcs_outside(arc: (f64, f64), dark: Option<(f64, f64)>) -> Vec<(f64, f64)> {
    let (start, length) = arc;
    let Some((dark_start, dark_length)) = dark else {
        return vec![arc];
    };
    // In the arc's own coordinate, 0 at its start: the dark arc and its copy a turn earlier.
    let offset = (dark_start - start).rem_euclid(TAU);
    let mut parts = vec![(0.0, length)];
    for lo in [offset, offset - TAU] {
        let hi = lo + dark_length;
        parts = parts
            .into_iter()
            .flat_map(|(a, len)| {
                let b = a + len;
                [(a, lo.min(b)), (hi.max(a), b)]
            })
            .filter(|(a, b)| b > a)
            .map(|(a, b)| (a, b - a))
            .collect();
    }
    parts.into_iter().map(|(a, len)| (start + a, len)).collect()
}

#[cfg(test)]
mod tests;
