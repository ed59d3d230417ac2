//! The HDR colour and depth textures a frame is drawn into before tone mapping, and the
//! caller's own ([`EmbedTarget`]).

use firmament_core::DepthConvention;

use crate::context::GpuContext;
use crate::error::RenderError;

/// Format of the HDR colour target: linear radiance, half float (renderable everywhere, unlike
/// Rgba32Float on GL). Passes clamp to [`HDR_MAX`]: a sun disc (~1.6·10⁹ cd/m²) does not fit.
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// The largest finite value of [`HDR_FORMAT`] (half float).
pub const HDR_MAX: f32 = 65504.0;
/// Format of the depth target. firmament uses reversed-Z: clear to 0, near is 1, test `Greater`.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// The depth buffer's clear value under reversed-Z: the far plane (infinity).
pub const DEPTH_CLEAR: f32 = 0.0;

/// HDR colour and depth targets of one size.
#[derive(Debug)]
#[non_exhaustive]
pub struct FrameTargets {
    /// Linear HDR radiance ([`HDR_FORMAT`]); can be copied out for EXR files.
    pub hdr: wgpu::Texture,
    /// View of `hdr`.
    pub hdr_view: wgpu::TextureView,
    /// Reversed-Z depth ([`DEPTH_FORMAT`]).
    pub depth: wgpu::Texture,
    /// View of `depth`.
    pub depth_view: wgpu::TextureView,
}

impl FrameTargets {
    /// Creates targets of `width` × `height` pixels.
    pub fn new(device: &wgpu::Device, width: u32, height: u32) -> Self {
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let make = |label, format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let hdr = make(
            "firmament FrameTargets hdr",
            HDR_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
        );
        let depth = make(
            "firmament FrameTargets depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let hdr_view = hdr.create_view(&wgpu::TextureViewDescriptor::default());
        let depth_view = depth.create_view(&wgpu::TextureViewDescriptor::default());
        Self {
            hdr,
            hdr_view,
            depth,
            depth_view,
        }
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.hdr.width(), self.hdr.height())
    }
}

/// Colour formats [`EmbedTarget::color`] may have: linear float HDR targets.
/// `Rgba32Float` also needs the device feature `FLOAT32_BLENDABLE` (firmament blends into it).
pub const EMBED_COLOR_FORMATS: [wgpu::TextureFormat; 2] =
    [wgpu::TextureFormat::Rgba16Float, wgpu::TextureFormat::Rgba32Float];

/// Depth formats [`EmbedTarget::depth`] may have: depth-only formats a shader can read (a
/// depth-stencil format cannot be bound as one texture).
pub const EMBED_DEPTH_FORMATS: [wgpu::TextureFormat; 3] = [
    wgpu::TextureFormat::Depth32Float,
    wgpu::TextureFormat::Depth24Plus,
    wgpu::TextureFormat::Depth16Unorm,
];

/// The caller's frame that [`Renderer::prepare_into`](crate::Renderer::prepare_into) and
/// [`Renderer::record_into`](crate::Renderer::record_into) draw into.
///
/// Rules (each broken one is a [`RenderError::InvalidTarget`] naming what is needed, never a wgpu
/// validation panic):
/// - `color`: a view of a whole single-sampled 2D texture of one of [`EMBED_COLOR_FORMATS`]
///   (linear radiance, to composite before your tone mapping) with `RENDER_ATTACHMENT` usage.
///   Multisampled targets are rejected: resolve yours into a single-sampled one first.
/// - `depth`: a view of a single-sampled texture of the colour target's size, of one of
///   [`EMBED_DEPTH_FORMATS`], with `RENDER_ATTACHMENT | TEXTURE_BINDING` usage, holding your
///   geometry's depth in `convention` (the sky is tested against its far plane, aerial
///   perspective and flare occlusion read it; it is never written).
/// - `output` (optional, [`with_output`](Self::with_output)): a displayable view — your window's
///   surface, an 8-bit texture — that firmament's output pass fills from `color` after
///   compositing, with the frame's exposure, tone curve and encoding (exactly as
///   [`Renderer::record`](crate::Renderer::record) finishes its own frames): a view of a whole
///   single-sampled 2D texture of the colour target's size with `RENDER_ATTACHMENT` usage, in a
///   colour-renderable format; `color` then also needs `TEXTURE_BINDING`. Without it, `color`
///   holds linear radiance for your own tone mapping.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub struct EmbedTarget<'a> {
    /// Your HDR colour target.
    pub color: &'a wgpu::TextureView,
    /// Your depth buffer, holding your geometry.
    pub depth: &'a wgpu::TextureView,
    /// How `depth` maps distance (the far plane finite or not as the frame's camera says).
    pub convention: DepthConvention,
    /// A displayable view that firmament's output pass tone-maps `color` into, if any.
    pub output: Option<&'a wgpu::TextureView>,
    /// Whether firmament applies aerial perspective over your geometry (from the depth buffer;
    /// the default). Off ([`without_aerial_perspective`](Self::without_aerial_perspective)) when
    /// your shaders fog themselves with `firmament_apply_aerial_perspective`, or draw nothing
    /// that needs it: two full-screen draws fewer.
    pub aerial_perspective: bool,
}

impl<'a> EmbedTarget<'a> {
    /// Your colour target and depth buffer, the depth in `convention`.
    pub fn new(color: &'a wgpu::TextureView, depth: &'a wgpu::TextureView, convention: DepthConvention) -> Self {
        Self {
            color,
            depth,
            convention,
            output: None,
            aerial_perspective: true,
        }
    }

    /// The same target, with no aerial perspective applied by firmament (see
    /// [`aerial_perspective`](Self::aerial_perspective)).
    #[must_use]
    pub fn without_aerial_perspective(self) -> Self {
        Self {
            aerial_perspective: false,
            ..self
        }
    }

    /// The same target, finished by firmament's output pass into `output` (see the rules above).
    #[must_use]
    pub fn with_output(self, output: &'a wgpu::TextureView) -> Self {
        Self {
            output: Some(output),
            ..self
        }
    }

    /// Width and height of the colour target, pixels.
    pub fn size(&self) -> (u32, u32) {
        let t = self.color.texture();
        (t.width(), t.height())
    }

    /// What the pipelines depend on: colour format, depth format, convention.
    pub(crate) fn key(&self) -> crate::passes::SkyTarget {
        crate::passes::SkyTarget::new(
            self.color.texture().format(),
            self.depth.texture().format(),
            self.convention,
        )
    }

    /// Checks the rules above on `ctx`'s device; the target's size.
    pub fn check(&self, ctx: &GpuContext) -> Result<(u32, u32), RenderError> {
        let invalid = |m: String| Err(RenderError::InvalidTarget(m));
        let color = self.color.texture();
        let depth = self.depth.texture();
        let format = color.format();
        if color.sample_count() > 1 || depth.sample_count() > 1 {
            return invalid(format!(
                "the colour target has {} samples and the depth buffer {}: firmament draws into \
                 single-sampled targets only; resolve your MSAA colour (and depth) into single-sampled \
                 textures first and pass those",
                color.sample_count(),
                depth.sample_count()
            ));
        }
        if !EMBED_COLOR_FORMATS.contains(&format) {
            return invalid(format!(
                "colour format {format:?} is not supported; firmament draws linear radiance into \
                 {EMBED_COLOR_FORMATS:?} (tone-map afterwards, or use Renderer::record for a \
                 finished image in any format)"
            ));
        }
        if format == wgpu::TextureFormat::Rgba32Float
            && !ctx.device.features().contains(wgpu::Features::FLOAT32_BLENDABLE)
        {
            return invalid(
                "an Rgba32Float colour target needs the device feature FLOAT32_BLENDABLE (firmament \
                 blends into it); request it, or use Rgba16Float"
                    .into(),
            );
        }
        if color.dimension() != wgpu::TextureDimension::D2 || color.depth_or_array_layers() != 1 {
            return invalid("the colour target must be a 2D texture with one layer".into());
        }
        if !color.usage().contains(wgpu::TextureUsages::RENDER_ATTACHMENT) {
            return invalid(format!(
                "the colour target's usages {:?} lack RENDER_ATTACHMENT",
                color.usage()
            ));
        }
        let depth_format = depth.format();
        if !EMBED_DEPTH_FORMATS.contains(&depth_format) {
            return invalid(format!(
                "depth format {depth_format:?} cannot be read by firmament's shaders; use one of \
                 {EMBED_DEPTH_FORMATS:?} (a depth-stencil format cannot be sampled as one texture)"
            ));
        }
        let needed = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
        if !depth.usage().contains(needed) {
            return invalid(format!(
                "the depth buffer's usages {:?} lack {:?} (firmament tests against it and reads it)",
                depth.usage(),
                needed - depth.usage()
            ));
        }
        let size = (color.width(), color.height());
        if (depth.width(), depth.height()) != size || depth.depth_or_array_layers() != 1 {
            return invalid(format!(
                "the depth buffer is {}x{} but the colour target {}x{}: they must be the same size, \
                 one layer",
                depth.width(),
                depth.height(),
                size.0,
                size.1
            ));
        }
        if let Some(output) = self.output {
            check_output(color, output.texture())?;
        }
        ctx.check_image_size(size.0, size.1)?;
        Ok(size)
    }
}

/// The rules for [`EmbedTarget::output`] against the colour target `color`.
fn check_output(color: &wgpu::Texture, output: &wgpu::Texture) -> Result<(), RenderError> {
    let invalid = |m: String| Err(RenderError::InvalidTarget(m));
    if !color.usage().contains(wgpu::TextureUsages::TEXTURE_BINDING) {
        return invalid(format!(
            "with an output view, the colour target's usages {:?} also need TEXTURE_BINDING (the \
             output pass reads it)",
            color.usage()
        ));
    }
    if output.sample_count() > 1 {
        return invalid(format!(
            "the output has {} samples: firmament's output pass writes single-sampled views only",
            output.sample_count()
        ));
    }
    let format = output.format();
    let renderable = format
        .guaranteed_format_features(wgpu::Features::empty())
        .allowed_usages
        .contains(wgpu::TextureUsages::RENDER_ATTACHMENT);
    if !renderable || format.is_depth_stencil_format() || format.is_compressed() {
        return invalid(format!(
            "the output's format {format:?} is not a colour-renderable format"
        ));
    }
    if !output.usage().contains(wgpu::TextureUsages::RENDER_ATTACHMENT) {
        return invalid(format!(
            "the output's usages {:?} lack RENDER_ATTACHMENT",
            output.usage()
        ));
    }
    if (output.width(), output.height()) != (color.width(), color.height())
        || output.dimension() != wgpu::TextureDimension::D2
        || output.depth_or_array_layers() != 1
    {
        return invalid(format!(
            "the output is {}x{} but the colour target {}x{}: it must be a 2D texture of the same \
             size, one layer",
            output.width(),
            output.height(),
            color.width(),
            color.height()
        ));
    }
    Ok(())
}
