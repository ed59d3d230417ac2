//! The building blocks of the atmosphere pass: its binding numbers, its own layout entries, and a
//! pipeline with its bind group for full-screen draws (`Stage`, drawn into the caller's pass);
//! compute dispatches and the common entries are `passes::compute`'s.

use crate::passes::common::PassPipeline;
pub(super) use crate::passes::compute::{
    ComputeKernel, ComputeStage, bind_group, sampler_entry, storage_buffer_entry, storage_entry, texture_entry,
};

/// Binding numbers shared by every atmosphere shader: those `shaders/atmosphere/bindings.wgsl`
/// declares (a test compares the two).
pub(super) mod binding {
    pub(crate) const PARAMS: u32 = 0;
    pub(crate) const VIEW: u32 = 1;
    pub(crate) const TRANSMITTANCE: u32 = 2;
    pub(crate) const MULTISCATTERING: u32 = 3;
    pub(crate) const SKY_VIEW: u32 = 4;
    pub(crate) const SAMPLER: u32 = 5;
    pub(crate) const TRANSMITTANCE_OUT: u32 = 6;
    pub(crate) const IRRADIANCE: u32 = 7;
    pub(crate) const AERIAL_SCATTERING_OUT: u32 = 8;
    pub(crate) const AERIAL_TRANSMITTANCE_OUT: u32 = 9;
    pub(crate) const AERIAL_SCATTERING: u32 = 10;
    pub(crate) const AERIAL_TRANSMITTANCE: u32 = 11;
    pub(crate) const SCENE_DEPTH: u32 = 12;
    pub(crate) const MULTISCATTERING_OUT: u32 = 13;
    pub(crate) const PREVIOUS_GROUND_IRRADIANCE: u32 = 14;
    pub(crate) const CLOUDS: u32 = 15;
    pub(crate) const CLOUD_COVERAGE_MAPS: u32 = 16;
    pub(crate) const MAP_SAMPLER: u32 = 17;
    pub(crate) const SURFACE_MAP: u32 = 18;
    pub(crate) const SKY_VIEW_OUT: u32 = 19;
    pub(crate) const SKY_OUT: u32 = 20;
    pub(crate) const BODY_MAPS: u32 = 21;
    pub(crate) const BODY_AIR_LIGHT: u32 = 22;
    pub(crate) const HDR_IN: u32 = 23;
    pub(crate) const RING_LIGHT: u32 = 27;
    pub(crate) const HDR_OUT: u32 = 24;
    pub(crate) const SKY_LIGHTING_PARAMS: u32 = 25;
    pub(crate) const SKY_LIGHTING_OUT: u32 = 26;
    pub(crate) const MULTISCATTERING_ORDERS: u32 = 28;
    pub(crate) const CLOUD_SHADOW_OUT: u32 = 29;
    pub(crate) const CLOUD_SHADOW_MAP: u32 = 30;
}

/// One of the pass's render pipelines with its bind group.
#[derive(Debug)]
pub(super) struct Stage {
    pub(super) pipeline: wgpu::RenderPipeline,
    pub(super) bind_group: wgpu::BindGroup,
}

impl Stage {
    /// Builds a stage whose bind group holds `resources` at the bindings the pipeline's entries
    /// declare.
    pub(super) fn new(
        device: &wgpu::Device,
        pipeline: PassPipeline<'_>,
        resources: &[(u32, wgpu::BindingResource<'_>)],
    ) -> Self {
        let owner = pipeline.owner;
        let (pipeline, layout) = pipeline.build(device);
        let bind_group = bind_group(device, owner, &layout, resources);
        Self { pipeline, bind_group }
    }
}

/// A uniform buffer seen by every stage.
pub(super) fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ..crate::passes::common::uniform_entry(binding)
    }
}

/// A filterable array texture (the multiple-scattering moments, the bodies' maps), seen by the
/// fragment and compute stages.
pub(super) fn array_texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    let mut entry = texture_entry(binding, true);
    if let wgpu::BindingType::Texture { view_dimension, .. } = &mut entry.ty {
        *view_dimension = wgpu::TextureViewDimension::D2Array;
    }
    entry
}

#[cfg(test)]
mod tests {
    use super::binding;

    /// Every binding of [`binding`] by the name of its WGSL global.
    fn rust_bindings() -> Vec<(String, u32)> {
        [
            ("atmosphere", binding::PARAMS),
            ("view", binding::VIEW),
            ("transmittance_lut", binding::TRANSMITTANCE),
            ("multiscattering_lut", binding::MULTISCATTERING),
            ("sky_view_lut", binding::SKY_VIEW),
            ("lut_sampler", binding::SAMPLER),
            ("transmittance_out", binding::TRANSMITTANCE_OUT),
            ("irradiance_lut", binding::IRRADIANCE),
            ("aerial_scattering_out", binding::AERIAL_SCATTERING_OUT),
            ("aerial_transmittance_out", binding::AERIAL_TRANSMITTANCE_OUT),
            ("aerial_scattering", binding::AERIAL_SCATTERING),
            ("aerial_transmittance", binding::AERIAL_TRANSMITTANCE),
            ("scene_depth", binding::SCENE_DEPTH),
            ("previous_ground_irradiance", binding::PREVIOUS_GROUND_IRRADIANCE),
            ("clouds", binding::CLOUDS),
            ("cloud_coverage_maps", binding::CLOUD_COVERAGE_MAPS),
            ("map_sampler", binding::MAP_SAMPLER),
            ("surface_map", binding::SURFACE_MAP),
            ("body_maps", binding::BODY_MAPS),
            ("body_air_light", binding::BODY_AIR_LIGHT),
            ("ring_light", binding::RING_LIGHT),
            ("cloud_shadow_out", binding::CLOUD_SHADOW_OUT),
            ("cloud_shadow_map", binding::CLOUD_SHADOW_MAP),
            ("multiscattering_out", binding::MULTISCATTERING_OUT),
            ("multiscattering_orders", binding::MULTISCATTERING_ORDERS),
            ("sky_view_out", binding::SKY_VIEW_OUT),
            ("sky_out", binding::SKY_OUT),
            ("hdr_in", binding::HDR_IN),
            ("hdr_out", binding::HDR_OUT),
            ("lighting", binding::SKY_LIGHTING_PARAMS),
            ("sky_lighting", binding::SKY_LIGHTING_OUT),
        ]
        .map(|(name, number)| (name.to_owned(), number))
        .into()
    }

    #[test]
    fn the_binding_numbers_are_those_of_the_wgsl() {
        let mut rust = rust_bindings();
        rust.sort();
        assert_eq!(crate::shaders::declared_bindings("atmosphere/bindings"), rust);
    }
}
