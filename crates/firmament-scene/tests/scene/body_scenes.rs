//! `[[bodies]]` (issue 28, several bodies): the Moon's preset, its place at the scene's date,
//! bodies as eclipsers, the night sky's Moon disc giving way to the body, and every bad value
//! naming its key and rule.

use crate::support::{message, preset, sky_of};
use firmament_core::atmosphere::body::{BodySurface, MOON_ALBEDO, MOON_RADIUS_M, Reflectance};
use firmament_core::atmosphere::eclipse::visible_fraction;
use firmament_core::frame::Sky;
use glam::DVec3;

#[test]
fn earth_moon_has_the_moon_as_a_body_and_an_eclipser() {
    let sky = sky_of(&preset("earth-moon", &[]).expect("valid"));
    assert_eq!(sky.bodies.len(), 1);
    let moon = &sky.bodies[0];
    assert_eq!(moon.radii, DVec3::splat(MOON_RADIUS_M));
    assert_eq!(moon.albedo, DVec3::splat(MOON_ALBEDO));
    assert_eq!(moon.reflectance, Reflectance::Lunar);
    assert_eq!(sky.eclipsers, vec![moon.eclipser()]);
    // The near side (the body's x axis) faces the planet; its pole is the planet's.
    let planet = &sky.atmosphere.planet;
    let towards = (planet.center - moon.center).normalize();
    assert!((moon.orientation * DVec3::X).angle_between(towards) < 1e-9);
    assert!((moon.orientation * DVec3::Z).angle_between(planet.orientation * DVec3::Z) < 1e-9);
    // Keys beside the preset replace its values; an ellipsoid takes `radii`.
    let sky = sky_of(
        &preset(
            "earth-moon",
            &[
                "bodies.0.albedo=[0.1, 0.12, 0.14]",
                "bodies.0.reflectance=\"lambert\"",
                "bodies.0.radii=[1.8e6, 1.7e6, 1.6e6]",
            ],
        )
        .expect("valid"),
    );
    assert_eq!(sky.bodies[0].albedo, DVec3::new(0.1, 0.12, 0.14));
    assert_eq!(sky.bodies[0].reflectance, Reflectance::Lambert);
    assert_eq!(sky.bodies[0].radii, DVec3::new(1.8e6, 1.7e6, 1.6e6));
    assert_eq!(sky.bodies[0].surface, BodySurface::LunarMaria);
    // A body of no preset is a plain Lambert ball: no maria.
    let plain = sky_of(
        &preset(
            "earth-moon",
            &["bodies=[{ position = [4.0e8, 0.0, 0.0], radius = 5.0e5 }]"],
        )
        .expect("valid"),
    );
    assert_eq!(plain.bodies[0].surface, BodySurface::Uniform);
    assert_eq!(plain.bodies[0].reflectance, Reflectance::Lambert);
}

/// The Moon asked for as a body at eclipse-2024's date stands where the ephemeris puts it (where
/// the scene's eclipsing Moon stands without bodies, within 1 km), in front of the Sun: Dallas
/// is still in totality, and the night sky draws no second Moon.
#[test]
fn the_moon_at_a_date_stands_where_the_ephemeris_puts_it() {
    let plain = sky_of(&preset("eclipse-2024", &[]).expect("valid"));
    let scene = preset("eclipse-2024", &["bodies=[{ preset = \"moon\" }]"]).expect("valid");
    let frame = scene.frame_at(None).expect("frame");
    let Sky::Atmosphere(sky) = &frame.sky else {
        panic!("expected an atmosphere sky")
    };
    assert_eq!(sky.bodies.len(), 1);
    assert_eq!(sky.eclipsers.len(), 1, "the body is the only eclipsing Moon");
    let moon = sky.bodies[0].center;
    let apart = moon.distance(plain.eclipsers[0].center);
    assert!(apart < 1000.0, "{apart} m from the eclipsing Moon's centre");
    let eye = frame.camera.position;
    let sun = sky.suns[0];
    assert_eq!(visible_fraction(eye, &sun, &sky.eclipsers), 0.0, "totality");
    assert!(
        frame.night.moon.is_none(),
        "the night sky's Moon disc gives way to the body"
    );
}

/// The Moon as a body lights the night as the ephemeris's moonlight does — its light summed over
/// its drawn disc (albedo 0.12, maria, its phase law) against the illuminance of its published V
/// magnitude (Allen via Krisciunas & Schaefer 1991) — within 5 % near full (earth-night) and at a
/// quarter, from the same direction within 0.05°, and it takes the moonlight's place.
#[test]
fn the_moon_as_a_body_lights_the_night_as_the_ephemeris_does() {
    let sky_at = |scene: &firmament_scene::Scene| {
        let frame = scene.frame_at(None).expect("frame");
        let Sky::Atmosphere(sky) = frame.sky else {
            panic!("expected an atmosphere sky")
        };
        sky
    };
    // 2025-03-13 (full on the 14th) and 2025-03-06 (first quarter), the Moon up at 45° N.
    for date in ["2025-03-13T23:30:00Z", "2025-03-06T19:00:00Z"] {
        let time = format!("time.date_time=\"{date}\"");
        let plain = sky_at(&preset("earth-night", &[&time]).expect("valid"));
        let with_body = sky_at(&preset("earth-night", &[&time, "bodies=[{ preset = \"moon\" }]"]).expect("valid"));
        let moonlight = plain.suns.iter().find(|s| !s.disc).expect("the ephemeris's moonlight");
        let body_light = with_body
            .suns
            .iter()
            .find(|s| s.from_body == Some(0))
            .expect("the body's light");
        assert_eq!(
            with_body.suns.iter().filter(|s| !s.disc).count(),
            1,
            "{date}: one moonlight"
        );
        let lux = |sky: &firmament_core::frame::AtmosphereSky, sun: &firmament_core::atmosphere::Sun| {
            sky.atmosphere.spectral_conversion().luminance(sun.irradiance)
        };
        let (want, got) = (lux(&plain, moonlight), lux(&with_body, body_light));
        println!("{date}: ephemeris {want:.4} lx, the body's {got:.4} lx");
        assert!((got / want - 1.0).abs() < 0.05, "{date}: {got} lx vs {want} lx");
        let apart = moonlight.direction.angle_between(body_light.direction).to_degrees();
        assert!(apart < 0.05, "{date}: {apart}° apart");
    }
    // Off by the key, and by day.
    let off = sky_at(&preset("earth-night", &["bodies=[{ preset = \"moon\", light = false }]"]).expect("valid"));
    assert!(off.suns.iter().all(|s| s.from_body.is_none()), "light = false");
    let day = sky_at(
        &preset(
            "earth-night",
            &[
                "time.date_time=\"2025-03-13T12:00:00Z\"",
                "bodies=[{ preset = \"moon\" }]",
            ],
        )
        .expect("valid"),
    );
    assert!(day.suns.iter().all(|s| s.from_body.is_none()), "by day");
}

#[test]
fn bad_bodies_name_the_key_and_the_rule() {
    let far = "position = [4.0e8, 0.0, 0.0]";
    let moon = |extra: &str| format!("{{ preset = \"moon\", {far}{extra} }}");
    let five = vec![0, 1, 2, 3, 4]
        .into_iter()
        .map(|i| format!("{{ preset = \"moon\", position = [4.0e8, {}.0e7, 0.0] }}", i))
        .collect::<Vec<_>>()
        .join(", ");
    for (body_list, key, rule) in [
        (format!("[{five}]"), "bodies", "at most 4"),
        (
            "[{ preset = \"moon\", position = [3.0e6, 0.0, 0.0] }]".to_owned(),
            "bodies[0].position",
            "clear of the planet",
        ),
        (
            format!("[{}, {{ preset = \"moon\", position = [4.01e8, 0.0, 0.0] }}]", moon("")),
            "bodies[1].position",
            "clear of every other body",
        ),
        (format!("[{}]", moon(", radius = -1.0")), "bodies[0].radius", "> 0"),
        (
            format!("[{}]", moon(", radius = 1.0, radii = [1.0, 1.0, 1.0]")),
            "bodies[0].radii",
            "not both",
        ),
        (
            format!("[{}]", moon(", radii = [1.0e6, 0.0, 1.0e6]")),
            "bodies[0].radii (b)",
            "> 0",
        ),
        (format!("[{}]", moon(", albedo = 1.5")), "bodies[0].albedo", "[0, 1]"),
        (
            format!("[{}]", moon(", reflectance = \"lommel\"")),
            "bodies[0].reflectance",
            "did you mean `lommel-seeliger`",
        ),
        (
            format!("[{}]", moon(", atmosphere = \"erth\"")),
            "bodies[0].atmosphere",
            "did you mean `earth`",
        ),
        (
            format!("[{}]", moon(", atmosphere = \"venus\"")),
            "bodies[0].atmosphere",
            "every order",
        ),
        (
            format!("[{}]", moon(", pole = [0.0, 0.0, 0.0]")),
            "bodies[0].pole",
            "not [0, 0, 0]",
        ),
        (
            "[{ preset = \"mon\", position = [4.0e8, 0.0, 0.0] }]".to_owned(),
            "bodies[0].preset",
            "did you mean `moon`",
        ),
        (
            "[{ preset = \"moon\" }]".to_owned(),
            "bodies[0].position",
            "without a date",
        ),
        (
            "[{ position = [4.0e8, 0.0, 0.0] }]".to_owned(),
            "bodies[0].radius",
            "must be given",
        ),
        (
            "[{ preset = \"moon\", position = [0.0, 0.0, 400000.0] }]".to_owned(),
            "bodies[0].position",
            "clear of the planet",
        ),
        (
            "[{ preset = \"moon\", position = [0.0, 0.0, 1.0e8] }]".to_owned(),
            "bodies[0].position",
            "clear of the camera",
        ),
    ] {
        let set = format!("bodies={body_list}");
        let sets = [set.as_str(), "camera.position=[0.0, 0.0, 1.0e8]"];
        let text = message(preset("earth-orbit", &sets));
        assert!(text.contains(key) && text.contains(rule), "{set}: {text}");
    }
}

/// A body's air is a preset's constituents up to its height, at the preset's wavelengths only.
#[test]
fn a_body_s_air_is_a_preset_s() {
    let air_body = "bodies=[{ preset = \"moon\", position = [4.0e8, 0.0, 0.0], atmosphere = \"mars\" }]";
    let sky = sky_of(&preset("earth-orbit", &[air_body]).expect("valid"));
    let air = sky.bodies[0].air.as_ref().expect("an air");
    let mars = firmament_core::atmosphere::presets::mars();
    assert_eq!(Some(&air.constituents), mars.medium.constituents().as_ref());
    assert_eq!(air.top_altitude_m, mars.planet.atmosphere_height);
    let text = message(preset(
        "earth-orbit",
        &[air_body, "atmosphere.wavelengths=[700.0, 550.0, 450.0]"],
    ));
    assert!(
        text.contains("bodies[0].atmosphere") && text.contains("default atmosphere.wavelengths"),
        "{text}"
    );
}

/// In a lunar eclipse the Moon as a body takes the light inside the Earth's shadow: red, and
/// standing in the shadow where the ephemeris puts it — its distance from the shadow's axis
/// within 50 km of the night sky's (geometric) Moon's, from Mexico City (the Moon 73° up) and
/// from where it is low (refraction lifts the drawn Moon by minutes of arc, hundreds of
/// kilometres at its distance; the shadow is lifted with it).
#[test]
fn a_moon_body_in_a_lunar_eclipse_stands_red_in_the_shadow() {
    for place in [&[][..], &["planet.latitude=0.0", "planet.longitude=-22.0"][..]] {
        let geometric = preset("lunar-eclipse-2025", place).expect("valid");
        let frame = geometric.frame_at(None).expect("frame");
        let moon = frame.night.moon.as_ref().expect("the night sky's Moon");
        let shadow = moon.shadow.as_ref().expect("the Moon in the shadow");
        let want_km = shadow.offset.length() * firmament_core::astro::moon::MOON_RADIUS_KM;

        let mut sets = place.to_vec();
        sets.push("bodies=[{ preset = \"moon\" }]");
        let sky = sky_of(&preset("lunar-eclipse-2025", &sets).expect("valid"));
        let body = &sky.bodies[0];
        let in_shadow = body.planet_shadow.as_ref().expect("the body in the shadow");
        let c = body.center - sky.atmosphere.planet.center;
        let got_km = (c - in_shadow.axis * c.dot(in_shadow.axis)).length() / 1000.0;
        let up_deg = body.center.normalize().z.asin().to_degrees();
        println!("Moon {up_deg:.1}° up: {got_km:.1} km from the axis, geometric {want_km:.1} km");
        assert!((got_km - want_km).abs() < 50.0, "{got_km} vs {want_km} km");
        // Deep red at the centre of the face the planet sees.
        let light = in_shadow.light_at(c - c.normalize() * MOON_RADIUS_M);
        assert!(light.x < 0.01 && light.x > 3.0 * light.z, "{light}");
    }
}
