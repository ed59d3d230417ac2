//! A still to a PNG, on a device of your own, in about ten lines of firmament code
//! (`render_still`).
//!
//! ```sh
//! cargo run -p firmament-examples --example headless_still -- [OUT.png] [WIDTH HEIGHT] [PRESET]
//! ```
//!
//! Defaults: `headless_still.png`, 640 × 360, the built-in `default` scene.

use std::error::Error;
use std::path::Path;

use firmament_render::headless::HeadlessRenderer;
use firmament_render::{GpuContext, wgpu};
use firmament_scene::SceneSource;

/// Renders the built-in scene `preset` at `width` × `height` to the PNG `path`.
pub(crate) fn render_still(path: &Path, preset: &str, width: u32, height: u32) -> Result<(), Box<dyn Error>> {
    // Your device, asked for what firmament needs (and the adapter's texture sizes).
    let adapter = pollster::block_on(wgpu::Instance::default().request_adapter(&Default::default()))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_features: firmament_render::required_features(),
        required_limits: firmament_render::required_limits().using_resolution(adapter.limits()),
        ..Default::default()
    }))?;
    let ctx = GpuContext::from_device(device, queue)?;
    // A scene, as a frame: what to draw.
    let frame = firmament_scene::load(SceneSource::Preset(preset), None, &[])?.frame_at(None)?;
    // Render to memory (8-bit sRGB RGBA, top row first) and save.
    let image = HeadlessRenderer::new(&ctx).render_ldr(&ctx, &frame, width, height)?;
    image::save_buffer(path, &image.pixels, width, height, image::ExtendedColorType::Rgba8)?;
    Ok(())
}

/// `[OUT.png] [WIDTH HEIGHT] [PRESET]`, each optional from the end.
pub(crate) fn run(args: impl IntoIterator<Item = String>) -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = args.into_iter().collect();
    let output = args.first().map_or("headless_still.png", String::as_str);
    let (width, height) = match (args.get(1), args.get(2)) {
        (Some(w), Some(h)) => (w.parse()?, h.parse()?),
        (None, None) => (640, 360),
        _ => return Err("give both WIDTH and HEIGHT".into()),
    };
    let preset = args.get(3).map_or("default", String::as_str);
    render_still(Path::new(output), preset, width, height)?;
    println!("wrote {output} ({width}x{height}, preset `{preset}`)");
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    run(std::env::args().skip(1))
}
