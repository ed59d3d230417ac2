//! The sun's glint on a wind-roughened sea: Cox & Munk's wave slopes, a Fresnel reflection at
//! each facet.
//!
//! Cox & Munk ("Measurement of the Roughness of the Sea Surface from Photographs of the Sun's
//! Glitter", J. Opt. Soc. Am. 44, 838, 1954) found the slopes of a clean sea Gaussian, with a
//! mean square slope growing with the wind speed `W` (m/s, 12.5 m above the sea):
//! `σ² = 0.003 + 0.00512·W` (over both directions; the slight up/cross-wind difference is left
//! out here, so the glint is isotropic). A facet tilted by β from the vertical has slopes of
//! `tan β`, so the slopes' density over the facet normals is Beckmann's distribution with
//! `m² = σ²`, `D(β) = exp(−tan²β/σ²) / (π σ² cos⁴β)`; each facet reflects by Fresnel's equations
//! for water (refractive index [`WATER_REFRACTIVE_INDEX`]); facets hidden from the sun or the eye
//! by the waves are taken out by Smith's shadowing for Beckmann's distribution (Walter et al.,
//! "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007, its rational fit).
//! The bidirectional reflectance is the microfacet one, `F·D·G / (4 μ_s μ_v)`.

use std::f64::consts::PI;

use glam::DVec3;

/// Water's refractive index in the visible (1.333–1.344 from 700 to 400 nm; sea water about
/// 0.006 more).
pub const WATER_REFRACTIVE_INDEX: f64 = 1.34;

/// Cox & Munk's mean square slope of a clean sea for a wind of `wind_speed_mps`:
/// `0.003 + 0.00512·W`.
pub fn slope_variance(wind_speed_mps: f64) -> f64 {
    0.003 + 0.00512 * wind_speed_mps.max(0.0)
}

/// Fresnel's reflectance of unpolarised light arriving from air at a smooth interface with a
/// medium of refractive index `n` (> 1), at incidence cosine `cos_incidence`.
pub fn fresnel_reflectance(cos_incidence: f64, n: f64) -> f64 {
    let c = cos_incidence.clamp(0.0, 1.0);
    // The form without the refraction angle (Cook & Torrance 1982): g = √(n² − 1 + c²).
    let g = (n * n - 1.0 + c * c).sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

/// Beckmann's distribution of facet normals tilted by `cos_tilt` from the vertical, for mean
/// square slope `sigma2`, sr⁻¹ (normalised: `∫ D cos β dω = 1`).
pub fn facet_distribution(cos_tilt: f64, sigma2: f64) -> f64 {
    if cos_tilt <= 0.0 {
        return 0.0;
    }
    let c2 = cos_tilt * cos_tilt;
    let tan2 = (1.0 - c2) / c2;
    (-tan2 / sigma2).exp() / (PI * sigma2 * c2 * c2)
}

/// Smith's share of facets seen from a direction at zenith cosine `mu` (Walter et al. 2007's
/// rational fit for Beckmann's distribution of mean square slope `sigma2`).
pub fn smith_visible(mu: f64, sigma2: f64) -> f64 {
    if mu <= 0.0 {
        return 0.0;
    }
    let a = mu / (sigma2.sqrt() * (1.0 - mu * mu).max(0.0).sqrt());
    if a >= 1.6 {
        1.0
    } else {
        (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a)
    }
}

/// The glint's bidirectional reflectance, sr⁻¹, of a sea whose mean normal is `up`, for light
/// from `to_sun` seen from `to_eye` (unit vectors, any frame): `F·D·G / (4 μ_s μ_v)`; 0 with
/// either below the horizon.
pub fn brdf(up: DVec3, to_sun: DVec3, to_eye: DVec3, sigma2: f64) -> f64 {
    let mu_s = up.dot(to_sun);
    let mu_v = up.dot(to_eye);
    if mu_s <= 0.0 || mu_v <= 0.0 {
        return 0.0;
    }
    let half = (to_sun + to_eye).normalize_or_zero();
    let cos_tilt = up.dot(half);
    let fresnel = fresnel_reflectance(to_sun.dot(half), WATER_REFRACTIVE_INDEX);
    let shadowing = smith_visible(mu_s, sigma2) * smith_visible(mu_v, sigma2);
    fresnel * facet_distribution(cos_tilt, sigma2) * shadowing / (4.0 * mu_s * mu_v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fresnel by Snell's law and the s- and p-polarised amplitudes (a different form from the
    /// one under test).
    fn fresnel_by_snell(cos_i: f64, n: f64) -> f64 {
        let sin_t = (1.0 - cos_i * cos_i).sqrt() / n;
        let cos_t = (1.0 - sin_t * sin_t).sqrt();
        let rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
        let rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
        0.5 * (rs * rs + rp * rp)
    }

    #[test]
    fn fresnel_agrees_with_snell_and_its_limits() {
        let n = WATER_REFRACTIVE_INDEX;
        let normal = ((n - 1.0) / (n + 1.0)).powi(2);
        assert!((fresnel_reflectance(1.0, n) - normal).abs() < 1e-12);
        assert!((fresnel_reflectance(0.0, n) - 1.0).abs() < 1e-12);
        for k in 1..20 {
            let c = f64::from(k) / 20.0;
            assert!(
                (fresnel_reflectance(c, n) - fresnel_by_snell(c, n)).abs() < 1e-12,
                "cos {c}"
            );
        }
    }

    /// ∫ D(β) cos β dω over the hemisphere, by the midpoint rule in β.
    fn projected_area(sigma2: f64) -> f64 {
        let steps = 200_000;
        let db = 0.5 * PI / f64::from(steps);
        (0..steps)
            .map(|i| {
                let beta = (f64::from(i) + 0.5) * db;
                facet_distribution(beta.cos(), sigma2) * beta.cos() * beta.sin() * 2.0 * PI * db
            })
            .sum()
    }

    #[test]
    fn the_facets_cover_the_sea_once_at_every_wind() {
        for wind in [0.5, 2.0, 7.0, 14.0, 30.0] {
            let area = projected_area(slope_variance(wind));
            assert!((area - 1.0).abs() < 1e-6, "wind {wind}: {area}");
        }
    }

    #[test]
    fn the_glint_straight_down_is_fresnel_over_the_slope_spread() {
        // Sun and eye overhead: every term by hand. F(1) = ((n − 1)/(n + 1))², D(0) = 1/(πσ²),
        // G = 1 (a = ∞), μ_s = μ_v = 1.
        let up = DVec3::Z;
        let sigma2 = slope_variance(7.0);
        let by_hand = ((WATER_REFRACTIVE_INDEX - 1.0) / (WATER_REFRACTIVE_INDEX + 1.0)).powi(2) / (4.0 * PI * sigma2);
        assert!((brdf(up, up, up, sigma2) / by_hand - 1.0).abs() < 1e-12);
        // Off the mirror direction it falls as exp(−tan²β/σ²).
        let tilt = 0.1f64;
        let eye = DVec3::new((2.0 * tilt).sin(), 0.0, (2.0 * tilt).cos());
        assert!(brdf(up, up, eye, sigma2) < brdf(up, up, up, sigma2));
        assert_eq!(brdf(up, up, -up, sigma2), 0.0);
        assert_eq!(brdf(up, -up, up, sigma2), 0.0);
    }

    /// The light a calm sea reflects from a sun at `mu_s` into the whole sky, as a share of the
    /// light arriving: ∫ f μ_v dω_v by the midpoint rule.
    fn albedo(mu_s: f64, sigma2: f64) -> f64 {
        let up = DVec3::Z;
        let sun = DVec3::new((1.0 - mu_s * mu_s).sqrt(), 0.0, mu_s);
        let (nt, np) = (2000, 400);
        let (dt, dp) = (0.5 * PI / f64::from(nt), 2.0 * PI / f64::from(np));
        let mut sum = 0.0;
        for i in 0..nt {
            let theta = (f64::from(i) + 0.5) * dt;
            for j in 0..np {
                let phi = (f64::from(j) + 0.5) * dp;
                let eye = DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
                sum += brdf(up, sun, eye, sigma2) * theta.cos() * theta.sin() * dt * dp;
            }
        }
        sum
    }

    #[test]
    fn a_calm_sea_reflects_what_a_flat_one_does() {
        // A nearly flat sea (W = 0: σ² = 0.003) reflects Fresnel's share of a sun that is not
        // low — a limit independent of the slope model.
        let sigma2 = slope_variance(0.0);
        for mu_s in [1.0, 0.7, 0.4] {
            let flat = fresnel_reflectance(mu_s, WATER_REFRACTIVE_INDEX);
            let rough = albedo(mu_s, sigma2);
            assert!((rough / flat - 1.0).abs() < 0.02, "μs {mu_s}: {rough} vs {flat}");
        }
    }
}
