//! How a whole body's light falls off with its phase angle `α` (at the body, between the sun and
//! the viewer): the closed form of a Lommel–Seeliger ball and the Moon's measured curve, whose
//! ratio makes the Moon's reflectance law ([`Reflectance::Lunar`](super::Reflectance::Lunar)).
//!
//! A Lommel–Seeliger ball's light, over its light at full phase, is
//! `Φ_LS(α) = 1 − sin(α/2)·tan(α/2)·ln(cot(α/4))` ([`lommel_seeliger_phase`]): 0.38 at a quarter. The
//! real Moon's falls much faster — its rough regolith shadows itself — as the fit of Krisciunas &
//! Schaefer (1991, *PASP* 103, 1033, eq. 9) to Allen's V magnitudes gives: `0.026|φ| + 4·10⁻⁹φ⁴`
//! magnitudes fainter than full, `φ` in degrees (0.09 of full at a quarter). Multiplying the
//! Lommel–Seeliger law at every point by `f(α) = Φ_Moon(α)/Φ_LS(α)` — the same `α` across the disc
//! for a far viewer — keeps its even brightness across the disc and gives the whole Moon the
//! measured curve (McEwen 1991, *Icarus* 92, 298, does the same with a fitted lunar phase
//! function). Past [`LUNAR_PHASE_MAX_RAD`], a thin crescent, `f` is held.

/// The phase angle past which the Moon's phase factor is held, radians (170°: the fit's data end
/// near there and both curves fall to nothing).
pub const LUNAR_PHASE_MAX_RAD: f64 = 170.0 * std::f64::consts::PI / 180.0;

/// How many magnitudes fainter than full the Moon is at phase angle `alpha` radians, at the same
/// distances (Krisciunas & Schaefer 1991, eq. 9; the module docs).
pub fn lunar_phase_magnitude(alpha: f64) -> f64 {
    let phi = alpha.to_degrees().abs();
    0.026 * phi + 4e-9 * phi.powi(4)
}

/// The disc-integrated light of a Lommel–Seeliger sphere at phase angle `g` (radians, in [0, π])
/// relative to full phase: `Φ(g) = 1 − sin(g/2) tan(g/2) ln cot(g/4)` (Fairbairn 2005, eq. 12).
/// 1 at g = 0, 0 at g = π.
pub fn lommel_seeliger_phase(g: f64) -> f64 {
    let g = g.abs();
    if !g.is_finite() || g >= std::f64::consts::PI {
        return 0.0;
    }
    if g < 1e-9 {
        return 1.0;
    }
    let half = 0.5 * g;
    (1.0 - half.sin() * half.tan() * (1.0 / (0.25 * g).tan()).ln()).max(0.0)
}

/// The Moon's factor on the Lommel–Seeliger law at phase angle `alpha` radians,
/// `Φ_Moon(α)/Φ_LS(α)` (the module docs): 1 at full, 0.24 at a quarter.
pub fn lunar_phase_factor(alpha: f64) -> f64 {
    let alpha = alpha.abs().min(LUNAR_PHASE_MAX_RAD);
    10f64.powf(-0.4 * lunar_phase_magnitude(alpha)) / lommel_seeliger_phase(alpha)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_moons_factor_is_one_at_full_and_a_quarter_of_the_law_at_quarter() {
        assert!((lunar_phase_factor(0.0) - 1.0).abs() < 1e-12);
        let quarter = std::f64::consts::FRAC_PI_2;
        // Φ_LS(90°) = 1 − (1/√2)·ln(1 + √2); the Moon is 2.6 magnitudes down there.
        let ls = 1.0 - std::f64::consts::FRAC_1_SQRT_2 * (1.0 + 2f64.sqrt()).ln();
        assert!((lommel_seeliger_phase(quarter) - ls).abs() < 1e-12);
        let moon = 10f64.powf(-0.4 * (0.026 * 90.0 + 4e-9 * 90f64.powi(4)));
        assert!((lunar_phase_factor(quarter) - moon / ls).abs() < 1e-12);
        // Held past the limit.
        assert_eq!(lunar_phase_factor(3.1), lunar_phase_factor(LUNAR_PHASE_MAX_RAD));
    }
}
