//! From a validated scene to the core's [`Frame`]: degrees become radians, times become seconds.

use firmament_core::camera::orientation_from_heading_pitch_roll;
use firmament_core::display::{DisplaySettings, Exposure};
use firmament_core::frame::{AtmosphereSky, SeedSky, Sky};
use firmament_core::gradient_sky::{DayCycle, GradientShape, GradientSkyState, SkyBands, SkyKeyframe};
use firmament_core::sun::{SolarPath, SunDisc};
use firmament_core::{Camera, Frame, TimeOfDay};
use glam::DVec3;

use crate::error::SceneError;
use crate::model::{AtmosphereModelName, Scene, SkyModelName};
use crate::validate::time;

impl Scene {
    /// The scene's own time of day (`time.time_of_day`).
    pub fn time_of_day(&self) -> Result<TimeOfDay, SceneError> {
        time("time.time_of_day", &self.time.time_of_day)
    }

    /// The camera, with the aspect ratio of `render.width / render.height`.
    pub fn camera(&self) -> Camera {
        let c = &self.camera;
        Camera {
            position: DVec3::from_array(c.position),
            orientation: orientation_from_heading_pitch_roll(
                c.heading.to_radians(),
                c.pitch.to_radians(),
                c.roll.to_radians(),
            ),
            fov_y: c.fov_y.to_radians(),
            aspect: f64::from(self.render.width) / f64::from(self.render.height),
            near: c.near,
            far: c.far,
        }
    }

    /// The gradient sky's band layout.
    pub fn gradient_shape(&self) -> GradientShape {
        let g = &self.sky.gradient;
        GradientShape {
            zenith_start: g.zenith_start.to_radians(),
            horizon_half_width: g.horizon_half_width.to_radians(),
            ground_start: g.ground_start.to_radians(),
            upper_exponent: g.upper_exponent,
            lower_exponent: g.lower_exponent,
            blend: g.blend,
        }
    }

    /// The gradient sky's day/night cycle.
    pub fn day_cycle(&self) -> Result<DayCycle, SceneError> {
        let g = &self.sky.gradient;
        let keyframes = g
            .keyframes
            .iter()
            .enumerate()
            .map(|(i, k)| {
                Ok(SkyKeyframe {
                    time: time(&format!("sky.gradient.keyframes[{i}].time"), &k.time)?,
                    bands: SkyBands {
                        zenith: k.zenith.0,
                        upper: k.upper.0,
                        horizon: k.horizon.0,
                        lower: k.lower.0,
                        ground: k.ground.0,
                        sun: k.sun.0,
                    },
                })
            })
            .collect::<Result<Vec<_>, SceneError>>()?;
        DayCycle::new(keyframes, g.keyframe_blend)
            .map_err(|e| SceneError::invalid("sky.gradient.keyframes", "[...]", e.to_string()))
    }

    /// The sun's path over the day.
    pub fn solar_path(&self) -> SolarPath {
        SolarPath {
            latitude: self.sun.latitude.to_radians(),
            declination: self.sun.declination.to_radians(),
        }
    }

    /// Exposure and tone curve.
    pub fn display_settings(&self) -> DisplaySettings {
        let exposure = match self.display.ev100 {
            Some(ev) => Exposure::from_ev100(ev),
            None => Exposure::multiplier(self.display.exposure),
        };
        DisplaySettings {
            exposure,
            tone_curve: self.display.tone_curve,
            encoding: self.display.encoding,
        }
    }

    /// The planet (posed so that the world frame is East-North-Up at `planet.latitude`,
    /// `planet.longitude`), its atmosphere and the suns of `[[suns]]`: the body's values with the
    /// scene's overrides.
    pub fn atmosphere_sky(&self) -> Result<AtmosphereSky, SceneError> {
        crate::atmosphere::sky(self)
    }

    /// The seed's own atmosphere model around the scene's planet (`atmosphere.model = "seed"`):
    /// the body's seed values with `[planet]`'s radii and `[atmosphere.seed]`'s overrides, the
    /// `[[suns]]` as the seed's stars.
    pub fn seed_sky(&self) -> Result<SeedSky, SceneError> {
        crate::atmosphere::seed_sky(self, &self.atmosphere_sky()?)
    }

    /// The camera's geodetic altitude above the surface of the scene's planet, metres (negative
    /// inside it); meaningful for atmosphere scenes (the seed's planet when
    /// `atmosphere.model = "seed"`).
    pub fn camera_altitude(&self) -> Result<f64, SceneError> {
        let planet = match self.atmosphere.model {
            AtmosphereModelName::Physical => self.atmosphere_sky()?.atmosphere.planet,
            AtmosphereModelName::Seed => crate::atmosphere::seed_planet(&self.seed_sky()?),
        };
        Ok(planet.altitude(planet.to_planet_frame(DVec3::from_array(self.camera.position))))
    }

    /// Everything needed to draw the scene at `time` (its own time when `None`; the atmosphere's
    /// suns do not move with it, objects' spins and the gradient sky's sun do), with the lens
    /// flares of `[flare]` and its sources (the suns, the lights marked `flare`). Builds the
    /// built-in meshes and loads mesh and texture files, so a bad or missing file is reported
    /// here.
    pub fn frame_at(&self, time: Option<TimeOfDay>) -> Result<Frame, SceneError> {
        let time = match time {
            Some(t) => t,
            None => self.time_of_day()?,
        };
        let sky = match self.sky.model {
            SkyModelName::Gradient => {
                let bands = self.day_cycle()?.bands_at(time);
                let s = &self.sun;
                let sun = SunDisc {
                    direction: self.solar_path().direction_at(time),
                    angular_radius: s.angular_radius.to_radians(),
                    disc_radiance: bands.sun.scale(s.disc_intensity),
                    glow_radiance: bands.sun.scale(s.glow_intensity),
                    glow_falloff: s.glow_falloff.to_radians(),
                    edge_softness: s.edge_softness,
                };
                Sky::Gradient(GradientSkyState {
                    shape: self.gradient_shape(),
                    bands,
                    sun,
                })
            }
            SkyModelName::Atmosphere => match self.atmosphere.model {
                AtmosphereModelName::Physical => Sky::Atmosphere(self.atmosphere_sky()?),
                AtmosphereModelName::Seed => Sky::Seed(self.seed_sky()?),
            },
            SkyModelName::Clear => {
                let [r, g, b, _] = self.sky.clear_color.rgba();
                Sky::Clear(firmament_core::LinearRgb::new(r, g, b))
            }
        };
        let camera = self.camera();
        let flares = crate::flare::flare_layer(self, &camera, &sky)?;
        let objects = crate::objects::object_layer(self, time, &sky)?;
        Ok(Frame {
            camera,
            sky,
            display: self.display_settings(),
            objects,
            flares,
        })
    }
}
