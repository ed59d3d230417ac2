//! The planet's surface map on the GPU (`atmosphere/surface.wgsl` reads it): the core's
//! [`SurfaceMap`] resampled to one fixed-size texture, uploaded when the scene's map changes.

use std::sync::Arc;

use firmament_core::atmosphere::surface::map::texel_centres;
use firmament_core::atmosphere::surface::{Surface, SurfaceMap};

use super::stages::{binding, sampler_entry, texture_entry};

/// The surface texture's size, texels (longitude × latitude): about 20 km a texel at Earth's
/// equator. Any map is resampled to it (bilinear at the new texel centres).
pub(super) const SURFACE_MAP_SIZE: (u32, u32) = (2048, 1024);

/// The surface texture (linear albedo in rgb, water fraction in a; Rgba16Float) and its sampler.
#[derive(Debug)]
pub(super) struct SurfaceTexture {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    sampler: wgpu::Sampler,
    /// The map the texture holds (`None`: nothing uploaded yet).
    uploaded: Option<Arc<SurfaceMap>>,
}

impl SurfaceTexture {
    pub(super) fn new(device: &wgpu::Device) -> Self {
        let texture = crate::targets::texture_2d(
            device,
            "firmament AtmospherePass surface map",
            SURFACE_MAP_SIZE,
            wgpu::TextureFormat::Rgba16Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        );
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("firmament AtmospherePass surface map sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            // Between the bodies' maps' mip levels; the other maps have one.
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        Self {
            texture,
            view,
            sampler,
            uploaded: None,
        }
    }

    /// Uploads `surface`'s map when it is not the one the texture holds (the same `Arc`); without
    /// a surface the texture is left as it is (the shaders do not read it).
    pub(super) fn prepare(&mut self, queue: &wgpu::Queue, surface: Option<&Surface>) {
        let Some(surface) = surface else { return };
        if self.uploaded.as_ref().is_some_and(|m| Arc::ptr_eq(m, &surface.map) || **m == *surface.map) {
            return;
        }
        let (width, height) = SURFACE_MAP_SIZE;
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &self.texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(&resampled(&surface.map)),
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
        self.uploaded = Some(surface.map.clone());
    }

    /// The layout entries of the texture and the maps' sampler (`map_sampler`), for stages
    /// that bind no other map.
    pub(super) fn entries() -> [wgpu::BindGroupLayoutEntry; 2] {
        [Self::texture_entry(), sampler_entry(binding::MAP_SAMPLER)]
    }

    /// The texture and this pass's sampler at their bindings.
    pub(super) fn resources(&self) -> [(u32, wgpu::BindingResource<'_>); 2] {
        [
            self.texture_resource(),
            (binding::MAP_SAMPLER, wgpu::BindingResource::Sampler(&self.sampler)),
        ]
    }

    /// The texture's layout entry alone, for stages that bind `map_sampler` with the cloud
    /// coverage maps (one sampler where the limits allow two).
    pub(super) fn texture_entry() -> wgpu::BindGroupLayoutEntry {
        texture_entry(binding::SURFACE_MAP, true)
    }

    /// The texture at its binding.
    pub(super) fn texture_resource(&self) -> (u32, wgpu::BindingResource<'_>) {
        (binding::SURFACE_MAP, wgpu::BindingResource::TextureView(&self.view))
    }
}

/// `map` resampled to [`SURFACE_MAP_SIZE`] (the core's bilinear lookup at the new texel centres),
/// as half floats' bits, four to a texel.
fn resampled(map: &SurfaceMap) -> Vec<u16> {
    let (width, height) = SURFACE_MAP_SIZE;
    texel_centres(width, height)
        .flat_map(|(latitude, longitude)| map.sample(latitude, longitude).map(|v| half::f16::from_f64(v).to_bits()))
        .collect()
}
