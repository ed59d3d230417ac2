//! `f32` data of the lens-flare passes: one [`FlareFrameUniforms`] per frame, one
//! [`FlareSourceGpu`] per source (read by the occlusion compute pass) and one
//! [`FlareInstance`] per element that can light the target, with the pixels it may light
//! ([`PixelRect`], [`FlareInstance::clipped`]).
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
    /// convention (a `DEPTH_*` of [`codes`]); the element count ([`Self::with_elements`]).
    pub fade: [f32; 4],
}

/// Mirrors `FlareSource` in `shaders/flare/bindings.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct FlareSourceGpu {
    /// Disc centre (NDC x, y), disc radii (NDC x, y).
    pub disc: [f32; 4],
    /// Reversed-Z depth of the source (0 for a sun: anything drawn hides it); its distance in
    /// metres (a very large number for a sun: the planet may hide it); then the [`PixelRect`]
    /// its elements may light, [`PixelRect::packed`] as `f32` bits ([`Self::with_rect`]).
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
    /// The source's index (into the visibility buffer); the [`PixelRect`] the element may light,
    /// [`PixelRect::packed`]; the radius (units of the element's, uv) beyond which its light is
    /// negligible, as `f32` bits. Set by [`Self::clipped`]; [`Self::new`] leaves an empty
    /// rectangle.
    pub source: [u32; 4],
}

/// Linear colour (display units: over the exposure, 1 = white on screen) below which an
/// element's light is not drawn: 2⁻¹³, 0.40 of an 8-bit step where the sRGB curve is steepest
/// (12.92 × 255 × 2⁻¹³) for tone curves no steeper than 1 at black (firmament's are not). Each
/// element left out of a pixel moves its encoded value by under half a step, so it changes an
/// 8-bit value by at most one and only where that value lay on a rounding boundary.
pub const FLARE_NEGLIGIBLE: f64 = 1.0 / 8192.0;

/// Whole pixels `[x0, x1) × [y0, y1)` of a target, x right and y down from the top-left corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PixelRect {
    /// The first column.
    pub x0: u32,
    /// The first row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

impl PixelRect {
    /// Whether it holds no pixel.
    pub fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }

    /// The smallest rectangle holding both (an empty one adds nothing).
    pub fn union(self, other: Self) -> Self {
        if self.is_empty() {
            return other;
        }
        if other.is_empty() {
            return self;
        }
        Self {
            x0: self.x0.min(other.x0),
            y0: self.y0.min(other.y0),
            x1: self.x1.max(other.x1),
            y1: self.y1.max(other.y1),
        }
    }

    /// Both corners as the shaders read them: `x0 | y0 << 16`, `x1 | y1 << 16` (coordinates up
    /// to 65 535, more than any wgpu texture).
    pub fn packed(&self) -> [u32; 2] {
        let pack = |x: u32, y: u32| x.min(0xffff) | y.min(0xffff) << 16;
        [pack(self.x0, self.y0), pack(self.x1, self.y1)]
    }
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

    /// The same values for `elements` element records.
    pub fn with_elements(mut self, elements: u32) -> Self {
        self.fade[3] = elements as f32;
        self
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

    /// The same source whose elements may light `rect` of the target.
    pub fn with_rect(mut self, rect: PixelRect) -> Self {
        let [lo, hi] = rect.packed();
        self.depth[2] = f32::from_bits(lo);
        self.depth[3] = f32::from_bits(hi);
        self
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

    /// The largest of its colour's channels at full visibility, edge fade included.
    fn peak(&self) -> f64 {
        let [r, g, b, fade] = self.color.map(f64::from);
        r.max(g).max(b) * fade
    }

    /// The radius (uv units: 1 at the element's radius) beyond which its light stays below
    /// [`FLARE_NEGLIGIBLE`] at full visibility, from each shape's falloff; `√2`, the quad's
    /// corner, for an image; `None` when all of it is negligible.
    pub fn cut_radius(&self) -> Option<f64> {
        let peak = self.peak();
        if peak.is_nan() || peak <= FLARE_NEGLIGIBLE {
            return None;
        }
        // The falloff each shape may not exceed beyond the cut.
        let floor = FLARE_NEGLIGIBLE / peak;
        let [shape, a, _, c] = self.shape.map(f64::from);
        let cut = match (shape + 0.5) as u32 {
            // (1 − r)², rays at most 1.
            codes::FLARE_GLOW | codes::FLARE_STREAKS => 1.0 - floor.sqrt(),
            // 1 − t², t = (r − (1 − w)) / w past the ring's middle.
            codes::FLARE_HALO if a > 0.0 => 1.0 - 0.5 * a * (1.0 - (1.0 - floor).sqrt()),
            // 1 − smoothstep(1 − s, 1, e): e, the polygon's "radius", is never below r.
            codes::FLARE_GHOST if c > 0.0 => {
                let smooth = |x: f64| x * x * (3.0 - 2.0 * x);
                // The smallest x with 1 − smooth(x) ≤ floor, by bisection (smooth rises).
                let (mut lo, mut hi) = (0.0, 1.0);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if 1.0 - smooth(mid) <= floor { hi = mid } else { lo = mid }
                }
                1.0 - c + c * hi
            }
            codes::FLARE_IMAGE => std::f64::consts::SQRT_2,
            _ => 1.0,
        };
        Some(cut)
    }

    /// The element with the pixels of a `width` × `height` target (of that aspect ratio) whose
    /// centres may lie within its [`cut_radius`](Self::cut_radius) — the quad for an image —
    /// with a pixel's margin for `f32` rounding, and that rectangle; `None` when its light is
    /// negligible or misses the target.
    pub fn clipped(mut self, (width, height): (u32, u32)) -> Option<(Self, PixelRect)> {
        let cut = self.cut_radius()?;
        let extent = cut.min(1.0);
        let [x, y, radius, stretch] = self.placement.map(f64::from);
        let (w, h) = (f64::from(width), f64::from(height));
        let aspect = w / h;
        let (half_x, half_y) = (extent * radius * stretch / aspect, extent * radius);
        let column = |ndc: f64| (ndc + 1.0) * 0.5 * w;
        let row = |ndc: f64| (1.0 - ndc) * 0.5 * h;
        let clamp = |v: f64, max: f64| v.clamp(0.0, max) as u32;
        let rect = PixelRect {
            x0: clamp(column(x - half_x).floor() - 1.0, w),
            y0: clamp(row(y + half_y).floor() - 1.0, h),
            x1: clamp(column(x + half_x).ceil() + 1.0, w),
            y1: clamp(row(y - half_y).ceil() + 1.0, h),
        };
        if rect.is_empty() {
            return None;
        }
        let [lo, hi] = rect.packed();
        self.source[1] = lo;
        self.source[2] = hi;
        self.source[3] = (cut as f32).to_bits();
        Some((self, rect))
    }
}
