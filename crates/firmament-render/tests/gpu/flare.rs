//! Lens flares on the GPU against the core's geometry: the occlusion pass's visible share against
//! the covered share of the source's disc computed in `f64`, the flare's energy following it,
//! nothing drawn for hidden, behind-camera or far off-screen sources, element positions against
//! NeHe's construction, and a sun half behind the planet's limb.

use crate::support;

use std::sync::Arc;

use firmament_core::classic::lighting::Material;
use firmament_core::classic::mesh::Mesh;
use firmament_core::classic::scene::{ObjectLayer, SceneObject};
use firmament_core::color::LinearRgb;
use firmament_core::display::{DisplaySettings, Exposure, ToneCurve};
use firmament_core::flare::{FlareElement, FlareLayer, FlareShape, FlareSource, LensFlare, element_centers, on_screen};
use firmament_core::frame::{AtmosphereSky, Sky};
use firmament_core::geometry::{Ray, Sphere};
use firmament_core::{Camera, Frame};
use glam::{DMat4, DVec2, DVec3, DVec4};

const WIDTH: u32 = 160;
const HEIGHT: u32 = 120;

/// At the origin looking down −z, 45° like NeHe's lesson.
fn camera() -> Camera {
    crate::support::origin_camera_45(WIDTH, HEIGHT)
}

/// A light 50 m ahead, 8 m in radius (a disc of about 23 pixels' radius).
fn light() -> FlareSource {
    FlareSource {
        position: DVec4::new(0.0, 0.0, -50.0, 1.0),
        radius: 8.0,
        color: DVec3::ONE,
    }
}

fn flare(samples: u32) -> LensFlare {
    LensFlare {
        samples,
        ..LensFlare::classic()
    }
}

/// A black occluding sphere of radius 4 m at (x, 0, −20).
fn occluder(x: f64) -> SceneObject {
    let mesh = Arc::new(Mesh::glt_sphere(4.0, 96, 48).expect("valid sphere"));
    let black = Material {
        diffuse: DVec4::new(0.0, 0.0, 0.0, 1.0),
        ..Material::default()
    };
    SceneObject::new(mesh, DMat4::from_translation(DVec3::new(x, 0.0, -20.0)), black)
}

fn frame(objects: Vec<SceneObject>, sources: Vec<FlareSource>, flare: LensFlare) -> Frame {
    Frame {
        camera: camera(),
        sky: Sky::Clear(LinearRgb::new(0.0, 0.0, 0.0)),
        display: DisplaySettings {
            exposure: Exposure::multiplier(1.0),
            tone_curve: ToneCurve::None,
            ..DisplaySettings::default()
        },
        objects: ObjectLayer {
            objects,
            ..ObjectLayer::default()
        },
        flares: FlareLayer {
            flare: Some(flare),
            sources,
        },
        night: Default::default(),
    }
}

/// The HDR image's summed RGB and the GPU's visibility per kept source.
fn render(frame: &Frame) -> (f64, f32, Vec<f32>) {
    let mut gpu = support::gpu();
    let support::Gpu { ctx, renderer } = &mut *gpu;
    let image = renderer.render_hdr(ctx, frame, WIDTH, HEIGHT).expect("render");
    let visibility = renderer.flare_visibility(ctx).expect("visibility");
    let energy = image
        .pixels
        .chunks_exact(4)
        .map(|p| f64::from(p[0] + p[1] + p[2]))
        .sum();
    let brightest = image
        .pixels
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .fold(0.0, f32::max);
    (energy, brightest, visibility)
}

/// The share of the light's disc the sphere at x leaves uncovered, from a fine grid in `f64`.
fn uncovered_share(x: f64) -> f64 {
    let camera = camera();
    let at = on_screen(&camera, &light(), 0.0).expect("on screen");
    let sphere = Sphere {
        center: DVec3::new(x, 0.0, -20.0),
        radius: 4.0,
    };
    let n = 400;
    let (mut inside, mut seen) = (0, 0);
    for i in 0..n {
        for j in 0..n {
            let u = DVec2::new(f64::from(i) + 0.5, f64::from(j) + 0.5) / f64::from(n) * 2.0 - 1.0;
            if u.length() > 1.0 {
                continue;
            }
            inside += 1;
            let ray = Ray::new(DVec3::ZERO, camera.view_direction(at.center + u * at.disc)).expect("ray");
            if sphere.intersect(&ray).is_none_or(|h| h.far < 0.0) {
                seen += 1;
            }
        }
    }
    f64::from(seen) / f64::from(inside)
}

#[test]
fn a_sphere_sliding_over_the_light_dims_its_flare_smoothly() {
    let samples = 64;
    let (full_energy, _, full) = render(&frame(vec![], vec![light()], flare(samples)));
    assert_eq!(full, [1.0]);
    assert!(full_energy > 0.0);
    let mut previous = 1.0f32;
    for step in 0..=10 {
        let x = -12.0 + 1.2 * f64::from(step);
        let (energy, _, visibility) = render(&frame(vec![occluder(x)], vec![light()], flare(samples)));
        let v = visibility[0];
        let expected = uncovered_share(x);
        println!(
            "x = {x:6.2}: GPU visible {v:.4}, covered share leaves {expected:.4}, energy ratio {:.4}",
            energy / full_energy
        );
        assert!(
            v <= previous + 1e-6,
            "visibility rose from {previous} to {v} at x = {x}"
        );
        previous = v;
        let tolerance = 1.0 / f64::from(samples) + 0.02;
        assert!(
            (f64::from(v) - expected).abs() <= tolerance,
            "x = {x}: {v} vs {expected}"
        );
        // The flare's light follows the visibility (the occluder itself is black).
        assert!(
            (energy / full_energy - f64::from(v)).abs() < 0.01,
            "x = {x}: energy ratio {} vs visibility {v}",
            energy / full_energy
        );
    }
    assert_eq!(previous, 0.0, "the sphere ends covering the whole disc");
}

#[test]
fn a_viewer_s_flare_fades_at_its_rates() {
    let smooth = LensFlare {
        fade_in: 4.0,
        fade_out: 2.0,
        ..flare(32)
    };
    let mut gpu = support::gpu();
    let support::Gpu { ctx, renderer } = &mut *gpu;
    let mut visibility_after = |objects: Vec<SceneObject>, interval: Option<f64>| {
        renderer.set_flare_interval(interval);
        let frame = frame(objects, vec![light()], smooth.clone());
        renderer.render_hdr(ctx, &frame, WIDTH, HEIGHT).expect("render");
        renderer.set_flare_interval(None);
        renderer.flare_visibility(ctx).expect("visibility")[0]
    };
    // A still takes the visible share at once; then frames 0.1 s apart move towards the new
    // share by at most 2/s down and 4/s up.
    assert_eq!(visibility_after(vec![], None), 1.0);
    let down: Vec<f32> = (0..3)
        .map(|_| visibility_after(vec![occluder(0.0)], Some(0.1)))
        .collect();
    let up: Vec<f32> = (0..2).map(|_| visibility_after(vec![], Some(0.1))).collect();
    for (got, want) in down.iter().chain(&up).zip([0.8, 0.6, 0.4, 0.8, 1.0]) {
        assert!((got - want).abs() < 1e-5, "{down:?} then {up:?}");
    }
}

#[test]
fn hidden_behind_or_far_off_screen_sources_draw_nothing() {
    // Fully hidden.
    let (energy, brightest, visibility) = render(&frame(vec![occluder(0.0)], vec![light()], flare(32)));
    assert_eq!(visibility, [0.0]);
    assert_eq!((energy, brightest), (0.0, 0.0));
    // Behind the camera.
    let behind = FlareSource {
        position: DVec4::new(0.0, 0.0, 50.0, 1.0),
        ..light()
    };
    let (energy, _, visibility) = render(&frame(vec![], vec![behind], flare(32)));
    assert!(visibility.is_empty());
    assert_eq!(energy, 0.0);
    // Past the right edge by more than the margin (and its disc).
    let off = FlareSource {
        position: DVec4::new(80.0, 0.0, -50.0, 1.0),
        ..light()
    };
    let (energy, _, visibility) = render(&frame(vec![], vec![off], flare(32)));
    assert!(visibility.is_empty());
    assert_eq!(energy, 0.0);
}

#[test]
fn elements_sit_where_nehe_s_construction_puts_them() {
    let camera = camera();
    let source = FlareSource {
        position: DVec4::new(9.0, 6.0, -50.0, 1.0),
        ..light()
    };
    for position in [0.0, 0.4, 1.0, 1.6] {
        let glow = LensFlare {
            elements: vec![FlareElement::new(
                FlareShape::Glow,
                [1.0, 1.0, 1.0],
                1.0,
                0.12,
                position,
            )],
            ..flare(16)
        };
        let mut gpu = support::gpu();
        let support::Gpu { ctx, renderer } = &mut *gpu;
        let image = renderer
            .render_hdr(ctx, &frame(vec![], vec![source], glow), WIDTH, HEIGHT)
            .expect("render");
        let (mut sum, mut weight) = (DVec2::ZERO, 0.0);
        for y in 0..HEIGHT {
            for x in 0..WIDTH {
                let w = f64::from(image.pixel(x, y).expect("inside")[0]);
                sum += DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5) * w;
                weight += w;
            }
        }
        let centroid = sum / weight;
        let ndc = element_centers(&camera, &source, &[position])[0].expect("placed");
        let expected = DVec2::new(
            (ndc.x + 1.0) / 2.0 * f64::from(WIDTH),
            (1.0 - ndc.y) / 2.0 * f64::from(HEIGHT),
        );
        println!("position {position}: centroid {centroid}, NeHe {expected}");
        assert!(
            (centroid - expected).length() < 0.25,
            "{position}: {centroid} vs {expected}"
        );
    }
}

/// A 256² picture whose red rises left to right, green bottom to top, blue a constant half.
fn ramp_picture() -> firmament_core::texture::TextureImage {
    let side = firmament_core::flare::FLARE_IMAGE_SIDE;
    let texels = (0..side)
        .flat_map(|t| (0..side).map(move |s| [s as u8, t as u8, 128, 255]))
        .collect();
    firmament_core::texture::TextureImage {
        width: side,
        height: side,
        texels,
    }
}

/// An image element is its picture over the element's quad: every pixel's HDR value equals the
/// element colour times the texel the f64 geometry puts there (a linear ramp, so bilinear
/// filtering and box-filtered mip levels give the ramp's value at that point), upright, and
/// turned by `rotation`.
#[test]
fn image_elements_draw_their_picture_upright_and_turned() {
    let camera = camera();
    let radius = 0.5; // half the screen height: 30 px on a 120 px image
    let color = DVec3::new(2.0, 1.0, 0.5);
    for rotation in [0.0, 90.0] {
        let mut picture_flare = LensFlare {
            elements: vec![FlareElement::new(
                FlareShape::Image { image: 0, rotation },
                color.to_array(),
                1.0,
                radius,
                0.0,
            )],
            ..flare(16)
        };
        picture_flare.images = vec![Arc::new(ramp_picture())];
        let mut gpu = support::gpu();
        let support::Gpu { ctx, renderer } = &mut *gpu;
        let image = renderer
            .render_hdr(ctx, &frame(vec![], vec![light()], picture_flare), WIDTH, HEIGHT)
            .expect("render");
        let center = on_screen(&camera, &light(), 0.0).expect("on screen").center;
        let (turn_sin, turn_cos) = f64::to_radians(rotation).sin_cos();
        let mut worst: f64 = 0.0;
        let mut checked = 0;
        for y in 0..HEIGHT {
            for x in 0..WIDTH {
                let ndc = DVec2::new(
                    (f64::from(x) + 0.5) / f64::from(WIDTH) * 2.0 - 1.0,
                    1.0 - (f64::from(y) + 0.5) / f64::from(HEIGHT) * 2.0,
                );
                // The quad's uv: radius in units of half the height, divided by the aspect in x.
                let uv = DVec2::new((ndc.x - center.x) * camera.aspect, ndc.y - center.y) / radius;
                // The picture's own coordinates: uv turned back by the rotation.
                let turned = DVec2::new(turn_cos * uv.x + turn_sin * uv.y, -turn_sin * uv.x + turn_cos * uv.y);
                let st = turned * 0.5 + 0.5;
                // Away from the edges, where a pixel straddles the quad's border.
                if st.min_element() < 0.05 || st.max_element() > 0.95 {
                    continue;
                }
                // Texel k holds k / 255 and sits at s = (k + 0.5) / 256.
                let ramp = |s: f64| ((s * 256.0 - 0.5) / 255.0).clamp(0.0, 1.0);
                let expected = color * DVec3::new(ramp(st.x), ramp(st.y), 128.0 / 255.0);
                let got = image.pixel(x, y).expect("inside");
                let got = DVec3::new(f64::from(got[0]), f64::from(got[1]), f64::from(got[2]));
                worst = worst.max(((got - expected) / color).abs().max_element());
                checked += 1;
            }
        }
        println!("image element, rotation {rotation}°: {checked} pixels, worst {worst:.2e} of the colour");
        assert!(checked > 1500, "{checked}");
        assert!(worst < 3.0 / 255.0, "rotation {rotation}: worst {worst}");
    }
}

#[test]
fn a_sun_on_the_horizon_is_half_hidden_by_the_planet() {
    let mut earth = firmament_core::atmosphere::presets::earth();
    earth.planet = earth.planet.posed_at(40f64.to_radians(), 0.0);
    // 2 m up, looking north at the horizon; the sun's centre on the geometric horizon.
    let height = 2.0;
    let dip = (2.0 * height / earth.planet.radii.x).sqrt();
    let sun_direction = DVec3::new(0.0, dip.cos(), -dip.sin());
    let sky = AtmosphereSky {
        atmosphere: earth,
        suns: vec![firmament_core::atmosphere::presets::earth_sun(sun_direction)],
    };
    let camera = Camera::from_heading_pitch(DVec3::new(0.0, 0.0, height), 0.0, 0.0);
    let sun = FlareSource {
        position: sun_direction.extend(0.0),
        radius: sky.suns[0].angular_radius,
        color: DVec3::ONE,
    };
    let samples = 128;
    let mut frame = frame(vec![], vec![sun], flare(samples));
    frame.camera = Camera {
        fov_y: 5f64.to_radians(),
        aspect: f64::from(WIDTH) / f64::from(HEIGHT),
        ..camera
    };
    frame.sky = Sky::Atmosphere(sky.clone());
    let (_, _, visibility) = render(&frame);
    // The f64 statement: the same samples, hidden where the ray meets the ellipsoid.
    let at = on_screen(&frame.camera, &sun, 0.0).expect("on screen");
    let planet = &sky.atmosphere.planet;
    let expected = firmament_core::flare::visible_fraction(at.center, at.disc, samples, |p| {
        let ray = Ray::new(frame.camera.position, frame.camera.view_direction(p)).expect("ray");
        planet
            .surface()
            .intersect(&planet.ray_to_planet_frame(&ray))
            .is_some_and(|h| h.far > 0.0)
    });
    println!("sun on the horizon: GPU {visibility:?}, f64 {expected}");
    assert!((expected - 0.5).abs() < 0.1, "{expected}");
    assert!(
        (f64::from(visibility[0]) - expected).abs() <= 1.0 / f64::from(samples) + 0.02,
        "{visibility:?} vs {expected}"
    );
}
