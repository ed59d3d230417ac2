//! From a validated scene to the core's [`Frame`]: degrees become radians, times become seconds.
//!
//! The scene model (`crate::model`) holds the file's keys in the file's units; this module and its
//! steps turn them into the core's types, checking each value on the way (each error names the
//! scene key): `atmosphere` (`[planet]`, `[atmosphere]`, `[[suns]]`, `[[clouds]]` →
//! [`AtmosphereSky`], or the seed's [`EmpiricalSky`]; the clouds' wind drift in
//! `atmosphere::clouds`), `time` (`[time]` → the frame's moment and the real sun), `objects`
//! (`[lighting]`, `[[lights]]`, `[[objects]]`, `[fog]`, `[shadows]`, `[ground]` → the object
//! layer), `flare` (`[flare]` → the flare layer) and `night` (the stars and the Moon at a real
//! instant).

pub(crate) mod atmosphere;
pub(crate) mod bodies;
pub(crate) mod flare;
mod lunar_eclipse;
mod night;
pub(crate) mod objects;
pub(crate) mod time;

pub use atmosphere::{EMPIRICAL_STAR_DISTANCE, EMPIRICAL_STAR_INTENSITY};
pub use night::MOON_DISPLAY_RADIANCE;
pub use time::{add_seconds, parse_date_time};

use firmament_core::astro::spa::SolarPosition;
use firmament_core::astro::{CivilDateTime, Instant};
use firmament_core::atmosphere::Planet;
use firmament_core::auto_exposure::{AutoExposure, ExposureMode};
use firmament_core::camera::orientation_from_heading_pitch_roll;
use firmament_core::display::{DisplaySettings, Exposure};
use firmament_core::frame::{AtmosphereSky, EmpiricalSky, Sky};
use firmament_core::sky::gradient::{DayCycle, GradientShape, GradientSkyState, SkyBands, SkyKeyframe};
use firmament_core::sky::sun::{SolarPath, SunDisc};
use firmament_core::{Camera, Frame, TimeOfDay};
use glam::DVec3;

use self::time::Moment;
use crate::checks::time_of_day;
use crate::error::SceneError;
use crate::model::{AtmosphereModelName, ExposureModeName, KeyframesBy, Scene, SkyModelName};

impl Scene {
    /// The scene's own time of day (`time.time_of_day`).
    pub fn time_of_day(&self) -> Result<TimeOfDay, SceneError> {
        time_of_day("time.time_of_day", &self.time.time_of_day)
    }

    /// The camera, with the aspect ratio of `render.width / render.height`.
    pub fn camera(&self) -> Camera {
        let c = &self.camera;
        Camera {
            position: DVec3::from_array(c.position),
            orientation: orientation_from_heading_pitch_roll(
                c.heading_deg.to_radians(),
                c.pitch_deg.to_radians(),
                c.roll_deg.to_radians(),
            ),
            fov_y: c.fov_y_deg.to_radians(),
            aspect: f64::from(self.render.width) / f64::from(self.render.height),
            near: c.near,
            far: c.far,
        }
    }

    /// The gradient sky's band layout.
    pub fn gradient_shape(&self) -> GradientShape {
        let g = &self.sky.gradient;
        GradientShape {
            zenith_start: g.zenith_start_deg.to_radians(),
            horizon_half_width: g.horizon_half_width_deg.to_radians(),
            ground_start: g.ground_start_deg.to_radians(),
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
                    time: time_of_day(&format!("sky.gradient.keyframes[{i}].time"), &k.time)?,
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
            latitude: self.sun.latitude_deg.to_radians(),
            declination: self.sun.declination_deg.to_radians(),
        }
    }

    /// Exposure and tone curve.
    pub fn display_settings(&self) -> DisplaySettings {
        let exposure = match self.display.ev100 {
            Some(ev) => Exposure::from_ev100(ev),
            None => Exposure::multiplier(self.display.exposure),
        };
        let display = &self.display;
        let exposure_mode = match display.exposure_mode {
            ExposureModeName::Manual => ExposureMode::Manual,
            ExposureModeName::Auto => ExposureMode::Auto(AutoExposure {
                ev100_min: display.auto_ev_min,
                ev100_max: display.auto_ev_max,
                compensation_ev: display.auto_compensation,
                speed_up_ev_per_s: display.auto_speed_up,
                speed_down_ev_per_s: display.auto_speed_down,
            }),
        };
        DisplaySettings {
            exposure,
            exposure_mode,
            tone_curve: display.tone_curve,
            encoding: display.encoding,
            bloom: display.bloom,
            night_vision: display.night_vision,
        }
    }

    /// The planet (posed so that the world frame is East-North-Up at `planet.latitude`,
    /// `planet.longitude`), its atmosphere, the suns of `[[suns]]` and the cloud layers of
    /// `[[clouds]]` (their coverage maps loaded): the body's values with the scene's overrides;
    /// with `time.date_time`, the first sun (or the body's own when there is none) stands where
    /// the real sun stood. At the scene's own moment the clouds have not drifted (see
    /// [`frame_at`](Self::frame_at)).
    pub fn atmosphere_sky(&self) -> Result<AtmosphereSky, SceneError> {
        let instant = match self.date_time()? {
            Some(civil) => Some(self.instant(&civil)?),
            None => None,
        };
        let real_sun = instant.as_ref().map(|i| self.real_sun(i)).transpose()?;
        self.atmosphere_sky_with(real_sun.as_ref(), instant.as_ref())
    }

    /// [`Self::atmosphere_sky`] with the first sun moved to `real_sun` (refracted, as seen) and
    /// the bodies where they stand at `instant`.
    fn atmosphere_sky_with(
        &self,
        real_sun: Option<&SolarPosition>,
        instant: Option<&Instant>,
    ) -> Result<AtmosphereSky, SceneError> {
        let mut sky = atmosphere::sky(self)?;
        if let Some(position) = real_sun {
            let direction = position.direction_enu(true);
            match sky.suns.first_mut() {
                Some(sun) => sun.direction = direction,
                None => sky.suns.push(self.planet.body.sun(direction)),
            }
        }
        bodies::add_bodies(self, instant, &mut sky)?;
        bodies::light_in_planet_shadow(self, instant, real_sun, &mut sky);
        bodies::add_lights(self, &mut sky);
        Ok(sky)
    }

    /// The gradient sky at clock time `clock`, its sun where `real_sun` is when given (else on
    /// `[sun]`'s path), its colours at the keyframes' time for that sun (see
    /// [`KeyframesBy`]).
    fn gradient_sky(&self, clock: TimeOfDay, real_sun: Option<&SolarPosition>) -> Result<GradientSkyState, SceneError> {
        let path = self.solar_path();
        let (direction, solar_time) = match real_sun {
            Some(p) => {
                // Local apparent solar time from the hour angle (0 at the meridian, west +).
                let hour_angle = (p.topocentric_hour_angle_deg + 180.0).rem_euclid(360.0) - 180.0;
                let solar = TimeOfDay::from_hours(12.0 + hour_angle / 15.0).unwrap_or(clock);
                (p.direction_enu(true), solar)
            }
            None => (path.direction_at(clock), clock),
        };
        let keyframe_time = match self.sky.gradient.by {
            KeyframesBy::Clock => solar_time,
            KeyframesBy::SunElevation => {
                let elevation = direction.z.clamp(-1.0, 1.0).asin();
                path.time_at_elevation(elevation, solar_time.hours() < 12.0)
            }
        };
        let bands = self.day_cycle()?.bands_at(keyframe_time);
        let s = &self.sun;
        let sun = SunDisc {
            direction,
            angular_radius: s.angular_radius_deg.to_radians(),
            disc_radiance: bands.sun.scale(s.disc_intensity),
            glow_radiance: bands.sun.scale(s.glow_intensity),
            glow_falloff: s.glow_falloff_deg.to_radians(),
            edge_softness: s.edge_softness,
        };
        Ok(GradientSkyState {
            shape: self.gradient_shape(),
            bands,
            sun,
        })
    }

    /// The seed's own atmosphere model, the empirical one, around the scene's planet
    /// (`atmosphere.model = "seed"`): the body's seed values with `[planet]`'s radii and
    /// `[atmosphere.seed]`'s overrides, the `[[suns]]` as the seed's stars.
    pub fn empirical_sky(&self) -> Result<EmpiricalSky, SceneError> {
        atmosphere::empirical_sky(self, &self.atmosphere_sky()?)
    }

    /// The camera's geodetic altitude above the surface of the scene's planet, metres (negative
    /// inside it); meaningful for atmosphere scenes (the seed's planet when
    /// `atmosphere.model = "seed"`).
    pub fn camera_altitude(&self) -> Result<f64, SceneError> {
        let planet = self.atmosphere_planet()?;
        Ok(planet.altitude(planet.to_planet_frame(DVec3::from_array(self.camera.position))))
    }

    /// The planet the atmosphere is drawn around, posed in the world frame (the seed's planet when
    /// `atmosphere.model = "seed"`), whatever `sky.model` is.
    pub fn atmosphere_planet(&self) -> Result<Planet, SceneError> {
        Ok(match self.atmosphere.model {
            AtmosphereModelName::Physical => self.atmosphere_sky()?.atmosphere.planet,
            AtmosphereModelName::Empirical => atmosphere::empirical_planet(&self.empirical_sky()?),
        })
    }

    /// The planet under the sky, posed in the world frame, when `sky.model = "atmosphere"`;
    /// `None` for the gradient and clear skies (their ground is the plane `up = 0`).
    pub fn planet(&self) -> Result<Option<Planet>, SceneError> {
        match self.sky.model {
            SkyModelName::Atmosphere => self.atmosphere_planet().map(Some),
            SkyModelName::Gradient | SkyModelName::Clear => Ok(None),
        }
    }

    /// Everything needed to draw the scene at `time` (its own time when `None`; on a scene with
    /// `time.date_time`, that clock time on the same date), with the lens flares of `[flare]`
    /// and its sources (the suns, the lights marked `flare`). Without a date the atmosphere's suns
    /// do not move with the time, objects' spins and the gradient sky's sun do; with one, the
    /// real sun moves too, and the wind carries the clouds by `wind × (the frame's instant − the
    /// scene's own)`. Builds the built-in meshes and loads mesh, texture and coverage-map files,
    /// so a bad or missing file is reported here.
    pub fn frame_at(&self, time: Option<TimeOfDay>) -> Result<Frame, SceneError> {
        self.frame_for(self.moment(time)?)
    }

    /// Everything needed to draw the scene at a real date and time (whether or not the scene has
    /// `time.date_time`): the real sun, moon and stars over `[planet]`'s latitude and longitude,
    /// the clouds carried by their wind since the scene's own `time.date_time` (J2000.0 for a
    /// scene without one).
    pub fn frame_at_date_time(&self, date_time: &CivilDateTime) -> Result<Frame, SceneError> {
        self.frame_for(self.moment_at(date_time)?)
    }

    /// Seconds of wind at `moment`: since the scene's own `time.date_time` (J2000.0 without
    /// one) when the moment has an instant, else 0 (see `atmosphere::clouds`).
    fn wind_seconds(&self, moment: &Moment) -> Result<f64, SceneError> {
        let origin = match (moment.instant, self.date_time()?) {
            (Some(_), Some(civil)) => Some(self.instant(&civil)?.jd),
            _ => None,
        };
        Ok(atmosphere::clouds::wind_seconds(moment.instant.map(|i| i.jd), origin))
    }

    fn frame_for(&self, moment: Moment) -> Result<Frame, SceneError> {
        let camera = self.camera();
        let real_sun = moment.instant.map(|i| self.real_sun(&i)).transpose()?;
        let sky = match self.sky.model {
            SkyModelName::Gradient => Sky::Gradient(self.gradient_sky(moment.clock, real_sun.as_ref())?),
            SkyModelName::Atmosphere => {
                let mut sky = self.atmosphere_sky_with(real_sun.as_ref(), moment.instant.as_ref())?;
                match self.atmosphere.model {
                    AtmosphereModelName::Physical => {
                        atmosphere::clouds::drift(&mut sky, self.wind_seconds(&moment)?);
                        if let Some(instant) = &moment.instant {
                            // A Moon body sends its own light (bodies::add_lights).
                            if !bodies::has_moon(self) {
                                night::add_moonlight(self, instant, &camera, &mut sky);
                                night::add_eclipsing_moon(self, instant, &camera, &mut sky);
                            }
                        }
                        Sky::Atmosphere(sky)
                    }
                    AtmosphereModelName::Empirical => Sky::Empirical(atmosphere::empirical_sky(self, &sky)?),
                }
            }
            SkyModelName::Clear => {
                let [r, g, b, _] = self.sky.clear_color.rgba();
                Sky::Clear(firmament_core::LinearRgb::new(r, g, b))
            }
        };
        let flares = flare::flare_layer(self, &camera, &sky)?;
        let objects = objects::object_layer(self, moment.clock, &sky)?;
        let night = moment
            .instant
            .map(|instant| night::night_layer(self, &instant, &camera, &sky))
            .unwrap_or_default();
        Ok(Frame {
            camera,
            sky,
            display: self.display_settings(),
            objects,
            flares,
            night,
        })
    }
}
