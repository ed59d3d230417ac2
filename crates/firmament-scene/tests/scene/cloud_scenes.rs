//! `[[clouds]]` (issue 26): the presets' layers, every key reaching the core's `CloudLayer`,
//! coverage maps next to the scene file, the wind's drift with the scene's time, and every bad
//! value naming its key and rule.

use firmament_core::TimeOfDay;
use firmament_core::astro::time::J2000;
use firmament_core::atmosphere::clouds::{CloudKind, CloudLayer, CoverageMap, DualHenyeyGreenstein, wind_drift};
use firmament_core::frame::{AtmosphereSky, Sky};
use firmament_scene::{CloudEntry, Scene, SceneDocument, SceneError, SceneSource, load, load_file, parse_date_time};
use glam::{DQuat, DVec3};
use image::{ImageFormat, Rgba, RgbaImage};
use toml::Value;

use crate::support::from_text;

/// One valid layer as TOML, for scenes built from text.
const CUMULUS: &str = "[[clouds]]\nkind = \"cumulus\"\nbottom = 1500.0\ntop = 3000.0\ncoverage = 0.4\ndensity = 0.05\n";

fn preset(name: &str, sets: &[&str]) -> Result<Scene, SceneError> {
    let sets: Vec<String> = sets.iter().map(|s| (*s).to_owned()).collect();
    load(SceneSource::Preset(name), None, &sets)
}

fn sky_of(scene: &Scene) -> AtmosphereSky {
    sky_in(scene.frame_at(None).expect("frame").sky)
}

fn sky_in(sky: Sky) -> AtmosphereSky {
    match sky {
        Sky::Atmosphere(sky) => sky,
        Sky::Gradient(_) | Sky::Empirical(_) | Sky::Clear(_) => panic!("expected an atmosphere sky"),
    }
}

/// The droplets' phase function the core gives a layer by default.
fn droplet_phase() -> DualHenyeyGreenstein {
    CloudLayer::new(0.0, 1.0, 0.0, 0.0, CloudKind::Uniform).phase
}

/// A `width × height` PNG whose texel at column `x`, row `y` (row 0 at the top) is `grey(x, y)`.
fn png(width: u32, height: u32, grey: impl Fn(u32, u32) -> u8) -> Vec<u8> {
    let image = RgbaImage::from_fn(width, height, |x, y| {
        let v = grey(x, y);
        Rgba([v, v, v, 255])
    });
    let mut bytes = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut bytes), ImageFormat::Png)
        .expect("encodes");
    bytes
}

#[test]
fn the_cloud_presets_have_their_layers() {
    let cumulus = sky_of(&preset("earth-clouds", &[]).expect("valid"));
    assert_eq!(cumulus.clouds.len(), 1);
    let layer = &cumulus.clouds[0];
    assert_eq!(layer.kind, CloudKind::Cumulus);
    assert_eq!((layer.bottom_m, layer.top_m), (1500.0, 3000.0));
    assert_eq!((layer.coverage, layer.density_per_m), (0.4, 0.05));
    assert_eq!((layer.albedo, layer.phase), (1.0, droplet_phase()));
    assert!((cumulus.suns[0].direction.z.asin().to_degrees() - 35.0).abs() < 1e-9);

    let sunset = sky_of(&preset("earth-clouds-sunset", &[]).expect("valid"));
    let kinds: Vec<CloudKind> = sunset.clouds.iter().map(|l| l.kind).collect();
    assert_eq!(kinds, [CloudKind::Cumulus, CloudKind::Cirrus]);
    assert!((8000.0..=10_000.0).contains(&sunset.clouds[1].bottom_m));
    assert!((sunset.suns[0].direction.z.asin().to_degrees() - 2.0).abs() < 1e-9);

    let orbit = sky_of(&preset("earth-orbit", &[]).expect("valid"));
    assert_eq!(orbit.clouds.len(), 1);
    assert_eq!(orbit.clouds[0].kind, CloudKind::Cumulus);
    assert_eq!(orbit.clouds[0].coverage, 0.1);

    let binary = sky_of(&preset("binary-sunset", &[]).expect("valid"));
    assert_eq!((binary.suns.len(), binary.clouds.len()), (2, 1));

    // The presets without clouds stay without.
    for name in ["earth-noon", "earth-sunset", "mars-noon", "saturn-orbit"] {
        assert!(sky_of(&preset(name, &[]).expect("valid")).clouds.is_empty(), "{name}");
    }
}

#[test]
fn every_key_reaches_the_core_layer() {
    let text = format!(
        "preset = \"earth-noon\"\n{CUMULUS}wind = [3.0, -4.0]\nseed = 42\nalbedo = 0.9\nphase = [0.7, -0.2, 0.6]\n\
         [[clouds]]\nkind = \"uniform\"\nbottom = 0.0\ntop = 500.0\ncoverage = 1.0\ndensity = 0.002\n"
    );
    let scene = from_text(&text).expect("valid");
    let sky = sky_of(&scene);
    let mut expected = CloudLayer::new(1500.0, 3000.0, 0.4, 0.05, CloudKind::Cumulus);
    expected.wind_mps = [3.0, -4.0];
    expected.seed = 42;
    expected.albedo = 0.9;
    expected.phase = DualHenyeyGreenstein {
        g_forward: 0.7,
        g_back: -0.2,
        blend: 0.6,
    };
    // No date: no drift.
    assert_eq!(sky.clouds[0], expected);
    assert_eq!(
        sky.clouds[1],
        CloudLayer::new(0.0, 500.0, 1.0, 0.002, CloudKind::Uniform)
    );
    // Every kind by its name.
    for kind in CloudKind::ALL {
        let scene = preset("earth-clouds", &[&format!("clouds.0.kind={}", kind.name())]).expect("a kind");
        assert_eq!(sky_of(&scene).clouds[0].kind, kind);
    }
    // The builder gives the file's layer.
    let built = Scene::builder()
        .atmosphere(firmament_scene::Body::Earth)
        .sun_at_deg(180.0, 45.0)
        .cloud(
            CloudEntry::new_m(CloudKind::Cumulus, 1500.0, 3000.0, 0.4, 0.05)
                .wind_mps(3.0, -4.0)
                .seed(42),
        )
        .build()
        .expect("valid");
    let layer = &sky_of(&built).clouds[0];
    assert_eq!(
        (layer.wind_mps, layer.seed, layer.phase),
        ([3.0, -4.0], 42, droplet_phase())
    );
}

#[test]
fn overrides_reach_layers_by_index_and_append_one_past_the_end() {
    let scene = preset("earth-clouds", &["clouds.0.coverage=0.75", "clouds.0.kind=stratus"]).expect("valid");
    let layer = &sky_of(&scene).clouds[0];
    assert_eq!((layer.coverage, layer.kind), (0.75, CloudKind::Stratus));

    // Index 1 appends a layer, which needs its required keys.
    let error = preset("earth-clouds", &["clouds.1.coverage=0.5"]).expect_err("incomplete");
    assert_eq!(error.to_string(), "clouds[1].bottom: missing: this key is required");
    let scene = preset(
        "earth-clouds",
        &[
            "clouds.1.kind=cirrus",
            "clouds.1.bottom=9000",
            "clouds.1.top=10000",
            "clouds.1.coverage=0.3",
            "clouds.1.density=0.001",
        ],
    )
    .expect("two layers");
    assert_eq!(sky_of(&scene).clouds.len(), 2);

    // The default scene has an empty list to append to; a scene file's list replaces the preset's.
    let scene = preset(
        "default",
        &["clouds=[{ kind = \"stratus\", bottom = 300, top = 800, coverage = 1, density = 0.04 }]"],
    )
    .expect("valid");
    assert_eq!(scene.clouds.len(), 1);
    let scene = from_text(&format!("preset = \"earth-clouds-sunset\"\n{CUMULUS}")).expect("valid");
    assert_eq!(scene.clouds.len(), 1);
}

#[test]
fn only_the_physical_atmosphere_draws_clouds_but_every_scene_checks_them() {
    // The crate's convention for sections one sky does not use (as `[[suns]]` under the gradient
    // sky): checked, then ignored.
    let gradient = from_text(CUMULUS).expect("a gradient scene with clouds is valid");
    assert!(matches!(gradient.frame_at(None).expect("frame").sky, Sky::Gradient(_)));
    let seed = preset("earth-clouds", &["atmosphere.model=\"seed\""]).expect("valid");
    assert!(matches!(seed.frame_at(None).expect("frame").sky, Sky::Empirical(_)));
    let error = from_text(&format!("{CUMULUS}coverage = 2.0\n").replace("coverage = 0.4\n", ""))
        .expect_err("checked in a gradient scene too");
    assert!(error.to_string().starts_with("clouds[0].coverage = 2:"), "{error}");
}

#[test]
fn scenes_without_a_date_do_not_drift() {
    let scene = preset("earth-clouds", &[]).expect("valid");
    for time in [None, Some(TimeOfDay::from_hours(15.0).expect("a time"))] {
        let sky = sky_in(scene.frame_at(time).expect("frame").sky);
        assert_eq!(sky.clouds[0].drift, DQuat::IDENTITY, "{time:?}");
    }
    assert_eq!(scene.atmosphere_sky().expect("sky").clouds[0].drift, DQuat::IDENTITY);
}

#[test]
fn the_wind_carries_the_clouds_from_the_scene_s_own_moment() {
    let scene = preset("earth-clouds", &["time.date_time=\"2024-03-20T09:00:00Z\""]).expect("valid");
    let own = sky_of(&scene);
    let planet = own.atmosphere.planet;
    let reference = planet.to_planet_frame(DVec3::ZERO);
    let wind = own.clouds[0].wind_mps;
    assert_ne!(wind, [0.0, 0.0]);
    // At the scene's own moment, no drift.
    assert_eq!(own.clouds[0].drift, DQuat::IDENTITY);
    assert_eq!(scene.atmosphere_sky().expect("sky").clouds[0].drift, DQuat::IDENTITY);

    // An hour later (a time-lapse's or viewer's date), and by `--time` on the same date.
    let later = parse_date_time("2024-03-20T10:00:00Z").expect("a date");
    let drift = sky_in(scene.frame_at_date_time(&later).expect("frame").sky).clouds[0].drift;
    let expected = wind_drift(&planet, reference, wind, 3600.0);
    assert!(drift.abs_diff_eq(expected, 1e-9), "{drift} vs {expected}");
    assert!(!drift.abs_diff_eq(DQuat::IDENTITY, 1e-9));
    let clock = TimeOfDay::from_hours(10.0).expect("a time");
    let by_clock = sky_in(scene.frame_at(Some(clock)).expect("frame").sky).clouds[0].drift;
    assert!(by_clock.abs_diff_eq(expected, 1e-9), "{by_clock} vs {expected}");

    // Smoothly: a second later it has hardly moved.
    let next = parse_date_time("2024-03-20T10:00:01Z").expect("a date");
    let moved = sky_in(scene.frame_at_date_time(&next).expect("frame").sky).clouds[0].drift;
    assert!(moved.angle_between(drift) < 1e-5, "{}", moved.angle_between(drift));

    // A scene without a date takes a time-lapse's instants from J2000.0.
    let undated = preset("earth-clouds", &[]).expect("valid");
    let j2000 = parse_date_time("2000-01-01T12:01:00Z").expect("a date");
    let drift = sky_in(undated.frame_at_date_time(&j2000).expect("frame").sky).clouds[0].drift;
    let expected = wind_drift(&planet, reference, wind, 60.0);
    assert!(drift.abs_diff_eq(expected, 1e-6), "{drift} vs {expected}");
    assert_eq!(J2000, 2_451_545.0);

    // A layer without wind stays put.
    let calm = preset(
        "earth-clouds",
        &["time.date_time=\"2024-03-20T09:00:00Z\"", "clouds.0.wind=[0, 0]"],
    )
    .expect("valid");
    let drift = sky_in(calm.frame_at_date_time(&later).expect("frame").sky).clouds[0].drift;
    assert_eq!(drift, DQuat::IDENTITY);
}

#[test]
fn coverage_maps_load_next_to_the_scene_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let maps = dir.path().join("maps");
    std::fs::create_dir(&maps).expect("folder");
    // 4 × 2: the top row (north) white, the bottom row (south) 51 (0.2), the last column 102.
    let grey = |x: u32, y: u32| {
        if x == 3 {
            102
        } else if y == 0 {
            255
        } else {
            51
        }
    };
    std::fs::write(maps.join("cover.png"), png(4, 2, grey)).expect("write");
    let scene_path = dir.path().join("s.toml");
    std::fs::write(
        &scene_path,
        format!("preset = \"earth-noon\"\n{CUMULUS}coverage_map = \"maps/cover.png\"\n"),
    )
    .expect("write");
    let scene = load_file(&scene_path, None, &[]).expect("valid");
    let map = sky_of(&scene).clouds[0].coverage_map.clone().expect("a map");
    let values = vec![1.0, 1.0, 1.0, 0.4, 0.2, 0.2, 0.2, 0.4];
    assert_eq!(map, CoverageMap::new(4, 2, values).expect("a map"));
    assert_eq!(
        scene.asset_paths(),
        [("clouds[0].coverage_map".to_owned(), dir.path().join("maps/cover.png"))]
    );

    // Saved elsewhere, the path becomes absolute and names the same file.
    let doc = SceneDocument::load_file(&scene_path, None, &[]).expect("loads");
    let elsewhere = tempfile::tempdir().expect("temp dir");
    let saved = elsewhere.path().join("saved.toml");
    doc.save(&saved).expect("saves");
    let reloaded = SceneDocument::load_file(&saved, None, &[]).expect("reloads");
    let path = reloaded
        .get("clouds.0.coverage_map")
        .and_then(Value::as_str)
        .expect("a path");
    assert!(std::path::Path::new(path).is_absolute(), "{path}");
    assert_eq!(
        sky_of(&reloaded.scene().expect("valid")).clouds[0].coverage_map,
        Some(map)
    );
}

#[test]
fn a_missing_or_broken_coverage_map_names_the_key_the_path_and_the_reason() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("text.png"), "hello").expect("write");
    std::fs::write(d.join("notes.txt"), "hello").expect("write");
    std::fs::create_dir(d.join("folder.png")).expect("folder");
    for (file, reason) in [
        ("nope.png", "does not exist"),
        ("text.png", "cannot decode the Png image"),
        ("notes.txt", "not an image file of a known format"),
        ("folder.png", "is not a regular file"),
    ] {
        let scene_path = d.join("s.toml");
        std::fs::write(&scene_path, format!("{CUMULUS}coverage_map = \"{file}\"\n")).expect("write");
        match load_file(&scene_path, None, &[]) {
            Err(SceneError::Asset { key, path, reason: why }) => {
                assert_eq!(key, "clouds[0].coverage_map");
                assert_eq!(path, d.join(file).display().to_string());
                assert!(why.contains(reason), "{file}: {why}");
            }
            other => panic!("{file}: expected an asset error, got {other:?}"),
        }
    }
}

#[test]
fn every_bad_cloud_value_names_its_key_and_rule() {
    let nine = format!("preset = \"earth-noon\"\n{}", CUMULUS.repeat(9));
    let cases: Vec<(String, &str)> = vec![
        (nine, "clouds = 9 layers: at most 8 cloud layers (MAX_CLOUD_LAYERS"),
        (
            with(&["bottom = 3000.0", "top = 3000.0"]),
            "clouds[0].top = 3000: must be a finite number of metres above clouds[0].bottom (3000 m): bottom < top",
        ),
        (
            with(&["bottom = 3500.0", "top = 3000.0"]),
            "clouds[0].top = 3000: must be a finite number of metres above clouds[0].bottom (3500 m)",
        ),
        (
            with(&["bottom = -10.0"]),
            "clouds[0].bottom = -10: must be a finite number of metres >= 0",
        ),
        (
            with(&["bottom = nan"]),
            "clouds[0].bottom = NaN: must be a finite number of metres >= 0",
        ),
        (
            with(&["top = inf"]),
            "clouds[0].top = inf: must be a finite number of metres above clouds[0].bottom",
        ),
        (
            with(&["top = 70000.0"]),
            "clouds[0].top = 70000: must be at most the top of the atmosphere, 60000 m above the surface",
        ),
        (
            with(&["coverage = 1.5"]),
            "clouds[0].coverage = 1.5: must be in [0, 1] (the share of the sky covered)",
        ),
        (
            with(&["coverage = -0.1"]),
            "clouds[0].coverage = -0.1: must be in [0, 1]",
        ),
        (with(&["coverage = nan"]), "clouds[0].coverage = NaN: must be in [0, 1]"),
        (
            with(&["density = -0.05"]),
            "clouds[0].density = -0.05: must be in [0, 10] per metre",
        ),
        (
            with(&["density = inf"]),
            "clouds[0].density = inf: must be in [0, 10] per metre",
        ),
        (
            with(&["density = 11.0"]),
            "clouds[0].density = 11: must be in [0, 10] per metre",
        ),
        (
            with(&["kind = \"cumulous\""]),
            "clouds[0].kind: unknown variant `cumulous`, expected one of `cumulus`, `stratocumulus`, `stratus`, `altostratus`, `cirrus`, `uniform` (did you mean `cumulus`?)",
        ),
        (
            with(&["wind = [1.0, 2.0, 3.0]"]),
            "clouds[0].wind: must be 2 numbers, [east, north] in m/s; found 3 numbers",
        ),
        (
            with(&["wind = 5.0"]),
            "clouds[0].wind: invalid type: floating point `5.0`, expected a sequence",
        ),
        (
            with(&["wind = [nan, 0.0]"]),
            "clouds[0].wind = [NaN, 0]: [east, north] must each be a finite speed within ±1000 m/s",
        ),
        (
            with(&["wind = [0.0, 2000.0]"]),
            "clouds[0].wind = [0, 2000]: [east, north] must each be a finite speed within ±1000 m/s",
        ),
        (
            with(&["seed = -1"]),
            "clouds[0].seed: invalid value: integer `-1`, expected u32",
        ),
        (
            with(&["albedo = 1.2"]),
            "clouds[0].albedo = 1.2: must be in [0, 1] (the single-scattering albedo)",
        ),
        (with(&["albedo = nan"]), "clouds[0].albedo = NaN: must be in [0, 1]"),
        (
            with(&["phase = [0.8, -0.3]"]),
            "clouds[0].phase: must be 3 numbers, [g_forward, g_back, blend]; found 2 numbers",
        ),
        (
            with(&["phase = [1.0, -0.3, 0.8]"]),
            "clouds[0].phase = [1, -0.3, 0.8]: g_forward (the first number) must be in (-1, 1)",
        ),
        (
            with(&["phase = [0.8, nan, 0.8]"]),
            "clouds[0].phase = [0.8, NaN, 0.8]: g_back (the second number) must be in (-1, 1)",
        ),
        (
            with(&["phase = [0.8, -0.3, 1.5]"]),
            "clouds[0].phase = [0.8, -0.3, 1.5]: blend (the third number, the forward lobe's weight) must be in [0, 1]",
        ),
        (
            with(&["covrage = 0.5"]),
            "clouds[0].covrage: unknown key (did you mean `coverage`?)",
        ),
        (without("kind"), "clouds[0].kind: missing: this key is required"),
        (
            with(&["coverage_map = 5"]),
            "clouds[0].coverage_map: invalid type: integer `5`, expected a string",
        ),
    ];
    for (text, expected) in cases {
        let error = from_text(&text).expect_err(&text).to_string();
        assert_eq!(error.lines().count(), 1, "{error}");
        assert!(
            error.starts_with(expected),
            "{text}\n  gives: {error}\n  wants: {expected}"
        );
    }
    // `--set` names the same keys.
    let error = preset("earth-clouds", &["clouds.0.density=-1"]).expect_err("negative");
    assert!(error.to_string().starts_with("clouds[0].density = -1:"), "{error}");
}

/// The one-layer scene (over `earth-noon`) with each `key = value` of `lines` in place of the
/// layer's own line for that key, or added.
fn with(lines: &[&str]) -> String {
    let mut layer: Vec<String> = CUMULUS.lines().map(str::to_owned).collect();
    for line in lines {
        let key = line.split(" = ").next().unwrap_or(line);
        match layer.iter().position(|l| l.starts_with(&format!("{key} = "))) {
            Some(i) => layer[i] = (*line).to_owned(),
            None => layer.push((*line).to_owned()),
        }
    }
    format!("preset = \"earth-noon\"\n{}\n", layer.join("\n"))
}

/// The one-layer scene without its line for `key`.
fn without(key: &str) -> String {
    let layer: Vec<&str> = CUMULUS
        .lines()
        .filter(|l| !l.starts_with(&format!("{key} = ")))
        .collect();
    format!("preset = \"earth-noon\"\n{}\n", layer.join("\n"))
}

#[test]
fn the_document_adds_layers_and_their_defaults() {
    let mut doc = SceneDocument::load(SceneSource::Preset("earth-noon"), None, &[]).expect("loads");
    assert_eq!(doc.get("clouds").and_then(Value::as_array).map(Vec::len), Some(0));
    doc.add_entry("clouds").expect("a layer");
    let scene = doc.scene().expect("the new layer is valid");
    assert_eq!(scene.clouds.len(), 1);
    let missing = doc.missing_keys("clouds.0");
    for key in ["wind", "seed", "coverage_map", "albedo", "phase"] {
        assert!(missing.contains(&key.to_owned()), "{missing:?}");
    }
    // The editor offers every kind by name.
    let kinds: Vec<String> = CloudKind::ALL.iter().map(|k| k.name().to_owned()).collect();
    assert_eq!(doc.accepted_names("clouds.0.kind"), Some(kinds));
    let before = sky_of(&scene);
    for key in ["wind", "seed", "albedo", "phase"] {
        doc.add_key(&format!("clouds.0.{key}"))
            .unwrap_or_else(|e| panic!("clouds.0.{key}: {e}"));
    }
    let phase = droplet_phase();
    assert_eq!(
        doc.get("clouds.0.phase"),
        Some(&Value::Array(
            [phase.g_forward, phase.g_back, phase.blend].map(Value::Float).to_vec()
        ))
    );
    assert_eq!(
        sky_of(&doc.scene().expect("valid")),
        before,
        "adding the defaults changed nothing"
    );
}
