//! Per-pass GPU timing (`Renderer::enable_pass_timing`): on where the device has timestamps inside
//! encoders and off elsewhere, never changing a pixel of `record` or `record_into`, and — where
//! supported — bringing back finite, non-negative times of the phases each frame ran, also after
//! encoders that were dropped unsubmitted.

use crate::support;

use firmament_core::{DepthConvention, Frame};
use firmament_render::pass_timing::{
    PHASE_AERIAL_PERSPECTIVE, PHASE_CLOUDS, PHASE_FLARES, PHASE_LUTS, PHASE_SKY_AND_OBJECTS, PHASE_TONEMAP, PHASES,
};
use firmament_render::readback::read_texture;
use firmament_render::{EmbedTarget, FrameTargets, GpuContext, PassTimes, Renderer, pass_timing_supported, wgpu};

/// Tiny: llvmpipe is slow.
const WIDTH: u32 = 32;
const HEIGHT: u32 = 18;
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// A gradient sky; an atmosphere with objects and aerial perspective; lens flares.
const PRESETS: [&str; 3] = ["default", "earth-objects", "nehe-flare"];

fn preset_frame(name: &str) -> Frame {
    firmament_scene::load(firmament_scene::SceneSource::Preset(name), None, &[])
        .and_then(|scene| scene.frame_at(None))
        .unwrap_or_else(|e| panic!("preset `{name}`: {e}"))
}

fn output_texture(ctx: &GpuContext) -> wgpu::Texture {
    ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("pass_timing test output"),
        size: wgpu::Extent3d {
            width: WIDTH,
            height: HEIGHT,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

/// Runs `f` and fails the test on any validation or out-of-memory error it raised.
fn checked<T>(ctx: &GpuContext, what: &str, f: impl FnOnce() -> T) -> T {
    let validation = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let oom = ctx.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let value = f();
    if let Some(error) = pollster::block_on(oom.pop()) {
        panic!("{what}: {error}");
    }
    if let Some(error) = pollster::block_on(validation.pop()) {
        panic!("{what}: {error}");
    }
    value
}

/// Prepares and records `frame` into `output` and submits it; the 8-bit image.
fn render(ctx: &GpuContext, renderer: &mut Renderer, frame: &Frame, output: &wgpu::Texture) -> Vec<u8> {
    checked(ctx, "record", || {
        renderer.prepare(ctx, frame, WIDTH, HEIGHT).expect("prepare");
        let view = output.create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("pass_timing test encoder"),
        });
        renderer.record(&mut encoder, &view);
        ctx.queue.submit([encoder.finish()]);
    });
    read_texture(ctx, output).expect("read back the output")
}

/// Clears `targets` (black, reversed-Z far plane: no geometry), prepares and records `frame` into
/// them with `record_into` and submits it; the HDR bytes.
fn render_into(ctx: &GpuContext, renderer: &mut Renderer, frame: &Frame, targets: &FrameTargets) -> Vec<u8> {
    checked(ctx, "record_into", || {
        let target = EmbedTarget::new(&targets.hdr_view, &targets.depth_view, DepthConvention::Reversed);
        renderer.prepare_into(ctx, frame, &target).expect("prepare_into");
        let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("pass_timing test encoder"),
        });
        support::clear_targets(&mut encoder, targets, wgpu::Color::BLACK, 0.0);
        renderer.record_into(&mut encoder, &target).expect("record_into");
        ctx.queue.submit([encoder.finish()]);
    });
    read_texture(ctx, &targets.hdr).expect("read back the HDR target")
}

/// Blocks until the GPU is idle, then asks for the times a few times.
fn wait_for_times(ctx: &GpuContext, renderer: &Renderer) -> Option<PassTimes> {
    (0..5).find_map(|_| {
        ctx.device
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("device idle");
        renderer.pass_times(ctx)
    })
}

/// Every phase of `times` is one of `PHASES`, in their order, with a finite non-negative time.
fn check_times(times: &PassTimes, expected: &[&str], what: &str) {
    let names: Vec<&str> = times.phases.iter().map(|p| p.name).collect();
    assert_eq!(names, expected, "{what}: the phases timed");
    let order: Vec<usize> = names
        .iter()
        .map(|name| PHASES.iter().position(|p| p == name).expect("a known phase"))
        .collect();
    assert!(order.is_sorted(), "{what}: phases out of order: {names:?}");
    for phase in &times.phases {
        assert!(
            phase.milliseconds.is_finite() && phase.milliseconds >= 0.0,
            "{what}: phase `{}` took {} ms",
            phase.name,
            phase.milliseconds
        );
    }
    assert!(times.total_ms().is_finite() && times.total_ms() >= 0.0);
}

#[test]
fn enabling_follows_the_device_and_defaults_off() {
    let gpu = support::gpu();
    let ctx = &gpu.ctx;
    let supported = pass_timing_supported(&ctx.device);
    eprintln!(
        "{}: per-pass GPU timing {}",
        ctx.adapter_summary(),
        if supported { "supported" } else { "unsupported" }
    );
    let mut renderer = Renderer::new(ctx, FORMAT);
    assert!(!renderer.pass_timing_enabled(), "timing is off by default");
    assert_eq!(renderer.pass_times(ctx), None);
    assert_eq!(renderer.enable_pass_timing(ctx), supported);
    assert_eq!(renderer.pass_timing_enabled(), supported);
    // Enabling twice keeps what there is.
    assert_eq!(renderer.enable_pass_timing(ctx), supported);
    renderer.disable_pass_timing();
    assert!(!renderer.pass_timing_enabled());
    assert_eq!(renderer.pass_times(ctx), None);
}

#[test]
fn enabling_is_refused_on_a_device_without_timestamps() {
    // The shared context's device, asked for again without the optional timestamp features.
    let _gpu = support::gpu();
    let ctx = support::user_context("pass_timing test device without timestamps");
    assert!(!pass_timing_supported(&ctx.device));
    let mut renderer = Renderer::new(&ctx, FORMAT);
    assert!(!renderer.enable_pass_timing(&ctx), "no timestamps: timing stays off");
    assert!(!renderer.pass_timing_enabled());
    let output = output_texture(&ctx);
    let image = render(&ctx, &mut renderer, &preset_frame("earth-objects"), &output);
    assert!(image.iter().any(|&c| c > 0));
    assert_eq!(wait_for_times(&ctx, &renderer), None);
}

#[test]
fn timing_changes_no_pixel() {
    let gpu = support::gpu();
    let ctx = &gpu.ctx;
    let mut plain = Renderer::new(ctx, FORMAT);
    let mut timed = Renderer::new(ctx, FORMAT);
    let supported = timed.enable_pass_timing(ctx);
    let output = output_texture(ctx);
    let targets = FrameTargets::new(&ctx.device, WIDTH, HEIGHT);
    for name in PRESETS {
        let frame = preset_frame(name);
        for i in 0..3 {
            let expected = render(ctx, &mut plain, &frame, &output);
            assert!(
                expected.iter().any(|&c| c > 0),
                "preset `{name}` rendered black: the comparison would prove nothing"
            );
            let got = render(ctx, &mut timed, &frame, &output);
            assert!(expected == got, "preset `{name}`, frame {i}: timing changed the image");

            let expected = render_into(ctx, &mut plain, &frame, &targets);
            let got = render_into(ctx, &mut timed, &frame, &targets);
            assert!(
                expected == got,
                "preset `{name}`, frame {i}: timing changed the record_into image"
            );
        }
        // Collecting the times (or finding none) changes nothing either.
        let times = wait_for_times(ctx, &timed);
        assert_eq!(times.is_some(), supported, "preset `{name}`: times iff supported");
    }
}

#[test]
fn supported_timing_brings_back_every_phase() {
    let gpu = support::gpu();
    let ctx = &gpu.ctx;
    let mut renderer = Renderer::new(ctx, FORMAT);
    if !renderer.enable_pass_timing(ctx) {
        assert!(!pass_timing_supported(&ctx.device));
        // Rendering with timing asked for but unavailable works and reports nothing.
        let output = output_texture(ctx);
        render(ctx, &mut renderer, &preset_frame("earth-objects"), &output);
        assert_eq!(wait_for_times(ctx, &renderer), None);
        eprintln!(
            "{}: no timestamps inside encoders; timing stays off",
            ctx.adapter_summary()
        );
        return;
    }
    let output = output_texture(ctx);

    // The showcase, an atmosphere with objects, auto-exposure and bloom: every phase of `record`
    // but the clouds.
    let showcase: Vec<&str> = PHASES.into_iter().filter(|p| *p != PHASE_CLOUDS).collect();
    let frame = preset_frame("golden-hour");
    for _ in 0..3 {
        render(ctx, &mut renderer, &frame, &output);
    }
    let times = wait_for_times(ctx, &renderer).expect("times after a blocking poll");
    check_times(&times, &showcase, "golden-hour");
    eprintln!("{}: golden-hour at {WIDTH}x{HEIGHT}: {times:?}", ctx.adapter_summary());

    // Clouds, without objects: their phase builds the aerial-perspective volume too.
    render(ctx, &mut renderer, &preset_frame("earth-clouds"), &output);
    let times = wait_for_times(ctx, &renderer).expect("times after a blocking poll");
    assert!(
        times.phases.iter().any(|p| p.name == PHASE_CLOUDS),
        "earth-clouds: the clouds are timed: {times:?}"
    );

    // A gradient sky: no LUTs, no aerial perspective.
    let frame = preset_frame("default");
    render(ctx, &mut renderer, &frame, &output);
    let times = wait_for_times(ctx, &renderer).expect("times after a blocking poll");
    check_times(&times, &[PHASE_SKY_AND_OBJECTS, PHASE_FLARES, PHASE_TONEMAP], "default");

    // `record_into` an atmosphere: no tonemap.
    let targets = FrameTargets::new(&ctx.device, WIDTH, HEIGHT);
    render_into(ctx, &mut renderer, &preset_frame("earth-noon"), &targets);
    let times = wait_for_times(ctx, &renderer).expect("times after a blocking poll");
    check_times(
        &times,
        &[
            PHASE_LUTS,
            PHASE_SKY_AND_OBJECTS,
            PHASE_AERIAL_PERSPECTIVE,
            PHASE_FLARES,
        ],
        "record_into earth-noon",
    );

    // Encoders dropped unsubmitted (more of them than read-back buffers) give their buffers back.
    renderer.prepare(ctx, &frame, WIDTH, HEIGHT).expect("prepare");
    let view = output.create_view(&wgpu::TextureViewDescriptor::default());
    for _ in 0..8 {
        let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("pass_timing test dropped encoder"),
        });
        renderer.record(&mut encoder, &view);
        drop(encoder);
    }
    // Frames submitted but never collected fill the ring; collecting frees it again.
    for _ in 0..8 {
        render(ctx, &mut renderer, &frame, &output);
    }
    let before = wait_for_times(ctx, &renderer).expect("times after a blocking poll");
    render(ctx, &mut renderer, &preset_frame("golden-hour"), &output);
    let after = wait_for_times(ctx, &renderer).expect("times after a blocking poll");
    check_times(
        &before,
        &[PHASE_SKY_AND_OBJECTS, PHASE_FLARES, PHASE_TONEMAP],
        "default again",
    );
    check_times(&after, &showcase, "golden-hour after dropped encoders");
}
