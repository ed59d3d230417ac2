//! Empirical-model scenes (`atmosphere.model = "seed"`): presets, `[atmosphere.seed]` and
//! `[[suns]]` to the core's `EmpiricalSky`, and the rules they break naming the key.

use firmament_core::atmosphere::empirical::EmpiricalAtmosphere;
use firmament_core::frame::{EMPIRICAL_DEFAULT_LUMINANCE, EmpiricalSky, Sky};
use firmament_scene::{
    AtmosphereModelName, EMPIRICAL_STAR_DISTANCE, EMPIRICAL_STAR_INTENSITY, Scene, SceneError, SceneSource, load,
};
use glam::DVec3;

fn preset(name: &str, sets: &[&str]) -> Result<Scene, SceneError> {
    let sets: Vec<String> = sets.iter().map(|s| (*s).to_owned()).collect();
    load(SceneSource::Preset(name), None, &sets)
}

fn empirical_sky_of(scene: &Scene) -> EmpiricalSky {
    match scene.frame_at(None).expect("frame").sky {
        Sky::Empirical(sky) => sky,
        other => panic!("expected the empirical sky, got {other:?}"),
    }
}

fn message(result: Result<Scene, SceneError>) -> String {
    result.expect_err("should fail").to_string()
}

#[test]
fn the_seed_presets_hold_the_seeds_values() {
    for (name, expected) in [
        ("seed-earth", EmpiricalAtmosphere::seed_earth()),
        ("seed-mars", EmpiricalAtmosphere::seed_mars()),
    ] {
        let scene = preset(name, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(scene.atmosphere.model, AtmosphereModelName::Empirical);
        let sky = empirical_sky_of(&scene);
        sky.validate().expect("valid for the core");
        assert_eq!(sky.atmosphere, expected, "{name}");
        assert_eq!(sky.luminance, EMPIRICAL_DEFAULT_LUMINANCE);
        assert_eq!(sky.stars.len(), 1, "{name}");
        // The camera is above the seed planet's surface and the world origin is on it.
        let camera = sky.to_planet_frame(DVec3::from_array(scene.camera.position));
        assert!(!sky.atmosphere.surface().contains(camera), "{name}");
        let origin = sky.to_planet_frame(DVec3::ZERO);
        assert!(
            ((origin / sky.atmosphere.surface().radii).length() - 1.0).abs() < 1e-12,
            "{name}"
        );
        // Something is drawn along the view axis (the globe or the sky).
        let forward = scene.camera().forward();
        let (rgb, _) = sky.color(DVec3::from_array(scene.camera.position), forward);
        assert!(rgb.max_element() > 0.0, "{name}: {rgb}");
    }
    // The physical presets keep the physical model.
    let earth = preset("earth-noon", &[]).expect("valid");
    assert_eq!(earth.atmosphere.model, AtmosphereModelName::Physical);
    assert!(matches!(earth.frame_at(None).expect("frame").sky, Sky::Atmosphere(_)));
}

#[test]
fn a_sun_becomes_an_empirical_star() {
    let scene = preset("seed-mars", &[]).expect("valid");
    let sky = empirical_sky_of(&scene);
    let star = sky.stars[0];
    // 1 AU from the planet centre, towards the sun's world direction.
    assert!((star.position.length() / EMPIRICAL_STAR_DISTANCE - 1.0).abs() < 1e-12);
    let world = sky.orientation * star.direction;
    let expected = firmament_core::camera::direction_from_heading_elevation(250f64.to_radians(), 12f64.to_radians());
    assert!((world - expected).length() < 1e-9, "{world} vs {expected}");
    // The radius subtends the body's sun's angular radius; the colour is the sun's spectrum
    // normalised to its largest channel, × 10.
    let sun = scene.atmosphere_sky().expect("sky").suns[0];
    assert!((star.radius / EMPIRICAL_STAR_DISTANCE - sun.angular_radius.sin()).abs() < 1e-15);
    assert!((star.color.max_element() - EMPIRICAL_STAR_INTENSITY).abs() < 1e-12);
    // A sun given by position sits there.
    let text = r#"
        preset = "seed-earth"
        [[suns]]
        position = [0.0, 1.0e9, 2.0e9]
        temperature = 3000.0
    "#;
    let scene = load(SceneSource::Text { text, origin: "test" }, None, &[]).expect("valid");
    let sky = empirical_sky_of(&scene);
    let star = sky.stars[0];
    let world = sky.orientation * star.position + sky.center;
    assert!((world - DVec3::new(0.0, 1.0e9, 2.0e9)).length() < 1e-3, "{world}");
    // A 3000 K sun is red: red is the largest channel.
    assert_eq!(star.color.x, EMPIRICAL_STAR_INTENSITY);
    assert!(star.color.x > star.color.y && star.color.y > star.color.z);
    // Two suns, two stars.
    let two = preset("seed-earth", &["suns.1.azimuth=10", "suns.1.elevation=5"]).expect("valid");
    assert_eq!(empirical_sky_of(&two).stars.len(), 2);
}

#[test]
fn empirical_values_override_and_planet_radii_apply() {
    let scene = preset(
        "seed-earth",
        &[
            "atmosphere.seed.height=80000",
            "atmosphere.seed.view_depth=1e6",
            "atmosphere.seed.b0=[0.5, 0.4, 0.3]",
            "atmosphere.seed.overglow=0.25",
            "atmosphere.seed.luminance=500",
            "planet.radius=6.4e6",
        ],
    )
    .expect("valid");
    let sky = empirical_sky_of(&scene);
    assert_eq!(
        sky.atmosphere,
        EmpiricalAtmosphere {
            equatorial_radius: 6.4e6,
            polar_radius: 6.4e6,
            height: 80_000.0,
            view_depth: 1.0e6,
            b0: DVec3::new(0.5, 0.4, 0.3),
            overglow: 0.25,
        }
    );
    assert_eq!(sky.luminance, 500.0);
    // planet.atmosphere_height is the seed's height when atmosphere.seed.height is not given.
    let sky = empirical_sky_of(&preset("seed-earth", &["planet.atmosphere_height=70000"]).expect("valid"));
    assert_eq!(sky.atmosphere.height, 70_000.0);
    // The seed model on Saturn needs the values the seed does not have.
    let msg = message(preset("seed-earth", &["planet.body=saturn"]));
    assert!(msg.starts_with("atmosphere.seed.view_depth: missing"), "{msg}");
    let saturn = preset(
        "seed-earth",
        &[
            "planet.body=saturn",
            "atmosphere.seed.view_depth=2e6",
            "atmosphere.seed.b0=[0.8, 0.7, 0.5]",
            "atmosphere.seed.overglow=0.3",
            "camera.position=[0.0, 0.0, 2.0e8]",
        ],
    )
    .expect("valid");
    let sky = empirical_sky_of(&saturn);
    assert_eq!(
        sky.atmosphere.equatorial_radius,
        saturn.planet.body.atmosphere().planet.radii.x
    );
}

#[test]
fn bad_empirical_values_name_their_key_and_rule() {
    for (set, key, rule) in [
        ("atmosphere.seed.height=0", "atmosphere.seed.height", "> 0"),
        ("atmosphere.seed.view_depth=-5", "atmosphere.seed.view_depth", "> 0"),
        ("atmosphere.seed.b0=[0.1, -0.2, 0.3]", "atmosphere.seed.b0", ">= 0"),
        ("atmosphere.seed.overglow=nan", "atmosphere.seed.overglow", "finite"),
        ("atmosphere.seed.luminance=0", "atmosphere.seed.luminance", "> 0"),
    ] {
        let msg = message(preset("seed-earth", &[set]));
        assert!(msg.starts_with(&format!("{key} = ")), "{set}: {msg}");
        assert!(msg.contains(rule), "{set}: {msg}");
    }
    // The Rust names say "empirical"; the keys and messages keep the scene file's "seed".
    let msg = message(preset("seed-earth", &["atmosphere.model=seeds"]));
    assert!(msg.starts_with("atmosphere.model: "), "{msg}");
    assert!(msg.contains("expected `physical` or `seed`"), "{msg}");
    let msg = message(preset("seed-earth", &["atmosphere.seed.view_dept=3"]));
    assert!(msg.contains("did you mean `view_depth`"), "{msg}");
    let msg = message(preset("seed-earth", &["atmosphere.seeds=1"]));
    assert!(msg.contains("did you mean `seed`"), "{msg}");
    let msg = message(preset("seed-earth", &["atmosphere.seed=3"]));
    assert!(msg.contains("expected struct SeedSection"), "{msg}");
    // The camera must be above the seed planet's ground.
    let msg = message(preset("seed-mars", &["camera.position=[0.0, 0.0, -10.0]"]));
    assert!(msg.starts_with("camera.position = "), "{msg}");
    assert!(msg.contains("inside the planet"), "{msg}");
}
