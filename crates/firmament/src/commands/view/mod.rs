//! `firmament view`: a window on a scene, drawn by the same `Renderer` and the same
//! scene-to-frame path as `firmament render`, with a flying camera, a clock, and a panel that
//! edits every scene value live and saves the scene.

mod app;
#[cfg_attr(
    not(test),
    expect(
        dead_code,
        reason = "NeHe lesson 44's camera whole, as its tests check it; the viewer drives it through flight"
    )
)]
mod controller;
mod fault;
#[cfg_attr(
    not(test),
    expect(
        dead_code,
        reason = "pose and altitude helpers the viewer does not call yet, tested with the controller"
    )
)]
mod flight;
mod gpu;
mod input;
mod options;
mod panel;
mod scene_editor;
mod session;
#[cfg_attr(
    not(test),
    expect(
        dead_code,
        reason = "the clock's rate and scrub controls, tested; the panel steps the rate ladder"
    )
)]
mod sim_clock;

use firmament_render::wgpu;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use firmament_render::Backend;
use winit::event_loop::EventLoop;

use crate::cli::ViewArgs;
use options::ViewOptions;

/// Opens the viewer and runs it until the window closes (or `--frames` are drawn).
pub(crate) fn run(args: &ViewArgs) -> Result<()> {
    let scene_args = super::scene_input::with_default_preset(
        &args.scene_args,
        args.scene.as_deref(),
        super::scene_input::SHOWCASE_PRESET,
    );
    let what = super::scene_input::describe_scene(args.scene.as_deref(), &scene_args);
    crate::limits::check_pixels("the window (--size)", args.size.0, args.size.1)?;
    // Check the outputs before opening anything, so a typo fails at once.
    if let Some(path) = &args.screenshot {
        crate::output::OutputFormat::from_path(path)?;
        crate::output::check_parent_dir(path)?;
    }
    if let Some(path) = &args.save_scene {
        crate::output::check_parent_dir(path)?;
    }
    let fault = fault::InjectedFault::from_env()?;
    let doc = super::scene_input::load_document(
        args.scene.as_deref(),
        scene_args.preset.as_deref(),
        &scene_args.overrides,
    )
    .with_context(|| format!("cannot build {what}"))?;
    let session = session::Session::new(doc).with_context(|| format!("cannot build {what}"))?;

    let event_loop = open_display()?;
    let backend: Backend = args.backend.into();
    let mut desc = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(event_loop.owned_display_handle()));
    desc.backends = backend.backends();
    let instance = wgpu::Instance::new(desc);
    let options = ViewOptions {
        size: args.size,
        frames: args.frames,
        screenshot: args.screenshot.clone(),
        exr_compression: args.exr_compression.unwrap_or_default(),
        save_path: args
            .save_scene
            .clone()
            .unwrap_or_else(|| PathBuf::from("firmament-scene.toml")),
        save_at_exit: args.frames.is_some() && args.save_scene.is_some(),
        paused: args.paused,
        nehe: args.nehe,
        render_scale: args.scale,
        backend,
        title: what,
        fault,
    };
    let mut app = app::App::new(options, instance, session);
    event_loop.run_app(&mut app).context("the window's event loop failed")?;
    tracing::info!("viewer: {}", app.summary());
    match app.error.take() {
        Some(error) => Err(error),
        None => Ok(()),
    }
}

/// The event loop of the desktop's display, or an error saying there is none.
fn open_display() -> Result<EventLoop<()>> {
    let unset = |name| std::env::var_os(name).is_none_or(|v| v.is_empty());
    if cfg!(target_os = "linux") && unset("DISPLAY") && unset("WAYLAND_DISPLAY") && unset("WAYLAND_SOCKET") {
        bail!(
            "no display: `firmament view` needs a window, and neither DISPLAY nor WAYLAND_DISPLAY \
             is set; render headless with `firmament render` (or run under a virtual display, \
             e.g. `xvfb-run firmament view`)"
        );
    }
    EventLoop::new().map_err(|e| {
        anyhow::anyhow!(
            "cannot connect to the display ({e}); `firmament view` needs a window — render \
             headless with `firmament render`"
        )
    })
}
