//! `atmosphere.model = "seed"`: the seed's own model, the empirical one ([`EmpiricalAtmosphere`]),
//! from the body's seed values, `[planet]`'s radii and `[atmosphere.seed]`, with `[[suns]]` as the
//! seed's stars.
//!
//! # Suns become stars
//! The seed lights its atmosphere with stars at real positions (`light_posr`, `light_dir`,
//! `light_col`, seed lines 519–531). A sun given by `position` sits at that point; one given by
//! `azimuth` and `elevation` sits [`EMPIRICAL_STAR_DISTANCE`] from the planet centre in its
//! direction. Its radius is the one that subtends the sun's angular radius from the planet centre
//! (`distance · sin α`), its direction (`light_dir`) is the one from the planet centre to it, and its
//! colour is the sun's spectral irradiance at the three model wavelengths (red first) divided by
//! its largest channel, times [`EMPIRICAL_STAR_INTENSITY`] (the seed's CPU side uploads the star's
//! colour × 10, line 528).

use firmament_core::atmosphere::empirical::{EmpiricalAtmosphere, EmpiricalStar};
use firmament_core::atmosphere::{Planet, Sun};
use firmament_core::frame::{AtmosphereSky, EMPIRICAL_DEFAULT_LUMINANCE, EmpiricalSky};
use glam::DVec3;

use crate::checks::{check, positive};
use crate::error::SceneError;
use crate::model::{Body, Scene};

/// Distance of a sun given by azimuth and elevation from the planet centre, metres (1 AU); only
/// the ratio of radius to distance matters for a star this far.
pub const EMPIRICAL_STAR_DISTANCE: f64 = firmament_core::atmosphere::presets::ASTRONOMICAL_UNIT;

/// The seed's visual intensity of a star: its colour × 10 (seed line 528), unitless.
pub const EMPIRICAL_STAR_INTENSITY: f64 = 10.0;

/// The seed's own values for `body`, if it has any.
fn body_seed(body: Body) -> Option<EmpiricalAtmosphere> {
    match body {
        Body::Earth => Some(EmpiricalAtmosphere::seed_earth()),
        Body::Mars => Some(EmpiricalAtmosphere::seed_mars()),
        Body::Saturn | Body::Venus | Body::Titan => None,
    }
}

/// The empirical sky of `scene`, every value checked; `physical` is the scene's checked physical
/// sky (its suns, their directions and colours).
pub(crate) fn empirical_sky(scene: &Scene, physical: &AtmosphereSky) -> Result<EmpiricalSky, SceneError> {
    let body = scene.planet.body;
    let section = &scene.atmosphere.empirical;
    let base = body_seed(body);
    let p = &scene.planet;
    for (key, value) in [
        ("atmosphere.seed.height", section.height),
        ("atmosphere.seed.view_depth", section.view_depth),
        ("atmosphere.seed.luminance", section.luminance),
    ] {
        if let Some(v) = value {
            positive(key, v, "")?;
        }
    }
    if let Some([r, g, b]) = section.b0 {
        check(
            [r, g, b].iter().all(|v| v.is_finite() && *v >= 0.0),
            "atmosphere.seed.b0",
            format!("[{r}, {g}, {b}]"),
            "every channel must be a finite number >= 0",
        )?;
    }
    if let Some(o) = section.overglow {
        check(o.is_finite(), "atmosphere.seed.overglow", o, "must be a finite number")?;
    }
    let missing = |field: &str| SceneError::WrongType {
        key: format!("atmosphere.seed.{field}"),
        message: format!(
            "missing: the seed has no values for {}; give atmosphere.seed.view_depth, b0 and overglow",
            body.name()
        ),
    };
    // Radii: the planet's when the scene sets them, else the seed's (else the body's).
    let physical_radii = physical.atmosphere.planet.radii;
    let radius_set = p.radius.is_some() || p.equatorial_radius.is_some() || p.polar_radius.is_some();
    let (equatorial_radius, polar_radius) = match base {
        Some(b) if !radius_set => (b.equatorial_radius, b.polar_radius),
        _ => (physical_radii.x, physical_radii.z),
    };
    let atmosphere = EmpiricalAtmosphere {
        equatorial_radius,
        polar_radius,
        height: section
            .height
            .or(p.atmosphere_height)
            .or(base.map(|b| b.height))
            .unwrap_or(physical.atmosphere.planet.atmosphere_height),
        view_depth: section
            .view_depth
            .or(base.map(|b| b.view_depth))
            .ok_or_else(|| missing("view_depth"))?,
        b0: section
            .b0
            .map(DVec3::from_array)
            .or(base.map(|b| b.b0))
            .ok_or_else(|| missing("b0"))?,
        overglow: section
            .overglow
            .or(base.map(|b| b.overglow))
            .ok_or_else(|| missing("overglow"))?,
    };
    let planet = Planet::spheroid(equatorial_radius, polar_radius, atmosphere.height)
        .posed_at(p.latitude_deg.to_radians(), p.longitude_deg.to_radians());
    let stars = scene
        .suns
        .iter()
        .zip(&physical.suns)
        .map(|(entry, sun)| star(&planet, sun, entry.position.map(DVec3::from_array)))
        .collect();
    let sky = EmpiricalSky {
        atmosphere,
        center: planet.center,
        orientation: planet.orientation,
        stars,
        luminance: section.luminance.unwrap_or(EMPIRICAL_DEFAULT_LUMINANCE),
    };
    sky.validate().map_err(|e| match e {
        firmament_core::CoreError::Invalid { field, value, rule } => {
            let key = match field {
                "atmosphere.seed.equatorial_radius" | "atmosphere.seed.polar_radius" if p.radius.is_some() => {
                    "planet.radius".to_owned()
                }
                "atmosphere.seed.equatorial_radius" => "planet.equatorial_radius".to_owned(),
                "atmosphere.seed.polar_radius" => "planet.polar_radius".to_owned(),
                f if f.starts_with("seed.stars") => "suns".to_owned(),
                "seed.luminance" => "atmosphere.seed.luminance".to_owned(),
                "seed.center" | "seed.orientation" => "planet.latitude".to_owned(),
                other => other.to_owned(),
            };
            SceneError::invalid(key, value, rule)
        }
        other => SceneError::invalid("atmosphere.seed", "(the seed atmosphere)", other.to_string()),
    })?;
    Ok(sky)
}

/// The posed planet of an empirical sky (its surface and pose), for the camera-above-ground rule.
pub(crate) fn empirical_planet(sky: &EmpiricalSky) -> Planet {
    Planet {
        radii: sky.atmosphere.surface().radii,
        center: sky.center,
        orientation: sky.orientation,
        atmosphere_height: sky.atmosphere.height,
        geometric_albedo: 0.0,
    }
}

/// A sun as an empirical star in the planet frame (see the module docs); `position` is the scene's
/// world-frame position of the sun, if it gave one.
fn star(planet: &Planet, sun: &Sun, position: Option<DVec3>) -> EmpiricalStar {
    let position = match position {
        Some(world) => planet.to_planet_frame(world),
        None => planet.direction_to_planet_frame(sun.direction).normalize_or_zero() * EMPIRICAL_STAR_DISTANCE,
    };
    let distance = position.length();
    let irradiance = sun.irradiance;
    let largest = irradiance.max_element();
    let color = if largest > 0.0 {
        irradiance / largest * EMPIRICAL_STAR_INTENSITY
    } else {
        DVec3::ZERO
    };
    EmpiricalStar {
        position,
        radius: distance * sun.angular_radius.sin(),
        direction: position.normalize_or_zero(),
        color,
    }
}
