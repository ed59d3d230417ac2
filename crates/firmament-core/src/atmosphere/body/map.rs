//! A body's albedo map: an equirectangular image over the body's surface that patterns its
//! normal albedo, so a moon or a planet beside the scene's shows its real face.
//!
//! The map ([`SurfaceMap`], its water channel unused) lies in the body's axes: longitude 0° along
//! `x` (for a moon the sub-planet point, as selenographic longitude puts it), 90° E along `y`,
//! latitude from the `xy` plane towards `z` (north), read at the surface normal (geodetic, as
//! the planet's own map). The map gives the **pattern and colour**, the body's albedo the
//! **level**: at a point the normal albedo is `min(A · m / m̄, 1)` per model wavelength, `A` the
//! body's albedo, `m` the map's texel and `m̄` its [`brightness`] (the mean over the sphere of
//! its red, green and blue). Any picture of the Moon then shows the Moon's geometric albedo
//! 0.12 on average, whatever the exposure it was made with.

use glam::DVec3;

use crate::atmosphere::Spectrum;
use crate::atmosphere::surface::SurfaceMap;

/// The map's brightness `m̄`: the area-weighted mean over the sphere of its red, green and blue,
/// averaged (0 only for a map black everywhere, which a body refuses).
pub fn brightness(map: &SurfaceMap) -> f64 {
    let [r, g, b, _] = map.mean();
    (r + g + b) / 3.0
}

/// The map's factor `m / m̄` on the body's albedo at the point with unit normal `n` in the body's
/// axes.
pub fn albedo_factor(map: &SurfaceMap, n: DVec3) -> Spectrum {
    let latitude = n.z.clamp(-1.0, 1.0).asin();
    let longitude = n.y.atan2(n.x);
    let [r, g, b, _] = map.sample(latitude, longitude);
    Spectrum::new(r, g, b) / brightness(map)
}
