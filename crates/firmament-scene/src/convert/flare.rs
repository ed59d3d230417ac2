//! From `[flare]` and the `[[lights]]` marked `flare = true` to the core's [`FlareLayer`]: the
//! flare (a preset's elements or the scene's own), checked, and its sources in the world frame.
//!
//! # Sources
//! - **Lights** with `flare = true`: the light's position (`w ≠ 0`, as the point `xyz/w`) or
//!   direction (`w = 0`) in the world frame — an eye-space light (`space = "eye"`) is carried
//!   there by the inverse of the camera's view matrix — with `flare_radius` (metres for a point,
//!   default 0.05; radians for a direction, default 0.005) and the light's diffuse RGB (negative
//!   channels as 0) as its colour.
//! - **Suns**, for each sky model:
//!   - `"atmosphere"` (physical): every sun of `[[suns]]`, its angular radius, and as colour its
//!     light at the camera through the air relative to the same sun in space — `E·T/π` over the
//!     luminance of `E/π`, linear sRGB — so a sun in a clear sky has luminance ≈ 1, a setting one
//!     is red and dim, and one below the horizon (colour 0) is left out;
//!   - `"atmosphere"` with `atmosphere.model = "seed"`: every star of the seed sky, in its
//!     direction from the camera, its angular radius seen from there, and as colour the star's
//!     colour scaled to luminance 1 times what the seed's own 8-step extinction lets through
//!     along that line of sight ([`EmpiricalAtmosphere::star_transmittance`](firmament_core::atmosphere::empirical::EmpiricalAtmosphere::star_transmittance):
//!     reddened and dimmed near the seed's horizon); left out when the seed's planet hides it;
//!   - `"gradient"`: the sun of `[sun]` at the frame's time, its colour the keyframes' `sun`
//!     colour at that time (linear; white at noon in the default cycle, orange at sunset, black
//!     at night, which leaves it out); left out too when its whole disc is below the horizon
//!     (`z < −sin r`);
//!   - `"clear"`: none.

use std::path::PathBuf;
use std::sync::Arc;

use firmament_core::classic::scene::LightSpace;
use firmament_core::flare::{
    Aperture, FlareElement, FlareLayer, FlareShape, FlareSource, LensFlare, MAX_FLARE_ELEMENTS, MAX_FLARE_IMAGES,
    MAX_FLARE_SAMPLES, MAX_FLARE_SOURCES,
};
use firmament_core::frame::{AtmosphereSky, EmpiricalSky, Sky};
use firmament_core::geometry::Ray;
use firmament_core::texture::TextureImage;
use firmament_core::{Camera, CoreError};
use glam::DVec3;

use crate::checks::check;
use crate::error::SceneError;
use crate::model::{FlareElementEntry, FlareKindName, LightEntry, Scene};

/// A light's `flare_radius` when absent: metres, for a positional light.
pub(crate) const DEFAULT_POINT_FLARE_RADIUS: f64 = 0.05;
/// A light's `flare_radius` when absent: radians, for a directional light (`w = 0`).
pub(crate) const DEFAULT_DIRECTIONAL_FLARE_RADIUS: f64 = 0.005;

/// A core flare error as a scene error: the core already names the scene key (`flare.…`).
fn from_core(error: CoreError) -> SceneError {
    match error {
        CoreError::InvalidItem { field, value, rule } => SceneError::invalid(field, value, rule),
        CoreError::Invalid { field, value, rule } => SceneError::invalid(field, value, rule),
        other => SceneError::invalid("flare", "[flare]", other.to_string()),
    }
}

/// The image files of a flare's elements, each loaded once.
struct FlareImages<'a> {
    /// The scene, whose folder (or confinement) relative paths are resolved in.
    scene: &'a Scene,
    /// The resolved path of each image, in the order first used.
    paths: Vec<PathBuf>,
    /// The images, resampled for the flare's texture array.
    images: Vec<Arc<TextureImage>>,
}

impl FlareImages<'_> {
    /// The index of `file` (loaded on first use) for the element whose key is `key`.
    fn index_of(&mut self, key: &str, file: &str) -> Result<u32, SceneError> {
        let path = self.scene.asset_file(key, file)?;
        if let Some(index) = self.paths.iter().position(|p| *p == path) {
            return Ok(index as u32);
        }
        check(
            self.images.len() < MAX_FLARE_IMAGES,
            key,
            format!("{file:?}"),
            "a flare may use at most 16 different image files (MAX_FLARE_IMAGES, a fixed limit of the flare pass \
             that no key raises: let elements share files)",
        )?;
        let image = crate::assets::load_flare_image_within(key, &path, self.scene.confinement.as_ref())?;
        self.paths.push(path);
        self.images.push(Arc::new(image));
        Ok(self.images.len() as u32 - 1)
    }
}

/// Element `i` of `flare.elements`; values that do not belong to its kind are errors.
fn element(i: usize, e: &FlareElementEntry, images: &mut FlareImages<'_>) -> Result<FlareElement, SceneError> {
    let key = |field: &str| format!("flare.elements[{i}].{field}");
    let kind = match e.kind {
        FlareKindName::Glow => "glow",
        FlareKindName::Streaks => "streaks",
        FlareKindName::Halo => "halo",
        FlareKindName::Ghost => "ghost",
        FlareKindName::Image => "image",
    };
    let allowed: &[&str] = match e.kind {
        FlareKindName::Glow => &[],
        FlareKindName::Streaks => &["points", "rotation", "sharpness"],
        FlareKindName::Halo => &["thickness"],
        FlareKindName::Ghost => &["sides", "rotation", "softness"],
        FlareKindName::Image => &["rotation"],
    };
    match (&e.file, e.kind) {
        (None, FlareKindName::Image) => {
            return Err(SceneError::invalid(
                key("file"),
                "(absent)",
                "an image element needs `file`, the picture to draw",
            ));
        }
        (Some(file), kind) if kind != FlareKindName::Image => {
            return Err(SceneError::invalid(
                key("file"),
                format!("{file:?}"),
                "only an image element (kind = \"image\") takes a file",
            ));
        }
        _ => {}
    }
    let given = [
        ("points", e.points.map(f64::from)),
        ("rotation", e.rotation_deg),
        ("sharpness", e.sharpness),
        ("thickness", e.thickness),
        ("sides", e.sides.map(f64::from)),
        ("softness", e.softness),
    ];
    for (field, value) in given {
        if let Some(value) = value {
            let rule = if allowed.is_empty() {
                format!("a {kind} element takes no shape values (kind = \"{kind}\")")
            } else {
                format!(
                    "not a value of a {kind} element (kind = \"{kind}\" takes {})",
                    allowed.join(", ")
                )
            };
            check(allowed.contains(&field), &key(field), value, &rule)?;
        }
    }
    let shape = match e.kind {
        FlareKindName::Glow => FlareShape::Glow,
        FlareKindName::Streaks => FlareShape::Streaks {
            points: e.points.unwrap_or(6),
            rotation: e.rotation_deg.unwrap_or(0.0),
            sharpness: e.sharpness.unwrap_or(24.0),
        },
        FlareKindName::Halo => FlareShape::Halo {
            thickness: e.thickness.unwrap_or(0.25),
        },
        FlareKindName::Ghost => FlareShape::Ghost {
            sides: e.sides.unwrap_or(6),
            rotation: e.rotation_deg.unwrap_or(0.0),
            softness: e.softness.unwrap_or(0.15),
        },
        FlareKindName::Image => FlareShape::Image {
            image: images.index_of(&key("file"), e.file.as_deref().unwrap_or_default())?,
            rotation: e.rotation_deg.unwrap_or(0.0),
        },
    };
    Ok(FlareElement {
        shape,
        color: DVec3::from_array(e.color),
        intensity: e.intensity,
        size: e.size,
        stretch: e.stretch,
        position: e.position,
    })
}

/// The scene's lens flare (whether or not it is enabled), every value checked.
pub(crate) fn lens_flare(scene: &Scene) -> Result<LensFlare, SceneError> {
    let f = &scene.flare;
    let base = LensFlare::preset(f.preset.name()).ok_or_else(|| {
        SceneError::invalid(
            "flare.preset",
            f.preset.name(),
            "not a built-in flare (classic, subtle, anamorphic)",
        )
    })?;
    // The core checks these too; here the message says they are fixed, and no image is loaded for
    // a list that is too long.
    check(
        (1..=MAX_FLARE_SAMPLES).contains(&f.samples),
        "flare.samples",
        f.samples,
        &format!(
            "must be 1 to {MAX_FLARE_SAMPLES} (MAX_FLARE_SAMPLES, a fixed limit of the flare pass that no key \
             raises)"
        ),
    )?;
    let listed = f.elements.as_ref().map_or(0, Vec::len);
    check(
        listed <= MAX_FLARE_ELEMENTS,
        "flare.elements",
        format!("{listed} elements"),
        &format!(
            "at most {MAX_FLARE_ELEMENTS} elements (MAX_FLARE_ELEMENTS, a fixed limit of the flare pass that no \
             key raises: drop the faintest elements)"
        ),
    )?;
    let mut images = FlareImages {
        scene,
        paths: Vec::new(),
        images: Vec::new(),
    };
    let elements = match &f.elements {
        None => base.elements,
        Some(list) => list
            .iter()
            .enumerate()
            .map(|(i, e)| element(i, e, &mut images))
            .collect::<Result<Vec<_>, _>>()?,
    };
    let flare = LensFlare {
        elements,
        samples: f.samples,
        margin: f.margin,
        intensity: f.intensity,
        fade_in: f.fade_in,
        fade_out: f.fade_out,
        images: images.images,
        aperture: Aperture {
            blades: f.aperture_blades.unwrap_or(base.aperture.blades),
            rotation: f.aperture_rotation.unwrap_or(base.aperture.rotation),
        },
        glare: f.glare,
    };
    flare.validate().map_err(from_core)?;
    Ok(flare)
}

/// Light `i`'s `flare_radius`: the given one, checked, or the default for its kind.
fn light_flare_radius(i: usize, entry: &LightEntry, directional: bool) -> Result<f64, SceneError> {
    let key = format!("lights[{i}].flare_radius");
    match entry.flare_radius {
        None if directional => Ok(DEFAULT_DIRECTIONAL_FLARE_RADIUS),
        None => Ok(DEFAULT_POINT_FLARE_RADIUS),
        Some(r) if directional => {
            check(
                r.is_finite() && r > 0.0 && r < std::f64::consts::FRAC_PI_2,
                &key,
                r,
                "a directional light's (w = 0) flare radius is an angle in radians, in (0, π/2)",
            )?;
            Ok(r)
        }
        Some(r) => {
            check(r.is_finite() && r > 0.0, &key, r, "must be a finite radius > 0 metres")?;
            Ok(r)
        }
    }
}

/// The flare sources of `[[lights]]` (those marked `flare = true`), world frame, for `camera`.
fn light_sources(scene: &Scene, camera: &Camera) -> Result<Vec<FlareSource>, SceneError> {
    let eye_to_world = camera.view_matrix().inverse();
    let mut sources = Vec::new();
    for (i, entry) in scene.lights.iter().enumerate() {
        // The light's own rules (position, colours) are checked with the lighting.
        let light = super::objects::light(i, entry)?;
        let p = light.light.position;
        let radius = light_flare_radius(i, entry, p.w == 0.0)?;
        if !entry.flare {
            continue;
        }
        let p = match light.space {
            LightSpace::Eye => eye_to_world * p,
            LightSpace::World => p,
        };
        let position = if p.w == 0.0 {
            p
        } else {
            (p.truncate() / p.w).extend(1.0)
        };
        check(
            position.is_finite(),
            &format!("lights[{i}].position"),
            format!("{:?}", light.light.position.to_array()),
            "a flare light's position must stay finite in the world frame",
        )?;
        sources.push(FlareSource {
            position,
            radius,
            color: light.light.diffuse.truncate().max(DVec3::ZERO),
        });
    }
    Ok(sources)
}

/// Luminance of linear sRGB (Rec. 709 weights).
fn luminance(c: DVec3) -> f64 {
    c.dot(DVec3::new(0.2126, 0.7152, 0.0722))
}

/// The physical atmosphere's suns as seen through the air from `eye` (see the module docs).
fn atmosphere_sources(sky: &AtmosphereSky, eye: DVec3) -> Vec<FlareSource> {
    let light = firmament_core::classic::sky_light::SkyLight::new(sky);
    let conversion = sky.atmosphere.spectral_conversion();
    sky.suns
        .iter()
        .zip(light.sun_colors(eye))
        // The Moon as a light (no disc of its own) gives no flare.
        .filter(|(sun, _)| sun.disc)
        .filter_map(|(sun, seen)| {
            let space = conversion.linear_srgb(sun.irradiance / std::f64::consts::PI);
            let unattenuated = luminance(DVec3::new(space.r, space.g, space.b));
            let color = seen.truncate() / unattenuated;
            (unattenuated > 0.0 && color.is_finite() && color.max_element() > 0.0).then(|| FlareSource {
                position: sun.direction.normalize().extend(0.0),
                radius: sun.angular_radius,
                color,
            })
        })
        .collect()
}

/// The empirical sky's stars seen from `eye`: white, left out where its planet hides them.
fn empirical_sources(sky: &EmpiricalSky, eye: DVec3) -> Vec<FlareSource> {
    let at = sky.to_planet_frame(eye);
    let surface = sky.atmosphere.surface();
    sky.stars
        .iter()
        .filter_map(|star| {
            let to = star.position - at;
            let distance = to.length();
            let ray = Ray::new(at, to)?;
            // Hidden when the line of sight runs into the ground (a hit ahead of the eye).
            if surface.intersect(&ray).is_some_and(|hits| hits.far > 1.0) {
                return None;
            }
            let angular_radius = (star.radius / distance).min(1.0).asin();
            let direction = sky.orientation.normalize() * ray.direction;
            let own = luminance(star.color);
            let color = star.color / own * sky.atmosphere.star_transmittance(at, ray.direction);
            (angular_radius > 0.0 && own > 0.0 && direction.is_finite() && color.max_element() > 0.0).then(|| {
                FlareSource {
                    position: direction.extend(0.0),
                    radius: angular_radius,
                    color,
                }
            })
        })
        .collect()
}

/// The suns of the frame's sky as flare sources (see the module docs).
fn sun_sources(sky: &Sky, eye: DVec3) -> Vec<FlareSource> {
    match sky {
        Sky::Atmosphere(sky) => atmosphere_sources(sky, eye),
        Sky::Empirical(sky) => empirical_sources(sky, eye),
        Sky::Gradient(state) => {
            let sun = &state.sun;
            let direction = sun.direction.normalize();
            let tint = state.bands.sun;
            let color = DVec3::new(tint.r, tint.g, tint.b).max(DVec3::ZERO);
            if direction.z < -sun.angular_radius.sin() || !color.is_finite() || color.max_element() <= 0.0 {
                return Vec::new();
            }
            vec![FlareSource {
                position: direction.extend(0.0),
                radius: sun.angular_radius,
                color,
            }]
        }
        Sky::Clear(_) => Vec::new(),
    }
}

/// Checks `[flare]` and the lights' flare values without building a frame.
pub(crate) fn validate(scene: &Scene) -> Result<(), SceneError> {
    lens_flare(scene)?;
    light_sources(scene, &scene.camera())?;
    Ok(())
}

/// The frame's flares for `camera` over `sky`: none unless `flare.enabled`.
pub(crate) fn flare_layer(scene: &Scene, camera: &Camera, sky: &Sky) -> Result<FlareLayer, SceneError> {
    let flare = lens_flare(scene)?;
    let lights = light_sources(scene, camera)?;
    if !scene.flare.enabled {
        return Ok(FlareLayer::default());
    }
    let mut sources = sun_sources(sky, camera.position);
    sources.extend(lights);
    check(
        sources.len() <= MAX_FLARE_SOURCES,
        "flare",
        format!("{} sources", sources.len()),
        "at most 64 flare sources, suns and lights with flare = true (MAX_FLARE_SOURCES, a fixed limit of the \
         flare pass that no key raises: set flare = false on the weakest lights)",
    )?;
    Ok(FlareLayer {
        flare: Some(flare),
        sources,
    })
}
