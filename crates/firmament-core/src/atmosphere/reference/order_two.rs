//! Second-order scattering by nested quadrature: a deterministic reference for the path tracer's
//! `per_order[2]` tally, W·m⁻²·sr⁻¹·nm⁻¹.
//!
//! The radiance reaching the eye at `x` along the view direction `v` after exactly two
//! scattering or reflection events is
//!
//! ```text
//! L₂(x, v) = ∫ T(x, y) ∫_{S²} σ_s P(y; v·ω) L₁(y, ω) dω dt  +  T(x, g) · ρ/π · E₁(g)
//! ```
//!
//! - `y` runs along the view ray; `σ_s P` is [`Medium::scattering_phase`] (Rayleigh and Mie
//!   together) for the cosine `v·ω` between the view ray and the direction `ω` the light comes
//!   from — the path tracer's convention.
//! - `L₁(y, ω)` is the radiance arriving at `y` from `ω` after exactly one event: sunlight
//!   scattered once along the ray from `y` towards `ω` (every sun, each a point, shadowed by the
//!   ground), plus, when that ray meets the ground, the directly sunlit ground (`ρ/π` times the
//!   suns' direct irradiance) attenuated back to `y`.
//! - The last term is there only when the view ray ends on the ground `g`: the ground's albedo
//!   `ρ` over π times `E₁`, its irradiance from once-scattered skylight (`∫ L₁ cos θ dω` over the
//!   upper hemisphere, from 1 mm above the ground, as the path tracer reflects).
//!
//! Every integral is a fixed rule, so the result is the same on any number of threads:
//! - **Along rays** (the view ray, each ray towards the light): Gauss–Legendre panels split where
//!   the ray passes closest to the centre, where it enters or leaves a sun's shadow, and where it
//!   crosses shells at the density profiles' kinks and every two e-folds of each exponential
//!   constituent, and split again until no panel is more than 2 optical depths thick. The optical depth from the ray's start to each
//!   node comes from the same nodes (the integral of their interpolating polynomial), so
//!   transmittance costs no extra evaluations.
//! - **Over directions**, in polar coordinates about the local up: the trapezoid rule in azimuth
//!   (which converges exponentially for a smooth periodic integrand), and in the polar angle
//!   Gauss–Legendre panels of at most 0.25 rad, narrow enough for the phase function's peak
//!   both about `v` and about each sun (Earth's haze, Cornette–Shanks with `g = 0.8`, has its
//!   singularities 0.22i rad from the peak), split exactly at the horizon seen from `y`
//!   (computed per azimuth, so ellipsoids too) and graded geometrically towards it on both
//!   sides, where the light changes fastest. With one sun over a sphere the light is
//!   mirror-symmetric about the sun's vertical plane through `y`, so `L₁` is computed for half
//!   the azimuths and weighted for both.
//! - **Towards the suns**: on a spherical planet a table of the optical depth to the top of the
//!   atmosphere over Bruneton's `(x_μ, x_r)` parameterisation (smooth, even at the horizon), with
//!   4 × 4-point Lagrange interpolation; on any other planet the optical depth is integrated at
//!   every point (correct, much slower). Ground shadow is an exact geometric test either way.
//!
//! [`SecondOrderSettings::refinement`] doubles every node count (and the table's resolution), so
//! two levels bound the error.
//!
//! [`Medium::scattering_phase`]: crate::atmosphere::Medium::scattering_phase

use std::f64::consts::PI;

use glam::DVec3;
use rayon::prelude::*;

use super::inputs::{Reference, segment};
use super::quadrature::GaussRule;
use crate::atmosphere::depth_table::DepthTable;
use crate::atmosphere::medium::{Density, DensityProfile, LocalCoefficients};
use crate::atmosphere::spectrum::Spectrum;
use crate::geometry::{Ellipsoid, Ray};

/// How finely [`Reference::second_order`] integrates.
///
/// At the defaults, on Bruneton's Earth seen from the ground, level 1 changes the result by
/// 6·10⁻⁵ (sun 30° or 60° from the zenith, looking 45° up), 6·10⁻⁵ looking 0.5° above the
/// horizon, 7.6·10⁻⁴ with the sun 5° up, 3.2·10⁻³ in twilight (sun 6° down, where shadow edges
/// cross the directions unaligned with the panels).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SecondOrderSettings {
    /// Gauss–Legendre nodes per panel along the view ray and the rays towards the light.
    pub ray_nodes: usize,
    /// Gauss–Legendre nodes per panel of the polar angle about the local up.
    pub polar_nodes: usize,
    /// Azimuths about the local up (trapezoid rule).
    pub azimuths: usize,
    /// Geometric panels (each a quarter of the one before) on each side of the horizon.
    pub horizon_panels: usize,
    /// Each level doubles the three node counts above and the sun table's resolution, and adds
    /// two horizon panels (at most 4 levels).
    pub refinement: u32,
}

impl Default for SecondOrderSettings {
    fn default() -> Self {
        Self {
            ray_nodes: 3,
            polar_nodes: 3,
            azimuths: 64,
            horizon_panels: 4,
            refinement: 0,
        }
    }
}

/// Widest panel of the polar angle, radians: Earth's haze peak is analytic within 0.22 rad.
const MAX_POLAR_PANEL: f64 = 0.25;
/// Width of the band each side of the horizon that is graded geometrically, radians.
const HORIZON_BAND: f64 = 0.25;
/// Ratio between successive graded panels at the horizon.
const HORIZON_GRADING: f64 = 4.0;
/// Largest optical depth (any wavelength) of one panel along a ray.
const MAX_PANEL_DEPTH: f64 = 2.0;
/// E-folds of an exponential constituent's density between shells.
const SHELL_E_FOLDS: f64 = 2.0;
/// Beyond this many e-folds a constituent adds no shells (its density there is < 5·10⁻⁵).
const MAX_SHELL_E_FOLDS: f64 = 10.0;
/// The sun table's size at refinement 0: x_μ × x_r.
const TABLE_SIZE: [usize; 2] = [256, 128];
/// Nodes per panel when the sun table is built.
const TABLE_NODES: usize = 8;
/// Height above the ground from which reflected light continues (the path tracer's), metres.
const GROUND_LIFT: f64 = 1e-3;

/// `L₂` along a planet-frame view ray (see the module docs).
pub(super) fn second_order(reference: &Reference, view: &Ray, settings: &SecondOrderSettings) -> Spectrum {
    Integrator::new(reference, settings).second_order(view)
}

/// Where the optical depth towards the suns comes from.
enum SunDepth {
    /// A spherical planet: the table.
    Table(DepthTable),
    /// Any other planet: integrated at every point.
    Exact,
}

/// Everything one evaluation of `L₂` reuses.
struct Integrator<'a> {
    reference: &'a Reference,
    ray_rule: GaussRule,
    polar_rule: GaussRule,
    azimuths: usize,
    horizon_panels: usize,
    /// Altitudes of the shells that split rays into panels, metres, ascending.
    shells: Vec<f64>,
    sun_depth: SunDepth,
    /// The radius of a spherical planet, whose altitude is simply `|p| − R`.
    sphere: Option<f64>,
    /// One sun over a spherical planet: the light is mirror-symmetric about the plane through
    /// the sun, the centre and any point, so each azimuth's `L₁` serves its mirror image too.
    mirror: bool,
}

impl<'a> Integrator<'a> {
    /// `L₂` along a planet-frame view ray.
    fn second_order(&self, view: &Ray) -> Spectrum {
        let Some(ray) = Ray::new(view.origin, view.direction) else {
            return Spectrum::ZERO;
        };
        let planet = &self.reference.atmosphere.planet;
        let medium = &self.reference.atmosphere.medium;
        let Some(view_segment) = segment(planet, &ray) else {
            return Spectrum::ZERO;
        };
        // The view ray's nodes: where, their weight times the transmittance from the eye, the
        // medium there.
        let mut nodes = Vec::new();
        let view_depth = self.march(
            &ray,
            view_segment.start,
            view_segment.end,
            &self.ray_rule,
            |p, weight, depth, coefficients| nodes.push((p, weight * (-depth).exp(), *coefficients)),
        );
        let columns = self.columns();
        // One task per (node, azimuth), summed afterwards in a fixed order: deterministic.
        let tasks: Vec<Spectrum> = (0..nodes.len() * columns)
            .into_par_iter()
            .map(|task| {
                let (p, weight, coefficients) = &nodes[task / columns];
                let phase = |omega: DVec3| medium.scattering_phase(coefficients, ray.direction.dot(omega));
                self.column(*p, task % columns, false, &phase) * *weight
            })
            .collect();
        let mut total: Spectrum = tasks.into_iter().sum();
        if view_segment.ends_on_ground {
            // Lit by once-scattered skylight, reflected from 1 mm above the ground as the path
            // tracer does.
            let ground = ray.at(view_segment.end);
            let start = ground + planet.up(ground) * GROUND_LIFT;
            let cosine = |_: DVec3| Spectrum::ONE;
            let irradiance: Vec<Spectrum> = (0..columns)
                .into_par_iter()
                .map(|j| self.column(start, j, true, &cosine))
                .collect();
            total += (-view_depth).exp() * medium.ground_albedo / PI * irradiance.into_iter().sum::<Spectrum>();
        }
        total
    }

    /// The rules for `settings`, and the sun table on a spherical planet.
    fn new(reference: &'a Reference, settings: &SecondOrderSettings) -> Self {
        let level = settings.refinement.min(4);
        let scale = 1usize << level;
        let planet = &reference.atmosphere.planet;
        let mut integrator = Self {
            reference,
            ray_rule: GaussRule::new(settings.ray_nodes.max(1).saturating_mul(scale)),
            polar_rule: GaussRule::new(settings.polar_nodes.max(1).saturating_mul(scale)),
            azimuths: settings.azimuths.max(3).saturating_mul(scale),
            horizon_panels: settings.horizon_panels.saturating_add(2 * level as usize),
            shells: shells(reference),
            sun_depth: SunDepth::Exact,
            sphere: (planet.radii.x == planet.radii.y && planet.radii.y == planet.radii.z).then_some(planet.radii.x),
            mirror: false,
        };
        integrator.mirror = integrator.sphere.is_some() && reference.suns.len() == 1;
        if let Some(radius) = integrator.sphere {
            let size = TABLE_SIZE.map(|s| s * scale);
            let top = radius + integrator.reference.atmosphere.planet.atmosphere_height;
            let rule = GaussRule::new(TABLE_NODES);
            let depth = |ray: &Ray, length: f64| integrator.march(ray, 0.0, length, &rule, |_, _, _, _| ());
            integrator.sun_depth = SunDepth::Table(DepthTable::new(radius, top, size, depth));
        }
        integrator
    }

    /// The geodetic altitude of a planet-frame point ([`Planet::altitude`], exact), metres.
    ///
    /// [`Planet::altitude`]: crate::atmosphere::Planet::altitude
    fn altitude(&self, p: DVec3) -> f64 {
        match self.sphere {
            Some(radius) => p.length() - radius,
            None => self.reference.atmosphere.planet.altitude(p),
        }
    }

    /// Visits the Gauss nodes of `[start, end]` along a planet-frame ray — the point, its weight
    /// (metres), the optical depth from `start` and the medium there — and returns the optical
    /// depth of the whole part.
    fn march(
        &self,
        ray: &Ray,
        start: f64,
        end: f64,
        rule: &GaussRule,
        mut visit: impl FnMut(DVec3, f64, Spectrum, &LocalCoefficients),
    ) -> Spectrum {
        let medium = &self.reference.atmosphere.medium;
        let n = rule.len();
        let mut nodes: Vec<(DVec3, LocalCoefficients)> = Vec::with_capacity(n);
        let mut depth = Spectrum::ZERO;
        let breaks = self.panels(ray, start, end);
        for pair in breaks.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let half = 0.5 * (b - a);
            nodes.clear();
            nodes.extend(rule.nodes.iter().map(|x| {
                let p = ray.at(a + half * (1.0 + x));
                (p, medium.at(self.altitude(p)))
            }));
            for (j, (p, coefficients)) in nodes.iter().enumerate() {
                let row = &rule.partial[j * n..(j + 1) * n];
                let to_node: Spectrum = row
                    .iter()
                    .zip(&nodes)
                    .map(|(w, (_, c))| c.extinction * *w)
                    .sum::<Spectrum>()
                    * half;
                visit(*p, rule.weights[j] * half, depth + to_node, coefficients);
            }
            depth += rule
                .weights
                .iter()
                .zip(&nodes)
                .map(|(w, (_, c))| c.extinction * *w)
                .sum::<Spectrum>()
                * half;
        }
        depth
    }

    /// Panel boundaries of `[start, end]` along a ray: its closest approach to the centre, the
    /// shells it crosses, where it enters or leaves the planet's shadow for each sun, then split
    /// evenly until no panel is thicker than [`MAX_PANEL_DEPTH`].
    fn panels(&self, ray: &Ray, start: f64, end: f64) -> Vec<f64> {
        let planet = &self.reference.atmosphere.planet;
        let medium = &self.reference.atmosphere.medium;
        let mut breaks = vec![start, end];
        let closest = -ray.origin.dot(ray.direction);
        let inside = |t: f64| t > start && t < end;
        if inside(closest) {
            breaks.push(closest);
        }
        for &h in &self.shells {
            let shell = Ellipsoid {
                center: DVec3::ZERO,
                radii: planet.radii + DVec3::splat(h),
            };
            if let Some(hits) = shell.intersect(ray) {
                breaks.extend([hits.near, hits.far].into_iter().filter(|&t| inside(t)));
            }
        }
        for sun in &self.reference.suns {
            breaks.extend(
                shadow_crossings(planet.radii, ray, sun.direction)
                    .into_iter()
                    .filter(|&t| inside(t)),
            );
        }
        breaks.sort_by(f64::total_cmp);
        let tiny = 1e-9 * (end - start).abs().max(1.0);
        breaks.dedup_by(|b, a| *b - *a <= tiny);
        if let Some(last) = breaks.last_mut() {
            *last = end;
        }
        let extinction = |t: f64| medium.at(self.altitude(ray.at(t))).extinction.max_element();
        let mut split = Vec::with_capacity(breaks.len() + 8);
        split.push(start);
        for pair in breaks.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            // The densest point of a panel is an end: shells split at the profiles' kinks and
            // the closest approach.
            let depth = extinction(a).max(extinction(b)) * (b - a);
            let pieces = (depth / MAX_PANEL_DEPTH).ceil().clamp(1.0, 4096.0) as usize;
            split.extend((1..=pieces).map(|i| a + (b - a) * i as f64 / pieces as f64));
        }
        split
    }

    /// Optical depth from a planet-frame point to the top of the atmosphere towards `direction`,
    /// `None` when the ground is in the way.
    fn depth_to_space(&self, p: DVec3, direction: DVec3) -> Option<Spectrum> {
        match &self.sun_depth {
            SunDepth::Table(table) => table.depth(p, direction),
            SunDepth::Exact => {
                let ray = Ray { origin: p, direction };
                match segment(&self.reference.atmosphere.planet, &ray) {
                    None => Some(Spectrum::ZERO),
                    Some(s) if s.ends_on_ground => None,
                    Some(s) => Some(self.march(&ray, s.start, s.end, &self.ray_rule, |_, _, _, _| ())),
                }
            }
        }
    }

    /// The suns' light at a planet-frame point, each weighted by `weigh(its direction)` and
    /// attenuated by the atmosphere towards it and by the optical depth `extra` (one exponential
    /// for both).
    fn sunlight(&self, p: DVec3, extra: Spectrum, weigh: impl Fn(DVec3) -> Spectrum) -> Spectrum {
        self.reference
            .suns
            .iter()
            .map(|sun| {
                let weight = weigh(sun.direction);
                if weight == Spectrum::ZERO {
                    return Spectrum::ZERO;
                }
                self.depth_to_space(p, sun.direction).map_or(Spectrum::ZERO, |depth| {
                    weight * sun.irradiance * (-(depth + extra)).exp()
                })
            })
            .sum()
    }

    /// `L₁`: the radiance arriving at planet-frame point `y` from `direction` after exactly one
    /// scattering or reflection.
    fn once_scattered(&self, y: DVec3, direction: DVec3) -> Spectrum {
        let planet = &self.reference.atmosphere.planet;
        let medium = &self.reference.atmosphere.medium;
        let ray = Ray { origin: y, direction };
        let Some(s) = segment(planet, &ray) else {
            return Spectrum::ZERO;
        };
        let mut sum = Spectrum::ZERO;
        let depth = self.march(
            &ray,
            s.start,
            s.end,
            &self.ray_rule,
            |p, weight, depth, coefficients| {
                let phased = |sun: DVec3| medium.scattering_phase(coefficients, direction.dot(sun));
                sum += self.sunlight(p, depth, phased) * weight;
            },
        );
        if s.ends_on_ground {
            // The path tracer's ground event: lit from 1 mm above, Lambertian.
            let ground = ray.at(s.end);
            let up = planet.up(ground);
            let cosine = |sun: DVec3| Spectrum::splat(up.dot(sun).max(0.0));
            sum += medium.ground_albedo / PI * self.sunlight(ground + up * GROUND_LIFT, depth, cosine);
        }
        sum
    }

    /// Azimuth columns to compute per point: with [`Self::mirror`], the azimuths in `[0, π]`.
    fn columns(&self) -> usize {
        if self.mirror {
            self.azimuths / 2 + 1
        } else {
            self.azimuths
        }
    }

    /// Column `index` of [`Self::columns`]: one azimuth's share of `∫ weigh(ω) L₁(y, ω) dω` over
    /// the sphere (or, with `cosine`, of `∫ cos θ L₁ dω` over the upper hemisphere) — and, with
    /// [`Self::mirror`], its mirror image's share too, which sees the same `L₁`.
    fn column(&self, y: DVec3, index: usize, cosine: bool, weigh: &impl Fn(DVec3) -> Spectrum) -> Spectrum {
        let up = self.reference.atmosphere.planet.up(y);
        // Azimuths from the first sun's, so that a lone sun's mirror plane holds azimuth 0.
        let (e1, e2) = match self.reference.suns.first() {
            Some(sun) => match (sun.direction - up * up.dot(sun.direction)).try_normalize() {
                Some(e1) => (e1, up.cross(e1)),
                None => up.any_orthonormal_pair(),
            },
            None => up.any_orthonormal_pair(),
        };
        let phi = 2.0 * PI * index as f64 / self.azimuths as f64;
        let across = e1 * phi.cos() + e2 * phi.sin();
        let mirrored = self.mirror && index != 0 && 2 * index != self.azimuths;
        let across_mirror = e1 * phi.cos() - e2 * phi.sin();
        let horizon = if cosine { 0.5 * PI } else { self.horizon(y, up, across) };
        let mut breaks = polar_breaks(0.0, horizon, self.horizon_panels, true);
        if !cosine {
            breaks.extend(
                polar_breaks(horizon, PI, self.horizon_panels, false)
                    .into_iter()
                    .skip(1),
            );
        }
        let rule = &self.polar_rule;
        let mut sum = Spectrum::ZERO;
        for pair in breaks.windows(2) {
            let half = 0.5 * (pair[1] - pair[0]);
            for (x, w) in rule.nodes.iter().zip(&rule.weights) {
                let theta = pair[0] + half * (1.0 + x);
                let (sin, cos) = theta.sin_cos();
                let omega = up * cos + across * sin;
                let mut weight = weigh(omega);
                if mirrored {
                    weight += weigh(up * cos + across_mirror * sin);
                }
                let jacobian = if cosine { sin * cos } else { sin };
                sum += weight * self.once_scattered(y, omega) * (w * half * jacobian);
            }
        }
        sum * (2.0 * PI / self.azimuths as f64)
    }

    /// The polar angle from `up` of the horizon seen from planet-frame point `y` towards the
    /// azimuth `across` (a unit vector perpendicular to `up`): directions beyond it meet the
    /// ground. The tangent of the ray `y + t(cos θ·up + sin θ·across)` to the ellipsoid, solved
    /// in the frame where the ellipsoid is the unit sphere.
    fn horizon(&self, y: DVec3, up: DVec3, across: DVec3) -> f64 {
        let radii = self.reference.atmosphere.planet.radii;
        let (p, u, e) = (y / radii, up / radii, across / radii);
        let k = p.length_squared() - 1.0;
        if k <= 0.0 {
            return 0.5 * PI;
        }
        // Tangent: (p·d)² = |d|²·k with d = c·u + s·e; in q = cot θ a quadratic.
        let (a, b) = (p.dot(u), p.dot(e));
        let qa = a * a - k * u.length_squared();
        let qb = 2.0 * (a * b - k * u.dot(e));
        let qc = b * b - k * e.length_squared();
        let discriminant = (qb * qb - 4.0 * qa * qc).max(0.0).sqrt();
        // The root whose ray runs towards the ellipsoid (p·d < 0, so q < −b/a).
        let roots = [(-qb - discriminant) / (2.0 * qa), (-qb + discriminant) / (2.0 * qa)];
        let q = roots
            .into_iter()
            .filter(|q| q * a + b < 0.0)
            .fold(f64::INFINITY, f64::min);
        if q.is_finite() {
            (1.0 / q).atan().rem_euclid(PI)
        } else {
            0.5 * PI
        }
    }
}

/// Where a planet-frame ray crosses the edge of the shadow the ellipsoid of `radii` casts away
/// from a sun towards `sun` (both roots, in or out of the shadow, or none). In the frame where
/// the ellipsoid is the unit sphere the shadow is a cylinder of radius 1 about the sun's axis,
/// behind the centre.
fn shadow_crossings(radii: DVec3, ray: &Ray, sun: DVec3) -> Vec<f64> {
    let Some(axis) = (sun / radii).try_normalize() else {
        return Vec::new();
    };
    let (origin, direction) = (ray.origin / radii, ray.direction / radii);
    let across = |v: DVec3| v - axis * v.dot(axis);
    let (a, b) = (across(direction), across(origin));
    let (qa, qb, qc) = (a.length_squared(), a.dot(b), b.length_squared() - 1.0);
    let discriminant = qb * qb - qa * qc;
    if qa == 0.0 || discriminant < 0.0 {
        return Vec::new();
    }
    let root = discriminant.sqrt();
    [(-qb - root) / qa, (-qb + root) / qa]
        .into_iter()
        .filter(|&t| (origin + direction * t).dot(axis) < 0.0)
        .collect()
}

/// Panel boundaries of the polar angle on `[a, b]`: panels of at most [`MAX_POLAR_PANEL`], the
/// last [`HORIZON_BAND`] before the horizon (`b` when `towards_end`, else `a`) graded in
/// `graded` panels, each [`HORIZON_GRADING`] times narrower than the one before.
fn polar_breaks(a: f64, b: f64, graded: usize, towards_end: bool) -> Vec<f64> {
    let length = b - a;
    if length <= 0.0 {
        return vec![a, b];
    }
    let band = HORIZON_BAND.min(0.5 * length);
    let uniform = length - band;
    let count = (uniform / MAX_POLAR_PANEL).ceil().max(1.0) as usize;
    // Distances from the horizon, descending.
    let mut distances: Vec<f64> = (0..count)
        .map(|i| band + uniform * (1.0 - i as f64 / count as f64))
        .collect();
    distances.extend((0..=graded).map(|i| band / HORIZON_GRADING.powi(i as i32)));
    distances.push(0.0);
    if towards_end {
        distances.iter().map(|d| b - d).collect()
    } else {
        distances.iter().rev().map(|d| a + d).collect()
    }
}

/// Altitudes at which rays are split into panels: every profile's kinks (a table's knots) and,
/// for each exponential term, every [`SHELL_E_FOLDS`] e-folds up to [`MAX_SHELL_E_FOLDS`].
fn shells(reference: &Reference) -> Vec<f64> {
    let medium = &reference.atmosphere.medium;
    let top = reference.atmosphere.planet.atmosphere_height;
    let mut shells = Vec::new();
    for term in &medium.terms {
        if term.extinction().max_element() <= 0.0 {
            continue;
        }
        let profile = match &term.density {
            Density::Profile(profile) => profile,
            Density::Table(table) => {
                shells.extend(table.pairs().map(|(h, _)| h));
                continue;
            }
        };
        shells.extend(profile_kinks(profile));
        for (i, layer) in profile.layers.iter().enumerate() {
            if layer.exp_term == 0.0 || layer.exp_scale == 0.0 {
                continue;
            }
            let base = if i == 0 { 0.0 } else { profile.layers[0].width.max(0.0) };
            let step = SHELL_E_FOLDS / layer.exp_scale.abs();
            let count = (MAX_SHELL_E_FOLDS / SHELL_E_FOLDS) as usize;
            shells.extend((1..=count).map(|m| base + step * m as f64));
        }
    }
    shells.retain(|h| h.is_finite() && *h > 0.0 && *h < top);
    shells.sort_by(f64::total_cmp);
    shells.dedup_by(|b, a| *b - *a < 1.0);
    shells
}

/// Altitudes where a profile's density has a kink: where its layers meet, and where a linear
/// layer is clamped at 0 or 1.
fn profile_kinks(profile: &DensityProfile) -> Vec<f64> {
    let mut kinks = vec![profile.layers[0].width];
    for layer in &profile.layers {
        if layer.exp_term == 0.0 && layer.linear_term != 0.0 {
            kinks.push(-layer.constant_term / layer.linear_term);
            kinks.push((1.0 - layer.constant_term) / layer.linear_term);
        }
    }
    kinks
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::reference::ReferenceSettings;
    use crate::atmosphere::{Planet, presets};

    /// Bruneton's Earth: the `earth` preset's medium on a sphere of 6360 km, lit from 30° zenith.
    fn bruneton_earth() -> Reference {
        let mut atmosphere = presets::earth();
        atmosphere.planet = Planet::sphere(6_360_000.0, 60_000.0);
        let sun = presets::earth_sun(DVec3::new(0.5, 0.0, 0.75_f64.sqrt()));
        Reference::new(
            atmosphere,
            &[sun],
            ReferenceSettings {
                view_steps: 2048,
                ..Default::default()
            },
        )
    }

    #[test]
    fn gauss_rules_integrate_polynomials_and_their_partial_integrals() {
        for n in [1, 2, 4, 7, 16, 32] {
            let rule = GaussRule::new(n);
            let degree = 2 * n as i32 - 1;
            let sum: f64 = rule
                .nodes
                .iter()
                .zip(&rule.weights)
                .map(|(x, w)| w * x.powi(degree - 1))
                .sum();
            let want = if (degree - 1) % 2 == 0 {
                2.0 / degree as f64
            } else {
                0.0
            };
            assert!((sum - want).abs() < 1e-13, "{n}: {sum} vs {want}");
            // ∫_{−1}^{x_j} x^(n−1) dx from the nodes' values.
            let power = n as i32 - 1;
            for j in 0..n {
                let got: f64 = (0..n)
                    .map(|k| rule.partial[j * n + k] * rule.nodes[k].powi(power))
                    .sum();
                let want = (rule.nodes[j].powi(power + 1) - (-1.0_f64).powi(power + 1)) / f64::from(power + 1);
                assert!((got - want).abs() < 1e-12, "{n}/{j}: {got} vs {want}");
            }
        }
    }

    /// The table against the reference's adaptive transmittance, from the ground to the top and
    /// from straight up to just above the horizon: within 10⁻⁴ relative (5·10⁻⁴ for rays
    /// grazing the ground from the top, whose optical depth is 4–10), worst where a horizontal
    /// ray starts just under the ozone's kinked peak.
    #[test]
    fn the_sun_table_matches_the_reference_transmittance() {
        let reference = bruneton_earth();
        let integrator = Integrator::new(&reference, &SecondOrderSettings::default());
        let SunDepth::Table(table) = &integrator.sun_depth else {
            panic!("a sphere gets a table");
        };
        for h in [0.001, 1.0, 300.0, 1_500.0, 7_000.0, 24_000.0, 59_000.0] {
            let p = DVec3::new(0.0, 0.0, 6_360_000.0 + h);
            let dip = (6_360_000.0 / (6_360_000.0 + h)).acos();
            for elevation in [-dip + 1e-4, -0.5 * dip, 0.0, 0.002, 0.02, 0.1, 0.4, 1.0, 1.57] {
                let direction = DVec3::new(elevation.cos(), 0.0, elevation.sin());
                let got = (-table.depth(p, direction).unwrap()).exp();
                let want = reference.transmittance_to_space(p, direction);
                let budget = if elevation < -0.5 * dip { 5e-4 } else { 1e-4 };
                assert!(
                    ((got - want) / want).abs().max_element() < budget,
                    "{h} m, {elevation} rad: {got} vs {want}"
                );
            }
            let below = DVec3::new((dip + 1e-4).cos(), 0.0, -(dip + 1e-4).sin());
            assert!(table.depth(p, below).is_none(), "{h}");
        }
    }

    /// `L₁` is what the reference's own single scattering and directly lit ground give along the
    /// same ray: the conventions (phase, sun, shadow, ground) are the reference's.
    #[test]
    fn once_scattered_light_is_the_references_single_scattering() {
        let reference = bruneton_earth();
        let coarse = Integrator::new(&reference, &SecondOrderSettings::default());
        let fine = Integrator::new(
            &reference,
            &SecondOrderSettings {
                refinement: 1,
                ..Default::default()
            },
        );
        let ground = 6_360_000.0;
        for (height, zenith, azimuth) in [
            (1.0, 45.0_f64, 0.0_f64),
            (1.0, 89.9, 180.0),
            (2_000.0, 92.0, 90.0),
            (2_000.0, 150.0, 0.0),
            (30_000.0, 95.5, 30.0),
        ] {
            let (z, a) = (zenith.to_radians(), azimuth.to_radians());
            let direction = DVec3::new(z.sin() * a.cos(), z.sin() * a.sin(), z.cos());
            let y = DVec3::new(0.0, 0.0, ground + height);
            let (single, lit_ground, _) = reference.single_scattering(&Ray { origin: y, direction }, f64::INFINITY);
            let want = single + lit_ground;
            for (integrator, budget) in [(&coarse, 3e-5), (&fine, 1e-6)] {
                let got = integrator.once_scattered(y, direction);
                assert!(
                    ((got - want) / want).abs().max_element() < budget,
                    "{height} m, {zenith}°: {got} vs {want}"
                );
            }
        }
    }

    /// On an ellipsoid (flattening 0.1) the horizon found per azimuth splits the directions
    /// that meet the ground from those that miss it.
    #[test]
    fn the_horizon_is_exact_on_an_ellipsoid() {
        let mut atmosphere = presets::earth();
        atmosphere.planet = Planet::spheroid(6_378_000.0, 0.9 * 6_378_000.0, 60_000.0);
        let reference = Reference::new(atmosphere.clone(), &[], ReferenceSettings::default());
        let integrator = Integrator::new(&reference, &SecondOrderSettings::default());
        let planet = &atmosphere.planet;
        for (latitude, height) in [(0.3_f64, 1.0), (0.8, 2_000.0), (1.2, 40_000.0)] {
            let foot = planet.surface_point(latitude, 0.4);
            let up = planet.up(foot);
            let y = foot + up * height;
            let (e1, e2) = up.any_orthonormal_pair();
            for phi in [0.0_f64, 1.0, 2.5, 4.0] {
                let across = e1 * phi.cos() + e2 * phi.sin();
                let horizon = integrator.horizon(y, up, across);
                let meets = |theta: f64| {
                    let ray = Ray::new(y, up * theta.cos() + across * theta.sin()).unwrap();
                    segment(planet, &ray).is_some_and(|s| s.ends_on_ground)
                };
                assert!(
                    !meets(horizon - 1e-7) && meets(horizon + 1e-7),
                    "{latitude} {height} {phi}: {horizon}"
                );
            }
        }
    }

    /// Integrating the optical depth towards the suns at every point (what a non-spherical
    /// planet gets) and reading it from the table give the same `L₂`, here on a sphere at a
    /// coarse setting.
    #[test]
    fn the_exact_sun_depth_agrees_with_the_table() {
        let reference = bruneton_earth();
        let settings = SecondOrderSettings {
            ray_nodes: 2,
            polar_nodes: 2,
            azimuths: 12,
            horizon_panels: 2,
            refinement: 0,
        };
        let view = Ray::new(DVec3::new(0.0, 0.0, 6_361_000.0), DVec3::new(-0.5, 0.3, 0.4)).unwrap();
        let table = second_order(&reference, &view, &settings);
        let mut exact = Integrator::new(&reference, &settings);
        exact.sun_depth = SunDepth::Exact;
        let exact = exact.second_order(&view);
        assert!(
            ((table - exact) / exact).abs().max_element() < 2e-4,
            "{table} vs {exact}"
        );
    }
}
