//! `f32` data of the lens-flare passes: one [`FlareFrameUniforms`] per frame, one
//! [`FlareSourceGpu`] per source (read by the occlusion compute pass) and one
//! [`FlareInstance`] per drawn element (a camera-facing quad).
//!
//! Screen positions are NDC, computed in `f64` by the core ([`firmament_core::flare`]); the
//! planet is seen camera-relative (view-space directions into the planet frame), so a sun behind
//! the limb is occluded correctly from the ground to 100 AU.

use bytemuck::{Pod, Zeroable};
use firmament_core::atmosphere::Planet;
use firmament_core::flare::{FlareElement, FlareShape, FlareSource, LensFlare, SourceOnScreen};
use firmament_core::{Camera, DepthConvention};
use glam::{DVec2, DVec3, Mat4};

use super::codes;
use super::planet_view::PlanetView;

/// Mirrors `FlareFrame` in `shaders/flare/bindings.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct FlareFrameUniforms {
    /// View-space direction → planet frame rotation (planet occlusion).
    pub view_to_planet: [[f32; 4]; 4],
    /// The camera in the planet frame, metres; `w` = `|o/a|² − 1` computed in `f64`.
    pub planet_origin: [f32; 4],
    /// The planet's semi-axes, metres; `w` = 1 when there is a planet to occlude.
    pub planet_radii: [f32; 4],
    /// Source count, samples per source, target width and height in pixels.
    pub counts: [u32; 4],
    /// tan of half the horizontal and vertical field of view; seconds since the last frame
    /// (0: a still, visibility taken at once); screen aspect (width / height).
    pub view: [f32; 4],
    /// Fade-in and fade-out rates (visibility per second, 0 = at once); the depth buffer's
    /// convention (a `DEPTH_*` of [`codes`]); unused.
    pub fade: [f32; 4],
}

/// Mirrors `FlareSource` in `shaders/flare/bindings.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct FlareSourceGpu {
    /// Disc centre (NDC x, y), disc radii (NDC x, y).
    pub disc: [f32; 4],
    /// Reversed-Z depth of the source (0 for a sun: anything drawn hides it); its distance in
    /// metres (a very large number for a sun: the planet may hide it); unused; unused.
    pub depth: [f32; 4],
}

/// One element quad; mirrors `FlareInstance` in `shaders/flare.wgsl` (vertex attributes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct FlareInstance {
    /// Centre (NDC x, y), radius (units of half the screen height), horizontal stretch.
    pub placement: [f32; 4],
    /// Colour to add at full visibility (linear RGB over the exposure); `w` = the source's
    /// fade at the screen edge.
    pub color: [f32; 4],
    /// Shape (a `FLARE_*` of [`codes`]), then its parameters: streaks
    /// `points`, rotation (radians), sharpness; halo thickness; ghost sides, rotation, softness;
    /// image layer, rotation.
    pub shape: [f32; 4],
    /// The source's index (into the visibility buffer); three unused.
    pub source: [u32; 4],
}

impl FlareFrameUniforms {
    /// The same values over a depth buffer in `convention` (what [`Self::new`] gives is
    /// reversed-Z's).
    pub fn for_depth_convention(mut self, convention: DepthConvention) -> Self {
        self.fade[2] = match convention {
            DepthConvention::Standard => codes::DEPTH_STANDARD,
            _ => codes::DEPTH_REVERSED,
        } as f32;
        self
    }

    /// The frame's values: `sources` kept sources sampled as `flare` says over a depth buffer of
    /// `depth_size` pixels, seen by `camera`; `planet` (when the sky has one) hides sources
    /// behind it; `dt` seconds since the last frame, or `None` for a still.
    pub fn new(
        camera: &Camera,
        planet: Option<&Planet>,
        flare: &LensFlare,
        sources: u32,
        depth_size: (u32, u32),
        dt: Option<f64>,
    ) -> Self {
        let (view_to_planet, planet_origin, planet_radii) = match planet {
            Some(planet) => {
                let o = planet.to_planet_frame(camera.position);
                let r = planet.radii;
                // The same view of the planet the sky passes take (only rotation and `c` used).
                let view = PlanetView::new(camera, planet.center, planet.orientation, o, r, r);
                (
                    view.view_to_planet,
                    [o.x as f32, o.y as f32, o.z as f32, view.camera_shape[0]],
                    [r.x as f32, r.y as f32, r.z as f32, 1.0],
                )
            }
            None => (Mat4::IDENTITY.to_cols_array_2d(), [0.0; 4], [1.0, 1.0, 1.0, 0.0]),
        };
        let tan_y = (0.5 * camera.fov_y).tan();
        Self {
            view_to_planet,
            planet_origin,
            planet_radii,
            counts: [sources, flare.samples, depth_size.0, depth_size.1],
            view: [
                (tan_y * camera.aspect) as f32,
                tan_y as f32,
                dt.unwrap_or(0.0).max(0.0) as f32,
                camera.aspect as f32,
            ],
            fade: [flare.fade_in as f32, flare.fade_out as f32, 0.0, 0.0],
        }
    }
}

impl FlareSourceGpu {
    /// `source` as `camera` sees it, placed on screen at `at`, over a reversed-Z depth buffer.
    pub fn new(camera: &Camera, source: &FlareSource, at: &SourceOnScreen) -> Self {
        Self::in_convention(camera, source, at, DepthConvention::Reversed)
    }

    /// `source` as `camera` sees it, placed on screen at `at`, its depth in `convention`.
    pub fn in_convention(
        camera: &Camera,
        source: &FlareSource,
        at: &SourceOnScreen,
        convention: DepthConvention,
    ) -> Self {
        let (depth, distance) = if source.position.w == 0.0 {
            (convention.far_depth() as f32, f32::MAX)
        } else {
            let p: DVec3 = source.position.truncate() / source.position.w;
            let clip = camera.projection_matrix_for(convention) * camera.view_matrix() * p.extend(1.0);
            (
                (clip.z / clip.w).clamp(0.0, 1.0) as f32,
                (p - camera.position).length() as f32,
            )
        };
        Self {
            disc: [
                at.center.x as f32,
                at.center.y as f32,
                at.disc.x as f32,
                at.disc.y as f32,
            ],
            depth: [depth, distance, 0.0, 0.0],
        }
    }
}

impl FlareInstance {
    /// `element` of source `index` centred at `center` (NDC), coloured `color` (linear RGB over
    /// the exposure, at full visibility), faded by the source's `edge_fade`.
    pub fn new(element: &FlareElement, center: DVec2, color: DVec3, edge_fade: f64, index: u32) -> Self {
        let shape = match element.shape {
            FlareShape::Glow => [codes::FLARE_GLOW as f32, 0.0, 0.0, 0.0],
            FlareShape::Streaks {
                points,
                rotation,
                sharpness,
            } => [codes::FLARE_STREAKS as f32, points as f32, rotation.to_radians() as f32, sharpness as f32],
            FlareShape::Halo { thickness } => [codes::FLARE_HALO as f32, thickness as f32, 0.0, 0.0],
            FlareShape::Ghost {
                sides,
                rotation,
                softness,
            } => [codes::FLARE_GHOST as f32, sides as f32, rotation.to_radians() as f32, softness as f32],
            FlareShape::Image { image, rotation } => {
                [codes::FLARE_IMAGE as f32, image as f32, rotation.to_radians() as f32, 0.0]
            }
        };
        Self {
            placement: [
                center.x as f32,
                center.y as f32,
                element.size as f32,
                element.stretch as f32,
            ],
            color: [color.x as f32, color.y as f32, color.z as f32, edge_fade as f32],
            shape,
            source: [index, 0, 0, 0],
        }
    }
}
