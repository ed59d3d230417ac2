//! Every rule a scene's values must follow, each error naming the key path, value and rule.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

use firmament_core::TimeOfDay;
use firmament_core::classic::mesh::{GLU_CACHE_SIZE, MAX_GLT_SPHERE_DIVISIONS, MAX_QUAD_SUBDIVISIONS};

use crate::assets::Confinement;
use crate::checks::{check, in_range, non_negative, positive, time_of_day};
use crate::convert::{atmosphere, flare, objects};
use crate::error::SceneError;
use crate::model::{AtmosphereModelName, MeshEntry, Scene, SkyModelName};

/// Largest image side the scene format accepts, pixels. The GPU's own limit may be lower; the
/// renderer checks that one.
pub const MAX_IMAGE_SIDE: u32 = 16_384;

/// Farthest the camera may be from the world origin, metres (10¹⁵ m, about 6700 AU): far past
/// the 100 AU firmament is tested to, and short of distances where a planet is a speck below
/// a pixel and `f64` positions themselves lose the metre.
pub const MAX_CAMERA_DISTANCE: f64 = 1.0e15;

/// The most `[[objects]]` entries one scene may have (each costs about 20 KB to draw, whatever
/// its mesh).
pub(crate) const MAX_OBJECTS: usize = 16_384;

/// The most triangles the built-in shapes (`glt_sphere`, `glu_sphere`, `quad`, `cube`) of one
/// scene may have together: about 1.7 GB and half a minute to build at the most (a
/// `glt_sphere` of 2896 × 2896). Mesh files are bounded by their loaders.
pub(crate) const MAX_SHAPE_TRIANGLES: u64 = 1 << 24;

impl Scene {
    /// Checks every rule of the scene format, as loading a file does: after changing fields in
    /// code, before drawing. The error names the key, the value and the rule.
    pub fn validate(&self) -> Result<(), SceneError> {
        validate(self)
    }
}

/// Checks every rule of the format.
pub(crate) fn validate(scene: &Scene) -> Result<(), SceneError> {
    let side = format!(
        "must be 1 to {MAX_IMAGE_SIDE} pixels (a fixed limit of the scene format that no key or flag raises; \
         firmament does not render an image in tiles)"
    );
    check(
        (1..=MAX_IMAGE_SIDE).contains(&scene.render.width),
        "render.width",
        scene.render.width,
        &side,
    )?;
    check(
        (1..=MAX_IMAGE_SIDE).contains(&scene.render.height),
        "render.height",
        scene.render.height,
        &side,
    )?;

    let cam = &scene.camera;
    let [e, n, u] = cam.position;
    check(
        [e, n, u].iter().all(|v| v.is_finite()),
        "camera.position",
        format!("[{e}, {n}, {u}]"),
        "every component must be a finite number of metres",
    )?;
    check(
        glam::DVec3::from_array(cam.position).length() <= MAX_CAMERA_DISTANCE,
        "camera.position",
        format!("[{e:e}, {n:e}, {u:e}]"),
        &format!(
            "must be within {:e} m (about 6700 AU) of the origin (a fixed limit of the scene format that no key \
             raises; firmament is tested to 100 AU)",
            MAX_CAMERA_DISTANCE
        ),
    )?;
    // Over an atmosphere the ground is curved: the altitude rule below replaces this one.
    check(
        u >= 0.0 || scene.sky.model != SkyModelName::Gradient,
        "camera.position",
        format!("[{e}, {n}, {u}]"),
        "the camera must be above the ground (up >= 0)",
    )?;
    check(
        cam.heading_deg.is_finite(),
        "camera.heading",
        cam.heading_deg,
        "must be a finite number of degrees",
    )?;
    in_range("camera.pitch", cam.pitch_deg, -90.0, 90.0, " degrees")?;
    check(
        cam.roll_deg.is_finite(),
        "camera.roll",
        cam.roll_deg,
        "must be a finite number of degrees",
    )?;
    check(
        cam.fov_y_deg.is_finite() && cam.fov_y_deg > 0.0 && cam.fov_y_deg < 180.0,
        "camera.fov_y",
        cam.fov_y_deg,
        "must be in (0, 180) degrees",
    )?;
    positive("camera.near", cam.near, " metres")?;
    if let Some(far) = cam.far {
        check(
            far.is_finite() && far > cam.near,
            "camera.far",
            far,
            "must be a finite number of metres > camera.near (omit it for an infinite far plane)",
        )?;
    }

    crate::convert::time::validate(scene)?;

    let sun = &scene.sun;
    in_range("sun.latitude", sun.latitude_deg, -90.0, 90.0, " degrees")?;
    in_range("sun.declination", sun.declination_deg, -90.0, 90.0, " degrees")?;
    check(
        sun.angular_radius_deg.is_finite() && sun.angular_radius_deg > 0.0 && sun.angular_radius_deg <= 10.0,
        "sun.angular_radius",
        sun.angular_radius_deg,
        "must be in (0, 10] degrees",
    )?;
    non_negative("sun.disc_intensity", sun.disc_intensity)?;
    non_negative("sun.glow_intensity", sun.glow_intensity)?;
    check(
        sun.glow_falloff_deg.is_finite() && sun.glow_falloff_deg > 0.0 && sun.glow_falloff_deg <= 180.0,
        "sun.glow_falloff",
        sun.glow_falloff_deg,
        "must be in (0, 180] degrees",
    )?;
    check(
        sun.edge_softness.is_finite() && sun.edge_softness > 0.0 && sun.edge_softness <= 1.0,
        "sun.edge_softness",
        sun.edge_softness,
        "must be in (0, 1]",
    )?;

    positive("display.exposure", scene.display.exposure, "")?;
    if let Some(ev) = scene.display.ev100 {
        in_range("display.ev100", ev, -20.0, 40.0, " (EV at ISO 100)")?;
    }
    let display = &scene.display;
    in_range(
        "display.auto_ev_min",
        display.auto_ev_min,
        -20.0,
        40.0,
        " (EV at ISO 100)",
    )?;
    in_range(
        "display.auto_ev_max",
        display.auto_ev_max,
        -20.0,
        40.0,
        " (EV at ISO 100)",
    )?;
    check(
        display.auto_ev_min <= display.auto_ev_max,
        "display.auto_ev_min",
        display.auto_ev_min,
        &format!("must be <= display.auto_ev_max ({})", display.auto_ev_max),
    )?;
    in_range(
        "display.auto_compensation",
        display.auto_compensation,
        -10.0,
        10.0,
        " EV",
    )?;
    positive("display.auto_speed_up", display.auto_speed_up, " EV per second")?;
    positive("display.auto_speed_down", display.auto_speed_down, " EV per second")?;
    in_range("display.bloom", display.bloom, 0.0, 1.0, "")?;

    let g = &scene.sky.gradient;
    check(
        g.horizon_half_width_deg.is_finite() && g.horizon_half_width_deg > 0.0 && g.horizon_half_width_deg < 90.0,
        "sky.gradient.horizon_half_width",
        g.horizon_half_width_deg,
        "must be in (0, 90) degrees",
    )?;
    check(
        g.zenith_start_deg.is_finite() && g.zenith_start_deg > g.horizon_half_width_deg && g.zenith_start_deg <= 90.0,
        "sky.gradient.zenith_start",
        g.zenith_start_deg,
        "must be above the horizon band (> horizon_half_width) and at most 90 degrees",
    )?;
    check(
        g.ground_start_deg.is_finite() && g.ground_start_deg < -g.horizon_half_width_deg && g.ground_start_deg >= -90.0,
        "sky.gradient.ground_start",
        g.ground_start_deg,
        "must be below the horizon band (< -horizon_half_width) and at least -90 degrees",
    )?;
    positive("sky.gradient.upper_exponent", g.upper_exponent, "")?;
    positive("sky.gradient.lower_exponent", g.lower_exponent, "")?;
    check(
        !g.keyframes.is_empty(),
        "sky.gradient.keyframes",
        "[]",
        "needs at least one keyframe",
    )?;
    let mut seen: Vec<(TimeOfDay, usize)> = Vec::with_capacity(g.keyframes.len());
    for (i, k) in g.keyframes.iter().enumerate() {
        let key = format!("sky.gradient.keyframes[{i}].time");
        let t = time_of_day(&key, &k.time)?;
        if let Some((_, first)) = seen.iter().find(|(s, _)| *s == t) {
            return Err(SceneError::invalid(
                key,
                format!("\"{}\"", k.time),
                format!("keyframe {first} has the same time; each keyframe needs its own"),
            ));
        }
        seen.push((t, i));
    }

    let mut sky = atmosphere::sky(scene)?;
    let instant = match scene.date_time()? {
        Some(civil) => Some(scene.instant(&civil)?),
        None => None,
    };
    crate::convert::bodies::add_bodies(scene, instant.as_ref(), &mut sky)?;
    // The seed's values are checked whenever the scene picks the seed model; its planet (the
    // seed's radii) is then the one the camera must be above.
    let planet = match scene.atmosphere.model {
        AtmosphereModelName::Physical => sky.atmosphere.planet,
        AtmosphereModelName::Empirical => atmosphere::empirical_planet(&atmosphere::empirical_sky(scene, &sky)?),
    };
    if scene.sky.model == SkyModelName::Atmosphere {
        atmosphere::camera_above_surface(scene, &planet)?;
    }
    let clear = scene.sky.clear_color.rgba();
    check(
        clear.iter().all(|c| c.is_finite() && *c >= 0.0),
        "sky.clear_color",
        format!("{clear:?}"),
        "every component must be a finite number >= 0",
    )?;
    check(
        scene.objects.len() <= MAX_OBJECTS,
        "objects",
        format!("{} objects", scene.objects.len()),
        &format!(
            "at most {MAX_OBJECTS} objects (a fixed limit of the scene format that no key or flag raises; \
             each object is drawn on its own: merge objects into one mesh file)"
        ),
    )?;
    if let Some(confinement) = &scene.confinement {
        check_confined(scene, confinement)?;
    }
    let mut triangles = 0_u64;
    for (i, object) in scene.objects.iter().enumerate() {
        let own = shape_triangles(&object.mesh);
        triangles = triangles.saturating_add(own);
        check(
            triangles <= MAX_SHAPE_TRIANGLES,
            &format!("objects[{i}].mesh"),
            format!("{own} triangles"),
            &format!(
                "the built-in shapes of a scene may have at most {MAX_SHAPE_TRIANGLES} triangles together \
                 (a glt_sphere of 2896 x 2896), and objects[0..={i}] have {triangles}: use fewer or coarser \
                 shapes (slices, stacks, subdivisions), or a mesh file (a fixed limit of the scene format that no key \
                 or flag raises)"
            ),
        )?;
    }
    objects::validate(scene)?;
    flare::validate(scene)?;
    log_paths_outside(scene);
    Ok(())
}

/// Under a confinement (untrusted mode): every file the scene names resolves inside its folder
/// — checked on the paths and the links in the folder, before any file is read — and the
/// built-in shapes stay within its triangles (mesh files are counted as they load).
fn check_confined(scene: &Scene, confinement: &Confinement) -> Result<(), SceneError> {
    for (key, written) in scene.written_asset_paths() {
        confinement.resolve(&key, &scene.base_dir, Path::new(written))?;
    }
    let triangles = scene
        .objects
        .iter()
        .map(|o| shape_triangles(&o.mesh))
        .fold(0, u64::saturating_add);
    let max = confinement.limits().max_triangles;
    check(
        triangles <= max,
        "objects",
        format!("{triangles} triangles of built-in shapes"),
        &untrusted_triangles_rule(max),
    )
}

/// The rule of untrusted mode's triangle limit `max`, for messages.
pub(crate) fn untrusted_triangles_rule(max: u64) -> String {
    format!(
        "untrusted mode allows at most {max} triangles in a scene's objects together (AssetLimits::max_triangles; \
         the command line raises it with --max-triangles)"
    )
}

/// Triangles a built-in shape will have, before it is built: the counts the core's builders give.
/// 0 for a mesh file (its loader bounds it) and for a shape its builder refuses (its own rule then
/// names the value).
fn shape_triangles(mesh: &MeshEntry) -> u64 {
    match *mesh {
        MeshEntry::GltSphere { slices, stacks, .. } => {
            if slices.max(stacks) > MAX_GLT_SPHERE_DIVISIONS {
                return 0;
            }
            2 * u64::from(slices) * u64::from(stacks)
        }
        MeshEntry::GluSphere { slices, stacks, .. } => {
            // GLU lowers both to its cache's size first.
            let (slices, stacks) = (slices.min(GLU_CACHE_SIZE - 1), stacks.min(GLU_CACHE_SIZE - 1));
            2 * u64::from(slices) * u64::from(stacks)
        }
        MeshEntry::Quad { subdivisions, .. } => {
            if subdivisions > MAX_QUAD_SUBDIVISIONS {
                return 0;
            }
            2 * u64::from(subdivisions) * u64::from(subdivisions)
        }
        MeshEntry::Cube { .. } => 12,
        MeshEntry::File { .. } => 0,
    }
}

/// Says in the log (once per file and key in a process) when a file the scene reads lies outside
/// its folder (the working directory for a scene without a file): an absolute path elsewhere, or
/// a relative one that climbs out with `..`. Judged on the paths as written, without following
/// links.
fn log_paths_outside(scene: &Scene) {
    let paths = scene.asset_paths();
    if paths.is_empty() {
        return;
    }
    let base = crate::assets::lexical_absolute(&scene.base_dir);
    static LOGGED: OnceLock<Mutex<HashSet<(String, PathBuf)>>> = OnceLock::new();
    for (key, path) in paths {
        let resolved = crate::assets::lexical_absolute(&path);
        if resolved.starts_with(&base) {
            continue;
        }
        let first = LOGGED
            .get_or_init(Mutex::default)
            .lock()
            .map(|mut logged| logged.insert((key.clone(), resolved.clone())))
            .unwrap_or(true);
        if first {
            let folder = if scene.base_dir.as_os_str().is_empty() {
                format!("the working directory {}", base.display())
            } else {
                format!("the scene's folder {}", base.display())
            };
            tracing::info!("{key}: reads {}, outside {folder}", resolved.display());
        }
    }
}

#[cfg(test)]
mod tests {
    use firmament_core::classic::mesh::Mesh;

    use super::*;

    #[test]
    fn shape_triangle_counts_are_the_builders_own() {
        let cases = [
            (
                MeshEntry::GltSphere {
                    radius: 1.0,
                    slices: 7,
                    stacks: 5,
                },
                Mesh::glt_sphere(1.0, 7, 5),
            ),
            (
                MeshEntry::GluSphere {
                    radius: 1.0,
                    slices: 7,
                    stacks: 5,
                },
                Mesh::glu_sphere(1.0, 7, 5),
            ),
            (
                MeshEntry::GluSphere {
                    radius: 1.0,
                    slices: 1000,
                    stacks: 300,
                },
                Mesh::glu_sphere(1.0, 1000, 300),
            ),
            (
                MeshEntry::Quad {
                    size: 1.0,
                    subdivisions: 3,
                },
                Mesh::quad(1.0, 3),
            ),
            (MeshEntry::Cube { size: 1.0 }, Mesh::cube(1.0)),
        ];
        for (entry, mesh) in cases {
            let built = mesh.expect("a valid shape").triangle_count() as u64;
            assert_eq!(shape_triangles(&entry), built, "{entry:?}");
        }
    }

    #[test]
    fn the_camera_stays_within_the_distance_limit() {
        let mut scene = Scene::preset("earth-orbit").expect("preset");
        scene.camera.position = [0.0, 0.0, 1.5e13]; // 100 AU
        assert!(validate(&scene).is_ok());
        scene.camera.position = [0.0, 0.0, 1.0e300];
        let message = validate(&scene).expect_err("too far").to_string();
        assert!(
            message.contains("camera.position") && message.contains("6700 AU"),
            "{message}"
        );
    }
}
