//! Objects lit by a physical atmosphere: each sun becomes a directional light and the sky's
//! irradiance the ambient term, in the same units as the sky the renderer draws (linear sRGB whose
//! Y is luminance, cd/m²), so objects and sky share one exposure.
//!
//! With a white Lambertian material (diffuse and ambient = albedo `ρ`) the fixed-function equation
//! then gives the radiance `ρ/π · (E_sun·T·cos θ + E_sky)`: a sun's diffuse and specular colour is
//! `E_sun·T/π` — its irradiance at the top of the atmosphere through the transmittance from the
//! **object** towards it ([`SkyLight::sun_colors`], one value per object at its origin, so a tower
//! on a hill keeps the sun after the street below has lost it) — and the scene ambient is
//! `E_sky/π`, the irradiance of the whole sky on a horizontal surface, taken once at the camera
//! (it changes over kilometres of altitude; the direct beam changes across a terminator). Aerial
//! perspective between the object and the camera is the renderer's.
//!
//! The beam also passes through the sky's cloud layers ([`SkyLight::sun_colors`]): a lens flare's
//! sun is dimmed by them, and a sun behind an overcast gives no shadows before a clear one.
//! Objects take the beam through the clear air ([`SkyLight::sun_colors_through_air`]): the
//! renderer dims it per fragment by the clouds' shadow map. The ambient term and the ground's
//! bounce do not see the clouds yet (docs/CLOUDS.md, "Not yet done").

use glam::{DVec3, DVec4};

use super::ground::{Ground, ground_object, surface_texture};
use super::lighting::{Light, LightModel, SpecularModel};
use super::scene::{ClassicLighting, LightSpace, SceneLight, Shading};
use super::shadow::ShadowLight;
use crate::atmosphere::reference::{GroundIrradiance, Reference, ReferenceSettings};
use crate::atmosphere::{SpectralConversion, Spectrum};
use crate::frame::AtmosphereSky;

/// Monte Carlo paths for the sky irradiance. Every point draws the same random numbers, so the
/// estimate is smooth in space (no flicker as the camera moves) and its error is a bias rather than
/// noise: 3–4 % low at 1024 paths, under 0.5 % from 3072 on (against 65 536, the Earth at noon
/// and with the Sun 25° up). 1024 paths cost about 30 ms a frame on two cores, 4096 four times
/// that: the viewer builds a frame every redraw, so the ambient term keeps the cheaper estimate.
pub const SKY_IRRADIANCE_PATHS: usize = 1024;

/// The light a physical sky gives objects: build once per frame, then ask per point.
#[derive(Debug)]
pub struct SkyLight<'a> {
    sky: &'a AtmosphereSky,
    /// The clear air: the sky's irradiance.
    reference: Reference,
    /// The air and the clouds: the suns' beams.
    beams: Reference,
    conversion: SpectralConversion,
    /// The last point's irradiance ([`Self::lighting`] and [`Self::ground`] share it).
    irradiance: std::sync::Mutex<Option<(DVec3, GroundIrradiance)>>,
}

impl<'a> SkyLight<'a> {
    /// The light of `sky`'s suns and atmosphere.
    pub fn new(sky: &'a AtmosphereSky) -> Self {
        let settings = ReferenceSettings {
            paths: SKY_IRRADIANCE_PATHS,
            ..ReferenceSettings::default()
        };
        let reference = Reference::new(sky.atmosphere.clone(), &sky.suns, settings)
            .with_eclipsers(&sky.eclipsers)
            .with_rings(sky.rings.as_ref())
            .with_surface(sky.surface.as_ref());
        Self {
            sky,
            beams: reference.clone().with_clouds(&sky.clouds),
            reference,
            conversion: sky.atmosphere.spectral_conversion(),
            irradiance: std::sync::Mutex::new(None),
        }
    }

    /// The irradiance on a horizontal surface at `point` (world frame, metres), computed once
    /// per point.
    fn irradiance(&self, point: DVec3) -> GroundIrradiance {
        let mut last = self.irradiance.lock().unwrap_or_else(|e| e.into_inner());
        match *last {
            Some((at, value)) if at == point => value,
            _ => {
                let value = self.reference.ground_irradiance(point);
                *last = Some((point, value));
                value
            }
        }
    }

    /// A spectral irradiance as a GL colour of radiance from a Lambertian reflector, `E/π`.
    fn rgb(&self, spectrum: DVec3) -> DVec4 {
        let c = self.conversion.linear_srgb(spectrum / std::f64::consts::PI);
        DVec4::new(c.r.max(0.0), c.g.max(0.0), c.b.max(0.0), 1.0)
    }

    /// Each sun's light colour at `point` (world frame, metres): `E·T/π`, `T` through the air
    /// and the clouds; black when the sun is below the point's horizon.
    pub fn sun_colors(&self, point: DVec3) -> Vec<DVec4> {
        self.beam_colors(&self.beams, point)
    }

    /// Each sun's light colour at `point` (world frame, metres) through the air alone: `E·T/π`,
    /// the clouds left to the renderer's shadow map (firmament-render's object pass dims each
    /// fragment by it, within its reach of the camera); black when the sun is below the point's
    /// horizon.
    pub fn sun_colors_through_air(&self, point: DVec3) -> Vec<DVec4> {
        self.beam_colors(&self.reference, point)
    }

    /// `E·T/π` of each sun at `point`, `T` through `medium`'s media, `E` less what an eclipse
    /// hides there.
    fn beam_colors(&self, medium: &Reference, point: DVec3) -> Vec<DVec4> {
        let planet = &self.sky.atmosphere.planet;
        let at = planet.to_planet_frame(point);
        self.sky
            .suns
            .iter()
            .enumerate()
            .map(|(i, sun)| {
                let towards = planet.direction_to_planet_frame(sun.direction.normalize());
                let visible = medium.sun_visible_fraction(point, i);
                self.rgb(sun.irradiance * medium.transmittance_to_space(at, towards) * visible)
            })
            .collect()
    }

    /// The classic lighting for objects seen from `camera` (world frame, metres): one
    /// world-space directional light per sun, coloured through the air at the camera (objects
    /// replace that with [`Self::sun_colors_through_air`] at their own origin; the clouds are the
    /// renderer's shadow map), no ambient of its own; the sky's
    /// irradiance at the camera as the scene ambient; a local viewer (real highlights depend on
    /// where the eye is).
    pub fn lighting(&self, camera: DVec3, shading: Shading, specular: SpecularModel) -> ClassicLighting {
        let lights = self
            .sky
            .suns
            .iter()
            .zip(self.sun_colors_through_air(camera))
            .map(|(sun, color)| SceneLight {
                light: Light {
                    ambient: DVec4::new(0.0, 0.0, 0.0, 1.0),
                    diffuse: color,
                    specular: color,
                    position: sun.direction.normalize().extend(0.0),
                    ..Light::gl_default(0)
                },
                space: LightSpace::World,
            })
            .collect();
        ClassicLighting {
            lights,
            model: LightModel {
                ambient: self.rgb(self.irradiance(camera).sky),
                local_viewer: true,
                two_side: false,
                separate_specular: false,
                // Radiance: no stage clamps it (`ObjectLighting::clamps`).
                clamp_vertex_color: false,
            },
            shading,
            specular,
        }
    }
}

impl SkyLight<'_> {
    /// The ground under a camera at `camera` (world frame, metres): the surface patch in the
    /// ground's albedo there (the planet surface's under the camera, or the medium's ground
    /// albedo) and the light it bounces up ([`Ground`]); `None` below the surface. The sky's
    /// irradiance is the same estimate as [`Self::lighting`]'s ambient (same seed).
    pub fn ground(&self, camera: DVec3) -> Option<Ground> {
        let atmosphere = &self.sky.atmosphere;
        let irradiance = self.irradiance(camera);
        let albedo = match &self.sky.surface {
            Some(surface) => {
                let planet = &atmosphere.planet;
                surface.at(planet.up(planet.to_planet_frame(camera))).albedo
            }
            None => atmosphere.medium.ground_albedo,
        };
        // An albedo as linear sRGB: what it reflects of this light, channel by channel (exact for
        // a grey ground, whatever the light's colour), as the sky pass's spectral ground shows it.
        let lit = self.rgb(irradiance.direct + irradiance.sky);
        let as_rgb = |albedo: Spectrum| {
            let reflected = self.rgb(albedo * (irradiance.direct + irradiance.sky));
            let mean = (albedo.x + albedo.y + albedo.z) / 3.0;
            let channel = |r: f64, l: f64| if l > 0.0 { (r / l).clamp(0.0, 1.0) } else { mean };
            DVec3::new(
                channel(reflected.x, lit.x),
                channel(reflected.y, lit.y),
                channel(reflected.z, lit.z),
            )
        };
        let (mut object, up, camera_height_m) = ground_object(&atmosphere.planet, camera, as_rgb(albedo).extend(1.0))?;
        if let Some(surface) = &self.sky.surface {
            surface_texture(&atmosphere.planet, surface, &mut object, as_rgb);
        }
        // A centimetre above the foot point: on the surface itself, rounding decides whether the
        // path to a sun starts below the ground.
        object.light_colors = self.sun_colors_through_air(object.model.transform_point3(DVec3::Z * 0.01));
        Some(Ground {
            object,
            up,
            camera_height_m,
            sky: self.rgb(irradiance.sky),
            bounced_sun: self.rgb(albedo * irradiance.direct),
            bounced_sky: self.rgb(albedo * irradiance.sky),
        })
    }

    /// The suns that cast shadows at a camera at `camera` (world frame, metres): those above its
    /// horizon, brightest first (by the luminance of their light there), at most `max_lights`.
    /// `light` indexes the frame's suns, which are [`Self::lighting`]'s lights in order.
    pub fn shadow_lights(&self, camera: DVec3, max_lights: u32) -> Vec<ShadowLight> {
        let mut lit: Vec<(usize, f64)> = self
            .sun_colors(camera)
            .iter()
            .enumerate()
            .map(|(i, c)| (i, 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z))
            .filter(|&(_, y)| y > 0.0)
            .collect();
        lit.sort_by(|a, b| b.1.total_cmp(&a.1));
        lit.into_iter()
            .take(max_lights as usize)
            .map(|(i, _)| {
                let sun = &self.sky.suns[i];
                ShadowLight {
                    light: i,
                    direction: sun.direction.normalize(),
                    angular_radius: sun.angular_radius,
                }
            })
            .collect()
    }
}

/// [`SkyLight::lighting`] in one call.
pub fn sky_lighting(sky: &AtmosphereSky, camera: DVec3, shading: Shading, specular: SpecularModel) -> ClassicLighting {
    SkyLight::new(sky).lighting(camera, shading, specular)
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
            atmosphere: earth.clone(),
            suns: vec![presets::earth_sun(DVec3::new(0.0, 0.5, 1.0).normalize())],
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
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
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        };
        let dark = sky_lighting(&set, DVec3::new(0.0, 0.0, 2.0), Shading::Phong, SpecularModel::Blinn);
        assert_eq!(dark.lights[0].light.diffuse.truncate(), DVec3::ZERO);
    }

    #[test]
    fn a_sun_just_below_the_street_s_horizon_still_lights_a_mountain_top() {
        let mut earth = presets::earth();
        earth.planet = earth.planet.posed_at(45f64.to_radians(), 0.0);
        // 1° below the horizon of the surface: the sun's grazing ray clears a point 3 km up
        // (the horizon dips by about 1.8° there).
        let sky = AtmosphereSky {
            atmosphere: earth,
            suns: vec![presets::earth_sun(
                DVec3::new(0.0, 1.0, -(1f64.to_radians().tan())).normalize(),
            )],
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        };
        let light = SkyLight::new(&sky);
        let street = light.sun_colors(DVec3::new(0.0, 0.0, 2.0))[0];
        let summit = light.sun_colors(DVec3::new(0.0, 0.0, 3000.0))[0];
        assert_eq!(street.truncate(), DVec3::ZERO);
        assert!(summit.x > 0.0 && summit.x > summit.z, "a red sunset beam: {summit}");
        let lit = light.lighting(DVec3::new(0.0, 0.0, 2.0), Shading::Gouraud, SpecularModel::Blinn);
        assert_eq!(lit.lights[0].light.diffuse, street);
    }

    #[test]
    fn a_uniform_cloud_layer_dims_the_beam_by_its_optical_depth() {
        use crate::atmosphere::clouds::{CloudKind, CloudLayer};
        let mut earth = presets::earth();
        earth.planet = earth.planet.posed_at(45f64.to_radians(), 0.0);
        let sky = |zenith_deg: f64, clouds: Vec<CloudLayer>| {
            let z = zenith_deg.to_radians();
            AtmosphereSky {
                atmosphere: earth.clone(),
                suns: vec![presets::earth_sun(DVec3::new(0.0, z.sin(), z.cos()))],
                clouds,
                eclipsers: Vec::new(),
                bodies: Vec::new(),
                rings: None,
                surface: None,
            }
        };
        // 1000 m of 0.001 m⁻¹ seen from 2 m: the beam's path through the shell between 1000 and
        // 2000 m on a sphere of the Earth's mean radius (a slant path's curvature term, 0.07 % at
        // 60°; the ellipsoid's own curvature here changes it by parts in 10⁶).
        let layer = CloudLayer::new(1000.0, 2000.0, 1.0, 0.001, CloudKind::Uniform);
        let path = |zenith_deg: f64| {
            let (r0, mu) = (6_371_000.0 + 2.0, zenith_deg.to_radians().cos());
            let to = |h: f64| -r0 * mu + ((6_371_000.0 + h).powi(2) - r0 * r0 * (1.0 - mu * mu)).sqrt();
            to(2000.0) - to(1000.0)
        };
        for zenith_deg in [0.0, 60.0] {
            let tau = 0.001 * path(zenith_deg);
            let (clear, cloudy) = (sky(zenith_deg, Vec::new()), sky(zenith_deg, vec![layer.clone()]));
            let (clear, cloudy) = (SkyLight::new(&clear), SkyLight::new(&cloudy));
            let below = DVec3::new(0.0, 0.0, 2.0);
            let ratio = cloudy.sun_colors(below)[0] / clear.sun_colors(below)[0];
            for channel in [ratio.x, ratio.y, ratio.z] {
                let want = (-tau).exp();
                assert!((channel / want - 1.0).abs() < 1e-5, "{zenith_deg}°: {ratio} vs {want}");
            }
            let above = DVec3::new(0.0, 0.0, 2500.0);
            assert_eq!(cloudy.sun_colors(above), clear.sun_colors(above), "{zenith_deg}°");
            // The sky's irradiance (the ambient) does not see the clouds yet.
            let lit = |light: &SkyLight<'_>| {
                light
                    .lighting(below, Shading::Phong, SpecularModel::Blinn)
                    .model
                    .ambient
            };
            assert_eq!(lit(&cloudy), lit(&clear));
        }
    }
}
