//! `[time]` with a real date: the sun where NREL's SPA puts it (the paper's own example), the
//! atmosphere's first sun moved there, another clock time on the same date, the gradient sky's
//! keyframes following the sun's elevation, and a clear error for each bad value.

use firmament_core::frame::Sky;
use firmament_core::{LinearRgb, TimeOfDay};
use firmament_scene::{Scene, SceneError, SceneSource, load};
use glam::DVec3;

fn load_scene(text: &str, sets: &[&str]) -> Result<Scene, SceneError> {
    let sets: Vec<String> = sets.iter().map(|s| (*s).to_owned()).collect();
    load(
        SceneSource::Text {
            text,
            origin: "test.toml",
        },
        None,
        &sets,
    )
}

/// The frame's physical sky.
fn atmosphere_of(frame: &firmament_core::Frame) -> &firmament_core::frame::AtmosphereSky {
    let Sky::Atmosphere(sky) = &frame.sky else {
        panic!("atmosphere")
    };
    sky
}

/// The frame of preset `name` with `sets`, at the scene's own moment.
fn preset_frame(name: &str, sets: &[&str]) -> firmament_core::Frame {
    let sets: Vec<String> = sets.iter().map(|s| (*s).to_owned()).collect();
    load(SceneSource::Preset(name), None, &sets)
        .expect("valid")
        .frame_at(None)
        .expect("frame")
}

fn gradient_sun(scene: &Scene, time: Option<TimeOfDay>) -> DVec3 {
    match scene.frame_at(time).expect("frame").sky {
        Sky::Gradient(state) => state.sun.direction,
        other => panic!("a gradient sky, not {other:?}"),
    }
}

/// Zenith angle and azimuth (east of north), degrees, of an East-North-Up direction.
fn zenith_azimuth(d: DVec3) -> (f64, f64) {
    let zenith = d.z.clamp(-1.0, 1.0).acos().to_degrees();
    let azimuth = d.x.atan2(d.y).to_degrees().rem_euclid(360.0);
    (zenith, azimuth)
}

/// Reda & Andreas (2004), table A5.1: 2003-10-17 12:30:30 −7 h at 39.742476° N, 105.1786° W,
/// 1830.14 m, 820 mbar, 11 °C, ΔT 67 s → zenith 50.11162°, azimuth 194.34024°.
const SPA_EXAMPLE: &str = r#"
[time]
date_time = "2003-10-17T12:30:30-07:00"
delta_t = 67.0
pressure = 820.0
temperature = 11.0

[planet]
latitude = 39.742476
longitude = -105.1786

[camera]
position = [0.0, 0.0, 1830.14]
"#;

#[test]
fn the_sun_stands_where_the_spa_paper_says() {
    let scene = load_scene(SPA_EXAMPLE, &[]).expect("valid");
    let (zenith, azimuth) = zenith_azimuth(gradient_sun(&scene, None));
    println!("SPA example: zenith {zenith:.6}°, azimuth {azimuth:.6}°");
    assert!((zenith - 50.11162).abs() < 2e-5, "{zenith}");
    assert!((azimuth - 194.34024).abs() < 2e-5, "{azimuth}");
    // The physical sky's first sun goes to the same place; with no [[suns]] the body's is added.
    let atmosphere = scene.atmosphere_sky().expect("sky");
    assert_eq!(atmosphere.suns.len(), 1);
    let (z, a) = zenith_azimuth(atmosphere.suns[0].direction);
    assert!((z - 50.11162).abs() < 2e-5 && (a - 194.34024).abs() < 2e-5, "{z} {a}");
    let two = load_scene(
        SPA_EXAMPLE,
        &[
            "suns.0.elevation=5",
            "suns.0.azimuth=0",
            "suns.1.elevation=30",
            "suns.1.azimuth=90",
        ],
    )
    .expect("valid")
    .atmosphere_sky()
    .expect("sky");
    assert_eq!(two.suns.len(), 2);
    assert!((zenith_azimuth(two.suns[0].direction).0 - 50.11162).abs() < 2e-5);
    assert!(
        (zenith_azimuth(two.suns[1].direction).0 - 60.0).abs() < 1e-9,
        "the second sun stays"
    );
}

#[test]
fn another_clock_time_keeps_the_date() {
    let scene = load_scene(SPA_EXAMPLE, &[]).expect("valid");
    let at = |hours: f64| gradient_sun(&scene, Some(TimeOfDay::from_hours(hours).expect("finite")));
    // Mid-October at 40° N: noon high in the south, midnight well below the horizon.
    let noon = at(11.77);
    assert!(noon.z > 0.6 && noon.y < 0.0, "{noon}");
    assert!(at(0.0).z < -0.5);
    // A civil date and time given by the caller (a time-lapse) wins over the scene's.
    let other = firmament_scene::parse_date_time("2003-06-21T12:00:00-07:00").expect("valid");
    let Sky::Gradient(state) = scene.frame_at_date_time(&other).expect("frame").sky else {
        panic!("gradient")
    };
    assert!(state.sun.direction.z > noon.z, "higher in June");
}

fn zenith_colour(scene: &Scene) -> LinearRgb {
    match scene.frame_at(None).expect("frame").sky {
        Sky::Gradient(state) => state.bands.zenith,
        other => panic!("a gradient sky, not {other:?}"),
    }
}

#[test]
fn gradient_keyframes_can_follow_the_sun_s_elevation() {
    // Midsummer at 60° N, 22:00 CEST: the sun still a few degrees up in the north-west.
    let midsummer = r#"
[time]
date_time = "2024-06-21T22:00:00+02:00"
[planet]
latitude = 60.0
longitude = 10.0
"#;
    let by_clock = load_scene(midsummer, &[]).expect("valid");
    let by_sun = load_scene(midsummer, &["sky.gradient.by=\"sun-elevation\""]).expect("valid");
    let sun = gradient_sun(&by_sun, None);
    assert_eq!(sun, gradient_sun(&by_clock, None), "the same sun either way");
    let elevation = sun.z.asin().to_degrees();
    assert!(elevation > 0.5 && elevation < 6.0, "{elevation}");
    // By the clock (solar time ≈ 20:38) the default cycle is deep in dusk; by the sun's
    // elevation it is the equinox-at-45° time with that elevation, late afternoon: brighter.
    let luminance = |c: LinearRgb| 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    let (clock, elevation_keyed) = (luminance(zenith_colour(&by_clock)), luminance(zenith_colour(&by_sun)));
    println!("zenith luminance by clock {clock:.4}, by sun elevation {elevation_keyed:.4}");
    assert!(elevation_keyed > 2.0 * clock, "{elevation_keyed} vs {clock}");
    // Without a date, following the elevation on the scene's own path changes nothing.
    let plain = load_scene("", &[]).expect("valid");
    let plain_by_sun = load_scene("", &["sky.gradient.by=\"sun-elevation\""]).expect("valid");
    let (a, b) = (zenith_colour(&plain), zenith_colour(&plain_by_sun));
    assert!(
        (a.r - b.r).abs() + (a.g - b.g).abs() + (a.b - b.b).abs() < 1e-9,
        "{a:?} vs {b:?}"
    );
}

#[test]
fn every_bad_time_value_names_its_key() {
    let cases = [
        ("time.date_time=\"yesterday\"", "time.date_time = \"yesterday\""),
        ("time.date_time=\"2023-02-30T00:00:00Z\"", "no such date"),
        ("time.pressure=0", "time.pressure = 0: must be in (0, 5000] millibars"),
        ("time.temperature=nan", "time.temperature"),
        ("time.delta_t=1e9", "time.delta_t"),
        ("time.star_limit=7", "time.star_limit = 7"),
        ("sky.gradient.by=\"moon\"", "sky.gradient.by"),
    ];
    for (set, expected) in cases {
        let message = load_scene("", &[set]).expect_err(set).to_string();
        assert!(message.contains(expected), "{set}: {message}");
    }
    let mars = load_scene(
        "[time]\ndate_time = \"2024-01-01T00:00:00Z\"\n[planet]\nbody = \"mars\"\n",
        &[],
    )
    .expect_err("no ephemeris for Mars")
    .to_string();
    assert!(
        mars.contains("planet.body = \"mars\"") && mars.contains("ephemeris"),
        "{mars}"
    );
    let lat = load_scene(
        "[time]\ndate_time = \"2024-01-01T00:00:00Z\"\n",
        &["planet.latitude=91"],
    )
    .expect_err("latitude")
    .to_string();
    assert!(lat.contains("planet.latitude"), "{lat}");
}

/// The brightest star within 2° of `direction` in a frame's night sky.
fn star_near(scene: &Scene, when: &str, direction: DVec3) -> Option<DVec3> {
    let civil = firmament_scene::parse_date_time(when).expect("valid");
    let frame = scene.frame_at_date_time(&civil).expect("frame");
    frame
        .night
        .stars
        .iter()
        .filter(|s| s.direction.angle_between(direction) < 2f64.to_radians())
        .max_by(|a, b| a.color.y.total_cmp(&b.color.y))
        .map(|s| s.direction)
}

#[test]
fn the_night_sky_turns_about_the_pole_and_hides_by_day() {
    let night = load_scene(
        "[time]\ntime_of_day = \"00:00\"\n[planet]\nlatitude = 45.0\n",
        &["sky.model=atmosphere"],
    )
    .expect("valid");
    // The celestial pole at 45° N: due north, 45° up.
    let pole = DVec3::new(0.0, 45f64.to_radians().cos(), 45f64.to_radians().sin());
    let evening = star_near(&night, "2025-01-15T18:00:00Z", pole).expect("Polaris");
    let morning = star_near(&night, "2025-01-16T06:00:00Z", pole).expect("Polaris");
    // Polaris circles the pole 0.65° away (no refraction is applied to stars).
    for d in [evening, morning] {
        let off = d.angle_between(pole).to_degrees();
        assert!((off - 0.65).abs() < 0.1, "{off}");
    }
    // A star near the celestial equator moves 180° in 12 hours: Polaris barely does.
    assert!(evening.angle_between(morning).to_degrees() < 1.4);
    let civil = firmament_scene::parse_date_time("2025-01-15T22:00:00Z").expect("valid");
    let frame = night.frame_at_date_time(&civil).expect("frame");
    let n = frame.night.stars.len();
    assert!(n > 3000 && n < 5000, "{n} stars above the horizon");
    // Magnitude-0 stars give about 2.5e-6 lux; through the air a little less.
    let brightest = frame.night.stars.iter().map(|s| s.color.y).fold(0.0, f64::max);
    assert!(brightest > 2e-6 && brightest < 2e-5, "{brightest}");
    // By day the gradient sky shows none; at night it does; switched off, none either.
    let gradient = |when: &str, sets: &[&str]| {
        let civil = firmament_scene::parse_date_time(when).expect("valid");
        load_scene("", sets)
            .expect("valid")
            .frame_at_date_time(&civil)
            .expect("frame")
            .night
    };
    assert!(gradient("2025-06-21T12:00:00Z", &[]).stars.is_empty());
    assert!(gradient("2025-01-15T23:00:00Z", &[]).stars.len() > 2000);
    assert!(
        gradient("2025-01-15T23:00:00Z", &["time.stars=false", "time.moon=false"])
            .stars
            .is_empty()
    );
    // Without a date there is no night sky.
    assert!(night.frame_at(None).expect("frame").night.stars.is_empty());
}

#[test]
fn the_moon_lights_a_physical_night_sky_without_a_flare() {
    // 2025-03-13 23:30 UTC at 45° N, 0° E: the Moon a few hours before full, high in the south.
    let text = "[time]\ndate_time = \"2025-03-13T23:30:00Z\"\n[flare]\nenabled = true\n";
    let scene = load_scene(text, &["sky.model=atmosphere"]).expect("valid");
    let frame = scene.frame_at(None).expect("frame");
    let sky = atmosphere_of(&frame);
    assert_eq!(sky.suns.len(), 2, "the Sun and the Moon");
    let (sun, moon) = (sky.suns[0], sky.suns[1]);
    assert!(sun.disc && !moon.disc);
    assert!(
        sun.direction.z < -0.5 && moon.direction.z > 0.5,
        "{} {}",
        sun.direction,
        moon.direction
    );
    // Nearly full: opposite the Sun. Moonlight is sunlight scaled to ~0.25 lux of ~1.3e5.
    assert!(sun.direction.angle_between(moon.direction).to_degrees() > 170.0);
    let ratio = moon.irradiance.y / sun.irradiance.y;
    assert!(ratio > 1.5e-6 && ratio < 3e-6, "{ratio}");
    // The night sky's Moon disc is the same Moon.
    let disc = frame.night.moon.expect("the Moon is up");
    assert!(disc.direction.angle_between(moon.direction) < 1e-9);
    // No flare from the Moon, none from the Sun below the horizon.
    assert!(frame.flares.sources.is_empty());
    // Switched off: no Moon light, no disc.
    let dark = load_scene(text, &["sky.model=atmosphere", "time.moon=false"]).expect("valid");
    let frame = dark.frame_at(None).expect("frame");
    let sky = atmosphere_of(&frame);
    assert_eq!(sky.suns.len(), 1);
    assert!(frame.night.moon.is_none());
}

#[test]
fn the_moon_eclipses_the_sun_in_dallas_on_2024_04_08() {
    let frame = preset_frame("eclipse-2024", &[]);
    let sky = atmosphere_of(&frame);
    // The Sun alone lights the sky: a new Moon gives no moonlight.
    assert_eq!(sky.suns.len(), 1);
    let sun = sky.suns[0];
    assert_eq!(sky.eclipsers.len(), 1, "the Moon");
    let moon = sky.eclipsers[0];
    let to_moon = moon.center - frame.camera.position;
    let moon_radius = (moon.radius_m / to_moon.length()).asin();
    let separation = to_moon.angle_between(sun.direction);
    // Totality: the Moon's disc covers the Sun's, both refracted alike.
    assert!(
        separation + sun.angular_radius < moon_radius,
        "{separation} + {} vs {moon_radius}",
        sun.angular_radius
    );
    assert!((3.5e8..4.1e8).contains(&to_moon.length()));
    // The night sky's Moon stands where the eclipser does.
    let disc = frame.night.moon.expect("the Moon is up");
    assert!(disc.direction.angle_between(to_moon) < 1e-9);
    // A day later the Moon is far from the Sun: no eclipser.
    let later = preset_frame("eclipse-2024", &["time.date_time=\"2024-04-09T18:42:38Z\""]);
    assert!(atmosphere_of(&later).eclipsers.is_empty());
}

#[test]
fn the_moon_goes_red_in_the_earth_s_shadow_on_2025_03_14() {
    let frame = preset_frame("lunar-eclipse-2025", &[]);
    let sky = atmosphere_of(&frame);
    let moon = frame.night.moon.expect("the Moon is up");
    let shadow = moon.shadow.expect("in the Earth's shadow");
    // NASA's umbral magnitude at greatest eclipse, 1.1784, puts the Moon's centre
    // ρ_u + R − 2·R·1.1784 from the axis, ρ_u = 1.02·(π_moon − s_sun + π_sun)·D the umbra's
    // radius (Danjon's enlargement; π the parallaxes, D the Moon's distance from the Earth's
    // centre, here from its angular radius).
    let moon_radius_km = 1737.4;
    let distance_km = moon_radius_km / moon.angular_radius.sin();
    let parallax = (6378.137 / distance_km).asin();
    let umbra_km = 1.02 * (parallax - sky.suns[0].angular_radius + 8.794f64.to_radians() / 3600.0) * distance_km;
    let nasa = umbra_km / moon_radius_km + 1.0 - 2.0 * 1.1784;
    let offset = shadow.offset.length();
    println!("the Moon's centre {offset:.3} Moon radii from the axis, NASA's {nasa:.3}");
    assert!(
        (offset - nasa).abs() < 0.15,
        "{offset} Moon radii from the axis, NASA's {nasa}"
    );
    let centre = shadow.light_at(-moon.direction);
    assert!(centre.y < 1e-3 && centre.x > 2.0 * centre.z, "{centre}");
    // The moonlight is as dim: a full moon's is ~2e-6 of sunlight, this ~1000× less.
    assert_eq!(sky.suns.len(), 2, "the Sun and the Moon");
    let ratio = sky.suns[1].irradiance.y / sky.suns[0].irradiance.y;
    assert!(ratio < 5e-9, "{ratio}");
    // Four hours later the Moon has left the shadow.
    let later = preset_frame("lunar-eclipse-2025", &["time.date_time=\"2025-03-14T10:30:00Z\""]);
    assert!(later.night.moon.is_none_or(|m| m.shadow.is_none()));
}
