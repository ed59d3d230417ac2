//! The viewer's settings from the command line.

use std::path::PathBuf;

use firmament_render::Backend;

use super::fault;

/// The viewer's settings from the command line.
#[derive(Debug, Clone)]
pub(crate) struct ViewOptions {
    /// Window size, physical pixels.
    pub(crate) size: (u32, u32),
    /// Frames to draw before closing.
    pub(crate) frames: Option<u64>,
    /// Screenshot written after the last frame.
    pub(crate) screenshot: Option<PathBuf>,
    /// How EXR screenshots are compressed.
    pub(crate) exr_compression: crate::cli::ExrCompression,
    /// Where "save scene" writes by default.
    pub(crate) save_path: PathBuf,
    /// Save the scene to `save_path` after the last of `frames`.
    pub(crate) save_at_exit: bool,
    /// Start with the clock stopped.
    pub(crate) paused: bool,
    /// Start with NeHe's controls.
    pub(crate) nehe: bool,
    /// Share of the window's pixels the scene is drawn at.
    pub(crate) render_scale: f32,
    /// Graphics API.
    pub(crate) backend: Backend,
    /// What the window's title names.
    pub(crate) title: String,
    /// A fault to inject for tests (`FIRMAMENT_VIEW_INJECT_FAULT`).
    pub(crate) fault: Option<fault::InjectedFault>,
}
