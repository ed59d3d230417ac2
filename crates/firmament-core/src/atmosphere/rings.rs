//! Planetary rings: a thin sheet of icy particles in the planet's equatorial plane (the planet
//! frame's `z = 0`), described by its normal optical depth τ(r) in bands of radius.
//!
//! # Model
//! - **Through the rings** a ray crossing the plane at radius `r` with `μ = |d·z|` keeps
//!   `e^(−τ(r)/μ)` of its light: the rings dim the sky and the sun's disc behind them, and cast
//!   their shadow on the globe and its air (the sun's light at a point times that of the ray from
//!   it towards the sun).
//! - **Seen lit** the rings scatter sunlight once, as a plane-parallel slab of single-scattering
//!   albedo ϖ and Henyey–Greenstein phase function `p` (Chandrasekhar, *Radiative Transfer*, 1960,
//!   ch. 1 §11; the form Cuzzi et al. use for Saturn's rings): with `μ₀ = |s·z|` and `E` the sun's
//!   irradiance, on the lit face `L = E·ϖ·p·μ₀/(μ₀ + μ)·(1 − e^(−τ(1/μ + 1/μ₀)))`, on the other face
//!   `L = E·ϖ·p·μ₀/(μ₀ − μ)·(e^(−τ/μ₀) − e^(−τ/μ))` (`E·ϖ·p·τ/μ·e^(−τ/μ)` where μ = μ₀). A point in
//!   the globe's shadow gets nothing. Light scattered more than once inside the rings, and the
//!   planet's light on them, are left out.
//! - **Their light on the globe** is that light gathered over the rings a ground point sees
//!   ([`Rings::light_on_ground`], `light`'s docs).
//! - **The GPU** reads τ from a table of [`RING_TABLE_ENTRIES`] samples across the rings (linear
//!   between them: a band's edge spreads over one entry, ~490 km for Saturn's).

use std::f64::consts::PI;

use glam::DVec3;

use crate::atmosphere::{Planet, Spectrum};
use crate::error::CoreError;

mod light;

pub use light::{GroundTransmittance, RING_LIGHT_TABLE_SIZE};

/// The most bands a ring system has.
pub const MAX_RING_BANDS: usize = 16;

/// Samples of the optical depth across the rings in the GPU's table.
pub const RING_TABLE_ENTRIES: usize = 128;

/// One band of the rings: between two radii, one normal optical depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RingBand {
    /// Inner radius, metres from the planet's centre.
    pub inner_m: f64,
    /// Outer radius, metres, > `inner_m`.
    pub outer_m: f64,
    /// Normal optical depth (perpendicular to the plane), dimensionless, >= 0.
    pub optical_depth: f64,
}

/// A planet's rings.
#[derive(Debug, Clone, PartialEq)]
pub struct Rings {
    /// The bands, from the inside out, not overlapping (between them: nothing); 1 to
    /// [`MAX_RING_BANDS`].
    pub bands: Vec<RingBand>,
    /// The particles' single-scattering albedo per model wavelength, in [0, 1].
    pub albedo: Spectrum,
    /// Henyey–Greenstein asymmetry of the particles' scattering, in (−1, 1): negative for
    /// macroscopic particles that scatter light back (the main rings), positive for dust.
    pub phase_g: f64,
}

impl Rings {
    /// Saturn's main rings. Radii: NASA's Saturnian Rings Fact Sheet (Williams, NSSDCA): C ring
    /// 74 658–92 000 km, B ring 92 000–117 580 km, Cassini division 117 580–122 170 km, A ring
    /// 122 170–136 775 km. Normal optical depths: typical Cassini values (Cuzzi et al. 2009,
    /// "Ring particle composition and size distribution", *Saturn from Cassini-Huygens*): C ring
    /// 0.1, inner B ring 1.0, B ring core 2.5, Cassini division 0.1, A ring 0.5. The particles'
    /// albedo, reddish (0.6, 0.5, 0.4 at 680, 550, 440 nm), and `g = −0.3`, backscattering, are
    /// this preset's choices for water-ice particles centimetres to metres across.
    pub fn saturn() -> Self {
        let band = |inner_km: f64, outer_km: f64, optical_depth| RingBand {
            inner_m: inner_km * 1000.0,
            outer_m: outer_km * 1000.0,
            optical_depth,
        };
        Self {
            bands: vec![
                band(74_658.0, 92_000.0, 0.1),
                band(92_000.0, 99_000.0, 1.0),
                band(99_000.0, 117_580.0, 2.5),
                band(117_580.0, 122_170.0, 0.1),
                band(122_170.0, 136_775.0, 0.5),
            ],
            albedo: Spectrum::new(0.6, 0.5, 0.4),
            phase_g: -0.3,
        }
    }

    /// The inner edge, metres.
    pub fn inner_m(&self) -> f64 {
        self.bands.first().map_or(0.0, |b| b.inner_m)
    }

    /// The outer edge, metres.
    pub fn outer_m(&self) -> f64 {
        self.bands.last().map_or(0.0, |b| b.outer_m)
    }

    /// Checks the rules against `planet`: 1 to [`MAX_RING_BANDS`] bands, each with finite radii,
    /// outer > inner, in order without overlapping, the first outside the planet's equator; optical
    /// depths finite and >= 0; albedo in [0, 1]; `g` in (−1, 1).
    pub fn validate(&self, planet: &Planet) -> Result<(), CoreError> {
        let invalid = |field, value: String, rule| Err(CoreError::Invalid { field, value, rule });
        if self.bands.is_empty() || self.bands.len() > MAX_RING_BANDS {
            return invalid(
                "rings.bands",
                format!("{} bands", self.bands.len()),
                "must hold 1 to 16 bands",
            );
        }
        let equator = planet.radii.x.max(planet.radii.y);
        let mut previous_outer = equator;
        for (i, band) in self.bands.iter().enumerate() {
            let item = |key: &str, value: f64, rule| {
                Err(CoreError::InvalidItem {
                    field: format!("rings.bands[{i}].{key}"),
                    value: value.to_string(),
                    rule,
                })
            };
            if !(band.inner_m.is_finite() && band.outer_m.is_finite() && band.outer_m > band.inner_m) {
                return item(
                    "outer_radius",
                    band.outer_m,
                    "must be finite metres and greater than the band's inner_radius",
                );
            }
            if band.inner_m < previous_outer || band.inner_m <= equator {
                return item(
                    "inner_radius",
                    band.inner_m,
                    "must lie outside the planet's equatorial radius and the band before (bands go from the inside out without overlapping)",
                );
            }
            if !(band.optical_depth.is_finite() && band.optical_depth >= 0.0) {
                return item("optical_depth", band.optical_depth, "must be finite and >= 0");
            }
            previous_outer = band.outer_m;
        }
        if !(self.albedo.is_finite() && self.albedo.min_element() >= 0.0 && self.albedo.max_element() <= 1.0) {
            return invalid(
                "rings.albedo",
                format!("{:?}", self.albedo.to_array()),
                "must lie in [0, 1]",
            );
        }
        if !(self.phase_g > -1.0 && self.phase_g < 1.0) {
            return invalid(
                "rings.g",
                self.phase_g.to_string(),
                "must lie strictly between -1 and 1",
            );
        }
        Ok(())
    }

    /// The normal optical depth at `r` metres from the centre in the plane (0 between bands and
    /// outside the rings).
    pub fn optical_depth_at(&self, r: f64) -> f64 {
        self.bands
            .iter()
            .find(|b| r >= b.inner_m && r < b.outer_m)
            .map_or(0.0, |b| b.optical_depth)
    }

    /// Where a planet-frame ray from `origin` along unit `direction` crosses the rings, ahead of
    /// it: the distance along the ray and the radius there, or `None`.
    pub fn crossing(&self, origin: DVec3, direction: DVec3) -> Option<(f64, f64)> {
        if direction.z == 0.0 {
            return None;
        }
        let t = -origin.z / direction.z;
        let r = (origin + direction * t).truncate().length();
        (t > 0.0 && r >= self.inner_m() && r < self.outer_m()).then_some((t, r))
    }

    /// The share of light that passes the rings along a planet-frame ray: `e^(−τ(r)/μ)` where it
    /// crosses them, 1 where it does not.
    pub fn transmittance(&self, origin: DVec3, direction: DVec3) -> f64 {
        self.crossing(origin, direction)
            .map_or(1.0, |(_, r)| (-self.optical_depth_at(r) / direction.z.abs()).exp())
    }

    /// The radiance the rings scatter towards a viewer looking along unit `view` (planet frame) at
    /// radius `r`, lit by a sun towards unit `sun` with irradiance `irradiance` (zero when the
    /// globe hides it: pass `lit = false`), per model wavelength. See the module docs.
    pub fn radiance(&self, r: f64, view: DVec3, sun: DVec3, irradiance: Spectrum, lit: bool) -> Spectrum {
        let tau = self.optical_depth_at(r);
        let (mu, mu0) = (view.z.abs(), sun.z.abs());
        if !lit || tau <= 0.0 || mu <= 0.0 || mu0 <= 0.0 {
            return Spectrum::ZERO;
        }
        // Light travels along −sun and leaves towards −view.
        let phase = henyey_greenstein(self.phase_g, sun.dot(view));
        let lit_face = (view.z > 0.0) != (sun.z > 0.0);
        let slab = if lit_face {
            mu0 / (mu0 + mu) * (1.0 - (-tau * (1.0 / mu + 1.0 / mu0)).exp())
        } else if (mu0 - mu).abs() < 1e-9 {
            mu0 * tau / (mu * mu) * (-tau / mu).exp()
        } else {
            mu0 / (mu0 - mu) * ((-tau / mu0).exp() - (-tau / mu).exp())
        };
        irradiance * self.albedo * (phase * slab)
    }

    /// The GPU's table: τ at `inner + k·(outer − inner)/(N − 1)`, k = 0…N−1
    /// ([`RING_TABLE_ENTRIES`]), each the band's value at its radius.
    pub fn optical_depth_table(&self) -> [f64; RING_TABLE_ENTRIES] {
        let (inner, outer) = (self.inner_m(), self.outer_m());
        std::array::from_fn(|k| {
            let r = inner + (outer - inner) * k as f64 / (RING_TABLE_ENTRIES - 1) as f64;
            self.optical_depth_at(r.min(outer - 1e-6))
        })
    }
}

/// Henyey–Greenstein's phase function, sr⁻¹, for the cosine `nu` between the propagation
/// directions before and after.
fn henyey_greenstein(g: f64, nu: f64) -> f64 {
    let denominator = 1.0 + g * g - 2.0 * g * nu;
    (1.0 - g * g) / (4.0 * PI * denominator * denominator.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn saturn_planet() -> Planet {
        Planet::spheroid(60_268_000.0, 54_364_000.0, 600_000.0)
    }

    #[test]
    fn saturn_s_rings_are_valid_and_bad_rings_name_the_rule() {
        let planet = saturn_planet();
        assert_eq!(Rings::saturn().validate(&planet), Ok(()));
        let mut inside = Rings::saturn();
        inside.bands[0].inner_m = 50_000_000.0;
        let message = inside.validate(&planet).unwrap_err().to_string();
        assert!(
            message.contains("rings.bands[0].inner_radius") && message.contains("equatorial"),
            "{message}"
        );
        let mut flipped = Rings::saturn();
        flipped.bands[4].outer_m = flipped.bands[4].inner_m;
        assert!(
            flipped
                .validate(&planet)
                .unwrap_err()
                .to_string()
                .contains("outer_radius")
        );
        let mut overlapping = Rings::saturn();
        overlapping.bands[2].inner_m = 95_000_000.0;
        assert!(
            overlapping
                .validate(&planet)
                .unwrap_err()
                .to_string()
                .contains("overlapping")
        );
        let mut negative = Rings::saturn();
        negative.bands[1].optical_depth = -1.0;
        assert!(
            negative
                .validate(&planet)
                .unwrap_err()
                .to_string()
                .contains("rings.bands[1].optical_depth")
        );
        let none = Rings {
            bands: vec![],
            ..Rings::saturn()
        };
        assert!(none.validate(&planet).unwrap_err().to_string().contains("1 to 16"));
        let forward = Rings {
            phase_g: 1.0,
            ..Rings::saturn()
        };
        assert!(forward.validate(&planet).unwrap_err().to_string().contains("rings.g"));
    }

    #[test]
    fn a_ray_through_the_b_ring_keeps_e_to_the_minus_tau_over_mu() {
        let rings = Rings::saturn();
        let origin = DVec3::new(105_000_000.0, 0.0, 50_000_000.0);
        let direction = DVec3::new(0.05, 0.02, -1.0).normalize();
        let (t, r) = rings.crossing(origin, direction).expect("crosses");
        assert!((origin + direction * t).z.abs() < 1e-3);
        let want = (-2.5 / direction.z.abs()).exp();
        assert!((99_000_000.0..117_580_000.0).contains(&r), "{r}");
        assert!((rings.transmittance(origin, direction) - want).abs() < 1e-12);
        // Parallel to the plane, behind, or through the Cassini division.
        assert_eq!(rings.transmittance(origin, DVec3::X), 1.0);
        assert_eq!(rings.transmittance(origin, -direction), 1.0);
        let division = DVec3::new(119_000_000.0, 0.0, 1.0);
        assert!((rings.transmittance(division, -DVec3::Z) - (-0.1f64).exp()).abs() < 1e-12);
    }

    #[test]
    fn the_slab_conserves_light_when_thin_and_saturates_when_thick() {
        let rings = Rings {
            bands: vec![RingBand {
                inner_m: 1.0,
                outer_m: 2.0,
                optical_depth: 1e-4,
            }],
            albedo: Spectrum::ONE,
            phase_g: 0.0,
        };
        let sun = DVec3::new(0.0, 0.6, 0.8);
        let view = DVec3::new(0.0, -0.6, -0.8).normalize();
        // Thin: single scattering is ϖ·p·τ·E/μ either face.
        let thin = rings.radiance(1.5, view, sun, Spectrum::ONE, true).y;
        let want = 1e-4 / view.z.abs() / (4.0 * PI);
        assert!((thin / want - 1.0).abs() < 1e-3, "{thin} vs {want}");
        let through = rings.radiance(1.5, -view, sun, Spectrum::ONE, true).y;
        assert!((through / want - 1.0).abs() < 1e-3, "{through} vs {want}");
        // Thick: the lit face tends to ϖ·p·μ₀/(μ₀ + μ), the far face to nothing.
        let thick = Rings {
            bands: vec![RingBand {
                optical_depth: 50.0,
                ..rings.bands[0]
            }],
            ..rings.clone()
        };
        let lit = thick.radiance(1.5, view, sun, Spectrum::ONE, true).y;
        assert!((lit - 0.8 / 1.6 / (4.0 * PI)).abs() < 1e-9, "{lit}");
        assert!(thick.radiance(1.5, -view, sun, Spectrum::ONE, true).y < 1e-15);
        assert_eq!(thick.radiance(1.5, view, sun, Spectrum::ONE, false), Spectrum::ZERO);
    }
}
