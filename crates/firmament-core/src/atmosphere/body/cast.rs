//! A body's light on the planet and on the other bodies — moonlight from the Moon as a body: the
//! sunlight its face sends towards a point, summed over the disc the point sees.
//!
//! # Model
//! Seen from a point `q`, the body covers a small cone around the direction `c` to its centre;
//! its irradiance at `q` on a plane facing `c` is
//!
//! `E = ∫ L(ω)·(ω·c) dω` over the directions `ω` that meet it,
//!
//! `L` the radiance its surface sends back towards `q` ([`Body::radiance`] lit by every sun past
//! the shadows, [`super::sunlight_share`], plus the planet's light, [`Body::planetshine_radiance`]).
//! The integral runs over the plane tangent to the unit sphere at `c` (`dω = dA/(1 + x² +
//! y²)^{3/2}`) in polar coordinates about `c`: [`CAST_AZIMUTHS`] azimuths, along each the
//! silhouette found by halving and [`CAST_RADII`] Gauss–Legendre nodes in `θ` from the centre
//! out, `r = r_edge·sin θ` (which smooths the limb, where a Lambert face's light falls as a
//! square root): phases, maria, maps, a lunar eclipse's red and the body's own shape come out of
//! the sum. Far from the body (the Moon from the Earth spans half a degree), the point gets this
//! light as from a sun: one direction and the disc's angular radius; the sky takes it as a sun
//! without a disc of its own ([`Sun::from_body`],
//! [`AtmosphereSky::add_body_lights`](crate::frame::AtmosphereSky::add_body_lights)). Left out:
//! the glow of the body's air and the sky's light on its ground (a few per cent of an
//! Earth-like body's light), and the light of the other bodies on it.

use std::f64::consts::{FRAC_PI_4, PI};
use std::sync::OnceLock;

use glam::DVec3;

use super::{Body, sunlight_share};
use crate::atmosphere::reference::quadrature::GaussRule;
use crate::atmosphere::rings::Rings;
use crate::atmosphere::{Planet, Spectrum, Sun};
use crate::geometry::Ray;

/// The azimuths around the disc's centre the sum takes, evenly spread.
pub const CAST_AZIMUTHS: usize = 48;

/// The Gauss–Legendre nodes along each azimuth, from the centre to the silhouette.
pub const CAST_RADII: usize = 16;

/// Halvings that find the silhouette along an azimuth (2⁻⁴⁸ of the disc's size).
const EDGE_HALVINGS: usize = 48;

/// The spectral irradiance body `index` of `bodies` sends to point `q` on a plane facing its
/// centre (the suns' irradiance units), lit by `suns` past the shadows of the `planet`, its
/// `rings` and the other bodies — all in the planet's frame (e.g.
/// [`Body::to_planet_frame`]). Zero inside the body.
pub fn cast_irradiance(
    q: DVec3,
    index: usize,
    suns: &[Sun],
    planet: &Planet,
    rings: Option<&Rings>,
    bodies: &[Body],
) -> Spectrum {
    static RULE: OnceLock<GaussRule> = OnceLock::new();
    let rule = RULE.get_or_init(|| GaussRule::new(CAST_RADII));
    let body = &bodies[index];
    let to_center = body.center - q;
    let distance = to_center.length();
    let reach = body.radii.max_element();
    if distance <= reach {
        return Spectrum::ZERO;
    }
    let c = to_center / distance;
    let (e1, e2) = c.any_orthonormal_pair();
    let ray = |x: f64, y: f64| Ray::new(q, c + x * e1 + y * e2);
    let meets = |x: f64, y: f64| ray(x, y).is_some_and(|r| body.hit(&r).is_some());
    // The radiance along (x, y) times dω·(ω·c) per unit area of the plane, 1/(1 + x² + y²)².
    let sample = |x: f64, y: f64| {
        let Some(ray) = ray(x, y) else { return Spectrum::ZERO };
        let Some(t) = body.hit(&ray) else { return Spectrum::ZERO };
        let p = ray.at(t);
        let to_viewer = -ray.direction;
        let light = |s: usize| sunlight_share(p, suns, s, planet, rings, bodies, index);
        let radiance = body.radiance(p, to_viewer, suns, light) + body.planetshine_radiance(p, to_viewer, suns, planet);
        radiance / (1.0 + x * x + y * y).powi(2)
    };
    // Beyond the silhouette: the tangent of the angle the largest semi-axis spans.
    let outer = (reach / distance).asin().tan() * 1.001;
    let step = 2.0 * PI / CAST_AZIMUTHS as f64;
    let mut sum = Spectrum::ZERO;
    for k in 0..CAST_AZIMUTHS {
        let (sin, cos) = ((k as f64 + 0.5) * step).sin_cos();
        let (mut inside, mut outside) = (0.0, outer);
        for _ in 0..EDGE_HALVINGS {
            let middle = 0.5 * (inside + outside);
            if meets(middle * cos, middle * sin) {
                inside = middle;
            } else {
                outside = middle;
            }
        }
        let edge = 0.5 * (inside + outside);
        // r = edge·sin θ, θ over [0, π/2]: r dr = edge²·sin θ·cos θ dθ, smooth at the limb.
        for (x, w) in rule.nodes.iter().zip(&rule.weights) {
            let theta = FRAC_PI_4 * (x + 1.0);
            let r = edge * theta.sin();
            let weight = step * w * FRAC_PI_4 * edge * edge * theta.sin() * theta.cos();
            sum += sample(r * cos, r * sin) * weight;
        }
    }
    sum
}

#[cfg(test)]
mod tests;
