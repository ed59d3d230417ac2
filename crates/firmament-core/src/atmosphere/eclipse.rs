//! Eclipses: bodies (the Moon, another world) that pass in front of a sun and hide part of its
//! limb-darkened disc from a point in space.
//!
//! # Model
//! A sun is a disc of angular radius α whose radiance falls off by the linear limb-darkening law
//! `I(μ)/I(1) = 1 − u·(1 − μ)` ([`Sun`]); an [`Eclipser`] is an opaque ball that a point `p`
//! sees as a disc of angular radius `β = asin(R/|c − p|)` centred `D` from the sun's centre.
//! Both discs are flat on the sky (every angle that matters is a few degrees or less, where the
//! sphere and its tangent plane differ by `α²/6` relative). In units of the sun's radius the body
//! is a disc of radius `k = β/α` at distance `d = D/α`, and the fraction of the sun's light it
//! hides is
//!
//! `H = ∫₀¹ I(r)·2θ(r)·r dr / ∫₀¹ I(r)·2π·r dr`,
//!
//! `θ(r)` the half-angle of the sun's ring of radius `r` inside the body's disc:
//! `π` where the ring lies inside it (`r ≤ k − d`), `0` where it misses it (`r ≤ d − k` or
//! `r ≥ d + k`), `acos((r² + d² − k²)/(2rd))` between. The denominator is `π(1 − u/3)`; the fully
//! covered core has a closed form; the partly covered rings `[|d − k|, min(1, d + k)]` are
//! integrated by Gauss–Legendre after `r = a + (b − a)(1 − cos φ)/2`, which takes away the
//! square-root ends of `θ` and of `I` at the limb ([`ECLIPSE_QUADRATURE_POINTS`] nodes:
//! within 3e-8 of the exact value, see the tests). The GPU (`atmosphere/eclipse.wgsl`) runs
//! the same quadrature in f32.
//!
//! Several bodies in front of one sun: their visible fractions multiply (exact unless two of
//! them overlap on that sun's disc, which needs two bodies nearly in line with it).
//!
//! A total solar eclipse hides the whole disc only from inside the body's umbra; the air around
//! it stays lit, which is what gives the darkened sky its sunset all round the horizon.

use std::f64::consts::PI;
use std::sync::OnceLock;

use glam::DVec3;

use crate::atmosphere::{Planet, Sun};
use crate::error::CoreError;

/// The most eclipsing bodies a sky takes (the GPU's uniform holds this many).
pub const MAX_ECLIPSERS: usize = 4;

/// Gauss–Legendre nodes over the sun's partly covered rings.
pub const ECLIPSE_QUADRATURE_POINTS: usize = 8;

/// An opaque ball that can pass in front of the suns: the Moon, a moon, another planet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Eclipser {
    /// Centre, metres, in the frame the sky is given in (the world frame for
    /// [`AtmosphereSky`](crate::frame::AtmosphereSky)).
    pub center: DVec3,
    /// Radius, metres, > 0 (the Moon's mean radius is 1 737 400 m).
    pub radius_m: f64,
}

impl Eclipser {
    /// Checks the rules: centre finite, radius finite and > 0 m.
    pub fn validate(&self) -> Result<(), CoreError> {
        if !self.center.is_finite() {
            return Err(CoreError::Invalid {
                field: "eclipser.center",
                value: format!("{:?}", self.center.to_array()),
                rule: "must be finite metres",
            });
        }
        if !(self.radius_m.is_finite() && self.radius_m > 0.0) {
            return Err(CoreError::Invalid {
                field: "eclipser.radius",
                value: self.radius_m.to_string(),
                rule: "must be a finite radius > 0 m",
            });
        }
        Ok(())
    }

    /// The same body with its centre moved from the world frame into `planet`'s frame.
    pub fn to_planet_frame(&self, planet: &Planet) -> Self {
        Self {
            center: planet.to_planet_frame(self.center),
            ..*self
        }
    }

    /// Whether the ray from `origin` along unit `direction` (in this body's frame) meets the body
    /// ahead of it: a sun's disc behind it is hidden there.
    pub fn hides(&self, origin: DVec3, direction: DVec3) -> bool {
        let to_center = self.center - origin;
        let along = to_center.dot(direction);
        along > 0.0 && to_center.length_squared() - along * along < self.radius_m * self.radius_m
    }

    /// The fraction of `sun`'s light (its `direction` in the frame of `p` and this body) that
    /// reaches point `p` past this body: 1 in full sunlight, 0 inside the umbra or the body.
    pub fn visible_fraction(&self, p: DVec3, sun: &Sun) -> f64 {
        let to_body = self.center - p;
        let distance = to_body.length();
        if distance <= self.radius_m {
            return 0.0;
        }
        let direction = sun.direction.normalize();
        // atan2 keeps the precision acos loses for small angles.
        let separation = to_body.cross(direction).length().atan2(to_body.dot(direction));
        let body_radius = (self.radius_m / distance).asin();
        if separation >= sun.angular_radius + body_radius {
            return 1.0;
        }
        1.0 - hidden_fraction(
            separation / sun.angular_radius,
            body_radius / sun.angular_radius,
            sun.limb_darkening,
        )
    }
}

/// The fraction of `sun`'s light reaching `p` past every body in `eclipsers` (see the module
/// docs for several at once) but the one whose light it is ([`Sun::from_body`]).
pub fn visible_fraction(p: DVec3, sun: &Sun, eclipsers: &[Eclipser]) -> f64 {
    eclipsers
        .iter()
        .enumerate()
        .filter(|(i, _)| sun.from_body != Some(*i))
        .map(|(_, e)| e.visible_fraction(p, sun))
        .product()
}

/// The fraction of a limb-darkened disc's light (radius 1, limb darkening `u` in [0, 1]) hidden
/// by a disc of radius `k` whose centre is `d` from its centre (both in units of its radius).
pub fn hidden_fraction(d: f64, k: f64, u: f64) -> f64 {
    let d = d.abs();
    if k <= 0.0 || d >= 1.0 + k {
        return 0.0;
    }
    if k >= 1.0 + d {
        return 1.0;
    }
    let total = PI * (1.0 - u / 3.0);
    // ∫₀^a I(r)·2πr dr over the core every ring of which the body covers.
    let core = (k - d).clamp(0.0, 1.0);
    let covered = PI * (1.0 - u) * core * core + 2.0 * PI * u / 3.0 * (1.0 - (1.0 - core * core).powf(1.5));
    let (a, b) = ((d - k).abs(), (d + k).min(1.0));
    let mut partial = 0.0;
    if b > a && d > 0.0 {
        static RULE: OnceLock<GaussLegendre> = OnceLock::new();
        let (nodes, weights) = RULE.get_or_init(gauss_legendre);
        for (x, w) in nodes.iter().zip(weights) {
            // φ over [0, π]: r = a + (b − a)(1 − cos φ)/2, dr = (b − a)/2·sin φ dφ.
            let phi = 0.5 * PI * (x + 1.0);
            let r = a + 0.5 * (b - a) * (1.0 - phi.cos());
            let jacobian = 0.5 * (b - a) * phi.sin() * 0.5 * PI;
            let cos_theta = ((r * r + d * d - k * k) / (2.0 * r * d)).clamp(-1.0, 1.0);
            let intensity = 1.0 - u * (1.0 - (1.0 - r * r).max(0.0).sqrt());
            partial += w * jacobian * intensity * 2.0 * cos_theta.acos() * r;
        }
    }
    ((covered + partial) / total).clamp(0.0, 1.0)
}

/// Nodes and weights of a Gauss–Legendre rule.
type GaussLegendre = ([f64; ECLIPSE_QUADRATURE_POINTS], [f64; ECLIPSE_QUADRATURE_POINTS]);

/// The nodes and weights of [`ECLIPSE_QUADRATURE_POINTS`]-point Gauss–Legendre on [−1, 1]
/// (Newton's method on the Legendre polynomial from Tricomi's initial guesses).
fn gauss_legendre() -> GaussLegendre {
    let n = ECLIPSE_QUADRATURE_POINTS;
    let mut nodes = [0.0; ECLIPSE_QUADRATURE_POINTS];
    let mut weights = [0.0; ECLIPSE_QUADRATURE_POINTS];
    for i in 0..n {
        let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for j in 2..=n {
                let j = j as f64;
                (p0, p1) = (p1, ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p0) / j);
            }
            derivative = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let step = p1 / derivative;
            x -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        nodes[i] = x;
        weights[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
    (nodes, weights)
}

/// The nodes and weights the GPU's quadrature uses, as f32 (`generated/constants` holds them).
pub fn eclipse_quadrature() -> ([f32; ECLIPSE_QUADRATURE_POINTS], [f32; ECLIPSE_QUADRATURE_POINTS]) {
    let (nodes, weights) = gauss_legendre();
    (nodes.map(|x| x as f32), weights.map(|w| w as f32))
}

#[cfg(test)]
mod tests;
