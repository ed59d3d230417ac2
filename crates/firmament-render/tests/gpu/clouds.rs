//! The cloud layers (`shaders/clouds/march.wgsl`) against closed forms and the f64 reference: a
//! uniform slab's transmittance, its shadow on the ground, the image left alone where no cloud
//! is, and reruns identical to the byte.

use firmament_core::atmosphere::clouds::{CloudKind, CloudLayer};
use firmament_core::atmosphere::{Atmosphere, Planet, Spectrum, Sun, presets};
use firmament_core::camera::Camera;
use firmament_core::frame::{AtmosphereSky, Frame, Sky};
use firmament_render::headless::Image;
use glam::DVec3;

use crate::support::{Gpu, direction, gpu};

/// Earth's sphere (Bruneton's radii) with no air at all: whatever dims the sun is cloud.
pub(crate) fn airless() -> Atmosphere {
    let mut atmosphere = presets::earth();
    atmosphere.planet = Planet::sphere(6_360_000.0, 60_000.0).posed_at(0.0, 0.0);
    atmosphere.medium.terms[0].scattering = Spectrum::ZERO;
    atmosphere.medium.terms[1].scattering = Spectrum::ZERO;
    atmosphere.medium.terms[1].absorption = Spectrum::ZERO;
    atmosphere.medium.terms[2].absorption = Spectrum::ZERO;
    atmosphere
}

/// A sun whose disc (3° across) fills a narrow view pointed at its centre.
fn wide_sun(view_zenith_deg: f64) -> Sun {
    Sun {
        angular_radius: 1.5f64.to_radians(),
        limb_darkening: 0.0,
        ..presets::earth_sun(direction(0.0, 90.0 - view_zenith_deg))
    }
}

pub(crate) fn camera_at(position: DVec3, forward: DVec3, fov_y_degrees: f64) -> Camera {
    Camera::looking_at(position, position + forward, DVec3::Z)
        .or_else(|| Camera::looking_at(position, position + forward, DVec3::Y))
        .expect("a view direction")
        .with_fov_y(fov_y_degrees.to_radians())
}

fn render(gpu: &mut Gpu, sky: AtmosphereSky, camera: Camera, width: u32, height: u32) -> Image<f32> {
    let frame = Frame::new(camera, Sky::Atmosphere(sky));
    let Gpu { ctx, renderer } = gpu;
    renderer.render_hdr(ctx, &frame, width, height).expect("render")
}

/// Length of the straight path from a point `height` metres above a sphere of `radius` through
/// the shell between `bottom` and `top` metres, at `zenith` radians from the local vertical.
fn path_through_shell(radius: f64, height: f64, bottom: f64, top: f64, zenith: f64) -> f64 {
    let r0 = radius + height;
    let distance_to = |r: f64| {
        // r0·cos θ terms of |o + t·d| = r, the far (upward) root.
        let b = r0 * zenith.cos();
        -b + (b * b - (r0 * r0 - r * r)).sqrt()
    };
    distance_to(radius + top) - distance_to(radius + bottom)
}

/// An absorbing uniform layer (albedo 0), 1000–2000 m up, σ = 10⁻³ m⁻¹ (τ = 1 straight up).
struct Absorber {
    bottom_m: f64,
    top_m: f64,
    density_per_m: f64,
}

const ABSORBER: Absorber = Absorber {
    bottom_m: 1_000.0,
    top_m: 2_000.0,
    density_per_m: 1.0e-3,
};

fn absorber() -> CloudLayer {
    CloudLayer {
        albedo: 0.0,
        ..CloudLayer::new(
            ABSORBER.bottom_m,
            ABSORBER.top_m,
            1.0,
            ABSORBER.density_per_m,
            CloudKind::Uniform,
        )
    }
}

#[test]
fn a_uniform_layer_dims_the_sun_by_its_closed_form_transmittance() {
    let mut gpu = gpu();
    let (bottom, top, density) = (ABSORBER.bottom_m, ABSORBER.top_m, ABSORBER.density_per_m);
    let absorber = absorber();
    let eye = DVec3::new(0.0, 0.0, 2.0);
    for zenith_deg in [0.0, 30.0, 60.0, 75.0] {
        let sun = wide_sun(zenith_deg);
        let camera = camera_at(eye, sun.direction, 0.5);
        let clear = AtmosphereSky {
            atmosphere: airless(),
            suns: vec![sun],
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        };
        let cloudy = AtmosphereSky {
            clouds: vec![absorber.clone()],
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
            ..clear.clone()
        };
        // An odd image: its centre pixel looks exactly along the camera, at the sun.
        let without = render(&mut gpu, clear, camera, 5, 5).pixel(2, 2).expect("inside");
        let with = render(&mut gpu, cloudy, camera, 5, 5).pixel(2, 2).expect("inside");
        let length = path_through_shell(6_360_000.0, eye.z, bottom, top, zenith_deg.to_radians());
        let expected = (-density * length).exp();
        for channel in 0..3 {
            let got = f64::from(with[channel]) / f64::from(without[channel]);
            assert!(
                (got / expected - 1.0).abs() < 0.005,
                "view zenith {zenith_deg}°, channel {channel}: transmittance {got:.5}, closed form {expected:.5} \
                 (path {length:.1} m)"
            );
        }
    }
}

#[test]
fn pixels_whose_rays_miss_every_layer_are_left_alone() {
    let mut gpu = gpu();
    // A layer far above a camera looking down from 100 m: every ray meets the ground first. The
    // sun is below the horizon, so the layer shadows no ground either (see
    // `a_uniform_layer_shadows_the_ground_by_its_closed_form_transmittance`).
    let sky = crate::support::street_sky(90.0, -3.0);
    let cloudy = AtmosphereSky {
        clouds: vec![CloudLayer::new(5_000.0, 6_000.0, 1.0, 0.02, CloudKind::Uniform)],
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
        ..sky.clone()
    };
    let camera = camera_at(DVec3::new(0.0, 0.0, 100.0), direction(0.0, -30.0), 20.0);
    let clear = render(&mut gpu, sky, camera, 8, 8);
    let with = render(&mut gpu, cloudy, camera, 8, 8);
    assert_eq!(clear.pixels, with.pixels, "every ray meets the ground before the layer");
}

/// The linear sRGB of the centre of a 5 × 5 image along `view` from `eye`, 1° across.
fn centre_radiance(gpu: &mut Gpu, sky: &AtmosphereSky, eye: DVec3, view: DVec3) -> DVec3 {
    let image = render(gpu, sky.clone(), camera_at(eye, view, 1.0), 5, 5);
    let p = image.pixel(2, 2).expect("inside");
    DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

#[test]
fn a_uniform_layer_shadows_the_ground_by_its_closed_form_transmittance() {
    let mut gpu = gpu();
    // No air: the ground is lit by the sun alone, `albedo/π · E · μ`, and an absorbing layer
    // takes e^(−σ·L) of it, L the sun's path through the shell from the ground.
    let (bottom, top, density) = (ABSORBER.bottom_m, ABSORBER.top_m, ABSORBER.density_per_m);
    let absorber = absorber();
    let eye = DVec3::new(0.0, 0.0, 2.0);
    for zenith_deg in [0.0, 30.0, 60.0, 75.0] {
        let clear = AtmosphereSky {
            atmosphere: airless(),
            suns: vec![presets::earth_sun(direction(90.0, 90.0 - zenith_deg))],
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        };
        let cloudy = AtmosphereSky {
            clouds: vec![absorber.clone()],
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
            ..clear.clone()
        };
        // The ground 3 m away, 40° down.
        let view = direction(250.0, -40.0);
        let without = centre_radiance(&mut gpu, &clear, eye, view);
        let with = centre_radiance(&mut gpu, &cloudy, eye, view);
        let length = path_through_shell(6_360_000.0, 0.0, bottom, top, zenith_deg.to_radians());
        let expected = (-density * length).exp();
        // The share of the ground's light the layer takes (the rest, down to 2 %, would show the
        // sky-view LUT's interpolation of the ground, relative to which it is subtracted).
        for channel in 0..3 {
            let lost = 1.0 - with[channel] / without[channel];
            assert!(
                (lost / (1.0 - expected) - 1.0).abs() < 0.005,
                "sun zenith {zenith_deg}°, channel {channel}: the layer takes {lost:.5} of the ground's \
                 light, closed form {:.5}",
                1.0 - expected
            );
        }
    }
}

#[test]
fn the_grounds_cloud_shadow_is_the_references_in_the_air() {
    use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
    use firmament_core::geometry::Ray;
    let mut gpu = gpu();
    // Earth's air, a scattering layer: what the layer takes off the ground's direct sunlight,
    // against the reference's sunlit ground (its deterministic part) with and without it. The
    // sky's light on the ground is not compared: the GPU's keeps no cloud shadow.
    let layer = CloudLayer::new(1_000.0, 1_500.0, 1.0, 1.0e-3, CloudKind::Uniform);
    let eye = DVec3::new(0.0, 0.0, 2.0);
    let view = direction(250.0, -40.0);
    for elevation in [60.0, 25.0] {
        let clear = crate::support::street_sky(90.0, elevation);
        let cloudy = AtmosphereSky {
            clouds: vec![layer.clone()],
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
            ..clear.clone()
        };
        let gpu_lost = centre_radiance(&mut gpu, &clear, eye, view) - centre_radiance(&mut gpu, &cloudy, eye, view);
        let ground = |sky: &AtmosphereSky| {
            let settings = ReferenceSettings {
                paths: 1,
                ..Default::default()
            };
            let reference = Reference::new(sky.atmosphere.clone(), &sky.suns, settings).with_clouds(&sky.clouds);
            let parts = reference.radiance(&Ray {
                origin: eye,
                direction: view,
            });
            let rgb = sky.atmosphere.spectral_conversion().linear_srgb(parts.ground);
            DVec3::new(rgb.r, rgb.g, rgb.b)
        };
        let want_lost = ground(&clear) - ground(&cloudy);
        let error = ((gpu_lost - want_lost) / want_lost).abs().max_element();
        println!("sun {elevation}°: the ground loses {gpu_lost:.4}, the reference's {want_lost:.4}");
        assert!(
            error < 0.02,
            "sun at {elevation}°: the clouds take {gpu_lost:.4} off the ground, the reference {want_lost:.4}"
        );
    }
}

#[test]
fn reruns_are_identical_to_the_byte() {
    let mut gpu = gpu();
    let sky = AtmosphereSky {
        clouds: vec![CloudLayer {
            seed: 7,
            ..CloudLayer::new(1_500.0, 3_000.0, 0.5, 0.05, CloudKind::Cumulus)
        }],
        ..crate::support::street_sky(90.0, 35.0)
    };
    let camera = camera_at(DVec3::new(0.0, 0.0, 2.0), direction(0.0, 30.0), 70.0);
    let first = render(&mut gpu, sky.clone(), camera, 24, 16);
    let second = render(&mut gpu, sky, camera, 24, 16);
    assert_eq!(first.pixels, second.pixels);
    let clear = render(&mut gpu, crate::support::street_sky(90.0, 35.0), camera, 24, 16);
    assert_ne!(first.pixels, clear.pixels, "the clouds show");
}

/// The GPU's linear sRGB along `view` from `eye` (the centre of a 1 × 1 image, 1° across).
fn gpu_radiance(gpu: &mut Gpu, sky: &AtmosphereSky, eye: DVec3, view: DVec3) -> DVec3 {
    let image = render(gpu, sky.clone(), camera_at(eye, view, 1.0), 1, 1);
    let p = image.pixel(0, 0).expect("inside");
    DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

/// The reference's linear sRGB along `view` from `eye` and the standard error of its luminance
/// (cd/m², from the Monte Carlo multiple scattering).
fn reference_radiance(sky: &AtmosphereSky, paths: usize, eye: DVec3, view: DVec3) -> (DVec3, f64) {
    use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
    use firmament_core::geometry::Ray;
    let reference = Reference::new(
        sky.atmosphere.clone(),
        &sky.suns,
        ReferenceSettings {
            paths,
            ..Default::default()
        },
    )
    .with_clouds(&sky.clouds);
    let parts = reference.radiance(&Ray {
        origin: eye,
        direction: view,
    });
    let conversion = sky.atmosphere.spectral_conversion();
    let rgb = conversion.linear_srgb(parts.total());
    let error = conversion.luminance(parts.multiple.standard_error);
    (DVec3::new(rgb.r, rgb.g, rgb.b), error)
}

/// Prints the GPU against the reference through a uniform slab and a cumulus layer at three sun
/// elevations (`cargo test --release -p firmament-render --test gpu -- --ignored --nocapture
/// cloud_radiance_survey`).
#[test]
#[ignore = "a survey for calibration, minutes in release"]
fn cloud_radiance_survey() {
    let mut gpu = gpu();
    let paths = 16_384;
    let slab = CloudLayer::new(1_000.0, 1_500.0, 1.0, 0.02, CloudKind::Uniform);
    let thin = CloudLayer::new(1_000.0, 1_100.0, 1.0, 0.01, CloudKind::Uniform);
    for (name, layer) in [("thin slab tau 1", thin), ("uniform slab tau 10", slab)] {
        for elevation in [60.0, 30.0, 10.0] {
            let sky = AtmosphereSky {
                clouds: vec![layer.clone()],
                eclipsers: Vec::new(),
                bodies: Vec::new(),
                rings: None,
                surface: None,
                ..crate::support::street_sky(0.0, elevation)
            };
            for (eye, view, what) in [
                (DVec3::new(0.0, 0.0, 2.0), direction(0.0, 89.0), "below, zenith"),
                (DVec3::new(0.0, 0.0, 2.0), direction(180.0, 45.0), "below, 45° away"),
                (
                    DVec3::new(0.0, 0.0, 4_000.0),
                    direction(180.0, -60.0),
                    "above, down away",
                ),
                (
                    DVec3::new(0.0, 0.0, 4_000.0),
                    direction(0.0, -60.0),
                    "above, down towards",
                ),
            ] {
                let got = gpu_radiance(&mut gpu, &sky, eye, view);
                let (want, error) = reference_radiance(&sky, paths, eye, view);
                let y = |c: DVec3| 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
                println!(
                    "{name:<22} sun {elevation:>4}° {what:<22} gpu {:>9.1} ref {:>9.1} ± {:>6.1} cd/m²  ratio {:.3}",
                    y(got),
                    y(want),
                    error,
                    y(got) / y(want)
                );
            }
        }
    }
}

/// The objects' sunlight under the clouds: the scene's ground patch (an object, lit by the GL
/// equations) loses what an absorbing uniform layer keeps from its sun, `1 − e^(−σ·L)` of its
/// direct light (`d_cm · light · n·l`, computed here from the frame), per fragment from the
/// clouds' shadow map. The sky's light on it is left as it was.
#[test]
fn the_objects_sunlight_passes_through_the_clouds_shadow_map() {
    let mut gpu = gpu();
    // Looking south and down at the ground 2.5 m away, the scene's objects and their shadows
    // (the sun in the south-west, 20° up) out of sight.
    let overrides = ["camera.heading=180", "camera.pitch=-42", "camera.fov_y=4"].map(String::from);
    let scene = firmament_scene::load(firmament_scene::SceneSource::Preset("earth-objects"), None, &overrides)
        .expect("the preset");
    let clear = scene.frame_at(None).expect("a frame");
    let mut cloudy = clear.clone();
    let Sky::Atmosphere(sky) = &mut cloudy.sky else {
        unreachable!("an atmosphere scene")
    };
    sky.clouds = vec![absorber()];
    let sun = sky.suns[0].direction.normalize();
    let ground = clear.objects.ground.as_ref().expect("a ground");
    let n_dot_l = ground.up.dot(sun);
    let Gpu { ctx, renderer } = &mut *gpu;
    let mut centre = |frame: &Frame| {
        let image = renderer.render_hdr(ctx, frame, 9, 9).expect("render");
        let p = image.pixel(4, 4).expect("inside");
        DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
    };
    let lost = centre(&clear) - centre(&cloudy);
    let zenith = n_dot_l.acos();
    let kept = (-ABSORBER.density_per_m
        * path_through_shell(6_367_000.0, 0.0, ABSORBER.bottom_m, ABSORBER.top_m, zenith))
    .exp();
    let direct = ground.object.front.diffuse.truncate() * ground.object.light_colors[0].truncate() * n_dot_l;
    let want = direct * (1.0 - kept);
    let error = ((lost - want) / want).abs().max_element();
    println!(
        "the ground loses {lost:.3}, closed form {want:.3} ({:.2} %)",
        100.0 * error
    );
    assert!(
        error < 0.01,
        "the ground loses {lost:.3} under the layer, the closed form {want:.3}"
    );
}

/// Transmittance (grey) of the reference's clouds between two world-frame points.
fn cloud_transmittance(
    reference: &firmament_core::atmosphere::reference::Reference,
    planet: &Planet,
    a: DVec3,
    b: DVec3,
) -> f64 {
    (-reference
        .optical_depth(planet.to_planet_frame(a), planet.to_planet_frame(b))
        .max_element())
    .exp()
}

/// A broken layer from afar, where every pixel spans more than one of its columns and the march
/// takes their average: the ground seen through it keeps the light of the gaps. An absorbing
/// cumulus layer (30 % cover, albedo 0) in airless air, seen from 300 km over a lit ground, two
/// ways (straight down with the sun 40° from the zenith; 35° from the zenith with the sun 50°
/// behind the camera): the share of the ground's light the image keeps against the mean of
/// `e^(−τ_view − τ_sun)` over rays through the image — the same field's optical depths in `f64`
/// towards the camera and towards the sun, taken through the columns themselves.
#[test]
fn a_broken_layer_seen_from_afar_keeps_the_light_of_its_gaps() {
    use firmament_core::atmosphere::reference::{Reference, ReferenceSettings};
    let mut gpu = gpu();
    let layer = CloudLayer {
        albedo: 0.0,
        seed: 5,
        ..CloudLayer::new(1_500.0, 3_000.0, 0.3, 0.05, CloudKind::Cumulus)
    };
    let cell = layer.column_cell_m().expect("cumulus has columns");
    // 32 × 32 pixels, each about twice a column cell across at 300 km: 130 km of ground, over
    // which the clouds' clusters average out.
    let (size, fov_deg) = (32u32, 24.0f64);
    let radius = 6_360_000.0;
    for (view_zenith, sun) in [(0.0f64, direction(90.0, 50.0)), (35.0, direction(0.0, 40.0))] {
        let clear = AtmosphereSky {
            atmosphere: airless(),
            suns: vec![presets::earth_sun(sun)],
            clouds: Vec::new(),
            eclipsers: Vec::new(),
            bodies: Vec::new(),
            rings: None,
            surface: None,
        };
        let cloudy = AtmosphereSky {
            clouds: vec![layer.clone()],
            ..clear.clone()
        };
        // Looking north-east of the camera's foot (the sun's azimuth 0° is north: it stands
        // behind the camera in the slanted view).
        let forward = DVec3::new(0.0, view_zenith.to_radians().sin(), -view_zenith.to_radians().cos());
        let eye = -forward * 300_000.0 / view_zenith.to_radians().cos();
        let camera = camera_at(eye, forward, fov_deg);
        let without = render(&mut gpu, clear.clone(), camera, size, size);
        let with = render(&mut gpu, cloudy.clone(), camera, size, size);
        let kept = with
            .pixels
            .chunks(4)
            .zip(without.pixels.chunks(4))
            .map(|(w, c)| f64::from(w[1]) / f64::from(c[1]))
            .sum::<f64>()
            / f64::from(size * size);
        let planet = &cloudy.atmosphere.planet;
        let reference = Reference::new(
            cloudy.atmosphere.clone(),
            &cloudy.suns,
            ReferenceSettings {
                paths: 1,
                ..Default::default()
            },
        )
        .with_clouds(&cloudy.clouds);
        // Rays through the whole image on a jittered grid, each to the ground (the sphere below
        // the world origin) and on to the sun.
        let (grid, half) = (64u32, (0.5 * fov_deg).to_radians().tan());
        let centre = DVec3::new(0.0, 0.0, -radius);
        let (mut both, mut view_only, mut sun_only) = (0.0, 0.0, 0.0);
        for i in 0..grid * grid {
            let (u, v) = (
                (f64::from(i % grid) + 0.5 + 0.4 * (f64::from(i * 7 % 5) / 5.0 - 0.4)) / f64::from(grid),
                (f64::from(i / grid) + 0.5 + 0.4 * (f64::from(i * 3 % 7) / 7.0 - 0.43)) / f64::from(grid),
            );
            let d = (camera.forward() + camera.right() * (2.0 * u - 1.0) * half + camera.up() * (2.0 * v - 1.0) * half)
                .normalize();
            let oc = eye - centre;
            let b = oc.dot(d);
            let t = -b - (b * b - (oc.length_squared() - radius * radius)).sqrt();
            let ground = eye + d * t;
            let towards_camera = cloud_transmittance(&reference, planet, ground, eye);
            let towards_sun = cloud_transmittance(&reference, planet, ground, ground + sun * 60_000.0);
            both += towards_camera * towards_sun;
            view_only += towards_camera;
            sun_only += towards_sun;
        }
        let n = f64::from(grid * grid);
        let (want, view_mean, sun_mean) = (both / n, view_only / n, sun_only / n);
        let error = kept / want - 1.0;
        println!(
            "view zenith {view_zenith}°: the image keeps {kept:.4} of the ground's light, the columns {want:.4} \
             (towards the camera {view_mean:.4}, the sun {sun_mean:.4}; cell {cell} m), error {:+.1} %",
            100.0 * error
        );
        assert!(
            error.abs() < 0.1,
            "view zenith {view_zenith}°: the image keeps {kept:.4} of the ground's light, the columns {want:.4}"
        );
    }
}
