//! Suns: distant stars that light the atmosphere, each treated as a direction for scattering and
//! drawn as a limb-darkened disc.

use std::f64::consts::PI;

use glam::DVec3;

use crate::atmosphere::spectrum::{Spectrum, Wavelengths};
use crate::error::CoreError;

/// One sun, as seen from the planet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sun {
    /// Unit direction from the planet towards the sun, world frame.
    pub direction: DVec3,
    /// Angular radius of the disc, radians.
    pub angular_radius: f64,
    /// Spectral irradiance at the top of the atmosphere, perpendicular to the sun, W·m⁻²·nm⁻¹.
    pub irradiance: Spectrum,
    /// Limb darkening coefficient `u` of the linear law `I(μ)/I(1) = 1 − u·(1 − μ)`, in [0, 1]
    /// (0.6 is the Sun's in the visible; Neckel & Labs 1994).
    pub limb_darkening: f64,
    /// Whether its disc is drawn: `false` for a light whose disc something else draws — the
    /// Moon as the night sky's light source, whose phase the night-sky pass shades (it still
    /// scatters and lights the ground; its [`Self::disc_radiance`] is zero).
    pub disc: bool,
    /// The body (an index into the sky's bodies, which is also its eclipser's) whose reflected
    /// light this is — its light on the planet and the other bodies: that body neither hides it
    /// nor is lit by it. `None` for a star and for the night sky's Moon.
    pub from_body: Option<usize>,
}

impl Sun {
    /// Checks the rules: unit-able direction, angular radius in (0, π/2), irradiance finite ≥ 0,
    /// limb darkening in [0, 1]. `index` names the sun in the message.
    pub fn validate(&self) -> Result<(), CoreError> {
        let invalid = |field, value: String, rule| Err(CoreError::Invalid { field, value, rule });
        if !(self.direction.is_finite() && self.direction.length_squared() > 0.0) {
            return invalid(
                "suns.direction",
                format!("{:?}", self.direction.to_array()),
                "must be a finite, non-zero direction (is the sun at zero distance?)",
            );
        }
        if !(self.angular_radius > 0.0 && self.angular_radius < PI / 2.0) {
            return invalid(
                "suns.angular_radius",
                self.angular_radius.to_string(),
                "must lie in (0, 90) degrees",
            );
        }
        if !(self.irradiance.is_finite() && self.irradiance.min_element() >= 0.0) {
            return invalid(
                "suns.irradiance",
                format!("{:?}", self.irradiance.to_array()),
                "must be finite and >= 0 W·m⁻²·nm⁻¹",
            );
        }
        if !(0.0..=1.0).contains(&self.limb_darkening) {
            return invalid(
                "suns.limb_darkening",
                self.limb_darkening.to_string(),
                "must lie in [0, 1]",
            );
        }
        Ok(())
    }

    /// Radiance of the disc centre above the atmosphere, W·m⁻²·sr⁻¹·nm⁻¹: the irradiance spread
    /// over the disc's solid angle with the limb-darkening profile (∫ I dω = E).
    pub fn center_radiance(&self) -> Spectrum {
        let solid_angle = 2.0 * PI * (1.0 - self.angular_radius.cos());
        // Mean of 1 − u(1 − μ) over the disc, μ = cos of the angle on the stellar surface:
        // ∫₀¹ (1 − u(1 − μ)) 2μ dμ = 1 − u/3.
        self.irradiance / (solid_angle * (1.0 - self.limb_darkening / 3.0))
    }

    /// Radiance of the corona (above the atmosphere) at `angle` radians from the disc's centre,
    /// W·m⁻²·sr⁻¹·nm⁻¹: [`baumbach_corona`] times the disc's mean radiance (the corona is the
    /// photosphere's light scattered, so it has the sun's spectrum); zero on the disc. It belongs
    /// to the sky, so it does not depend on [`Self::disc`]: an environment map, which adds the
    /// discs itself, keeps it (for the Moon as a light it is a millionth of the Moon's own
    /// radiance, nothing to see). Only worth drawing in an eclipse: by day the sky near the sun
    /// is brighter.
    pub fn corona_radiance(&self, angle: f64) -> Spectrum {
        let solid_angle = 2.0 * PI * (1.0 - self.angular_radius.cos());
        self.irradiance / solid_angle * baumbach_corona(angle / self.angular_radius)
    }

    /// Radiance of the disc (above the atmosphere) seen at angle `angle` radians from its centre:
    /// zero outside the disc.
    pub fn disc_radiance(&self, angle: f64) -> Spectrum {
        if !self.disc || angle >= self.angular_radius {
            return Spectrum::ZERO;
        }
        let s = (angle / self.angular_radius).min(1.0);
        let mu = (1.0 - s * s).sqrt();
        self.center_radiance() * (1.0 - self.limb_darkening * (1.0 - mu))
    }
}

/// Baumbach's fit (1937, "Strahlung, Ergiebigkeit und Elektronendichte der Sonnenkorona",
/// Astronomische Nachrichten 263) to the white-light corona's radiance `r` solar radii from the
/// Sun's centre, over the mean radiance of its disc: `10⁻⁶·(0.0532·r^−2.5 + 1.425·r^−7 +
/// 2.565·r^−17)`, 4·10⁻⁶ at the limb and ~10⁻⁹ at 5 radii; in all ~10⁻⁶ of the Sun's light, about
/// half the full Moon's. Zero inside the disc and beyond [`CORONA_MAX_RADII`].
pub fn baumbach_corona(r: f64) -> f64 {
    if !(1.0..CORONA_MAX_RADII).contains(&r) {
        return 0.0;
    }
    1e-6 * (0.0532 * r.powf(-2.5) + 1.425 * r.powi(-7) + 2.565 * r.powi(-17))
}

/// How far out the corona is drawn, solar radii (there it is ~10⁻¹¹ of the disc).
pub const CORONA_MAX_RADII: f64 = 30.0;

/// Relative spectral radiance of a black body at `kelvin`, normalised to 1 at 550 nm (Planck's
/// law), at the model's wavelengths: the colour of a sun given by its temperature.
pub fn blackbody_spectrum(kelvin: f64, wavelengths: Wavelengths) -> Spectrum {
    // h·c/k_B in m·K.
    const C2: f64 = 1.438_776_877e-2;
    let planck = |nm: f64| {
        let lambda = nm * 1e-9;
        1.0 / (lambda.powi(5) * ((C2 / (lambda * kelvin)).exp_m1()))
    };
    let reference = planck(550.0);
    Spectrum::from_array(wavelengths.0.map(|nm| planck(nm) / reference))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disc_radiance_integrates_to_the_irradiance() {
        let sun = Sun {
            direction: DVec3::Z,
            angular_radius: 0.004675,
            irradiance: Spectrum::new(1.474, 1.8504, 1.91198),
            limb_darkening: 0.6,
            disc: true,
            from_body: None,
        };
        // ∫ L dω over the disc, small-angle rings.
        let n = 20_000;
        let mut sum = Spectrum::ZERO;
        for i in 0..n {
            let angle = (i as f64 + 0.5) / n as f64 * sun.angular_radius;
            let ring = 2.0 * PI * angle.sin() * sun.angular_radius / n as f64;
            sum += sun.disc_radiance(angle) * ring;
        }
        assert!(
            (sum / sun.irradiance - Spectrum::ONE).abs().max_element() < 1e-5,
            "{sum}"
        );
    }

    #[test]
    fn the_corona_holds_a_millionth_of_the_sun_and_fades_outwards() {
        // ∫ B(r)·2πr dr over the corona, against the disc's π (mean radiance 1): by the
        // formula's own integrals, 2·10⁻⁶·(0.0532/0.5 + 1.425/5 + 2.565/15) less the part beyond
        // 30 radii.
        let n = 200_000;
        let step = (CORONA_MAX_RADII - 1.0) / n as f64;
        let sum: f64 = (0..n)
            .map(|i| {
                let r = 1.0 + (i as f64 + 0.5) * step;
                baumbach_corona(r) * 2.0 * PI * r * step
            })
            .sum();
        let beyond = 2.0 * 1e-6 * 0.0532 / 0.5 * CORONA_MAX_RADII.powf(-0.5);
        let closed = 2e-6 * (0.0532 / 0.5 + 1.425 / 5.0 + 2.565 / 15.0) - beyond;
        assert!((sum / PI - closed).abs() < 1e-4 * closed, "{} vs {closed}", sum / PI);
        assert!(baumbach_corona(1.0) > 4e-6 && baumbach_corona(5.0) < 1e-9);
        assert_eq!(baumbach_corona(0.9), 0.0);
    }

    #[test]
    fn blackbody_colours_are_ordered() {
        let w = Wavelengths::default();
        let sun = blackbody_spectrum(5778.0, w);
        let red_dwarf = blackbody_spectrum(3000.0, w);
        let blue_star = blackbody_spectrum(20_000.0, w);
        assert!(red_dwarf.x > 1.0 && red_dwarf.z < 1.0);
        assert!(blue_star.z > blue_star.y && blue_star.x < 1.0);
        assert!((sun.y - 1.0).abs() < 1e-12 && (sun.x - 1.0).abs() < 0.2);
    }
}
