//! `planet.surface`, `planet.albedo_map`, `planet.water_map`, `planet.surface_seed` and
//! `planet.wind_speed`: the planet's surface ([`firmament_core::atmosphere::surface`]).
//!
//! Built-in surfaces are made once per process and shared: Earth's map is decoded from the
//! crate's `data/earth-surface.png` (its README says where it came from), a procedural one is
//! baked per seed; a user's maps are made once while their files stay as they were
//! ([`FileCache`]).

use std::path::Path;
use std::sync::{Arc, Mutex, OnceLock};

use firmament_core::CoreError;
use firmament_core::atmosphere::surface::{
    DEFAULT_WIND_SPEED_MPS, MAX_WIND_SPEED_MPS, Surface, SurfaceMap, procedural,
};
use firmament_core::color::srgb_to_linear;
use firmament_core::texture::TextureImage;

use crate::assets::FileCache;
use crate::checks::{check, in_range};
use crate::error::SceneError;
use crate::model::{Scene, SurfaceName};

/// Earth's surface map: RGB the sRGB-encoded albedo, alpha the water fraction.
const EARTH_SURFACE_PNG: &[u8] = include_bytes!("../../../data/earth-surface.png");

/// The scene's surface, or `None` when it names none (the medium's `ground_albedo` everywhere).
pub(super) fn surface(scene: &Scene) -> Result<Option<Surface>, SceneError> {
    let section = &scene.planet;
    let refuse = |key: &str, value: &dyn std::fmt::Display, rule: &str| Err(SceneError::invalid(key, value, rule));
    if let (Some(_), Some(map)) = (section.surface, &section.albedo_map) {
        return refuse(
            "planet.albedo_map",
            &format!("{map:?}"),
            "give either planet.surface (a built-in surface) or planet.albedo_map, not both",
        );
    }
    if let (None, Some(map)) = (&section.albedo_map, &section.water_map) {
        return refuse("planet.water_map", &format!("{map:?}"), "needs planet.albedo_map");
    }
    if let Some(seed) = section.surface_seed {
        check(seed >= 0, "planet.surface_seed", seed, "must be an integer >= 0")?;
        if section.surface != Some(SurfaceName::Procedural) {
            return refuse("planet.surface_seed", &seed, "needs planet.surface = \"procedural\"");
        }
    }
    let map = match (section.surface, &section.albedo_map) {
        (Some(SurfaceName::Earth), _) => earth()?,
        (Some(SurfaceName::Procedural), _) => procedural_map(section.surface_seed.unwrap_or(1) as u64)?,
        (None, Some(file)) => mapped(scene, file, section.water_map.as_deref())?,
        (None, None) => {
            if let Some(wind) = section.wind_speed {
                return refuse(
                    "planet.wind_speed",
                    &wind,
                    "needs a surface with water (planet.surface or planet.albedo_map)",
                );
            }
            return Ok(None);
        }
    };
    let wind_speed_mps = section.wind_speed.unwrap_or(DEFAULT_WIND_SPEED_MPS);
    in_range("planet.wind_speed", wind_speed_mps, 0.0, MAX_WIND_SPEED_MPS, " m/s")?;
    Ok(Some(Surface { map, wind_speed_mps }))
}

/// Earth's built-in map, decoded once.
fn earth() -> Result<Arc<SurfaceMap>, SceneError> {
    static EARTH: OnceLock<Result<Arc<SurfaceMap>, String>> = OnceLock::new();
    EARTH
        .get_or_init(|| {
            let image =
                crate::assets::load_texture_bytes("planet.surface", Path::new("earth-surface.png"), EARTH_SURFACE_PNG)
                    .map_err(|e| e.to_string())?;
            surface_map(&image, Water::Alpha)
                .map(Arc::new)
                .map_err(|e| e.to_string())
        })
        .clone()
        .map_err(|reason| SceneError::invalid("planet.surface", "\"earth\"", reason))
}

/// The procedural surface of `seed`, baked once per seed (the last few kept).
fn procedural_map(seed: u64) -> Result<Arc<SurfaceMap>, SceneError> {
    static BAKED: Mutex<Vec<(u64, Arc<SurfaceMap>)>> = Mutex::new(Vec::new());
    let mut baked = BAKED.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some((_, map)) = baked.iter().find(|(s, _)| *s == seed) {
        return Ok(map.clone());
    }
    let (width, height) = procedural::DEFAULT_SIZE;
    let map = Arc::new(
        procedural::bake(seed, width, height)
            .map_err(|e| SceneError::invalid("planet.surface_seed", seed, e.to_string()))?,
    );
    if baked.len() >= 4 {
        baked.remove(0);
    }
    baked.push((seed, map.clone()));
    Ok(map)
}

/// Surface maps made from files, while the files stay as they were.
static MAPPED: FileCache<SurfaceMap> = FileCache::new();

/// The map of the scene's `albedo_map` file and, if given, its `water_map` file, made once while
/// the files stay as they were.
fn mapped(scene: &Scene, albedo_file: &str, water_file: Option<&str>) -> Result<Arc<SurfaceMap>, SceneError> {
    let albedo_path = scene.asset_file("planet.albedo_map", albedo_file)?;
    let water_path = water_file
        .map(|file| scene.asset_file("planet.water_map", file))
        .transpose()?;
    let mut paths = vec![albedo_path.as_path()];
    paths.extend(water_path.as_deref());
    MAPPED.get_or_make(
        &paths,
        scene.confinement.is_none(),
        |map| map.width() as usize * map.height() as usize * std::mem::size_of::<[f32; 4]>(),
        || {
            read_mapped(
                scene,
                (albedo_file, &albedo_path),
                water_file.zip(water_path.as_deref()),
            )
        },
    )
}

/// The map of the albedo image that `key` names as `file`, all land (a body's map), made once
/// while the file stays as it was.
pub(crate) fn albedo_map(scene: &Scene, key: &str, file: &str) -> Result<Arc<SurfaceMap>, SceneError> {
    let path = scene.asset_file(key, file)?;
    MAPPED.get_or_make(
        &[path.as_path()],
        scene.confinement.is_none(),
        |map| map.width() as usize * map.height() as usize * std::mem::size_of::<[f32; 4]>(),
        || {
            let image = crate::assets::load_texture_within(key, &path, scene.confinement.as_ref())?;
            surface_map(&image, Water::None).map_err(|e| SceneError::invalid(key, file, e.to_string()))
        },
    )
}

/// The map of the albedo image and the water image (each its scene value and resolved path).
fn read_mapped(
    scene: &Scene,
    (albedo_file, albedo_path): (&str, &Path),
    water: Option<(&str, &Path)>,
) -> Result<SurfaceMap, SceneError> {
    let load = |key: &str, path: &Path| -> Result<TextureImage, SceneError> {
        crate::assets::load_texture_within(key, path, scene.confinement.as_ref())
    };
    let water_file = water.map(|(file, _)| file);
    let albedo = load("planet.albedo_map", albedo_path)?;
    let water = water.map(|(_, path)| load("planet.water_map", path)).transpose()?;
    if let (Some(w), Some(file)) = (&water, water_file)
        && (w.width, w.height) != (albedo.width, albedo.height)
    {
        return Err(SceneError::invalid(
            "planet.water_map",
            format!("{file:?} ({}x{})", w.width, w.height),
            format!(
                "must have the size of planet.albedo_map ({}x{})",
                albedo.width, albedo.height
            ),
        ));
    }
    let water = water.as_ref().map_or(Water::None, Water::Image);
    surface_map(&albedo, water).map_err(|e| SceneError::invalid("planet.albedo_map", albedo_file, e.to_string()))
}

/// Where a surface map's water comes from.
#[derive(Clone, Copy)]
enum Water<'a> {
    /// Nowhere: all land.
    None,
    /// The albedo image's alpha (the built-in map).
    Alpha,
    /// An image of its own, the mean of its RGB (0–1).
    Image(&'a TextureImage),
}

/// A surface map from an albedo image (RGB sRGB-encoded) and its water.
fn surface_map(albedo: &TextureImage, water: Water<'_>) -> Result<SurfaceMap, CoreError> {
    let (width, height) = (albedo.width, albedo.height);
    // A texture's row 0 is the bottom of the picture; the map's row 0 is its top.
    let texels = (0..height)
        .rev()
        .flat_map(|t| (0..width).map(move |s| (s, t)))
        .map(|(s, t)| {
            let [r, g, b, a] = albedo.texel(s, t).unwrap_or([0; 4]);
            let linear = |v: u8| srgb_to_linear(f64::from(v) / 255.0) as f32;
            let wet = match water {
                Water::None => 0.0,
                Water::Alpha => f32::from(a) / 255.0,
                Water::Image(w) => w.texel(s, t).map_or(0.0, |[r, g, b, _]| {
                    (f32::from(r) + f32::from(g) + f32::from(b)) / (3.0 * 255.0)
                }),
            };
            [linear(r), linear(g), linear(b), wet]
        })
        .collect();
    SurfaceMap::new(width, height, texels)
}
