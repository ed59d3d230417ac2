//! A sun's disc seen from a point through the air, as small pieces of known irradiance that an
//! environment map adds into the pixels they fall in.
//!
//! The disc (its limb darkening, [`Sun::disc_radiance`]) is cut into rings and sectors; each piece
//! carries `L·T·dω` — radiance above the air times the transmittance from the eye along the
//! piece's own direction (so a disc setting behind the horizon, or behind a cloud, loses the
//! right part) times its solid angle — in luminance-scaled linear sRGB. A pixel that receives
//! pieces adds their sum divided by its own solid angle: it holds the disc's mean radiance over the
//! pixel, and the map's `Σ radiance × solid angle` over the disc is the sun's irradiance at the
//! eye, whatever the pixel size.

use std::f64::consts::TAU;

use glam::DVec3;
use rayon::prelude::*;

use crate::atmosphere::clouds::CloudLayer;
use crate::atmosphere::reference::{Reference, ReferenceSettings};
use crate::atmosphere::{Atmosphere, Eclipser, Spectrum, Sun};
use crate::color::LinearRgb;

/// Rings the disc is cut into, from its centre to its limb.
const RINGS: usize = 32;
/// Sectors of each ring.
const SECTORS: usize = 128;

/// One piece of a sun's disc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscSample {
    /// Unit world direction of the piece's centre.
    pub direction: DVec3,
    /// The piece's irradiance at the eye, normal to its direction: `L·T·dω`, luminance-scaled
    /// linear sRGB (lux for the physical atmosphere).
    pub irradiance: LinearRgb,
}

/// A sun as seen from the eye: where it is and how much of its light the air lets through.
#[derive(Debug, Clone, PartialEq)]
pub struct SunAtEye {
    /// Unit world direction towards the sun's centre.
    pub direction: DVec3,
    /// Transmittance from the eye to space towards the disc's centre (zero below the horizon).
    pub transmittance: Spectrum,
    /// Spectral irradiance at the eye normal to the sun's rays, after the air, W·m⁻²·nm⁻¹: the
    /// sun's irradiance above the air times [`transmittance`](Self::transmittance) (what
    /// `firmament sky-sample` reports as the sun's irradiance, before its cosine on the ground).
    pub irradiance: Spectrum,
    /// [`irradiance`](Self::irradiance) in luminance-scaled linear sRGB (lux).
    pub irradiance_rgb: LinearRgb,
    /// The disc in pieces whose irradiances sum to the disc's own irradiance at the eye (the
    /// transmittance taken along each piece); empty when the sun has no disc drawn
    /// ([`Sun::disc`]).
    pub disc: Vec<DiscSample>,
}

/// `sun` of `atmosphere` (with cloud layers `clouds`, and `eclipsers` that may stand in front of
/// it) seen from world point `eye`, metres: an eclipser takes the pieces of the disc behind it,
/// and its share of the sun's light off the irradiance.
pub fn sun_at_eye(
    atmosphere: &Atmosphere,
    clouds: &[CloudLayer],
    eclipsers: &[Eclipser],
    sun: &Sun,
    eye: DVec3,
) -> SunAtEye {
    let reference = Reference::new(
        atmosphere.clone(),
        std::slice::from_ref(sun),
        ReferenceSettings::default(),
    )
    .with_clouds(clouds)
    .with_eclipsers(eclipsers);
    let hidden = |d: DVec3| eclipsers.iter().any(|e| e.hides(eye, d));
    let planet = atmosphere.planet;
    let from = planet.to_planet_frame(eye);
    let transmittance = |direction: DVec3| {
        reference.transmittance_to_space(from, planet.direction_to_planet_frame(direction).normalize())
    };
    let direction = sun.direction.normalize();
    let conversion = atmosphere.spectral_conversion();
    let centre = transmittance(direction);
    let irradiance = sun.irradiance * centre * reference.sun_visible_fraction(eye, 0);
    let disc = match sun.disc {
        true => disc_pieces(sun, direction)
            .into_par_iter()
            .filter(|(d, _)| !hidden(*d))
            .map(|(d, radiance_solid_angle)| DiscSample {
                direction: d,
                irradiance: conversion.linear_srgb(radiance_solid_angle * transmittance(d)),
            })
            .collect(),
        false => Vec::new(),
    };
    SunAtEye {
        direction,
        transmittance: centre,
        irradiance,
        irradiance_rgb: conversion.linear_srgb(irradiance),
        disc,
    }
}

/// The disc above the air in [`RINGS`] × [`SECTORS`] pieces: each piece's direction and
/// `L·dω` (spectral), scaled so that they sum to the sun's irradiance exactly (the midpoint rule
/// alone is off by about 10⁻³ at the limb, where the limb-darkening profile is steepest).
fn disc_pieces(sun: &Sun, direction: DVec3) -> Vec<(DVec3, Spectrum)> {
    let (e1, e2) = direction.any_orthonormal_pair();
    let radius = sun.angular_radius;
    let mut pieces = Vec::with_capacity(RINGS * SECTORS);
    for ring in 0..RINGS {
        let (a0, a1) = (
            radius * ring as f64 / RINGS as f64,
            radius * (ring + 1) as f64 / RINGS as f64,
        );
        let angle = 0.5 * (a0 + a1);
        // The ring's solid angle 2π(cos a0 − cos a1), written for small discs.
        let ring_solid_angle = TAU * 2.0 * (0.5 * (a1 + a0)).sin() * (0.5 * (a1 - a0)).sin();
        let radiance = sun.disc_radiance(angle) * (ring_solid_angle / SECTORS as f64);
        let (sin_a, cos_a) = angle.sin_cos();
        for sector in 0..SECTORS {
            let phi = TAU * (sector as f64 + 0.5) / SECTORS as f64;
            let (sin_p, cos_p) = phi.sin_cos();
            let d = (direction * cos_a + (e1 * cos_p + e2 * sin_p) * sin_a).normalize();
            pieces.push((d, radiance));
        }
    }
    let total: Spectrum = pieces.iter().map(|(_, l)| *l).sum();
    let scale = Spectrum::from_array([0, 1, 2].map(|i| {
        if total[i] > 0.0 {
            sun.irradiance[i] / total[i]
        } else {
            0.0
        }
    }));
    pieces.iter_mut().for_each(|(_, l)| *l *= scale);
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::presets;
    use glam::DQuat;

    /// Earth posed so that the world is ENU at 45° N (the world origin on the ground).
    fn earth() -> Atmosphere {
        let mut atmosphere = presets::earth();
        atmosphere.planet = atmosphere.planet.posed_at(45f64.to_radians(), 0.0);
        atmosphere
    }

    fn direction(azimuth: f64, elevation: f64) -> DVec3 {
        let (a, e) = (azimuth.to_radians(), elevation.to_radians());
        DVec3::new(e.cos() * a.sin(), e.cos() * a.cos(), e.sin())
    }

    #[test]
    fn the_pieces_sum_to_the_irradiance_after_the_air() {
        let atmosphere = earth();
        let sun = presets::earth_sun(direction(120.0, 30.0));
        let seen = sun_at_eye(&atmosphere, &[], &[], &sun, DVec3::new(0.0, 0.0, 2.0));
        assert_eq!(seen.disc.len(), RINGS * SECTORS);
        let sum = seen
            .disc
            .iter()
            .fold(LinearRgb::new(0.0, 0.0, 0.0), |a, s| a + s.irradiance);
        let want = seen.irradiance_rgb;
        // The transmittance changes across the half-degree disc by a part in 10⁴ at 30° up.
        for (got, want) in [(sum.r, want.r), (sum.g, want.g), (sum.b, want.b)] {
            assert!((got / want - 1.0).abs() < 1e-3, "{got} vs {want}");
        }
        // Every piece lies on the disc.
        let cos_radius = sun.angular_radius.cos();
        assert!(seen.disc.iter().all(|s| s.direction.dot(sun.direction) > cos_radius));
        // Through the air, less than above it.
        assert!(seen.transmittance.max_element() < 1.0 && seen.transmittance.min_element() > 0.3);
    }

    #[test]
    fn a_set_sun_gives_nothing_and_a_disc_less_sun_no_pieces() {
        let atmosphere = earth();
        let set = presets::earth_sun(direction(270.0, -5.0));
        let seen = sun_at_eye(&atmosphere, &[], &[], &set, DVec3::new(0.0, 0.0, 2.0));
        assert_eq!(seen.irradiance, Spectrum::ZERO);
        assert!(seen.disc.iter().all(|s| s.irradiance.r == 0.0 && s.irradiance.g == 0.0));
        let moon_light = Sun {
            disc: false,
            from_body: None,
            ..presets::earth_sun(direction(0.0, 40.0))
        };
        let seen = sun_at_eye(&atmosphere, &[], &[], &moon_light, DVec3::ZERO);
        assert!(seen.disc.is_empty() && seen.irradiance.max_element() > 0.0);
    }

    #[test]
    fn an_eclipse_takes_the_pieces_behind_the_moon_and_their_share_of_light() {
        let atmosphere = earth();
        let sun = presets::earth_sun(direction(180.0, 50.0));
        let eye = DVec3::new(0.0, 0.0, 2.0);
        let clear = sun_at_eye(&atmosphere, &[], &[], &sun, eye);
        // The Moon 360 000 km out, half a solar radius off the sun's centre.
        let off = DQuat::from_axis_angle(sun.direction.cross(DVec3::Z).normalize(), 0.5 * sun.angular_radius);
        let moon = Eclipser {
            center: eye + off * sun.direction * 3.6e8,
            radius_m: 1.7374e6,
        };
        let eclipsed = sun_at_eye(&atmosphere, &[], &[moon], &sun, eye);
        let hidden = 1.0 - eclipsed.irradiance.y / clear.irradiance.y;
        let k = (moon.radius_m / 3.6e8).asin() / sun.angular_radius;
        let want = crate::atmosphere::eclipse::hidden_fraction(0.5, k, sun.limb_darkening);
        assert!((hidden - want).abs() < 1e-3, "{hidden} vs {want}");
        // The pieces left sum to what is seen, within the pieces' own resolution.
        let sum: f64 = eclipsed.disc.iter().map(|s| s.irradiance.g).sum();
        assert!(
            (sum / eclipsed.irradiance_rgb.g - 1.0).abs() < 0.02,
            "{sum} vs {}",
            eclipsed.irradiance_rgb.g
        );
        assert!(eclipsed.disc.len() < clear.disc.len() / 3);
    }
}
