//! GPU tests of planet surfaces (`atmosphere/surface.wgsl`) against the f64 core
//! (`firmament_core::atmosphere::surface`) and reference: a map's albedo and the sea's glint as
//! the core's closed forms give them under an air too thin to matter, the ground read per ray
//! where the sky-view LUT used to hold it, and the glint through Earth's air against the path
//! tracer.

use crate::support::{centre_radiance, far_view_difference, gpu, sky_reference};

use firmament_core::atmosphere::surface::{Surface, SurfaceMap};
use firmament_core::atmosphere::{Planet, Spectrum, presets};
use firmament_core::frame::AtmosphereSky;
use firmament_core::geometry::Ray;
use glam::DVec3;

/// Eight columns of 45° of longitude, one row: land of albedo (0.3, 0.2, 0.1) centred on −22.5°,
/// open water (albedo 0.01, 0.02, 0.04) centred on +22.5°, half of each elsewhere.
fn two_halves() -> Surface {
    let land = [0.3, 0.2, 0.1, 0.0];
    let water = [0.01, 0.02, 0.04, 1.0];
    let half = [0.15, 0.1, 0.07, 0.5];
    let texels = (0..8)
        .map(|column| match column {
            3 => land,
            4 => water,
            _ => half,
        })
        .collect();
    Surface {
        wind_speed_mps: 4.0,
        ..Surface::new(SurfaceMap::new(8, 1, texels).expect("a map"))
    }
}

/// Earth's air on Bruneton's sphere (the world ENU at 0°, 0°) with `surface`, one sun from the
/// planet-frame direction `sun`, the air's coefficients times `air`.
fn earth_with(surface: Surface, sun: DVec3, air: f64) -> AtmosphereSky {
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(6_360_000.0, 60_000.0).posed_at(0.0, 0.0);
    for term in &mut atmosphere.medium.terms {
        term.scattering *= air;
        term.absorption *= air;
    }
    atmosphere.medium.ground_albedo = surface.mean_albedo();
    let world_sun = atmosphere.planet.orientation * sun;
    AtmosphereSky {
        atmosphere,
        suns: vec![presets::earth_sun(world_sun)],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: Some(surface),
    }
}

/// The surface point at longitude `longitude_deg` on the equator, planet frame, and its up.
fn equator(longitude_deg: f64) -> (DVec3, DVec3) {
    let up = DVec3::new(longitude_deg.to_radians().cos(), longitude_deg.to_radians().sin(), 0.0);
    (up * 6_360_000.0, up)
}

/// The direction `sun` mirrored about `up`.
fn mirrored(sun: DVec3, up: DVec3) -> DVec3 {
    2.0 * sun.dot(up) * up - sun
}

/// The GPU's radiance of planet-frame point `p` seen from `distance` metres along `to_eye`.
fn seen(gpu: &mut crate::support::Gpu, sky: &AtmosphereSky, p: DVec3, to_eye: DVec3, distance: f64) -> DVec3 {
    let planet = &sky.atmosphere.planet;
    let world = |v: DVec3| planet.center + planet.orientation * v;
    let eye = world(p + to_eye * distance);
    centre_radiance(gpu, sky, eye, world(p) - eye)
}

/// Spectral radiance as the GPU's linear sRGB.
fn as_srgb(sky: &AtmosphereSky, radiance: Spectrum) -> DVec3 {
    let c = sky.atmosphere.spectral_conversion().linear_srgb(radiance);
    DVec3::new(c.r, c.g, c.b)
}

/// Under an air a million times thinner than Earth's, the ground from orbit is the sun's
/// irradiance times the core's reflectance: the map's albedo on land, the albedo and the
/// Cox–Munk glint on water — at the glint's peak and on its flank — within 1 %.
#[test]
fn the_ground_shows_the_map_s_albedo_and_the_sea_s_glint() {
    let mut gpu = gpu();
    let surface = two_halves();
    let cases: [(f64, f64, f64); 4] = [
        // (longitude, sun zenith angle from the point's up, eye: mirror direction tilted by).
        (-22.5, 30.0, 20.0),
        (22.5, 30.0, 0.0),
        (22.5, 50.0, 0.0),
        (22.5, 30.0, 8.0),
    ];
    for (longitude, sun_zenith, tilt) in cases {
        let (p, up) = equator(longitude);
        let east = DVec3::new(-up.y, up.x, 0.0);
        let sun = (up * sun_zenith.to_radians().cos() + east * sun_zenith.to_radians().sin()).normalize();
        let sky = earth_with(surface.clone(), sun, 1e-6);
        // Tilt the eye about the north axis, away from the mirror direction.
        let mirror = mirrored(sun, up);
        let to_eye = glam::DQuat::from_axis_angle(DVec3::Z, -tilt.to_radians()) * mirror;
        let got = seen(&mut gpu, &sky, p, to_eye, 400_000.0);
        let ground = surface.at(up);
        let factor = surface.reflectance_factor(&ground, up, sun, to_eye);
        let want = as_srgb(&sky, sky.suns[0].irradiance * factor);
        let error = ((got - want) / want).abs().max_element();
        println!("{longitude}° sun {sun_zenith}° tilt {tilt}°: gpu {got:.2} core {want:.2} relative {error:.5}");
        assert!(
            error < 0.01,
            "{longitude}° sun {sun_zenith}° tilt {tilt}°: {got} vs {want}"
        );
    }
}

/// Earth's air over the sea near the glint, seen from 10 km up: the GPU (the sky-view LUT's air
/// and the ground read per ray) against the f64 reference (single scattering, the ground's
/// reflection by the same surface, 1024 paths for the rest), within 5 %.
#[test]
fn the_glint_through_earth_s_air_is_the_reference_s() {
    let mut gpu = gpu();
    let surface = two_halves();
    let (p, up) = equator(22.5);
    let east = DVec3::new(-up.y, up.x, 0.0);
    let sun = (up * 40f64.to_radians().cos() + east * 40f64.to_radians().sin()).normalize();
    let sky = earth_with(surface.clone(), sun, 1.0);
    let reference = sky_reference(&sky, 1024).with_surface(sky.surface.as_ref());
    let planet = sky.atmosphere.planet;
    for tilt in [0.0, 10.0] {
        let to_eye = glam::DQuat::from_axis_angle(DVec3::Z, -f64::to_radians(tilt)) * mirrored(sun, up);
        let eye_height = 10_000.0 / to_eye.dot(up);
        let got = seen(&mut gpu, &sky, p, to_eye, eye_height);
        let eye = planet.center + planet.orientation * (p + to_eye * eye_height);
        let ray = Ray {
            origin: eye,
            direction: (planet.orientation * -to_eye).normalize(),
        };
        let want = as_srgb(&sky, reference.radiance(&ray).total());
        let error = ((got - want) / want).abs().max_element();
        println!("tilt {tilt}°: gpu {got:.2} reference {want:.2} relative {error:.4}");
        assert!(error < 0.05, "tilt {tilt}°: {got} vs {want}");
    }
}

/// A surface of one albedo with no water, seen from a mountain (the sky-view LUT's path): the
/// ground read per ray matches the ground the LUT holds without a surface, within 2 % (full
/// against delta-M transmittance, per ray against the LUT's texels).
#[test]
fn a_uniform_surface_matches_the_lut_s_own_ground() {
    let mut gpu = gpu();
    let albedo = presets::earth().medium.ground_albedo;
    let uniform =
        Surface::new(SurfaceMap::uniform([albedo.x as f32, albedo.y as f32, albedo.z as f32, 0.0]).expect("a map"));
    let (p, up) = equator(0.0);
    let east = DVec3::new(-up.y, up.x, 0.0);
    let sun = (up * 50f64.to_radians().cos() + east * 50f64.to_radians().sin()).normalize();
    let with = earth_with(uniform, sun, 1.0);
    let without = AtmosphereSky {
        surface: None,
        ..with.clone()
    };
    for (down, across) in [(20.0, 0.0), (35.0, 90.0), (60.0, 180.0)] {
        let d: f64 = f64::to_radians(down);
        let a: f64 = f64::to_radians(across);
        let north = DVec3::Z;
        let to_eye = (up * d.sin() + (east * a.cos() + north * a.sin()) * d.cos()).normalize();
        let distance = 3_000.0 / d.sin();
        let a_got = seen(&mut gpu, &with, p, to_eye, distance);
        let b_got = seen(&mut gpu, &without, p, to_eye, distance);
        let error = ((a_got - b_got) / b_got).abs().max_element();
        println!("{down}° down, {across}°: per ray {a_got:.2} LUT {b_got:.2} relative {error:.4}");
        assert!(error < 0.02, "{down}° down: {a_got} vs {b_got}");
    }
}

/// From 4 km up, the ground patch under the camera (drawn as an object, lit by the suns and the
/// sky's light, its albedo a texture of the surface map) against the same ground drawn by the
/// sky pass (`ground.enabled = false`): Spain's plains towards Africa within 4.5 % at the median
/// pixel and 6 % at the worst, so no seam shows where the sky pass takes over at the patch's
/// edge, 100 km out. (A ground of one albedo differs by 2.6 % and 4.9 %: the object's lighting
/// and aerial perspective against the sky pass's ground.)
#[test]
fn the_ground_patch_wears_the_surface_as_the_sky_pass_does() {
    let mut gpu = gpu();
    let (width, height) = (64, 36);
    let render = |gpu: &mut crate::support::Gpu, ground: bool| -> Vec<f32> {
        let overrides: Vec<String> = [
            "planet.surface=\"earth\"",
            "planet.latitude=38.0",
            "planet.longitude=-5.0",
            "camera.position=[0.0, 0.0, 4000.0]",
            "camera.heading=180.0",
            "camera.pitch=-8.0",
            "objects=[]",
            &format!("ground.enabled={ground}"),
        ]
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
        let scene = firmament_scene::load(firmament_scene::SceneSource::Preset("earth-objects"), None, &overrides)
            .expect("a scene");
        let frame = scene.frame_at(None).expect("a frame");
        let crate::support::Gpu { ctx, renderer } = gpu;
        renderer.render_hdr(ctx, &frame, width, height).expect("render").pixels
    };
    let with = render(&mut gpu, true);
    let without = render(&mut gpu, false);
    // The rows below the horizon (28° field of view down from −8°: the horizon at 2° below the
    // camera's level lies near the top third).
    let mut errors = Vec::new();
    for row in height / 2..height {
        for column in 0..width {
            let i = ((row * width + column) * 4) as usize;
            let a = glam::Vec3::from_slice(&with[i..i + 3]);
            let b = glam::Vec3::from_slice(&without[i..i + 3]);
            errors.push(((a - b).abs() / b.max(glam::Vec3::splat(1e-6))).max_element());
        }
    }
    errors.sort_by(f32::total_cmp);
    let (median, worst) = (errors[errors.len() / 2], errors[errors.len() - 1]);
    println!("patch against sky pass: median {median:.4}, worst {worst:.4}");
    assert!(median < 0.045 && worst < 0.06, "median {median}, worst {worst}");
}

/// Earth with a procedural surface seen from 1 AU and from 100 AU with a field of view 100×
/// narrower: the same image, every pixel within 1/255 of the brightest (the budget; the
/// map is read at each ray's ground point, found from its closest approach to the centre).
#[test]
fn a_surface_from_100_au_looks_as_from_1_au() {
    use firmament_core::atmosphere::surface::procedural;
    let mut gpu = gpu();
    let sun = DVec3::new(0.2, 1.0, 0.4).normalize();
    let sky = AtmosphereSky {
        atmosphere: presets::earth(),
        suns: vec![presets::earth_sun(sun)],
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: Some(Surface::new(procedural::bake(5, 256, 128).expect("a map"))),
    };
    let size = 32;
    let towards_eye = DVec3::new(0.3, 0.9, 0.2).normalize();
    let (worst, lit) = far_view_difference(&mut gpu, &sky, towards_eye, 6.4e6, size);
    println!(
        "worst {:.2}/255 of the brightest pixel over {lit} lit pixels",
        worst * 255.0
    );
    assert!(lit > size * size / 8, "{lit} lit pixels");
    assert!(worst < 1.0 / 255.0, "worst {worst}");
}
