//! `planet.surface`, `planet.albedo_map`, `planet.water_map`, `planet.surface_seed` and
//! `planet.wind_speed` (issue 28, surfaces): the built-in surfaces, maps next to the scene file,
//! the medium's albedo becoming the surface's mean, and every bad value naming its key and rule.

use crate::support::{message, preset, sky_of};
use firmament_core::atmosphere::body::BodySurface;
use firmament_core::atmosphere::surface::{DEFAULT_WIND_SPEED_MPS, SurfaceMap};
use firmament_scene::load_file;
use image::{ImageFormat, Rgba, RgbaImage};

/// A PNG whose texel at column `x`, row `y` (row 0 at the top) is `rgba(x, y)`.
fn png(width: u32, height: u32, rgba: impl Fn(u32, u32) -> [u8; 4]) -> Vec<u8> {
    let image = RgbaImage::from_fn(width, height, |x, y| Rgba(rgba(x, y)));
    let mut bytes = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut bytes), ImageFormat::Png)
        .expect("encodes");
    bytes
}

#[test]
fn earth_s_surface_is_natural_earth_and_its_mean_lights_the_luts() {
    let sky = sky_of(&preset("earth-noon", &["planet.surface=\"earth\""]).expect("valid"));
    let surface = sky.surface.expect("a surface");
    assert_eq!(surface.wind_speed_mps, DEFAULT_WIND_SPEED_MPS);
    let [_, _, _, water] = surface.map.mean();
    // Earth's oceans cover 71 % of its area.
    assert!((water - 0.71).abs() < 0.03, "water {water}");
    // The multiple-scattering LUTs see the map's mean albedo.
    assert_eq!(sky.atmosphere.medium.ground_albedo, surface.mean_albedo());
    // The Sahara is dry land, the Pacific open water, Antarctica bright ice.
    let d = f64::to_radians;
    assert_eq!(surface.map.sample(d(23.0), d(10.0))[3], 0.0);
    assert!(surface.map.sample(d(0.0), d(-150.0))[3] > 0.99);
    assert!(surface.map.sample(d(-85.0), d(0.0))[1] > 0.6);
}

#[test]
fn a_procedural_surface_is_made_by_its_seed() {
    let a = sky_of(
        &preset(
            "earth-noon",
            &["planet.surface=\"procedural\"", "planet.surface_seed=3"],
        )
        .expect("valid"),
    );
    let b = sky_of(
        &preset(
            "earth-noon",
            &["planet.surface=\"procedural\"", "planet.surface_seed=3"],
        )
        .expect("valid"),
    );
    let c = sky_of(
        &preset(
            "earth-noon",
            &["planet.surface=\"procedural\"", "planet.wind_speed=12.0"],
        )
        .expect("valid"),
    );
    let (a, b, c) = (a.surface.expect("a"), b.surface.expect("b"), c.surface.expect("c"));
    assert_eq!(a, b);
    assert_ne!(a.map, c.map);
    assert_eq!(c.wind_speed_mps, 12.0);
}

#[test]
fn albedo_and_water_maps_load_next_to_the_scene_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let maps = dir.path().join("maps");
    std::fs::create_dir(&maps).expect("folder");
    // 2 × 1: the left texel sRGB 188 (linear 0.5) land, the right sRGB 0 water; the albedo image
    // is opaque, which says nothing of water.
    std::fs::write(
        maps.join("albedo.png"),
        png(2, 1, |x, _| if x == 0 { [188, 188, 188, 255] } else { [0, 0, 0, 255] }),
    )
    .expect("write");
    std::fs::write(
        maps.join("water.png"),
        png(2, 1, |x, _| if x == 0 { [0, 0, 0, 255] } else { [255, 255, 255, 255] }),
    )
    .expect("write");
    let scene_path = dir.path().join("s.toml");
    let write = |extra: &str| {
        std::fs::write(
            &scene_path,
            format!("preset = \"earth-noon\"\n[planet]\nalbedo_map = \"maps/albedo.png\"\n{extra}"),
        )
        .expect("write");
    };
    write("");
    let scene = load_file(&scene_path, None, &[]).expect("valid");
    let map = sky_of(&scene).surface.expect("a surface").map;
    let half = firmament_core::color::srgb_to_linear(188.0 / 255.0) as f32;
    assert_eq!(
        *map,
        SurfaceMap::new(2, 1, vec![[half, half, half, 0.0], [0.0; 4]]).expect("map")
    );
    write("water_map = \"maps/water.png\"\n");
    let scene = load_file(&scene_path, None, &[]).expect("valid");
    let map = sky_of(&scene).surface.expect("a surface").map;
    assert_eq!((map.texels()[0][3], map.texels()[1][3]), (0.0, 1.0));
    assert_eq!(
        scene.asset_paths(),
        [
            ("planet.albedo_map".to_owned(), dir.path().join("maps/albedo.png")),
            ("planet.water_map".to_owned(), dir.path().join("maps/water.png")),
        ]
    );
    // A water map of another size.
    std::fs::write(maps.join("small.png"), png(1, 1, |_, _| [0, 0, 0, 255])).expect("write");
    write("water_map = \"maps/small.png\"\n");
    let text = load_file(&scene_path, None, &[]).expect_err("sizes differ").to_string();
    assert!(text.contains("planet.water_map") && text.contains("size"), "{text}");
    // A missing file names the key and the path.
    write("water_map = \"maps/nope.png\"\n");
    let text = load_file(&scene_path, None, &[]).expect_err("missing").to_string();
    assert!(text.contains("planet.water_map") && text.contains("nope.png"), "{text}");
}

#[test]
fn bad_surfaces_name_the_key_and_the_rule() {
    for (sets, key, rule) in [
        (&["planet.surface=\"mud\""][..], "surface", "unknown variant"),
        (
            &["planet.surface=\"earth\"", "planet.albedo_map=\"a.png\""][..],
            "planet.albedo_map",
            "not both",
        ),
        (
            &["planet.water_map=\"w.png\""][..],
            "planet.water_map",
            "needs planet.albedo_map",
        ),
        (
            &["planet.surface=\"earth\"", "planet.surface_seed=2"][..],
            "planet.surface_seed",
            "procedural",
        ),
        (
            &["planet.surface=\"procedural\"", "planet.surface_seed=-1"][..],
            "planet.surface_seed",
            ">= 0",
        ),
        (&["planet.wind_speed=5.0"][..], "planet.wind_speed", "needs a surface"),
        (
            &["planet.surface=\"earth\"", "planet.wind_speed=31.0"][..],
            "planet.wind_speed",
            "[0, 30]",
        ),
        (
            &["planet.surface=\"earth\"", "planet.wind_speed=nan"][..],
            "planet.wind_speed",
            "",
        ),
        (
            &["planet.surface=\"earth\"", "atmosphere.ground_albedo=0.3"][..],
            "atmosphere.ground_albedo",
            "remove one",
        ),
    ] {
        let text = message(preset("earth-noon", sets));
        assert!(text.contains(key) && text.contains(rule), "{sets:?}: {text}");
    }
}

#[test]
fn a_body_s_albedo_map_loads_next_to_the_scene_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    // 2 × 1: the western half sRGB 188 (linear 0.5), the eastern black: brightness 0.25.
    std::fs::write(
        dir.path().join("moon.png"),
        png(2, 1, |x, _| if x == 0 { [188, 188, 188, 255] } else { [0, 0, 0, 255] }),
    )
    .expect("write");
    std::fs::write(dir.path().join("black.png"), png(2, 1, |_, _| [0, 0, 0, 255])).expect("write");
    let scene_path = dir.path().join("s.toml");
    let write = |map: &str| {
        let body = format!("position = [4.0e8, 0.0, 0.0]\nradius = 5.0e5\nalbedo = 0.1\nalbedo_map = \"{map}\"\n");
        std::fs::write(&scene_path, format!("preset = \"earth-moon\"\n[[bodies]]\n{body}")).expect("write");
    };
    write("moon.png");
    let scene = load_file(&scene_path, None, &[]).expect("valid");
    let sky = sky_of(&scene);
    let BodySurface::Map(map) = &sky.bodies[0].surface else {
        panic!("a map: {:?}", sky.bodies[0].surface);
    };
    let half = firmament_core::color::srgb_to_linear(188.0 / 255.0) as f32;
    assert_eq!(
        **map,
        SurfaceMap::new(2, 1, vec![[half, half, half, 0.0], [0.0; 4]]).expect("map")
    );
    // The western texel's centre (90° W, the body's −y) shows 0.1 × 0.5 / 0.25.
    let body = &sky.bodies[0];
    let west = body.center + body.orientation * glam::DVec3::NEG_Y * 5.0e5;
    let albedo = body.albedo_at(west);
    assert!(
        (albedo.x - 0.1 * f64::from(half) / (f64::from(half) / 2.0)).abs() < 1e-9,
        "{albedo:?}"
    );
    assert_eq!(
        scene.asset_paths(),
        [("bodies[0].albedo_map".to_owned(), dir.path().join("moon.png"))]
    );
    // A black map has no brightness to scale; a missing file names the key and the path.
    write("black.png");
    let text = load_file(&scene_path, None, &[]).expect_err("black").to_string();
    assert!(
        text.contains("bodies[0].albedo_map") && text.contains("black everywhere"),
        "{text}"
    );
    write("nope.png");
    let text = load_file(&scene_path, None, &[]).expect_err("missing").to_string();
    assert!(
        text.contains("bodies[0].albedo_map") && text.contains("nope.png"),
        "{text}"
    );
}
