//! From scene radiance to display values: exposure and tone curves, as `f64` references for the
//! GPU tonemap pass.

use serde::{Deserialize, Serialize};

use crate::auto_exposure::ExposureMode;
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
    /// AgX (Troy Sobotka, 2023; Blender's default view transform since 4.0): 16.5 stops around
    /// middle grey, highlights that desaturate towards white as film's do.
    Agx,
}

impl ToneCurve {
    /// Every curve, in a stable order (for listings and tests).
    pub const ALL: [Self; 4] = [Self::None, Self::AcesFitted, Self::PbrNeutral, Self::Agx];

    /// The scene-file name of the curve.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::AcesFitted => "aces_fitted",
            Self::PbrNeutral => "pbr_neutral",
            Self::Agx => "agx",
        }
    }

    /// Applies the curve to an exposed linear colour; the result is linear, in [0, 1].
    pub fn apply(self, c: LinearRgb) -> LinearRgb {
        let out = match self {
            Self::None => c,
            Self::AcesFitted => aces_fitted(c),
            Self::PbrNeutral => pbr_neutral(c),
            Self::Agx => agx(c),
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
    /// Scales radiance before the tone curve (in auto mode, the flares' reference only).
    pub exposure: Exposure,
    /// The scene's exposure or the meter's ([`crate::auto_exposure`]).
    pub exposure_mode: ExposureMode,
    /// Bloom's strength in [0, 1]: the share of each pixel's light spread over its
    /// neighbourhood (0 = off). Energy-conserving: the picture's total light is unchanged.
    pub bloom: f64,
    /// The eye's night vision below photopic levels ([`crate::night_vision`]).
    pub night_vision: bool,
    /// The tone curve.
    pub tone_curve: ToneCurve,
    /// How 8-bit outputs store the result.
    pub encoding: Encoding,
}

impl DisplaySettings {
    /// The display colour (linear, [0, 1], before sRGB encoding) for a scene radiance.
    /// Night vision, when on, acts on the radiance before exposure; bloom and auto-exposure
    /// are not modelled here.
    pub fn display_linear(&self, radiance: LinearRgb) -> LinearRgb {
        let seen = if self.night_vision {
            crate::night_vision::night_vision(radiance)
        } else {
            radiance
        };
        self.tone_curve.apply(seen.scale(self.exposure.multiplier))
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

/// AgX's inset matrix on linear sRGB (rows; Benjamin Wrensch, "Minimal AgX Implementation",
/// 2023, from Sobotka's AgX); the outset is its inverse.
pub const AGX_INSET: [[f64; 3]; 3] = [
    [0.842479062253094, 0.0784335999999992, 0.0792237451477643],
    [0.0423282422610123, 0.878468636469772, 0.0791661274605434],
    [0.0423756549057051, 0.0784336, 0.879142973793104],
];
/// The stops below and above middle grey (log2 0.18 = −2.47393) AgX's log encoding spans.
pub const AGX_MIN_EV: f64 = -12.47393;
/// See [`AGX_MIN_EV`].
pub const AGX_MAX_EV: f64 = 4.026069;

/// AgX's base sigmoid on the log-encoded value x ∈ [0, 1], in the closed form of the curve
/// Sobotka's LUT generator builds (a power sigmoid of slope 2 through (20/33, 1/2): 20/33 is
/// middle grey's encoded value; exponents 3 below and 13/4 above; derived by bWFuanVzYWth,
/// github.com/bWFuanVzYWth/AgX, 2023). Its display values assume a 2.2 power.
pub fn agx_sigmoid(x: f64) -> f64 {
    const PIVOT: f64 = 20.0 / 33.0;
    let (a, b) = if x <= PIVOT {
        (59.507875, 3.0)
    } else {
        (69.862_789_135_455_39, 13.0 / 4.0)
    };
    let d = x - PIVOT;
    0.5 + 2.0 * d * (1.0 + a * d.abs().powf(b)).powf(-1.0 / b)
}

/// AgX's outset: the inverse of [`AGX_INSET`] (computed once: the CPU applies curves per pixel).
static AGX_OUTSET: std::sync::LazyLock<glam::DMat3> =
    std::sync::LazyLock::new(|| glam::DMat3::from_cols_array_2d(&AGX_INSET).transpose().inverse());

fn agx(c: LinearRgb) -> LinearRgb {
    let v = mul3(AGX_INSET, c);
    let encode = |x: f64| {
        let stops = x.max(f64::MIN_POSITIVE).log2().clamp(AGX_MIN_EV, AGX_MAX_EV);
        agx_sigmoid((stops - AGX_MIN_EV) / (AGX_MAX_EV - AGX_MIN_EV))
    };
    let display = *AGX_OUTSET * glam::DVec3::new(encode(v.r), encode(v.g), encode(v.b));
    let linear = |d: f64| d.max(0.0).powf(2.2);
    LinearRgb::new(linear(display.x), linear(display.y), linear(display.z))
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
    fn agx_sigmoid_matches_wrenschs_published_polynomial() {
        // Wrensch's sixth-order fit of the same curve ("Minimal AgX Implementation", 2023).
        let fit = |x: f64| {
            let (x2, x4) = (x * x, x * x * x * x);
            15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232
        };
        for i in 0..=100 {
            let x = f64::from(i) / 100.0;
            assert!(
                (agx_sigmoid(x) - fit(x)).abs() < 0.01,
                "x = {x}: {} vs {}",
                agx_sigmoid(x),
                fit(x)
            );
        }
        assert!(agx_sigmoid(0.0).abs() < 1e-3 && (agx_sigmoid(1.0) - 1.0).abs() < 1e-3);
    }

    #[test]
    fn agx_puts_middle_grey_at_half_and_whitens_highlights() {
        // Middle grey (0.18, neutral: the inset keeps greys) encodes to 20/33 and displays at 1/2.
        let grey = ToneCurve::Agx.apply(LinearRgb::new(0.18, 0.18, 0.18));
        assert!((grey.g - 0.5f64.powf(2.2)).abs() < 2e-4, "{grey:?}");
        // A saturated red 10 stops up comes out near white.
        let hot = ToneCurve::Agx.apply(LinearRgb::new(184.0, 9.2, 9.2));
        assert!(hot.r > 0.95 && hot.g > 0.6, "{hot:?}");
        assert_eq!(ToneCurve::Agx.apply(LinearRgb::BLACK), LinearRgb::BLACK);
    }

    #[test]
    fn ev100_matches_lagarde() {
        // EV100 = 0 → 1/1.2; each stop halves the exposure.
        assert!((Exposure::from_ev100(0.0).multiplier - 1.0 / 1.2).abs() < 1e-15);
        let ratio = Exposure::from_ev100(14.0).multiplier / Exposure::from_ev100(15.0).multiplier;
        assert!((ratio - 2.0).abs() < 1e-12);
    }
}
