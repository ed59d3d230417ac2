//! Bodies beside the planet: airless worlds (the Moon, a moon, an asteroid) drawn in the same
//! view as the planet, lit by every sun, shadowed by the planet, by its rings and by each other,
//! and hiding the suns, the air and the stars behind them.
//!
//! # Model
//! A body is an opaque ellipsoid (semi-axes `radii` along its own x, y and polar z axis, posed
//! by `orientation`) with one normal albedo per model wavelength and a reflectance law:
//!
//! - **Lambert**: `L = (A/π)·E·μ₀`;
//! - **Lommel–Seeliger**, the single-scattering law of a dark, porous regolith whose brightness
//!   does not fall towards the limb (Hapke, *Theory of Reflectance and Emittance Spectroscopy*,
//!   2nd ed. 2012, §9.2; Fairbairn 2005, *JRASC* 99, 92): `L = (A/π)·E·2μ₀/(μ₀ + μ)`;
//! - **Lunar**, the Moon's: Lommel–Seeliger times `f(α)`, a factor of the phase angle that gives
//!   the whole disc the Moon's measured phase curve ([`phase`]; `f(0) = 1`),
//!
//! `E` the sun's irradiance, `μ₀` and `μ` the cosines of the incidence and emergence angles and
//! `A` the **normal albedo** (the reflectance at normal incidence seen face-on, relative to a
//! white Lambert surface): every law gives `A·E/π` there, and for Lommel–Seeliger (and the Moon's)
//! `A` is also the geometric albedo. The night sky's Moon disc uses the same normalisation
//! ([`crate::sky::night::lommel_seeliger`]).
//!
//! Each sun reaches a point of a body dimmed by the planet, by the rings' shadow and by every
//! other body, as [`crate::atmosphere::eclipse`] computes for the air. The planet is an opaque
//! ball of its volumetric mean radius, unless the body carries the light inside the planet's
//! shadow ([`Body::planet_shadow`], set by
//! [`AtmosphereSky::light_bodies_in_planet_shadow`](crate::frame::AtmosphereSky::light_bodies_in_planet_shadow)):
//! then its umbra is the deep red of a lunar eclipse, sunlight bent into it through the planet's
//! air ([`crate::atmosphere::planet_shadow`]), the profile taken at the body's centre's distance
//! behind the planet (the Moon spans ±0.5 % of it).
//!
//! # Planet-shine
//! The planet's sunlit face lights the bodies too (earthshine, the Moon's ashen light): seen from
//! a body at distance `d` ≫ its mean radius `R` it is a point of light whose irradiance, face-on,
//! is `E_pl = p·E·(R/d)²·Φ(α)` ([`planetshine`]), `p` its geometric albedo
//! ([`Planet::geometric_albedo`]), `α` the phase angle at the planet between the sun and the
//! body, and `Φ(α) = (sin α + (π − α)·cos α)/π` the phase law of a Lambert sphere (Russell 1916,
//! *ApJ* 43, 173), the planet's clouds and air taken as a matte diffuser. It reaches a point of
//! the body by the same reflectance law as sunlight, with the cosine towards the planet. Earth,
//! full, lights the Moon with `0.434 × 1.3·10⁵ lx × (6371/384 400)² ≈ 15 lx`. Close moons (`d`
//! a few `R`) get it less exactly.
//!
//! # Their light on the planet
//! Each body's sunlit face lights the planet and the other bodies in turn (moonlight): [`cast`]
//! sums what the point sees of it, and the sky carries it as a sun without a disc of its own
//! that the body neither hides nor is lit by ([`Sun::from_body`]).

use std::f64::consts::PI;
use std::sync::Arc;

use glam::{DQuat, DVec3};

use crate::atmosphere::eclipse::Eclipser;
use crate::atmosphere::planet_shadow::{PlanetShadow, SHADOW_ENTRIES};
use crate::atmosphere::rings::Rings;
use crate::atmosphere::surface::SurfaceMap;
use crate::atmosphere::{Planet, Spectrum, Sun};
use crate::error::CoreError;
use crate::geometry::{Ellipsoid, Ray};

pub use air::{AirLight, AirSegment, BodyAir};

/// The most bodies a sky takes (they are its eclipsers too, and the GPU's uniform holds this
/// many: [`crate::atmosphere::eclipse::MAX_ECLIPSERS`]).
pub const MAX_BODIES: usize = crate::atmosphere::eclipse::MAX_ECLIPSERS;

/// The Moon's mean radius, metres (IAU WGCCRE 2015: 1737.4 km).
pub const MOON_RADIUS_M: f64 = 1_737_400.0;

/// The Moon's geometric albedo in V, 0.12 (Allen's *Astrophysical Quantities*, 4th ed. 2000,
/// §12.5), which for the Lommel–Seeliger law is also its normal albedo. The Moon's slight
/// reddening is left out, as it is for moonlight.
pub const MOON_ALBEDO: f64 = 0.12;

/// How a body's surface sends back the light it receives (the module docs give both laws).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Reflectance {
    /// A matte diffuser: radiance `∝ μ₀`.
    #[default]
    Lambert,
    /// A dark regolith: radiance `∝ 2μ₀/(μ₀ + μ)`, as bright at the limb as at the centre.
    LommelSeeliger,
    /// The Moon's: Lommel–Seeliger times the factor of its phase angle that gives the whole
    /// disc the Moon's measured phase curve ([`phase`]): a quarter moon is 0.09 of full, not 0.38.
    Lunar,
}

impl Reflectance {
    /// The code the shaders read (`BODY_REFLECTANCE_*` in the generated constants).
    pub const fn gpu_code(self) -> u32 {
        match self {
            Self::Lambert => 0,
            Self::LommelSeeliger => 1,
            Self::Lunar => 2,
        }
    }

    /// The law's factor for incidence cosine `mu0` and emergence cosine `mu`: 1 at normal
    /// incidence seen face-on, 0 on the night side.
    pub fn factor(self, mu0: f64, mu: f64) -> f64 {
        if mu0 <= 0.0 {
            return 0.0;
        }
        match self {
            Self::Lambert => mu0,
            Self::LommelSeeliger | Self::Lunar => 2.0 * mu0 / (mu0 + mu.max(0.0)),
        }
    }

    /// The law's factor for the phase angle whose cosine is `cos_alpha` (between the light's and
    /// the viewer's directions at the point): [`phase::lunar_phase_factor`] for the Moon's law,
    /// 1 for the others.
    pub fn phase_factor(self, cos_alpha: f64) -> f64 {
        match self {
            Self::Lambert | Self::LommelSeeliger => 1.0,
            Self::Lunar => phase::lunar_phase_factor(cos_alpha.clamp(-1.0, 1.0).acos()),
        }
    }
}

/// What a body's surface looks like beyond its normal albedo.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum BodySurface {
    /// The albedo everywhere.
    #[default]
    Uniform,
    /// The Moon's near-side maria on brighter highlands ([`maria`]), in the body's axes.
    LunarMaria,
    /// An equirectangular map in the body's axes, its pattern and colour on the albedo's level
    /// ([`map`]).
    Map(Arc<SurfaceMap>),
}

impl BodySurface {
    /// The code the shaders read (`BODY_SURFACE_*` in the generated constants).
    pub const fn gpu_code(&self) -> u32 {
        match self {
            Self::Uniform => 0,
            Self::LunarMaria => 1,
            Self::Map(_) => 2,
        }
    }
}

/// An airless body in the view.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Centre, metres, in the frame the sky is given in (the world frame of
    /// [`AtmosphereSky`](crate::frame::AtmosphereSky)).
    pub center: DVec3,
    /// Semi-axes along the body's x, y and polar z axis, metres, each > 0.
    pub radii: DVec3,
    /// Rotation from the body's axes to that frame.
    pub orientation: DQuat,
    /// Normal albedo per model wavelength, each in [0, 1].
    pub albedo: Spectrum,
    /// How the surface sends the light back.
    pub reflectance: Reflectance,
    /// The pattern over the albedo.
    pub surface: BodySurface,
    /// The light inside the planet's shadow where the body stands, if it stands there (a lunar
    /// eclipse); `None`: the planet is an opaque ball.
    pub planet_shadow: Option<BodyInShadow>,
    /// The body's own air ([`air`]); `None`: airless.
    pub air: Option<BodyAir>,
}

/// The light a body gets inside the planet's shadow from one sun: that sun's share across the
/// shadow at the body's distance behind the planet ([`PlanetShadow`]).
#[derive(Debug, Clone, PartialEq)]
pub struct BodyInShadow {
    /// The sun (an index into the sky's suns) whose shadow it is.
    pub sun: usize,
    /// Unit direction of the shadow's axis from the planet's centre, same frame as the body:
    /// away from the sun. Where the body is drawn lifted by refraction, this is the axis lifted
    /// with it, so the body stands where it does in the shadow.
    pub axis: DVec3,
    /// The sunlight's share across the shadow.
    pub profile: PlanetShadow,
}

impl BodyInShadow {
    /// Checks the rules: the axis a finite unit vector; the profile's step finite and > 0 m, its
    /// [`SHADOW_ENTRIES`] shares finite and ≥ 0 (the GPU's table holds that many).
    pub fn validate(&self) -> Result<(), CoreError> {
        if !(self.axis.is_finite() && (self.axis.length() - 1.0).abs() < 1e-6) {
            return Err(invalid(
                "body.planet_shadow.axis",
                format!("{:?}", self.axis.to_array()),
                "must be a unit vector",
            ));
        }
        let profile = &self.profile;
        let shares_ok = profile.light.iter().all(|l| l.is_finite() && l.min_element() >= 0.0);
        if !(profile.step_m.is_finite() && profile.step_m > 0.0) || profile.light.len() != SHADOW_ENTRIES || !shares_ok
        {
            return Err(invalid(
                "body.planet_shadow.profile",
                format!("step {} m, {} entries", profile.step_m, profile.light.len()),
                "must step a finite distance > 0 m between 64 finite shares ≥ 0 (PlanetShadow::new)",
            ));
        }
        Ok(())
    }

    /// The sunlight's share at point `p`, relative to the planet's centre (same frame as the
    /// body): the profile at `p`'s distance from the shadow's axis behind the planet, 1 before it.
    pub fn light_at(&self, p: DVec3) -> Spectrum {
        let behind = p.dot(self.axis);
        if behind <= 0.0 {
            return Spectrum::ONE;
        }
        self.profile.at((p - self.axis * behind).length())
    }
}

impl Body {
    /// The Moon at `center`: a ball of its mean radius, its geometric albedo, its own law
    /// ([`Reflectance::Lunar`]), its maria (the near side, `x` of its axes, faces along the
    /// frame's x: pose it with `orientation`).
    pub fn moon(center: DVec3) -> Self {
        Self {
            center,
            radii: DVec3::splat(MOON_RADIUS_M),
            orientation: DQuat::IDENTITY,
            albedo: Spectrum::splat(MOON_ALBEDO),
            reflectance: Reflectance::Lunar,
            surface: BodySurface::LunarMaria,
            planet_shadow: None,
            air: None,
        }
    }

    /// Checks the rules: centre finite, semi-axes finite and > 0 m, orientation a finite unit
    /// quaternion, albedo in [0, 1].
    pub fn validate(&self) -> Result<(), CoreError> {
        if !self.center.is_finite() {
            return Err(invalid(
                "body.center",
                format!("{:?}", self.center.to_array()),
                "must be finite metres",
            ));
        }
        if !(self.radii.is_finite() && self.radii.min_element() > 0.0) {
            return Err(invalid(
                "body.radii",
                format!("{:?}", self.radii.to_array()),
                "every semi-axis must be a finite length > 0 m",
            ));
        }
        if !(self.orientation.is_finite() && (self.orientation.length() - 1.0).abs() < 1e-6) {
            return Err(invalid(
                "body.orientation",
                format!("{:?}", self.orientation),
                "must be a unit quaternion",
            ));
        }
        if !self.albedo.to_array().iter().all(|a| (0.0..=1.0).contains(a)) {
            return Err(invalid(
                "body.albedo",
                format!("{:?}", self.albedo.to_array()),
                "every value must be in [0, 1]",
            ));
        }
        if let BodySurface::Map(surface) = &self.surface
            && map::brightness(surface) <= 0.0
        {
            return Err(invalid(
                "body.surface",
                "a black map".to_owned(),
                "an albedo map must not be black everywhere (its mean sets nothing to scale)",
            ));
        }
        self.planet_shadow.as_ref().map_or(Ok(()), BodyInShadow::validate)?;
        self.air.as_ref().map_or(Ok(()), BodyAir::validate)
    }

    /// How far the body reaches from its centre, metres: its largest semi-axis, its air's top
    /// included.
    pub fn reach(&self) -> f64 {
        let air = self
            .air
            .as_ref()
            .map_or(0.0, |air| air.top_altitude_m / self.mean_radius());
        self.radii.max_element() * (1.0 + air)
    }

    /// The radius of the ball of the same volume, metres: what the body hides of a sun.
    pub fn mean_radius(&self) -> f64 {
        self.radii.element_product().cbrt()
    }

    /// The body as an opaque ball that eclipses the suns ([`Self::mean_radius`]).
    pub fn eclipser(&self) -> Eclipser {
        Eclipser {
            center: self.center,
            radius_m: self.mean_radius(),
        }
    }

    /// The same body with its pose (and its shadow's axis) moved from the world frame into
    /// `planet`'s frame.
    pub fn to_planet_frame(&self, planet: &Planet) -> Self {
        Self {
            center: planet.to_planet_frame(self.center),
            orientation: (planet.orientation.inverse() * self.orientation).normalize(),
            planet_shadow: self.planet_shadow.as_ref().map(|shadow| BodyInShadow {
                axis: planet.direction_to_planet_frame(shadow.axis),
                ..shadow.clone()
            }),
            ..self.clone()
        }
    }

    /// The distance along `ray` (same frame as the body) to where it first meets the surface
    /// ahead of its origin, if it does.
    pub fn hit(&self, ray: &Ray) -> Option<f64> {
        let local = Ray::new(
            self.orientation.inverse() * (ray.origin - self.center),
            self.orientation.inverse() * ray.direction,
        )?;
        let hits = Ellipsoid {
            center: DVec3::ZERO,
            radii: self.radii,
        }
        .intersect(&local)?;
        (hits.near > 0.0).then_some(hits.near)
    }

    /// The outward unit normal at surface point `p` (same frame as the body).
    pub fn normal_at(&self, p: DVec3) -> DVec3 {
        let local = self.orientation.inverse() * (p - self.center);
        (self.orientation * (local / (self.radii * self.radii))).normalize()
    }

    /// The radiance the planet's light (planet-shine, module docs) sends from surface point `p`
    /// towards a viewer along `to_viewer`, all in `planet`'s frame (the body too, e.g.
    /// [`Self::to_planet_frame`]), for `suns` lighting the planet.
    pub fn planetshine_radiance(&self, p: DVec3, to_viewer: DVec3, suns: &[Sun], planet: &Planet) -> Spectrum {
        self.reflect(
            p,
            to_viewer,
            suns.iter().map(|sun| {
                let (to_planet, share) = planetshine(p, sun.direction.normalize(), planet);
                (to_planet, sun.irradiance * share)
            }),
        )
    }

    /// The normal albedo at surface point `p` (same frame as the body): [`Self::albedo`] times
    /// the surface's pattern (for a map, at most 1).
    pub fn albedo_at(&self, p: DVec3) -> Spectrum {
        let local = || self.orientation.inverse() * self.normal_at(p);
        match &self.surface {
            BodySurface::Uniform => self.albedo,
            BodySurface::LunarMaria => self.albedo * maria::albedo_factor(local()),
            BodySurface::Map(surface) => (self.albedo * map::albedo_factor(surface, local())).min(Spectrum::ONE),
        }
    }

    /// The radiance the surface point `p` (same frame as the body, on the surface) sends
    /// towards a viewer along `to_viewer` (unit), lit by `suns` (sun `s`'s irradiance reaches it
    /// times `light(s)`, the share the shadows leave, per model wavelength: e.g.
    /// [`sunlight_share`]): spectral, the suns' irradiance units per steradian.
    pub fn radiance(&self, p: DVec3, to_viewer: DVec3, suns: &[Sun], light: impl Fn(usize) -> Spectrum) -> Spectrum {
        self.reflect(
            p,
            to_viewer,
            suns.iter()
                .enumerate()
                .map(|(s, sun)| (sun.direction.normalize(), sun.irradiance * light(s))),
        )
    }

    /// What surface point `p` sends back along `to_viewer` of the light arriving from each unit
    /// direction with its face-on irradiance, by the body's law and albedo.
    fn reflect(&self, p: DVec3, to_viewer: DVec3, incoming: impl Iterator<Item = (DVec3, Spectrum)>) -> Spectrum {
        let n = self.normal_at(p);
        let mu = n.dot(to_viewer);
        let received = incoming.fold(Spectrum::ZERO, |sum, (direction, irradiance)| {
            let law = self.reflectance.factor(n.dot(direction), mu);
            sum + irradiance * (law * self.reflectance.phase_factor(direction.dot(to_viewer)))
        });
        received * self.albedo_at(p) / PI
    }

    /// The first of `suns` (world-frame directions) whose shadow of `planet` (its penumbra, the
    /// air's height included) reaches the body, and the body's centre's distance behind the
    /// planet along that shadow's axis, metres.
    pub fn shadowing_sun(&self, suns: &[Sun], planet: &Planet) -> Option<(usize, f64)> {
        let center = self.center - planet.center;
        let reach = planet.radii.max_element() + planet.atmosphere_height + self.radii.max_element();
        suns.iter().enumerate().find_map(|(s, sun)| {
            let axis = -sun.direction.normalize();
            let behind = center.dot(axis);
            let across = (center - axis * behind).length();
            (behind > 0.0 && across < reach + behind * sun.angular_radius).then_some((s, behind))
        })
    }
}

/// The planet-shine at planet-frame point `p` from the light of the sun towards unit
/// `sun_direction` (planet frame): the unit direction to the planet's centre and the irradiance
/// face-on per unit of the sun's (the module docs give the model).
pub fn planetshine(p: DVec3, sun_direction: DVec3, planet: &Planet) -> (DVec3, f64) {
    let distance = p.length();
    let to_planet = -p / distance;
    let cos_alpha = sun_direction.dot(-to_planet).clamp(-1.0, 1.0);
    let alpha = cos_alpha.acos();
    let phase = (alpha.sin() + (PI - alpha) * cos_alpha) / PI;
    let radius = planet.radii.element_product().cbrt();
    (to_planet, planet.geometric_albedo * (radius / distance).powi(2) * phase)
}

/// The share of sun `s`'s light (its direction in the planet frame) that reaches the point `p` of
/// body `index` of `bodies` (all in `planet`'s frame), per model wavelength: past the planet (its
/// shadow's light where the body carries it, [`Body::planet_shadow`]), its `rings`, every other
/// body and the body's own air ([`Body::air_transmittance`]). Zero where the light is the body's
/// own ([`Sun::from_body`]).
pub fn sunlight_share(
    p: DVec3,
    suns: &[Sun],
    s: usize,
    planet: &Planet,
    rings: Option<&Rings>,
    bodies: &[Body],
    index: usize,
) -> Spectrum {
    let air = bodies[index].air_transmittance(p, suns[s].direction.normalize());
    shadows_share(p, suns, s, planet, rings, bodies, index) * air
}

/// [`sunlight_share`] without the body's own air: what the shadows of the planet, its rings and
/// the other bodies leave of sun `s` at `p` (the light [`Body::air_along`] takes).
pub fn shadows_share(
    p: DVec3,
    suns: &[Sun],
    s: usize,
    planet: &Planet,
    rings: Option<&Rings>,
    bodies: &[Body],
    index: usize,
) -> Spectrum {
    let sun = &suns[s];
    if sun.from_body == Some(index) {
        return Spectrum::ZERO;
    }
    let globe = match &bodies[index].planet_shadow {
        Some(shadow) if shadow.sun == s => shadow.light_at(p),
        _ => {
            let ball = Eclipser {
                center: DVec3::ZERO,
                radius_m: planet.radii.element_product().cbrt(),
            };
            Spectrum::splat(ball.visible_fraction(p, sun))
        }
    };
    let others: f64 = bodies
        .iter()
        .enumerate()
        .filter(|(i, _)| *i != index && sun.from_body != Some(*i))
        .map(|(_, b)| b.eclipser().visible_fraction(p, sun))
        .product();
    let rings = rings.map_or(1.0, |r| r.transmittance(p, sun.direction.normalize()));
    globe * (others * rings)
}

/// Checks every body and that none overlaps the planet with its air, nor another body.
pub fn validate_bodies(bodies: &[Body], planet: &Planet) -> Result<(), CoreError> {
    if bodies.len() > MAX_BODIES {
        return Err(invalid(
            "bodies",
            format!("{} bodies", bodies.len()),
            "at most 4 bodies",
        ));
    }
    let planet_reach = planet.radii.max_element() + planet.atmosphere_height;
    for (i, body) in bodies.iter().enumerate() {
        body.validate()?;
        let reach = body.reach();
        if body.center.distance(planet.center) <= planet_reach + reach {
            return Err(invalid(
                "body.center",
                format!("{:?}", body.center.to_array()),
                "must lie clear of the planet and its atmosphere (centres farther apart than their largest \
                 radii, the atmosphere's height included)",
            ));
        }
        for other in &bodies[..i] {
            if body.center.distance(other.center) <= reach + other.reach() {
                return Err(invalid(
                    "body.center",
                    format!("{:?}", body.center.to_array()),
                    "must lie clear of every other body (centres farther apart than their largest radii, \
                     their airs' heights included)",
                ));
            }
        }
    }
    Ok(())
}

fn invalid(field: &'static str, value: String, rule: &'static str) -> CoreError {
    CoreError::Invalid { field, value, rule }
}

pub mod air;
pub mod cast;
pub mod map;
pub mod maria;
pub mod phase;

#[cfg(test)]
mod tests;
