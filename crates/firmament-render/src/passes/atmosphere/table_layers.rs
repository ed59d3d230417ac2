//! An array texture of small Rgba16Float tables, one per layer, uploaded layer by layer: what the
//! bodies' air light and the rings' light keep on the GPU (a [`Lut`] the CPU writes).

use super::luts::Lut;

/// The texture and its array view, read with the LUTs' sampler.
#[derive(Debug)]
pub(super) struct TableLayers {
    lut: Lut,
    size: (u32, u32),
}

impl TableLayers {
    /// `layers` (at least 2, so the view is an array) tables of `size` texels (width, height),
    /// labelled after `owner`.
    pub(super) fn new(device: &wgpu::Device, owner: &str, size: (u32, u32), layers: u32) -> Self {
        let lut = Lut::with_layers(
            device,
            owner,
            size,
            layers,
            wgpu::TextureFormat::Rgba16Float,
            wgpu::TextureUsages::empty(),
        );
        Self { lut, size }
    }

    /// The array view.
    pub(super) fn view(&self) -> &wgpu::TextureView {
        &self.lut.view
    }

    /// Writes `layer`: its texels row by row, four half floats' bits each.
    pub(super) fn write(&self, queue: &wgpu::Queue, layer: u32, texels: &[u16]) {
        let (width, height) = self.size;
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &self.lut.texture,
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
