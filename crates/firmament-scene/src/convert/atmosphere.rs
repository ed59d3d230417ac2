//! From `[planet]`, `[atmosphere]`, `[[suns]]` and `[[clouds]]` to the core's [`AtmosphereSky`],
//! checking every value on the way (each error names the scene key), and the rule that keeps the
//! camera above the planet's surface.
//!
//! The body (`planet.body`) gives every value; each key a scene sets replaces the body's. The
//! core's own checks run last, as a backstop, with their field names turned into scene keys.

pub(crate) mod clouds;
mod empirical;
mod medium;
mod planet;
mod suns;
pub(super) mod surface;
mod terms;

pub use empirical::{EMPIRICAL_STAR_DISTANCE, EMPIRICAL_STAR_INTENSITY};
pub(crate) use empirical::{empirical_planet, empirical_sky};

use firmament_core::CoreError;
use firmament_core::atmosphere::rings::{RingBand, Rings};
use firmament_core::atmosphere::{Atmosphere, Planet};
use firmament_core::frame::AtmosphereSky;
use glam::DVec3;

use crate::error::SceneError;
use crate::model::{Body, Scene};

/// How far below the surface the camera may be and still count as on it, metres (rounding in
/// posing the planet is far smaller).
const SURFACE_TOLERANCE: f64 = 1e-3;

/// The scene's planet, atmosphere, suns and cloud layers (coverage maps loaded, no drift),
/// checked.
pub(crate) fn sky(scene: &Scene) -> Result<AtmosphereSky, SceneError> {
    let body = scene.planet.body;
    let planet = planet::planet(&scene.planet)?;
    let (mut medium, wavelengths) = medium::medium(&scene.atmosphere, body)?;
    let surface = surface::surface(scene)?;
    if let Some(surface) = &surface {
        if let Some(albedo) = &scene.atmosphere.ground_albedo {
            return Err(SceneError::invalid(
                "atmosphere.ground_albedo",
                format!("{albedo:?}"),
                "has no effect with a planet surface (planet.surface or planet.albedo_map), whose albedo map \
                 gives the ground's albedo: remove one",
            ));
        }
        // The multiple-scattering LUTs assume one albedo everywhere: the surface's mean.
        medium.ground_albedo = surface.mean_albedo();
    }
    let atmosphere = Atmosphere {
        planet,
        medium,
        wavelengths,
    };
    atmosphere
        .validate()
        .map_err(|e| from_core(e, |field| scene_key(field, scene)))?;
    let suns = suns::suns(&scene.suns, body, &atmosphere)?;
    let clouds = clouds::clouds(scene, &atmosphere)?;
    let sky = AtmosphereSky {
        atmosphere,
        suns,
        clouds,
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: rings(scene)?,
        surface,
    };
    sky.validate()
        .map_err(|e| from_core(e, |field| scene_key(field, scene)))?;
    Ok(sky)
}

/// `[rings]` as the core's rings: the body's with the scene's overrides, or `None` when they are
/// off. Their rules are checked with the sky's (`AtmosphereSky::validate`).
fn rings(scene: &Scene) -> Result<Option<Rings>, SceneError> {
    let section = &scene.rings;
    if !section.enabled {
        return Ok(None);
    }
    let mut rings = match (scene.planet.body, &section.bands) {
        (Body::Saturn, _) => Rings::saturn(),
        (_, Some(_)) => Rings {
            bands: Vec::new(),
            ..Rings::saturn()
        },
        (body, None) => {
            return Err(SceneError::invalid(
                "rings.bands",
                "(none)",
                format!(
                    "must be given for planet.body = \"{}\": only saturn has rings of its own",
                    body.name()
                ),
            ));
        }
    };
    if let Some(bands) = &section.bands {
        rings.bands = bands
            .iter()
            .map(|b| RingBand {
                inner_m: b.inner_radius,
                outer_m: b.outer_radius,
                optical_depth: b.optical_depth,
            })
            .collect();
    }
    if let Some(albedo) = section.albedo {
        rings.albedo = albedo.spectrum();
    }
    if let Some(g) = section.g {
        rings.phase_g = g;
    }
    Ok(Some(rings))
}

/// Checks that the camera is not inside the planet: its geodetic altitude must be >= 0.
pub(crate) fn camera_above_surface(scene: &Scene, planet: &Planet) -> Result<(), SceneError> {
    let world = DVec3::from_array(scene.camera.position);
    let p = planet.to_planet_frame(world);
    let altitude = planet.altitude(p);
    if altitude >= -SURFACE_TOLERANCE {
        return Ok(());
    }
    // p = foot + altitude·up(foot): the nearest surface point, back in the world frame.
    let foot = planet.center + planet.orientation.normalize() * (p - planet.up(p) * altitude);
    let [e, n, u] = scene.camera.position;
    let [fe, fn_, fu] = foot.to_array().map(metres);
    Err(SceneError::invalid(
        "camera.position",
        format!("[{e}, {n}, {u}]"),
        format!(
            "the camera is inside the planet ({}): its altitude is {} m, and the nearest point of the \
             surface is at [{fe}, {fn_}, {fu}] (east, north, up, metres); the camera must be at an \
             altitude >= 0",
            scene.planet.body.name(),
            metres(altitude),
        ),
    ))
}

/// A length rounded to the millimetre for messages (without a negative zero).
fn metres(value: f64) -> f64 {
    (value * 1000.0).round() / 1000.0 + 0.0
}

/// A core validation error as a scene error, its field named by `key_of`.
fn from_core(error: CoreError, key_of: impl Fn(&str) -> String) -> SceneError {
    match error {
        CoreError::Invalid { field, value, rule } => SceneError::invalid(key_of(field), value, rule),
        CoreError::InvalidItem { field, value, rule } => SceneError::invalid(key_of(&field), value, rule),
        other => SceneError::invalid("atmosphere", "(the whole atmosphere)", other.to_string()),
    }
}

/// The scene key behind one of the core's field names.
fn scene_key(field: &str, scene: &Scene) -> String {
    if let Some(key) = clouds::scene_key(field) {
        return key;
    }
    let p = &scene.planet;
    let sphere = p.radius.is_some();
    let key = match field {
        "planet.radii.x" | "planet.radii.y" if !sphere => "planet.equatorial_radius",
        "planet.radii.z" if !sphere => "planet.polar_radius",
        "planet.radii" if !sphere && p.polar_radius.is_some() => "planet.polar_radius",
        "planet.radii" if !sphere => "planet.equatorial_radius",
        "planet.radii.x" | "planet.radii.y" | "planet.radii.z" | "planet.radii" => "planet.radius",
        "atmosphere.height" => "planet.atmosphere_height",
        "planet.center" | "planet.orientation" => "planet.latitude",
        other => other,
    };
    key.to_owned()
}
