//! The Moon's maria as an albedo pattern on a body's surface: dark basalt plains on
//! brighter highlands, so a Moon body shows the face everyone knows.
//!
//! Each mare is a round patch at its centre's selenographic latitude and longitude with its
//! diameter, from the IAU's *Gazetteer of Planetary Nomenclature* (USGS Astrogeology, rounded to
//! 0.1° and 10 km); Oceanus Procellarum and Mare Frigoris, which are far from round, are chains of
//! smaller round patches laid along them by eye on the Gazetteer's maps (an approximation). In
//! the body's axes `x` points to 0° N 0° E (the mean sub-Earth point), `y` to 0° N 90° E, `z`
//! north. The pattern multiplies the body's normal albedo: [`HIGHLAND_FACTOR`] on the highlands,
//! [`MARE_FACTOR`] on the maria, blended across each patch's rim (between [`EDGE_INNER`] and
//! [`EDGE_OUTER`] of its angular radius), the darkest patch winning where they overlap. With the
//! Moon's geometric albedo 0.12 they give 0.138 and 0.072: near-side highlands 0.11–0.18, maria
//! 0.07–0.10 (Hapke, *Theory of Reflectance and Emittance Spectroscopy*, 2nd ed. 2012, §12;
//! Lane & Irvine 1973, *AJ* 78, 267), and a near-side mean close to 0.12 (a test checks within
//! 10 %).

use glam::DVec3;

use crate::atmosphere::body::MOON_RADIUS_M;

/// One mare: centre latitude and longitude (°, east positive) and diameter (km).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mare {
    /// Selenographic latitude of the centre, °.
    pub latitude_deg: f64,
    /// Selenographic longitude of the centre, ° east.
    pub longitude_deg: f64,
    /// Diameter, km.
    pub diameter_km: f64,
}

const fn mare(latitude_deg: f64, longitude_deg: f64, diameter_km: f64) -> Mare {
    Mare {
        latitude_deg,
        longitude_deg,
        diameter_km,
    }
}

/// The maria (see the module docs for the sources).
pub const MARIA: [Mare; 26] = [
    mare(32.8, -15.6, 1150.0), // Imbrium
    mare(27.3, 18.4, 670.0),   // Serenitatis
    mare(8.5, 31.4, 870.0),    // Tranquillitatis
    mare(17.0, 59.1, 560.0),   // Crisium
    mare(-7.8, 53.7, 840.0),   // Fecunditatis
    mare(-15.2, 35.5, 330.0),  // Nectaris
    mare(-21.3, -16.6, 710.0), // Nubium
    mare(-24.4, -38.6, 390.0), // Humorum
    mare(13.3, 3.6, 250.0),    // Vaporum
    mare(-10.5, -23.1, 380.0), // Cognitum
    mare(7.5, -30.9, 510.0),   // Insularum
    mare(1.3, 87.5, 370.0),    // Smythii
    mare(13.3, 86.1, 360.0),   // Marginis
    mare(-38.9, 93.0, 600.0),  // Australe
    mare(44.1, -31.5, 240.0),  // Sinus Iridum
    mare(27.3, 147.9, 280.0),  // Moscoviense, on the far side
    mare(-33.7, 163.5, 320.0), // Ingenii, on the far side
    mare(40.0, -56.0, 600.0),  // Oceanus Procellarum, north
    mare(22.0, -58.0, 800.0),  // Procellarum, middle
    mare(5.0, -52.0, 700.0),   // Procellarum, south
    mare(-8.0, -45.0, 450.0),  // Procellarum, southern tip
    mare(56.0, -40.0, 280.0),  // Mare Frigoris, west
    mare(57.0, -20.0, 280.0),  // Frigoris
    mare(57.0, 0.0, 280.0),    // Frigoris
    mare(56.0, 20.0, 280.0),   // Frigoris
    mare(55.0, 40.0, 280.0),   // Frigoris, east
];

/// The pattern's factor on the highlands.
pub const HIGHLAND_FACTOR: f64 = 1.15;

/// The pattern's factor on the maria.
pub const MARE_FACTOR: f64 = 0.6;

/// Where a patch's rim begins and ends, in units of its angular radius.
pub const EDGE_INNER: f64 = 0.85;

/// See [`EDGE_INNER`].
pub const EDGE_OUTER: f64 = 1.15;

impl Mare {
    /// The unit direction of the centre in the body's axes.
    pub fn center(&self) -> DVec3 {
        let (lat, lon) = (self.latitude_deg.to_radians(), self.longitude_deg.to_radians());
        DVec3::new(lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin())
    }

    /// The angular radius seen from the Moon's centre, radians.
    pub fn angular_radius(&self) -> f64 {
        0.5 * self.diameter_km * 1000.0 / MOON_RADIUS_M
    }
}

fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The factor the pattern puts on the albedo at the point whose outward unit normal in the
/// body's axes is `normal`.
pub fn albedo_factor(normal: DVec3) -> f64 {
    let mare = MARIA.iter().fold(0.0f64, |darkest, m| {
        let c = m.center();
        let angle = normal.cross(c).length().atan2(normal.dot(c)) / m.angular_radius();
        darkest.max(1.0 - smoothstep(EDGE_INNER, EDGE_OUTER, angle))
    });
    HIGHLAND_FACTOR + (MARE_FACTOR - HIGHLAND_FACTOR) * mare
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_near_side_averages_the_moon_s_albedo() {
        // Seen from Earth (along −x): equal areas of the disc weighted alike.
        let mean = crate::sky::night::mean_over_face(DVec3::NEG_X, |n| DVec3::splat(albedo_factor(n))).x;
        assert!((mean - 1.0).abs() < 0.1, "near-side mean factor {mean}");
    }

    #[test]
    fn maria_are_dark_and_highlands_bright() {
        let tranquillitatis = MARIA[2].center();
        assert_eq!(albedo_factor(tranquillitatis), MARE_FACTOR);
        // Near Tycho, in the southern highlands, and on the far side.
        let tycho = mare(-43.3, -11.2, 0.0).center();
        assert_eq!(albedo_factor(tycho), HIGHLAND_FACTOR);
        assert_eq!(albedo_factor(DVec3::new(-1.0, 0.0, 0.0)), HIGHLAND_FACTOR);
    }
}
