//! The lens-flare passes: an occlusion compute pass that samples the depth buffer (and the
//! planet) over every source's disc and writes its visible share to a GPU buffer, and an element
//! pass that adds each source's flare — glows, streaks, halos, ghosts along the axis through the
//! screen centre — to the HDR target, scaled by that share. Nothing is read back to the CPU.
//!
//! Placement is the core's ([`firmament_core::flare`]): sources are projected and elements laid
//! out in `f64` in `prepare`; the GPU only decides how much of each source is hidden.

use firmament_core::atmosphere::Planet;
use firmament_core::flare::{FlareLayer, MAX_FLARE_ELEMENTS, MAX_FLARE_SOURCES, element_centers, on_screen};
use firmament_core::{Camera, DepthConvention};

use super::flare_images::FlareImageArray;
use crate::gpu_types::{FlareFrameUniforms, FlareInstance, FlareSourceGpu};
use crate::passes::common::{uniform_buffer, uniform_entry, uniform_entry_in};
use crate::shaders;
use crate::targets::HDR_FORMAT;

/// Most element quads in a frame.
const MAX_INSTANCES: usize = MAX_FLARE_SOURCES * MAX_FLARE_ELEMENTS;

/// Binding numbers of both pipelines: those `shaders/flare/bindings.wgsl` declares (a test
/// compares the two).
mod binding {
    /// The frame uniforms (both passes).
    pub(super) const FRAME: u32 = 0;
    /// The sources (occlusion).
    pub(super) const SOURCES: u32 = 1;
    /// The visibility buffer, written (occlusion).
    pub(super) const VISIBILITY: u32 = 2;
    /// The depth buffer (occlusion).
    pub(super) const DEPTH: u32 = 3;
    /// The visibility buffer, read (elements).
    pub(super) const ELEMENT_VISIBILITY: u32 = 4;
    /// The element images (elements).
    pub(super) const IMAGES: u32 = 5;
    /// Their sampler (elements).
    pub(super) const IMAGE_SAMPLER: u32 = 6;
}

/// Lens flares of a frame's suns and lights.
#[derive(Debug)]
pub struct FlarePass {
    occlusion: wgpu::ComputePipeline,
    occlusion_layout: wgpu::BindGroupLayout,
    /// Rebuilt by [`Self::bind_depth`].
    occlusion_bind_group: Option<wgpu::BindGroup>,
    draw: wgpu::RenderPipeline,
    draw_layout: wgpu::BindGroupLayout,
    /// Rebuilt when the flare's images change.
    draw_bind_group: wgpu::BindGroup,
    images: FlareImageArray,
    image_sampler: wgpu::Sampler,
    frame_uniforms: wgpu::Buffer,
    sources: wgpu::Buffer,
    /// One `f32` per source: the visible share, kept between frames for smoothing.
    visibility: wgpu::Buffer,
    instances: wgpu::Buffer,
    source_count: u32,
    instance_count: u32,
    depth_size: (u32, u32),
    /// Seconds between frames for the fade rates; `None` for stills.
    interval: Option<f64>,
    /// The convention of the bound depth buffer.
    convention: DepthConvention,
}

fn storage_entry(binding: u32, visibility: wgpu::ShaderStages, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn buffer(device: &wgpu::Device, label: &str, size: usize, usage: wgpu::BufferUsages) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size as u64,
        usage: usage | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// The element pass's bind group: frame uniforms, visibility, the element images and their sampler.
fn draw_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    frame_uniforms: &wgpu::Buffer,
    visibility: &wgpu::Buffer,
    images: &wgpu::TextureView,
    sampler: &wgpu::Sampler,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("firmament FlarePass element bind group"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: binding::FRAME,
                resource: frame_uniforms.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: binding::ELEMENT_VISIBILITY,
                resource: visibility.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: binding::IMAGES,
                resource: wgpu::BindingResource::TextureView(images),
            },
            wgpu::BindGroupEntry {
                binding: binding::IMAGE_SAMPLER,
                resource: wgpu::BindingResource::Sampler(sampler),
            },
        ],
    })
}

impl FlarePass {
    /// Builds both pipelines for [`HDR_FORMAT`] targets.
    pub fn new(device: &wgpu::Device) -> Self {
        Self::with_format(device, HDR_FORMAT)
    }

    /// Builds both pipelines for colour targets of `format`.
    pub fn with_format(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        use wgpu::ShaderStages as S;
        let frame_uniforms = uniform_buffer::<FlareFrameUniforms>(device, "firmament FlarePass frame uniforms");
        let sources = buffer(
            device,
            "firmament FlarePass sources",
            MAX_FLARE_SOURCES * std::mem::size_of::<FlareSourceGpu>(),
            wgpu::BufferUsages::STORAGE,
        );
        let visibility = buffer(
            device,
            "firmament FlarePass visibility",
            MAX_FLARE_SOURCES * 4,
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        );
        let instances = buffer(
            device,
            "firmament FlarePass element instances",
            MAX_INSTANCES * std::mem::size_of::<FlareInstance>(),
            wgpu::BufferUsages::VERTEX,
        );

        let occlusion_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("firmament FlarePass occlusion bind group layout"),
            entries: &[
                uniform_entry_in(binding::FRAME, S::COMPUTE),
                storage_entry(binding::SOURCES, S::COMPUTE, true),
                storage_entry(binding::VISIBILITY, S::COMPUTE, false),
                wgpu::BindGroupLayoutEntry {
                    binding: binding::DEPTH,
                    visibility: S::COMPUTE,
                    ty: wgpu::BindingType::Texture {
                        // Read as unfilterable float: GLSL has no textureLoad of depth textures.
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("firmament FlarePass occlusion shader"),
            source: wgpu::ShaderSource::Wgsl(shaders::FLARE_OCCLUSION.source().into()),
        });
        let occlusion = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("firmament FlarePass occlusion pipeline"),
            layout: Some(&device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("firmament FlarePass occlusion pipeline layout"),
                bind_group_layouts: &[Some(&occlusion_layout)],
                immediate_size: 0,
            })),
            module: &module,
            entry_point: Some("cs_main"),
            compilation_options: Default::default(),
            cache: None,
        });

        let draw_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("firmament FlarePass element bind group layout"),
            entries: &[
                uniform_entry(binding::FRAME),
                storage_entry(binding::ELEMENT_VISIBILITY, S::FRAGMENT, true),
                wgpu::BindGroupLayoutEntry {
                    binding: binding::IMAGES,
                    visibility: S::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2Array,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: binding::IMAGE_SAMPLER,
                    visibility: S::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("firmament FlarePass element shader"),
            source: wgpu::ShaderSource::Wgsl(shaders::FLARE.source().into()),
        });
        let draw = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("firmament FlarePass element pipeline"),
            layout: Some(&device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("firmament FlarePass element pipeline layout"),
                bind_group_layouts: &[Some(&draw_layout)],
                immediate_size: 0,
            })),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<FlareInstance>() as u64,
                    step_mode: wgpu::VertexStepMode::Instance,
                    attributes: &wgpu::vertex_attr_array![
                        0 => Float32x4, 1 => Float32x4, 2 => Float32x4, 3 => Uint32x4
                    ],
                })],
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleStrip,
                ..Default::default()
            },
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: Some(super::common::ADDITIVE),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let images = FlareImageArray::new(device);
        let image_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("firmament FlarePass element image sampler"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let draw_bind_group = draw_bind_group(
            device,
            &draw_layout,
            &frame_uniforms,
            &visibility,
            &images.view,
            &image_sampler,
        );
        Self {
            occlusion,
            occlusion_layout,
            occlusion_bind_group: None,
            draw,
            draw_layout,
            draw_bind_group,
            images,
            image_sampler,
            frame_uniforms,
            sources,
            visibility,
            instances,
            source_count: 0,
            instance_count: 0,
            depth_size: (0, 0),
            interval: None,
            convention: DepthConvention::Reversed,
        }
    }

    /// Binds the depth buffer (`width` × `height`, in the convention of
    /// [`Self::set_depth_convention`]; reversed-Z by default) whose geometry hides sources.
    /// Call again when the depth texture changes.
    pub fn bind_depth(&mut self, device: &wgpu::Device, depth: &wgpu::TextureView, width: u32, height: u32) {
        self.depth_size = (width, height);
        self.occlusion_bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament FlarePass occlusion bind group"),
            layout: &self.occlusion_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: binding::FRAME,
                    resource: self.frame_uniforms.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: binding::SOURCES,
                    resource: self.sources.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: binding::VISIBILITY,
                    resource: self.visibility.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: binding::DEPTH,
                    resource: wgpu::BindingResource::TextureView(depth),
                },
            ],
        }));
    }

    /// Lays out `layer`'s flares for `camera` (whose aspect must be the target's): which sources
    /// can flare (in front, within the margin), where each element goes, its colour over the
    /// display's `exposure` multiplier (so 1 is white on screen). `planet`, when the sky has one,
    /// hides sources behind it. Visibility fades at the flare's rates over the interval of
    /// [`Self::set_interval`]. Sources and elements past the limits are dropped (scenes validate
    /// the counts).
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layer: &FlareLayer,
        camera: &Camera,
        exposure: f64,
        planet: Option<&Planet>,
    ) {
        self.source_count = 0;
        self.instance_count = 0;
        let Some(flare) = &layer.flare else {
            return;
        };
        if self.images.update(device, queue, &flare.images) {
            self.draw_bind_group = draw_bind_group(
                device,
                &self.draw_layout,
                &self.frame_uniforms,
                &self.visibility,
                &self.images.view,
                &self.image_sampler,
            );
        }
        let positions: Vec<f64> = flare.elements.iter().map(|e| e.position).collect();
        let scale = flare.intensity / if exposure > 0.0 { exposure } else { 1.0 };
        let mut sources = Vec::new();
        let mut instances = Vec::new();
        for source in layer.sources.iter().take(MAX_FLARE_SOURCES) {
            let Some(at) = on_screen(camera, source, flare.margin) else {
                continue;
            };
            let index = sources.len() as u32;
            sources.push(FlareSourceGpu::in_convention(camera, source, &at, self.convention));
            let centers = element_centers(camera, source, &positions);
            for (element, center) in flare.elements.iter().take(MAX_FLARE_ELEMENTS).zip(centers) {
                if let Some(center) = center {
                    let color = element.color * source.color * element.intensity * scale;
                    instances.push(FlareInstance::new(element, center, color, at.edge_fade, index));
                }
            }
        }
        let uniforms = FlareFrameUniforms::new(
            camera,
            planet,
            flare,
            sources.len() as u32,
            self.depth_size,
            self.interval,
        )
        .for_depth_convention(self.convention);
        queue.write_buffer(&self.frame_uniforms, 0, bytemuck::bytes_of(&uniforms));
        if !sources.is_empty() {
            queue.write_buffer(&self.sources, 0, bytemuck::cast_slice(&sources));
        }
        if !instances.is_empty() {
            queue.write_buffer(&self.instances, 0, bytemuck::cast_slice(&instances));
        }
        self.source_count = sources.len() as u32;
        self.instance_count = instances.len() as u32;
    }

    /// Sets the convention of the depth buffer [`Self::bind_depth`] binds (reversed-Z, the
    /// default, or standard), from the next `prepare` on.
    pub fn set_depth_convention(&mut self, convention: DepthConvention) {
        self.convention = convention;
    }

    /// Sets the time between frames (seconds) for the fade rates: a viewer's frame interval;
    /// `None` (the default) takes each frame's visibility at once, as stills should.
    pub fn set_interval(&mut self, seconds: Option<f64>) {
        self.interval = seconds;
    }

    /// Whether the last `prepare` left any flare to draw.
    pub fn is_empty(&self) -> bool {
        self.instance_count == 0
    }

    /// Encodes the occlusion pass: each source's visible share from the bound depth buffer,
    /// after the geometry that hides sources is drawn. Nothing without [`Self::bind_depth`].
    pub fn record_occlusion(&self, encoder: &mut wgpu::CommandEncoder) {
        let Some(bind_group) = &self.occlusion_bind_group else {
            return;
        };
        if self.source_count == 0 {
            return;
        }
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("firmament FlarePass occlusion"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.occlusion);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(self.source_count.div_ceil(64), 1, 1);
    }

    /// Draws the elements into a render pass the caller already began (additive; no depth).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        if self.instance_count == 0 {
            return;
        }
        pass.set_pipeline(&self.draw);
        pass.set_bind_group(0, &self.draw_bind_group, &[]);
        pass.set_vertex_buffer(0, self.instances.slice(..));
        pass.draw(0..4, 0..self.instance_count);
    }

    /// Encodes occlusion, then the elements added onto `color` (loaded, e.g. the HDR target).
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView) {
        if self.instance_count == 0 {
            return;
        }
        self.record_occlusion(encoder);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("firmament FlarePass elements"),
            color_attachments: &[Some(super::common::load_color_attachment(color))],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        self.draw(&mut pass);
    }

    /// The visibility buffer (one `f32` per prepared source, in the order they were kept), for
    /// tests and tools that copy it out; the rendering path never reads it back.
    pub fn visibility_buffer(&self) -> &wgpu::Buffer {
        &self.visibility
    }

    /// How many sources the last `prepare` kept.
    pub fn source_count(&self) -> u32 {
        self.source_count
    }
}

#[cfg(test)]
mod tests {
    use super::binding;

    #[test]
    fn the_binding_numbers_are_those_of_the_wgsl() {
        let mut rust: Vec<(String, u32)> = [
            ("frame", binding::FRAME),
            ("sources", binding::SOURCES),
            ("visibility", binding::VISIBILITY),
            ("depth_buffer", binding::DEPTH),
            ("element_visibility", binding::ELEMENT_VISIBILITY),
            ("images", binding::IMAGES),
            ("image_sampler", binding::IMAGE_SAMPLER),
        ]
        .map(|(name, number)| (name.to_owned(), number))
        .into();
        rust.sort();
        assert_eq!(crate::shaders::declared_bindings("flare/bindings"), rust);
    }
}
