//! What the passes share: the sky's target description, pipeline building, blend and depth states
//! for drawing at the far plane, uniform buffers and layout entries, and begun render passes.

use firmament_core::DepthConvention;

/// What a sky pass draws into: the colour and depth formats and the depth buffer's convention
/// (the sky goes at its far plane, tested against it). Pipelines are built for one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct SkyTarget {
    /// The colour attachment's format.
    pub color: wgpu::TextureFormat,
    /// The depth attachment's format.
    pub depth: wgpu::TextureFormat,
    /// How its depths run.
    pub convention: firmament_core::DepthConvention,
}

impl SkyTarget {
    /// firmament's own targets: [`HDR_FORMAT`](crate::HDR_FORMAT) colour,
    /// [`DEPTH_FORMAT`](crate::DEPTH_FORMAT) reversed-Z depth.
    pub const OWN: Self = Self::new(
        crate::targets::HDR_FORMAT,
        crate::targets::DEPTH_FORMAT,
        firmament_core::DepthConvention::Reversed,
    );

    /// A target of these formats and convention.
    pub const fn new(
        color: wgpu::TextureFormat,
        depth: wgpu::TextureFormat,
        convention: firmament_core::DepthConvention,
    ) -> Self {
        Self {
            color,
            depth,
            convention,
        }
    }
}

/// Additive blending: light added to what the target holds (the night sky over the sky, flares
/// over everything); alpha is kept.
pub(crate) const ADDITIVE: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::Zero,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
};

/// A colour attachment of `view` that keeps (loads and stores) what earlier passes left.
pub(crate) fn load_color_attachment(view: &wgpu::TextureView) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Load,
            store: wgpu::StoreOp::Store,
        },
    }
}

/// Begins a render pass that loads and stores `color` and `depth` (for passes drawn over what
/// earlier passes left).
pub(crate) fn begin_load_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    color: &wgpu::TextureView,
    depth: &wgpu::TextureView,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(load_color_attachment(color))],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: depth,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        ..Default::default()
    })
}

/// Begins a render pass that clears `depth` to `depth_value` (reversed-Z) and, if given, a colour
/// view to its colour.
pub fn begin_clear_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    color: Option<(&wgpu::TextureView, wgpu::Color)>,
    depth: &wgpu::TextureView,
    depth_value: f32,
) -> wgpu::RenderPass<'e> {
    let color_attachment = color.map(|(view, clear)| wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(clear),
            store: wgpu::StoreOp::Store,
        },
    });
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[color_attachment],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: depth,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(depth_value),
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: None,
        }),
        ..Default::default()
    })
}

/// Depth state of a sky drawn at the far plane (reversed-Z depth 0, standard depth 1): tested
/// `GreaterEqual` (reversed) or `LessEqual` (standard) without writes, so it fills exactly the
/// pixels nothing nearer covered.
pub(crate) fn far_plane_depth_state(
    format: wgpu::TextureFormat,
    convention: DepthConvention,
) -> wgpu::DepthStencilState {
    let compare = match convention {
        DepthConvention::Standard => wgpu::CompareFunction::LessEqual,
        _ => wgpu::CompareFunction::GreaterEqual,
    };
    wgpu::DepthStencilState {
        format,
        depth_write_enabled: Some(false),
        depth_compare: Some(compare),
        stencil: wgpu::StencilState::default(),
        bias: wgpu::DepthBiasState::default(),
    }
}

/// The far-plane passes' `FAR_DEPTH` override (`common/fullscreen.wgsl`, `night_sky.wgsl`) for
/// `convention`.
pub(crate) fn far_depth_constant(convention: DepthConvention) -> (&'static str, f64) {
    ("FAR_DEPTH", convention.far_depth())
}

/// A bilinear sampler clamped at the edges, labelled for its owner.
pub(crate) fn linear_clamp_sampler(device: &wgpu::Device, label: &str) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some(label),
        address_mode_u: wgpu::AddressMode::ClampToEdge,
        address_mode_v: wgpu::AddressMode::ClampToEdge,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    })
}

/// A uniform buffer of `T`'s size, labelled for its owner.
pub(crate) fn uniform_buffer<T>(device: &wgpu::Device, label: &str) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: std::mem::size_of::<T>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// A bind group layout entry for a uniform buffer visible to the fragment and vertex stages.
pub(crate) fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    uniform_entry_in(binding, wgpu::ShaderStages::VERTEX_FRAGMENT)
}

/// A bind group layout entry for a uniform buffer visible to `stages`.
pub(crate) fn uniform_entry_in(binding: u32, stages: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: stages,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// What differs between firmament's single-bind-group pipelines (full-screen triangles when
/// `vertex_buffers` is empty, meshes otherwise).
pub(crate) struct PassPipeline<'a> {
    /// The owner, for labels (`"GradientSkyPass"`).
    pub(crate) owner: &'a str,
    /// Composed WGSL with `vs_main` and `fs_main`.
    pub(crate) source: &'a str,
    /// The single bind group's layout entries.
    pub(crate) entries: &'a [wgpu::BindGroupLayoutEntry],
    /// Colour target format.
    pub(crate) color: wgpu::TextureFormat,
    /// Depth state, if the pass has a depth attachment.
    pub(crate) depth_stencil: Option<wgpu::DepthStencilState>,
    /// Vertex buffer layouts (empty for a full-screen triangle made from the vertex index).
    pub(crate) vertex_buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    /// Topology, winding and culling.
    pub(crate) primitive: wgpu::PrimitiveState,
    /// Values of the shader's pipeline-overridable constants (`override` in WGSL).
    pub(crate) constants: &'a [(&'a str, f64)],
}

impl PassPipeline<'_> {
    /// Builds the pipeline and its bind group layout, labelled for the owner.
    pub(crate) fn build(&self, device: &wgpu::Device) -> (wgpu::RenderPipeline, wgpu::BindGroupLayout) {
        self.build_blended(device, None)
    }

    /// Builds the pipeline with `blend` on its colour target, and its bind group layout.
    pub(crate) fn build_blended(
        &self,
        device: &wgpu::Device,
        blend: Option<wgpu::BlendState>,
    ) -> (wgpu::RenderPipeline, wgpu::BindGroupLayout) {
        self.build_with_groups(device, blend, &[])
    }

    /// Builds the pipeline with `blend` and the layouts of `later_groups` as bind groups 1, 2, …
    /// after its own (group 0, whose layout it returns).
    pub(crate) fn build_with_groups(
        &self,
        device: &wgpu::Device,
        blend: Option<wgpu::BlendState>,
        later_groups: &[&wgpu::BindGroupLayout],
    ) -> (wgpu::RenderPipeline, wgpu::BindGroupLayout) {
        let targets = [Some(wgpu::ColorTargetState {
            format: self.color,
            blend,
            write_mask: wgpu::ColorWrites::ALL,
        })];
        let owner = self.owner;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&format!("firmament {owner} shader")),
            source: wgpu::ShaderSource::Wgsl(self.source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("firmament {owner} bind group layout")),
            entries: self.entries,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&format!("firmament {owner} pipeline layout")),
            bind_group_layouts: &std::iter::once(Some(&layout))
                .chain(later_groups.iter().map(|&l| Some(l)))
                .collect::<Vec<_>>(),
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(&format!("firmament {owner} pipeline")),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: self.constants,
                    ..Default::default()
                },
                buffers: self.vertex_buffers,
            },
            primitive: self.primitive,
            depth_stencil: self.depth_stencil.clone(),
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: self.constants,
                    ..Default::default()
                },
                targets: &targets,
            }),
            multiview_mask: None,
            cache: None,
        });
        (pipeline, layout)
    }
}
