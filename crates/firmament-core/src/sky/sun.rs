//! Where the sun stands in a local sky for a time of day, and how its disc and glow look.

use glam::DVec3;

use crate::camera::direction_from_heading_elevation;
use crate::color::LinearRgb;
use crate::sky::time_of_day::{SECONDS_PER_DAY, TimeOfDay};

/// The sun's diurnal path for a fixed latitude and declination, in local apparent solar time.
///
/// This is the textbook horizon-coordinate transform (e.g. Meeus, *Astronomical Algorithms*,
/// 2nd ed., eq. 13.5–13.6) with the hour angle `H = 15° · (t − 12 h)`; it ignores the equation of
/// time and refraction. Real dates and places come from the ephemeris, not from here.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolarPath {
    /// Observer latitude, radians, north positive, in [-π/2, π/2].
    pub latitude: f64,
    /// Solar declination, radians, in [-23.44°, 23.44°] over a year (0 at the equinoxes).
    pub declination: f64,
}

impl SolarPath {
    /// The unit direction to the sun in the local East-North-Up frame at a solar time of day.
    pub fn direction_at(&self, time: TimeOfDay) -> DVec3 {
        let hour_angle = std::f64::consts::TAU * (time.seconds() / SECONDS_PER_DAY - 0.5);
        let (sin_lat, cos_lat) = self.latitude.sin_cos();
        let (sin_dec, cos_dec) = self.declination.sin_cos();
        let (sin_h, cos_h) = hour_angle.sin_cos();
        // Equatorial (hour angle, declination) → horizon frame, east-north-up components.
        let east = -cos_dec * sin_h;
        let north = cos_lat * sin_dec - sin_lat * cos_dec * cos_h;
        let up = sin_lat * sin_dec + cos_lat * cos_dec * cos_h;
        DVec3::new(east, north, up).normalize()
    }

    /// The time of day at which the sun on this path stands at `elevation` (radians), in the
    /// morning (`rising`) or the afternoon: the inverse of [`Self::direction_at`]'s elevation,
    /// `cos H = (sin e − sin φ sin δ) / (cos φ cos δ)`. An elevation above the path's noon gives
    /// noon, below its midnight gives midnight (the cosine is clamped). A gradient sky uses it to
    /// follow the real sun's elevation with keyframes authored on this path
    /// (`sky.gradient.by = "sun-elevation"`).
    pub fn time_at_elevation(&self, elevation: f64, rising: bool) -> TimeOfDay {
        let (sin_lat, cos_lat) = self.latitude.sin_cos();
        let (sin_dec, cos_dec) = self.declination.sin_cos();
        let denominator = cos_lat * cos_dec;
        let cos_h = if denominator.abs() < 1e-12 {
            // At a pole the elevation never changes over the day: call it noon.
            1.0
        } else {
            ((elevation.sin() - sin_lat * sin_dec) / denominator).clamp(-1.0, 1.0)
        };
        let hour_angle_days = cos_h.acos() / std::f64::consts::TAU;
        let days = if rising {
            0.5 - hour_angle_days
        } else {
            0.5 + hour_angle_days
        };
        TimeOfDay::from_seconds(days * SECONDS_PER_DAY).unwrap_or(TimeOfDay::MIDNIGHT)
    }
}

/// How the sun is drawn over a sky: a limb-softened disc and an exponential glow.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunDisc {
    /// Unit direction to the sun's centre, local frame.
    pub direction: DVec3,
    /// Angular radius of the disc, radians (the real sun: 0.2666°, i.e. 4.653e-3 rad).
    pub angular_radius: f64,
    /// Radiance of the disc, linear RGB.
    pub disc_radiance: LinearRgb,
    /// Radiance of the glow at the sun's centre, linear RGB.
    pub glow_radiance: LinearRgb,
    /// Angle over which the glow falls by a factor e, radians, > 0.
    pub glow_falloff: f64,
    /// Fraction of the radius over which the disc's edge fades, (0, 1].
    pub edge_softness: f64,
}

/// Half-width of the horizon line that hides the sun below it, radians (0.5°).
pub const SUN_HORIZON_FADE: f64 = 0.5 * std::f64::consts::PI / 180.0;

impl SunDisc {
    /// The radiance the sun adds to a view ray `view` (unit, local frame).
    pub fn radiance(&self, view: DVec3) -> LinearRgb {
        // atan2 of |a × b| and a · b keeps full precision at small angles, where acos does not.
        let angle = view.cross(self.direction).length().atan2(view.dot(self.direction));
        let inner = self.angular_radius * (1.0 - self.edge_softness);
        let coverage = 1.0 - smoothstep(inner, self.angular_radius, angle);
        let glow = (-angle / self.glow_falloff).exp();
        // The ground hides the sun: fade it out across the horizon line.
        let above = smoothstep(-SUN_HORIZON_FADE, SUN_HORIZON_FADE, view.z.clamp(-1.0, 1.0).asin());
        (self.disc_radiance.scale(coverage) + self.glow_radiance.scale(glow)).scale(above)
    }

    /// A sun standing at a heading and elevation (radians); for tests and fixed-sun scenes.
    pub fn direction_from(heading: f64, elevation: f64) -> DVec3 {
        direction_from_heading_elevation(heading, elevation)
    }
}

/// Hermite smoothstep, as GLSL/WGSL define it; `edge0 == edge1` gives a step.
pub fn smoothstep(edge0: f64, edge1: f64, x: f64) -> f64 {
    if edge1 == edge0 {
        return if x < edge0 { 0.0 } else { 1.0 };
    }
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(hours: f64) -> TimeOfDay {
        TimeOfDay::from_hours(hours).expect("finite")
    }

    #[test]
    fn equinox_sun_rises_east_at_six_and_culminates_at_colatitude() {
        let lat = 40f64.to_radians();
        let path = SolarPath {
            latitude: lat,
            declination: 0.0,
        };
        let rise = path.direction_at(at(6.0));
        assert!(rise.z.abs() < 1e-12 && (rise.x - 1.0).abs() < 1e-12);
        let set = path.direction_at(at(18.0));
        assert!(set.z.abs() < 1e-12 && (set.x + 1.0).abs() < 1e-12);
        let noon = path.direction_at(at(12.0));
        // Northern latitude: the noon sun is due south at elevation 90° − latitude.
        assert!((noon.z.asin() - (90f64 - 40.0).to_radians()).abs() < 1e-12);
        assert!(noon.y < 0.0 && noon.x.abs() < 1e-12);
    }

    #[test]
    fn midsummer_pole_sun_circles_at_declination() {
        let dec = 23.44f64.to_radians();
        let path = SolarPath {
            latitude: 90f64.to_radians(),
            declination: dec,
        };
        for h in [0.0, 5.0, 13.0, 23.9] {
            assert!((path.direction_at(at(h)).z.asin() - dec).abs() < 1e-9);
        }
    }

    #[test]
    fn disc_and_glow() {
        let sun = SunDisc {
            direction: SunDisc::direction_from(0.0, 0.5),
            angular_radius: 0.01,
            disc_radiance: LinearRgb::new(10.0, 10.0, 10.0),
            glow_radiance: LinearRgb::new(1.0, 0.5, 0.25),
            glow_falloff: 0.1,
            edge_softness: 0.2,
        };
        let centre = sun.radiance(sun.direction);
        assert!((centre.r - 11.0).abs() < 1e-12 && (centre.b - 10.25).abs() < 1e-12);
        let away = sun.radiance(SunDisc::direction_from(0.0, 0.7));
        assert!((away.r - (-2f64).exp()).abs() < 1e-9);
        // Below the horizon nothing shows.
        assert_eq!(sun.radiance(SunDisc::direction_from(0.0, -0.1)), LinearRgb::BLACK);
    }

    #[test]
    fn time_at_elevation_inverts_the_path() {
        let path = SolarPath {
            latitude: 45f64.to_radians(),
            declination: 10f64.to_radians(),
        };
        for hours in [5.5, 7.0, 9.25, 11.9, 12.1, 15.0, 18.5] {
            let t = TimeOfDay::from_hours(hours).expect("finite");
            let elevation = path.direction_at(t).z.asin();
            let back = path.time_at_elevation(elevation, hours < 12.0);
            assert!((back.hours() - hours).abs() < 1e-9, "{hours} -> {}", back.hours());
        }
        // Beyond the path: noon above its highest, midnight below its lowest.
        assert!((path.time_at_elevation(1.5, true).hours() - 12.0).abs() < 1e-9);
        assert!(path.time_at_elevation(-1.5, false).hours().abs() < 1e-9);
    }
}
