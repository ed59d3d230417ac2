//! `[planet]`: the body's ellipsoid with the scene's radii and atmosphere height, posed so that
//! the world frame is East-North-Up at `latitude`, `longitude`.

use firmament_core::atmosphere::Planet;

use crate::checks::{check, in_range, positive};
use crate::error::SceneError;
use crate::model::PlanetSection;

/// The largest ratio between the radii the core accepts.
const MAX_RADIUS_RATIO: f64 = 10.0;

/// The posed planet, every value checked.
pub(super) fn planet(section: &PlanetSection) -> Result<Planet, SceneError> {
    let body = section.body.atmosphere().planet;
    for (key, value) in [
        ("planet.radius", section.radius),
        ("planet.equatorial_radius", section.equatorial_radius),
        ("planet.polar_radius", section.polar_radius),
        ("planet.atmosphere_height", section.atmosphere_height),
    ] {
        if let Some(v) = value {
            positive(key, v, " metres")?;
        }
    }
    if section.radius.is_some() {
        for (key, value) in [
            ("planet.equatorial_radius", section.equatorial_radius),
            ("planet.polar_radius", section.polar_radius),
        ] {
            if let Some(v) = value {
                return Err(SceneError::invalid(
                    key,
                    v,
                    "give either planet.radius (a sphere) or planet.equatorial_radius and \
                     planet.polar_radius, not both",
                ));
            }
        }
    }
    let equatorial = section.radius.or(section.equatorial_radius).unwrap_or(body.radii.x);
    let polar = section.radius.or(section.polar_radius).unwrap_or(body.radii.z);
    // Blame the radius the scene set (the polar one when it set both).
    let (key, value, other) = if section.polar_radius.is_some() || section.equatorial_radius.is_none() {
        ("planet.polar_radius", polar, ("planet.equatorial_radius", equatorial))
    } else {
        ("planet.equatorial_radius", equatorial, ("planet.polar_radius", polar))
    };
    check(
        value.max(other.1) <= MAX_RADIUS_RATIO * value.min(other.1),
        key,
        value,
        &format!("must be within {MAX_RADIUS_RATIO} times {} ({} m)", other.0, other.1),
    )?;
    in_range("planet.latitude", section.latitude_deg, -90.0, 90.0, " degrees")?;
    check(
        section.longitude_deg.is_finite(),
        "planet.longitude",
        section.longitude_deg,
        "must be a finite number of degrees",
    )?;
    let height = section.atmosphere_height.unwrap_or(body.atmosphere_height);
    Ok(Planet::spheroid(equatorial, polar, height)
        .with_geometric_albedo(body.geometric_albedo)
        .posed_at(section.latitude_deg.to_radians(), section.longitude_deg.to_radians()))
}
