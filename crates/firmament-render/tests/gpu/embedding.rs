//! Bring your own device: a renderer made from a device this test creates with
//! `required_features()` and `required_limits()` renders the same bytes as the CLI's
//! `GpuContext::headless` path, every preset renders on a device with exactly those limits, and a
//! device below them is refused with the limit named — never a wgpu validation panic.

use crate::support;

use std::sync::{Arc, Mutex};

use firmament_core::Frame;
use firmament_render::headless::HeadlessRenderer;
use firmament_render::{Backend, GpuContext, RenderError, wgpu};

/// The adapter `GpuContext::headless(Backend::Auto)` picks, found the way an embedder would.
fn adapter() -> wgpu::Adapter {
    let instance = wgpu::Instance::default();
    pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        ..Default::default()
    }))
    .unwrap_or_else(|e| panic!("GPU tests need an adapter and found none: {e}"))
}

/// A device of `adapter` with firmament's features and `limits`.
fn device(adapter: &wgpu::Adapter, limits: wgpu::Limits) -> (wgpu::Device, wgpu::Queue) {
    pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("gpu_embedding test device"),
        required_features: firmament_render::required_features(),
        required_limits: limits,
        ..Default::default()
    }))
    .unwrap_or_else(|e| panic!("the adapter refused a device with limits it offers: {e}"))
}

/// A device with exactly `required_limits()` whose validation errors are collected instead of
/// panicking, so that a shortfall fails the test with wgpu's message.
fn device_at_required_limits() -> (GpuContext, Arc<Mutex<Vec<String>>>) {
    let (device, queue) = device(&adapter(), firmament_render::required_limits());
    let errors = Arc::new(Mutex::new(Vec::new()));
    let sink = Arc::clone(&errors);
    device.on_uncaptured_error(Arc::new(move |error| {
        sink.lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
            .push(error.to_string());
    }));
    let ctx = GpuContext::from_device(device, queue).expect("a device at required_limits() is accepted");
    (ctx, errors)
}

fn preset_frame(name: &str) -> Frame {
    firmament_scene::load(firmament_scene::SceneSource::Preset(name), None, &[])
        .and_then(|scene| scene.frame_at(None))
        .unwrap_or_else(|e| panic!("preset `{name}`: {e}"))
}

#[test]
fn embedded_device_renders_the_same_bytes_as_the_headless_context() {
    let _gpu = support::gpu();
    let headless = GpuContext::headless(Backend::Auto).expect("GPU tests need an adapter");
    let adapter = adapter();
    let (device, queue) = device(&adapter, firmament_render::required_limits());
    // The caller keeps its own handles: the context shares the device, it does not take it.
    let embedded = GpuContext::from_device(device.clone(), queue.clone()).expect("device meets the requirements");
    assert_eq!(embedded.device.adapter_info(), headless.device.adapter_info());
    assert_eq!(embedded.device.limits(), firmament_render::required_limits());

    let mut from_headless = HeadlessRenderer::new(&headless);
    let mut from_embedded = HeadlessRenderer::new(&embedded);
    // Every pass: gradient sky; atmosphere with objects and aerial perspective; stars and the
    // Moon; lens flares; the seed's model; classic lighting.
    for name in [
        "default",
        "earth-objects",
        "earth-night",
        "nehe-flare",
        "seed-earth",
        "fixed-function-tour",
    ] {
        let frame = preset_frame(name);
        let (width, height) = (96, 54);
        let expected = from_headless
            .render_ldr(&headless, &frame, width, height)
            .expect("headless render");
        let got = from_embedded
            .render_ldr(&embedded, &frame, width, height)
            .expect("embedded render");
        assert!(
            expected.pixels.iter().any(|&c| c > 0),
            "preset `{name}` rendered black: the comparison would prove nothing"
        );
        let differing = expected
            .pixels
            .chunks_exact(4)
            .zip(got.pixels.chunks_exact(4))
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            differing, 0,
            "preset `{name}`: {differing} pixels differ between the two paths"
        );
        let expected = from_headless.render_hdr(&headless, &frame, width, height).expect("HDR");
        let got = from_embedded.render_hdr(&embedded, &frame, width, height).expect("HDR");
        assert!(
            expected
                .pixels
                .iter()
                .zip(&got.pixels)
                .all(|(a, b)| a.to_bits() == b.to_bits()),
            "preset `{name}`: the HDR images differ"
        );
    }
}

#[test]
fn every_preset_renders_on_a_device_with_exactly_the_required_limits() {
    let _gpu = support::gpu();
    let (ctx, errors) = device_at_required_limits();
    let mut renderer = HeadlessRenderer::new(&ctx);
    for preset in firmament_scene::PRESETS {
        let frame = preset_frame(preset.name);
        if let Err(e) = renderer.render_ldr(&ctx, &frame, 24, 16) {
            panic!("preset `{}` on a device at required_limits(): {e}", preset.name);
        }
    }
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("device idle");
    let errors = errors.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    assert!(
        errors.is_empty(),
        "required_limits() is too low for the passes (update it and its table):\n{}",
        errors.join("\n")
    );
    // The image size is the caller's: beyond the device's texture limit it is refused per frame.
    let side = firmament_render::required_limits().max_texture_dimension_2d;
    match renderer.render_ldr(&ctx, &preset_frame("default"), side + 1, 16) {
        Err(RenderError::ImageSize { width, max, .. }) => assert_eq!((width, max), (side + 1, side)),
        other => panic!("an image wider than the device allows must be refused, got {other:?}"),
    }
}

#[test]
fn a_device_below_the_required_limits_is_refused_naming_the_limit() {
    let _gpu = support::gpu();
    let adapter = adapter();
    let required = firmament_render::required_limits();
    let cases = [
        (
            wgpu::Limits {
                max_storage_buffers_per_shader_stage: 0,
                ..required.clone()
            },
            "max_storage_buffers_per_shader_stage",
            u64::from(required.max_storage_buffers_per_shader_stage),
            0,
        ),
        (
            wgpu::Limits {
                max_texture_dimension_2d: 1024,
                ..required.clone()
            },
            "max_texture_dimension_2d",
            u64::from(required.max_texture_dimension_2d),
            1024,
        ),
    ];
    for (limits, limit, needed, available) in cases {
        let (device, queue) = device(&adapter, limits);
        let Err(error) = GpuContext::from_device(device, queue) else {
            panic!("{limit}: a device below required_limits() was accepted");
        };
        let RenderError::LimitsTooLow { shortfalls, .. } = &error else {
            panic!("{limit}: expected LimitsTooLow, got {error}");
        };
        let named: Vec<_> = shortfalls.iter().map(|s| (s.name, s.required, s.available)).collect();
        assert_eq!(named, [(limit, needed, available)]);
        let message = error.to_string();
        assert!(
            message.contains(&format!("`{limit}` is {available}, firmament needs at least {needed}")),
            "{message}"
        );
        assert!(
            message.contains("required_limits()"),
            "the message says what to ask for: {message}"
        );
    }
}
