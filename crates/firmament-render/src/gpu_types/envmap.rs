//! `f32` data of the environment-map pass ([`crate::envmap::EnvironmentMapPass`]): the output's
//! sizes, and the suns' disc pieces summed per texel.
//!
//! A piece's contribution to its texel is rounded to `f32` here exactly as the CPU path rounds it
//! (`irradiance / texel solid angle`, in `f64`, then `as f32`), and the pieces of one texel keep
//! the CPU's order, so the GPU's sums are the CPU's, addition for addition.

use bytemuck::{Pod, Zeroable};

/// Mirrors `EnvmapParams` in `shaders/envmap/from_faces.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
pub struct EnvmapParamsUniforms {
    /// The cube layer drawn (0 for an equirectangular map).
    pub face: u32,
    /// The faces' side, texels.
    pub size: u32,
    /// The output's width, pixels.
    pub width: u32,
    /// The output's height, pixels.
    pub height: u32,
}

/// Mirrors `DiscTexel` in `shaders/envmap/from_faces.wgsl`: one texel that disc pieces fall in,
/// its place in the output and its run of pieces.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
pub struct DiscTexelInstance {
    /// Column, pixels from the left.
    pub x: u32,
    /// Row, pixels from the top.
    pub y: u32,
    /// The cube layer (0 for an equirectangular map).
    pub face: u32,
    /// The first of its pieces in the pieces buffer.
    pub first: u32,
    /// How many pieces follow.
    pub count: u32,
}
