//! `[[clouds]]`: each entry's values checked (every error names `clouds[i].key` and the rule), its
//! coverage map loaded, and the wind's drift at a frame's moment.
//!
//! # Time and drift
//! The wind carries a layer's pattern by [`wind_drift`] over `seconds` of scene time, about the
//! planet's centre, with the layer's `wind` as the velocity at the planet-frame surface point
//! under the world origin (`planet.latitude`, `planet.longitude`): a point of the scene, not the
//! camera, so that moving the camera (flying in the viewer, a camera in orbit) never moves the
//! clouds. `seconds` is the frame's instant minus an origin, in UT seconds:
//! - the origin is the scene's own `time.date_time` when it has one, so a still at the scene's
//!   own moment shows each layer as its seed lays it out (no drift), and asking for another time
//!   of day, a viewer's clock or a time-lapse moves the clouds by `wind × (that time − the
//!   scene's)`;
//! - a scene without a date has J2000.0 (JD 2451545.0, 2000-01-01 12:00 UT) as its origin for
//!   the instants a time-lapse gives it;
//! - a frame without an instant (a scene without a date, drawn at a time of day) has no drift.
//!
//! Either way the drift is a smooth function of the instant, so a time-lapse drifts smoothly;
//! [`wind_drift`] reduces the angle itself, so years of wind are fine.

use std::path::Path;
use std::sync::Arc;

use firmament_core::CoreError;
use firmament_core::astro::time::J2000;
use firmament_core::atmosphere::Atmosphere;
use firmament_core::atmosphere::clouds::{CloudLayer, CoverageMap, DualHenyeyGreenstein, MAX_CLOUD_LAYERS, wind_drift};
use firmament_core::frame::AtmosphereSky;
use glam::DVec3;

use crate::assets::FileCache;
use crate::checks::{check, in_range};
use crate::error::SceneError;
use crate::model::{CloudEntry, Scene};

/// The densest cloud the format takes, m⁻¹ (visibility about 0.4 m; real clouds are below 0.3).
pub(crate) const MAX_CLOUD_DENSITY: f64 = 10.0;

/// The fastest wind the format takes, m/s, per component (Neptune's winds reach about 600).
pub(crate) const MAX_WIND_SPEED: f64 = 1000.0;

/// Seconds in a day, for Julian Dates.
const SECONDS_PER_DAY: f64 = 86_400.0;

/// The scene's cloud layers, every value checked and every coverage map loaded (relative paths
/// from the scene's folder); each layer without drift.
pub(super) fn clouds(scene: &Scene, atmosphere: &Atmosphere) -> Result<Vec<CloudLayer>, SceneError> {
    let entries = &scene.clouds;
    check(
        entries.len() <= MAX_CLOUD_LAYERS,
        "clouds",
        format!("{} layers", entries.len()),
        &format!(
            "at most {MAX_CLOUD_LAYERS} cloud layers (MAX_CLOUD_LAYERS, a fixed limit of the renderer that no key or \
             flag raises: merge layers)"
        ),
    )?;
    entries
        .iter()
        .enumerate()
        .map(|(i, entry)| layer(i, entry, scene, atmosphere))
        .collect()
}

fn layer(i: usize, entry: &CloudEntry, scene: &Scene, atmosphere: &Atmosphere) -> Result<CloudLayer, SceneError> {
    let key = |field: &str| format!("clouds[{i}].{field}");
    let (bottom, top) = (entry.bottom_m, entry.top_m);
    check(
        bottom.is_finite() && bottom >= 0.0,
        &key("bottom"),
        bottom,
        "must be a finite number of metres >= 0 (the altitude of the layer's base above the surface)",
    )?;
    check(
        top.is_finite() && top > bottom,
        &key("top"),
        top,
        &format!("must be a finite number of metres above clouds[{i}].bottom ({bottom} m): bottom < top"),
    )?;
    let ceiling = atmosphere.planet.atmosphere_height;
    check(
        top <= ceiling,
        &key("top"),
        top,
        &format!(
            "must be at most the top of the atmosphere, {ceiling} m above the surface (planet.atmosphere_height): \
             clouds lie inside the air"
        ),
    )?;
    in_range(
        &key("coverage"),
        entry.coverage,
        0.0,
        1.0,
        " (the share of the sky covered)",
    )?;
    in_range(
        &key("density"),
        entry.density_per_m,
        0.0,
        MAX_CLOUD_DENSITY,
        " per metre (the extinction at full density; typical cumulus 0.02 to 0.1)",
    )?;
    let [east, north] = entry.wind_mps;
    check(
        entry
            .wind_mps
            .iter()
            .all(|v| v.is_finite() && v.abs() <= MAX_WIND_SPEED),
        &key("wind"),
        format!("[{east}, {north}]"),
        &format!("[east, north] must each be a finite speed within ±{MAX_WIND_SPEED} m/s"),
    )?;
    in_range(
        &key("albedo"),
        entry.albedo,
        0.0,
        1.0,
        " (the single-scattering albedo)",
    )?;

    let mut layer = CloudLayer::new(bottom, top, entry.coverage, entry.density_per_m, entry.kind);
    layer.wind_mps = entry.wind_mps;
    layer.seed = entry.seed;
    layer.albedo = entry.albedo;
    if let Some(phase) = entry.phase {
        layer.phase = phase_function(&key("phase"), phase)?;
    }
    if let Some(file) = &entry.coverage_map {
        let key = key("coverage_map");
        let path = scene.asset_file(&key, file)?;
        layer.coverage_map = Some(coverage_map(&key, &path, scene)?.as_ref().clone());
    }
    Ok(layer)
}

/// `phase = [g_forward, g_back, blend]`, checked.
fn phase_function(key: &str, [g_forward, g_back, blend]: [f64; 3]) -> Result<DualHenyeyGreenstein, SceneError> {
    let shown = format!("[{g_forward}, {g_back}, {blend}]");
    let asymmetry = |g: f64| g.is_finite() && g.abs() < 1.0;
    check(
        asymmetry(g_forward),
        key,
        &shown,
        "g_forward (the first number) must be in (-1, 1)",
    )?;
    check(
        asymmetry(g_back),
        key,
        &shown,
        "g_back (the second number) must be in (-1, 1)",
    )?;
    check(
        blend.is_finite() && (0.0..=1.0).contains(&blend),
        key,
        &shown,
        "blend (the third number, the forward lobe's weight) must be in [0, 1]",
    )?;
    Ok(DualHenyeyGreenstein {
        g_forward,
        g_back,
        blend,
    })
}

/// Coverage maps made from files, while the files stay as they were.
static COVERAGE_MAPS: FileCache<CoverageMap> = FileCache::new();

/// The coverage map in the image file at `path`, made once while the file stays as it was.
fn coverage_map(key: &str, path: &Path, scene: &Scene) -> Result<Arc<CoverageMap>, SceneError> {
    COVERAGE_MAPS.get_or_make(
        &[path],
        scene.confinement.is_none(),
        |map| std::mem::size_of_val(map.values()),
        || read_coverage_map(key, path, scene),
    )
}

/// The coverage map in the image file at `path`: each texel's mean of red, green and blue as
/// 0–1, its top row at latitude +90°, its left column at longitude −180°.
fn read_coverage_map(key: &str, path: &Path, scene: &Scene) -> Result<CoverageMap, SceneError> {
    let image = crate::assets::load_texture_within(key, path, scene.confinement.as_ref())?;
    let (width, height) = (image.width, image.height);
    // A texture's row 0 is the bottom of the picture; the map's row 0 is its top.
    let values: Vec<f32> = (0..height)
        .rev()
        .flat_map(|t| (0..width).map(move |s| (s, t)))
        .map(|(s, t)| {
            image.texel(s, t).map_or(0.0, |[r, g, b, _]| {
                (f32::from(r) + f32::from(g) + f32::from(b)) / (3.0 * 255.0)
            })
        })
        .collect();
    CoverageMap::new(width, height, values).map_err(|e| SceneError::Asset {
        key: key.to_owned(),
        path: path.display().to_string(),
        reason: match e {
            CoreError::Invalid { rule, .. } | CoreError::InvalidItem { rule, .. } => {
                format!("not a coverage map: {rule}")
            }
            other => format!("not a coverage map: {other}"),
        },
    })
}

/// Seconds of wind at a frame's instant (Julian Date, UT): since the scene's own instant
/// `origin_jd` when it has a date, else since J2000.0; 0 without an instant. See the module docs.
pub(crate) fn wind_seconds(instant_jd: Option<f64>, origin_jd: Option<f64>) -> f64 {
    instant_jd.map_or(0.0, |jd| (jd - origin_jd.unwrap_or(J2000)) * SECONDS_PER_DAY)
}

/// Sets every layer's drift to where its wind has carried it after `seconds` (see the module
/// docs); no wind or no time leaves the layer where its seed put it.
pub(crate) fn drift(sky: &mut AtmosphereSky, seconds: f64) {
    let planet = sky.atmosphere.planet;
    let reference = planet.to_planet_frame(DVec3::ZERO);
    for layer in &mut sky.clouds {
        if seconds != 0.0 && layer.wind_mps != [0.0, 0.0] {
            layer.drift = wind_drift(&planet, reference, layer.wind_mps, seconds);
        }
    }
}

/// The scene key of one of the core's cloud field names (`clouds[2].density_per_m` →
/// `clouds[2].density`).
pub(super) fn scene_key(field: &str) -> Option<String> {
    let rest = field.strip_prefix("clouds[")?;
    let (index, name) = rest.split_once("].")?;
    let name = match name.split('.').next().unwrap_or(name) {
        "bottom_m" => "bottom",
        "top_m" => "top",
        "density_per_m" => "density",
        "wind_mps" => "wind",
        other => other,
    };
    Some(format!("clouds[{index}].{name}"))
}
