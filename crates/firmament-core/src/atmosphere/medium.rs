//! What the atmosphere is made of: density profiles, scattering and absorption coefficients, and
//! phase functions.
//!
//! The density model is Bruneton's ("Precomputed Atmospheric Scattering: a New Implementation",
//! 2017, `DensityProfileLayer`): each constituent's coefficients are its sea-level values times a
//! dimensionless density `d(h) = clamp(exp_term·e^(exp_scale·h) + linear_term·h + constant_term,
//! 0, 1)`, with a profile of two layers: the first below its `width`, the second above.
//!
//! Coefficients are [`Spectrum`]s in m⁻¹, one value per model wavelength.

use std::f64::consts::PI;

use crate::atmosphere::spectrum::Spectrum;
use crate::error::CoreError;

/// One layer of a density profile (Bruneton 2017). Altitude `h` in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DensityLayer {
    /// Where this layer ends, metres above the surface (only the first layer's is used).
    pub width: f64,
    /// Factor of the exponential term, dimensionless.
    pub exp_term: f64,
    /// Rate of the exponential term, m⁻¹ (−1/scale height).
    pub exp_scale: f64,
    /// Slope of the linear term, m⁻¹.
    pub linear_term: f64,
    /// Constant term, dimensionless.
    pub constant_term: f64,
}

impl DensityLayer {
    /// No constituent at all.
    pub const EMPTY: Self = Self {
        width: 0.0,
        exp_term: 0.0,
        exp_scale: 0.0,
        linear_term: 0.0,
        constant_term: 0.0,
    };

    /// `e^(−h/scale_height)`.
    pub fn exponential(scale_height: f64) -> Self {
        Self {
            exp_term: 1.0,
            exp_scale: -1.0 / scale_height,
            ..Self::EMPTY
        }
    }

    /// Density 1 at every height.
    pub fn constant() -> Self {
        Self {
            constant_term: 1.0,
            ..Self::EMPTY
        }
    }

    /// The layer's density at altitude `h` metres, clamped to [0, 1].
    pub fn density(&self, h: f64) -> f64 {
        (self.exp_term * (self.exp_scale * h).exp() + self.linear_term * h + self.constant_term).clamp(0.0, 1.0)
    }
}

/// A two-layer density profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DensityProfile {
    /// `layers[0]` below `layers[0].width`, `layers[1]` above.
    pub layers: [DensityLayer; 2],
}

impl DensityProfile {
    /// One layer everywhere.
    pub fn single(layer: DensityLayer) -> Self {
        Self {
            layers: [DensityLayer::EMPTY, layer],
        }
    }

    /// A tent: 0 at `bottom`, rising linearly to 1 at `peak`, back to 0 at `top` (metres).
    pub fn tent(bottom: f64, peak: f64, top: f64) -> Self {
        let rise = 1.0 / (peak - bottom);
        let fall = 1.0 / (top - peak);
        Self {
            layers: [
                DensityLayer {
                    width: peak,
                    linear_term: rise,
                    constant_term: -bottom * rise,
                    ..DensityLayer::EMPTY
                },
                DensityLayer {
                    linear_term: -fall,
                    constant_term: top * fall,
                    ..DensityLayer::EMPTY
                },
            ],
        }
    }

    /// Density at altitude `h` metres, in [0, 1].
    pub fn density(&self, h: f64) -> f64 {
        if h < self.layers[0].width {
            self.layers[0].density(h)
        } else {
            self.layers[1].density(h)
        }
    }

    fn validate(&self, field: &'static str) -> Result<(), CoreError> {
        let all_finite = self.layers.iter().all(|l| {
            [l.width, l.exp_term, l.exp_scale, l.linear_term, l.constant_term]
                .iter()
                .all(|v| v.is_finite())
        });
        if all_finite {
            Ok(())
        } else {
            Err(CoreError::Invalid {
                field,
                value: format!("{self:?}"),
                rule: "every density layer term must be finite",
            })
        }
    }
}

/// The phase function of aerosols.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MiePhase {
    /// Cornette & Shanks, "Physically reasonable analytic expression for the single-scattering
    /// phase function", Applied Optics 31(16), 1992 — as Bruneton 2017 and Hillaire 2020 use.
    CornetteShanks {
        /// Asymmetry parameter, in (−1, 1).
        g: f64,
    },
    /// Henyey & Greenstein, "Diffuse radiation in the galaxy", ApJ 93, 1941.
    HenyeyGreenstein {
        /// Asymmetry parameter, in (−1, 1).
        g: f64,
    },
}

impl MiePhase {
    /// The asymmetry parameter `g`.
    pub fn g(self) -> f64 {
        match self {
            Self::CornetteShanks { g } | Self::HenyeyGreenstein { g } => g,
        }
    }

    /// Phase function value, sr⁻¹, for the cosine `nu` of the scattering angle (between the
    /// propagation directions: `nu = 1` is straight through).
    pub fn eval(self, nu: f64) -> f64 {
        match self {
            Self::CornetteShanks { g } => cornette_shanks(g, nu),
            Self::HenyeyGreenstein { g } => henyey_greenstein(g, nu),
        }
    }

    /// The Legendre coefficient `a_l` of the phase function, which is
    /// `Σ (2l + 1)/(4π)·a_l·P_l(ν)` (`a_0 = 1`; `a_1` is the mean cosine).
    ///
    /// Henyey–Greenstein's are `g^l`. Cornette–Shanks is Henyey–Greenstein times
    /// `3(1 + ν²)/(2(2 + g²))`, and `ν²P_l = α_l P_{l+2} + β_l P_l + γ_l P_{l−2}` with
    /// `α_l = (l+1)(l+2)/((2l+1)(2l+3))`, `β_l = (2l² + 2l − 1)/((2l−1)(2l+3))`,
    /// `γ_l = l(l−1)/((2l−1)(2l+1))`, so its coefficients are
    /// `3/(2(2 + g²))·(g^l + α_l g^{l+2} + β_l g^l + γ_l g^{l−2})` — for `g = 0.8`: 0.844, 0.710,
    /// 0.577, 0.465, 0.374 for l = 1…5, against `g^l`'s 0.8, 0.64, 0.512, 0.410, 0.328.
    pub fn legendre_coefficient(self, l: u32) -> f64 {
        match self {
            Self::HenyeyGreenstein { g } => g.powi(l as i32),
            Self::CornetteShanks { g } => {
                let n = f64::from(l);
                let alpha = (n + 1.0) * (n + 2.0) / ((2.0 * n + 1.0) * (2.0 * n + 3.0));
                let beta = (2.0 * n * n + 2.0 * n - 1.0) / ((2.0 * n - 1.0) * (2.0 * n + 3.0));
                let gamma = n * (n - 1.0) / ((2.0 * n - 1.0) * (2.0 * n + 1.0));
                // γ_l vanishes for l ≤ 1, where g^{l−2} would be a negative power.
                let below = if l >= 2 { gamma * g.powi(l as i32 - 2) } else { 0.0 };
                3.0 / (2.0 * (2.0 + g * g)) * ((1.0 + beta) * g.powi(l as i32) + alpha * g.powi(l as i32 + 2) + below)
            }
        }
    }
}

/// Rayleigh's phase function `3/(16π)·(1 + ν²)`, sr⁻¹.
pub fn rayleigh_phase(nu: f64) -> f64 {
    3.0 / (16.0 * PI) * (1.0 + nu * nu)
}

/// Henyey–Greenstein phase function, sr⁻¹.
pub fn henyey_greenstein(g: f64, nu: f64) -> f64 {
    let denominator = 1.0 + g * g - 2.0 * g * nu;
    (1.0 - g * g) / (4.0 * PI * denominator * denominator.sqrt())
}

/// Cornette–Shanks phase function, sr⁻¹.
pub fn cornette_shanks(g: f64, nu: f64) -> f64 {
    let denominator = 1.0 + g * g - 2.0 * g * nu;
    3.0 / (8.0 * PI) * (1.0 - g * g) * (1.0 + nu * nu) / ((2.0 + g * g) * denominator * denominator.sqrt())
}

/// Molecules: pure scatterers with Rayleigh's phase function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rayleigh {
    /// Scattering coefficient at density 1, m⁻¹.
    pub scattering: Spectrum,
    /// Density profile.
    pub density: DensityProfile,
}

/// Aerosols: scatter and absorb.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mie {
    /// Scattering coefficient at density 1, m⁻¹.
    pub scattering: Spectrum,
    /// Extinction coefficient (scattering + absorption) at density 1, m⁻¹.
    pub extinction: Spectrum,
    /// Density profile.
    pub density: DensityProfile,
    /// Phase function.
    pub phase: MiePhase,
}

/// An absorbing gas (ozone on Earth): absorbs, does not scatter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Absorber {
    /// Absorption coefficient at density 1, m⁻¹.
    pub absorption: Spectrum,
    /// Density profile.
    pub density: DensityProfile,
}

/// The whole medium and the ground under it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Medium {
    /// Molecular scattering.
    pub rayleigh: Rayleigh,
    /// Aerosols.
    pub mie: Mie,
    /// Absorbing gas.
    pub absorber: Absorber,
    /// Lambertian ground albedo per wavelength, in [0, 1].
    pub ground_albedo: Spectrum,
}

/// Scattering and extinction at one point, m⁻¹.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalCoefficients {
    /// Rayleigh scattering.
    pub rayleigh_scattering: Spectrum,
    /// Mie scattering.
    pub mie_scattering: Spectrum,
    /// Total extinction (all constituents).
    pub extinction: Spectrum,
}

impl Medium {
    /// Coefficients at altitude `h` metres.
    pub fn at(&self, h: f64) -> LocalCoefficients {
        let rayleigh_scattering = self.rayleigh.scattering * self.rayleigh.density.density(h);
        let mie_density = self.mie.density.density(h);
        let mie_scattering = self.mie.scattering * mie_density;
        let extinction = rayleigh_scattering
            + self.mie.extinction * mie_density
            + self.absorber.absorption * self.absorber.density.density(h);
        LocalCoefficients {
            rayleigh_scattering,
            mie_scattering,
            extinction,
        }
    }

    /// Scattered radiance fraction per steradian at `h` for scattering-angle cosine `nu`:
    /// `σ_R·P_R(ν) + σ_M·P_M(ν)`, m⁻¹·sr⁻¹.
    pub fn scattering_phase(&self, coefficients: &LocalCoefficients, nu: f64) -> Spectrum {
        coefficients.rayleigh_scattering * rayleigh_phase(nu) + coefficients.mie_scattering * self.mie.phase.eval(nu)
    }

    /// Checks the rules: every coefficient finite and ≥ 0, Mie extinction ≥ Mie scattering,
    /// `g` in (−1, 1), albedo in [0, 1], density terms finite.
    pub fn validate(&self) -> Result<(), CoreError> {
        let non_negative = |field, s: Spectrum| {
            if s.is_finite() && s.min_element() >= 0.0 {
                Ok(())
            } else {
                Err(CoreError::Invalid {
                    field,
                    value: format!("{:?}", s.to_array()),
                    rule: "every coefficient must be finite and >= 0 (m⁻¹)",
                })
            }
        };
        non_negative("atmosphere.rayleigh.scattering", self.rayleigh.scattering)?;
        non_negative("atmosphere.mie.scattering", self.mie.scattering)?;
        non_negative("atmosphere.mie.extinction", self.mie.extinction)?;
        non_negative("atmosphere.ozone.absorption", self.absorber.absorption)?;
        if (self.mie.extinction - self.mie.scattering).min_element() < 0.0 {
            return Err(CoreError::Invalid {
                field: "atmosphere.mie.extinction",
                value: format!("{:?}", self.mie.extinction.to_array()),
                rule: "must be >= atmosphere.mie.scattering at every wavelength",
            });
        }
        let g = self.mie.phase.g();
        if !(g > -1.0 && g < 1.0) {
            return Err(CoreError::Invalid {
                field: "atmosphere.mie.g",
                value: g.to_string(),
                rule: "must lie strictly between -1 and 1",
            });
        }
        if !(self.ground_albedo.is_finite()
            && self.ground_albedo.min_element() >= 0.0
            && self.ground_albedo.max_element() <= 1.0)
        {
            return Err(CoreError::Invalid {
                field: "atmosphere.ground_albedo",
                value: format!("{:?}", self.ground_albedo.to_array()),
                rule: "must lie in [0, 1]",
            });
        }
        self.rayleigh.density.validate("atmosphere.rayleigh.density")?;
        self.mie.density.validate("atmosphere.mie.density")?;
        self.absorber.density.validate("atmosphere.ozone.density")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn integrate_sphere(f: impl Fn(f64) -> f64) -> f64 {
        // ∫ f(ν) dω = 2π ∫_{-1}^{1} f(ν) dν, midpoint rule.
        let n = 200_000;
        (0..n).map(|i| f(-1.0 + (i as f64 + 0.5) * 2.0 / n as f64)).sum::<f64>() * 2.0 / n as f64 * 2.0 * PI
    }

    /// Legendre polynomial P_l(x) by Bonnet's recursion.
    fn legendre(l: u32, x: f64) -> f64 {
        let (mut previous, mut current) = (1.0, x);
        if l == 0 {
            return previous;
        }
        for n in 1..l {
            let n = f64::from(n);
            (previous, current) = (current, ((2.0 * n + 1.0) * x * current - n * previous) / (n + 1.0));
        }
        current
    }

    #[test]
    fn legendre_coefficients_match_quadrature() {
        for g in [-0.6, 0.0, 0.5, 0.8, 0.9] {
            for phase in [MiePhase::CornetteShanks { g }, MiePhase::HenyeyGreenstein { g }] {
                for l in 0..=6 {
                    let quadrature = integrate_sphere(|nu| phase.eval(nu) * legendre(l, nu));
                    let closed = phase.legendre_coefficient(l);
                    assert!(
                        (closed - quadrature).abs() < 1e-6,
                        "{phase:?} l = {l}: {closed} vs {quadrature}"
                    );
                }
            }
        }
    }

    #[test]
    fn phase_functions_are_normalised() {
        assert!((integrate_sphere(rayleigh_phase) - 1.0).abs() < 1e-9);
        for g in [-0.5, 0.0, 0.3, 0.8] {
            assert!(
                (integrate_sphere(|nu| henyey_greenstein(g, nu)) - 1.0).abs() < 1e-6,
                "HG {g}"
            );
            assert!(
                (integrate_sphere(|nu| cornette_shanks(g, nu)) - 1.0).abs() < 1e-6,
                "CS {g}"
            );
        }
    }

    #[test]
    fn tent_profile_matches_bruneton_ozone() {
        let tent = DensityProfile::tent(10_000.0, 25_000.0, 40_000.0);
        // Bruneton's demo: layer 0 width 25 km, linear 1/15 km, constant −2/3; layer 1 −1/15 km, 8/3.
        assert!((tent.layers[0].constant_term + 2.0 / 3.0).abs() < 1e-12);
        assert!((tent.layers[1].constant_term - 8.0 / 3.0).abs() < 1e-12);
        for (h, d) in [
            (0.0, 0.0),
            (10_000.0, 0.0),
            (17_500.0, 0.5),
            (25_000.0, 1.0),
            (32_500.0, 0.5),
            (45_000.0, 0.0),
        ] {
            assert!((tent.density(h) - d).abs() < 1e-12, "{h}");
        }
    }
}
