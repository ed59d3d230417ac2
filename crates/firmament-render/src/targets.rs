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
pub(crate) const DEPTH_CLEAR: f32 = 0.0;

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
        let make = |label, format, usage| texture_2d(device, label, (width, height), format, usage);
        let hdr = make(
            "firmament FrameTargets hdr",
            HDR_FORMAT,
            // Storage and copies in: the atmosphere's sky and aerial perspective are compute
            // passes here.
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
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

/// A 2D texture of one mip level and one sample, labelled.
pub(crate) fn texture_2d(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// A 1 × 1 [`HDR_FORMAT`] texture's view for a pass to bind before it is given the frame's.
pub(crate) fn hdr_placeholder(device: &wgpu::Device, label: &str) -> wgpu::TextureView {
    texture_2d(device, label, (1, 1), HDR_FORMAT, wgpu::TextureUsages::TEXTURE_BINDING)
        .create_view(&wgpu::TextureViewDescriptor::default())
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
/// - Every view is of a whole texture: a 2D texture with one layer and one mip level, viewed in
///   its own format. wgpu's `TextureView` does not say which layer, mip level or format it shows,
///   so firmament checks the texture behind it — a texture with mips or layers is refused even
///   when the view shows one whole image (render into a plain texture and copy), and a view in
///   another of the texture's `view_formats` is not detected (don't pass one).
/// - `color`: single-sampled, of one of [`EMBED_COLOR_FORMATS`] (linear radiance, to composite
///   before your tone mapping; `Rgba32Float` needs `FLOAT32_BLENDABLE`) with `RENDER_ATTACHMENT`
///   usage. Multisampled targets are rejected: resolve yours into a single-sampled one first.
/// - `depth`: the colour target's size and sample count (1), of one of [`EMBED_DEPTH_FORMATS`],
///   with `RENDER_ATTACHMENT | TEXTURE_BINDING` usage, holding your geometry's depth in
///   `convention` (the sky is tested against its far plane, aerial perspective and flare
///   occlusion read it; it is never written).
/// - `output` (optional, [`with_output`](Self::with_output)): a displayable view — your window's
///   surface, an 8-bit texture — that firmament's output pass fills from `color` after
///   compositing, with the frame's exposure, tone curve and encoding (exactly as
///   [`Renderer::record`](crate::Renderer::record) finishes its own frames): single-sampled, the
///   colour target's size, with `RENDER_ATTACHMENT` usage, in a colour-renderable float format
///   ([`check_output_format`]); `color` then also needs `TEXTURE_BINDING`. Without it, `color`
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

    /// Checks the rules above on `ctx`'s device; the target's size.
    pub fn check(&self, ctx: &GpuContext) -> Result<(u32, u32), RenderError> {
        let size = self.check_with(ctx.device.features())?;
        ctx.check_image_size(size.0, size.1)?;
        Ok(size)
    }

    /// The rules above on a device with `features`, all but the device's largest texture side;
    /// the target's size. [`Renderer::record_into`](crate::Renderer::record_into) checks its
    /// target with these too: it need not be the very one prepared.
    pub(crate) fn check_with(&self, features: wgpu::Features) -> Result<(u32, u32), RenderError> {
        let invalid = |m: String| Err(RenderError::InvalidTarget(m));
        let color = self.color.texture();
        let depth = self.depth.texture();
        let format = color.format();
        let samples = (color.sample_count(), depth.sample_count());
        if samples.0 != samples.1 {
            return invalid(format!(
                "the colour target has {} samples but the depth buffer {}: their sample counts must match, \
                 and be 1 (firmament draws into single-sampled targets only)",
                samples.0, samples.1
            ));
        }
        if samples.0 > 1 {
            return invalid(format!(
                "the colour target and depth buffer have {} samples: firmament draws into single-sampled \
                 targets only; resolve your MSAA colour (and depth) into single-sampled textures first and \
                 pass those",
                samples.0
            ));
        }
        whole_2d("colour target", color)?;
        if !EMBED_COLOR_FORMATS.contains(&format) {
            return invalid(format!(
                "colour format {format:?} is not supported; firmament draws linear radiance into \
                 {EMBED_COLOR_FORMATS:?} (tone-map afterwards, or use Renderer::record for a \
                 finished image in any format)"
            ));
        }
        if format == wgpu::TextureFormat::Rgba32Float && !features.contains(wgpu::Features::FLOAT32_BLENDABLE) {
            return invalid(
                "an Rgba32Float colour target needs the device feature FLOAT32_BLENDABLE (firmament \
                 blends into it); request it, or use Rgba16Float"
                    .into(),
            );
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
        whole_2d("depth buffer", depth)?;
        let needed = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
        if !depth.usage().contains(needed) {
            return invalid(format!(
                "the depth buffer's usages {:?} lack {:?} (firmament tests against it and reads it)",
                depth.usage(),
                needed - depth.usage()
            ));
        }
        let size = (color.width(), color.height());
        if (depth.width(), depth.height()) != size {
            return invalid(format!(
                "the depth buffer is {}x{} but the colour target {}x{}: they must be the same size",
                depth.width(),
                depth.height(),
                size.0,
                size.1
            ));
        }
        if let Some(output) = self.output {
            check_output(features, color, output.texture())?;
        }
        Ok(size)
    }
}

/// The rule every texture behind a view of an [`EmbedTarget`] follows: one whole 2D image. wgpu's
/// `TextureView` does not tell which mip level, layer or format it shows, so a view of part of a
/// texture could not be told from the whole; the texture itself must be that one image.
fn whole_2d(what: &str, texture: &wgpu::Texture) -> Result<(), RenderError> {
    let (dimension, layers, mips) = (
        texture.dimension(),
        texture.depth_or_array_layers(),
        texture.mip_level_count(),
    );
    if dimension != wgpu::TextureDimension::D2 || layers != 1 || mips != 1 {
        return Err(RenderError::InvalidTarget(format!(
            "the {what} is a {dimension:?} texture of {layers} layer(s) and {mips} mip level(s): firmament \
             needs a view of a whole 2D texture with one layer and one mip level (wgpu's TextureView \
             does not say which layer or mip a view shows; render into such a texture and copy it \
             into yours)"
        )));
    }
    Ok(())
}

/// Whether `format` can be a colour output of firmament's output pass on a device with
/// `features`, which writes a float colour without blending: a colour-renderable, non-integer
/// format. `Err` names why not.
pub fn check_output_format(format: wgpu::TextureFormat, features: wgpu::Features) -> Result<(), String> {
    let renderable = format
        .guaranteed_format_features(features)
        .allowed_usages
        .contains(wgpu::TextureUsages::RENDER_ATTACHMENT);
    let float = matches!(
        format.sample_type(None, Some(features)),
        Some(wgpu::TextureSampleType::Float { .. })
    );
    if !renderable || !float || format.is_depth_stencil_format() || format.is_compressed() {
        return Err(format!(
            "{format:?} is not a colour-renderable float format on this device (firmament's output \
             pass writes a float colour: use e.g. Rgba8UnormSrgb, Bgra8UnormSrgb, Rgba8Unorm or \
             Rgba16Float)"
        ));
    }
    Ok(())
}

/// The rules for [`EmbedTarget::output`] against the colour target `color`.
fn check_output(features: wgpu::Features, color: &wgpu::Texture, output: &wgpu::Texture) -> Result<(), RenderError> {
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
    whole_2d("output", output)?;
    check_output_format(output.format(), features)
        .or_else(|reason| invalid(format!("the output's format {reason}")))?;
    if !output.usage().contains(wgpu::TextureUsages::RENDER_ATTACHMENT) {
        return invalid(format!(
            "the output's usages {:?} lack RENDER_ATTACHMENT",
            output.usage()
        ));
    }
    if (output.width(), output.height()) != (color.width(), color.height()) {
        return invalid(format!(
            "the output is {}x{} but the colour target {}x{}: it must be the same size",
            output.width(),
            output.height(),
            color.width(),
            color.height()
        ));
    }
    Ok(())
}
