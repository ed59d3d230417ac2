//! An array texture of small Rgba16Float tables, one per layer, uploaded layer by layer: what the
//! bodies' air light and the rings' light keep on the GPU.

/// The texture and its array view, read with the LUTs' sampler.
#[derive(Debug)]
pub(super) struct TableLayers {
    texture: wgpu::Texture,
    pub(super) view: wgpu::TextureView,
    size: (u32, u32),
}

impl TableLayers {
    /// `layers` tables of `size` texels (width, height), labelled after `owner`.
    pub(super) fn new(device: &wgpu::Device, owner: &str, size: (u32, u32), layers: u32) -> Self {
        let (width, height) = size;
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(&format!("firmament AtmospherePass {owner}")),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: layers,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba16Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some(&format!("firmament AtmospherePass {owner} view")),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        Self { texture, view, size }
    }

    /// Writes `layer`: its texels row by row, four half floats' bits each.
    pub(super) fn write(&self, queue: &wgpu::Queue, layer: u32, texels: &[u16]) {
        let (width, height) = self.size;
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &self.texture,
                mip_level: 0,
                origin: wgpu::Origin3d { x: 0, y: 0, z: layer },
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(width * 8),
                rows_per_image: Some(height),
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
    }
}
