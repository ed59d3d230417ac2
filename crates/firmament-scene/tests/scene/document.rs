//! `SceneDocument`: loading, key-by-key edits, reset, and saving files that give the same scene.

use std::path::{Path, PathBuf};

use firmament_scene::{PRESETS, Scene, SceneDocument, SceneError, SceneOrigin, SceneSource, load, load_file};
use toml::Value;

fn preset(name: &str) -> SceneDocument {
    SceneDocument::load(SceneSource::Preset(name), None, &[]).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The scene with what legitimately differs between a document and its saved file cleared: the
/// folder assets resolve against and the (informational) preset name.
fn normalised(mut scene: Scene) -> Scene {
    scene.base_dir = PathBuf::new();
    scene.preset = None;
    scene
}

fn without_preset(table: &toml::Table) -> toml::Table {
    let mut table = table.clone();
    table.remove("preset");
    table
}

#[test]
fn every_preset_saves_to_a_file_that_gives_the_identical_scene() {
    let dir = tempfile::tempdir().expect("temp dir");
    for p in PRESETS {
        let doc = preset(p.name);
        let original = doc.scene().unwrap_or_else(|e| panic!("{}: {e}", p.name));
        let path = dir.path().join(format!("{}.toml", p.name));
        doc.save(&path).unwrap_or_else(|e| panic!("{}: {e}", p.name));

        let text = std::fs::read_to_string(&path).expect("saved");
        assert!(text.starts_with("# Written by firmament"), "{}: {text}", p.name);
        assert_eq!(text.lines().next().map(|l| l.starts_with('#')), Some(true));
        let parsed: toml::Table = text.parse().expect("valid TOML");
        assert!(!parsed.contains_key("preset"), "{}: no preset key", p.name);
        assert_eq!(
            text,
            doc.to_toml_string(),
            "{}: presets have no asset paths to rewrite",
            p.name
        );

        let reloaded = SceneDocument::load_file(&path, None, &[]).unwrap_or_else(|e| panic!("{}: {e}", p.name));
        assert_eq!(reloaded.get("preset"), Some(&Value::String("default".to_owned())));
        assert_eq!(
            without_preset(reloaded.table()),
            without_preset(doc.table()),
            "{}: the saved table layers back to itself",
            p.name
        );
        let scene = load_file(&path, None, &[]).unwrap_or_else(|e| panic!("{}: {e}", p.name));
        assert_eq!(scene.base_dir, dir.path());
        assert_eq!(normalised(scene), normalised(original), "{}", p.name);
    }
}

#[test]
fn load_goes_through_the_document() {
    let sets = vec!["display.exposure=2.5".to_owned(), "suns.0.elevation=3".to_owned()];
    let doc = SceneDocument::load(SceneSource::Preset("dusk"), Some("earth-noon"), &sets).expect("loads");
    assert_eq!(doc.origin(), &SceneOrigin::Preset("earth-noon".to_owned()));
    assert_eq!(doc.origin().to_string(), "preset `earth-noon`");
    assert_eq!(doc.base_dir(), Path::new(""));
    assert!(!doc.is_modified(), "overrides are part of the table as loaded");
    let scene = doc.scene().expect("valid");
    assert_eq!(
        scene,
        load(SceneSource::Preset("dusk"), Some("earth-noon"), &sets).expect("valid")
    );
    assert_eq!(scene.display.exposure, 2.5);
    assert_eq!(scene.suns.len(), 1);

    let text = SceneDocument::load(
        SceneSource::Text {
            text: "[render]\nwidth = 64\n",
            origin: "scenes/mine.toml",
        },
        None,
        &[],
    )
    .expect("loads");
    assert_eq!(text.origin(), &SceneOrigin::Text("scenes/mine.toml".to_owned()));
    assert_eq!(text.base_dir(), Path::new("scenes"));
    assert_eq!(text.scene().expect("valid").base_dir, Path::new("scenes"));
    assert_eq!(text.get("render.width"), Some(&Value::Integer(64)));
}

#[test]
fn edits_show_in_the_scene_and_reset_undoes_them() {
    let mut doc = preset("default");
    assert!(!doc.is_modified());
    doc.set("display.exposure", Value::Float(0.25)).expect("set");
    doc.apply_override("display.tone_curve=aces_fitted").expect("override");
    doc.set(
        "camera.position",
        Value::Array(vec![1.0.into(), 2.0.into(), 3.0.into()]),
    )
    .expect("set");
    // One past the end appends a table, as --set does.
    doc.set("suns.0.azimuth", Value::Float(90.0)).expect("append");
    doc.set("suns.0.elevation", Value::Float(10.0)).expect("set");
    assert!(doc.is_modified());
    let scene = doc.scene().expect("valid");
    assert_eq!(scene.display.exposure, 0.25);
    assert_eq!(scene.display.tone_curve, firmament_core::display::ToneCurve::AcesFitted);
    assert_eq!(scene.camera.position, [1.0, 2.0, 3.0]);
    assert_eq!(scene.suns.len(), 1);

    // Every edit saves: the file gives the edited scene.
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("edited.toml");
    doc.save(&path).expect("saves");
    assert_eq!(
        normalised(load_file(&path, None, &[]).expect("valid")),
        normalised(scene)
    );

    doc.reset();
    assert!(!doc.is_modified());
    assert_eq!(doc.scene().expect("valid"), preset("default").scene().expect("valid"));

    // An edit set back to its old value is no change.
    let old = doc.get("render.width").cloned().expect("width");
    doc.set("render.width", Value::Integer(99)).expect("set");
    assert!(doc.is_modified());
    doc.set("render.width", old).expect("set");
    assert!(!doc.is_modified());

    // Generic editors work on the table itself.
    doc.table_mut()
        .get_mut("render")
        .and_then(Value::as_table_mut)
        .expect("render")
        .insert("height".to_owned(), Value::Integer(100));
    assert_eq!(doc.scene().expect("valid").render.height, 100);
}

#[test]
fn bad_edits_give_the_errors_of_set() {
    let mut doc = preset("default");
    doc.set("display.exposure", Value::Float(-1.0)).expect("set");
    let error = doc.scene().expect_err("negative exposure");
    let from_set = load(
        SceneSource::Preset("default"),
        None,
        &["display.exposure=-1.0".to_owned()],
    )
    .expect_err("negative exposure");
    assert_eq!(error, from_set);
    let message = error.to_string();
    assert!(
        message.contains("display.exposure") && message.contains("> 0"),
        "{message}"
    );

    // Wrong types and unknown keys, too.
    let mut doc = preset("default");
    doc.set("render.width", Value::String("wide".to_owned())).expect("set");
    let from_set = load(SceneSource::Preset("default"), None, &["render.width=wide".to_owned()]);
    assert_eq!(
        doc.scene().expect_err("a string width"),
        from_set.expect_err("a string width")
    );
    let mut doc = preset("default");
    doc.set("camera.fov", Value::Float(40.0)).expect("set");
    let message = doc.scene().expect_err("unknown key").to_string();
    assert!(message.contains("camera.fov") && message.contains("fov_y"), "{message}");

    // Paths that cannot be reached are errors worded like --set's, and change nothing.
    let mut doc = preset("binary-sunset");
    for (path, rule) in [
        ("suns.3.elevation", "past the end"),
        ("suns.x", "array index"),
        ("render.width.x", "cannot set `x` inside a integer"),
        ("display..exposure", "empty part"),
    ] {
        match doc.set(path, Value::Float(1.0)) {
            Err(SceneError::BadOverride { item, rule: got }) => {
                assert_eq!(item, format!("{path}=1.0"));
                assert!(got.contains(rule), "{path}: {got}");
            }
            other => panic!("{path}: expected BadOverride, got {other:?}"),
        }
    }
    assert!(!doc.is_modified());
    let error = doc.apply_override("display.exposure").expect_err("no value");
    assert!(error.to_string().contains("expected key.path=value"), "{error}");
}

#[test]
fn get_reads_dotted_paths_with_indices() {
    let doc = preset("binary-sunset");
    assert_eq!(doc.get("suns.1.temperature"), Some(&Value::Float(3600.0)));
    assert_eq!(doc.get("suns.0.name"), Some(&Value::String("primary".to_owned())));
    assert_eq!(
        doc.get("sky.gradient.keyframes.0.time"),
        Some(&Value::String("03:00".to_owned()))
    );
    assert_eq!(doc.get("render.width"), Some(&Value::Integer(1280)));
    assert_eq!(doc.get("preset"), Some(&Value::String("binary-sunset".to_owned())));
    assert!(doc.get("suns").and_then(Value::as_array).is_some_and(|s| s.len() == 2));
    for missing in [
        "suns.2",
        "suns.x",
        "suns.0.nothing",
        "render.width.x",
        "",
        "render.",
        "nothing",
    ] {
        assert_eq!(doc.get(missing), None, "{missing}");
    }
}

#[test]
fn saving_into_a_missing_folder_writes_nothing() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("missing").join("scene.toml");
    match preset("default").save(&path) {
        Err(SceneError::Write { path: named, reason }) => {
            assert_eq!(named, path.display().to_string());
            assert!(
                reason.contains("missing") && reason.contains("not an existing folder"),
                "{reason}"
            );
        }
        other => panic!("expected SceneError::Write, got {other:?}"),
    }
    assert!(!path.exists());
    assert!(!dir.path().join("missing").exists());
    let message = preset("default").save(&path).expect_err("missing").to_string();
    assert!(message.contains(&path.display().to_string()), "{message}");
}

#[test]
fn saving_over_a_file_replaces_it_whole_and_leaves_no_temporary_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, "x".repeat(100_000)).expect("old file");
    let doc = preset("noon");
    doc.save(&path).expect("saves");
    assert_eq!(std::fs::read_to_string(&path).expect("saved"), doc.to_toml_string());
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .expect("lists")
        .map(|e| e.expect("entry").file_name())
        .collect();
    assert_eq!(names, ["scene.toml"]);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        let fresh = dir.path().join("fresh.toml");
        doc.save(&fresh).expect("saves");
        let mode = std::fs::metadata(&fresh).expect("saved").permissions().mode();
        assert_eq!(mode & 0o777, 0o644);
    }
}

/// A scene with a mesh, a texture and a flare image next to it, in `folder`.
fn write_assets(folder: &Path) {
    std::fs::write(
        folder.join("tri.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
    )
    .expect("write obj");
    let image = image::RgbaImage::from_raw(2, 1, vec![255, 0, 0, 255, 0, 0, 255, 255]).expect("image");
    image.save(folder.join("tex.png")).expect("write png");
    image.save(folder.join("glow.png")).expect("write png");
}

const ASSET_SCENE: &str = r#"
[[objects]]
mesh = { kind = "file", path = "tri.obj" }
texture = { file = "./tex.png", filter = "nearest" }

[[objects]]
mesh = { kind = "cube", size = 1.0 }

[flare]
enabled = true
elements = [
  { kind = "image", file = "glow.png", size = 0.3 },
  { kind = "glow", size = 0.1 },
]
"#;

/// Where each asset key of `scene` resolves: (mesh, texture, flare image).
fn resolved(scene: &Scene) -> (PathBuf, PathBuf, PathBuf) {
    let mesh = match &scene.objects[0].mesh {
        firmament_scene::MeshEntry::File { path } => scene.base_dir.join(path),
        other => panic!("expected a file mesh, got {other:?}"),
    };
    let texture = scene.objects[0]
        .texture
        .as_ref()
        .and_then(|t| t.file.as_ref())
        .expect("texture file");
    let elements = scene.flare.elements.as_ref().expect("elements");
    let image = elements[0].file.as_ref().expect("image file");
    let absolute = |p: PathBuf| std::path::absolute(p).expect("absolute");
    (
        absolute(mesh),
        absolute(scene.base_dir.join(texture)),
        absolute(scene.base_dir.join(image)),
    )
}

#[test]
fn relative_asset_paths_still_name_the_same_files_when_saved_elsewhere() {
    let base = tempfile::tempdir().expect("temp dir");
    let elsewhere = tempfile::tempdir().expect("temp dir");
    write_assets(base.path());
    let origin = base.path().join("scene.toml");
    std::fs::write(&origin, ASSET_SCENE).expect("scene");
    let doc = SceneDocument::load_file(&origin, None, &[]).expect("loads");
    assert_eq!(doc.origin(), &SceneOrigin::File(origin.clone()));
    assert_eq!(doc.base_dir(), base.path());
    let original = doc.scene().expect("valid");
    let files = resolved(&original);
    assert_eq!(files.0, base.path().join("tri.obj"));

    // Saved elsewhere: absolute paths to the same files; the scene draws the same.
    let moved = elsewhere.path().join("moved.toml");
    doc.save(&moved).expect("saves");
    let text = std::fs::read_to_string(&moved).expect("saved");
    let abs = |name: &str| base.path().join(name).display().to_string();
    for name in ["tri.obj", "tex.png", "glow.png"] {
        assert!(text.contains(&abs(name)), "{name} should be absolute in:\n{text}");
    }
    let scene = load_file(&moved, None, &[]).expect("valid");
    assert_eq!(scene.base_dir, elsewhere.path());
    assert_eq!(resolved(&scene), files);
    let frame = scene.frame_at(None).expect("assets load from the saved file");
    assert_eq!(frame.objects.objects[0].mesh.triangle_count(), 1);
    let texture = frame.objects.objects[0].texture.as_ref().expect("textured");
    assert_eq!(texture.image.texel(1, 0), Some([0, 0, 255, 255]));
    assert_eq!(
        normalised(scene).objects[1],
        normalised(original.clone()).objects[1],
        "other objects are untouched"
    );
    // The document itself is unchanged by saving.
    assert!(!doc.is_modified());
    assert_eq!(
        doc.get("objects.0.mesh.path"),
        Some(&Value::String("tri.obj".to_owned()))
    );

    // Saved next to the scene: paths stay relative.
    let beside = base.path().join("copy.toml");
    doc.save(&beside).expect("saves");
    let text = std::fs::read_to_string(&beside).expect("saved");
    assert!(text.contains("\"tri.obj\"") && text.contains("\"./tex.png\"") && text.contains("\"glow.png\""));
    assert!(!text.contains(&base.path().display().to_string()), "{text}");
    assert_eq!(text, doc.to_toml_string());
    let scene = load_file(&beside, None, &[]).expect("valid");
    assert_eq!(resolved(&scene), files);
    assert_eq!(normalised(scene), normalised(original));
}

#[test]
fn absolute_asset_paths_are_kept() {
    let base = tempfile::tempdir().expect("temp dir");
    let elsewhere = tempfile::tempdir().expect("temp dir");
    write_assets(base.path());
    let text = ASSET_SCENE.replace(
        "\"tri.obj\"",
        &format!("{:?}", base.path().join("tri.obj").display().to_string()),
    );
    let origin = base.path().join("scene.toml");
    let doc = SceneDocument::load(
        SceneSource::Text {
            text: &text,
            origin: &origin.display().to_string(),
        },
        None,
        &[],
    )
    .expect("loads");
    let moved = elsewhere.path().join("moved.toml");
    doc.save(&moved).expect("saves");
    let scene = load_file(&moved, None, &[]).expect("valid");
    assert_eq!(resolved(&scene), resolved(&doc.scene().expect("valid")));
}

#[test]
fn known_keys_are_the_formats_own_and_missing_ones_can_be_added_with_their_values() {
    let mut doc = preset("earth-sunset");
    let atmosphere = doc.known_keys("atmosphere").expect("atmosphere keys");
    for key in ["rayleigh_scattering", "mie_g", "ozone_absorption", "wavelengths"] {
        assert!(atmosphere.contains(&key.to_owned()), "{key} in {atmosphere:?}");
    }
    let planet_missing = doc.missing_keys("planet");
    for key in ["equatorial_radius", "polar_radius", "atmosphere_height"] {
        assert!(planet_missing.contains(&key.to_owned()), "{key} in {planet_missing:?}");
    }
    assert!(!planet_missing.contains(&"latitude".to_owned()), "{planet_missing:?}");
    assert!(
        doc.known_keys("")
            .expect("top-level keys")
            .contains(&"flare".to_owned())
    );
    assert!(
        doc.known_keys("suns.0")
            .expect("a sun's keys")
            .contains(&"temperature".to_owned())
    );
    assert_eq!(doc.known_keys("camera.fov_y"), None, "a number has no keys");

    // Added keys take the values the scene had without them: the scene is unchanged.
    let before = doc.scene().expect("scene");
    for key in [
        "planet.equatorial_radius",
        "planet.atmosphere_height",
        "atmosphere.rayleigh_scattering",
        "atmosphere.mie_g",
    ] {
        let value = doc.add_key(key).unwrap_or_else(|e| panic!("{key}: {e}"));
        assert_eq!(doc.get(key), Some(&value));
    }
    assert_eq!(
        doc.get("planet.equatorial_radius").and_then(Value::as_float),
        Some(6_378_137.0),
        "WGS84's equatorial radius"
    );
    let after = doc.scene().expect("scene with the keys added");
    assert_eq!(
        after.atmosphere_sky().expect("sky"),
        before.atmosphere_sky().expect("sky"),
        "adding a key with its effective value changed the sky"
    );
    assert!(!doc.missing_keys("planet").contains(&"equatorial_radius".to_owned()));

    // Keys without such a value get one of their type (a key with a fixed set of names its
    // first name): the scene still parses, whatever rule validation then applies.
    let mut doc = preset("default");
    doc.table_mut().remove("fog");
    let fog = doc.missing_keys("fog");
    assert!(fog.contains(&"mode".to_owned()), "{fog:?}");
    for key in &fog {
        doc.add_key(&format!("fog.{key}"))
            .unwrap_or_else(|e| panic!("fog.{key}: {e}"));
    }
    assert!(doc.get("fog.mode").is_some_and(Value::is_str));
    match doc.scene() {
        Ok(_) | Err(SceneError::Invalid { .. }) => {}
        Err(other) => panic!("the added fog keys do not parse: {other}"),
    }
}

#[test]
fn empty_lists_grow_by_an_entry_that_parses() {
    for (preset_name, list) in [("default", "objects"), ("default", "lights"), ("earth-sunset", "suns")] {
        let mut doc = preset(preset_name);
        doc.set(list, Value::Array(Vec::new())).expect("empty the list");
        doc.add_entry(list).unwrap_or_else(|e| panic!("{list}: {e}"));
        assert!(
            doc.get(&format!("{list}.0")).is_some_and(Value::is_table),
            "{list}: no entry"
        );
        doc.scene()
            .unwrap_or_else(|e| panic!("{preset_name} with one new {list} entry: {e}"));
        doc.add_entry(list).expect("a second entry");
        assert_eq!(doc.get(list).and_then(Value::as_array).map(Vec::len), Some(2));
    }
    let mut doc = preset("nehe-flare");
    doc.set("flare.elements", Value::Array(Vec::new()))
        .expect("no elements");
    doc.add_entry("flare.elements").expect("an element");
    doc.scene().expect("a flare with one new element");
    assert!(doc.add_entry("camera").is_err(), "the camera is no list");
}

#[test]
fn key_paths_join_under_the_top_level() {
    assert_eq!(SceneDocument::key_path("", "flare"), "flare");
    assert_eq!(SceneDocument::key_path("suns.0", "temperature"), "suns.0.temperature");
}
