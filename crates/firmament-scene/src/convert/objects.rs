//! From `[lighting]`, `[[lights]]`, `[[objects]]`, `[fog]`, `[shadows]` and `[ground]` to the
//! core's [`ObjectLayer`]: the rules each value must follow, GL's initial values for what is left
//! out, and the meshes and textures built or loaded.

use std::sync::Arc;

use firmament_core::TimeOfDay;
use firmament_core::classic::fog::{Fog, FogCoordinate, FogMode, FogSun, HeightFog};
use firmament_core::classic::lighting::{Light, LightModel, Material, SpecularModel};
use firmament_core::classic::mesh::Mesh;
use firmament_core::classic::scene::{
    ClassicLighting, LightSpace, MAX_CLASSIC_LIGHTS, ObjectLayer, ObjectLighting, ObjectTexture, SceneFog, SceneLight,
    SceneObject, Shading, TransformStep, transform_from_steps,
};
use firmament_core::classic::shadow::{ShadowLight, ShadowSettings, Shadows};
use firmament_core::classic::sky_light::SkyLight;
use firmament_core::frame::Sky;
use firmament_core::texture::TextureFilter;
use firmament_core::texture::TextureImage;
use glam::{DMat4, DVec3, DVec4};

use crate::assets;
use crate::checks::{check, in_range, non_negative};
use crate::error::SceneError;
use crate::model::{
    AtmosphereModelName, FilterName, FogCoordinateName, FogModeName, GlColor, LightEntry, LightSpaceName,
    LightingModelName, MaterialEntry, MeshEntry, ObjectEntry, Scene, ShadingName, SkyModelName, SpecularName,
    TextureEntry, TransformEntry,
};

fn color(key: &str, c: GlColor) -> Result<DVec4, SceneError> {
    let rgba = c.rgba();
    check(
        rgba.iter().all(|v| v.is_finite()),
        key,
        format!("{rgba:?}"),
        "every component must be a finite number",
    )?;
    Ok(DVec4::from_array(rgba))
}

fn finite3(key: &str, v: [f64; 3], rule: &str) -> Result<DVec3, SceneError> {
    check(v.iter().all(|c| c.is_finite()), key, format!("{v:?}"), rule)?;
    Ok(DVec3::from_array(v))
}

/// Light `i` of `[[lights]]`, GL's initial values where the entry says nothing.
pub(crate) fn light(i: usize, entry: &LightEntry) -> Result<SceneLight, SceneError> {
    let key = |field: &str| format!("lights[{i}].{field}");
    let initial = Light::gl_default(i);
    let pick = |field: &str, c: Option<GlColor>, default: DVec4| c.map_or(Ok(default), |c| color(&key(field), c));
    let position = match entry.position {
        None => initial.position,
        Some(p) => {
            check(
                p.iter().all(|c| c.is_finite()) && p != [0.0; 4],
                &key("position"),
                format!("{p:?}"),
                "must be finite and not all zero (w = 0: a direction towards the light; w = 1: a point)",
            )?;
            DVec4::from_array(p)
        }
    };
    let spot_direction = match entry.spot_direction {
        None => initial.spot_direction,
        Some(d) => {
            let d = finite3(&key("spot_direction"), d, "every component must be finite")?;
            check(
                d.length_squared() > 0.0,
                &key("spot_direction"),
                format!("{:?}", d.to_array()),
                "must not be zero",
            )?;
            d
        }
    };
    let spot_exponent = entry.spot_exponent.unwrap_or(initial.spot_exponent);
    in_range(&key("spot_exponent"), spot_exponent, 0.0, 128.0, "")?;
    let spot_cutoff = entry.spot_cutoff_deg.unwrap_or(initial.spot_cutoff);
    check(
        spot_cutoff == 180.0 || (spot_cutoff.is_finite() && (0.0..=90.0).contains(&spot_cutoff)),
        &key("spot_cutoff"),
        spot_cutoff,
        "must be in [0, 90] degrees, or 180 for no spot (GL's rule)",
    )?;
    let [constant, linear, quadratic] = entry.attenuation.unwrap_or([
        initial.constant_attenuation,
        initial.linear_attenuation,
        initial.quadratic_attenuation,
    ]);
    check(
        [constant, linear, quadratic].iter().all(|v| v.is_finite() && *v >= 0.0),
        &key("attenuation"),
        format!("[{constant}, {linear}, {quadratic}]"),
        "constant, linear and quadratic attenuation must each be finite and >= 0",
    )?;
    Ok(SceneLight {
        light: Light {
            ambient: pick("ambient", entry.ambient, initial.ambient)?,
            diffuse: pick("diffuse", entry.diffuse, initial.diffuse)?,
            specular: pick("specular", entry.specular, initial.specular)?,
            position,
            spot_direction,
            spot_exponent,
            spot_cutoff,
            constant_attenuation: constant,
            linear_attenuation: linear,
            quadratic_attenuation: quadratic,
        },
        space: match entry.space {
            LightSpaceName::Eye => LightSpace::Eye,
            LightSpaceName::World => LightSpace::World,
        },
    })
}

/// A material: `entry` over `base`.
fn material(key: &str, entry: &MaterialEntry, base: Material) -> Result<Material, SceneError> {
    let pick = |field: &str, c: Option<GlColor>, default: DVec4| {
        c.map_or(Ok(default), |c| color(&format!("{key}.{field}"), c))
    };
    let shininess = entry.shininess.unwrap_or(base.shininess);
    in_range(&format!("{key}.shininess"), shininess, 0.0, 128.0, " (GL's range)")?;
    Ok(Material {
        ambient: pick("ambient", entry.ambient, base.ambient)?,
        diffuse: pick("diffuse", entry.diffuse, base.diffuse)?,
        specular: pick("specular", entry.specular, base.specular)?,
        emission: pick("emission", entry.emission, base.emission)?,
        shininess,
    })
}

fn transform(key: &str, steps: &[TransformEntry]) -> Result<Vec<TransformStep>, SceneError> {
    steps
        .iter()
        .enumerate()
        .map(|(j, step)| {
            let key = format!("{key}.transform[{j}]");
            Ok(match *step {
                TransformEntry::Translate(t) => {
                    TransformStep::Translate(finite3(&key, t, "translate: every component must be finite")?)
                }
                TransformEntry::Rotate([degrees, x, y, z]) => {
                    let axis = finite3(&key, [x, y, z], "rotate: the axis must be finite")?;
                    check(
                        degrees.is_finite() && axis.length_squared() > 0.0,
                        &key,
                        format!("rotate = [{degrees}, {x}, {y}, {z}]"),
                        "rotate = [degrees, x, y, z] needs a finite angle and a non-zero axis",
                    )?;
                    TransformStep::Rotate { degrees, axis }
                }
                TransformEntry::Scale(s) => {
                    let s = finite3(&key, s, "scale: every component must be finite")?;
                    check(
                        s.min_element().abs() > 0.0 && s.x * s.y * s.z != 0.0,
                        &key,
                        format!("scale = {:?}", s.to_array()),
                        "scale factors must not be zero (the normal matrix would not exist)",
                    )?;
                    TransformStep::Scale(s)
                }
            })
        })
        .collect()
}

/// One mesh of an object: the triangles, mesh → object transform, and the file's base colour
/// and texture if it gave them.
struct ObjectMesh {
    mesh: Arc<Mesh>,
    transform: DMat4,
    base_color: Option<DVec4>,
    texture: Option<Arc<TextureImage>>,
}

/// Builds or loads the mesh of object `key`. A file with several meshes gives several.
fn meshes(key: &str, entry: &MeshEntry, scene: &Scene) -> Result<Vec<ObjectMesh>, SceneError> {
    let core = |r: Result<Mesh, firmament_core::CoreError>| {
        r.map(|mesh| {
            vec![ObjectMesh {
                mesh: Arc::new(mesh),
                transform: DMat4::IDENTITY,
                base_color: None,
                texture: None,
            }]
        })
        .map_err(|e| core_error(&format!("{key}.mesh"), e))
    };
    match entry {
        MeshEntry::GltSphere { radius, slices, stacks } => {
            // GLTools takes a float radius; the core checks it after rounding.
            core(Mesh::glt_sphere(*radius as f32, *slices, *stacks))
        }
        MeshEntry::GluSphere { radius, slices, stacks } => core(Mesh::glu_sphere(*radius, *slices, *stacks)),
        MeshEntry::Quad { size, subdivisions } => core(Mesh::quad(*size, *subdivisions)),
        MeshEntry::Cube { size } => core(Mesh::cube(*size)),
        MeshEntry::File { path } => {
            let key = format!("{key}.mesh.path");
            let resolved = scene.asset_file(&key, path)?;
            let loaded = assets::load_model_within(&key, &resolved, scene.confinement.as_ref())?;
            Ok(loaded
                .into_iter()
                .map(|m| ObjectMesh {
                    mesh: m.mesh,
                    transform: m.transform,
                    base_color: m.base_color.map(DVec4::from_array),
                    texture: m.texture,
                })
                .collect())
        }
    }
}

fn core_error(key: &str, e: firmament_core::CoreError) -> SceneError {
    match e {
        firmament_core::CoreError::Invalid { field, value, rule } => {
            SceneError::invalid(format!("{key}.{field}"), value, rule)
        }
        other => SceneError::invalid(key, "", other.to_string()),
    }
}

fn texture(key: &str, entry: &TextureEntry, scene: &Scene) -> Result<ObjectTexture, SceneError> {
    let image = match (&entry.file, &entry.checkerboard) {
        (Some(file), None) => {
            let key = format!("{key}.file");
            let resolved = scene.asset_file(&key, file)?;
            assets::load_texture_shared(&key, &resolved, scene.confinement.as_ref())?
        }
        (None, Some(c)) => {
            let byte = |j: usize| -> Result<[u8; 4], SceneError> {
                let rgba = color(&format!("{key}.checkerboard.colors[{j}]"), c.colors[j])?;
                check(
                    rgba.min_element() >= 0.0 && rgba.max_element() <= 1.0,
                    &format!("{key}.checkerboard.colors[{j}]"),
                    format!("{:?}", rgba.to_array()),
                    "texel colours must be in [0, 1]",
                )?;
                Ok(rgba.to_array().map(|v| (v * 255.0).round() as u8))
            };
            Arc::new(TextureImage::checkerboard(c.size, c.squares, byte(0)?, byte(1)?).map_err(|e| core_error(key, e))?)
        }
        _ => {
            return Err(SceneError::invalid(
                key,
                "{...}",
                "needs exactly one of `file` and `checkerboard`",
            ));
        }
    };
    Ok(ObjectTexture {
        image,
        filter: match entry.filter {
            FilterName::Nearest => TextureFilter::Nearest,
            FilterName::Linear => TextureFilter::Linear,
        },
    })
}

/// The spin's rotation at `time` (seconds since midnight × speed), about the object's origin.
fn spin_step(key: &str, object: &ObjectEntry, time: TimeOfDay) -> Result<Option<TransformStep>, SceneError> {
    let Some(spin) = object.spin else {
        return Ok(None);
    };
    let axis = finite3(&format!("{key}.spin.axis"), spin.axis, "every component must be finite")?;
    check(
        axis.length_squared() > 0.0,
        &format!("{key}.spin.axis"),
        format!("{:?}", spin.axis),
        "must not be zero",
    )?;
    check(
        spin.degrees_per_second.is_finite(),
        &format!("{key}.spin.degrees_per_second"),
        spin.degrees_per_second,
        "must be a finite number of degrees per second",
    )?;
    let degrees = (spin.degrees_per_second * time.seconds()).rem_euclid(360.0);
    Ok(Some(TransformStep::Rotate { degrees, axis }))
}

fn objects(scene: &Scene, time: TimeOfDay, load: bool) -> Result<Vec<SceneObject>, SceneError> {
    let mut out = Vec::new();
    // Untrusted mode bounds the triangles of every object together, mesh files included.
    let max_triangles = scene.confinement.as_ref().map(|c| c.limits().max_triangles);
    let mut triangles = 0_u64;
    for (i, entry) in scene.objects.iter().enumerate() {
        let key = format!("objects[{i}]");
        let front = material(&format!("{key}.material"), &entry.material, Material::default())?;
        let back = match &entry.back_material {
            None => front,
            Some(b) => material(&format!("{key}.back_material"), b, front)?,
        };
        let mut steps = transform(&key, &entry.transform)?;
        steps.extend(spin_step(&key, entry, time)?);
        let model = transform_from_steps(&steps);
        if !load {
            continue;
        }
        let texture = entry
            .texture
            .as_ref()
            .map(|t| texture(&format!("{key}.texture"), t, scene))
            .transpose()?;
        for part in meshes(&key, &entry.mesh, scene)? {
            let ObjectMesh {
                mesh,
                transform: mesh_transform,
                base_color,
                texture: file_texture,
            } = part;
            if let Some(max) = max_triangles {
                triangles = triangles.saturating_add(mesh.triangle_count() as u64);
                check(
                    triangles <= max,
                    &format!("{key}.mesh"),
                    format!("{triangles} triangles in objects[0..={i}]"),
                    &crate::validate::untrusted_triangles_rule(max),
                )?;
            }
            // A file's base colour is its diffuse colour unless the scene sets one.
            let with_base = |m: Material| match base_color {
                Some(c) if entry.material.diffuse.is_none() => Material { diffuse: c, ..m },
                _ => m,
            };
            let texture = texture.clone().or_else(|| {
                file_texture.map(|image| ObjectTexture {
                    image,
                    filter: TextureFilter::Linear,
                })
            });
            out.push(SceneObject {
                mesh,
                model: model * mesh_transform,
                front: with_base(front),
                back: with_base(back),
                texture,
                fog_coord: entry.fog_coord,
                light_colors: Vec::new(),
            });
        }
    }
    Ok(out)
}

/// The objects' lighting; `sky_light` is the frame's sky light for `lighting.model = "sky"`
/// (`None` checks the rules only, skipping the sky's costly irradiance).
fn lighting(scene: &Scene, sky_light: Option<&SkyLight<'_>>) -> Result<ObjectLighting, SceneError> {
    let l = &scene.lighting;
    check(
        scene.lights.len() <= MAX_CLASSIC_LIGHTS,
        "lights",
        format!("{} lights", scene.lights.len()),
        "at most 8 lights (GL_MAX_LIGHTS, a fixed limit of the classic lighting model that no key or flag \
         raises: drop or merge the weakest lights)",
    )?;
    let lights = scene
        .lights
        .iter()
        .enumerate()
        .map(|(i, e)| light(i, e))
        .collect::<Result<Vec<_>, _>>()?;
    let shading = match l.shading {
        ShadingName::Flat => Shading::Flat,
        ShadingName::Gouraud => Shading::Gouraud,
        ShadingName::Phong => Shading::Phong,
    };
    let specular = match l.specular {
        SpecularName::Blinn => SpecularModel::Blinn,
        SpecularName::Phong => SpecularModel::Phong,
    };
    let model = LightModel {
        ambient: color("lighting.ambient", l.ambient)?,
        local_viewer: l.local_viewer,
        two_side: l.two_side,
        separate_specular: l.separate_specular,
        clamp_vertex_color: l.clamp_vertex_color,
    };
    Ok(match l.model {
        LightingModelName::Unlit => ObjectLighting::Unlit,
        LightingModelName::Classic => ObjectLighting::Classic(ClassicLighting {
            lights,
            model,
            shading,
            specular,
        }),
        LightingModelName::Sky => {
            check(
                scene.sky.model == SkyModelName::Atmosphere && scene.atmosphere.model == AtmosphereModelName::Physical,
                "lighting.model",
                "\"sky\"",
                "objects lit by the sky need the physical atmosphere (sky.model = \"atmosphere\", atmosphere.model = \"physical\")",
            )?;
            let Some(sky_light) = sky_light else {
                // Validation only: the reference's sky irradiance is computed when the frame is.
                return Ok(ObjectLighting::Unlit);
            };
            let camera = glam::DVec3::from_array(scene.camera.position);
            let mut lit = sky_light.lighting(camera, shading, specular);
            lit.model.two_side = l.two_side;
            lit.model.separate_specular = l.separate_specular;
            // `clamp_vertex_color` has no say here: radiance is clamped nowhere.
            ObjectLighting::Sky(lit)
        }
    })
}

fn fog(scene: &Scene) -> Result<SceneFog, SceneError> {
    let f = &scene.fog;
    let fog_color = color("fog.color", f.color)?;
    let coordinate = match f.coordinate {
        FogCoordinateName::EyePlaneDepth => FogCoordinate::EyePlaneDepth,
        FogCoordinateName::EyeDistance => FogCoordinate::EyeDistance,
        FogCoordinateName::Vertex => FogCoordinate::Vertex,
    };
    let classic = |mode| {
        Ok(SceneFog::Classic(Fog {
            mode,
            coordinate,
            color: fog_color,
        }))
    };
    match f.mode {
        FogModeName::None => Ok(SceneFog::None),
        FogModeName::Linear => {
            check(f.start.is_finite(), "fog.start", f.start, "must be a finite distance")?;
            check(
                f.end.is_finite() && f.end > f.start,
                "fog.end",
                f.end,
                "must be a finite distance > fog.start",
            )?;
            classic(FogMode::Linear {
                start: f.start,
                end: f.end,
            })
        }
        FogModeName::Exp | FogModeName::Exp2 => {
            non_negative("fog.density", f.density)?;
            classic(if f.mode == FogModeName::Exp {
                FogMode::Exp { density: f.density }
            } else {
                FogMode::Exp2 { density: f.density }
            })
        }
        FogModeName::Height => {
            non_negative("fog.density", f.density)?;
            non_negative("fog.falloff", f.falloff)?;
            check(
                f.base_height.is_finite(),
                "fog.base_height",
                f.base_height,
                "must be a finite height in metres",
            )?;
            Ok(SceneFog::Height {
                fog: HeightFog {
                    density: f.density,
                    falloff: f.falloff,
                    base_height: f.base_height,
                },
                color: fog_color,
                sun: fog_sun(scene)?,
            })
        }
    }
}

/// The height fog's sun in-scattering, if `fog.sun_color` asks for it.
fn fog_sun(scene: &Scene) -> Result<Option<FogSun>, SceneError> {
    let f = &scene.fog;
    let Some(sun_color) = f.sun_color else {
        return Ok(None);
    };
    let color = color("fog.sun_color", sun_color)?;
    check(
        f.sun_exponent.is_finite() && f.sun_exponent >= 1.0,
        "fog.sun_exponent",
        f.sun_exponent,
        "must be a finite number >= 1",
    )?;
    let direction = match f.sun_direction {
        Some(d) => {
            let d = finite3("fog.sun_direction", d, "must be a finite direction")?;
            check(
                d.length() > 0.0,
                "fog.sun_direction",
                format!("{d}"),
                "must not be zero",
            )?;
            d.normalize()
        }
        None => {
            check(
                !scene.suns.is_empty(),
                "fog.sun_direction",
                "(absent)",
                "is needed when the scene has no [[suns]] to take it from",
            )?;
            scene.atmosphere_sky()?.suns[0].direction.normalize()
        }
    };
    Ok(Some(FogSun {
        direction,
        color,
        exponent: f.sun_exponent,
    }))
}

/// The shadow settings of `[shadows]` when the suns cast (`None` when they do not). The numeric
/// keys are checked in every scene, shadows on or off, so that a bad value is found before it is
/// used; `shadows.enabled = true` needs lit objects (`lighting.model = "sky"` or `"classic"`) and
/// `lighting.shading = "phong"`.
fn shadow_settings(scene: &Scene) -> Result<Option<ShadowSettings>, SceneError> {
    let settings = scene.shadows.settings();
    // The core's rules name the scene's keys (`shadows.map_size`, …) already.
    settings.validate().map_err(|e| match e {
        firmament_core::CoreError::Invalid { field, value, rule } => SceneError::invalid(field, value, rule),
        other => SceneError::invalid("shadows", "", other.to_string()),
    })?;
    if scene.shadows.enabled == Some(true) {
        let l = &scene.lighting;
        check(
            l.model != LightingModelName::Unlit,
            "shadows.enabled",
            true,
            &format!(
                "shadows need lit objects, lighting.model = \"sky\" (the atmosphere's suns cast) or \"classic\" \
                 (its directional world-space lights cast), and lighting.model is \"{}\": set shadows.enabled = \
                 false or leave it out",
                lighting_model_name(l.model)
            ),
        )?;
        check(
            l.shading == ShadingName::Phong,
            "shadows.enabled",
            true,
            &format!(
                "shadows are computed per fragment and need lighting.shading = \"phong\", and lighting.shading is \
                 \"{}\"",
                shading_name(l.shading)
            ),
        )?;
    }
    Ok(scene.shadows_enabled().then_some(settings))
}

fn lighting_model_name(model: LightingModelName) -> &'static str {
    match model {
        LightingModelName::Classic => "classic",
        LightingModelName::Unlit => "unlit",
        LightingModelName::Sky => "sky",
    }
}

fn shading_name(shading: ShadingName) -> &'static str {
    match shading {
        ShadingName::Flat => "flat",
        ShadingName::Gouraud => "gouraud",
        ShadingName::Phong => "phong",
    }
}

/// Checks every rule of `[lighting]`, `[[lights]]`, `[[objects]]`, `[fog]` and `[shadows]`
/// without loading files (loading happens in [`object_layer`]).
pub(crate) fn validate(scene: &Scene) -> Result<(), SceneError> {
    lighting(scene, None)?;
    shadow_settings(scene)?;
    fog(scene)?;
    objects(scene, TimeOfDay::MIDNIGHT, false)?;
    Ok(())
}

/// The scene's objects at `time` (for spins), their lighting and fog, and under a sky light the
/// suns' shadows and the ground; builds the built-in meshes and loads mesh and texture files.
pub(crate) fn object_layer(scene: &Scene, time: TimeOfDay, sky: &Sky) -> Result<ObjectLayer, SceneError> {
    let mut objects = objects(scene, time, true)?;
    // Objects lit by the sky: one sky light for the frame (`lighting` requires an atmosphere).
    let sky_light = match (scene.lighting.model, sky) {
        (LightingModelName::Sky, Sky::Atmosphere(sky)) => Some(SkyLight::new(sky)),
        _ => None,
    };
    let lighting = lighting(scene, sky_light.as_ref())?;
    let shadow_settings = shadow_settings(scene)?;
    let (mut shadows, mut ground) = (Shadows::default(), None);
    if let Some(light) = &sky_light {
        // Each object sees the suns through the air at its own origin; the renderer dims them
        // per fragment by the clouds' shadow map.
        for object in &mut objects {
            object.light_colors = light.sun_colors_through_air(object.model.transform_point3(DVec3::ZERO));
        }
        // The camera, as `lighting` takes the sky's light at it.
        let camera = DVec3::from_array(scene.camera.position);
        if let Some(settings) = shadow_settings {
            shadows = Shadows {
                settings: Some(settings),
                lights: light.shadow_lights(camera, settings.max_lights),
            };
        }
        if scene.ground.enabled {
            ground = light.ground(camera);
        }
    } else if let (ObjectLighting::Classic(classic), Some(settings)) = (&lighting, shadow_settings) {
        // Classic scenes cast only when they ask (`shadows.enabled = true`): GL has no shadows.
        shadows = Shadows {
            settings: Some(settings),
            lights: ShadowLight::from_classic(classic, settings.max_lights),
        };
    }
    Ok(ObjectLayer {
        objects,
        lighting,
        fog: fog(scene)?,
        shadows,
        ground,
    })
}
