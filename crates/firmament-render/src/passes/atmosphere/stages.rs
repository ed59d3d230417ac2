//! The building blocks of the atmosphere pass: bind group layout entries, and a pipeline with its
//! bind group for full-screen draws (`Stage`, drawn into the caller's pass) and compute dispatches
//! (`ComputeStage`).

use crate::passes::common::PassPipeline;

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
    pub(crate) const SKY_VIEW_OUT: u32 = 19;
    pub(crate) const SKY_OUT: u32 = 20;
    pub(crate) const HDR_IN: u32 = 23;
    pub(crate) const HDR_OUT: u32 = 24;
    pub(crate) const SKY_LIGHTING_PARAMS: u32 = 25;
    pub(crate) const SKY_LIGHTING_OUT: u32 = 26;
    pub(crate) const MULTISCATTERING_ORDERS: u32 = 28;
}

/// A sampled 2D texture, seen by the fragment and compute stages.
pub(super) fn texture_entry(binding: u32, filterable: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A filtering sampler, seen by the fragment and compute stages.
pub(super) fn sampler_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        count: None,
    }
}

/// A write-only 2D storage texture of `format`, for compute stages.
pub(super) fn storage_entry(binding: u32, format: wgpu::TextureFormat) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
        count: None,
    }
}

/// A read-write storage buffer, for compute stages.
pub(super) fn storage_buffer_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: false },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A bind group of `resources` (binding, resource) for `layout`, labelled for `owner`.
pub(super) fn bind_group(
    device: &wgpu::Device,
    owner: &str,
    layout: &wgpu::BindGroupLayout,
    resources: &[(u32, wgpu::BindingResource<'_>)],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
        .iter()
        .map(|(binding, resource)| wgpu::BindGroupEntry {
            binding: *binding,
            resource: resource.clone(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(&format!("firmament {owner} bind group")),
        layout,
        entries: &entries,
    })
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

/// A compute pipeline (entry point `cs_main`) with its bind group.
#[derive(Debug)]
pub(super) struct ComputeStage {
    owner: &'static str,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    bind_group: wgpu::BindGroup,
}

impl ComputeStage {
    /// Builds the pipeline from `source` with one bind group of `entries` holding `resources`.
    pub(super) fn new(
        device: &wgpu::Device,
        owner: &'static str,
        source: &str,
        entries: &[wgpu::BindGroupLayoutEntry],
        resources: &[(u32, wgpu::BindingResource<'_>)],
    ) -> Self {
        Self::with_constants(device, owner, source, entries, resources, &[])
    }

    /// [`new`](Self::new) with pipeline-overridable `constants` set.
    pub(super) fn with_constants(
        device: &wgpu::Device,
        owner: &'static str,
        source: &str,
        entries: &[wgpu::BindGroupLayoutEntry],
        resources: &[(u32, wgpu::BindingResource<'_>)],
        constants: &[(&str, f64)],
    ) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&format!("firmament {owner} shader")),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("firmament {owner} bind group layout")),
            entries,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&format!("firmament {owner} pipeline layout")),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(&format!("firmament {owner} pipeline")),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("cs_main"),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                ..Default::default()
            },
            cache: None,
        });
        let bind_group = bind_group(device, owner, &layout, resources);
        Self {
            owner,
            pipeline,
            layout,
            bind_group,
        }
    }

    /// Binds `resources` instead (new targets of the same layout).
    pub(super) fn rebind(&mut self, device: &wgpu::Device, resources: &[(u32, wgpu::BindingResource<'_>)]) {
        self.bind_group = bind_group(device, self.owner, &self.layout, resources);
    }

    /// Dispatches `workgroups` in a compute pass of its own.
    pub(super) fn dispatch(&self, encoder: &mut wgpu::CommandEncoder, workgroups: (u32, u32, u32)) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&format!("firmament {}", self.owner)),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.dispatch_workgroups(workgroups.0, workgroups.1, workgroups.2);
    }
}

/// A uniform buffer seen by every stage.
pub(super) fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ..crate::passes::common::uniform_entry(binding)
    }
}

/// The multiple-scattering moments' array texture, filterable, seen by the fragment and compute
/// stages.
pub(super) fn moments_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
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
