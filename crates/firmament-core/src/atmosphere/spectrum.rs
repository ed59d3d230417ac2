//! Spectral quantities at the model's three wavelengths, and how they become luminance and
//! linear sRGB.
//!
//! # From three samples to colour (Bruneton 2017's `ConvertSpectrumToLinearSrgb`)
//! The spectrum between the samples is interpolated linearly and held constant beyond them; it is
//! integrated against the CIE 1931 2° colour-matching functions from 360 to 830 nm, giving CIE
//! XYZ in W·m⁻²·sr⁻¹; `Y × 683 lm/W` is the luminance in cd/m², and the XYZ → linear sRGB matrix of
//! IEC 61966-2-1 gives linear sRGB *scaled so that its Y is the luminance in cd/m²*. The
//! colour-matching functions are Wyman, Sloan & Shirley's multi-lobe fit ("Simple Analytic
//! Approximations to the CIE XYZ Color Matching Functions", JCGT 2(2), 2013), whose integrals are
//! within 0.1 % of the tabulated ones (tested below). Because the interpolation is linear in the
//! samples, the whole conversion is one 3×3 matrix.

use glam::{DMat3, DVec3};

use crate::color::LinearRgb;
use crate::error::CoreError;

/// One value per model wavelength (see [`Wavelengths`]); the unit is the field's.
pub type Spectrum = DVec3;

/// Maximum luminous efficacy of radiation, lm/W (the definition of the candela).
pub const MAX_LUMINOUS_EFFICACY: f64 = 683.0;

/// The model's three wavelengths, nanometres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wavelengths(pub [f64; 3]);

impl Default for Wavelengths {
    /// 680, 550 and 440 nm: red, green and blue, as Bruneton's and Hillaire's models use.
    fn default() -> Self {
        Self([680.0, 550.0, 440.0])
    }
}

impl Wavelengths {
    /// Checks the rules: each finite, within 360–830 nm, all different.
    pub fn validate(&self) -> Result<(), CoreError> {
        let [a, b, c] = self.0;
        let ok = self.0.iter().all(|w| w.is_finite() && (360.0..=830.0).contains(w)) && a != b && b != c && a != c;
        if ok {
            Ok(())
        } else {
            Err(CoreError::Invalid {
                field: "atmosphere.wavelengths",
                value: format!("{:?}", self.0),
                rule: "needs three different wavelengths within 360..830 nm",
            })
        }
    }
}

/// The conversion from spectral radiance at the model's wavelengths to colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralConversion {
    /// Spectral radiance samples (W·m⁻²·sr⁻¹·nm⁻¹) → CIE XYZ radiance (W·m⁻²·sr⁻¹).
    pub to_xyz: DMat3,
}

/// CIE XYZ → linear sRGB (IEC 61966-2-1).
const XYZ_TO_SRGB: DMat3 = DMat3::from_cols_array(&[
    3.2406, -0.9689, 0.0557, //
    -1.5372, 1.8758, -0.2040, //
    -0.4986, 0.0415, 1.0570,
]);

impl SpectralConversion {
    /// The conversion for these wavelengths.
    pub fn new(wavelengths: Wavelengths) -> Self {
        let mut order = [0usize, 1, 2];
        order.sort_by(|&i, &j| wavelengths.0[i].total_cmp(&wavelengths.0[j]));
        let sorted = order.map(|i| wavelengths.0[i]);
        // Weight of each (sorted) sample in the interpolated spectrum at λ.
        let weights = |lambda: f64| -> [f64; 3] {
            if lambda <= sorted[0] {
                return [1.0, 0.0, 0.0];
            }
            if lambda >= sorted[2] {
                return [0.0, 0.0, 1.0];
            }
            let k = if lambda < sorted[1] { 0 } else { 1 };
            let u = (lambda - sorted[k]) / (sorted[k + 1] - sorted[k]);
            let mut w = [0.0; 3];
            w[k] = 1.0 - u;
            w[k + 1] = u;
            w
        };
        let mut columns = [DVec3::ZERO; 3];
        // 0.1 nm midpoint rule: the kinks at the samples cost < 1e-6 relative.
        let steps = 4700;
        let dl = (830.0 - 360.0) / steps as f64;
        for s in 0..steps {
            let lambda = 360.0 + (s as f64 + 0.5) * dl;
            let cmf = cie_1931(lambda) * dl;
            for (k, w) in weights(lambda).into_iter().enumerate() {
                columns[order[k]] += cmf * w;
            }
        }
        Self {
            to_xyz: DMat3::from_cols(columns[0], columns[1], columns[2]),
        }
    }

    /// Luminance, cd/m², of a spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹).
    pub fn luminance(&self, radiance: Spectrum) -> f64 {
        MAX_LUMINOUS_EFFICACY * (self.to_xyz * radiance).y
    }

    /// Linear sRGB whose Y is the luminance in cd/m².
    pub fn linear_srgb(&self, radiance: Spectrum) -> LinearRgb {
        let rgb = XYZ_TO_SRGB * (self.to_xyz * radiance) * MAX_LUMINOUS_EFFICACY;
        LinearRgb::new(rgb.x, rgb.y, rgb.z)
    }

    /// The 3×3 matrix from spectral radiance to luminance-scaled linear sRGB.
    pub fn to_linear_srgb_matrix(&self) -> DMat3 {
        XYZ_TO_SRGB * self.to_xyz * MAX_LUMINOUS_EFFICACY
    }
}

/// The CIE 1931 2° colour-matching functions (x̄, ȳ, z̄) at `lambda` nm, by Wyman et al.'s
/// multi-lobe fit.
pub fn cie_1931(lambda: f64) -> DVec3 {
    let g = |mu: f64, below: f64, above: f64| {
        let sigma = if lambda < mu { below } else { above };
        (-0.5 * ((lambda - mu) / sigma).powi(2)).exp()
    };
    DVec3::new(
        1.056 * g(599.8, 37.9, 31.0) + 0.362 * g(442.0, 16.0, 26.7) - 0.065 * g(501.1, 20.4, 26.2),
        0.821 * g(568.8, 46.9, 40.5) + 0.286 * g(530.9, 16.3, 31.1),
        1.217 * g(437.0, 11.8, 36.0) + 0.681 * g(459.0, 26.0, 13.8),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_matching_integrals_match_the_cie_tables() {
        // CIE 1931 2° tables summed at 1 nm over 360..830 nm: 106.865, 106.857, 106.892.
        let sum: DVec3 = (360..=830).map(|l| cie_1931(l as f64)).sum();
        for (got, table) in sum.to_array().into_iter().zip([106.865, 106.857, 106.892]) {
            assert!((got / table - 1.0).abs() < 1e-3, "{got} vs {table}");
        }
        assert!((cie_1931(555.0).y - 1.0).abs() < 0.01);
    }

    #[test]
    fn a_flat_spectrum_is_white_with_the_right_luminance() {
        let conversion = SpectralConversion::new(Wavelengths::default());
        let flat = DVec3::ONE;
        // A flat 1 W·m⁻²·sr⁻¹·nm⁻¹ spectrum: Y = ∫ȳ ≈ 106.86, luminance 683 × that.
        let luminance = conversion.luminance(flat);
        assert!((luminance / (683.0 * 106.857) - 1.0).abs() < 2e-3, "{luminance}");
        // Equal-energy white (X = Y = Z) is pink in sRGB: the matrix's row sums
        // (1.2048, 0.9484, 0.9087) times Y. Three samples reproduce it within 0.6 %.
        let rgb = conversion.linear_srgb(flat).scale(1.0 / luminance);
        for (got, want) in rgb.to_array().into_iter().zip([1.2048, 0.9484, 0.9087]) {
            assert!((got / want - 1.0).abs() < 6e-3, "{rgb:?}");
        }
        // Order of the wavelengths does not matter.
        let shuffled = SpectralConversion::new(Wavelengths([440.0, 680.0, 550.0]));
        let a = conversion.linear_srgb(DVec3::new(1.0, 2.0, 3.0));
        let b = shuffled.linear_srgb(DVec3::new(3.0, 1.0, 2.0));
        assert!((a.r - b.r).abs() < 1e-9 && (a.b - b.b).abs() < 1e-9);
    }

    #[test]
    fn bad_wavelengths_are_refused() {
        assert!(Wavelengths([680.0, 680.0, 440.0]).validate().is_err());
        assert!(Wavelengths([f64::NAN, 550.0, 440.0]).validate().is_err());
        assert!(Wavelengths([1000.0, 550.0, 440.0]).validate().is_err());
        assert!(Wavelengths::default().validate().is_ok());
    }
}
