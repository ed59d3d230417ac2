//! The images of a flare's [`FlareShape::Image`](firmament_core::flare::FlareShape::Image)
//! elements as one `Rgba8Unorm` 2D array texture with a full mip chain, so one bind group serves
//! every element however many images the flare uses.
//!
//! Texels are used as stored (bytes / 255, like NeHe's sprites under `GL_MODULATE`); the mip
//! levels are 2×2 box averages of those values, which is what they stand for. The array always
//! has at least two layers: wgpu's GL backend makes a one-layer texture a plain 2D texture, which
//! a `D2Array` view cannot bind.

use std::sync::Arc;

use firmament_core::flare::FLARE_IMAGE_SIDE;
use firmament_core::texture::TextureImage;

/// Mip levels of a [`FLARE_IMAGE_SIDE`] square down to 1 texel.
const MIP_LEVELS: u32 = FLARE_IMAGE_SIDE.ilog2() + 1;

/// A flare's images on the GPU, and what they were made from (to skip identical uploads).
#[derive(Debug)]
pub(crate) struct FlareImageArray {
    pub(crate) view: wgpu::TextureView,
    uploaded: Vec<Arc<TextureImage>>,
}

impl FlareImageArray {
    /// An empty (black) array of two layers.
    pub(crate) fn new(device: &wgpu::Device) -> Self {
        Self {
            view: array_view(&create(device, 2)),
            uploaded: Vec::new(),
        }
    }

    /// Uploads `images` (each [`FLARE_IMAGE_SIDE`] square) unless they equal the last ones.
    /// Returns whether the view changed (a bind group that holds it must be rebuilt).
    pub(crate) fn update(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, images: &[Arc<TextureImage>]) -> bool {
        if images == self.uploaded.as_slice() {
            return false;
        }
        let texture = create(device, (images.len() as u32).max(2));
        for (layer, image) in images.iter().enumerate() {
            upload(queue, &texture, layer as u32, image);
        }
        self.view = array_view(&texture);
        self.uploaded = images.to_vec();
        true
    }
}

fn create(device: &wgpu::Device, layers: u32) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("firmament FlarePass element images"),
        size: wgpu::Extent3d {
            width: FLARE_IMAGE_SIDE,
            height: FLARE_IMAGE_SIDE,
            depth_or_array_layers: layers,
        },
        mip_level_count: MIP_LEVELS,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

fn array_view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some("firmament FlarePass element images view"),
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    })
}

/// Writes `image` and its mip chain into `layer`. Images of another size are skipped (the core
/// validates the side before a flare gets here).
fn upload(queue: &wgpu::Queue, texture: &wgpu::Texture, layer: u32, image: &TextureImage) {
    if image.width != FLARE_IMAGE_SIDE || image.height != FLARE_IMAGE_SIDE {
        return;
    }
    let mut side = FLARE_IMAGE_SIDE;
    let mut texels = image.texels.clone();
    for level in 0..MIP_LEVELS {
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: level,
                origin: wgpu::Origin3d { x: 0, y: 0, z: layer },
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(&texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * side),
                rows_per_image: Some(side),
            },
            wgpu::Extent3d {
                width: side,
                height: side,
                depth_or_array_layers: 1,
            },
        );
        if side > 1 {
            texels = half_size(&texels, side);
            side /= 2;
        }
    }
}

/// The next mip level of a `side` × `side` square (`side` even): each texel the rounded mean of
/// a 2×2 block.
fn half_size(texels: &[[u8; 4]], side: u32) -> Vec<[u8; 4]> {
    let (side, half) = (side as usize, side as usize / 2);
    (0..half * half)
        .map(|k| {
            let (x, y) = (2 * (k % half), 2 * (k / half));
            let block = [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)].map(|(i, j)| texels[j * side + i]);
            std::array::from_fn(|c| {
                let sum: u32 = block.iter().map(|t| u32::from(t[c])).sum();
                ((sum + 2) / 4) as u8
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mip_levels_average_blocks() {
        let texels = [[0, 0, 0, 0], [255, 0, 0, 0], [255, 255, 0, 0], [255, 255, 255, 1]];
        assert_eq!(half_size(&texels, 2), vec![[191, 128, 64, 0]]);
        assert_eq!(MIP_LEVELS, 9);
    }
}
