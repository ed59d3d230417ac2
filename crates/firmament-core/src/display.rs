//! From scene radiance to display values: exposure and tone curves, as `f64` references for the
//! GPU tonemap pass.

use serde::{Deserialize, Serialize};

use crate::color::LinearRgb;

/// The tone curve applied after exposure, before sRGB encoding.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ToneCurve {
    /// Clamp to [0, 1]: the classic fixed-function OpenGL look, exact for LDR colours.
    #[default]
    None,
    /// Stephen Hill's fit of the ACES RRT + sRGB ODT (BakingLab, 2016).
    AcesFitted,
    /// Khronos PBR Neutral (Khronos 3D Commerce, 2024): keeps base colours, compresses highlights.
    PbrNeutral,
}

impl ToneCurve {
    /// Every curve, in a stable order (for listings and tests).
    pub const ALL: [Self; 3] = [Self::None, Self::AcesFitted, Self::PbrNeutral];

    /// The scene-file name of the curve.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::AcesFitted => "aces_fitted",
            Self::PbrNeutral => "pbr_neutral",
        }
    }

    /// Applies the curve to an exposed linear colour; the result is linear, in [0, 1].
    pub fn apply(self, c: LinearRgb) -> LinearRgb {
        let out = match self {
            Self::None => c,
            Self::AcesFitted => aces_fitted(c),
            Self::PbrNeutral => pbr_neutral(c),
        };
        LinearRgb::new(saturate(out.r), saturate(out.g), saturate(out.b))
    }
}

/// Exposure: the factor that scales scene radiance before the tone curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exposure {
    /// Linear multiplier, > 0.
    pub multiplier: f64,
}

impl Exposure {
    /// A plain multiplier (1 = unchanged).
    pub fn multiplier(multiplier: f64) -> Self {
        Self { multiplier }
    }

    /// From an exposure value at ISO 100: `1 / (1.2 · 2^EV100)`, the saturation-based
    /// photometric exposure of Lagarde & de Rousiers, "Moving Frostbite to PBR" (2014), §5.1.
    pub fn from_ev100(ev100: f64) -> Self {
        Self {
            multiplier: 1.0 / (1.2 * 2f64.powf(ev100)),
        }
    }
}

impl Default for Exposure {
    fn default() -> Self {
        Self::multiplier(1.0)
    }
}

/// How display values are stored in an 8-bit image.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Encoding {
    /// The sRGB transfer function (what a display expects of linear light).
    #[default]
    Srgb,
    /// Stored as they are, `round(255·v)`: what an 8-bit OpenGL framebuffer without
    /// `GL_FRAMEBUFFER_SRGB` holds, so classic scenes give the GL program's pixels.
    None,
}

/// How a frame's HDR radiance becomes a display image.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DisplaySettings {
    /// Scales radiance before the tone curve.
    pub exposure: Exposure,
    /// The tone curve.
    pub tone_curve: ToneCurve,
    /// How 8-bit outputs store the result.
    pub encoding: Encoding,
}

impl DisplaySettings {
    /// The display colour (linear, [0, 1], before sRGB encoding) for a scene radiance.
    pub fn display_linear(&self, radiance: LinearRgb) -> LinearRgb {
        self.tone_curve.apply(radiance.scale(self.exposure.multiplier))
    }
}

fn saturate(x: f64) -> f64 {
    // NaN becomes 0 so a bad pixel never turns into a bright one.
    if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) }
}

fn mul3(m: [[f64; 3]; 3], c: LinearRgb) -> LinearRgb {
    let v = c.to_array();
    let row = |r: [f64; 3]| r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    LinearRgb::new(row(m[0]), row(m[1]), row(m[2]))
}

/// sRGB → ACES AP1 input matrix (with the RRT's saturation), rows as published by Hill.
pub const ACES_INPUT: [[f64; 3]; 3] = [
    [0.59719, 0.35458, 0.04823],
    [0.07600, 0.90834, 0.01566],
    [0.02840, 0.13383, 0.83777],
];
/// ODT → sRGB output matrix, rows as published by Hill.
pub const ACES_OUTPUT: [[f64; 3]; 3] = [
    [1.60475, -0.53108, -0.07367],
    [-0.10208, 1.10813, -0.00605],
    [-0.00327, -0.07276, 1.07602],
];

fn aces_fitted(c: LinearRgb) -> LinearRgb {
    let rrt_odt = |v: f64| {
        let a = v * (v + 0.024_578_6) - 0.000_090_537;
        let b = v * (0.983_729 * v + 0.432_951) + 0.238_081;
        a / b
    };
    let v = mul3(ACES_INPUT, c);
    mul3(ACES_OUTPUT, LinearRgb::new(rrt_odt(v.r), rrt_odt(v.g), rrt_odt(v.b)))
}

fn pbr_neutral(c: LinearRgb) -> LinearRgb {
    // Constants from the Khronos PBR Neutral specification.
    const START_COMPRESSION: f64 = 0.8 - 0.04;
    const DESATURATION: f64 = 0.15;
    let x = c.r.min(c.g).min(c.b);
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    let c = LinearRgb::new(c.r - offset, c.g - offset, c.b - offset);
    let peak = c.r.max(c.g).max(c.b);
    if peak < START_COMPRESSION {
        return c;
    }
    let d = 1.0 - START_COMPRESSION;
    let new_peak = 1.0 - d * d / (peak + d - START_COMPRESSION);
    let c = c.scale(new_peak / peak);
    let g = 1.0 - 1.0 / (DESATURATION * (peak - new_peak) + 1.0);
    c.lerp(LinearRgb::new(new_peak, new_peak, new_peak), g)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn none_is_clamp() {
        let c = ToneCurve::None.apply(LinearRgb::new(-1.0, 0.25, 7.0));
        assert_eq!(c, LinearRgb::new(0.0, 0.25, 1.0));
    }

    #[test]
    fn pbr_neutral_keeps_low_values_and_compresses_peaks() {
        // Below the compression start, with the min channel ≥ 0.08, only the 0.04 offset applies.
        let c = ToneCurve::PbrNeutral.apply(LinearRgb::new(0.5, 0.3, 0.1));
        assert!(c.max_abs_diff(LinearRgb::new(0.46, 0.26, 0.06)) < 1e-12);
        let bright = ToneCurve::PbrNeutral.apply(LinearRgb::new(100.0, 100.0, 100.0));
        assert!(bright.r > 0.99 && bright.r <= 1.0);
    }

    #[test]
    fn aces_fitted_reference_points() {
        // Black stays (almost) black, mid-grey lands near 0.18-ish display-linear, white saturates.
        let black = ToneCurve::AcesFitted.apply(LinearRgb::BLACK);
        assert!(black.r < 1e-3);
        let grey = ToneCurve::AcesFitted.apply(LinearRgb::new(0.18, 0.18, 0.18));
        assert!((0.1..0.3).contains(&grey.g), "{grey:?}");
        let hot = ToneCurve::AcesFitted.apply(LinearRgb::new(1e4, 1e4, 1e4));
        assert!(hot.r > 0.99);
    }

    #[test]
    fn ev100_matches_lagarde() {
        // EV100 = 0 → 1/1.2; each stop halves the exposure.
        assert!((Exposure::from_ev100(0.0).multiplier - 1.0 / 1.2).abs() < 1e-15);
        let ratio = Exposure::from_ev100(14.0).multiplier / Exposure::from_ev100(15.0).multiplier;
        assert!((ratio - 2.0).abs() < 1e-12);
    }
}
