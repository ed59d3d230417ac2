//! GPU tests of the sky and tonemap passes against the f64 core, on whatever adapter the machine
//! has (a software rasterizer on CI). They fail, never skip, when no adapter exists.

use crate::support::{self, Gpu, gpu};

use firmament_core::color::{LinearRgb, linear_to_srgb};
use firmament_core::display::{DisplaySettings, Exposure, ToneCurve};
use firmament_core::frame::Sky;
use firmament_core::sky::gradient::{Blend, DayCycle, GradientShape, GradientSkyState, SkyBands, SkyKeyframe};
use firmament_core::sky::sun::SunDisc;
use firmament_core::{Camera, Frame, TimeOfDay};
use firmament_render::FrameTargets;
use firmament_render::headless::Image;
use firmament_render::passes::GradientSkyPass;
use firmament_render::readback::read_texture;
use glam::{DVec2, DVec3};

fn rgb(r: f64, g: f64, b: f64) -> LinearRgb {
    LinearRgb::new(r, g, b)
}

fn test_bands() -> SkyBands {
    SkyBands {
        zenith: rgb(0.05, 0.15, 0.6),
        upper: rgb(0.2, 0.35, 0.8),
        horizon: rgb(0.9, 0.6, 0.3),
        lower: rgb(0.4, 0.3, 0.25),
        ground: rgb(0.1, 0.1, 0.08),
        sun: rgb(1.0, 0.9, 0.7),
    }
}

fn sky(bands: SkyBands, sun_intensity: f64) -> GradientSkyState {
    GradientSkyState {
        shape: GradientShape::default(),
        bands,
        sun: SunDisc {
            direction: SunDisc::direction_from(0.3, 0.2),
            angular_radius: 3f64.to_radians(),
            disc_radiance: bands.sun.scale(sun_intensity),
            glow_radiance: bands.sun.scale(0.2 * sun_intensity),
            glow_falloff: 10f64.to_radians(),
            edge_softness: 0.2,
        },
    }
}

fn frame(camera: Camera, sky: GradientSkyState, display: DisplaySettings) -> Frame {
    Frame {
        camera,
        sky: Sky::Gradient(sky),
        display,
        objects: Default::default(),
        flares: Default::default(),
        night: Default::default(),
    }
}

/// The view direction through the centre of pixel (x, y), y = 0 at the top.
fn pixel_direction(camera: &Camera, x: u32, y: u32, width: u32, height: u32) -> DVec3 {
    let ndc = DVec2::new(
        (f64::from(x) + 0.5) / f64::from(width) * 2.0 - 1.0,
        1.0 - (f64::from(y) + 0.5) / f64::from(height) * 2.0,
    );
    let camera = Camera {
        aspect: f64::from(width) / f64::from(height),
        ..*camera
    };
    camera.view_direction(ndc)
}

fn hdr_pixel(image: &Image<f32>, x: u32, y: u32) -> LinearRgb {
    let p = image.pixel(x, y).expect("inside");
    rgb(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

/// Largest difference, over every pixel, between the GPU's HDR image and the core's radiance.
fn max_hdr_error(image: &Image<f32>, frame: &Frame) -> (f64, (u32, u32)) {
    let mut worst = (0.0, (0, 0));
    for y in 0..image.height {
        for x in 0..image.width {
            let reference = frame
                .sky
                .gradient_radiance(pixel_direction(&frame.camera, x, y, image.width, image.height))
                .expect("a gradient sky");
            let err =
                hdr_pixel(image, x, y).max_abs_diff(reference) / reference.r.max(reference.g).max(reference.b).max(1.0);
            if err > worst.0 {
                worst = (err, (x, y));
            }
        }
    }
    worst
}

#[test]
fn every_hdr_pixel_matches_the_core_reference() {
    let mut gpu = gpu();
    let Gpu { ctx, renderer } = &mut *gpu;
    for (heading, pitch, fov) in [(0.0, 0.0, 90.0), (1.0, 40.0, 120.0), (4.0, -50.0, 60.0)] {
        for blend in [Blend::Smooth, Blend::Linear] {
            let camera = Camera {
                fov_y: f64::to_radians(fov),
                ..Camera::from_heading_pitch(DVec3::new(0.0, 0.0, 2.0), heading, f64::to_radians(pitch))
            };
            let mut sky = sky(test_bands(), 3.0);
            sky.shape.blend = blend;
            let frame = frame(camera, sky, DisplaySettings::default());
            let image = renderer.render_hdr(ctx, &frame, 48, 36).expect("render");
            let (err, at) = max_hdr_error(&image, &frame);
            // Half floats hold 11 significant bits; 1/255 is the bar for band colours.
            assert!(
                err < 1.0 / 255.0,
                "heading {heading} pitch {pitch} {blend:?}: error {err} at {at:?}"
            );
        }
    }
}

#[test]
fn zenith_horizon_and_ground_pixels_equal_the_band_colours() {
    let mut gpu = gpu();
    let Gpu { ctx, renderer } = &mut *gpu;
    let bands = test_bands();
    // Odd sizes put a pixel centre exactly on the view axis.
    for (pitch, expected) in [(90.0, bands.zenith), (0.0, bands.horizon), (-90.0, bands.ground)] {
        let camera = Camera::from_heading_pitch(DVec3::ZERO, 0.0, f64::to_radians(pitch));
        let frame = frame(camera, sky(bands, 0.0), DisplaySettings::default());
        let image = renderer.render_hdr(ctx, &frame, 33, 33).expect("render");
        let got = hdr_pixel(&image, 16, 16);
        assert!(
            got.max_abs_diff(expected) < 1.0 / 255.0,
            "pitch {pitch}: {got:?} vs {expected:?}"
        );
    }
}

#[test]
fn keyframes_are_continuous_across_midnight_on_the_gpu() {
    let mut gpu = gpu();
    let Gpu { ctx, renderer } = &mut *gpu;
    let key = |h: f64, v: f64| SkyKeyframe {
        time: TimeOfDay::from_hours(h).expect("finite"),
        bands: SkyBands {
            zenith: rgb(v, v, v),
            ..test_bands()
        },
    };
    let cycle = DayCycle::new(vec![key(21.0, 0.1), key(3.0, 0.5), key(12.0, 0.9)], Blend::Smooth).expect("valid");
    let camera = Camera::from_heading_pitch(DVec3::ZERO, 0.0, f64::to_radians(90.0));
    let mut zenith_at = |seconds: f64| {
        let bands = cycle.bands_at(TimeOfDay::from_seconds(seconds).expect("finite"));
        let image = renderer
            .render_hdr(ctx, &frame(camera, sky(bands, 0.0), DisplaySettings::default()), 9, 9)
            .expect("render");
        hdr_pixel(&image, 4, 4).r
    };
    let before = zenith_at(86_399.0);
    let after = zenith_at(0.0);
    let later = zenith_at(60.0);
    assert!((before - after).abs() < 1e-3, "pop at midnight: {before} → {after}");
    assert!(
        after < later && later < 0.5,
        "not moving towards 03:00: {after} → {later}"
    );
}

#[test]
fn the_sky_stays_behind_everything_already_drawn() {
    let gpu = gpu();
    let ctx = &gpu.ctx;
    let pass = GradientSkyPass::new(&ctx.device);
    let camera = Camera::default();
    pass.prepare(&ctx.queue, &sky(test_bands(), 0.0), &camera);
    let targets = FrameTargets::new(&ctx.device, 16, 8);
    let marker = wgpu::Color {
        r: 0.0,
        g: 1.0,
        b: 0.0,
        a: 1.0,
    };
    // Depth 0 is the far plane (nothing drawn): the sky fills. Depth 0.5: something is in front.
    for (depth, expect_sky) in [(0.0, true), (0.5, false), (1e-6, false)] {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("test") });
        support::clear_targets(&mut encoder, &targets, marker, depth);
        pass.record(&mut encoder, &targets.hdr_view, &targets.depth_view);
        ctx.queue.submit([encoder.finish()]);
        let bytes = read_texture(ctx, &targets.hdr).expect("readback");
        let green: Vec<f32> = bytes
            .chunks_exact(8)
            .map(|p| half::f16::from_le_bytes([p[2], p[3]]).to_f32())
            .collect();
        let all_marker = green.iter().all(|g| *g == 1.0);
        assert_eq!(!all_marker, expect_sky, "depth {depth}");
    }
}

#[test]
fn odd_sizes_read_back_correctly_through_every_tone_curve() {
    let mut gpu = gpu();
    let Gpu { ctx, renderer } = &mut *gpu;
    let camera = Camera {
        fov_y: 1.2,
        ..Camera::from_heading_pitch(DVec3::ZERO, 0.5, 0.3)
    };
    // Bright bands so the curves do real work.
    let bright = SkyBands {
        zenith: rgb(0.4, 1.5, 4.0),
        horizon: rgb(6.0, 3.0, 0.5),
        ..test_bands()
    };
    for curve in ToneCurve::ALL {
        let display = DisplaySettings {
            exposure: Exposure::multiplier(0.8),
            tone_curve: curve,
            ..Default::default()
        };
        let frame = frame(camera, sky(bright, 2.0), display);
        let (w, h) = (333, 71);
        let image = renderer.render_ldr(ctx, &frame, w, h).expect("render");
        assert_eq!(image.pixels.len(), (w * h * 4) as usize);
        let mut worst = 0i32;
        for y in (0..h).step_by(5) {
            for x in (0..w).step_by(7) {
                let radiance = frame
                    .sky
                    .gradient_radiance(pixel_direction(&camera, x, y, w, h))
                    .expect("a gradient sky");
                let display = display.display_linear(radiance);
                let expected = display.to_array().map(|c| (linear_to_srgb(c) * 255.0).round() as i32);
                let got = image.pixel(x, y).expect("inside");
                for c in 0..3 {
                    worst = worst.max((i32::from(got[c]) - expected[c]).abs());
                }
                assert_eq!(got[3], 255);
            }
        }
        // One code value for rounding, one for f16 storage and f32 maths on the GPU.
        assert!(worst <= 2, "{curve:?}: worst difference {worst} code values");
    }
}

#[test]
fn too_large_images_are_refused_with_the_limit() {
    let mut gpu = gpu();
    let Gpu { ctx, renderer } = &mut *gpu;
    let max = ctx.max_image_side();
    let frame = frame(Camera::default(), sky(test_bands(), 0.0), DisplaySettings::default());
    let err = renderer.render_ldr(ctx, &frame, max + 1, 4).expect_err("too large");
    assert!(err.to_string().contains(&max.to_string()), "{err}");
    assert!(renderer.render_ldr(ctx, &frame, 0, 4).is_err());
    // The readback buffer is checked before rendering, against the device's own limit.
    let side = max.min(16_384);
    let needed = u64::from(firmament_render::readback::padded_bytes_per_row(side, 8)) * u64::from(side);
    let result = firmament_render::readback::check_readback(ctx, side, side, firmament_render::HDR_FORMAT);
    if needed > ctx.device.limits().max_buffer_size {
        let err = result.expect_err("over the buffer limit");
        assert!(err.to_string().contains("this GPU allows"), "{err}");
    } else {
        assert_eq!(result.ok(), Some(needed));
    }
}
