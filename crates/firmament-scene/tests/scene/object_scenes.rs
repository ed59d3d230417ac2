//! `[lighting]`, `[[lights]]`, `[[objects]]` and `[fog]`: GL's defaults, GL-ordered transforms,
//! the classic presets, and a clear error for each bad value.

use firmament_core::classic::fog::{FogCoordinate, FogMode};
use firmament_core::classic::lighting::Material;
use firmament_core::classic::scene::{LightSpace, ObjectLighting, SceneFog, Shading};
use firmament_core::frame::Sky;
use firmament_scene::{SceneSource, load};
use glam::{DVec3, DVec4};

use crate::support::from_text;

/// The message of the first error, from loading or from building the frame.
fn error(text: &str) -> String {
    match from_text(text).and_then(|s| s.frame_at(None)) {
        Ok(_) => panic!("should fail:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const SPHERE: &str = r#"
[[objects]]
mesh = { kind = "glt_sphere", radius = 1.0, slices = 26, stacks = 13 }
"#;

#[test]
fn absent_values_are_gl_initial_values() {
    let text = format!("[[lights]]\n[[lights]]\nposition = [1.0, 2.0, 3.0, 1.0]\n{SPHERE}");
    let frame = from_text(&text).expect("valid").frame_at(None).expect("frame");
    let ObjectLighting::Classic(lighting) = &frame.objects.lighting else {
        panic!("classic lighting is the default")
    };
    assert_eq!(lighting.shading, Shading::Gouraud);
    assert_eq!(lighting.model.ambient, DVec4::new(0.2, 0.2, 0.2, 1.0));
    assert!(lighting.model.clamp_vertex_color, "GL clamps vertex colours by default");
    // Light 0 white, light 1 black; both at GL's defaults otherwise.
    assert_eq!(lighting.lights[0].light.diffuse, DVec4::ONE);
    assert_eq!(lighting.lights[0].light.position, DVec4::new(0.0, 0.0, 1.0, 0.0));
    assert_eq!(lighting.lights[1].light.diffuse, DVec4::new(0.0, 0.0, 0.0, 1.0));
    assert_eq!(lighting.lights[1].light.spot_cutoff, 180.0);
    assert_eq!(lighting.lights[1].space, LightSpace::Eye);
    let object = &frame.objects.objects[0];
    assert_eq!(object.front, Material::default());
    assert_eq!(object.back, object.front);
    assert_eq!(object.mesh.vertex_count(), 27 * 14);
    assert_eq!(frame.objects.fog, SceneFog::None);
}

#[test]
fn transforms_apply_in_gl_call_order_and_back_materials_layer_over_front() {
    let text = r#"
[[objects]]
mesh = { kind = "cube", size = 1.0 }
transform = [{ translate = [1.0, 0.0, 0.0] }, { rotate = [90.0, 0.0, 0.0, 1.0] }, { scale = [2.0, 2.0, 2.0] }]
material = { diffuse = [0.1, 0.2, 0.3], shininess = 5.0 }
back_material = { diffuse = [0.9, 0.8, 0.7, 0.5] }
"#;
    let frame = from_text(text).expect("valid").frame_at(None).expect("frame");
    let object = &frame.objects.objects[0];
    let p = object.model.transform_point3(DVec3::X);
    assert!((p - DVec3::new(1.0, 2.0, 0.0)).length() < 1e-12, "{p}");
    assert_eq!(object.front.diffuse, DVec4::new(0.1, 0.2, 0.3, 1.0));
    assert_eq!(object.back.diffuse, DVec4::new(0.9, 0.8, 0.7, 0.5));
    assert_eq!(object.back.shininess, 5.0);
}

#[test]
fn spins_turn_with_the_time_of_day() {
    let text = format!("{SPHERE}spin = {{ axis = [0.0, 0.0, 1.0], degrees_per_second = 1.0 }}\n");
    let scene = from_text(&text).expect("valid");
    // 00:01:30 → 90° about z.
    let t = "00:01:30".parse().expect("time");
    let frame = scene.frame_at(Some(t)).expect("frame");
    let p = frame.objects.objects[0].model.transform_point3(DVec3::X);
    assert!((p - DVec3::Y).length() < 1e-12, "{p}");
}

#[test]
fn fog_and_clear_sky() {
    let text = r#"
[sky]
model = "clear"
clear_color = [0.1, 0.2, 0.3]
[fog]
mode = "exp2"
density = 0.3
coordinate = "eye_distance"
color = [0.5, 0.6, 0.7]
"#;
    let frame = from_text(text).expect("valid").frame_at(None).expect("frame");
    assert!(matches!(frame.sky, Sky::Clear(c) if c.b == 0.3));
    let SceneFog::Classic(fog) = frame.objects.fog else {
        panic!("classic fog")
    };
    assert_eq!(fog.mode, FogMode::Exp2 { density: 0.3 });
    assert_eq!(fog.coordinate, FogCoordinate::EyeDistance);
}

#[test]
fn classic_presets_state_the_superbible_scene() {
    for name in ["superbible-ads", "superbible-phong", "fixed-function-tour"] {
        let scene = load(SceneSource::Preset(name), None, &[]).expect(name);
        let frame = scene.frame_at(None).expect(name);
        assert!(!frame.objects.objects.is_empty(), "{name}");
        assert_eq!(
            frame.display.encoding,
            firmament_core::display::Encoding::None,
            "{name}"
        );
    }
    let ads = load(SceneSource::Preset("superbible-ads"), None, &[]).expect("valid");
    let frame = ads.frame_at(None).expect("frame");
    // The camera's view is GL's eye space: the identity.
    let view = frame.camera.view_matrix();
    assert!(view.abs_diff_eq(glam::DMat4::IDENTITY, 1e-12), "{view}");
    let object = &frame.objects.objects[0];
    assert_eq!(object.mesh.triangle_count(), 26 * 13 * 2);
    assert_eq!(object.front.diffuse, DVec4::new(0.0, 0.0, 1.0, 1.0));
    assert_eq!(object.front.shininess, 128.0);
    let ObjectLighting::Classic(lighting) = &frame.objects.lighting else {
        panic!("classic")
    };
    assert_eq!(lighting.lights[0].light.position, DVec4::new(-100.0, 100.0, 100.0, 1.0));
    // The book's shaders pass colours in varyings, which GL does not clamp.
    assert!(!lighting.model.clamp_vertex_color);
    let phong = load(SceneSource::Preset("superbible-phong"), None, &[]).expect("valid");
    let ObjectLighting::Classic(lighting) = phong.frame_at(None).expect("frame").objects.lighting else {
        panic!("classic")
    };
    assert_eq!(lighting.shading, Shading::Phong);
}

#[test]
fn clamp_vertex_color_is_a_boolean_key() {
    let lighting = |text: &str| {
        let frame = from_text(text).expect("valid").frame_at(None).expect("frame");
        let ObjectLighting::Classic(lighting) = frame.objects.lighting else {
            panic!("classic lighting is the default")
        };
        lighting.model
    };
    assert!(!lighting("[lighting]\nclamp_vertex_color = false\n").clamp_vertex_color);
    assert!(lighting("[lighting]\nclamp_vertex_color = true\n").clamp_vertex_color);
    // `--set` reaches it like any key.
    let scene = load(
        SceneSource::Preset("superbible-ads"),
        None,
        &["lighting.clamp_vertex_color=true".to_owned()],
    )
    .expect("valid");
    let ObjectLighting::Classic(lighting) = scene.frame_at(None).expect("frame").objects.lighting else {
        panic!("classic")
    };
    assert!(lighting.model.clamp_vertex_color);
    for value in ["1", "\"no\"", "[true]"] {
        let message = error(&format!("[lighting]\nclamp_vertex_color = {value}\n"));
        assert!(
            message.contains("lighting.clamp_vertex_color") && message.contains("bool"),
            "clamp_vertex_color = {value} gave: {message}"
        );
    }
}

#[test]
fn bad_values_name_the_key_and_the_rule() {
    let cases = [
        (
            format!("{SPHERE}material = {{ shininess = 200.0 }}\n"),
            "objects[0].material.shininess = 200: must be in [0, 128]",
        ),
        (
            "[[lights]]\nspot_cutoff = 100.0\n".to_owned(),
            "lights[0].spot_cutoff = 100: must be in [0, 90] degrees, or 180",
        ),
        (
            "[[lights]]\nattenuation = [1.0, -0.5, 0.0]\n".to_owned(),
            "lights[0].attenuation",
        ),
        (
            "[fog]\nmode = \"linear\"\nstart = 5.0\nend = 5.0\n".to_owned(),
            "fog.end = 5: must be a finite distance > fog.start",
        ),
        ("[fog]\nmode = \"exp\"\ndensity = -1.0\n".to_owned(), "fog.density = -1"),
        ("[[lights]]\n".repeat(9), "at most 8 lights"),
        (
            "[[objects]]\nmesh = { kind = \"file\", path = \"no/such/mesh.obj\" }\n".to_owned(),
            "objects[0].mesh.path",
        ),
        (
            "[[objects]]\nmesh = { kind = \"glt_sphere\", radius = -1.0, slices = 26, stacks = 13 }\n".to_owned(),
            "objects[0].mesh.radius",
        ),
        (
            format!("{SPHERE}transform = [{{ scale = [1.0, 0.0, 1.0] }}]\n"),
            "objects[0].transform[0]",
        ),
        (
            format!("{SPHERE}texture = {{ filter = \"nearest\" }}\n"),
            "objects[0].texture",
        ),
        (
            format!("{SPHERE}texture = {{ file = \"missing.png\" }}\n"),
            "objects[0].texture.file",
        ),
        ("[lighting]\nshading = \"toon\"\n".to_owned(), "lighting.shading"),
        (
            "[lighting]\nmodel = \"sky\"\n".to_owned(),
            "lighting.model = \"sky\": objects lit by the sky need the physical atmosphere",
        ),
        (
            "[[lights]]\nposition = [0.0, 0.0, 0.0, 0.0]\n".to_owned(),
            "lights[0].position",
        ),
    ];
    for (text, expected) in cases {
        let message = error(&text);
        assert!(
            message.contains(expected),
            "{text}\ngave: {message}\nexpected: {expected}"
        );
    }
}

#[test]
fn mesh_and_texture_files_are_found_next_to_the_scene_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    // A triangle without normals (computed on load) and a 2×1 texture.
    std::fs::write(
        dir.path().join("tri.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
    )
    .expect("write obj");
    let image = image::RgbaImage::from_raw(2, 1, vec![255, 0, 0, 255, 0, 0, 255, 255]).expect("image");
    image.save(dir.path().join("tex.png")).expect("write png");
    let text = r#"
[[objects]]
mesh = { kind = "file", path = "tri.obj" }
texture = { file = "tex.png", filter = "nearest" }
"#;
    let origin = dir.path().join("scene.toml");
    let scene = load(
        SceneSource::Text {
            text,
            origin: &origin.display().to_string(),
        },
        None,
        &[],
    )
    .expect("valid");
    let frame = scene.frame_at(None).expect("frame");
    let object = &frame.objects.objects[0];
    assert_eq!(object.mesh.triangle_count(), 1);
    assert_eq!(object.mesh.normals[0], [0.0, 0.0, 1.0]);
    let texture = object.texture.as_ref().expect("textured");
    assert_eq!(texture.image.texel(1, 0), Some([0, 0, 255, 255]));
}

#[test]
fn sky_lighting_comes_from_the_atmosphere_suns() {
    let scene = load(SceneSource::Preset("earth-objects"), None, &[]).expect("valid");
    let frame = scene.frame_at(None).expect("frame");
    let ObjectLighting::Sky(lighting) = &frame.objects.lighting else {
        panic!("sky lighting")
    };
    assert_eq!(lighting.lights.len(), 1);
    let sun = lighting.lights[0];
    assert_eq!(sun.space, LightSpace::World);
    assert_eq!(sun.light.position.w, 0.0);
    // The Sun 20° up in the south-west: its light comes from there.
    let d = sun.light.position.truncate();
    assert!(
        (d.z - 20f64.to_radians().sin()).abs() < 1e-9 && d.x < 0.0 && d.y < 0.0,
        "{d}"
    );
    assert!(sun.light.diffuse.y > lighting.model.ambient.y && lighting.model.ambient.y > 0.0);
    assert!(!frame.objects.lighting.clamps());
    // Every object has the sun's colour at its own origin: near the camera, about the camera's.
    for object in &frame.objects.objects {
        let own = object.light_colors[0];
        assert!(
            (own.y / sun.light.diffuse.y - 1.0).abs() < 0.05,
            "{own} vs {}",
            sun.light.diffuse
        );
    }
}

#[test]
fn vertex_fog_coordinates_and_height_fog_sun() {
    let text = r#"
[fog]
mode = "linear"
start = 1.0
end = 5.0
coordinate = "vertex"
[[objects]]
mesh = { kind = "quad", size = 1.0, subdivisions = 1 }
fog_coord = 2.5
"#
    .to_string();
    let frame = from_text(&text).expect("valid").frame_at(None).expect("frame");
    let SceneFog::Classic(fog) = frame.objects.fog else {
        panic!("classic fog")
    };
    assert_eq!(fog.coordinate, FogCoordinate::Vertex);
    assert_eq!(frame.objects.objects[0].fog_coord, 2.5);

    let height = |extra: &str| {
        format!("[fog]\nmode = \"height\"\ndensity = 0.01\nfalloff = 0.1\nsun_color = [1.0, 0.8, 0.5]\n{extra}{SPHERE}")
    };
    let frame = from_text(&height("sun_direction = [0.0, 2.0, 0.0]\nsun_exponent = 4.0\n"))
        .expect("valid")
        .frame_at(None)
        .expect("frame");
    let SceneFog::Height { sun: Some(sun), .. } = frame.objects.fog else {
        panic!("height fog with a sun")
    };
    assert_eq!(sun.direction, DVec3::Y);
    assert_eq!(sun.exponent, 4.0);
    assert_eq!(sun.color, DVec4::new(1.0, 0.8, 0.5, 1.0));
    // Without a direction it is the first sun's.
    let preset = load(
        SceneSource::Preset("earth-objects"),
        None,
        &[
            "fog.mode=\"height\"".to_owned(),
            "fog.sun_color=[1.0, 1.0, 1.0]".to_owned(),
        ],
    )
    .expect("valid");
    let frame = preset.frame_at(None).expect("frame");
    let SceneFog::Height { sun: Some(sun), .. } = frame.objects.fog else {
        panic!("height fog with a sun")
    };
    assert!(
        (sun.direction.z - 20f64.to_radians().sin()).abs() < 1e-9,
        "{}",
        sun.direction
    );

    for (extra, key, rule) in [
        ("sun_exponent = 0.5\n", "fog.sun_exponent", ">= 1"),
        (
            "sun_direction = [0.0, 0.0, 0.0]\n",
            "fog.sun_direction",
            "must not be zero",
        ),
        ("", "fog.sun_direction", "no [[suns]]"),
    ] {
        let message = error(&format!("[sky]\nmodel = \"clear\"\n{}", height(extra)));
        assert!(message.contains(key) && message.contains(rule), "{message}");
    }
}
