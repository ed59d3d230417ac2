//! From `[[bodies]]` to the core's [`Body`]s, every value checked on the way (each error names
//! the scene key): the Moon's preset, its place at the scene's date, the rules that keep bodies
//! apart from the planet, from each other and from the camera.

use firmament_core::astro::Instant;
use firmament_core::astro::moon::moon_view;
use firmament_core::astro::spa::SolarPosition;
use firmament_core::atmosphere::body::{self, Body, BodyAir, BodySurface, MAX_BODIES, Reflectance, validate_bodies};
use firmament_core::atmosphere::presets;
use firmament_core::frame::AtmosphereSky;
use firmament_core::sky::night::HORIZON_CUTOFF_DEG;
use glam::{DQuat, DVec3};

use crate::checks::{check, positive};
use crate::error::{SceneError, did_you_mean};
use crate::model::{BodyEntry, Scene};

/// The presets `bodies[i].preset` takes.
const PRESETS: [&str; 1] = ["moon"];

/// The airs `bodies[i].atmosphere` takes.
const AIRS: [&str; 3] = ["earth", "mars", "saturn"];

/// The laws `bodies[i].reflectance` takes.
const REFLECTANCES: [&str; 3] = ["lambert", "lommel-seeliger", "lunar"];

/// Adds the scene's bodies to `sky` (as bodies and eclipsers), placing a `"moon"` without a
/// `position` where the Moon stood at `instant`.
pub(crate) fn add_bodies(scene: &Scene, instant: Option<&Instant>, sky: &mut AtmosphereSky) -> Result<(), SceneError> {
    let entries = &scene.bodies;
    check(
        entries.len() <= MAX_BODIES,
        "bodies",
        format!("{} bodies", entries.len()),
        &format!("at most {MAX_BODIES} bodies (a fixed limit of the renderer that no key or flag raises)"),
    )?;
    let bodies = entries
        .iter()
        .enumerate()
        .map(|(i, entry)| body(i, entry, scene, instant, sky))
        .collect::<Result<Vec<_>, _>>()?;
    if let Err(error) = validate_bodies(&bodies, &sky.atmosphere.planet) {
        // Name the entry the core's rule is about: the first that breaks it on its own terms.
        let i = (0..bodies.len())
            .find(|&i| validate_bodies(&bodies[..=i], &sky.atmosphere.planet).is_err())
            .unwrap_or(0);
        let rule = match error {
            firmament_core::CoreError::Invalid { rule, .. } => rule.to_owned(),
            other => other.to_string(),
        };
        return Err(SceneError::invalid(
            format!("bodies[{i}].position"),
            format!("{:?}", bodies[i].center.to_array()),
            rule,
        ));
    }
    let camera = DVec3::from_array(scene.camera.position);
    for (i, body) in bodies.iter().enumerate() {
        let local = body.orientation.inverse() * (camera - body.center);
        check(
            (local / body.radii).length() > 1.0,
            &format!("bodies[{i}].position"),
            format!("{:?}", body.center.to_array()),
            "must keep the body clear of the camera (camera.position is inside it)",
        )?;
    }
    for body in bodies {
        sky.add_body(body);
    }
    Ok(())
}

/// Gives the bodies in the planet's shadow the light there (a lunar eclipse's red:
/// [`AtmosphereSky::light_bodies_in_planet_shadow`], the profile cached). A Moon placed at
/// `instant` is drawn lifted by refraction; the real sun's shadow (`real_sun`, the first sun) is
/// lifted with it, so it stands in the shadow where it really stands.
pub(crate) fn light_in_planet_shadow(
    scene: &Scene,
    instant: Option<&Instant>,
    real_sun: Option<&SolarPosition>,
    sky: &mut AtmosphereSky,
) {
    sky.light_bodies_in_planet_shadow(super::lunar_eclipse::profile);
    let (Some(instant), Some(sun)) = (instant, real_sun) else {
        return;
    };
    let (lat, lon) = (scene.planet.latitude_deg, scene.planet.longitude_deg);
    for (entry, body) in scene.bodies.iter().zip(&mut sky.bodies) {
        let placed = entry.position.is_none() && entry.preset.as_deref() == Some("moon");
        if let Some(shadow) = body.planet_shadow.as_mut().filter(|s| placed && s.sun == 0) {
            let geometric = moon_view(instant, lat, lon, 0.0).direction;
            let lift = DQuat::from_rotation_arc(geometric, super::night::refracted(scene, instant, geometric));
            shadow.axis = lift * -sun.direction_enu(false);
        }
    }
}

/// Adds each body's light on the planet as a sun without a disc
/// ([`AtmosphereSky::add_body_lights`]), seen from the camera inside the air, from the planet's
/// centre beyond it (the light falls on the planet, not on a far camera). Left out: the bodies
/// whose `light` is off, a body below the horizon of a camera under the air (as the night sky's
/// Moon is), and every body's by day under the air — a sun above the camera's horizon outshines
/// the full Moon 4·10⁵ times, and each light costs a sun in every pass.
pub(crate) fn add_lights(scene: &Scene, sky: &mut AtmosphereSky) {
    let planet = &sky.atmosphere.planet;
    let camera = DVec3::from_array(scene.camera.position);
    let in_air = planet.altitude(planet.to_planet_frame(camera)) < planet.atmosphere_height;
    let up = (camera - planet.center).normalize_or_zero();
    if in_air
        && sky
            .suns
            .iter()
            .any(|s| s.from_body.is_none() && s.direction.dot(up) > 0.0)
    {
        return;
    }
    let at = if in_air { camera } else { planet.center };
    let above = HORIZON_CUTOFF_DEG.to_radians().sin();
    let wanted: Vec<bool> = scene
        .bodies
        .iter()
        .zip(&sky.bodies)
        .map(|(entry, body)| {
            let up_there = !in_air || (body.center - at).normalize_or_zero().dot(up) >= above;
            entry.light != Some(false) && up_there
        })
        .collect();
    sky.add_body_lights(at, |i| wanted[i]);
}

/// Whether the scene has the Moon as a body (then the night sky's disc of the Moon, its
/// eclipser and its light are left out: the body is all three).
pub(crate) fn has_moon(scene: &Scene) -> bool {
    scene.bodies.iter().any(|b| b.preset.as_deref() == Some("moon"))
}

fn body(
    i: usize,
    entry: &BodyEntry,
    scene: &Scene,
    instant: Option<&Instant>,
    sky: &AtmosphereSky,
) -> Result<Body, SceneError> {
    let key = |field: &str| format!("bodies[{i}].{field}");
    let preset = match entry.preset.as_deref() {
        None => None,
        Some("moon") => Some("moon"),
        Some(other) => return Err(unknown_name(&key("preset"), other, &PRESETS)),
    };
    let center = match (entry.position, preset, instant) {
        (Some(p), _, _) => {
            let p = DVec3::from_array(p);
            check(
                p.is_finite(),
                &key("position"),
                format!("{:?}", p.to_array()),
                "must be 3 finite numbers of metres",
            )?;
            p
        }
        (None, Some("moon"), Some(instant)) => {
            // Topocentric from the world frame's origin (the surface point under the camera),
            // lifted by refraction as the suns are, so an eclipse's discs line up.
            let (lat, lon) = (scene.planet.latitude_deg, scene.planet.longitude_deg);
            let view = moon_view(instant, lat, lon, 0.0);
            super::night::refracted(scene, instant, view.direction) * (view.equatorial.distance_km * 1000.0)
        }
        (None, Some(_), None) => {
            return Err(SceneError::invalid(
                key("position"),
                "(none)",
                "must be given without a date (time.date_time), which places the Moon",
            ));
        }
        (None, _, _) => {
            return Err(SceneError::invalid(
                key("position"),
                "(none)",
                "must be given: [east, north, up] in metres",
            ));
        }
    };
    let mut body = Body::moon(center);
    if preset.is_none() {
        body.reflectance = Reflectance::Lambert;
        body.surface = BodySurface::Uniform;
        if entry.radius.is_none() && entry.radii.is_none() {
            return Err(SceneError::invalid(
                key("radius"),
                "(none)",
                "must be given (or radii, or preset = \"moon\")",
            ));
        }
    }
    match (entry.radius, entry.radii) {
        (Some(_), Some(_)) => {
            return Err(SceneError::invalid(
                key("radii"),
                "(both)",
                format!("give radius or radii, not both ({})", key("radius")),
            ));
        }
        (Some(r), None) => {
            positive(&key("radius"), r, " m")?;
            body.radii = DVec3::splat(r);
        }
        (None, Some(radii)) => {
            for (axis, r) in ["a", "b", "c"].iter().zip(radii) {
                positive(&format!("{} ({axis})", key("radii")), r, " m")?;
            }
            body.radii = DVec3::from_array(radii);
        }
        (None, None) => {}
    }
    let pole = match entry.pole {
        Some(pole) => {
            let pole = DVec3::from_array(pole);
            check(
                pole.is_finite() && pole.length() > 0.0,
                &key("pole"),
                format!("{:?}", pole.to_array()),
                "must be a finite direction, not [0, 0, 0]",
            )?;
            pole.normalize()
        }
        None => sky.atmosphere.planet.orientation * DVec3::Z,
    };
    body.orientation = facing(pole, sky.atmosphere.planet.center - center);
    if let Some(albedo) = entry.albedo {
        let a = albedo.0;
        check(
            a.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v)),
            &key("albedo"),
            format!("{a:?}"),
            "every value must be in [0, 1]",
        )?;
        body.albedo = albedo.spectrum();
    }
    if let Some(name) = &entry.reflectance {
        body.reflectance = match name.as_str() {
            "lambert" => Reflectance::Lambert,
            "lommel-seeliger" => Reflectance::LommelSeeliger,
            "lunar" => Reflectance::Lunar,
            other => return Err(unknown_name(&key("reflectance"), other, &REFLECTANCES)),
        };
    }
    if let Some(name) = &entry.atmosphere {
        body.air = Some(air(&key("atmosphere"), name, sky)?);
    }
    if let Some(file) = &entry.albedo_map {
        let map = super::atmosphere::surface::albedo_map(scene, &key("albedo_map"), file)?;
        check(
            body::map::brightness(&map) > 0.0,
            &key("albedo_map"),
            format!("{file:?}"),
            "must not be black everywhere (its mean brightness is scaled to the body's albedo)",
        )?;
        body.surface = BodySurface::Map(map);
    }
    Ok(body)
}

/// The air `bodies[i].atmosphere = name` gives (`key` names it in errors).
fn air(key: &str, name: &str, sky: &AtmosphereSky) -> Result<BodyAir, SceneError> {
    let preset = match name {
        "earth" => presets::earth(),
        "mars" => presets::mars(),
        "saturn" => presets::saturn(),
        "venus" | "titan" => {
            return Err(SceneError::invalid(
                key,
                format!("\"{name}\""),
                "must be \"earth\", \"mars\" or \"saturn\": a body's air is drawn with single scattering, \
                 and Venus's and Titan's thick airs need every order (make them the [planet])",
            ));
        }
        other => return Err(unknown_name(key, other, &AIRS)),
    };
    check(
        sky.atmosphere.wavelengths == preset.wavelengths,
        key,
        format!("\"{name}\""),
        "needs the default atmosphere.wavelengths (the presets' coefficients are at 680, 550 and 440 nm)",
    )?;
    Ok(BodyAir::from_atmosphere(&preset).expect("the earth, mars and saturn presets are constituents"))
}

/// The rotation that puts a body's `z` axis on `pole` and its `x` axis (its 0° N 0° E) as near
/// `towards` (the planet: a moon's near side faces it) as the pole allows.
fn facing(pole: DVec3, towards: DVec3) -> DQuat {
    let x = towards - pole * towards.dot(pole);
    if x.length() <= 1e-9 * towards.length() {
        return DQuat::from_rotation_arc(DVec3::Z, pole);
    }
    let x = x.normalize();
    DQuat::from_mat3(&glam::DMat3::from_cols(x, pole.cross(x), pole)).normalize()
}

/// `key = "given"` is none of `names`: the error lists them and suggests the closest.
fn unknown_name(key: &str, given: &str, names: &[&str]) -> SceneError {
    let hint = did_you_mean(given, names.iter().copied())
        .map(|best| format!(" (did you mean `{best}`?)"))
        .unwrap_or_default();
    let list = names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(" or ");
    SceneError::invalid(key, format!("\"{given}\""), format!("must be {list}{hint}"))
}
