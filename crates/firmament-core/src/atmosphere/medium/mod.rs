//! What the atmosphere is made of: a list of terms, each with its scattering and absorption
//! spectra, its density profile and its phase function, and the ground under them.
//!
//! A term's coefficients are its values at density 1 (m⁻¹, one value per model wavelength) times
//! its dimensionless density at the altitude ([`density`]): Bruneton's profiles ("Precomputed
//! Atmospheric Scattering: a New Implementation", 2017, `DensityProfileLayer`) or a table. Its
//! phase function ([`phase`]) is one of the analytic ones or a table. Bevy's `ScatteringMedium`
//! and Bruneton's density layers describe airs the same way. Earth's, Mars's and Saturn's air is
//! three terms made by [`Constituents`]: molecules, aerosols and an absorbing gas.

pub mod constituents;
pub mod density;
pub mod phase;

pub use constituents::{Absorber, Constituents, Mie, Rayleigh};
pub use density::{Density, DensityLayer, DensityProfile, DensityTable};
pub use phase::{Phase, PhaseTable, cornette_shanks, henyey_greenstein, rayleigh_phase};

use crate::atmosphere::spectrum::Spectrum;
use crate::error::CoreError;

/// The most terms a medium may have (the GPU's uniform holds this many).
pub const MAX_TERMS: usize = 8;

/// One constituent of the medium.
#[derive(Debug, Clone, PartialEq)]
pub struct MediumTerm {
    /// Scattering coefficient at density 1, m⁻¹.
    pub scattering: Spectrum,
    /// Absorption coefficient at density 1, m⁻¹.
    pub absorption: Spectrum,
    /// How the density varies with altitude.
    pub density: Density,
    /// The phase function of the light it scatters (unused where it does not scatter).
    pub phase: Phase,
}

impl MediumTerm {
    /// Scattering plus absorption at density 1, m⁻¹.
    pub fn extinction(&self) -> Spectrum {
        self.scattering + self.absorption
    }
}

/// Trapezoids of [`Medium::vertical_scattering_depth`] and
/// [`Medium::altitude_of_scattering_depth`].
pub const DEPTH_STEPS: usize = 1024;

/// The whole medium and the ground under it.
#[derive(Debug, Clone, PartialEq)]
pub struct Medium {
    /// The terms, at most [`MAX_TERMS`].
    pub terms: Vec<MediumTerm>,
    /// Lambertian ground albedo per wavelength, in [0, 1].
    pub ground_albedo: Spectrum,
}

/// Scattering and extinction at one point, m⁻¹.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalCoefficients {
    /// Each term's scattering, in the medium's order (zero past its terms).
    pub scattering: [Spectrum; MAX_TERMS],
    /// Total extinction (all terms).
    pub extinction: Spectrum,
}

impl LocalCoefficients {
    /// No medium at all.
    pub const NONE: Self = Self {
        scattering: [Spectrum::ZERO; MAX_TERMS],
        extinction: Spectrum::ZERO,
    };

    /// The scattering of all terms together, m⁻¹.
    pub fn total_scattering(&self) -> Spectrum {
        self.scattering.iter().copied().sum()
    }

    /// The mean of two points' coefficients.
    pub fn mean(&self, other: &Self) -> Self {
        Self {
            scattering: std::array::from_fn(|i| (self.scattering[i] + other.scattering[i]) * 0.5),
            extinction: (self.extinction + other.extinction) * 0.5,
        }
    }
}

impl Medium {
    /// Molecules, aerosols and an absorbing gas over a ground of `ground_albedo`.
    pub fn from_constituents(constituents: &Constituents, ground_albedo: Spectrum) -> Self {
        Self {
            terms: constituents.terms(),
            ground_albedo,
        }
    }

    /// The three constituents, where the terms are exactly the ones they make.
    pub fn constituents(&self) -> Option<Constituents> {
        Constituents::from_terms(&self.terms)
    }

    /// Coefficients at altitude `h` metres.
    pub fn at(&self, h: f64) -> LocalCoefficients {
        let mut local = LocalCoefficients::NONE;
        for (term, scattering) in self.terms.iter().zip(&mut local.scattering) {
            let density = term.density.at(h);
            *scattering = term.scattering * density;
            local.extinction += term.extinction() * density;
        }
        local
    }

    /// Scattered radiance fraction per steradian at a point of `coefficients` for scattering-angle
    /// cosine `nu`: `Σ σ_i·p_i(ν)`, m⁻¹·sr⁻¹.
    pub fn scattering_phase(&self, coefficients: &LocalCoefficients, nu: f64) -> Spectrum {
        self.terms
            .iter()
            .zip(&coefficients.scattering)
            .filter(|(_, s)| **s != Spectrum::ZERO)
            .map(|(term, s)| *s * term.phase.eval(nu))
            .sum()
    }

    /// The vertical scattering optical depth between altitudes `bottom` and `top` metres, all
    /// terms together, by trapezoids over [`DEPTH_STEPS`] steps (within 10⁻⁵ of an exponential
    /// profile's closed form over Earth's 60 km).
    pub fn vertical_scattering_depth(&self, bottom: f64, top: f64) -> Spectrum {
        let dh = (top - bottom) / DEPTH_STEPS as f64;
        let scattering = |i: usize| -> Spectrum { self.at(bottom + dh * i as f64).scattering.iter().sum() };
        let inner: Spectrum = (1..DEPTH_STEPS).map(scattering).sum();
        (inner + (scattering(0) + scattering(DEPTH_STEPS)) * 0.5) * dh
    }

    /// The altitude, metres, above which the vertical scattering optical depth up to `top` is
    /// `depth` at the wavelength that scatters most (0 when the whole air scatters less), to
    /// within `top`/[`DEPTH_STEPS`].
    pub fn altitude_of_scattering_depth(&self, top: f64, depth: f64) -> f64 {
        let dh = top / DEPTH_STEPS as f64;
        let scattering = |h: f64| -> f64 { self.at(h).scattering.iter().sum::<Spectrum>().max_element() };
        let mut above = 0.0;
        for i in (0..DEPTH_STEPS).rev() {
            let (low, high) = (dh * i as f64, dh * (i + 1) as f64);
            above += 0.5 * (scattering(low) + scattering(high)) * dh;
            if above >= depth {
                return low;
            }
        }
        0.0
    }

    /// Whether any term scatters or absorbs at all.
    pub fn has_air(&self) -> bool {
        self.terms.iter().any(|t| t.extinction() != Spectrum::ZERO)
    }

    /// The density of the molecules that refract light, at altitude `h` metres: the first
    /// term with Rayleigh's phase function that scatters (none: 0).
    pub fn molecular_density(&self, h: f64) -> f64 {
        self.terms
            .iter()
            .find(|t| t.phase == Phase::Rayleigh && t.scattering != Spectrum::ZERO)
            .map_or(0.0, |t| t.density.at(h))
    }

    /// Checks the rules: 1 to [`MAX_TERMS`] terms, every coefficient finite and ≥ 0, phase
    /// functions valid, density terms finite, albedo in [0, 1].
    pub fn validate(&self) -> Result<(), CoreError> {
        if self.terms.is_empty() || self.terms.len() > MAX_TERMS {
            return Err(CoreError::Invalid {
                field: "atmosphere.terms",
                value: format!("{} terms", self.terms.len()),
                rule: "needs 1 to 8 terms",
            });
        }
        for (i, term) in self.terms.iter().enumerate() {
            let field = |name: &str| format!("atmosphere.terms[{i}].{name}");
            for (name, s) in [("scattering", term.scattering), ("absorption", term.absorption)] {
                if !(s.is_finite() && s.min_element() >= 0.0) {
                    return Err(CoreError::InvalidItem {
                        field: field(name),
                        value: format!("{:?}", s.to_array()),
                        rule: "every coefficient must be finite and >= 0 (m⁻¹)",
                    });
                }
            }
            term.phase.validate(&field("phase"))?;
            term.density.validate(&field("profile"))?;
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
        Ok(())
    }
}

/// Checks a table of `(x, value)` pairs: at least two, every `x` finite and increasing strictly,
/// every value finite and >= 0; `field` names it in the error.
pub(crate) fn check_table(field: &str, pairs: &[(f64, f64)]) -> Result<(), CoreError> {
    let rule = if pairs.len() < 2 {
        Some("needs at least two pairs")
    } else if !pairs.iter().all(|(x, v)| x.is_finite() && v.is_finite() && *v >= 0.0) {
        Some("every abscissa must be finite and every value finite and >= 0")
    } else if !pairs.windows(2).all(|w| w[1].0 > w[0].0) {
        Some("the abscissae (altitudes, angles) must increase strictly")
    } else {
        None
    };
    match rule {
        Some(rule) => Err(CoreError::InvalidItem {
            field: field.to_owned(),
            value: format!("{pairs:?}"),
            rule,
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests;
