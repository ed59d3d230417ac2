//! A table of the optical depth from any point of a spherical shell of air to its top, for the
//! f64 integrators that need the sun's transmittance at many points (the reference's order-2
//! quadrature, a body's air's tables): built once by the caller's own integration, read by
//! 4 × 4-point Lagrange interpolation.

use glam::DVec3;
use rayon::prelude::*;

use crate::atmosphere::spectrum::Spectrum;
use crate::geometry::Ray;

/// The optical depth from a point to the top of the atmosphere of a spherical planet, over
/// Bruneton's parameterisation ("Precomputed Atmospheric Scattering: a New Implementation",
/// 2017, `GetTransmittanceTextureUvFromRMu` without the texel-centre offsets): `x_r = ρ/H` and
/// `x_μ = (d − d_min)/(d_max − d_min)`, `d` the distance to the top, covering exactly the
/// directions that miss the ground.
pub(crate) struct DepthTable {
    bottom: f64,
    top: f64,
    /// `H`: the distance from the ground to the top along a horizontal ray at the ground.
    horizon: f64,
    size: [usize; 2],
    /// Row-major over x_r, then x_μ.
    values: Vec<Spectrum>,
}

impl DepthTable {
    /// The table between radii `bottom` and `top` (m) at `size` nodes (x_μ × x_r), each node's
    /// optical depth `depth_along(ray, length)` along `ray` over `length` metres.
    pub(crate) fn new(
        bottom: f64,
        top: f64,
        size: [usize; 2],
        depth_along: impl Fn(&Ray, f64) -> Spectrum + Sync,
    ) -> Self {
        let horizon = (top * top - bottom * bottom).sqrt();
        let [n_mu, n_r] = size;
        let values = (0..n_mu * n_r)
            .into_par_iter()
            .map(|index| {
                let (i_r, i_mu) = (index / n_mu, index % n_mu);
                let rho = horizon * i_r as f64 / (n_r - 1) as f64;
                let r = (rho * rho + bottom * bottom).sqrt();
                let (d_min, d_max) = (top - r, rho + horizon);
                let d = d_min + (d_max - d_min) * i_mu as f64 / (n_mu - 1) as f64;
                let mu = if d <= 0.0 {
                    1.0
                } else {
                    ((horizon * horizon - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
                };
                let ray = Ray {
                    origin: DVec3::new(0.0, 0.0, r),
                    direction: DVec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu),
                };
                depth_along(&ray, d)
            })
            .collect();
        Self {
            bottom,
            top,
            horizon,
            size,
            values,
        }
    }

    /// The optical depth from planet-frame point `p` to the top towards `direction`; `None`
    /// when the ray meets the ground.
    pub(crate) fn depth(&self, p: DVec3, direction: DVec3) -> Option<Spectrum> {
        let length = p.length();
        let r = length.clamp(self.bottom, self.top);
        let mu = (p.dot(direction) / length).clamp(-1.0, 1.0);
        if mu < 0.0 && r * r * (1.0 - mu * mu) < self.bottom * self.bottom {
            return None;
        }
        let horizon = self.horizon;
        let rho = (r * r - self.bottom * self.bottom).max(0.0).sqrt();
        let discriminant = (r * r * (mu * mu - 1.0) + self.top * self.top).max(0.0);
        let d = (-r * mu + discriminant.sqrt()).max(0.0);
        let (d_min, d_max) = (self.top - r, rho + horizon);
        let x_mu = ((d - d_min) / (d_max - d_min)).clamp(0.0, 1.0);
        let x_r = (rho / horizon).clamp(0.0, 1.0);
        Some(self.interpolate(x_mu, x_r))
    }

    /// 4 × 4-point Lagrange interpolation (the stencil shifted inwards at the edges).
    fn interpolate(&self, x_mu: f64, x_r: f64) -> Spectrum {
        let [n_mu, n_r] = self.size;
        let (mu_start, mu_weights) = stencil(x_mu * (n_mu - 1) as f64, n_mu);
        let (r_start, r_weights) = stencil(x_r * (n_r - 1) as f64, n_r);
        let mut sum = Spectrum::ZERO;
        for (i, wr) in r_weights.iter().enumerate() {
            let row = (r_start + i) * n_mu + mu_start;
            let along: Spectrum = mu_weights
                .iter()
                .zip(&self.values[row..row + 4])
                .map(|(w, v)| *v * *w)
                .sum();
            sum += along * *wr;
        }
        sum
    }
}

/// The first of 4 grid points around the continuous index `x` on a grid of `n ≥ 4` points, and
/// their cubic Lagrange weights.
fn stencil(x: f64, n: usize) -> (usize, [f64; 4]) {
    let start = (x as usize).saturating_sub(1).min(n - 4);
    let t = x - start as f64;
    let (t1, t2, t3) = (t - 1.0, t - 2.0, t - 3.0);
    let weights = [
        -t1 * t2 * t3 / 6.0,
        0.5 * t * t2 * t3,
        -0.5 * t * t1 * t3,
        t * t1 * t2 / 6.0,
    ];
    (start, weights)
}
