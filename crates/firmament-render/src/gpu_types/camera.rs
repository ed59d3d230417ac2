//! The camera passes' GPU structs (`shaders/camera/bindings.wgsl`): the meter's uniforms and the
//! auto-exposure state it keeps between frames. The `f64` reference is
//! [`firmament_core::auto_exposure`].

use bytemuck::{Pod, Zeroable};
use firmament_core::Camera;
use firmament_core::auto_exposure::{
    AutoExposure, METERING_BRIGHT_FRACTION, ev100_for_luminance, METERING_CELL, METERING_DARK_FRACTION, METERING_LOG2_MAX, METERING_LOG2_MIN,
    masked_cos, sun_discs,
};
use firmament_core::frame::{Frame, MAX_SUNS};

use super::clip_to_world_direction;
use super::pack::vec3_w;

/// Bins of the meter's histogram (`METERING_BINS` in WGSL; a test compares them).
pub const METERING_BINS: u32 = 256;

/// `Metering` in WGSL: what the meter leaves out and how the exposure may move this frame.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct MeteringUniforms {
    /// Clip space → camera-relative world directions.
    pub clip_to_world: [[f32; 4]; 4],
    /// Each masked disc: unit direction (world) and the cosine of its masked angular radius.
    pub discs: [[f32; 4]; MAX_SUNS],
    /// log2 of the lowest and highest metered luminance (cd/m²); the dark and bright shares.
    pub range: [f32; 4],
    /// The EV100 bounds; the meter's offset, EV100 − log2(L) (`log2(100 / K)` less the
    /// compensation); a bound on the angle from a meter cell's centre to its pixels' (radians).
    pub ev: [f32; 4],
    /// The largest rise and fall of the EV100 this frame; 1 in `z` to jump to the target.
    pub step: [f32; 4],
    /// How many discs; the image's width and height (pixels); unused.
    pub counts: [u32; 4],
}

impl MeteringUniforms {
    /// The meter's uniforms for `frame` seen by `camera` (aspect set) at `size`, adapting over
    /// `seconds` (`None`: jump to the target).
    pub fn new(frame: &Frame, camera: &Camera, auto: &AutoExposure, size: (u32, u32), seconds: Option<f64>) -> Self {
        let mut discs = [[0.0; 4]; MAX_SUNS];
        let sun_discs = sun_discs(frame);
        for (slot, (direction, angular_radius)) in discs.iter_mut().zip(&sun_discs) {
            *slot = vec3_w(*direction, masked_cos(*angular_radius));
        }
        let (rise, fall, jump) = match seconds {
            Some(dt) => (auto.speed_up_ev_per_s * dt, auto.speed_down_ev_per_s * dt, 0.0),
            None => (0.0, 0.0, 1.0),
        };
        Self {
            clip_to_world: clip_to_world_direction(camera).to_cols_array_2d(),
            discs,
            range: [
                METERING_LOG2_MIN as f32,
                METERING_LOG2_MAX as f32,
                METERING_DARK_FRACTION as f32,
                METERING_BRIGHT_FRACTION as f32,
            ],
            ev: [
                auto.ev100_min as f32,
                auto.ev100_max as f32,
                (ev100_for_luminance(1.0) - auto.compensation_ev) as f32,
                cell_radius(camera, size.1) as f32,
            ],
            step: [rise as f32, fall as f32, jump, 0.0],
            counts: [sun_discs.len().min(MAX_SUNS) as u32, size.0, size.1, 0],
        }
    }
}

/// An upper bound on the angle between a meter cell's centre and its pixels' centres, radians:
/// the half-diagonal of a cell at the image's centre, where a rectilinear pixel spans the most,
/// doubled for safety (the meter tests a cell's pixels one by one only near a disc).
fn cell_radius(camera: &Camera, height: u32) -> f64 {
    let pixel = 2.0 * (0.5 * camera.fov_y).tan() / f64::from(height.max(1));
    let half_diagonal = f64::from(METERING_CELL) * std::f64::consts::FRAC_1_SQRT_2;
    2.0 * (half_diagonal * pixel).atan()
}

/// `ExposureState` in WGSL: the auto-exposure kept between frames.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Pod, Zeroable)]
pub struct ExposureStateGpu {
    /// The EV100 in use.
    pub ev100: f32,
    /// The EV100 the meter asked for in the last frame.
    pub target_ev100: f32,
    /// log2 of the last metered luminance (cd/m²).
    pub metered_log2: f32,
    /// Frames metered since the state was made.
    pub frames: u32,
}
