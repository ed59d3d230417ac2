//! `[[suns]]`: each entry's direction, disc, colour and irradiance, defaults from the body's sun.

use firmament_core::atmosphere::star::blackbody_spectrum;
use firmament_core::atmosphere::{Atmosphere, Spectrum, Sun};
use firmament_core::camera::direction_from_heading_elevation;
use firmament_core::frame::MAX_SUNS;
use glam::DVec3;

use crate::checks::{check, in_range, non_negative};
use crate::error::SceneError;
use crate::model::{Body, SunEntry};

/// Black-body temperatures the scene accepts, kelvin (Planck's law stays finite in f64 over the
/// model wavelengths).
const TEMPERATURES: (f64, f64) = (500.0, 1.0e6);

/// The suns, every value checked.
pub(super) fn suns(entries: &[SunEntry], body: Body, atmosphere: &Atmosphere) -> Result<Vec<Sun>, SceneError> {
    check(
        entries.len() <= MAX_SUNS,
        "suns",
        format!("{} suns", entries.len()),
        &format!(
            "at most {MAX_SUNS} suns (MAX_SUNS, a fixed limit of the renderer that no key or flag raises: \
             drop the faintest suns)"
        ),
    )?;
    entries
        .iter()
        .enumerate()
        .map(|(i, entry)| sun(i, entry, body, atmosphere))
        .collect()
}

fn sun(i: usize, entry: &SunEntry, body: Body, atmosphere: &Atmosphere) -> Result<Sun, SceneError> {
    let key = |field: &str| format!("suns[{i}].{field}");
    let direction = direction(i, entry, atmosphere)?;
    let base = body.sun(direction);

    let shape = match (entry.temperature, entry.color) {
        (Some(_), Some(c)) => {
            return Err(SceneError::invalid(
                key("color"),
                format!("[{}, {}, {}]", c.0.r, c.0.g, c.0.b),
                "give either temperature or color, not both",
            ));
        }
        (Some(kelvin), None) => {
            let (lo, hi) = TEMPERATURES;
            in_range(&key("temperature"), kelvin, lo, hi, " kelvin")?;
            blackbody_spectrum(kelvin, atmosphere.wavelengths)
        }
        (None, Some(c)) => {
            check(
                c.0.g > 0.0,
                &key("color"),
                format!("[{}, {}, {}]", c.0.r, c.0.g, c.0.b),
                "green (the middle wavelength, where irradiance is given) must be > 0",
            )?;
            Spectrum::new(c.0.r, c.0.g, c.0.b)
        }
        (None, None) => base.irradiance,
    };
    let irradiance = entry.irradiance.unwrap_or(base.irradiance.y);
    non_negative(&key("irradiance"), irradiance)?;

    let angular_radius = match entry.angular_radius_deg {
        Some(degrees) => {
            check(
                degrees.is_finite() && degrees > 0.0 && degrees < 90.0,
                &key("angular_radius"),
                degrees,
                "must be in (0, 90) degrees",
            )?;
            degrees.to_radians()
        }
        None => base.angular_radius,
    };
    let limb_darkening = entry.limb_darkening.unwrap_or(base.limb_darkening);
    in_range(&key("limb_darkening"), limb_darkening, 0.0, 1.0, "")?;

    let sun = Sun {
        direction,
        angular_radius,
        irradiance: if shape == base.irradiance && irradiance == base.irradiance.y {
            // The body's own sun, exactly.
            base.irradiance
        } else {
            shape / shape.y * irradiance
        },
        limb_darkening,
        disc: true,
        from_body: None,
    };
    sun.validate().map_err(|e| match e {
        firmament_core::CoreError::Invalid { field, value, rule } => {
            SceneError::invalid(key(field.trim_start_matches("suns.")), value, rule)
        }
        other => SceneError::invalid(format!("suns[{i}]"), "(the sun)", other.to_string()),
    })?;
    Ok(sun)
}

/// The unit world-frame direction towards the sun, from `azimuth`/`elevation` or `position`.
fn direction(i: usize, entry: &SunEntry, atmosphere: &Atmosphere) -> Result<DVec3, SceneError> {
    let key = |field: &str| format!("suns[{i}].{field}");
    let missing = |field: &str, message: &str| SceneError::WrongType {
        key: key(field),
        message: format!("missing: {message}"),
    };
    match (entry.azimuth_deg, entry.elevation_deg, entry.position) {
        (Some(_), _, Some([e, n, u])) | (_, Some(_), Some([e, n, u])) => Err(SceneError::invalid(
            key("position"),
            format!("[{e}, {n}, {u}]"),
            "give either azimuth and elevation or position, not both",
        )),
        (Some(azimuth), Some(elevation), None) => {
            check(
                azimuth.is_finite(),
                &key("azimuth"),
                azimuth,
                "must be a finite number of degrees",
            )?;
            in_range(&key("elevation"), elevation, -90.0, 90.0, " degrees")?;
            Ok(direction_from_heading_elevation(
                azimuth.to_radians(),
                elevation.to_radians(),
            ))
        }
        (Some(_), None, None) => Err(missing(
            "elevation",
            "azimuth needs an elevation (degrees), or give a position instead",
        )),
        (None, Some(_), None) => Err(missing(
            "azimuth",
            "elevation needs an azimuth (degrees from north, clockwise), or give a position instead",
        )),
        (None, None, Some(position)) => from_position(&key("position"), position, atmosphere),
        (None, None, None) => Err(SceneError::WrongType {
            key: format!("suns[{i}]"),
            message: "missing a direction: give azimuth and elevation (degrees) or position ([east, north, up], \
                      metres)"
                .to_owned(),
        }),
    }
}

/// The direction from the planet's centre to a world-frame `position`, which must lie above the
/// atmosphere (a sun is a distant light, not a lamp inside the air).
fn from_position(key: &str, position: [f64; 3], atmosphere: &Atmosphere) -> Result<DVec3, SceneError> {
    let [e, n, u] = position;
    let shown = format!("[{e}, {n}, {u}]");
    check(
        position.iter().all(|v| v.is_finite()),
        key,
        &shown,
        "every component must be a finite number of metres",
    )?;
    let planet = &atmosphere.planet;
    let world = DVec3::from_array(position);
    let from_centre = world - planet.center;
    check(
        from_centre.length() > 0.0,
        key,
        &shown,
        "is the planet's centre: a sun at zero distance has no direction",
    )?;
    let altitude = planet.altitude(planet.to_planet_frame(world));
    check(
        altitude > planet.atmosphere_height,
        key,
        &shown,
        &format!(
            "must lie above the atmosphere (its top is {} m above the surface; this point is at altitude \
             {altitude:.0} m)",
            planet.atmosphere_height
        ),
    )?;
    Ok(from_centre.normalize())
}
