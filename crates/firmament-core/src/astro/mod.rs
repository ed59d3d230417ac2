//! Astronomy for a sky at a real date, time and place: time scales, the sun's position (NREL's
//! SPA), the moon's position and phase, sidereal time and the stars.
//!
//! # Conventions (for this module)
//! - **Instants** are [`Instant`]s: a Julian Date in Universal Time (UT1 ≈ UTC, within 0.9 s) and
//!   ΔT = TT − UT in seconds, so that both Julian Ephemeris Date (dynamical time, for the
//!   ephemerides) and Julian Date (for the Earth's rotation) are at hand.
//! - **Angles** in the public API are degrees where the name says `_deg`, radians elsewhere.
//! - **Topocentric horizon coordinates**: zenith angle from the local vertical, azimuth measured
//!   eastward from north (0° north, 90° east), as NREL's SPA gives them. The local frame of the
//!   rest of firmament is East-North-Up; [`horizon_direction`] converts.

pub mod eclipse;
pub mod moon;
mod moon_terms;
pub mod sidereal;
pub mod spa;
mod spa_terms;
pub mod stars;
pub mod time;

pub use time::{CivilDateTime, Instant};

use glam::DVec3;

/// The unit East-North-Up direction of a point at `zenith_deg` from the zenith and `azimuth_deg`
/// eastward from north.
pub fn horizon_direction(zenith_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (sin_z, cos_z) = zenith_deg.to_radians().sin_cos();
    let (sin_a, cos_a) = azimuth_deg.to_radians().sin_cos();
    DVec3::new(sin_z * sin_a, sin_z * cos_a, cos_z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn horizon_direction_points_east_north_up() {
        assert!((horizon_direction(0.0, 123.0) - DVec3::Z).length() < 1e-12);
        assert!((horizon_direction(90.0, 0.0) - DVec3::Y).length() < 1e-12);
        assert!((horizon_direction(90.0, 90.0) - DVec3::X).length() < 1e-12);
    }
}
