//! Everything needed to draw one frame, in `f64`: the renderer's only input.

use glam::DVec3;

use crate::atmosphere::{Atmosphere, Sun};
use crate::camera::Camera;
use crate::color::LinearRgb;
use crate::display::DisplaySettings;
use crate::gradient_sky::GradientSkyState;

/// The sky model drawn behind everything.
#[derive(Debug, Clone, PartialEq)]
#[expect(
    clippy::large_enum_variant,
    reason = "both variants are a few hundred bytes and a frame is built once per frame"
)]
pub enum Sky {
    /// The keyframed gradient sky of seed 002.
    Gradient(GradientSkyState),
    /// A physically based atmosphere around a planet, lit by one or more suns.
    Atmosphere(AtmosphereSky),
}

impl Sky {
    /// The gradient sky's radiance along a unit view direction in the local frame — the
    /// reference the GPU gradient pass is tested against. `None` for the atmosphere, whose
    /// radiance depends on where the camera is: use
    /// [`Reference`](crate::atmosphere::reference::Reference) for it.
    pub fn gradient_radiance(&self, view: DVec3) -> Option<LinearRgb> {
        match self {
            Self::Gradient(sky) => Some(sky.radiance(view)),
            Self::Atmosphere(_) => None,
        }
    }
}

/// The most suns a frame may have (the GPU passes loop over a fixed-size array).
pub const MAX_SUNS: usize = 8;

/// A planet's atmosphere and its suns, in the same world frame as the camera.
#[derive(Debug, Clone, PartialEq)]
pub struct AtmosphereSky {
    /// The planet (posed in the world frame), its medium and the model wavelengths.
    pub atmosphere: Atmosphere,
    /// The suns, world-frame directions; 0 to [`MAX_SUNS`].
    pub suns: Vec<Sun>,
}

impl AtmosphereSky {
    /// Checks the atmosphere, every sun and the number of suns.
    pub fn validate(&self) -> Result<(), crate::CoreError> {
        self.atmosphere.validate()?;
        if self.suns.len() > MAX_SUNS {
            return Err(crate::CoreError::Invalid {
                field: "suns",
                value: format!("{} suns", self.suns.len()),
                rule: "at most 8 suns",
            });
        }
        self.suns.iter().try_for_each(Sun::validate)
    }
}

/// One frame: where we look from, what sky we see, and how it is shown.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// The camera (its aspect is overridden by the render target's).
    pub camera: Camera,
    /// The sky.
    pub sky: Sky,
    /// Exposure and tone curve.
    pub display: DisplaySettings,
}
