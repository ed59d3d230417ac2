//! Scenes in code: a `SceneBuilder` scene equals the scene file saying the same things (one model,
//! one set of rules), and a bad value gives the file's own message.

use firmament_scene::{
    Body, FlarePresetName, FogCoordinateName, GlColor, LightEntry, LightingModelName, MaterialEntry, MeshEntry,
    MiePhaseName, ObjectEntry, Scene, SceneBuilder, SceneError, SceneSource, ShadingName, SunEntry,
};

fn parse(text: &str) -> Result<Scene, SceneError> {
    firmament_scene::load(
        SceneSource::Text {
            text,
            origin: "test.toml",
        },
        None,
        &[],
    )
}

#[test]
fn a_built_scene_equals_the_same_scene_file() {
    let built = Scene::builder()
        .image_size_px(640, 360)
        .camera_position_m([1.0, 2.0, 300.0])
        .camera_direction_deg(10.0, 5.0)
        .camera_roll_deg(2.0)
        .fov_y_deg(50.0)
        .clip_planes_m(0.5, Some(90_000.0))
        .time_of_day("16:30")
        .exposure_ev100(13.5)
        .tone_curve(firmament_core::display::ToneCurve::AcesFitted)
        .atmosphere(Body::Earth)
        .planet_location_deg(45.0, 7.5)
        .planet_sphere_m(6_360_000.0)
        .atmosphere_height_m(60_000.0)
        .rayleigh_per_m([5.8e-6, 13.5e-6, 33.1e-6], 8000.0)
        .mie_per_m([3.996e-6; 3], [4.44e-6; 3], 1200.0, 0.8)
        .mie_phase(MiePhaseName::CornetteShanks)
        .ozone_per_m([0.65e-6, 1.881e-6, 0.085e-6], 10_000.0, 25_000.0, 40_000.0)
        .ground_albedo([0.1; 3])
        .sun(SunEntry::at_deg(225.0, 20.0).named("Sun").temperature_k(5800.0))
        .sun_at_deg(90.0, 10.0)
        .lighting(LightingModelName::Classic, ShadingName::Phong)
        .light(
            LightEntry::at([1.0, 1.0, 1.0, 0.0])
                .in_world()
                .color(GlColor::Rgb([1.0, 0.9, 0.8])),
        )
        .object(
            ObjectEntry::new(MeshEntry::Cube { size: 2.0 })
                .named("cube")
                .translate_m([0.0, 10.0, 1.0])
                .rotate_deg(25.0, [0.0, 0.0, 1.0])
                .scale([1.0, 2.0, 1.0])
                .diffuse(GlColor::Rgb([0.8, 0.5, 0.2])),
        )
        .exp_fog_per_m(0.01, GlColor::Rgb([0.5, 0.5, 0.5]))
        .flare(FlarePresetName::Subtle)
        .build()
        .expect("a valid scene");
    let parsed = parse(
        r#"
[render]
width = 640
height = 360

[camera]
position = [1.0, 2.0, 300.0]
heading = 10.0
pitch = 5.0
roll = 2.0
fov_y = 50.0
near = 0.5
far = 90000.0

[time]
time_of_day = "16:30"

[display]
ev100 = 13.5
tone_curve = "aces_fitted"

[sky]
model = "atmosphere"

[planet]
body = "earth"
latitude = 45.0
longitude = 7.5
radius = 6360000.0
atmosphere_height = 60000.0

[atmosphere]
rayleigh_scattering = [5.8e-6, 13.5e-6, 33.1e-6]
rayleigh_scale_height = 8000.0
mie_scattering = [3.996e-6, 3.996e-6, 3.996e-6]
mie_extinction = [4.44e-6, 4.44e-6, 4.44e-6]
mie_scale_height = 1200.0
mie_g = 0.8
mie_phase = "cornette_shanks"
ozone_absorption = [0.65e-6, 1.881e-6, 0.085e-6]
ozone_bottom = 10000.0
ozone_peak = 25000.0
ozone_top = 40000.0
ground_albedo = [0.1, 0.1, 0.1]

[[suns]]
name = "Sun"
azimuth = 225.0
elevation = 20.0
temperature = 5800.0

[[suns]]
azimuth = 90.0
elevation = 10.0

[lighting]
model = "classic"
shading = "phong"

[[lights]]
space = "world"
position = [1.0, 1.0, 1.0, 0.0]
diffuse = [1.0, 0.9, 0.8]
specular = [1.0, 0.9, 0.8]

[[objects]]
name = "cube"
mesh = { kind = "cube", size = 2.0 }
transform = [{ translate = [0.0, 10.0, 1.0] }, { rotate = [25.0, 0.0, 0.0, 1.0] }, { scale = [1.0, 2.0, 1.0] }]
material = { diffuse = [0.8, 0.5, 0.2] }

[fog]
mode = "exp"
density = 0.01
color = [0.5, 0.5, 0.5]

[flare]
enabled = true
preset = "subtle"
"#,
    )
    .expect("the same scene as a file");
    assert_eq!(built, parsed);
    // And it draws: the frame both give.
    assert_eq!(
        built.frame_at(None).expect("a frame"),
        parsed.frame_at(None).expect("a frame")
    );
}

/// The setters for the rest of the format, and `edit` for any field, against the same file.
#[test]
fn the_remaining_setters_and_edit_equal_the_same_scene_file() {
    let built = Scene::builder()
        .refraction_air(950.0, -5.0)
        .delta_t_s(Some(69.0))
        .star_limit_mag(5.0)
        .gradient_sun_path_deg(60.0, 23.0)
        .fog_coordinate(FogCoordinateName::EyeDistance)
        .linear_fog_m(10.0, 500.0, GlColor::Rgba([0.6, 0.6, 0.7, 1.0]))
        .flare(FlarePresetName::Classic)
        .flare_look(0.5, 32)
        .sun(
            SunEntry::at_position_m([0.0, 1.0e11, 1.0e11])
                .limb_darkening(0.5)
                .angular_radius_deg(0.3),
        )
        .light(
            LightEntry::at([0.0, 0.0, 5.0, 1.0])
                .spot_deg([0.0, 0.0, -1.0], 30.0, 4.0)
                .attenuation([1.0, 0.1, 0.01])
                .with_flare(),
        )
        .object(
            ObjectEntry::new(MeshEntry::GltSphere {
                radius: 1.0,
                slices: 12,
                stacks: 6,
            })
            .back_material(MaterialEntry {
                diffuse: Some(GlColor::Rgb([0.8, 0.2, 0.2])),
                ..Default::default()
            })
            .spin_deg_per_s([0.0, 0.0, 1.0], 10.0),
        )
        .edit(|scene| scene.camera.heading_deg = 123.0)
        .build()
        .expect("a valid scene");
    let parsed = parse(
        r#"
[camera]
heading = 123.0

[time]
pressure = 950.0
temperature = -5.0
delta_t = 69.0
star_limit = 5.0

[sun]
latitude = 60.0
declination = 23.0

[fog]
mode = "linear"
start = 10.0
end = 500.0
color = [0.6, 0.6, 0.7, 1.0]
coordinate = "eye_distance"

[flare]
enabled = true
preset = "classic"
intensity = 0.5
samples = 32

[[suns]]
position = [0.0, 1.0e11, 1.0e11]
limb_darkening = 0.5
angular_radius = 0.3

[[lights]]
position = [0.0, 0.0, 5.0, 1.0]
spot_direction = [0.0, 0.0, -1.0]
spot_cutoff = 30.0
spot_exponent = 4.0
attenuation = [1.0, 0.1, 0.01]
flare = true

[[objects]]
mesh = { kind = "glt_sphere", radius = 1.0, slices = 12, stacks = 6 }
back_material = { diffuse = [0.8, 0.2, 0.2] }
spin = { axis = [0.0, 0.0, 1.0], degrees_per_second = 10.0 }
"#,
    )
    .expect("the same scene as a file");
    assert_eq!(built, parsed);
}

#[test]
fn an_empty_builder_is_the_default_scene_file() {
    assert_eq!(SceneBuilder::new().build(), parse(""));
    assert_eq!(
        SceneBuilder::from_preset("earth-noon").and_then(SceneBuilder::build),
        parse("preset = \"earth-noon\"")
    );
    let error = SceneBuilder::from_preset("earth-nooon").expect_err("no such preset");
    assert!(error.to_string().contains("did you mean `earth-noon`"), "{error}");
}

#[test]
fn the_camera_keys_build_as_the_file_says_them() {
    use firmament_core::auto_exposure::{AutoExposure, ExposureMode};
    // The file's defaults are the core's.
    let auto = AutoExposure::default();
    let built = Scene::builder()
        .auto_exposure(auto)
        .bloom(0.2)
        .night_vision(true)
        .build();
    assert_eq!(
        built,
        parse("[display]\nexposure_mode = \"auto\"\nbloom = 0.2\nnight_vision = true")
    );
    let display = built.expect("a scene").display_settings();
    assert_eq!(display.exposure_mode, ExposureMode::Auto(auto));
    assert_eq!((display.bloom, display.night_vision), (0.2, true));
    assert_eq!(
        parse("").expect("the default").display_settings().exposure_mode,
        ExposureMode::Manual
    );
}

#[test]
fn bad_builder_values_give_the_scene_files_messages() {
    let cases: [(SceneBuilder, &str); 6] = [
        (Scene::builder().fov_y_deg(0.0), "[camera]\nfov_y = 0.0"),
        (
            Scene::builder().image_size_px(0, 10),
            "[render]\nwidth = 0\nheight = 10",
        ),
        (
            Scene::builder().clip_planes_m(10.0, Some(5.0)),
            "[camera]\nnear = 10.0\nfar = 5.0",
        ),
        (
            Scene::builder().atmosphere(Body::Earth).sun_at_deg(0.0, 95.0),
            "[sky]\nmodel = \"atmosphere\"\n[[suns]]\nazimuth = 0.0\nelevation = 95.0",
        ),
        (
            Scene::builder().mie_per_m([1e-5; 3], [1e-6; 3], 1200.0, 0.8),
            "[atmosphere]\nmie_scattering = 1e-5\nmie_extinction = 1e-6\nmie_scale_height = 1200.0\nmie_g = 0.8",
        ),
        (Scene::builder().time_of_day("25:00"), "[time]\ntime_of_day = \"25:00\""),
    ];
    for (builder, text) in cases {
        let built = builder.build().expect_err("an invalid scene").to_string();
        let parsed = parse(text).expect_err("an invalid file").to_string();
        println!("{built}");
        assert_eq!(built, parsed, "for the file\n{text}");
    }
}
