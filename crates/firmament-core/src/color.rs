//! Linear RGB colours and the sRGB transfer function.

use serde::{Deserialize, Serialize};

/// A colour in linear RGB with Rec. 709 / sRGB primaries. Values are relative radiance and may
/// exceed 1 (HDR); they are not gamma-encoded.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct LinearRgb {
    /// Red, linear.
    pub r: f64,
    /// Green, linear.
    pub g: f64,
    /// Blue, linear.
    pub b: f64,
}

impl LinearRgb {
    /// Black.
    pub const BLACK: Self = Self::new(0.0, 0.0, 0.0);
    /// White (1, 1, 1).
    pub const WHITE: Self = Self::new(1.0, 1.0, 1.0);

    /// A colour from linear components.
    pub const fn new(r: f64, g: f64, b: f64) -> Self {
        Self { r, g, b }
    }

    /// A colour from sRGB-encoded components in [0, 1] (as in `#rrggbb`), decoded to linear.
    pub fn from_srgb(r: f64, g: f64, b: f64) -> Self {
        Self::new(srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b))
    }

    /// A colour from 8-bit sRGB components, decoded to linear.
    pub fn from_srgb8(r: u8, g: u8, b: u8) -> Self {
        Self::from_srgb(f64::from(r) / 255.0, f64::from(g) / 255.0, f64::from(b) / 255.0)
    }

    /// Linear interpolation: `self` at `t = 0`, `other` at `t = 1`.
    pub fn lerp(self, other: Self, t: f64) -> Self {
        Self::new(
            self.r + (other.r - self.r) * t,
            self.g + (other.g - self.g) * t,
            self.b + (other.b - self.b) * t,
        )
    }

    /// Every component multiplied by `k`.
    pub fn scale(self, k: f64) -> Self {
        Self::new(self.r * k, self.g * k, self.b * k)
    }

    /// The components as an array `[r, g, b]`.
    pub fn to_array(self) -> [f64; 3] {
        [self.r, self.g, self.b]
    }

    /// The largest absolute difference between two colours' components.
    pub fn max_abs_diff(self, other: Self) -> f64 {
        (self.r - other.r)
            .abs()
            .max((self.g - other.g).abs())
            .max((self.b - other.b).abs())
    }

    /// True when every component is finite and not negative.
    pub fn is_finite_non_negative(self) -> bool {
        self.to_array().iter().all(|c| c.is_finite() && *c >= 0.0)
    }
}

impl std::ops::Add for LinearRgb {
    type Output = Self;

    /// Component-wise sum.
    fn add(self, other: Self) -> Self {
        Self::new(self.r + other.r, self.g + other.g, self.b + other.b)
    }
}

/// The sRGB electro-optical transfer function (IEC 61966-2-1): encoded value → linear.
pub fn srgb_to_linear(encoded: f64) -> f64 {
    if encoded <= 0.04045 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

/// The inverse sRGB transfer function (IEC 61966-2-1): linear → encoded value.
pub fn linear_to_srgb(linear: f64) -> f64 {
    if linear <= 0.003_130_8 {
        linear * 12.92
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trip_and_published_points() {
        // IEC 61966-2-1: the breakpoints and mid-grey.
        assert!((srgb_to_linear(0.5) - 0.214_041_140_5).abs() < 1e-9);
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-12);
        for i in 0..=255 {
            let e = f64::from(i) / 255.0;
            assert!((linear_to_srgb(srgb_to_linear(e)) - e).abs() < 1e-12);
        }
    }
}
