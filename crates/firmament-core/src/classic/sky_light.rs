//! Objects lit by a physical atmosphere: each sun becomes a directional light and the sky's
//! irradiance the ambient term, in the same units as the sky the renderer draws (linear sRGB whose
//! Y is luminance, cd/m²), so objects and sky share one exposure.
//!
//! With a white Lambertian material (diffuse and ambient = albedo `ρ`) the fixed-function equation
//! then gives the radiance `ρ/π · (E_sun·T·cos θ + E_sky)`: the lights' diffuse and specular
//! colours are `E_sun·T/π` — the sun's irradiance at the top of the atmosphere through the
//! transmittance from the point towards it — and the scene ambient is `E_sky/π`, the irradiance of
//! the whole sky on a horizontal surface. Both are taken at one point (the camera: objects are
//! small next to the atmosphere's scale heights), so nothing varies across an object but the
//! equations' own terms. Aerial perspective between the object and the camera is the renderer's.

use glam::{DVec3, DVec4};

use super::lighting::{Light, LightModel, SpecularModel};
use super::scene::{ClassicLighting, LightSpace, SceneLight, Shading};
use crate::atmosphere::reference::{Reference, ReferenceSettings};
use crate::frame::AtmosphereSky;

/// Monte Carlo paths for the sky irradiance: its standard error is about 1/√paths of the value
/// (3 % at 1024), plenty for an ambient term.
pub const SKY_IRRADIANCE_PATHS: usize = 1024;

/// The classic lighting that `sky`'s suns and sky give objects near `point` (world frame, metres).
/// Lights are world-space directional lights with no ambient of their own; the model has a local
/// viewer (real highlights depend on where the eye is).
pub fn sky_lighting(sky: &AtmosphereSky, point: DVec3, shading: Shading, specular: SpecularModel) -> ClassicLighting {
    let settings = ReferenceSettings {
        paths: SKY_IRRADIANCE_PATHS,
        ..ReferenceSettings::default()
    };
    let reference = Reference::new(sky.atmosphere, &sky.suns, settings);
    let planet = &sky.atmosphere.planet;
    let conversion = sky.atmosphere.spectral_conversion();
    let rgb = |spectrum: DVec3| {
        let c = conversion.linear_srgb(spectrum / std::f64::consts::PI);
        DVec4::new(c.r.max(0.0), c.g.max(0.0), c.b.max(0.0), 1.0)
    };
    let at = planet.to_planet_frame(point);
    let lights = sky
        .suns
        .iter()
        .map(|sun| {
            let direction = sun.direction.normalize();
            let transmittance = reference.transmittance_to_space(at, planet.direction_to_planet_frame(direction));
            let color = rgb(sun.irradiance * transmittance);
            SceneLight {
                light: Light {
                    ambient: DVec4::new(0.0, 0.0, 0.0, 1.0),
                    diffuse: color,
                    specular: color,
                    position: direction.extend(0.0),
                    ..Light::gl_default(0)
                },
                space: LightSpace::World,
            }
        })
        .collect();
    let ambient = rgb(reference.ground_irradiance(point).sky);
    ClassicLighting {
        lights,
        model: LightModel {
            ambient,
            local_viewer: true,
            two_side: false,
            separate_specular: false,
        },
        shading,
        specular,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::presets;

    #[test]
    fn a_high_sun_outshines_the_sky_and_a_set_sun_gives_no_light() {
        let mut earth = presets::earth();
        // The world frame East-North-Up on the surface at 45° N.
        earth.planet = earth.planet.posed_at(45f64.to_radians(), 0.0);
        let high = AtmosphereSky {
            atmosphere: earth,
            suns: vec![presets::earth_sun(DVec3::new(0.0, 0.5, 1.0).normalize())],
        };
        let lit = sky_lighting(&high, DVec3::new(0.0, 0.0, 2.0), Shading::Phong, SpecularModel::Blinn);
        let sun = lit.lights[0].light.diffuse;
        let sky = lit.model.ambient;
        // Clear noon: the direct beam is several times the diffuse sky, which is bluer.
        assert!(sun.y > 2.0 * sky.y, "sun {sun} sky {sky}");
        assert!(
            sky.z / sky.x > sun.z / sun.x,
            "the sky is bluer than the sun: {sky} {sun}"
        );
        // Top-of-atmosphere irradiance / π bounds the beam from above.
        let outside = high
            .atmosphere
            .spectral_conversion()
            .linear_srgb(high.suns[0].irradiance / std::f64::consts::PI);
        assert!(sun.y < outside.g, "{sun} vs {outside:?}");
        let set = AtmosphereSky {
            atmosphere: earth,
            suns: vec![presets::earth_sun(DVec3::new(0.0, 1.0, -0.2).normalize())],
        };
        let dark = sky_lighting(&set, DVec3::new(0.0, 0.0, 2.0), Shading::Phong, SpecularModel::Blinn);
        assert_eq!(dark.lights[0].light.diffuse.truncate(), DVec3::ZERO);
    }
}
