//! Physically based planetary atmospheres: the model (planet, medium, suns) and the f64
//! reference integrator every GPU atmosphere pass is tested against.
//!
//! # Names and units (shared with the WGSL atmosphere shaders)
//! - `h`: altitude above the ellipsoid surface, metres (see [`planet`] for how it is computed).
//! - `r`: distance from the planet centre, metres; `mu`: cosine of the view zenith angle;
//!   `mu_s`: cosine of the sun zenith angle; `nu`: cosine of the angle between view and sun
//!   directions (1 = looking at the sun; it is also the cosine of the scattering angle between
//!   the light's and the scattered light's propagation directions).
//! - Coefficients σ: m⁻¹. Phase functions: sr⁻¹. Irradiance: W·m⁻²·nm⁻¹. Radiance:
//!   W·m⁻²·sr⁻¹·nm⁻¹, one value per model wavelength ([`spectrum::Spectrum`]).
//! - Geometry is computed in the *planet frame* (see [`planet::Planet`]) in f64.

pub mod body;
pub mod clouds;
mod depth_table;
pub mod eclipse;
pub mod empirical;
pub mod medium;
pub mod planet;
pub mod planet_shadow;
pub mod presets;
pub mod reference;
pub mod rings;
pub mod spectrum;
pub mod star;
pub mod surface;

pub use eclipse::Eclipser;
pub use medium::{DensityLayer, DensityProfile, Medium, MediumTerm, Phase};
pub use planet::Planet;
pub use spectrum::{SpectralConversion, Spectrum, Wavelengths};
pub use star::Sun;

use crate::error::CoreError;

/// A planet with its atmosphere: everything but the lights.
#[derive(Debug, Clone, PartialEq)]
pub struct Atmosphere {
    /// The planet's shape and pose, and the atmosphere's height.
    pub planet: Planet,
    /// The medium and the ground albedo.
    pub medium: Medium,
    /// The wavelengths the spectra are sampled at.
    pub wavelengths: Wavelengths,
}

impl Atmosphere {
    /// Checks every rule of the planet, the medium and the wavelengths.
    pub fn validate(&self) -> Result<(), CoreError> {
        self.planet.validate()?;
        self.medium.validate()?;
        self.wavelengths.validate()
    }

    /// The conversion from this model's spectral radiance to colour.
    pub fn spectral_conversion(&self) -> SpectralConversion {
        SpectralConversion::new(self.wavelengths)
    }
}
