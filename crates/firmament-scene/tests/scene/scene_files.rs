//! Scene files end to end: layering, overrides, strict parsing and every validation rule.

use firmament_scene::{SceneError, SceneSource, load};

use crate::support::from_text;

fn with_sets(sets: &[&str]) -> Result<firmament_scene::Scene, SceneError> {
    let sets: Vec<String> = sets.iter().map(|s| (*s).to_owned()).collect();
    load(SceneSource::Preset("default"), None, &sets)
}

fn message(result: Result<firmament_scene::Scene, SceneError>) -> String {
    result.expect_err("should fail").to_string()
}

#[test]
fn an_empty_file_is_the_default_scene() {
    let empty = from_text("").expect("valid");
    let default = load(SceneSource::Preset("default"), None, &[]).expect("valid");
    assert_eq!(empty, default);
    assert_eq!(default.render.width, 1280);
    assert_eq!(default.sky.gradient.keyframes.len(), 8);
}

#[test]
fn files_layer_over_their_preset_and_sets_layer_over_files() {
    let scene = from_text("preset = \"noon\"\n[camera]\npitch = 3.0\n").expect("valid");
    assert_eq!(scene.time.time_of_day, "12:30"); // from noon
    assert_eq!(scene.camera.pitch_deg, 3.0); // from the file
    assert_eq!(scene.camera.fov_y_deg, 75.0); // from noon
    assert_eq!(scene.sun.latitude_deg, 45.0); // from default
    let scene = load(
        SceneSource::Text {
            text: "[camera]\npitch = 3.0\n",
            origin: "t",
        },
        Some("dusk"),
        &[
            "camera.pitch=7.5".to_owned(),
            "display.tone_curve=aces_fitted".to_owned(),
        ],
    )
    .expect("valid");
    assert_eq!(scene.preset.as_deref(), Some("dusk"));
    assert_eq!(scene.camera.pitch_deg, 7.5);
    assert_eq!(scene.display.tone_curve, firmament_core::display::ToneCurve::AcesFitted);
}

#[test]
fn sets_reach_into_arrays_and_parse_toml_values() {
    let scene = with_sets(&[
        "sky.gradient.keyframes.0.zenith=#ff0000",
        "camera.position=[1.0, 2.0, 3.0]",
        "time.time_of_day=\"06:30\"",
        "camera.far=1e6",
    ])
    .expect("valid");
    assert_eq!(scene.sky.gradient.keyframes[0].zenith.0.r, 1.0);
    assert_eq!(scene.camera.position, [1.0, 2.0, 3.0]);
    assert_eq!(scene.time.time_of_day, "06:30");
    assert_eq!(scene.camera.far, Some(1e6));
    assert!(message(with_sets(&["sky.gradient.keyframes.99.zenith=#ff0000"])).contains("past the end"));
    assert!(message(with_sets(&["camera.fov_y.deep=1"])).contains("camera.fov_y"));
    assert!(message(with_sets(&["no_equals_sign"])).contains("expected key.path=value"));
    assert!(message(with_sets(&["camera..fov_y=1"])).contains("empty part"));
}

#[test]
fn unknown_keys_suggest_the_closest() {
    let msg = message(from_text("[camera]\nfovy = 40.0\n"));
    assert_eq!(msg, "camera.fovy: unknown key (did you mean `fov_y`?)");
    let msg = message(from_text("[sky.gradient]\nzenit_start = 40.0\n"));
    assert!(
        msg.contains("sky.gradient.zenit_start") && msg.contains("`zenith_start`"),
        "{msg}"
    );
    let msg = message(from_text("[camra]\nfov_y = 40.0\n"));
    assert!(
        msg.starts_with("camra: unknown key") && msg.contains("`camera`"),
        "{msg}"
    );
    let msg = message(from_text(
        "[[sky.gradient.keyframes]]\ntime = \"01:00\"\nzenithh = \"#000000\"\n",
    ));
    assert!(
        msg.contains("keyframes[0].zenithh") && msg.contains("`zenith`"),
        "{msg}"
    );
}

#[test]
fn wrong_types_and_syntax_name_the_place() {
    let msg = message(from_text("[camera]\nfov_y = \"wide\"\n"));
    assert!(msg.starts_with("camera.fov_y: "), "{msg}");
    let msg = message(from_text("[render]\nwidth = -5\n"));
    assert!(msg.starts_with("render.width: "), "{msg}");
    let msg = message(from_text("[camera\nfov_y = 1"));
    assert!(
        msg.starts_with("test.toml is not valid TOML") && msg.contains("line 1"),
        "{msg}"
    );
    let msg = message(from_text(
        "[sky.gradient]\nkeyframes = [{ time = \"01:00\", zenith = \"blue\" }]\n",
    ));
    assert!(msg.contains("keyframes[0].zenith") && msg.contains("#rrggbb"), "{msg}");
    let msg = message(from_text("[sky]\nmodel = \"atmosfear\"\n"));
    assert!(
        msg.starts_with("sky.model: ") && msg.contains("gradient") && msg.contains("atmosphere"),
        "{msg}"
    );
    let msg = message(from_text("preset = 3\n"));
    assert!(msg.starts_with("preset: "), "{msg}");
}

#[test]
fn every_rule_names_key_value_and_rule() {
    let cases: &[(&str, &str)] = &[
        ("camera.fov_y=0", "camera.fov_y = 0: must be in (0, 180) degrees"),
        ("camera.fov_y=180", "camera.fov_y = 180: must be in (0, 180) degrees"),
        ("camera.fov_y=nan", "camera.fov_y = NaN: must be in (0, 180) degrees"),
        ("camera.pitch=91", "camera.pitch = 91: must be in [-90, 90] degrees"),
        (
            "camera.heading=inf",
            "camera.heading = inf: must be a finite number of degrees",
        ),
        ("camera.near=0", "camera.near = 0: must be a finite number > 0 metres"),
        (
            "camera.far=0.05",
            "camera.far = 0.05: must be a finite number of metres > camera.near",
        ),
        ("camera.position=[0, 0, -1]", "the camera must be above the ground"),
        ("camera.position=[nan, 0, 1]", "every component must be a finite number"),
        ("render.width=0", "render.width = 0: must be 1 to 16384 pixels"),
        (
            "render.height=100000",
            "render.height = 100000: must be 1 to 16384 pixels",
        ),
        (
            "time.time_of_day=\"25:00\"",
            "time.time_of_day = \"25:00\": hours must be 0 to 24",
        ),
        ("sun.latitude=-91", "sun.latitude = -91: must be in [-90, 90] degrees"),
        (
            "sun.angular_radius=0",
            "sun.angular_radius = 0: must be in (0, 10] degrees",
        ),
        (
            "sun.disc_intensity=-1",
            "sun.disc_intensity = -1: must be a finite number >= 0",
        ),
        ("sun.edge_softness=2", "sun.edge_softness = 2: must be in (0, 1]"),
        (
            "display.exposure=0",
            "display.exposure = 0: must be a finite number > 0",
        ),
        ("display.ev100=100", "display.ev100 = 100: must be in [-20, 40]"),
        (
            "sky.gradient.horizon_half_width=0",
            "sky.gradient.horizon_half_width = 0: must be in (0, 90) degrees",
        ),
        (
            "sky.gradient.zenith_start=2",
            "sky.gradient.zenith_start = 2: must be above the horizon band",
        ),
        (
            "sky.gradient.ground_start=-1",
            "sky.gradient.ground_start = -1: must be below the horizon band",
        ),
        (
            "sky.gradient.upper_exponent=-2",
            "sky.gradient.upper_exponent = -2: must be a finite number > 0",
        ),
        (
            "sky.gradient.keyframes=[]",
            "sky.gradient.keyframes = []: needs at least one keyframe",
        ),
        (
            "sky.gradient.keyframes.1.time=\"03:00\"",
            "sky.gradient.keyframes[1].time = \"03:00\": keyframe 0 has the same time",
        ),
        (
            "sky.gradient.keyframes.1.time=\"3 pm\"",
            "sky.gradient.keyframes[1].time = \"3 pm\": expected HH:MM",
        ),
    ];
    for (set, expected) in cases {
        let msg = message(with_sets(&[set]));
        assert!(
            msg.contains(expected),
            "--set {set}\n  got:      {msg}\n  expected: {expected}"
        );
    }
}

#[test]
fn unknown_presets_and_missing_files_are_reported() {
    let msg = message(load(SceneSource::Preset("dwan"), None, &[]));
    assert!(msg.contains("unknown preset `dwan`; did you mean `dawn`?"), "{msg}");
    let msg = message(from_text("preset = \"nope\"\n"));
    assert!(msg.contains("unknown preset `nope`"), "{msg}");
    let err = firmament_scene::load_file(std::path::Path::new("/no/such/scene.toml"), None, &[]).expect_err("missing");
    assert!(
        err.to_string()
            .starts_with("cannot read scene file /no/such/scene.toml"),
        "{err}"
    );
}

#[test]
fn scene_converts_to_the_core_frame() {
    let scene = with_sets(&["camera.heading=90", "camera.pitch=0", "time.time_of_day=\"12:00\""]).expect("valid");
    let frame = scene.frame_at(None).expect("frame");
    // Heading 90° looks east.
    assert!((frame.camera.forward() - glam::DVec3::X).length() < 1e-12);
    assert!((frame.camera.aspect - 1280.0 / 720.0).abs() < 1e-12);
    // At 12:00 the colours are exactly the "day" keyframe's.
    let firmament_core::frame::Sky::Gradient(sky) = frame.sky else {
        panic!("the default scene has a gradient sky")
    };
    let day = scene
        .sky
        .gradient
        .keyframes
        .iter()
        .find(|k| k.time == "12:00")
        .expect("day keyframe");
    assert_eq!(sky.bands.zenith, day.zenith.0);
    // Noon at 45° N, equinox: the sun stands 45° up in the south.
    assert!((sky.sun.direction.z.asin().to_degrees() - 45.0).abs() < 1e-9);
}
