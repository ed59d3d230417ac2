//! The bodies' albedo maps on the GPU (`atmosphere/bodies.wgsl` reads them): one array layer per
//! body, each body's [`BodySurface::Map`] resampled to [`BODY_MAP_SIZE`] with a full chain of mip
//! levels (a body a few pixels across reads a small level instead of shimmering), uploaded when
//! that body's map changes.

use std::sync::Arc;

use firmament_core::atmosphere::body::{BodySurface, MAX_BODIES};
use firmament_core::atmosphere::surface::SurfaceMap;
use firmament_core::atmosphere::surface::map::texel_centres;
use firmament_core::color::linear_to_srgb;
use firmament_core::frame::AtmosphereSky;

use super::stages::{array_texture_entry, binding};
use crate::gpu_types::BODY_MAP_SIZE;

/// The maps' texels: sRGB-encoded linear albedo in 8 bits (the sampler decodes before it
/// filters), alpha unused.
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// The texture of every body's map, read with the maps' sampler (`map_sampler`).
#[derive(Debug)]
pub(super) struct BodyMaps {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    /// The map each layer holds (`None`: nothing uploaded there).
    uploaded: [Option<Arc<SurfaceMap>>; MAX_BODIES],
}

impl BodyMaps {
    pub(super) fn new(device: &wgpu::Device) -> Self {
        let (width, height) = BODY_MAP_SIZE;
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("firmament AtmospherePass body maps"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: MAX_BODIES as u32,
            },
            mip_level_count: mip_levels(),
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("firmament AtmospherePass body maps view"),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        Self {
            texture,
            view,
            uploaded: Default::default(),
        }
    }

    /// Uploads each of `sky`'s bodies' maps into its layer when the layer does not hold it
    /// already; layers of bodies without a map are left as they are (the shaders do not read
    /// them).
    pub(super) fn prepare(&mut self, queue: &wgpu::Queue, sky: &AtmosphereSky) {
        for (layer, body) in sky.bodies.iter().enumerate().take(MAX_BODIES) {
            let BodySurface::Map(map) = &body.surface else { continue };
            if self.uploaded[layer]
                .as_ref()
                .is_some_and(|m| Arc::ptr_eq(m, map) || **m == **map)
            {
                continue;
            }
            for (level, (size, texels)) in mip_chain(map).into_iter().enumerate() {
                queue.write_texture(
                    wgpu::TexelCopyTextureInfo {
                        texture: &self.texture,
                        mip_level: level as u32,
                        origin: wgpu::Origin3d {
                            x: 0,
                            y: 0,
                            z: layer as u32,
                        },
                        aspect: wgpu::TextureAspect::All,
                    },
                    &texels,
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(size.0 * 4),
                        rows_per_image: Some(size.1),
                    },
                    wgpu::Extent3d {
                        width: size.0,
                        height: size.1,
                        depth_or_array_layers: 1,
                    },
                );
            }
            self.uploaded[layer] = Some(map.clone());
        }
    }

    /// The texture's layout entry (the sky stages read it with the maps' sampler).
    pub(super) fn entry() -> wgpu::BindGroupLayoutEntry {
        array_texture_entry(binding::BODY_MAPS)
    }

    /// The texture at its binding.
    pub(super) fn resource(&self) -> (u32, wgpu::BindingResource<'_>) {
        (binding::BODY_MAPS, wgpu::BindingResource::TextureView(&self.view))
    }
}

/// The number of mip levels down to one texel across.
fn mip_levels() -> u32 {
    BODY_MAP_SIZE.0.max(BODY_MAP_SIZE.1).ilog2() + 1
}

/// `map` resampled to [`BODY_MAP_SIZE`] (the core's bilinear lookup at the new texel centres)
/// and every mip level below it (2 × 2 means of the level above, in linear albedo), each as its
/// size and its [`FORMAT`] texels.
fn mip_chain(map: &SurfaceMap) -> Vec<((u32, u32), Vec<u8>)> {
    let mut size = BODY_MAP_SIZE;
    let mut linear: Vec<[f32; 3]> = texel_centres(size.0, size.1)
        .map(|(latitude, longitude)| {
            let [r, g, b, _] = map.sample(latitude, longitude);
            [r as f32, g as f32, b as f32]
        })
        .collect();
    let mut levels = Vec::with_capacity(mip_levels() as usize);
    loop {
        levels.push((size, encoded(&linear)));
        if size == (1, 1) {
            return levels;
        }
        let next = ((size.0 / 2).max(1), (size.1 / 2).max(1));
        linear = halved(&linear, size, next);
        size = next;
    }
}

/// The level of size `next` below the `size` one: each texel the mean of the (up to) 2 × 2
/// texels above it.
fn halved(texels: &[[f32; 3]], size: (u32, u32), next: (u32, u32)) -> Vec<[f32; 3]> {
    let (sx, sy) = (size.0 / next.0, size.1 / next.1);
    let mut out = Vec::with_capacity((next.0 * next.1) as usize);
    for y in 0..next.1 {
        for x in 0..next.0 {
            let mut sum = [0.0f32; 3];
            for dy in 0..sy {
                for dx in 0..sx {
                    let texel = texels[((y * sy + dy) * size.0 + x * sx + dx) as usize];
                    for (s, v) in sum.iter_mut().zip(texel) {
                        *s += v;
                    }
                }
            }
            out.push(sum.map(|s| s / (sx * sy) as f32));
        }
    }
    out
}

/// Linear texels as [`FORMAT`]'s bytes.
fn encoded(texels: &[[f32; 3]]) -> Vec<u8> {
    texels
        .iter()
        .flat_map(|t| {
            let [r, g, b] = t.map(|v| (linear_to_srgb(f64::from(v).clamp(0.0, 1.0)) * 255.0).round() as u8);
            [r, g, b, 255]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_chain_halves_down_to_one_texel_keeping_the_mean() {
        let map = SurfaceMap::new(2, 1, vec![[1.0, 0.0, 0.25, 0.0], [0.0, 1.0, 0.25, 0.0]]).unwrap();
        let chain = mip_chain(&map);
        assert_eq!(chain.len() as u32, mip_levels());
        assert_eq!(chain[0].0, BODY_MAP_SIZE);
        let (size, last) = chain.last().unwrap();
        assert_eq!(*size, (1, 1));
        // The whole map's mean (bilinear resampling keeps it: halves of 1 and 0 give ½), encoded.
        let half = (linear_to_srgb(0.5) * 255.0).round() as u8;
        let quarter = (linear_to_srgb(0.25) * 255.0).round() as u8;
        assert_eq!(last[..3], [half, half, quarter]);
    }
}
