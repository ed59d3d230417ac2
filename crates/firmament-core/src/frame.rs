//! Everything needed to draw one frame, in `f64`: the renderer's only input.

use glam::DVec3;

use crate::camera::Camera;
use crate::color::LinearRgb;
use crate::display::DisplaySettings;
use crate::gradient_sky::GradientSkyState;

/// The sky model drawn behind everything.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sky {
    /// The keyframed gradient sky of seed 002.
    Gradient(GradientSkyState),
}

impl Sky {
    /// The radiance along a unit view direction in the local frame — the reference every GPU
    /// sky pass is tested against.
    pub fn radiance(&self, view: DVec3) -> LinearRgb {
        match self {
            Self::Gradient(sky) => sky.radiance(view),
        }
    }
}

/// One frame: where we look from, what sky we see, and how it is shown.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// The camera (its aspect is overridden by the render target's).
    pub camera: Camera,
    /// The sky.
    pub sky: Sky,
    /// Exposure and tone curve.
    pub display: DisplaySettings,
}
