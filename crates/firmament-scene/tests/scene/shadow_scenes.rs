//! `[shadows]` and `[ground]`: the core's defaults, the sky-lit preset's shadows and ground, none
//! in classic scenes, and a clear error for each bad value.

use firmament_core::classic::scene::ObjectLighting;
use firmament_core::classic::shadow::{ShadowSettings, Shadows};
use firmament_scene::{GroundSection, Scene, SceneDocument, SceneSource, ShadowsSection, load};
use glam::DVec3;

/// `preset` with `--set` style overrides.
fn preset_with(preset: &str, overrides: &[&str]) -> Result<Scene, firmament_scene::SceneError> {
    let overrides: Vec<String> = overrides.iter().map(|s| (*s).to_owned()).collect();
    load(SceneSource::Preset(preset), None, &overrides)
}

/// The message of the first error, from loading or from building the frame.
fn error(preset: &str, overrides: &[&str]) -> String {
    match preset_with(preset, overrides).and_then(|s| s.frame_at(None)) {
        Ok(_) => panic!("should fail: {preset} with {overrides:?}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn the_default_keys_are_the_core_s_defaults() {
    let scene = Scene::preset("default").expect("default preset");
    assert_eq!(scene.shadows.settings(), ShadowSettings::default());
    assert_eq!(scene.shadows, ShadowsSection::default());
    assert_eq!(scene.shadows.enabled, None);
    assert_eq!(ShadowsSection::default().settings(), ShadowSettings::default());
    assert_eq!(scene.ground, GroundSection { enabled: true });
    assert_eq!(GroundSection::default(), GroundSection { enabled: true });
    // Classic lighting: off unless asked.
    assert!(!scene.shadows_enabled());
}

#[test]
fn the_sky_lit_preset_casts_the_sun_s_shadows_onto_a_ground() {
    let scene = Scene::preset("earth-objects").expect("valid");
    assert!(
        scene.shadows_enabled(),
        "absent enabled: on under sky lighting with Phong shading"
    );
    let frame = scene.frame_at(None).expect("frame");
    let shadows = &frame.objects.shadows;
    assert_eq!(shadows.settings, Some(ShadowSettings::default()));
    assert!(shadows.any());
    assert_eq!(shadows.lights.len(), 1, "{:?}", shadows.lights);
    let sun = shadows.lights[0];
    assert_eq!(sun.light, 0);
    let ObjectLighting::Sky(lighting) = &frame.objects.lighting else {
        panic!("sky lighting")
    };
    let towards = lighting.lights[sun.light].light.position.truncate().normalize();
    assert!(sun.direction.distance(towards) < 1e-9, "{} vs {towards}", sun.direction);
    assert!(
        (sun.direction.z - 20f64.to_radians().sin()).abs() < 1e-9,
        "{}",
        sun.direction
    );
    assert_eq!(frame.camera.position, DVec3::new(0.0, 0.0, 1.7), "the street, 1.7 m up");
    assert!(
        sun.angular_radius > 0.0 && sun.angular_radius < 0.01,
        "{}",
        sun.angular_radius
    );

    let ground = frame.objects.ground.as_ref().expect("a ground under the sky");
    assert!(
        (ground.camera_height_m - 1.7).abs() < 1e-6,
        "{}",
        ground.camera_height_m
    );
    assert!(ground.up.distance(DVec3::Z) < 1e-9, "{}", ground.up);
    // Its material is the medium's ground albedo (Earth's: a grey 0.1), ambient = diffuse.
    let albedo = scene.atmosphere_sky().expect("sky").atmosphere.medium.ground_albedo;
    let material = ground.object.front;
    for (channel, want) in [material.diffuse.x, material.diffuse.y, material.diffuse.z]
        .into_iter()
        .zip(albedo.to_array())
    {
        assert!((channel - want).abs() < 1e-6, "{} vs {albedo:?}", material.diffuse);
    }
    assert!((material.diffuse.x - 0.1).abs() < 1e-6, "{}", material.diffuse);
    assert_eq!(material.ambient, material.diffuse);
    assert!(ground.bounced_sun.y > 0.0 && ground.bounced_sky.y > 0.0 && ground.sky.y > 0.0);
    assert_eq!(ground.object.light_colors.len(), 1, "the Sun's colour at the ground");
}

#[test]
fn classic_scenes_have_no_shadows_and_no_ground() {
    for preset in ["fixed-function-tour", "default", "superbible-phong"] {
        let frame = Scene::preset(preset).expect("valid").frame_at(None).expect("frame");
        assert_eq!(frame.objects.shadows, Shadows::default(), "{preset}");
        assert!(frame.objects.ground.is_none(), "{preset}");
    }
    // Classic lighting with Phong shading, shadows left to their default: still off.
    let frame = preset_with("superbible-phong", &["shadows.enabled=false"])
        .expect("valid")
        .frame_at(None)
        .expect("frame");
    assert_eq!(frame.objects.shadows, Shadows::default());
}

#[test]
fn a_classic_scene_that_asks_gets_shadows_of_its_world_directional_lights() {
    // superbible-phong's one light is positional and moves with the eye: it casts nothing. A
    // world-space directional light added to it casts; no ground is drawn (GL has none).
    let frame = preset_with(
        "superbible-phong",
        &[
            "shadows.enabled=true",
            "lights.1.space=\"world\"",
            "lights.1.position=[0.0, 0.0, 1.0, 0.0]",
            "lights.1.diffuse=[0.5, 0.5, 0.5]",
        ],
    )
    .expect("valid")
    .frame_at(None)
    .expect("frame");
    let shadows = &frame.objects.shadows;
    assert_eq!(shadows.settings, Some(ShadowSettings::default()));
    assert_eq!(shadows.lights.len(), 1);
    assert_eq!(shadows.lights[0].light, 1);
    assert_eq!(shadows.lights[0].direction, DVec3::Z);
    assert_eq!(shadows.lights[0].angular_radius, 0.0);
    assert!(frame.objects.ground.is_none());
}

#[test]
fn the_keys_turn_shadows_and_ground_off_and_shape_them() {
    let frame = |overrides: &[&str]| {
        preset_with("earth-objects", overrides)
            .expect("valid")
            .frame_at(None)
            .expect("frame")
    };
    // Gouraud shading: shadows off by default, the ground stays.
    let gouraud = frame(&["lighting.shading=\"gouraud\""]);
    assert_eq!(gouraud.objects.shadows, Shadows::default());
    assert!(gouraud.objects.ground.is_some());
    let off = frame(&["shadows.enabled=false", "ground.enabled=false"]);
    assert_eq!(off.objects.shadows, Shadows::default());
    assert!(off.objects.ground.is_none());
    let on = frame(&["shadows.enabled=true"]);
    assert_eq!(on.objects.shadows.lights.len(), 1);

    let shaped = frame(&[
        "shadows.map_size=1024",
        "shadows.cascades=2",
        "shadows.distance=150.0",
        "shadows.split_blend=0.5",
        "shadows.depth_bias=0.5",
        "shadows.normal_bias=2.0",
        "shadows.max_suns=1",
    ]);
    assert_eq!(
        shaped.objects.shadows.settings,
        Some(ShadowSettings {
            map_size: 1024,
            cascades: 2,
            distance_m: 150.0,
            split_blend: 0.5,
            depth_bias_texels: 0.5,
            normal_bias_texels: 2.0,
            max_lights: 1,
        })
    );

    // Two suns up: both cast, brightest (the higher, through less air) first; max_suns caps them.
    let two = ["suns.1.azimuth=90.0", "suns.1.elevation=5.0", "suns.0.elevation=40.0"];
    let both = frame(&two);
    let lights: Vec<usize> = both.objects.shadows.lights.iter().map(|l| l.light).collect();
    assert_eq!(lights, vec![0, 1]);
    let one = frame(&[two[0], two[1], two[2], "shadows.max_suns=1"]);
    let lights: Vec<usize> = one.objects.shadows.lights.iter().map(|l| l.light).collect();
    assert_eq!(lights, vec![0]);
    // A sun below the horizon casts nothing.
    let night = frame(&["suns.0.elevation=-10.0"]);
    assert!(night.objects.shadows.lights.is_empty());
    assert!(!night.objects.shadows.any());
}

#[test]
fn bad_shadow_values_name_the_key_and_the_rule() {
    // The numeric keys are checked in every scene, shadows on or off.
    for preset in ["earth-objects", "default"] {
        for (set, expected) in [
            (
                "shadows.map_size=100",
                "shadows.map_size = 100: must be 256 to 8192 texels",
            ),
            (
                "shadows.map_size=10000",
                "shadows.map_size = 10000: must be 256 to 8192 texels",
            ),
            ("shadows.cascades=0", "shadows.cascades = 0: must be 1 to 4"),
            ("shadows.cascades=9", "shadows.cascades = 9: must be 1 to 4"),
            (
                "shadows.distance=0.0",
                "shadows.distance = 0: must be more than 0 and at most 100000 metres",
            ),
            ("shadows.distance=nan", "shadows.distance = NaN: must be more than 0"),
            ("shadows.distance=inf", "shadows.distance = inf: must be more than 0"),
            ("shadows.split_blend=1.5", "shadows.split_blend = 1.5: must be 0 to 1"),
            ("shadows.split_blend=nan", "shadows.split_blend = NaN: must be 0 to 1"),
            (
                "shadows.depth_bias=-1",
                "shadows.depth_bias = -1: must be 0 to 16 texels",
            ),
            (
                "shadows.normal_bias=17",
                "shadows.normal_bias = 17: must be 0 to 16 texels",
            ),
            ("shadows.max_suns=0", "shadows.max_suns = 0: must be 1 to 8"),
            ("shadows.max_suns=9", "shadows.max_suns = 9: must be 1 to 8"),
        ] {
            let message = error(preset, &[set]);
            assert!(
                message.contains(expected),
                "{preset}, {set}\ngave: {message}\nexpected: {expected}"
            );
        }
        let message = error(preset, &["shadows.map_size=8192", "shadows.max_suns=8"]);
        assert!(
            message.contains("shadows.map_size = 8192 with 4 cascades × 8 suns") && message.contains("512 MiB"),
            "{message}"
        );
    }

    // Shadows asked for where they cannot be.
    for (preset, sets, expected) in [
        (
            "fixed-function-tour",
            &["shadows.enabled=true"][..],
            "lighting.shading is \"gouraud\"",
        ),
        (
            "superbible-phong",
            &["shadows.enabled=true", "lighting.model=\"unlit\""][..],
            "lighting.model is \"unlit\"",
        ),
        (
            "earth-objects",
            &["shadows.enabled=true", "lighting.model=\"unlit\""][..],
            "shadows.enabled = true: shadows need lit objects",
        ),
        (
            "earth-objects",
            &["shadows.enabled=true", "lighting.shading=\"gouraud\""][..],
            "shadows.enabled = true: shadows are computed per fragment and need lighting.shading = \"phong\"",
        ),
        (
            "earth-objects",
            &["shadows.enabled=true", "lighting.shading=\"flat\""][..],
            "lighting.shading is \"flat\"",
        ),
    ] {
        let message = error(preset, sets);
        assert!(
            message.contains(expected),
            "{preset} {sets:?}\ngave: {message}\nexpected: {expected}"
        );
    }

    // Wrong types and unknown keys.
    for (set, expected) in [
        ("shadows.map_size=-5", "shadows.map_size: invalid value"),
        (
            "shadows.map_size=2048.0",
            "shadows.map_size: invalid type: floating point",
        ),
        ("shadows.enabled=\"yes\"", "shadows.enabled: invalid type: string"),
        ("ground.enabled=1", "ground.enabled: invalid type: integer"),
        (
            "shadows.mapsize=1024",
            "shadows.mapsize: unknown key (did you mean `map_size`?)",
        ),
        ("ground.albedo=0.3", "ground.albedo: unknown key"),
    ] {
        let message = error("earth-objects", &[set]);
        assert!(
            message.contains(expected),
            "{set}\ngave: {message}\nexpected: {expected}"
        );
    }
}

#[test]
fn validation_alone_finds_the_same_errors() {
    let mut scene = Scene::preset("earth-objects").expect("valid");
    scene.shadows.cascades = 5;
    let message = scene.validate().expect_err("5 cascades").to_string();
    assert!(message.contains("shadows.cascades = 5: must be 1 to 4"), "{message}");
    scene.shadows.cascades = 4;
    scene.lighting.shading = firmament_scene::ShadingName::Gouraud;
    scene.shadows.enabled = Some(true);
    let message = scene.validate().expect_err("Gouraud").to_string();
    assert!(message.contains("need lighting.shading = \"phong\""), "{message}");
    scene.shadows.enabled = None;
    scene.validate().expect("off by default under Gouraud shading");
    assert!(!scene.shadows_enabled());
}

#[test]
fn adding_the_enabled_key_keeps_what_the_scene_does() {
    for (preset, on) in [("earth-objects", true), ("fixed-function-tour", false)] {
        let mut doc = SceneDocument::load(SceneSource::Preset(preset), None, &[]).expect("valid");
        assert!(doc.missing_keys("shadows").contains(&"enabled".to_owned()), "{preset}");
        let value = doc.add_key("shadows.enabled").expect("added");
        assert_eq!(value, toml::Value::Boolean(on), "{preset}");
        let scene = doc.scene().expect("still valid");
        assert_eq!(scene.shadows.enabled, Some(on));
        assert_eq!(scene.shadows_enabled(), on);
    }
}
