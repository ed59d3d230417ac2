//! The rings' light on the ground on the GPU (`atmosphere/rings.wgsl` reads it): per sun, one
//! array layer of the core's [`Rings::light_table`] through the air's [`GroundTransmittance`],
//! made when the rings, the planet's shape, its air or the sun's elevation over the ring plane
//! changes, and uploaded then.

use firmament_core::atmosphere::Atmosphere;
use firmament_core::atmosphere::rings::{GroundTransmittance, RING_LIGHT_TABLE_SIZE, Rings};
use firmament_core::frame::{AtmosphereSky, MAX_SUNS};
use glam::{DQuat, DVec3};

use super::stages::{array_texture_entry, binding};
use super::table_layers::TableLayers;
use crate::gpu_types::half_texels;

/// The sun's elevation over the ring plane is kept to this step (sine, about 0.006°) in what a
/// table was made from, so a sun that drifts by less (a time-lapse's) does not remake it.
const SUN_ELEVATION_STEP: f64 = 1e-4;

/// What a sun's table is made from: the rings, the planet and its air (unposed) and the sine of
/// the sun's elevation over the ring plane in steps of [`SUN_ELEVATION_STEP`].
type Key = (Rings, Atmosphere, i64);

/// The texture of every sun's table, read with the LUTs' sampler (`lut_sampler`).
#[derive(Debug)]
pub(super) struct RingLight {
    layers: TableLayers,
    /// What each sun's layer was made from (`None`: nothing uploaded there).
    uploaded: [Option<Key>; MAX_SUNS],
}

impl RingLight {
    pub(super) fn new(device: &wgpu::Device) -> Self {
        let (width, height) = RING_LIGHT_TABLE_SIZE;
        Self {
            layers: TableLayers::new(device, "ring light", (width as u32, height as u32), MAX_SUNS as u32),
            uploaded: Default::default(),
        }
    }

    /// Makes and uploads the table of each of `sky`'s suns whose layer does not hold it already;
    /// without rings nothing is made (the shaders read the table only with rings).
    pub(super) fn prepare(&mut self, queue: &wgpu::Queue, sky: &AtmosphereSky) {
        let Some(rings) = &sky.rings else { return };
        let planet = &sky.atmosphere.planet;
        let mut unposed = sky.atmosphere.clone();
        unposed.planet.center = DVec3::ZERO;
        unposed.planet.orientation = DQuat::IDENTITY;
        let mut air = None;
        for (i, sun) in sky.suns.iter().enumerate().take(MAX_SUNS) {
            let s = planet.direction_to_planet_frame(sun.direction).normalize_or_zero();
            let step = (s.z / SUN_ELEVATION_STEP).round() as i64;
            if matches!(&self.uploaded[i], Some((r, a, k)) if r == rings && *a == unposed && *k == step) {
                continue;
            }
            let air = air.get_or_insert_with(|| GroundTransmittance::new(&sky.atmosphere));
            let table = rings.light_table(planet.radii, s, air);
            self.layers.write(queue, i as u32, &half_texels(&table));
            self.uploaded[i] = Some((rings.clone(), unposed.clone(), step));
        }
    }

    /// The texture's layout entry (the stages that light the ground read it with the LUTs'
    /// sampler).
    pub(super) fn entry() -> wgpu::BindGroupLayoutEntry {
        array_texture_entry(binding::RING_LIGHT)
    }

    /// The texture at its binding.
    pub(super) fn resource(&self) -> (u32, wgpu::BindingResource<'_>) {
        (binding::RING_LIGHT, wgpu::BindingResource::TextureView(self.layers.view()))
    }
}
