//! Lens flares on the GPU against the core's geometry: the occlusion pass's visible share against
//! the covered share of the source's disc computed in `f64`, the flare's energy following it,
//! nothing drawn for hidden, behind-camera or far off-screen sources (and not a bit of the
//! others' light changed by them), every pixel of the procedural shapes against their formulas in
//! `f64`, element positions against NeHe's construction, and a sun half behind the planet's limb.

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
use firmament_render::gpu_types::flare::FLARE_NEGLIGIBLE;
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
        clouds: Vec::new(),
        eclipsers: Vec::new(),
        bodies: Vec::new(),
        rings: None,
        surface: None,
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

/// A light up and to the right, 1 m in radius, clear of the occluder at the centre.
fn side_light() -> FlareSource {
    FlareSource {
        position: DVec4::new(20.0, 8.0, -50.0, 1.0),
        radius: 1.0,
        color: DVec3::new(1.0, 0.8, 0.6),
    }
}

#[test]
fn a_hidden_source_changes_no_bit_of_the_others_light() {
    let mut gpu = support::gpu();
    let support::Gpu { ctx, renderer } = &mut *gpu;
    let mut render = |sources: Vec<FlareSource>| {
        let image = renderer
            .render_hdr(ctx, &frame(vec![occluder(0.0)], sources, flare(32)), WIDTH, HEIGHT)
            .expect("render");
        let visibility = renderer.flare_visibility(ctx).expect("visibility");
        (image.pixels, visibility)
    };
    let (alone, visibility) = render(vec![side_light()]);
    assert_eq!(visibility, [1.0]);
    assert!(alone.iter().any(|&c| c > 0.0), "the visible light drew nothing");
    // The centre light is behind the sphere, first or last in the list.
    for sources in [vec![light(), side_light()], vec![side_light(), light()]] {
        let hidden_first = sources[0] == light();
        let (both, visibility) = render(sources);
        assert_eq!(visibility, if hidden_first { [0.0, 1.0] } else { [1.0, 0.0] });
        let differing = alone
            .iter()
            .zip(&both)
            .filter(|(a, b)| a.to_bits() != b.to_bits())
            .count();
        assert_eq!(differing, 0, "the hidden light changed {differing} channels");
    }
}

/// What the quads drew before the flare became a compute pass: the light of one procedural
/// element at `uv` (units of its radius), per the shapes of `shaders/flare.wgsl`, in `f64`.
fn falloff(shape: FlareShape, uv: DVec2) -> f64 {
    let r = uv.length();
    let glow = (1.0 - r).max(0.0).powi(2);
    match shape {
        FlareShape::Glow => glow,
        FlareShape::Streaks {
            points,
            rotation,
            sharpness,
        } => {
            let a = uv.y.atan2(uv.x) - rotation.to_radians();
            (0.5 * f64::from(points) * a).cos().abs().powf(sharpness) * glow
        }
        FlareShape::Halo { thickness } => {
            let half_width = 0.5 * thickness;
            let t = (r - (1.0 - half_width)) / half_width;
            (1.0 - t * t).max(0.0)
        }
        FlareShape::Ghost {
            sides,
            rotation,
            softness,
        } => {
            let edge = if sides < 3 {
                r
            } else {
                let sector = std::f64::consts::TAU / f64::from(sides);
                let a = uv.y.atan2(uv.x) - rotation.to_radians();
                let local = a - sector * (a / sector).floor() - 0.5 * sector;
                r * local.cos() / (0.5 * sector).cos()
            };
            let x = ((edge - (1.0 - softness)) / softness).clamp(0.0, 1.0);
            1.0 - x * x * (3.0 - 2.0 * x)
        }
        FlareShape::Image { .. } => unreachable!("procedural shapes only"),
    }
}

/// Every pixel of two seen lights' flares — each procedural shape, round and stretched, near the
/// centre and past it, one light fading at the screen's edge, one element too faint to draw — is
/// the sum of the shapes' formulas in `f64`, as the quads drew it: within the HDR target's
/// half-float step, and within the light left out where each element is negligible.
#[test]
fn seen_elements_light_every_pixel_as_their_formulas_say() {
    let camera = camera();
    let streaks = FlareShape::Streaks {
        points: 6,
        rotation: 10.0,
        sharpness: 8.0,
    };
    let ghost = |sides| FlareShape::Ghost {
        sides,
        rotation: 15.0,
        softness: 0.3,
    };
    let shapes = LensFlare {
        elements: vec![
            FlareElement::new(FlareShape::Glow, [1.0, 0.9, 0.8], 0.8, 0.3, 0.0),
            FlareElement::new(streaks, [0.6, 0.7, 1.0], 0.5, 0.4, 0.0),
            FlareElement::new(FlareShape::Halo { thickness: 0.3 }, [0.9, 0.4, 0.3], 0.3, 0.25, 0.5),
            FlareElement::new(ghost(6), [0.3, 0.9, 0.5], 0.2, 0.15, 1.4),
            FlareElement::new(ghost(0), [0.8, 0.5, 1.0], 1e-4, 0.2, 1.8),
            FlareElement {
                stretch: 3.0,
                ..FlareElement::new(FlareShape::Glow, [0.4, 0.6, 1.0], 0.4, 0.1, 0.8)
            },
        ],
        margin: 0.5,
        ..flare(16)
    };
    // The second light's disc is past the left edge, inside the margin: it fades.
    let edge = FlareSource {
        position: DVec4::new(-30.0, -6.0, -50.0, 1.0),
        radius: 1.0,
        color: DVec3::new(0.5, 1.0, 0.7),
    };
    let fade = on_screen(&camera, &edge, shapes.margin)
        .expect("within the margin")
        .edge_fade;
    assert!(fade > 0.1 && fade < 0.9, "{fade}");
    let sources = vec![side_light(), edge];
    let positions: Vec<f64> = shapes.elements.iter().map(|e| e.position).collect();
    let placed: Vec<(DVec2, DVec3, &FlareElement)> = sources
        .iter()
        .flat_map(|source| {
            let at = on_screen(&camera, source, shapes.margin).expect("on screen");
            let centers = element_centers(&camera, source, &positions);
            shapes.elements.iter().zip(centers).map(move |(element, center)| {
                let color = element.color * source.color * element.intensity * at.edge_fade;
                (center.expect("placed"), color, element)
            })
        })
        .collect();
    assert!(
        placed.iter().any(|(_, c, _)| c.max_element() < FLARE_NEGLIGIBLE),
        "one element is faint enough to be left out"
    );
    let mut gpu = support::gpu();
    let support::Gpu { ctx, renderer } = &mut *gpu;
    // 1760 × 1320 has more 16-pixel bins than the pass keeps: its bins are 32 pixels wide.
    for (width, height) in [(WIDTH, HEIGHT), (1760, 1320)] {
        let image = renderer
            .render_hdr(ctx, &frame(vec![], sources.clone(), shapes.clone()), width, height)
            .expect("render");
        assert_eq!(renderer.flare_visibility(ctx).expect("visibility"), [1.0, 1.0]);
        let (mut worst, mut lit) = (0.0f64, 0);
        for y in 0..height {
            for x in 0..width {
                let ndc = DVec2::new(
                    (f64::from(x) + 0.5) / f64::from(width) * 2.0 - 1.0,
                    1.0 - (f64::from(y) + 0.5) / f64::from(height) * 2.0,
                );
                let expected: DVec3 = placed
                    .iter()
                    .map(|(center, color, element)| {
                        let d = ndc - *center;
                        let uv = DVec2::new(d.x * camera.aspect / element.stretch, d.y) / element.size;
                        *color * falloff(element.shape, uv)
                    })
                    .sum();
                let got = image.pixel(x, y).expect("inside");
                let got = DVec3::new(f64::from(got[0]), f64::from(got[1]), f64::from(got[2]));
                // Half-float rounding of the sum, and the elements' left-out tails: each under half
                // an 8-bit step where the sRGB curve is steepest (12.92 at black).
                let tails = placed.len() as f64 * 0.5 / (255.0 * 12.92);
                let allowed = expected * 2f64.powi(-10) + DVec3::splat(tails);
                worst = worst.max(((got - expected).abs() / allowed).max_element());
                if expected.max_element() > 1e-3 {
                    lit += 1;
                }
            }
        }
        println!("procedural shapes at {width}×{height}: {lit} lit pixels, worst error {worst:.3} of the allowance");
        assert!(lit > 2000 * (width / WIDTH).pow(2), "{lit}");
        assert!(worst <= 1.0, "worst {worst}");
    }
}
