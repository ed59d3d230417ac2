//! The atmosphere's medium LUTs are rebuilt only when the medium changes, exactly once per change;
//! with `Renderer::set_incremental_lut_rebuild` the build is spread over frames that keep drawing
//! the previous medium, and ends in the pixels a build within one frame gives.

use crate::support;

use firmament_core::frame::Sky;
use firmament_core::{Frame, TimeOfDay};
use firmament_render::headless::{LDR_FORMAT, ldr_texture};
use firmament_render::passes::atmosphere::MEDIUM_BUILD_STEPS;
use firmament_render::readback::read_texture;
use firmament_render::{GpuContext, Renderer, wgpu};

/// Tiny: llvmpipe is slow, and each medium build takes seconds on it.
const WIDTH: u32 = 32;
const HEIGHT: u32 = 18;
const FORMAT: wgpu::TextureFormat = LDR_FORMAT;

fn scene() -> firmament_scene::Scene {
    firmament_scene::load(firmament_scene::SceneSource::Preset("earth-sunset"), None, &[]).expect("earth-sunset")
}

fn sky_of(frame: &mut Frame) -> &mut firmament_core::frame::AtmosphereSky {
    match &mut frame.sky {
        Sky::Atmosphere(sky) => sky,
        _ => panic!("earth-sunset's sky is an atmosphere"),
    }
}

/// The preset's frame with twice its Rayleigh scattering (a change of medium).
fn thicker_air(mut frame: Frame) -> Frame {
    let rayleigh = &mut sky_of(&mut frame).atmosphere.medium.terms[0];
    rayleigh.scattering *= 2.0;
    frame
}

fn output_texture(ctx: &GpuContext) -> wgpu::Texture {
    ldr_texture(
        &ctx.device,
        "gpu_lut_rebuild test output",
        (WIDTH, HEIGHT),
        wgpu::TextureUsages::COPY_SRC,
    )
}

/// Prepares, records and submits `frame`; the 8-bit image.
fn render(ctx: &GpuContext, renderer: &mut Renderer, frame: &Frame, output: &wgpu::Texture) -> Vec<u8> {
    let validation = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
    renderer.prepare(ctx, frame, WIDTH, HEIGHT).expect("prepare");
    let view = output.create_view(&wgpu::TextureViewDescriptor::default());
    let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("gpu_lut_rebuild test encoder"),
    });
    renderer.record(&mut encoder, &view);
    ctx.queue.submit([encoder.finish()]);
    if let Some(error) = pollster::block_on(validation.pop()) {
        panic!("record: {error}");
    }
    read_texture(ctx, output).expect("read back the output")
}

#[test]
fn medium_luts_rebuild_once_per_medium_change_and_incrementally_when_asked() {
    let gpu = support::gpu();
    let ctx = &gpu.ctx;
    let output = output_texture(ctx);
    let scene = scene();
    let base = scene.frame_at(None).expect("frame");

    // (a) A whole renderer: the first frame builds; camera, sun and time do not.
    let mut whole = Renderer::new(ctx, FORMAT);
    let before = render(ctx, &mut whole, &base, &output);
    assert_eq!(whole.medium_lut_builds(), (1, false), "the first frame builds the LUTs");
    let mut moved = base.clone();
    moved.camera.position.z += 2_000.0;
    sky_of(&mut moved).suns[0].direction = support::direction(200.0, 30.0);
    let later = scene
        .frame_at(Some(TimeOfDay::from_hours(9.5).expect("a time of day")))
        .expect("frame at 09:30");
    for frame in [&moved, &later, &base] {
        render(ctx, &mut whole, frame, &output);
    }
    assert_eq!(
        whole.medium_lut_builds(),
        (1, false),
        "a new camera, sun or time rebuilt the medium's LUTs"
    );

    // (b) A change of medium builds once, in its frame.
    let thicker = thicker_air(base.clone());
    let rebuilt = render(ctx, &mut whole, &thicker, &output);
    assert_eq!(whole.medium_lut_builds(), (2, false));
    assert!(rebuilt != before, "twice the Rayleigh scattering changes the sky");
    assert!(render(ctx, &mut whole, &thicker, &output) == rebuilt);
    assert_eq!(whole.medium_lut_builds(), (2, false), "the same medium again rebuilt");

    // (c) Incrementally: the frames of the build draw the old medium, the last one the new
    // medium exactly as the whole build did.
    let mut incremental = Renderer::new(ctx, FORMAT);
    incremental.set_incremental_lut_rebuild(true);
    assert!(
        render(ctx, &mut incremental, &base, &output) == before,
        "first build is whole"
    );
    for frame in 1..MEDIUM_BUILD_STEPS {
        let image = render(ctx, &mut incremental, &thicker, &output);
        assert_eq!(incremental.medium_lut_builds(), (1, true), "frame {frame} of the build");
        assert!(
            image == before,
            "frame {frame} of the build drew something else than the old medium"
        );
    }
    let last = render(ctx, &mut incremental, &thicker, &output);
    assert_eq!(incremental.medium_lut_builds(), (2, false));
    assert!(
        last == rebuilt,
        "the incremental build ends in other pixels than the whole build"
    );
}

#[test]
fn a_medium_change_during_an_incremental_build_starts_over() {
    let gpu = support::gpu();
    let ctx = &gpu.ctx;
    let output = output_texture(ctx);
    let base = scene().frame_at(None).expect("frame");
    let thicker = thicker_air(base.clone());
    let thickest = thicker_air(thicker.clone());

    let mut whole = Renderer::new(ctx, FORMAT);
    let expected = render(ctx, &mut whole, &thickest, &output);

    let mut incremental = Renderer::new(ctx, FORMAT);
    incremental.set_incremental_lut_rebuild(true);
    let before = render(ctx, &mut incremental, &base, &output);
    for _ in 0..3 {
        render(ctx, &mut incremental, &thicker, &output);
    }
    for frame in 1..MEDIUM_BUILD_STEPS {
        let image = render(ctx, &mut incremental, &thickest, &output);
        assert!(
            image == before,
            "frame {frame} of the second build drew something else than the old medium"
        );
    }
    assert!(render(ctx, &mut incremental, &thickest, &output) == expected);
    assert_eq!(
        incremental.medium_lut_builds(),
        (2, false),
        "the abandoned build was counted"
    );
}

/// Wall time of `render` (prepare, record, submit, wait for the image), milliseconds.
fn timed(ctx: &GpuContext, renderer: &mut Renderer, frame: &Frame, output: &wgpu::Texture) -> f64 {
    let start = std::time::Instant::now();
    render(ctx, renderer, frame, output);
    start.elapsed().as_secs_f64() * 1000.0
}

/// The longest frame of a medium change, whole and incremental (printed for
/// docs/PERFORMANCE.md): spreading the build leaves no frame as long as the whole build's.
#[test]
fn an_incremental_build_has_no_frame_as_long_as_the_whole_build() {
    let gpu = support::gpu();
    let ctx = &gpu.ctx;
    let output = output_texture(ctx);
    let base = scene().frame_at(None).expect("frame");
    let thicker = thicker_air(base.clone());

    let mut whole = Renderer::new(ctx, FORMAT);
    timed(ctx, &mut whole, &base, &output);
    let steady = timed(ctx, &mut whole, &base, &output);
    let whole_ms = timed(ctx, &mut whole, &thicker, &output);

    let mut incremental = Renderer::new(ctx, FORMAT);
    incremental.set_incremental_lut_rebuild(true);
    timed(ctx, &mut incremental, &base, &output);
    let steps: Vec<f64> = (0..MEDIUM_BUILD_STEPS)
        .map(|_| timed(ctx, &mut incremental, &thicker, &output))
        .collect();
    let longest = steps.iter().copied().fold(0.0, f64::max);
    eprintln!(
        "{WIDTH}x{HEIGHT}: steady frame {steady:.0} ms; medium change: whole build {whole_ms:.0} ms in one frame, \
         incremental longest {longest:.0} ms (frames: {})",
        steps.iter().map(|ms| format!("{ms:.0}")).collect::<Vec<_>>().join(" ")
    );
    assert_eq!(incremental.medium_lut_builds(), (2, false));
    assert!(
        longest < whole_ms,
        "an incremental frame took {longest:.0} ms, the whole build {whole_ms:.0} ms"
    );
}
