//! Everything needed to draw one frame, in `f64`: the renderer's only input.

use glam::{DQuat, DVec3};

use crate::atmosphere::body::cast::cast_irradiance;
use crate::atmosphere::body::{Body, BodyInShadow};
use crate::atmosphere::clouds::CloudLayer;
use crate::atmosphere::empirical::{EmpiricalAtmosphere, EmpiricalStar};
use crate::atmosphere::planet_shadow::PlanetShadow;
use crate::atmosphere::rings::Rings;
use crate::atmosphere::surface::Surface;
use crate::atmosphere::{Atmosphere, Eclipser, Sun};
use crate::camera::Camera;
use crate::classic::scene::ObjectLayer;
use crate::color::LinearRgb;
use crate::display::DisplaySettings;
use crate::flare::FlareLayer;
use crate::sky::gradient::GradientSkyState;
use crate::sky::night::NightLayer;

/// The sky model drawn behind everything.
#[derive(Debug, Clone, PartialEq)]
pub enum Sky {
    /// The keyframed gradient sky of seed 002.
    Gradient(GradientSkyState),
    /// A physically based atmosphere around a planet, lit by one or more suns.
    Atmosphere(AtmosphereSky),
    /// The seed's own empirical atmosphere model (seed 000, version 3.1;
    /// [`crate::atmosphere::empirical`]).
    Empirical(EmpiricalSky),
    /// One colour everywhere, as a GL program's `glClearColor` (radiance, or GL units in a
    /// classic scene).
    Clear(LinearRgb),
}

impl Sky {
    /// The gradient sky's radiance along a unit view direction in the local frame — the
    /// reference the GPU gradient pass is tested against. `None` for the atmospheres, whose
    /// radiance depends on where the camera is: use
    /// [`Reference`](crate::atmosphere::reference::Reference) or [`EmpiricalSky::radiance`] for
    /// them.
    pub fn gradient_radiance(&self, view: DVec3) -> Option<LinearRgb> {
        match self {
            Self::Gradient(sky) => Some(sky.radiance(view)),
            Self::Atmosphere(_) | Self::Empirical(_) | Self::Clear(_) => None,
        }
    }
}

/// The most suns a frame may have (the GPU passes loop over a fixed-size array).
pub const MAX_SUNS: usize = 8;

/// A planet's atmosphere and its suns, in the same world frame as the camera.
#[derive(Debug, Clone, PartialEq)]
pub struct AtmosphereSky {
    /// The planet (posed in the world frame), its medium and the model wavelengths.
    pub atmosphere: Atmosphere,
    /// The suns, world-frame directions; 0 to [`MAX_SUNS`].
    pub suns: Vec<Sun>,
    /// Cloud layers inside the air, 0 to
    /// [`MAX_CLOUD_LAYERS`](crate::atmosphere::clouds::MAX_CLOUD_LAYERS).
    pub clouds: Vec<CloudLayer>,
    /// Bodies that can pass in front of the suns (the Moon at a real date), world frame, 0 to
    /// [`MAX_ECLIPSERS`](crate::atmosphere::eclipse::MAX_ECLIPSERS): where one hides part of a
    /// sun, the air, the ground and everything lit there get that much less of it
    /// ([`crate::atmosphere::eclipse`]).
    pub eclipsers: Vec<Eclipser>,
    /// Airless bodies drawn beside the planet, world frame, 0 to
    /// [`MAX_BODIES`](crate::atmosphere::body::MAX_BODIES) ([`crate::atmosphere::body`]): lit by
    /// the suns, shadowed by the planet and each other. Each is also an eclipser, the first
    /// `eclipsers` in the same order: add them with [`Self::add_body`].
    pub bodies: Vec<Body>,
    /// The planet's rings, if it has any ([`crate::atmosphere::rings`]): drawn lit by the suns,
    /// dimming what lies behind them and shadowing the globe.
    pub rings: Option<Rings>,
    /// The planet's surface, if the ground is more than the medium's `ground_albedo` everywhere
    /// ([`crate::atmosphere::surface`]): albedo and water over the globe, the suns' glint.
    pub surface: Option<Surface>,
}

impl AtmosphereSky {
    /// Adds `body`, and the same body among the eclipsers (after the bodies before it), so it
    /// hides the suns from the air, the ground and the other bodies.
    pub fn add_body(&mut self, body: Body) {
        self.eclipsers.insert(self.bodies.len(), body.eclipser());
        self.bodies.push(body);
    }

    /// Adds each body's light on the planet (moonlight) as a sun seen from world-frame point `at`
    /// (usually the camera, or the planet's centre for a camera far out): towards the body's
    /// centre, the angular radius of its volumetric mean radius, no disc of its own (the body
    /// is drawn), [`Sun::from_body`] naming it, and the irradiance its sunlit face sends to
    /// `at` ([`crate::atmosphere::body::cast`]) under the suns already there that are not
    /// bodies' lights, their shadows and the planet's light included. Only the bodies whose
    /// index `wanted` takes are summed; a body that sends none, or that `at` is inside, is left
    /// out, and so is every body once there are [`MAX_SUNS`] suns. The bodies' lights already
    /// there are replaced. Call it after the bodies are placed and lit ([`Self::add_body`],
    /// [`Self::light_bodies_in_planet_shadow`]); it costs milliseconds of CPU per body
    /// (docs/PERFORMANCE.md, "A body's light").
    pub fn add_body_lights(&mut self, at: DVec3, wanted: impl Fn(usize) -> bool) {
        self.suns.retain(|s| s.from_body.is_none());
        let planet = &self.atmosphere.planet;
        let suns: Vec<Sun> = self
            .suns
            .iter()
            .map(|s| Sun {
                direction: planet.direction_to_planet_frame(s.direction),
                ..*s
            })
            .collect();
        let bodies: Vec<Body> = self.bodies.iter().map(|b| b.to_planet_frame(planet)).collect();
        let rings = self.rings.as_ref();
        let q = planet.to_planet_frame(at);
        for (index, body) in self.bodies.iter().enumerate().filter(|(i, _)| wanted(*i)) {
            if self.suns.len() >= MAX_SUNS {
                return;
            }
            // Zero from inside the body's reach, so `at` lies outside it where this is positive.
            let irradiance = cast_irradiance(q, index, &suns, planet, rings, &bodies);
            if irradiance.max_element() > 0.0 {
                let to_body = body.center - at;
                let distance = to_body.length();
                self.suns.push(Sun {
                    direction: to_body / distance,
                    angular_radius: (body.mean_radius() / distance).asin(),
                    irradiance,
                    limb_darkening: 0.0,
                    disc: false,
                    from_body: Some(index),
                });
            }
        }
    }

    /// Gives every body that stands in the planet's shadow of one of the suns (its penumbra
    /// reaching it: [`Body::shadowing_sun`]) the light inside that shadow
    /// ([`Body::planet_shadow`]), `profile(atmosphere, sun, distance_m)` being the shadow
    /// `distance_m` behind the planet — usually [`PlanetShadow::new`] with the default settings,
    /// which takes tens of milliseconds (docs/PERFORMANCE.md), so cache it across frames. Other
    /// bodies lose any shadow they had.
    pub fn light_bodies_in_planet_shadow(&mut self, mut profile: impl FnMut(&Atmosphere, &Sun, f64) -> PlanetShadow) {
        for body in &mut self.bodies {
            body.planet_shadow = body
                .shadowing_sun(&self.suns, &self.atmosphere.planet)
                .map(|(sun, distance_m)| BodyInShadow {
                    sun,
                    axis: -self.suns[sun].direction.normalize(),
                    profile: profile(&self.atmosphere, &self.suns[sun], distance_m),
                });
        }
    }

    /// Checks the atmosphere, every sun, every eclipser and body and their numbers.
    pub fn validate(&self) -> Result<(), crate::error::CoreError> {
        self.atmosphere.validate()?;
        if self.suns.len() > MAX_SUNS {
            return Err(crate::error::CoreError::Invalid {
                field: "suns",
                value: format!("{} suns", self.suns.len()),
                rule: "at most 8 suns",
            });
        }
        self.suns.iter().try_for_each(Sun::validate)?;
        if self.eclipsers.len() > crate::atmosphere::eclipse::MAX_ECLIPSERS {
            return Err(crate::error::CoreError::Invalid {
                field: "eclipsers",
                value: format!("{} eclipsers", self.eclipsers.len()),
                rule: "at most 4 eclipsing bodies",
            });
        }
        self.eclipsers.iter().try_for_each(Eclipser::validate)?;
        crate::atmosphere::body::validate_bodies(&self.bodies, &self.atmosphere.planet)?;
        if self.bodies.iter().zip(&self.eclipsers).any(|(b, e)| b.eclipser() != *e)
            || self.eclipsers.len() < self.bodies.len()
        {
            return Err(crate::error::CoreError::Invalid {
                field: "bodies",
                value: format!("{} bodies, {} eclipsers", self.bodies.len(), self.eclipsers.len()),
                rule: "each body must also be the eclipser of the same index (AtmosphereSky::add_body)",
            });
        }
        if let Some(sun) = self
            .suns
            .iter()
            .find(|s| s.from_body.is_some_and(|b| b >= self.bodies.len()))
        {
            return Err(crate::error::CoreError::Invalid {
                field: "suns.from_body",
                value: format!("body {:?} of {}", sun.from_body, self.bodies.len()),
                rule: "must be one of the sky's bodies",
            });
        }
        if let Some(shadow) = self
            .bodies
            .iter()
            .filter_map(|b| b.planet_shadow.as_ref())
            .find(|s| s.sun >= self.suns.len())
        {
            return Err(crate::error::CoreError::Invalid {
                field: "body.planet_shadow.sun",
                value: format!("sun {} of {}", shadow.sun, self.suns.len()),
                rule: "must be one of the sky's suns",
            });
        }
        if let Some(rings) = &self.rings {
            rings.validate(&self.atmosphere.planet)?;
        }
        if let Some(surface) = &self.surface {
            surface.validate()?;
        }
        crate::atmosphere::clouds::validate_layers(&self.clouds)
    }
}

/// The most stars an [`EmpiricalSky`] may have (the seed itself takes 3, `_lights`, seed line 297;
/// firmament's GPU pass takes as many as it takes suns).
pub const MAX_EMPIRICAL_STARS: usize = MAX_SUNS;

/// Luminance of the seed colour 1 (white) in the HDR target, cd/m², unless a scene says
/// otherwise: a bright daylight sky, so the seed's saturated limb (1) and its zenith (≈ 0.2) land
/// where daylight exposures (EV100 12–14) put them.
pub const EMPIRICAL_DEFAULT_LUMINANCE: f64 = 10_000.0;

/// The seed's own atmosphere model, the empirical one, around a posed planet: the sky firmament
/// draws for `atmosphere.model = "seed"`.
///
/// The seed works in its planet frame ([`crate::atmosphere::empirical`]: origin at the planet
/// centre, `z` along the polar axis, metres); `center` and `orientation` place that frame in the
/// world, like [`Planet`](crate::atmosphere::Planet)'s pose, so a world-frame camera maps into it.
#[derive(Debug, Clone, PartialEq)]
pub struct EmpiricalSky {
    /// The seed's parameters (radii, height, view depth, B0, overglow).
    pub atmosphere: EmpiricalAtmosphere,
    /// Planet centre in world coordinates, metres.
    pub center: DVec3,
    /// Rotation from the planet frame to the world frame.
    pub orientation: DQuat,
    /// The stars (the seed's `light_*` uniforms), **planet frame**; 0 to [`MAX_EMPIRICAL_STARS`].
    pub stars: Vec<EmpiricalStar>,
    /// Luminance that the seed's colour 1 becomes in the HDR target, cd/m² (the seed's colours
    /// are unitless display values in [0, 1]; see [`EMPIRICAL_DEFAULT_LUMINANCE`]).
    pub luminance: f64,
}

impl EmpiricalSky {
    /// Checks the seed's parameters, the pose, the number of stars, every star (finite
    /// position, radius > 0 m, finite non-zero direction, colour finite and >= 0) and the
    /// luminance (finite, > 0 cd/m²). Field names start with `seed.` (the atmosphere's own with
    /// `atmosphere.seed.`).
    pub fn validate(&self) -> Result<(), crate::error::CoreError> {
        let invalid = |field, value: String, rule| Err(crate::error::CoreError::Invalid { field, value, rule });
        self.atmosphere.validate()?;
        if !self.center.is_finite() {
            return invalid("seed.center", format!("{:?}", self.center.to_array()), "must be finite");
        }
        if !(self.orientation.is_finite() && self.orientation.length_squared() > 0.0) {
            return invalid(
                "seed.orientation",
                format!("{:?}", self.orientation.to_array()),
                "must be a finite rotation",
            );
        }
        if self.stars.len() > MAX_EMPIRICAL_STARS {
            return invalid("seed.stars", format!("{} stars", self.stars.len()), "at most 8 stars");
        }
        for star in &self.stars {
            if !star.position.is_finite() {
                return invalid(
                    "seed.stars.position",
                    format!("{:?}", star.position.to_array()),
                    "must be finite (metres)",
                );
            }
            if !(star.radius.is_finite() && star.radius > 0.0) {
                return invalid(
                    "seed.stars.radius",
                    star.radius.to_string(),
                    "must be a finite radius > 0 m",
                );
            }
            if !(star.direction.is_finite() && star.direction.length_squared() > 0.0) {
                return invalid(
                    "seed.stars.direction",
                    format!("{:?}", star.direction.to_array()),
                    "must be a finite, non-zero direction",
                );
            }
            if !(star.color.is_finite() && star.color.min_element() >= 0.0) {
                return invalid(
                    "seed.stars.color",
                    format!("{:?}", star.color.to_array()),
                    "every channel must be finite and >= 0",
                );
            }
        }
        if !(self.luminance.is_finite() && self.luminance > 0.0) {
            return invalid(
                "seed.luminance",
                self.luminance.to_string(),
                "must be a finite luminance > 0 cd/m²",
            );
        }
        Ok(())
    }

    /// A world-space point in the planet frame, metres.
    pub fn to_planet_frame(&self, world: DVec3) -> DVec3 {
        self.orientation.normalize().inverse() * (world - self.center)
    }

    /// A world-space direction in the planet frame.
    pub fn direction_to_planet_frame(&self, world: DVec3) -> DVec3 {
        self.orientation.normalize().inverse() * world
    }

    /// The seed's `(rgb, alpha)` for a world-frame view ray ([`EmpiricalAtmosphere::color`]):
    /// unitless colour in [0, 1] and alpha 0 or 1.
    pub fn color(&self, origin: DVec3, direction: DVec3) -> (DVec3, f64) {
        self.atmosphere.color(
            self.to_planet_frame(origin),
            self.direction_to_planet_frame(direction),
            &self.stars,
        )
    }

    /// What the GPU pass writes for a world-frame view ray with nothing behind the sky: the
    /// seed's colour (blended `ONE, ONE_MINUS_SRC_ALPHA` over black, i.e. the colour itself) times
    /// [`luminance`](Self::luminance), linear RGB in cd/m².
    pub fn radiance(&self, origin: DVec3, direction: DVec3) -> LinearRgb {
        let (rgb, _) = self.color(origin, direction);
        let rgb = rgb * self.luminance;
        LinearRgb::new(rgb.x, rgb.y, rgb.z)
    }
}

/// One frame: where we look from, what sky we see, and how it is shown.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// The camera (its aspect is overridden by the render target's).
    pub camera: Camera,
    /// The sky.
    pub sky: Sky,
    /// Exposure and tone curve.
    pub display: DisplaySettings,
    /// Objects in front of the sky, their lighting and fog.
    pub objects: ObjectLayer,
    /// Lens flares of the suns and lights.
    pub flares: FlareLayer,
    /// Stars and the Moon, added over the sky where nothing nearer is drawn
    /// ([`NightLayer::default`]: none).
    pub night: NightLayer,
}

impl Frame {
    /// `sky` seen by `camera`, shown with the default display settings (exposure 1, no tone
    /// curve, sRGB), with no objects, flares or night sky; the `with_` methods add them.
    pub fn new(camera: Camera, sky: Sky) -> Self {
        Self {
            camera,
            sky,
            display: DisplaySettings::default(),
            objects: ObjectLayer::default(),
            flares: FlareLayer::default(),
            night: NightLayer::default(),
        }
    }

    /// The same frame shown with `display`.
    #[must_use]
    pub fn with_display(self, display: DisplaySettings) -> Self {
        Self { display, ..self }
    }

    /// The same frame with `objects` in front of the sky.
    #[must_use]
    pub fn with_objects(self, objects: ObjectLayer) -> Self {
        Self { objects, ..self }
    }

    /// The same frame with `flares`.
    #[must_use]
    pub fn with_flares(self, flares: FlareLayer) -> Self {
        Self { flares, ..self }
    }

    /// The same frame with `night` (stars and the Moon).
    #[must_use]
    pub fn with_night(self, night: NightLayer) -> Self {
        Self { night, ..self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Planet;

    #[test]
    fn a_frame_built_with_new_and_with_is_the_literal() {
        let camera = Camera::from_heading_pitch(DVec3::Z, 1.0, 0.1)
            .with_fov_y(0.7)
            .with_clip_planes(0.5, Some(9.0));
        let display = DisplaySettings {
            exposure: crate::display::Exposure::from_ev100(14.0),
            ..Default::default()
        };
        let sky = Sky::Clear(LinearRgb::new(0.1, 0.2, 0.3));
        let built = Frame::new(camera, sky.clone()).with_display(display);
        let literal = Frame {
            camera: Camera {
                fov_y: 0.7,
                near: 0.5,
                far: Some(9.0),
                ..Camera::from_heading_pitch(DVec3::Z, 1.0, 0.1)
            },
            sky,
            display,
            objects: ObjectLayer::default(),
            flares: FlareLayer::default(),
            night: NightLayer::default(),
        };
        assert_eq!(built, literal);
    }

    fn empirical_sky() -> EmpiricalSky {
        let a = EmpiricalAtmosphere::seed_earth();
        let planet = Planet::spheroid(a.equatorial_radius, a.polar_radius, a.height).posed_at(0.6, -1.2);
        let sun = planet.direction_to_planet_frame(DVec3::new(0.3, -0.8, 0.5).normalize());
        EmpiricalSky {
            atmosphere: a,
            center: planet.center,
            orientation: planet.orientation,
            stars: vec![EmpiricalStar::at(sun * 1.5e11, 7.0e8, DVec3::splat(10.0))],
            luminance: EMPIRICAL_DEFAULT_LUMINANCE,
        }
    }

    #[test]
    fn empirical_sky_maps_the_world_into_the_planet_frame() {
        let sky = empirical_sky();
        assert_eq!(sky.validate(), Ok(()));
        // The world origin is on the surface, the world +z its geodetic up (a ray straight up
        // from 2 m is the seed's zenith ray there).
        let o = sky.to_planet_frame(DVec3::new(0.0, 0.0, 2.0));
        let d = sky.direction_to_planet_frame(DVec3::Z);
        assert_eq!(
            sky.color(DVec3::new(0.0, 0.0, 2.0), DVec3::Z),
            sky.atmosphere.color(o, d, &sky.stars)
        );
        let (rgb, _) = sky.color(DVec3::new(0.0, 0.0, 2.0), DVec3::Z);
        assert!(rgb.max_element() > 0.0);
        let radiance = sky.radiance(DVec3::new(0.0, 0.0, 2.0), DVec3::Z);
        assert_eq!(
            DVec3::new(radiance.r, radiance.g, radiance.b),
            rgb * EMPIRICAL_DEFAULT_LUMINANCE
        );
        assert_eq!(Sky::Empirical(sky).gradient_radiance(DVec3::Z), None);
    }

    #[test]
    fn empirical_sky_validation_names_the_field() {
        let field = |sky: EmpiricalSky| match sky.validate() {
            Err(crate::error::CoreError::Invalid { field, .. }) => field,
            other => panic!("{other:?}"),
        };
        let good = empirical_sky();
        let mut sky = good.clone();
        sky.atmosphere.view_depth = 0.0;
        assert_eq!(field(sky), "atmosphere.seed.view_depth");
        let mut sky = good.clone();
        sky.luminance = f64::NAN;
        assert_eq!(field(sky), "seed.luminance");
        let mut sky = good.clone();
        sky.center = DVec3::INFINITY;
        assert_eq!(field(sky), "seed.center");
        let mut sky = good.clone();
        sky.stars[0].radius = 0.0;
        assert_eq!(field(sky), "seed.stars.radius");
        let mut sky = good.clone();
        sky.stars[0].color = DVec3::new(1.0, -1.0, 0.0);
        assert_eq!(field(sky), "seed.stars.color");
        let mut sky = good.clone();
        sky.stars[0].direction = DVec3::ZERO;
        assert_eq!(field(sky), "seed.stars.direction");
        let mut sky = good;
        sky.stars = vec![sky.stars[0]; MAX_EMPIRICAL_STARS + 1];
        assert_eq!(field(sky), "seed.stars");
    }
}
