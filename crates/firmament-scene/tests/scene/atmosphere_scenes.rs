//! Atmosphere scenes: `[planet]`, `[atmosphere]` and `[[suns]]` from presets and overrides to the
//! core's `AtmosphereSky`, and every rule they break naming the key.

use crate::support::{message, preset, sky_of};
use firmament_core::atmosphere::star::blackbody_spectrum;
use firmament_core::atmosphere::{Phase, Wavelengths, presets};
use firmament_scene::{Body, SceneSource, load};
use glam::DVec3;

const ATMOSPHERE_PRESETS: [&str; 10] = [
    "earth-noon",
    "earth-sunset",
    "earth-orbit",
    "mars-noon",
    "binary-sunset",
    "saturn-orbit",
    "venus-surface",
    "venus-orbit",
    "titan-surface",
    "titan-orbit",
];

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300)
}

#[test]
fn every_atmosphere_preset_parses_validates_and_converts() {
    for name in ATMOSPHERE_PRESETS {
        let scene = preset(name, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
        let sky = sky_of(&scene);
        sky.validate().expect("valid for the core");
        assert!(!sky.suns.is_empty(), "{name} has no sun");
        // The camera is above the posed planet's surface, and the world origin is on it.
        let planet = sky.atmosphere.planet;
        let camera = planet.to_planet_frame(DVec3::from_array(scene.camera.position));
        assert!(planet.altitude(camera) > 0.0, "{name}");
        assert!(
            planet.altitude(planet.to_planet_frame(DVec3::ZERO)).abs() < 1e-6,
            "{name}"
        );
        // The body's preset medium comes through unchanged, but for the ground's albedo under a
        // surface: the surface's mean.
        let mut medium = scene.planet.body.atmosphere().medium;
        if let Some(surface) = &sky.surface {
            medium.ground_albedo = surface.mean_albedo();
        }
        assert_eq!(sky.atmosphere.medium, medium, "{name}");
    }
    let binary = sky_of(&preset("binary-sunset", &[]).expect("valid"));
    assert_eq!(binary.suns.len(), 2);
    let saturn = preset("saturn-orbit", &[]).expect("valid");
    assert_eq!(saturn.planet.body, Body::Saturn);
    assert!((sky_of(&saturn).atmosphere.planet.flattening() - 0.098).abs() < 1e-3);
}

#[test]
fn the_earth_presets_put_the_sun_where_they_say() {
    let noon = sky_of(&preset("earth-noon", &[]).expect("valid"));
    let sun = noon.suns[0];
    // Azimuth 180 (south), elevation 45: (0, −cos 45°, sin 45°) in East-North-Up.
    let expected = DVec3::new(0.0, -1.0, 1.0).normalize();
    assert!((sun.direction - expected).length() < 1e-12, "{}", sun.direction);
    assert_eq!(sun, presets::earth_sun(sun.direction));
    let sunset = sky_of(&preset("earth-sunset", &[]).expect("valid"));
    assert!((sunset.suns[0].direction.z.asin().to_degrees() - 2.0).abs() < 1e-9);
}

#[test]
fn a_radius_gives_brunetons_sphere() {
    let scene = preset("earth-noon", &["planet.radius=6360000"]).expect("valid");
    let planet = sky_of(&scene).atmosphere.planet;
    assert_eq!(planet.radii, DVec3::splat(6_360_000.0));
    assert_eq!(planet.flattening(), 0.0);
    assert_eq!(planet.atmosphere_height, 60_000.0);
}

#[test]
fn overrides_reach_the_core_values() {
    let scene = preset(
        "earth-noon",
        &[
            "planet.equatorial_radius=3000000",
            "planet.polar_radius=2500000",
            "planet.atmosphere_height=80000",
            "planet.latitude=-30",
            "planet.longitude=100",
            "atmosphere.rayleigh_scattering=[1e-6, 2e-6, 3e-6]",
            "atmosphere.rayleigh_scale_height=7000",
            "atmosphere.mie_scattering=2e-6",
            "atmosphere.mie_extinction=[3e-6, 3e-6, 4e-6]",
            "atmosphere.mie_scale_height=900",
            "atmosphere.mie_g=0.7",
            "atmosphere.mie_phase=henyey_greenstein",
            "atmosphere.ozone_absorption=1e-6",
            "atmosphere.ozone_peak=30000",
            "atmosphere.ground_albedo=[0.3, 0.2, 0.1]",
            "atmosphere.wavelengths=[700, 546, 435]",
        ],
    )
    .expect("valid");
    let sky = sky_of(&scene);
    let a = sky.atmosphere;
    assert_eq!(a.planet.radii, DVec3::new(3e6, 3e6, 2.5e6));
    assert_eq!(a.planet.atmosphere_height, 80_000.0);
    // Posed at 30° S: the world's up is the surface normal there, whose planet-frame z is −sin 30°.
    let up = a.planet.direction_to_planet_frame(DVec3::Z);
    assert!((up.z + 0.5).abs() < 1e-12, "{up}");
    let m = a.medium.constituents().expect("the shorthand's three terms");
    assert_eq!(m.rayleigh.scattering.to_array(), [1e-6, 2e-6, 3e-6]);
    assert!(close(m.rayleigh.density.density(7_000.0), (-1.0_f64).exp()));
    assert_eq!(m.mie.scattering.to_array(), [2e-6; 3]);
    assert_eq!(m.mie.extinction.to_array(), [3e-6, 3e-6, 4e-6]);
    assert!(close(m.mie.density.density(900.0), (-1.0_f64).exp()));
    assert_eq!(m.mie.phase, Phase::HenyeyGreenstein { g: 0.7 });
    assert_eq!(m.absorber.absorption.to_array(), [1e-6; 3]);
    // Earth's tent with the peak moved: 0 at 10 km, 1 at 30 km, 0 at 40 km.
    assert!(m.absorber.density.density(10_000.0).abs() < 1e-12);
    assert!((m.absorber.density.density(30_000.0) - 1.0).abs() < 1e-12);
    assert!((m.absorber.density.density(20_000.0) - 0.5).abs() < 1e-12);
    assert!(m.absorber.density.density(40_000.0).abs() < 1e-12);
    assert_eq!(a.medium.ground_albedo.to_array(), [0.3, 0.2, 0.1]);
    assert_eq!(a.wavelengths, Wavelengths([700.0, 546.0, 435.0]));
    // Untouched: the phase of the Mie keeps Earth's kind unless told; here it was told.
    let untouched = sky_of(&preset("earth-noon", &["atmosphere.mie_g=0.5"]).expect("valid"));
    assert_eq!(
        untouched.atmosphere.medium.terms[1].phase,
        Phase::CornetteShanks { g: 0.5 }
    );
}

#[test]
fn sun_overrides_reach_the_core_values() {
    let scene = preset(
        "earth-noon",
        &[
            "suns.0.temperature=3000",
            "suns.0.irradiance=0.5",
            "suns.0.angular_radius=2",
            "suns.0.limb_darkening=0.25",
            "suns.1.azimuth=90",
            "suns.1.elevation=0",
            "suns.1.color=\"#ff8000\"",
            "suns.2.position=[0, 0, 1.5e13]",
        ],
    )
    .expect("valid");
    let sky = sky_of(&scene);
    assert_eq!(sky.suns.len(), 3);
    let [hot, coloured, placed] = [sky.suns[0], sky.suns[1], sky.suns[2]];
    let bb = blackbody_spectrum(3000.0, Wavelengths::default());
    assert!(close(hot.irradiance.y, 0.5));
    assert!(close(hot.irradiance.x / hot.irradiance.y, bb.x / bb.y));
    assert!(close(hot.irradiance.z / hot.irradiance.y, bb.z / bb.y));
    assert!(close(hot.angular_radius, 2.0_f64.to_radians()));
    assert_eq!(hot.limb_darkening, 0.25);
    // "#ff8000": red 1, green sRGB 128 → linear 0.2159, blue 0; scaled to Earth's 1.8504 at 550 nm.
    assert!((coloured.direction - DVec3::X).length() < 1e-12);
    let green = firmament_core::color::srgb_to_linear(128.0 / 255.0);
    assert!(close(coloured.irradiance.y, 1.8504));
    assert!(close(coloured.irradiance.x, 1.8504 / green));
    assert_eq!(coloured.irradiance.z, 0.0);
    // 100 AU straight up: the direction from the planet's centre, nearly +Z.
    let centre = sky.atmosphere.planet.center;
    let expected = (DVec3::new(0.0, 0.0, 1.5e13) - centre).normalize();
    assert!((placed.direction - expected).length() < 1e-12);
    assert!(placed.direction.z > 0.999_999);
}

#[test]
fn scene_files_replace_the_presets_suns_as_a_whole() {
    let text = "preset = \"binary-sunset\"\n[[suns]]\nazimuth = 10.0\nelevation = 20.0\n";
    let scene = load(SceneSource::Text { text, origin: "t.toml" }, None, &[]).expect("valid");
    assert_eq!(scene.suns.len(), 1);
    assert_eq!(scene.suns[0].azimuth_deg, Some(10.0));
    assert_eq!(scene.suns[0].temperature, None);
    let scene = preset("earth-sunset", &["suns=[]"]).expect("no suns is valid");
    assert!(sky_of(&scene).suns.is_empty());
}

#[test]
fn atmosphere_scenes_measure_the_camera_against_the_curved_ground() {
    // 100 km east the Earth's surface has fallen ~784 m below the tangent plane: `up` = −500 is
    // still in the air.
    let scene = preset("earth-noon", &["camera.position=[100000, 0, -500]"]).expect("valid");
    assert!(sky_of(&scene).suns.len() == 1);
    // From 100 AU, looking down at the planet.
    preset("earth-noon", &["camera.position=[0, 0, 1.5e13]", "camera.pitch=-90"]).expect("valid");
    // The gradient sky keeps its flat-ground rule.
    let msg = message(preset("default", &["camera.position=[100000, 0, -500]"]));
    assert!(msg.contains("the camera must be above the ground (up >= 0)"), "{msg}");
}

#[test]
fn a_camera_inside_the_planet_says_where_it_and_the_surface_are() {
    let msg = message(preset("earth-noon", &["camera.position=[0, 0, -100]"]));
    assert!(
        msg.starts_with("camera.position = [0, 0, -100]: the camera is inside the planet (earth)"),
        "{msg}"
    );
    assert!(msg.contains("its altitude is -100 m"), "{msg}");
    assert!(msg.contains("the surface is at [0, 0, 0]"), "{msg}");
}

#[test]
fn every_bad_value_names_its_key() {
    let centre = sky_of(&preset("earth-noon", &[]).expect("valid"))
        .atmosphere
        .planet
        .center;
    let at_centre = format!("suns.0.position=[{}, {}, {}]", centre.x, centre.y, centre.z);
    let nine_suns = format!("suns=[{}]", ["{ azimuth = 0, elevation = 10 }"; 9].join(", "));
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["planet.radius=-1"],
            "planet.radius = -1: must be a finite number > 0 metres",
        ),
        (
            vec!["planet.equatorial_radius=0"],
            "planet.equatorial_radius = 0: must be a finite number > 0 metres",
        ),
        (
            vec!["planet.polar_radius=70000000"],
            "planet.polar_radius = 70000000: must be within 10 times planet.equatorial_radius (6378137 m)",
        ),
        (
            vec!["planet.radius=6360000", "planet.polar_radius=6350000"],
            "planet.polar_radius = 6350000: give either planet.radius (a sphere) or",
        ),
        (
            vec!["planet.atmosphere_height=0"],
            "planet.atmosphere_height = 0: must be a finite number > 0 metres",
        ),
        (
            vec!["planet.latitude=nan"],
            "planet.latitude = NaN: must be in [-90, 90] degrees",
        ),
        (
            vec!["atmosphere.rayleigh_scattering=[nan, 1e-6, 1e-6]"],
            "atmosphere.rayleigh_scattering = [NaN, 1e-6, 1e-6]: every value must be a finite number >= 0",
        ),
        (
            vec!["atmosphere.mie_extinction=-1e-6"],
            "atmosphere.mie_extinction = [-1e-6, -1e-6, -1e-6]: every value must be",
        ),
        (
            vec!["atmosphere.mie_scattering=1e-5"],
            concat!(
                "atmosphere.mie_scattering = [1e-5, 1e-5, 1e-5]: must be <= the mie extinction ",
                "([4.44e-6, 4.44e-6, 4.44e-6] m⁻¹, earth's"
            ),
        ),
        (
            vec!["atmosphere.rayleigh_scale_height=0"],
            "atmosphere.rayleigh_scale_height = 0: must be a finite number > 0 metres",
        ),
        (
            vec!["atmosphere.mie_g=1"],
            "atmosphere.mie_g = 1: must lie strictly between -1 and 1",
        ),
        (
            vec!["atmosphere.ozone_top=20000"],
            "atmosphere.ozone_top = 20000: must be above atmosphere.ozone_peak (25000 m)",
        ),
        (
            vec!["atmosphere.ground_albedo=1.5"],
            "atmosphere.ground_albedo = [1.5, 1.5, 1.5]: every value must lie in [0, 1]",
        ),
        (
            vec!["atmosphere.wavelengths=[680, 680, 440]"],
            "atmosphere.wavelengths = [680, 680, 440]: needs three different wavelengths",
        ),
        (vec![nine_suns.as_str()], "suns = 9 suns: at most 8 suns"),
        (
            vec!["suns.0.position=[0, 0, 1e12]"],
            "suns[0].position = [0, 0, 1000000000000]: give either azimuth and elevation or position, not both",
        ),
        (
            vec!["suns=[{ azimuth = 10 }]"],
            "suns[0].elevation: missing: azimuth needs an elevation",
        ),
        (vec!["suns=[{ irradiance = 1 }]"], "suns[0]: missing a direction"),
        (
            vec!["suns.0.elevation=91"],
            "suns[0].elevation = 91: must be in [-90, 90] degrees",
        ),
        (
            vec!["suns=[{ position = [0, 0, 1000] }]"],
            "suns[0].position = [0, 0, 1000]: must lie above the atmosphere",
        ),
        (
            vec!["suns=[{ position = [0, 0, 0] }]", at_centre.as_str()],
            "a sun at zero distance has no direction",
        ),
        (
            vec!["suns.0.angular_radius=0"],
            "suns[0].angular_radius = 0: must be in (0, 90) degrees",
        ),
        (
            vec!["suns.0.temperature=5000", "suns.0.color=\"#ffffff\""],
            "suns[0].color = [1, 1, 1]: give either temperature or color, not both",
        ),
        (
            vec!["suns.0.temperature=10"],
            "suns[0].temperature = 10: must be in [500, 1000000] kelvin",
        ),
        (
            vec!["suns.0.color=[1, 0, 1]"],
            "suns[0].color = [1, 0, 1]: green (the middle wavelength, where irradiance is given) must be > 0",
        ),
        (
            vec!["suns.0.irradiance=nan"],
            "suns[0].irradiance = NaN: must be a finite number >= 0",
        ),
        (
            vec!["suns.0.limb_darkening=2"],
            "suns[0].limb_darkening = 2: must be in [0, 1]",
        ),
        (
            vec!["camera.position=[0, 0, -100]"],
            "camera.position = [0, 0, -100]: the camera is inside the planet",
        ),
    ];
    for (sets, expected) in &cases {
        let msg = message(preset("earth-noon", sets));
        assert!(
            msg.contains(expected),
            "--set {sets:?}\n  got:      {msg}\n  expected: {expected}"
        );
    }
}

#[test]
fn mars_has_no_ozone_tent_to_take_corners_from() {
    let msg = message(preset("mars-noon", &["atmosphere.ozone_peak=20000"]));
    assert!(
        msg.starts_with("atmosphere.ozone_bottom: missing: mars has no ozone layer"),
        "{msg}"
    );
    let scene = preset(
        "mars-noon",
        &[
            "atmosphere.ozone_bottom=1000",
            "atmosphere.ozone_peak=2000",
            "atmosphere.ozone_top=3000",
        ],
    )
    .expect("valid");
    let density = sky_of(&scene).atmosphere.medium.terms[2].density.clone();
    assert!((density.at(2_000.0) - 1.0).abs() < 1e-12);
}

#[test]
fn unknown_atmosphere_keys_and_bodies_are_named() {
    let msg = message(preset("earth-noon", &["atmosphere.rayleigh_scatter=1e-6"]));
    assert!(
        msg.starts_with("atmosphere.rayleigh_scatter: unknown key (did you mean `rayleigh_scattering`?)"),
        "{msg}"
    );
    let msg = message(preset("earth-noon", &["suns.0.azimut=3"]));
    assert!(msg.contains("suns[0].azimut") && msg.contains("`azimuth`"), "{msg}");
    let msg = message(preset("earth-noon", &["planet.body=jupiter"]));
    assert!(
        msg.starts_with("planet.body: ") && msg.contains("saturn") && msg.contains("venus") && msg.contains("titan"),
        "{msg}"
    );
    let msg = message(preset("earth-noon", &["atmosphere.mie_phase=rayleigh"]));
    assert!(
        msg.starts_with("atmosphere.mie_phase: ") && msg.contains("henyey_greenstein"),
        "{msg}"
    );
    let msg = message(preset("earth-noon", &["atmosphere.ground_albedo=\"grey\""]));
    assert!(
        msg.starts_with("atmosphere.ground_albedo: ") && msg.contains("a number or [a, b, c]"),
        "{msg}"
    );
}

#[test]
fn sets_append_a_sun_one_past_the_end() {
    let scene = preset(
        "earth-sunset",
        &["suns.1.azimuth=250", "suns.1.elevation=10", "suns.1.temperature=9000"],
    )
    .expect("valid");
    assert_eq!(sky_of(&scene).suns.len(), 2);
    let msg = message(preset("earth-sunset", &["suns.5.azimuth=250"]));
    assert!(msg.contains("index 5 is past the end of an array of 1"), "{msg}");
}

#[test]
fn saturn_s_rings_come_from_the_preset_and_bad_rings_name_the_key() {
    let rings = sky_of(&preset("saturn-rings", &[]).expect("valid"))
        .rings
        .expect("rings");
    assert_eq!(rings, firmament_core::atmosphere::rings::Rings::saturn());
    assert!(sky_of(&preset("saturn-orbit", &[]).expect("valid")).rings.is_none());
    // Overrides of Saturn's.
    let dusty = sky_of(&preset("saturn-rings", &["rings.g=0.7", "rings.albedo=0.9"]).expect("valid"));
    let dusty = dusty.rings.expect("rings");
    assert_eq!(dusty.phase_g, 0.7);
    assert_eq!(dusty.albedo, DVec3::splat(0.9));
    // Another body needs its bands.
    let earth = message(preset("earth-orbit", &["rings.enabled=true"]));
    assert!(
        earth.contains("rings.bands") && earth.contains("only saturn"),
        "{earth}"
    );
    let own = sky_of(
        &preset(
            "earth-orbit",
            &[
                "rings.enabled=true",
                "rings.bands=[{ inner_radius = 1.0e7, outer_radius = 1.5e7, optical_depth = 0.3 }]",
            ],
        )
        .expect("valid"),
    );
    assert_eq!(own.rings.expect("rings").bands.len(), 1);
    for (set, key) in [
        (
            "rings.bands=[{ inner_radius = 5.0e7, outer_radius = 9.0e7, optical_depth = 0.3 }]",
            "rings.bands[0].inner_radius",
        ),
        (
            "rings.bands=[{ inner_radius = 9.0e7, outer_radius = 8.0e7, optical_depth = 0.3 }]",
            "rings.bands[0].outer_radius",
        ),
        (
            "rings.bands=[{ inner_radius = 8.0e7, outer_radius = 9.0e7, optical_depth = 0.3 }, { inner_radius = 8.5e7, outer_radius = 9.5e7, optical_depth = 0.3 }]",
            "rings.bands[1].inner_radius",
        ),
        (
            "rings.bands=[{ inner_radius = 8.0e7, outer_radius = 9.0e7, optical_depth = -1.0 }]",
            "rings.bands[0].optical_depth",
        ),
        ("rings.bands=[]", "rings.bands"),
        ("rings.albedo=1.5", "rings.albedo"),
        ("rings.g=-1.0", "rings.g"),
    ] {
        let text = message(preset("saturn-rings", &[set]));
        assert!(text.contains(key), "{set}: {text}");
    }
}

#[test]
fn the_venus_and_titan_presets_stand_on_their_bodies() {
    for (name, body, on_the_ground) in [
        ("venus-surface", Body::Venus, true),
        ("venus-orbit", Body::Venus, false),
        ("titan-surface", Body::Titan, true),
        ("titan-orbit", Body::Titan, false),
    ] {
        let scene = preset(name, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(scene.planet.body, body, "{name}");
        let sky = sky_of(&scene);
        let core = body.atmosphere();
        assert_eq!(sky.atmosphere.medium, core.medium, "{name}");
        assert_eq!(sky.atmosphere.planet.radii, core.planet.radii, "{name}");
        assert_eq!(
            sky.atmosphere.planet.atmosphere_height, core.planet.atmosphere_height,
            "{name}"
        );
        let sun = sky.suns[0];
        assert_eq!(sun, body.sun(sun.direction), "{name}");
        let planet = sky.atmosphere.planet;
        let altitude = planet.altitude(planet.to_planet_frame(DVec3::from_array(scene.camera.position)));
        assert_eq!(altitude < 10.0, on_the_ground, "{name}: {altitude} m up");
        // From orbit the whole globe and its air are in view.
        if !on_the_ground {
            let top = planet.radii.x + planet.atmosphere_height;
            let half_width = (top / (planet.radii.x + altitude)).asin().to_degrees();
            assert!(2.0 * half_width < scene.camera.fov_y_deg, "{name}");
        }
    }
}

#[test]
fn venus_and_titan_bodies_give_the_core_presets() {
    for (name, medium, sun) in [
        ("venus", presets::venus().medium, presets::venus_sun as fn(DVec3) -> _),
        ("titan", presets::titan().medium, presets::titan_sun),
    ] {
        let scene = preset("earth-noon", &[&format!("planet.body={name}")]).expect("valid");
        assert_eq!(scene.planet.body.name(), name);
        let sky = sky_of(&scene);
        assert_eq!(sky.atmosphere.medium, medium, "{name}");
        assert_eq!(sky.suns[0], sun(sky.suns[0].direction), "{name}");
        // Their air is free-form terms: the ground albedo may change, the shorthand keys may not.
        let scene = preset(
            "earth-noon",
            &[&format!("planet.body={name}"), "atmosphere.ground_albedo=0.3"],
        )
        .expect("valid");
        let air = sky_of(&scene).atmosphere.medium;
        assert_eq!(air.terms, medium.terms);
        assert_eq!(air.ground_albedo.to_array(), [0.3; 3]);
        let msg = message(preset(
            "earth-noon",
            &[&format!("planet.body={name}"), "atmosphere.mie_g=0.5"],
        ));
        assert!(
            msg.starts_with(&format!("planet.body = {name}: "))
                && msg.contains("atmosphere.mie_g")
                && msg.contains("[[atmosphere.terms]]"),
            "{msg}"
        );
        // No seed values and no rings of their own.
        let msg = message(preset("seed-earth", &[&format!("planet.body={name}")]));
        assert!(msg.contains(&format!("the seed has no values for {name}")), "{msg}");
        let msg = message(preset(
            "earth-noon",
            &[&format!("planet.body={name}"), "rings.enabled=true"],
        ));
        assert!(msg.contains("only saturn"), "{msg}");
    }
}
