//! The light of the bodies' airs on the GPU (`atmosphere/body_air.wgsl` and `bodies.wgsl` read
//! it): per body with air, two array layers of its [`AirLight`] tables — the light scattered
//! more than once, and the sky's light on its ground — made by the core when the air, the
//! body's size or its albedo changes, and uploaded then.

use firmament_core::atmosphere::Spectrum;
use firmament_core::atmosphere::body::{Body, BodyAir, MAX_BODIES};
use firmament_core::frame::AtmosphereSky;

use super::stages::{array_texture_entry, binding};
use crate::gpu_types::{BODY_AIR_LIGHT_SIZE, body_air_light_layers};

/// What a body's tables are made from: its air, its mean radius (m) and its albedo.
type Key = (BodyAir, f64, Spectrum);

/// The texture of every body's tables, read with the LUTs' sampler (`lut_sampler`).
#[derive(Debug)]
pub(super) struct BodyAirLight {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    /// What each body's layers were made from (`None`: nothing uploaded there).
    uploaded: [Option<Key>; MAX_BODIES],
}

impl BodyAirLight {
    pub(super) fn new(device: &wgpu::Device) -> Self {
        let (width, height) = BODY_AIR_LIGHT_SIZE;
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("firmament AtmospherePass body air light"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 2 * MAX_BODIES as u32,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba16Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("firmament AtmospherePass body air light view"),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        Self {
            texture,
            view,
            uploaded: Default::default(),
        }
    }

    /// Makes and uploads the tables of each of `sky`'s bodies with air whose layers do not
    /// hold them already; other layers are left as they are (the shaders read them only for
    /// bodies with air).
    pub(super) fn prepare(&mut self, queue: &wgpu::Queue, sky: &AtmosphereSky) {
        for (i, body) in sky.bodies.iter().enumerate().take(MAX_BODIES) {
            let Some(key) = key(body) else { continue };
            if self.uploaded[i].as_ref() == Some(&key) {
                continue;
            }
            let Some(light) = body.air_light() else { continue };
            let (width, height) = BODY_AIR_LIGHT_SIZE;
            for (k, texels) in body_air_light_layers(&light).iter().enumerate() {
                queue.write_texture(
                    wgpu::TexelCopyTextureInfo {
                        texture: &self.texture,
                        mip_level: 0,
                        origin: wgpu::Origin3d {
                            x: 0,
                            y: 0,
                            z: (2 * i + k) as u32,
                        },
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
            self.uploaded[i] = Some(key);
        }
    }

    /// The texture's layout entry (the sky stages read it with the LUTs' sampler).
    pub(super) fn entry() -> wgpu::BindGroupLayoutEntry {
        array_texture_entry(binding::BODY_AIR_LIGHT)
    }

    /// The texture at its binding.
    pub(super) fn resource(&self) -> (u32, wgpu::BindingResource<'_>) {
        (binding::BODY_AIR_LIGHT, wgpu::BindingResource::TextureView(&self.view))
    }
}

/// What `body`'s tables are made from, if it has air.
fn key(body: &Body) -> Option<Key> {
    Some((body.air.clone()?, body.mean_radius(), body.albedo))
}
