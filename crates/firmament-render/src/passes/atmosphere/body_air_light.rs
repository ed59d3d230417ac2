//! The light of the bodies' airs on the GPU (`atmosphere/body_air.wgsl` and `bodies.wgsl` read
//! it): per body with air, two array layers of its [`AirLight`] tables — the light scattered
//! more than once, and the sky's light on its ground — made by the core when the air, the
//! body's size or its albedo changes, and uploaded then.

use firmament_core::atmosphere::Spectrum;
use firmament_core::atmosphere::body::{Body, BodyAir, MAX_BODIES};
use firmament_core::frame::AtmosphereSky;

use super::stages::{array_texture_entry, binding};
use super::table_layers::TableLayers;
use crate::gpu_types::{BODY_AIR_LIGHT_SIZE, body_air_light_layers};

/// What a body's tables are made from: its air, its mean radius (m) and its albedo.
type Key = (BodyAir, f64, Spectrum);

/// The texture of every body's tables, read with the LUTs' sampler (`lut_sampler`).
#[derive(Debug)]
pub(super) struct BodyAirLight {
    layers: TableLayers,
    /// What each body's layers were made from (`None`: nothing uploaded there).
    uploaded: [Option<Key>; MAX_BODIES],
}

impl BodyAirLight {
    pub(super) fn new(device: &wgpu::Device) -> Self {
        Self {
            layers: TableLayers::new(device, "body air light", BODY_AIR_LIGHT_SIZE, 2 * MAX_BODIES as u32),
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
            for (k, texels) in body_air_light_layers(&light).iter().enumerate() {
                self.layers.write(queue, (2 * i + k) as u32, texels);
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
        (binding::BODY_AIR_LIGHT, wgpu::BindingResource::TextureView(self.layers.view()))
    }
}

/// What `body`'s tables are made from, if it has air.
fn key(body: &Body) -> Option<Key> {
    Some((body.air.clone()?, body.mean_radius(), body.albedo))
}
