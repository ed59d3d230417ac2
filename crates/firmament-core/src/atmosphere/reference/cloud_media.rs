//! Cloud layers as media of the reference: where a ray crosses the layers' shells, the pieces of
//! the ray between crossings and the layers each lies in, the clouds' optical depth by quadrature
//! (deterministic) or by ratio tracking (the path tracer's next-event estimation), and their
//! dual Henyey–Greenstein phase function with its sampling.
//!
//! # Shells
//! A layer fills `bottom_m ≤ h ≤ top_m` in exact geodetic altitude `h` ([`Planet::altitude`]).
//! On a sphere its shells are spheres, intersected in closed form. On any other ellipsoid the
//! shell at height `h` is the surface at distance `h` from the ellipsoid (not an ellipsoid:
//! the ellipsoid inflated by `h` lies inside it, up to metres away on a flattened planet), found
//! along the ray by root finding on `g(t) = h(ray(t))`. Outside the planet `g` is the distance
//! to a convex body, hence convex along any line, and 1-Lipschitz: each level is crossed at most
//! twice, the crossings bracket the minimum of `g` (found by golden-section search) and are
//! refined by Newton's method safeguarded by bisection (`g′ = direction · up`), to 1e-7 m. A
//! chord whose Lipschitz bounds keep a level out of reach is not searched at all.
//!
//! # Quadrature inside a layer
//! [`CloudKind::Uniform`] layers are constant in each piece: their optical depth is the density
//! times the piece's length, exact up to the shell geometry. Every other kind is integrated by
//! composite Simpson with panels no longer than a fraction of the field's finest feature
//! ([`feature_step`]).

use glam::DVec3;
use rand::Rng;

use crate::atmosphere::Planet;
use crate::atmosphere::clouds::{CloudKind, CloudLayer, DualHenyeyGreenstein};
use crate::geometry::{Ray, Sphere};

/// Layers' cloud densities at one point, m⁻¹, by layer index (0 for layers not there).
pub(super) type Densities = [f64; crate::atmosphere::clouds::MAX_CLOUD_LAYERS];

/// A cosine drawn from a dual Henyey–Greenstein phase function: a lobe picked by `blend` with
/// `u_lobe`, then that lobe's Henyey–Greenstein with `u`.
pub(super) fn sample_phase(p: &DualHenyeyGreenstein, u_lobe: f64, u: f64) -> f64 {
    let g = if u_lobe < p.blend { p.g_forward } else { p.g_back };
    super::path_tracer::sample_henyey_greenstein(g, u)
}

/// The longest quadrature panel a layer needs, metres; `None` for a layer that is constant
/// between its shells ([`CloudKind::Uniform`]). The field's finest features
/// ([`CloudShape`](crate::atmosphere::clouds::CloudShape)) are the detail noise's second
/// octave, half a `detail_cell_m` across, and the fades at the cloud's base and top,
/// `base_softness` and `top_softness` of the layer's thickness: a panel is at most 1/32 of the
/// detail cell and a quarter of the thinner fade (but no less than 1/1024 of the thickness).
pub(super) fn feature_step(layer: &CloudLayer) -> Option<f64> {
    if layer.kind == CloudKind::Uniform {
        return None;
    }
    let thickness = layer.top_m - layer.bottom_m;
    let step = match layer.kind.shape() {
        Some(shape) => (shape.detail_cell_m / 32.0).min(thickness * shape.base_softness.min(shape.top_softness) / 4.0),
        None => thickness / 64.0,
    };
    Some(step.max(thickness / 1024.0))
}

/// A layer's density at `p` with altitude `h`, taken as inside the layer (the altitude clamped
/// to it): the value on the side of a shell the caller's piece lies on. The coverage map, if
/// any, is read at `p`'s geodetic latitude and longitude, as
/// [`CloudLayer::density_at`] does.
pub(super) fn density_inside(planet: &Planet, layer: &CloudLayer, p: DVec3, h: f64) -> f64 {
    layer.density_with_coverage(p, h.clamp(layer.bottom_m, layer.top_m), layer.coverage_at(planet, p))
}

/// A part of a ray between consecutive shell crossings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Piece {
    /// Start, metres along the ray.
    pub a: f64,
    /// End, metres along the ray.
    pub b: f64,
    /// Bit `l` set when the piece lies in layer `l`.
    pub inside: u32,
}

impl Piece {
    /// The indices of the layers the piece lies in.
    pub(super) fn layers(self) -> impl Iterator<Item = usize> {
        (0..32).filter(move |l| self.inside & (1 << l) != 0)
    }
}

/// The parameters in `(t0, t1)`, sorted, where a planet-frame ray crosses any layer's bottom or
/// top shell.
pub(super) fn crossings(planet: &Planet, layers: &[CloudLayer], ray: &Ray, t0: f64, t1: f64) -> Vec<f64> {
    let mut levels: Vec<f64> = layers.iter().flat_map(|l| [l.bottom_m, l.top_m]).collect();
    levels.sort_by(f64::total_cmp);
    levels.dedup();
    let mut found = Vec::new();
    if t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) || levels.is_empty() {
        return found;
    }
    let inside = |t: f64| t > t0 && t < t1;
    let sphere = planet.radii.x == planet.radii.y && planet.radii.y == planet.radii.z;
    let mut rest = Vec::new();
    for &h in &levels {
        if sphere || h <= 0.0 {
            // The shell is a sphere, or (height 0) the surface itself: exact intersections.
            let hits = if sphere {
                Sphere {
                    center: DVec3::ZERO,
                    radius: planet.radii.x + h,
                }
                .intersect(ray)
            } else {
                planet.surface().intersect(ray)
            };
            if let Some(hits) = hits {
                found.extend([hits.near, hits.far].into_iter().filter(|&t| inside(t)));
            }
        } else {
            rest.push(h);
        }
    }
    if !rest.is_empty() {
        geodetic_crossings(planet, ray, &rest, t0, t1, &mut found);
    }
    found.sort_by(f64::total_cmp);
    found.dedup();
    found
}

/// Crossings of the geodetic shells at heights `levels` (all > 0) by the chord `[t0, t1]` of a
/// ray on an ellipsoid (see the module docs).
fn geodetic_crossings(planet: &Planet, ray: &Ray, levels: &[f64], t0: f64, t1: f64, found: &mut Vec<f64>) {
    // g⁺ = max(h, 0) is convex and 1-Lipschitz along the ray.
    let g = |t: f64| planet.altitude(ray.at(t)).max(0.0);
    let (g0, g1) = (g(t0), g(t1));
    let highest = g0.max(g1);
    let lower_bound = 0.5 * (g0 + g1 - (t1 - t0));
    let candidates: Vec<f64> = levels
        .iter()
        .copied()
        .filter(|&h| h > lower_bound && h < highest)
        .collect();
    if candidates.is_empty() {
        return;
    }
    // The minimum of g⁺ on the chord, by golden-section search (g⁺ is unimodal).
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (t0, t1);
    let mut x1 = hi - ratio * (hi - lo);
    let mut x2 = lo + ratio * (hi - lo);
    let (mut f1, mut f2) = (g(x1), g(x2));
    let tolerance = 1e-9 * (t1 - t0) + 1e-7;
    while hi - lo > tolerance {
        if f1 <= f2 {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - ratio * (hi - lo);
            f1 = g(x1);
        } else {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + ratio * (hi - lo);
            f2 = g(x2);
        }
    }
    let (t_min, g_min) = if f1 <= f2 { (x1, f1) } else { (x2, f2) };
    for h in candidates {
        if g_min >= h {
            continue;
        }
        // Where the ellipsoid inflated by h meets the ray: a first guess, metres off at most.
        let guess = crate::geometry::Ellipsoid {
            center: DVec3::ZERO,
            radii: planet.radii + DVec3::splat(h),
        }
        .intersect(ray);
        if g0 > h {
            found.push(root(planet, ray, h, t0, t_min, guess.map(|s| s.near)));
        }
        if g1 > h {
            found.push(root(planet, ray, h, t_min, t1, guess.map(|s| s.far)));
        }
    }
}

/// The single root of `h(ray(t)) = level` between `lo` and `hi` (where the altitude is above
/// the level at one end and below it at the other): Newton from `guess`, safeguarded by
/// bisection.
fn root(planet: &Planet, ray: &Ray, level: f64, lo: f64, hi: f64, guess: Option<f64>) -> f64 {
    let f = |t: f64| planet.altitude(ray.at(t)) - level;
    let (mut lo, mut hi) = (lo, hi);
    // Orient the bracket so that f(lo) < 0 < f(hi).
    if f(lo) > 0.0 {
        std::mem::swap(&mut lo, &mut hi);
    }
    let mut t = guess.filter(|t| (t - lo) * (t - hi) < 0.0).unwrap_or(0.5 * (lo + hi));
    for _ in 0..200 {
        let value = f(t);
        if value < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        if (hi - lo).abs() <= 1e-7 || value == 0.0 {
            break;
        }
        let slope = ray.direction.dot(planet.up(ray.at(t)));
        let newton = t - value / slope;
        let mut next = if slope != 0.0 && (newton - lo) * (newton - hi) < 0.0 {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - t).abs() <= 1e-8 {
            // Converged by Newton: one more step would not move; stop on this side.
            t = next;
            break;
        }
        if next == lo || next == hi {
            next = 0.5 * (lo + hi);
        }
        t = next;
    }
    t
}

/// The pieces of the chord `[t0, t1]` of a planet-frame ray between shell crossings, each with
/// the layers it lies in (decided at its middle, by exact altitude).
pub(super) fn pieces(planet: &Planet, layers: &[CloudLayer], ray: &Ray, t0: f64, t1: f64) -> Vec<Piece> {
    if t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) {
        return Vec::new();
    }
    let mut edges = vec![t0];
    edges.extend(crossings(planet, layers, ray, t0, t1));
    edges.push(t1);
    edges
        .windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let h = planet.altitude(ray.at(0.5 * (a + b)));
            let inside = layers
                .iter()
                .enumerate()
                .filter(|(_, l)| h >= l.bottom_m && h <= l.top_m)
                .fold(0, |mask, (i, _)| mask | (1 << i));
            Piece { a, b, inside }
        })
        .collect()
}

/// The optical depth of one layer along a piece lying in it (deterministic: exact for a uniform
/// layer, composite Simpson for any other).
pub(super) fn layer_depth(planet: &Planet, layer: &CloudLayer, ray: &Ray, a: f64, b: f64) -> f64 {
    let density = |t: f64| {
        let p = ray.at(t);
        density_inside(planet, layer, p, planet.altitude(p))
    };
    match feature_step(layer) {
        None => density(0.5 * (a + b)) * (b - a),
        Some(step) => {
            let n = (((b - a) / step).ceil() as usize).max(2).next_multiple_of(2);
            let h = (b - a) / n as f64;
            let sum: f64 = (0..=n)
                .map(|i| {
                    let w = if i == 0 || i == n {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    w * density(a + h * i as f64)
                })
                .sum();
            sum * h / 3.0
        }
    }
}

/// The clouds' optical depth (grey) along the chord `[t0, t1]` of a planet-frame ray.
pub(super) fn optical_depth(planet: &Planet, layers: &[CloudLayer], ray: &Ray, t0: f64, t1: f64) -> f64 {
    pieces(planet, layers, ray, t0, t1)
        .into_iter()
        .map(|piece| {
            piece
                .layers()
                .map(|l| layer_depth(planet, &layers[l], ray, piece.a, piece.b))
                .sum::<f64>()
        })
        .sum()
}

/// Below this transmittance estimate the clouds' transmittance plays Russian roulette: it
/// survives with probability `T/ROULETTE_BELOW`, becoming `ROULETTE_BELOW`. Unbiased, and it ends
/// the walk through a thick cloud early (and spares the caller the air's transmittance).
const ROULETTE_BELOW: f64 = 1e-2;

/// Russian roulette on a small transmittance estimate ([`ROULETTE_BELOW`]).
fn roulette(transmittance: f64, rng: &mut impl Rng) -> f64 {
    if transmittance >= ROULETTE_BELOW {
        transmittance
    } else if transmittance > 0.0 && rng.random::<f64>() * ROULETTE_BELOW < transmittance {
        ROULETTE_BELOW
    } else {
        0.0
    }
}

/// An unbiased estimate of the clouds' transmittance along the chord `[t0, t1]` of a planet-frame
/// ray: uniform layers exactly, the others by ratio tracking (Novák, Selle & Jarosz, "Residual
/// Ratio Tracking for Estimating Attenuation in Participating Media", 2014) against the sum of
/// their `density_per_m` (the field's maximum), with Russian roulette below
/// [`ROULETTE_BELOW`]. Draws random numbers only when the ray meets a layer. Densities use the GPU's altitude ([`Planet::approximate_altitude`]), as
/// the path tracer's air does.
pub(super) fn transmittance_estimate(
    planet: &Planet,
    layers: &[CloudLayer],
    ray: &Ray,
    t0: f64,
    t1: f64,
    rng: &mut impl Rng,
) -> f64 {
    let mut transmittance = 1.0;
    for piece in pieces(planet, layers, ray, t0, t1) {
        let mut uniform_depth = 0.0;
        let mut majorant = 0.0;
        let mut noisy = 0u32;
        for l in piece.layers() {
            let layer = &layers[l];
            if feature_step(layer).is_none() {
                uniform_depth += layer_depth_approximate(planet, layer, ray, piece.a, piece.b);
            } else {
                majorant += layer.density_per_m;
                noisy |= 1 << l;
            }
        }
        transmittance = roulette(transmittance * (-uniform_depth).exp(), rng);
        if transmittance == 0.0 {
            return 0.0;
        }
        if noisy == 0 || majorant <= 0.0 {
            continue;
        }
        let mut t = piece.a;
        loop {
            t -= (1.0 - rng.random::<f64>()).ln() / majorant;
            if t >= piece.b {
                break;
            }
            let p = ray.at(t);
            let h = planet.approximate_altitude(p);
            let density: f64 = (0..layers.len())
                .filter(|l| noisy & (1 << l) != 0)
                .map(|l| density_inside(planet, &layers[l], p, h))
                .sum();
            transmittance = roulette(transmittance * (1.0 - density.min(majorant) / majorant), rng);
            if transmittance == 0.0 {
                return 0.0;
            }
        }
    }
    transmittance
}

/// A uniform layer's optical depth along a piece lying in it, its density taken at the middle
/// with the GPU's altitude.
fn layer_depth_approximate(planet: &Planet, layer: &CloudLayer, ray: &Ray, a: f64, b: f64) -> f64 {
    let p = ray.at(0.5 * (a + b));
    density_inside(planet, layer, p, planet.approximate_altitude(p)) * (b - a)
}

/// The clouds' scattering coefficient times their phase function at the cosine `nu`, m⁻¹·sr⁻¹
/// (grey), for the layers' densities at one point.
pub(super) fn scattering_phase(layers: &[CloudLayer], densities: &Densities, nu: f64) -> f64 {
    layers
        .iter()
        .zip(densities)
        .filter(|(_, d)| **d > 0.0)
        .map(|(layer, d)| layer.albedo * d * layer.phase.eval(nu))
        .sum()
}

/// The clouds' scattering coefficient at one point, m⁻¹ (grey).
pub(super) fn scattering(layers: &[CloudLayer], densities: &Densities) -> f64 {
    layers.iter().zip(densities).map(|(layer, d)| layer.albedo * d).sum()
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::atmosphere::presets;

    /// The crossings of an oblate planet's geodetic shells are where the exact altitude equals the
    /// level, found independently by marching and bisecting.
    #[test]
    fn geodetic_crossings_are_where_the_altitude_is_the_level() {
        let planet = crate::atmosphere::Planet::spheroid(6_378_137.0, 6_378_137.0 * 0.9, 100_000.0);
        let layer = CloudLayer::new(1_500.0, 4_000.0, 1.0, 0.05, CloudKind::Uniform);
        let base = planet.surface_point(40f64.to_radians(), 0.3);
        let up = planet.up(base);
        let east = DVec3::Z.cross(up).normalize();
        for (elevation, height) in [(0.0f64, 2.0), (3.0, 2.0), (30.0, 2.0), (-2.0, 9_000.0), (0.5, 3_000.0)] {
            let (s, c) = elevation.to_radians().sin_cos();
            let ray = Ray::new(base + up * height, east * c + up * s).unwrap();
            let end = 2_000_000.0;
            let got = crossings(&planet, std::slice::from_ref(&layer), &ray, 0.0, end);
            // Brute force: march 1 m steps near sign changes found on a 100 m grid.
            let mut want = Vec::new();
            for level in [layer.bottom_m, layer.top_m] {
                let f = |t: f64| planet.altitude(ray.at(t)) - level;
                let steps = 20_000;
                let dt = end / steps as f64;
                for i in 0..steps {
                    let (a, b) = (dt * i as f64, dt * (i + 1) as f64);
                    if f(a).signum() != f(b).signum() {
                        let (mut lo, mut hi) = (a, b);
                        for _ in 0..100 {
                            let m = 0.5 * (lo + hi);
                            if f(m).signum() == f(lo).signum() {
                                lo = m;
                            } else {
                                hi = m;
                            }
                        }
                        want.push(0.5 * (lo + hi));
                    }
                }
            }
            want.sort_by(f64::total_cmp);
            assert_eq!(got.len(), want.len(), "{elevation}°: {got:?} vs {want:?}");
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() < 1e-5, "{elevation}°: {got:?} vs {want:?}");
                let p = ray.at(*g);
                let h = planet.altitude(p);
                assert!(
                    (h - layer.bottom_m).abs() < 1e-5 || (h - layer.top_m).abs() < 1e-5,
                    "{h}"
                );
            }
        }
        // A sphere is intersected in closed form.
        let earth = presets::earth().planet;
        let sphere = crate::atmosphere::Planet::sphere(earth.radii.x, earth.atmosphere_height);
        let ray = Ray::new(DVec3::new(0.0, 0.0, earth.radii.x + 2.0), DVec3::new(1.0, 0.0, 0.1)).unwrap();
        let got = crossings(&sphere, std::slice::from_ref(&layer), &ray, 0.0, 1e7);
        assert_eq!(got.len(), 2);
        for (t, level) in got.iter().zip([layer.bottom_m, layer.top_m]) {
            assert!((sphere.altitude(ray.at(*t)) - level).abs() < 1e-6);
        }
    }

    #[test]
    fn dual_henyey_greenstein_is_normalised_and_sampled() {
        let p = DualHenyeyGreenstein {
            g_forward: 0.8,
            g_back: -0.3,
            blend: 0.8,
        };
        let n = 200_000;
        let integral: f64 = (0..n)
            .map(|i| p.eval(-1.0 + (i as f64 + 0.5) * 2.0 / n as f64))
            .sum::<f64>()
            * 2.0
            / n as f64
            * 2.0
            * PI;
        assert!((integral - 1.0).abs() < 1e-6, "{integral}");
        // Mean cosine: blend·g_f + (1 − blend)·g_b.
        let m = 1000;
        let mean: f64 = (0..m)
            .flat_map(|i| (0..m).map(move |j| ((i as f64 + 0.5) / m as f64, (j as f64 + 0.5) / m as f64)))
            .map(|(a, b)| sample_phase(&p, a, b))
            .sum::<f64>()
            / (m * m) as f64;
        assert!((mean - (0.8 * 0.8 - 0.2 * 0.3)).abs() < 1e-4, "{mean}");
    }

    /// The composite Simpson rule at [`feature_step`] resolves every kind's field: the optical
    /// depth along slant rays through each layer agrees with a 0.25 m midpoint rule to 2e-3 (relative
    /// above an optical depth of 1, absolute below).
    #[test]
    fn the_feature_step_resolves_the_field() {
        let planet = crate::atmosphere::Planet::sphere(6_371_000.0, 60_000.0);
        let mut worst: f64 = 0.0;
        for kind in CloudKind::ALL {
            let layer = CloudLayer {
                seed: 7,
                ..CloudLayer::new(1_000.0, 2_500.0, 0.95, 0.05, kind)
            };
            let mut clouded = 0;
            for (i, elevation) in [90.0f64, 70.0, 40.0, 25.0, 12.0].into_iter().enumerate() {
                let (s, c) = elevation.to_radians().sin_cos();
                let origin = DVec3::new(3_000.0 * i as f64, 1_700.0 * i as f64, 6_371_002.0);
                let ray = Ray::new(origin, DVec3::new(c, 0.3 * c, s)).unwrap();
                let end = 2_600.0 / s;
                let got = optical_depth(&planet, std::slice::from_ref(&layer), &ray, 0.0, end);
                let n = (end / 0.25) as usize;
                let fine: f64 = (0..n)
                    .map(|k| layer.density_at(&planet, ray.at((k as f64 + 0.5) * end / n as f64)))
                    .sum::<f64>()
                    * end
                    / n as f64;
                // Relative where thick, absolute (a transmittance error) where thin.
                let error = (got - fine).abs() / fine.max(1.0);
                worst = worst.max(error);
                clouded += usize::from(fine > 0.0);
                assert!(error < 2e-3, "{kind:?} at {elevation}°: {got} vs {fine}");
            }
            assert!(clouded >= 2, "{kind:?}: the rays meet too little cloud");
        }
        println!("worst relative error of the optical depth: {worst:.2e}");
    }
}
