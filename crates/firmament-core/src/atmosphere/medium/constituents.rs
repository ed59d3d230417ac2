//! The classic three-constituent air — molecules, aerosols and an absorbing gas — as the
//! presets give it and `[atmosphere]`'s shorthand keys set it. [`Constituents::terms`] turns it
//! into the [`MediumTerm`]s every path reads.

use crate::atmosphere::medium::{Density, DensityProfile, MediumTerm, Phase};
use crate::atmosphere::spectrum::Spectrum;

/// Molecules: pure scatterers with Rayleigh's phase function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rayleigh {
    /// Scattering coefficient at density 1, m⁻¹.
    pub scattering: Spectrum,
    /// Density profile.
    pub density: DensityProfile,
}

/// Aerosols: scatter and absorb.
#[derive(Debug, Clone, PartialEq)]
pub struct Mie {
    /// Scattering coefficient at density 1, m⁻¹.
    pub scattering: Spectrum,
    /// Extinction coefficient (scattering + absorption) at density 1, m⁻¹.
    pub extinction: Spectrum,
    /// Density profile.
    pub density: DensityProfile,
    /// Phase function: Cornette–Shanks or Henyey–Greenstein.
    pub phase: Phase,
}

/// An absorbing gas (ozone on Earth): absorbs, does not scatter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Absorber {
    /// Absorption coefficient at density 1, m⁻¹.
    pub absorption: Spectrum,
    /// Density profile.
    pub density: DensityProfile,
}

/// Molecules, aerosols and an absorbing gas.
#[derive(Debug, Clone, PartialEq)]
pub struct Constituents {
    /// Molecular scattering.
    pub rayleigh: Rayleigh,
    /// Aerosols.
    pub mie: Mie,
    /// Absorbing gas.
    pub absorber: Absorber,
}

impl Constituents {
    /// The three terms, in this order: molecules, aerosols (absorbing extinction − scattering),
    /// the gas.
    pub fn terms(&self) -> Vec<MediumTerm> {
        vec![
            MediumTerm {
                scattering: self.rayleigh.scattering,
                absorption: Spectrum::ZERO,
                density: Density::Profile(self.rayleigh.density),
                phase: Phase::Rayleigh,
            },
            MediumTerm {
                scattering: self.mie.scattering,
                absorption: self.mie.extinction - self.mie.scattering,
                density: Density::Profile(self.mie.density),
                phase: self.mie.phase.clone(),
            },
            MediumTerm {
                scattering: Spectrum::ZERO,
                absorption: self.absorber.absorption,
                density: Density::Profile(self.absorber.density),
                phase: Phase::Rayleigh,
            },
        ]
    }

    /// The constituents behind `terms`, where they are exactly what [`Self::terms`] makes.
    pub fn from_terms(terms: &[MediumTerm]) -> Option<Self> {
        let [rayleigh, mie, absorber] = terms else { return None };
        let profile = |term: &MediumTerm| match term.density {
            Density::Profile(p) => Some(p),
            Density::Table(_) => None,
        };
        let shorthand = rayleigh.phase == Phase::Rayleigh
            && rayleigh.absorption == Spectrum::ZERO
            && matches!(mie.phase, Phase::CornetteShanks { .. } | Phase::HenyeyGreenstein { .. })
            && absorber.scattering == Spectrum::ZERO;
        shorthand.then_some(())?;
        Some(Self {
            rayleigh: Rayleigh {
                scattering: rayleigh.scattering,
                density: profile(rayleigh)?,
            },
            mie: Mie {
                scattering: mie.scattering,
                extinction: mie.scattering + mie.absorption,
                density: profile(mie)?,
                phase: mie.phase.clone(),
            },
            absorber: Absorber {
                absorption: absorber.absorption,
                density: profile(absorber)?,
            },
        })
    }
}
