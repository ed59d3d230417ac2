//! Night vision: how the eye sees below photopic levels — rods take over from cones, colour
//! fades and the picture shifts towards blue — as the `f64` reference for the output pass.
//!
//! Krawczyk, Myszkowski & Seidel, "Perceptual Effects in Real-time Tone Mapping" (SCCG 2005),
//! §3: the rods' (scotopic) luminance `V = Y · (1.33 · (1 + (Y + Z) / X) − 1.68)` (Larson,
//! Rushmeier & Piatko 1997, after Jensen et al. 2000's night-sky model), mixed with the cones'
//! colour by `σ(Y) = σ_b / (σ_b + Y)` (`σ_b` [`MESOPIC_HALF_LUMINANCE`], where rods and cones
//! weigh equally), the rods' share seen in the bluish grey [`SCOTOPIC_TINT`]:
//! `rgb' = (1 − σ) · rgb + σ · V · tint`. `Y` is the pixel's luminance in cd/m², before exposure,
//! so a frame's radiance must be photometric (the physical sky's is).

use crate::color::LinearRgb;

/// `σ_b`, cd/m²: the luminance where the rods' and the cones' shares are equal.
pub const MESOPIC_HALF_LUMINANCE: f64 = 0.4;
/// The colour in which the rods' signal is seen (linear RGB, Krawczyk et al. 2005).
pub const SCOTOPIC_TINT: [f64; 3] = [1.05, 0.97, 1.27];

/// Linear sRGB → CIE XYZ (D65), the sRGB specification's matrix (IEC 61966-2-1).
const XYZ_FROM_SRGB: [[f64; 3]; 3] = [
    [0.4124, 0.3576, 0.1805],
    [0.2126, 0.7152, 0.0722],
    [0.0193, 0.1192, 0.9505],
];

/// The rods' luminance of a linear RGB radiance in cd/m² (never negative).
pub fn scotopic_luminance(c: LinearRgb) -> f64 {
    let [x, y, z] = XYZ_FROM_SRGB.map(|row| row[0] * c.r + row[1] * c.g + row[2] * c.b);
    if x <= 0.0 {
        return 0.0;
    }
    (y * (1.33 * (1.0 + (y + z) / x) - 1.68)).max(0.0)
}

/// The rods' share of what the eye sees at luminance `y` cd/m²: 1 in the dark, 0 in daylight.
pub fn rod_share(y: f64) -> f64 {
    MESOPIC_HALF_LUMINANCE / (MESOPIC_HALF_LUMINANCE + y.max(0.0))
}

/// What an eye sees of the radiance `c` (linear RGB, cd/m²): the cones' colour and the rods'
/// bluish grey, mixed by the rods' share at the pixel's luminance.
pub fn night_vision(c: LinearRgb) -> LinearRgb {
    let y = crate::auto_exposure::luminance(c);
    let sigma = rod_share(y);
    let v = scotopic_luminance(c);
    let [r, g, b] = SCOTOPIC_TINT;
    LinearRgb::new(
        (1.0 - sigma) * c.r + sigma * v * r,
        (1.0 - sigma) * c.g + sigma * v * g,
        (1.0 - sigma) * c.b + sigma * v * b,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn daylight_is_unchanged_and_moonlight_turns_blue_grey() {
        // At noon luminances (thousands of cd/m²) the rods' share is below 1e-3.
        let noon = LinearRgb::new(3000.0, 5000.0, 8000.0);
        assert!(night_vision(noon).max_abs_diff(noon) / 8000.0 < 1e-3);
        // A moonlit red (0.01 cd/m²): nearly all rods, so blue exceeds red.
        let red = LinearRgb::new(0.03, 0.005, 0.004);
        let seen = night_vision(red);
        assert!(seen.b > seen.r, "{seen:?}");
        assert!((rod_share(MESOPIC_HALF_LUMINANCE) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn the_scotopic_luminance_favours_blue() {
        // Equal luminance: the rods see blue light brighter than red (their peak is at 507 nm).
        let y = 0.1;
        let blue = LinearRgb::new(0.0, 0.0, y / 0.0722);
        let red = LinearRgb::new(y / 0.2126, 0.0, 0.0);
        assert!(scotopic_luminance(blue) > 2.0 * scotopic_luminance(red));
    }
}
