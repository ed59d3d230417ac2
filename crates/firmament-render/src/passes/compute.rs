//! Compute building blocks shared by the passes: bind group layout entries for compute (and
//! fragment) stages, and a compute pipeline with its bind group (`ComputeStage`).

/// A sampled 2D texture, seen by the fragment and compute stages.
pub(crate) fn texture_entry(binding: u32, filterable: bool) -> wgpu::BindGroupLayoutEntry {
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
pub(crate) fn sampler_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        count: None,
    }
}

/// A write-only 2D storage texture of `format`, for compute stages.
pub(crate) fn storage_entry(binding: u32, format: wgpu::TextureFormat) -> wgpu::BindGroupLayoutEntry {
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
pub(crate) fn storage_buffer_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
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
pub(crate) fn bind_group(
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

/// A compute pipeline (entry point `cs_main`) and its bind group layout, dispatched with any
/// bind group of that layout (a pass that runs one shader over several images).
#[derive(Debug)]
pub(crate) struct ComputeKernel {
    owner: &'static str,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl ComputeKernel {
    /// Builds the pipeline from `source` with one bind group layout of `entries` and the
    /// pipeline-overridable `constants` set.
    pub(crate) fn new(
        device: &wgpu::Device,
        owner: &'static str,
        source: &str,
        entries: &[wgpu::BindGroupLayoutEntry],
        constants: &[(&str, f64)],
    ) -> Self {
        Self::with_groups(device, owner, (source, "cs_main"), entries, constants, &[])
    }

    /// [`new`](Self::new) for the entry point `source.1` of `source.0`, with the layouts of
    /// `later_groups` as bind groups 1, 2, … after its own.
    pub(crate) fn with_groups(
        device: &wgpu::Device,
        owner: &'static str,
        (source, entry_point): (&str, &str),
        entries: &[wgpu::BindGroupLayoutEntry],
        constants: &[(&str, f64)],
        later_groups: &[&wgpu::BindGroupLayout],
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
            bind_group_layouts: &std::iter::once(Some(&layout))
                .chain(later_groups.iter().map(|&l| Some(l)))
                .collect::<Vec<_>>(),
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(&format!("firmament {owner} pipeline")),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some(entry_point),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                ..Default::default()
            },
            cache: None,
        });
        Self {
            owner,
            pipeline,
            layout,
        }
    }

    /// A bind group of `resources` for this kernel's layout.
    pub(crate) fn bind(&self, device: &wgpu::Device, resources: &[(u32, wgpu::BindingResource<'_>)]) -> wgpu::BindGroup {
        bind_group(device, self.owner, &self.layout, resources)
    }

    /// Dispatches `workgroups` with `bind_group` in a compute pass of its own.
    pub(crate) fn dispatch(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        bind_group: &wgpu::BindGroup,
        workgroups: (u32, u32, u32),
    ) {
        self.dispatch_with(encoder, bind_group, &[], workgroups);
    }

    /// [`dispatch`](Self::dispatch) with `later` bound as groups 1, 2, ….
    pub(crate) fn dispatch_with(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        bind_group: &wgpu::BindGroup,
        later: &[&wgpu::BindGroup],
        workgroups: (u32, u32, u32),
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&format!("firmament {}", self.owner)),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        for (i, group) in later.iter().enumerate() {
            pass.set_bind_group(i as u32 + 1, *group, &[]);
        }
        pass.dispatch_workgroups(workgroups.0, workgroups.1, workgroups.2);
    }
}

/// A [`ComputeKernel`] with the one bind group it is dispatched with.
#[derive(Debug)]
pub(crate) struct ComputeStage {
    kernel: ComputeKernel,
    bind_group: wgpu::BindGroup,
}

impl ComputeStage {
    /// Builds the pipeline from `source` with one bind group of `entries` holding `resources`.
    pub(crate) fn new(
        device: &wgpu::Device,
        owner: &'static str,
        source: &str,
        entries: &[wgpu::BindGroupLayoutEntry],
        resources: &[(u32, wgpu::BindingResource<'_>)],
    ) -> Self {
        Self::with_constants(device, owner, source, entries, resources, &[])
    }

    /// A stage of `kernel` whose bind group holds `resources`.
    pub(crate) fn of_kernel(
        device: &wgpu::Device,
        kernel: ComputeKernel,
        resources: &[(u32, wgpu::BindingResource<'_>)],
    ) -> Self {
        let bind_group = kernel.bind(device, resources);
        Self { kernel, bind_group }
    }

    /// [`new`](Self::new) with pipeline-overridable `constants` set.
    pub(crate) fn with_constants(
        device: &wgpu::Device,
        owner: &'static str,
        source: &str,
        entries: &[wgpu::BindGroupLayoutEntry],
        resources: &[(u32, wgpu::BindingResource<'_>)],
        constants: &[(&str, f64)],
    ) -> Self {
        let kernel = ComputeKernel::new(device, owner, source, entries, constants);
        let bind_group = kernel.bind(device, resources);
        Self { kernel, bind_group }
    }

    /// Binds `resources` instead (new targets of the same layout).
    pub(crate) fn rebind(&mut self, device: &wgpu::Device, resources: &[(u32, wgpu::BindingResource<'_>)]) {
        self.bind_group = self.kernel.bind(device, resources);
    }

    /// Dispatches `workgroups` in a compute pass of its own.
    pub(crate) fn dispatch(&self, encoder: &mut wgpu::CommandEncoder, workgroups: (u32, u32, u32)) {
        self.kernel.dispatch(encoder, &self.bind_group, workgroups);
    }

    /// [`dispatch`](Self::dispatch) with `later` bound as groups 1, 2, ….
    pub(crate) fn dispatch_with(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        later: &[&wgpu::BindGroup],
        workgroups: (u32, u32, u32),
    ) {
        self.kernel.dispatch_with(encoder, &self.bind_group, later, workgroups);
    }
}
