//! `[flare]` and the lights' `flare` keys: the defaults, the presets and the scene's own elements,
//! sources in the world frame (eye-space lights, suns through the air), the `nehe-flare` preset,
//! and a clear error naming the key for each bad value.

use firmament_core::TimeOfDay;
use firmament_core::flare::{FlareElement, FlareLayer, FlareShape, LensFlare, on_screen};
use firmament_core::frame::Sky;
use firmament_scene::{FlarePresetName, Scene, SceneError, SceneSource, load};
use glam::{DVec3, DVec4};

use crate::support::from_text;

fn preset(name: &str, sets: &[&str]) -> Result<Scene, SceneError> {
    let sets: Vec<String> = sets.iter().map(|s| (*s).to_owned()).collect();
    load(SceneSource::Preset(name), None, &sets)
}

fn flares(scene: &Scene) -> FlareLayer {
    scene.frame_at(None).expect("frame").flares
}

fn luminance(c: DVec3) -> f64 {
    c.dot(DVec3::new(0.2126, 0.7152, 0.0722))
}

/// The message of the first error, from loading (validation) alone.
fn load_error(text: &str) -> String {
    match from_text(text) {
        Ok(_) => panic!("should fail to load:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn by_default_there_are_no_flares() {
    let scene = preset("default", &[]).expect("valid");
    let f = &scene.flare;
    assert!(!f.enabled);
    assert_eq!(f.preset, FlarePresetName::Classic);
    assert_eq!(f.elements, None);
    assert_eq!((f.samples, f.margin, f.intensity), (32, 0.2, 1.0));
    assert_eq!((f.fade_in, f.fade_out), (0.0, 0.0));
    assert_eq!(flares(&scene), FlareLayer::default());
    // A light marked `flare` draws nothing while flares are off.
    let text = "[[lights]]\nflare = true\n";
    assert_eq!(flares(&from_text(text).expect("valid")), FlareLayer::default());
}

#[test]
fn the_classic_preset_arrives_with_the_scene_s_settings() {
    let text = r#"
[flare]
enabled = true
samples = 64
margin = 0.5
intensity = 2.0
fade_in = 4.0
fade_out = 8.0
"#;
    let layer = flares(&from_text(text).expect("valid"));
    let flare = layer.flare.expect("enabled");
    assert_eq!(flare.elements, LensFlare::classic().elements);
    assert_eq!(flare.samples, 64);
    assert_eq!(
        (flare.margin, flare.intensity, flare.fade_in, flare.fade_out),
        (0.5, 2.0, 4.0, 8.0)
    );
    // The gradient sky's sun at 17:45, in the keyframes' orange, its disc's angular radius.
    assert_eq!(layer.sources.len(), 1);
    let sun = layer.sources[0];
    assert_eq!(sun.position.w, 0.0);
    assert!(sun.position.z > 0.0, "above the horizon: {}", sun.position);
    assert!(
        sun.color.x == 1.0 && sun.color.y < 0.5 && sun.color.z < 0.1,
        "{}",
        sun.color
    );
    assert!((sun.radius - 0.2666f64.to_radians()).abs() < 1e-15);
    // Other presets by name; at midnight the gradient's sun is below the horizon.
    for (name, want) in [("subtle", LensFlare::subtle()), ("anamorphic", LensFlare::anamorphic())] {
        let scene = preset(
            "default",
            &[
                "flare.enabled=true",
                &format!("flare.preset={name}"),
                "time.time_of_day=\"00:00\"",
            ],
        )
        .expect(name);
        let layer = flares(&scene);
        assert_eq!(layer.flare.expect(name).elements, want.elements);
        assert!(layer.sources.is_empty(), "{name}: {:?}", layer.sources);
    }
}

#[test]
fn elements_replace_the_preset_s_with_defaults_for_shape_values() {
    let text = r#"
[flare]
enabled = true
preset = "subtle"
elements = [
    { kind = "glow", size = 0.3 },
    { kind = "streaks", size = 0.5, points = 4, rotation = 45.0, color = [1.0, 0.5, 0.25], intensity = 0.5 },
    { kind = "halo", size = 0.2, position = 1.0, thickness = 0.1 },
    { kind = "ghost", size = 0.1, sides = 0, position = 1.5, stretch = 2.0 },
    { kind = "ghost", size = 0.1, position = -0.5 },
]
"#;
    let flare = flares(&from_text(text).expect("valid")).flare.expect("enabled");
    let e = &flare.elements;
    assert_eq!(e.len(), 5);
    assert_eq!(e[0], FlareElement::new(FlareShape::Glow, [1.0; 3], 1.0, 0.3, 0.0));
    assert_eq!(
        e[1],
        FlareElement::new(
            FlareShape::Streaks {
                points: 4,
                rotation: 45.0,
                sharpness: 24.0
            },
            [1.0, 0.5, 0.25],
            0.5,
            0.5,
            0.0
        )
    );
    assert_eq!(e[2].shape, FlareShape::Halo { thickness: 0.1 });
    assert_eq!(e[2].position, 1.0);
    assert_eq!(
        e[3].shape,
        FlareShape::Ghost {
            sides: 0,
            rotation: 0.0,
            softness: 0.15
        }
    );
    assert_eq!((e[3].stretch, e[3].position), (2.0, 1.5));
    assert_eq!(
        e[4].shape,
        FlareShape::Ghost {
            sides: 6,
            rotation: 0.0,
            softness: 0.15
        }
    );
    // An empty list is a flare with no elements.
    let scene = preset("default", &["flare.enabled=true", "flare.elements=[]"]).expect("valid");
    assert!(flares(&scene).flare.expect("enabled").elements.is_empty());
}

#[test]
fn light_sources_are_in_the_world_frame_under_a_turned_camera() {
    let text = r#"
[camera]
position = [1.0, 2.0, 3.0]
heading = 30.0
pitch = 10.0
roll = 5.0

[sky]
model = "clear"

[flare]
enabled = true

[[lights]]
space = "eye"
position = [0.0, 0.0, -10.0, 1.0]
diffuse = [1.0, 0.5, 0.25]
flare = true

[[lights]]
space = "eye"
position = [0.0, 1.0, 0.0, 0.0]
diffuse = [0.2, 0.3, -0.1]
flare = true

[[lights]]
space = "world"
position = [10.0, 20.0, 30.0, 2.0]
flare = true
flare_radius = 0.5

[[lights]]
position = [0.0, 0.0, -1.0, 1.0]
"#;
    let scene = from_text(text).expect("valid");
    let frame = scene.frame_at(None).expect("frame");
    let camera = frame.camera;
    let sources = frame.flares.sources;
    assert_eq!(sources.len(), 3, "the unmarked light is no source");
    // 10 m straight ahead of the eye.
    let ahead = camera.position + camera.forward() * 10.0;
    assert!(
        (sources[0].position.truncate() - ahead).length() < 1e-12,
        "{}",
        sources[0].position
    );
    assert_eq!(sources[0].position.w, 1.0);
    assert_eq!(sources[0].radius, 0.05);
    assert_eq!(sources[0].color, DVec3::new(1.0, 0.5, 0.25));
    let seen = on_screen(&camera, &sources[0], 0.0).expect("ahead is on screen");
    assert!(seen.center.length() < 1e-9);
    // A direction: up on the screen, rotated but not moved; radians by default.
    assert!((sources[1].position - camera.up().extend(0.0)).length() < 1e-12);
    assert_eq!(sources[1].radius, 0.005);
    assert_eq!(
        sources[1].color,
        DVec3::new(0.2, 0.3, 0.0),
        "negative channels count as 0"
    );
    // World lights stay; w ≠ 1 is divided out.
    assert_eq!(sources[2].position, DVec4::new(5.0, 10.0, 15.0, 1.0));
    assert_eq!(sources[2].radius, 0.5);
    assert_eq!(sources[2].color, DVec3::ZERO, "light 2's initial diffuse is GL's black");
}

#[test]
fn a_setting_sun_flares_red_and_dim_and_a_set_sun_not_at_all() {
    let scene = preset("earth-sunset", &[]).expect("valid");
    assert!(scene.flare.enabled);
    assert_eq!(scene.flare.preset, FlarePresetName::Subtle);
    let frame = scene.frame_at(None).expect("frame");
    let Sky::Atmosphere(sky) = &frame.sky else {
        panic!("atmosphere")
    };
    let layer = frame.flares;
    assert_eq!(layer.flare.expect("on").elements, LensFlare::subtle().elements);
    assert_eq!(layer.sources.len(), 1);
    let sunset = layer.sources[0];
    assert_eq!(sunset.position, sky.suns[0].direction.normalize().extend(0.0));
    assert_eq!(sunset.radius, sky.suns[0].angular_radius);
    let c = sunset.color;
    assert!(c.x > c.y && c.y > c.z, "red-dominant: {c}");
    let y = luminance(c);
    assert!(y > 0.0 && y < 0.5, "dimmed at 2°: {y}");
    // High in a clear sky: nearly all of it, less red.
    let noon = flares(&preset("earth-sunset", &["suns.0.elevation=60"]).expect("valid")).sources[0].color;
    let high = luminance(noon);
    assert!(high > y && high > 0.7 && high < 1.0, "{high}");
    assert!(noon.x / noon.z < c.x / c.z, "{noon} vs {c}");
    // Above the atmosphere nothing is lost: luminance 1.
    let orbit = flares(&preset("earth-sunset", &["camera.position=[0, 0, 200000]"]).expect("valid")).sources[0].color;
    assert!((luminance(orbit) - 1.0).abs() < 1e-9, "{orbit}");
    // Below the horizon: no source.
    let set = preset("earth-sunset", &["suns.0.elevation=-3"]).expect("valid");
    assert!(flares(&set).sources.is_empty());
}

#[test]
fn empirical_stars_flare_through_their_own_air_unless_the_planet_hides_them() {
    let scene = preset("seed-mars", &["flare.enabled=true"]).expect("valid");
    let frame = scene.frame_at(None).expect("frame");
    assert!(matches!(frame.sky, Sky::Empirical(_)));
    let sources = frame.flares.sources;
    assert_eq!(sources.len(), 1);
    // Dimmed by the seed's extinction, and (Mars's B0 is reddish) bluer than it started.
    let c = sources[0].color;
    assert!(luminance(c) > 0.2 && luminance(c) < 1.0, "{c}");
    assert!(c.z > c.x, "{c}");
    let low =
        flares(&preset("seed-mars", &["flare.enabled=true", "suns.0.elevation=2"]).expect("valid")).sources[0].color;
    assert!(luminance(low) < luminance(c), "{low} vs {c}");
    // From far above the seed's atmosphere nothing is lost.
    let high = preset("seed-mars", &["flare.enabled=true", "camera.position=[0, 0, 2000000]"]).expect("valid");
    let from_space = flares(&high).sources[0].color;
    assert!((luminance(from_space) - 1.0).abs() < 1e-9, "{from_space}");
    let sun = scene.atmosphere_sky().expect("sky").suns[0];
    let direction = sources[0].position.truncate();
    // Seen from the camera, not from the planet centre: a parallax of R / 1 AU ≈ 2e-5.
    assert!(
        direction.angle_between(sun.direction) < 1e-4,
        "{direction} vs {}",
        sun.direction
    );
    assert!((sources[0].radius / sun.angular_radius - 1.0).abs() < 1e-4);
    let set = preset("seed-mars", &["flare.enabled=true", "suns.0.elevation=-5"]).expect("valid");
    assert!(flares(&set).sources.is_empty());
}

#[test]
fn a_gradient_sun_flares_in_its_keyframe_colour() {
    let at = |time: &str| {
        let sets = ["flare.enabled=true".to_owned(), format!("time.time_of_day=\"{time}\"")];
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        flares(&preset("default", &sets).expect("valid")).sources
    };
    // The default cycle's sun colour: white at noon, #ff9040 at 17:30, black by night.
    let noon = at("12:00");
    assert_eq!(noon.len(), 1);
    assert!((noon[0].color - DVec3::ONE).length() < 1e-9, "{}", noon[0].color);
    let sunset = at("17:30")[0].color;
    let srgb = |byte: f64| firmament_core::color::srgb_to_linear(byte / 255.0);
    let expected = DVec3::new(1.0, srgb(144.0), srgb(64.0));
    assert!((sunset - expected).length() < 1e-6, "{sunset} vs {expected}");
    assert!(at("23:00").is_empty());
}

#[test]
fn image_elements_load_each_file_once_next_to_the_scene_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let picture = image::RgbaImage::from_fn(64, 32, |x, _| image::Rgba([(x * 4) as u8, 0, 0, 255]));
    picture.save(dir.path().join("glow.png")).expect("write png");
    let text = r#"
[flare]
enabled = true
elements = [
  { kind = "image", file = "glow.png", size = 0.3 },
  { kind = "glow", size = 0.1 },
  { kind = "image", file = "glow.png", size = 0.1, position = 0.5, rotation = 45.0 },
]
"#;
    let origin = dir.path().join("scene.toml");
    let source = SceneSource::Text {
        text,
        origin: &origin.display().to_string(),
    };
    let scene = load(source, None, &[]).expect("valid");
    let flare = flares(&scene).flare.expect("on");
    assert_eq!(flare.images.len(), 1, "one file, loaded once");
    let side = firmament_core::flare::FLARE_IMAGE_SIDE;
    assert_eq!((flare.images[0].width, flare.images[0].height), (side, side));
    // Resampled, red still rises from left to right.
    let left = flare.images[0].texel(10, 100).expect("inside")[0];
    let right = flare.images[0].texel(240, 100).expect("inside")[0];
    assert!(left < 20 && right > 230, "{left} {right}");
    assert_eq!(
        flare.elements[2].shape,
        FlareShape::Image {
            image: 0,
            rotation: 45.0
        }
    );
    // A missing file names the element's key and the path.
    let missing = text.replace("\"glow.png\", size = 0.1", "\"nowhere.png\", size = 0.1");
    let source = SceneSource::Text {
        text: &missing,
        origin: &origin.display().to_string(),
    };
    let message = load(source, None, &[]).expect_err("missing file").to_string();
    assert!(
        message.contains("flare.elements[2].file") && message.contains("nowhere.png"),
        "{message}"
    );
}

#[test]
fn nehe_flare_shows_the_light_and_its_tile_hides_it_at_00_01() {
    let scene = preset("nehe-flare", &[]).expect("valid");
    let frame = scene.frame_at(None).expect("frame");
    let layer = &frame.flares;
    assert_eq!(
        layer.flare.as_ref().expect("on").elements,
        LensFlare::classic().elements
    );
    assert_eq!(layer.sources.len(), 1);
    let light = layer.sources[0];
    // The world frame is the eye frame here.
    assert!(
        (light.position - DVec4::new(-15.0, 9.0, -50.0, 1.0)).length() < 1e-9,
        "{}",
        light.position
    );
    assert_eq!((light.radius, light.color), (1.0, DVec3::ONE));
    let seen = on_screen(&frame.camera, &light, 0.0).expect("on screen");
    assert!(
        seen.center.x < -0.3 && seen.center.y > 0.3,
        "upper left: {}",
        seen.center
    );
    // The tile (a cube of side 8 squashed in z) against the line of sight to the light's centre
    // and to points on its disc: clear at 00:00, covering the whole disc at 00:01.
    let covered = |time: &str| {
        let t: TimeOfDay = time.parse().expect("time");
        let frame = scene.frame_at(Some(t)).expect("frame");
        let to_object = frame.objects.objects[0].model.inverse();
        let target = light.position.truncate();
        let side = target.cross(DVec3::Y).normalize();
        let up = side.cross(target).normalize();
        let points = [DVec3::ZERO, side, -side, up, -up].map(|o| target + o * light.radius);
        points.map(|p| {
            // Slab test of the segment eye → p in the object's frame against [-4, 4]³.
            let a = to_object.transform_point3(DVec3::ZERO);
            let d = to_object.transform_point3(p) - a;
            let (mut t0, mut t1) = (0.0f64, 1.0f64);
            for i in 0..3 {
                let (lo, hi) = ((-4.0 - a[i]) / d[i], (4.0 - a[i]) / d[i]);
                t0 = t0.max(lo.min(hi));
                t1 = t1.min(lo.max(hi));
            }
            t0 <= t1
        })
    };
    assert_eq!(covered("00:00"), [false; 5]);
    assert_eq!(covered("00:01"), [true; 5]);
    assert!(covered("00:00:40").contains(&true) && covered("00:00:40").contains(&false));
    assert_eq!(covered("00:02"), [false; 5]);
}

#[test]
fn every_bad_flare_value_names_its_key() {
    let flare = |body: &str| format!("[flare]\nenabled = true\n{body}\n");
    let element = |e: &str| flare(&format!("elements = [{{ kind = \"glow\", size = 0.1 }}, {e}]"));
    let cases: Vec<(String, &str)> = vec![
        (flare("samples = 0"), "flare.samples = 0: must be 1 to 256"),
        (flare("samples = 257"), "flare.samples = 257"),
        (flare("samples = -1"), "flare.samples"),
        (flare("margin = -0.1"), "flare.margin"),
        (flare("intensity = nan"), "flare.intensity"),
        (flare("fade_in = -1.0"), "flare.fade_in"),
        (flare("fade_out = inf"), "flare.fade_out"),
        (flare("preset = \"sparkle\""), "flare.preset"),
        ("[flare]\nenabled = \"yes\"\n".to_owned(), "flare.enabled"),
        (flare("glare = -1.0"), "flare.glare = -1: must be a finite number >= 0"),
        (flare("glare = nan"), "flare.glare"),
        (
            flare("aperture_blades = 2"),
            "flare.aperture_blades = 2: must be 0 (a round iris) or 3 to 16",
        ),
        (flare("aperture_rotation = inf"), "flare.aperture_rotation"),
        (flare("glear = 1.0"), "flare.glear"),
        (element("{ kind = \"sparkle\", size = 0.1 }"), "flare.elements[1].kind"),
        (element("{ size = 0.1 }"), "flare.elements[1].kind"),
        (element("{ kind = \"glow\" }"), "flare.elements[1].size"),
        (element("{ kind = \"glow\", size = 0.0 }"), "flare.elements[1].size = 0"),
        (element("{ kind = \"glow\", size = -1.0 }"), "flare.elements[1].size"),
        (
            element("{ kind = \"glow\", size = 0.1, color = [nan, 0.0, 0.0] }"),
            "flare.elements[1].color",
        ),
        (
            element("{ kind = \"glow\", size = 0.1, color = [1.0, -1.0, 0.0] }"),
            "flare.elements[1].color",
        ),
        (
            element("{ kind = \"glow\", size = 0.1, intensity = -1.0 }"),
            "flare.elements[1].intensity",
        ),
        (
            element("{ kind = \"glow\", size = 0.1, stretch = 0.0 }"),
            "flare.elements[1].stretch",
        ),
        (
            element("{ kind = \"glow\", size = 0.1, position = nan }"),
            "flare.elements[1].position",
        ),
        (
            element("{ kind = \"glow\", size = 0.1, radius = 1.0 }"),
            "flare.elements[1].radius",
        ),
        (
            element("{ kind = \"streaks\", size = 0.1, points = 1 }"),
            "flare.elements[1].points",
        ),
        (
            element("{ kind = \"streaks\", size = 0.1, points = 33 }"),
            "flare.elements[1].points",
        ),
        (
            element("{ kind = \"streaks\", size = 0.1, sharpness = 0.5 }"),
            "flare.elements[1].sharpness",
        ),
        (
            element("{ kind = \"streaks\", size = 0.1, rotation = inf }"),
            "flare.elements[1].rotation",
        ),
        (
            element("{ kind = \"halo\", size = 0.1, thickness = 0.0 }"),
            "flare.elements[1].thickness",
        ),
        (
            element("{ kind = \"halo\", size = 0.1, points = 4 }"),
            "flare.elements[1].points",
        ),
        (
            element("{ kind = \"glow\", size = 0.1, sides = 6 }"),
            "flare.elements[1].sides",
        ),
        (
            element("{ kind = \"ghost\", size = 0.1, sides = 2 }"),
            "flare.elements[1].sides",
        ),
        (
            element("{ kind = \"ghost\", size = 0.1, softness = 1.5 }"),
            "flare.elements[1].softness",
        ),
        (
            element("{ kind = \"image\", size = 0.1 }"),
            "flare.elements[1].file = (absent): an image element needs `file`",
        ),
        (
            element("{ kind = \"glow\", size = 0.1, file = \"a.png\" }"),
            "flare.elements[1].file",
        ),
        (
            element("{ kind = \"image\", size = 0.1, file = \"missing-flare.png\" }"),
            "missing-flare.png does not exist",
        ),
        (
            element("{ kind = \"image\", size = 0.1, file = \"a.png\", sides = 3 }"),
            "flare.elements[1].sides",
        ),
        (
            "[[lights]]\nflare = true\nposition = [0.0, 0.0, -5.0, 1.0]\nflare_radius = 0.0\n".to_owned(),
            "lights[0].flare_radius = 0",
        ),
        (
            "[[lights]]\nflare = true\nflare_radius = 2.0\n".to_owned(),
            "lights[0].flare_radius = 2: a directional light's",
        ),
        ("[[lights]]\nflare = 1\n".to_owned(), "lights[0].flare"),
    ];
    for (text, expected) in cases {
        let message = load_error(&text);
        assert!(
            message.contains(expected),
            "{text}\n  got:      {message}\n  expected: {expected}"
        );
    }
    // Out of range whether or not flares are on.
    let message = load_error("[flare]\nsamples = 0\n");
    assert!(message.contains("flare.samples"), "{message}");
}

#[test]
fn a_cloud_between_the_eye_and_the_sun_dims_its_flare_by_the_beam() {
    // The sun 60° up behind a uniform layer 500 m thick of 0.001 m⁻¹: its optical depth along
    // the beam, from the camera's altitude, through the shell (the Earth's mean radius; the
    // ellipsoid's own curvature changes it by parts in 10⁶).
    let sets = ["suns.0.elevation=60"];
    let altitude = preset("earth-sunset", &sets)
        .expect("valid")
        .camera_altitude()
        .expect("over the ground");
    let (r0, mu) = (6_371_000.0 + altitude, 30f64.to_radians().cos());
    let to = |h: f64| -r0 * mu + ((6_371_000.0_f64 + h).powi(2) - r0 * r0 * (1.0 - mu * mu)).sqrt();
    let tau = 0.001 * (to(1500.0) - to(1000.0));
    let clear = flares(&preset("earth-sunset", &sets).expect("valid")).sources[0].color;
    let cloud = [
        "suns.0.elevation=60",
        "clouds.0.kind=\"uniform\"",
        "clouds.0.bottom=1000.0",
        "clouds.0.top=1500.0",
        "clouds.0.coverage=1.0",
        "clouds.0.density=0.001",
    ];
    let dimmed = flares(&preset("earth-sunset", &cloud).expect("valid")).sources[0].color;
    let want = (-tau).exp();
    for (d, c) in [(dimmed.x, clear.x), (dimmed.y, clear.y), (dimmed.z, clear.z)] {
        assert!((d / c / want - 1.0).abs() < 1e-5, "{dimmed} / {clear} vs {want}");
    }
    // Above the layer the flare is the clear sky's.
    let over = [&cloud[..], &["camera.position=[0, 0, 3000]"]].concat();
    let over_clear = [&sets[..], &["camera.position=[0, 0, 3000]"]].concat();
    assert_eq!(
        flares(&preset("earth-sunset", &over).expect("valid")).sources[0].color,
        flares(&preset("earth-sunset", &over_clear).expect("valid")).sources[0].color
    );
}
