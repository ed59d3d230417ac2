//! The HDR colour and depth textures a frame is drawn into before tone mapping.

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
