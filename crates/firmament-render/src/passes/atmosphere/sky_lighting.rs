//! The light the sky and the suns give at the camera, for users' own materials: one compute
//! dispatch per frame (`atmosphere/sky_lighting.wgsl`, after the sky-view LUT) fills a
//! [`SkyLightingGpu`] buffer with each sun's world direction and `E·T` at the camera and the sky's
//! radiance as spherical harmonics of bands 0–2, which `shaders/include/firmament_lighting.wgsl`
//! turns into irradiance on any normal (Ramamoorthi & Hanrahan 2001). Conventions and units:
//! [`crate::gpu_types::sky_lighting`].
//!
//! The sky is the sky-view LUT's (the sky the sky pass draws inside the atmosphere), sampled at
//! the centres of [`SKY_LIGHTING_GRID`](crate::gpu_types::sky_lighting::SKY_LIGHTING_GRID) equal-area cells about the camera's local up, one
//! workgroup of 256 threads summed in shared memory.

use std::num::NonZeroU64;

use firmament_core::Camera;
use firmament_core::frame::AtmosphereSky;

use super::luts::AtmosphereLuts;
use super::stages::{ComputeStage, binding, sampler_entry, storage_buffer_entry, texture_entry, uniform_entry};
use crate::gpu_types::{SkyLightingGpu, SkyLightingParamsUniforms};
use crate::passes::common::uniform_buffer;
use crate::shaders;

/// The bind group layout entry of the lighting buffer in a user's pipeline, at `binding`: a
/// uniform buffer of `size_of::<SkyLightingGpu>()` bytes (416) seen by the vertex, fragment and
/// compute stages, as `shaders::FIRMAMENT_LIGHTING_WGSL` declares it.
pub fn sky_lighting_layout_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: NonZeroU64::new(std::mem::size_of::<SkyLightingGpu>() as u64),
        },
        count: None,
    }
}

/// The stage: its parameters, the lighting buffer it writes, and its pipeline.
#[derive(Debug)]
pub(super) struct SkyLightingStage {
    stage: ComputeStage,
    params: wgpu::Buffer,
    output: wgpu::Buffer,
}

/// What the stage reads besides its own buffers.
pub(super) struct SkyLightingResources<'a> {
    pub(super) params: &'a wgpu::Buffer,
    pub(super) view: &'a wgpu::Buffer,
    pub(super) luts: &'a AtmosphereLuts,
    pub(super) sampler: &'a wgpu::Sampler,
    pub(super) surface: &'a super::surface::SurfaceTexture,
    pub(super) ring_light: &'a super::ring_light::RingLight,
}

impl SkyLightingStage {
    pub(super) fn new(device: &wgpu::Device, resources: &SkyLightingResources<'_>) -> Self {
        let params =
            uniform_buffer::<SkyLightingParamsUniforms>(device, "firmament AtmospherePass sky lighting params");
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("firmament AtmospherePass sky lighting buffer"),
            size: std::mem::size_of::<SkyLightingGpu>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let mut entries = vec![
            uniform_entry(binding::PARAMS),
            uniform_entry(binding::VIEW),
            texture_entry(binding::TRANSMITTANCE, false),
            texture_entry(binding::IRRADIANCE, true),
            texture_entry(binding::SKY_VIEW, true),
            sampler_entry(binding::SAMPLER),
            uniform_entry(binding::SKY_LIGHTING_PARAMS),
            storage_buffer_entry(binding::SKY_LIGHTING_OUT),
        ];
        // The ground the sky-view LUT leaves out when the planet has a surface.
        entries.extend(super::surface::SurfaceTexture::entries());
        entries.push(super::ring_light::RingLight::entry());
        let luts = resources.luts;
        let mut bound = vec![
            (binding::PARAMS, resources.params.as_entire_binding()),
            (binding::VIEW, resources.view.as_entire_binding()),
            (
                binding::TRANSMITTANCE,
                wgpu::BindingResource::TextureView(&luts.transmittance.view),
            ),
            (
                binding::IRRADIANCE,
                wgpu::BindingResource::TextureView(&luts.irradiance.view),
            ),
            (
                binding::SKY_VIEW,
                wgpu::BindingResource::TextureView(&luts.sky_view.view),
            ),
            (binding::SAMPLER, wgpu::BindingResource::Sampler(resources.sampler)),
            (binding::SKY_LIGHTING_PARAMS, params.as_entire_binding()),
            (binding::SKY_LIGHTING_OUT, output.as_entire_binding()),
        ];
        bound.extend(resources.surface.resources());
        bound.push(resources.ring_light.resource());
        let stage = ComputeStage::new(
            device,
            "AtmospherePass sky lighting",
            &shaders::ATMOSPHERE_SKY_LIGHTING,
            &entries,
            &bound,
        );
        Self { stage, params, output }
    }

    /// Uploads the frame's planet rotation and whether the sky lights the camera.
    pub(super) fn prepare(&self, queue: &wgpu::Queue, sky: &AtmosphereSky, camera: &Camera) {
        let params = SkyLightingParamsUniforms::new(sky, camera);
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
    }

    /// Encodes the one-workgroup dispatch (after the frame's sky-view LUT).
    pub(super) fn record(&self, encoder: &mut wgpu::CommandEncoder) {
        self.stage.dispatch(encoder, (1, 1, 1));
    }

    /// The lighting buffer.
    pub(super) fn buffer(&self) -> &wgpu::Buffer {
        &self.output
    }
}
