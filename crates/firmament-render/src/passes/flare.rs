//! The lens-flare passes: an occlusion compute pass that samples the depth buffer (and the
//! planet) over every source's disc and writes its visible share to a GPU buffer, with the
//! indirect arguments of the element and composite passes; a binning pass that marks which
//! elements of the seen sources may light each bin of pixels; an element compute pass that sums
//! each pixel's elements — glows, streaks, halos, ghosts along the axis through the screen centre
//! — scaled by their source's share into the pass's own target; and a composite quad that adds
//! that target to the HDR target. Nothing is read back to the CPU: a hidden source costs its
//! occlusion samples and no more.
//!
//! Placement is the core's ([`firmament_core::flare`]): sources are projected and elements laid
//! out, and clipped to where their light is above
//! [`FLARE_NEGLIGIBLE`](crate::gpu_types::flare::FLARE_NEGLIGIBLE), in `f64` in `prepare`; the
//! GPU only decides how much of each source is hidden. Why compute: docs/PERFORMANCE.md, "Lens
//! flares".

use firmament_core::atmosphere::Planet;
use firmament_core::flare::{FlareLayer, MAX_FLARE_ELEMENTS, MAX_FLARE_SOURCES, element_centers, on_screen};
use firmament_core::{Camera, DepthConvention};

use super::flare_images::FlareImageArray;
use crate::gpu_types::codes;
use crate::gpu_types::flare::PixelRect;
use crate::gpu_types::{FlareFrameUniforms, FlareInstance, FlareSourceGpu};
use crate::passes::common::{uniform_buffer, uniform_entry_in};
use crate::shaders;
use crate::targets::HDR_FORMAT;

/// Most element records in a frame (`MAX_INSTANCES` of `shaders/flare/bindings.wgsl`).
const MAX_INSTANCES: usize = MAX_FLARE_SOURCES * MAX_FLARE_ELEMENTS;

/// The pass's own target: each pixel's summed element light.
const ACCUMULATION_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The element pass's tile side, pixels (`FLARE_TILE` of `shaders/flare/bindings.wgsl`).
const TILE: u32 = 16;

/// Most bins: the bins' side grows (in powers of two) with the target to keep within this, so
/// the state buffer has one size (4 MiB of bins).
const MAX_BINS: u32 = 8192;

/// Byte offsets in the records buffer of `FlareRecords`' members (`shaders/flare/bindings.wgsl`;
/// a test compares them).
mod records {
    /// [`FlareSourceGpu`](crate::gpu_types::FlareSourceGpu) × `MAX_FLARE_SOURCES`.
    pub(super) const SOURCES: u64 = 0;
    /// [`FlareInstance`](crate::gpu_types::FlareInstance)s.
    pub(super) const ELEMENTS: u64 = 2048;
}

/// Byte offsets in the state buffer of `FlareState`'s members (`shaders/flare/bindings.wgsl`; a
/// test compares them).
mod state {
    /// One `f32` per source.
    #[cfg(test)]
    pub(super) const VISIBILITY: u64 = 0;
    /// The element pass's `DispatchIndirectArgs`.
    pub(super) const DISPATCH: u64 = 256;
    /// The composite pass's `DrawIndirectArgs`.
    pub(super) const DRAW: u64 = 272;
    /// The lit rectangle (four `u32`), the composite quad's instance attribute.
    pub(super) const RECT: u64 = 288;
    /// The bin grid (four `u32`), written by `prepare`.
    pub(super) const GRID: u64 = 304;
    /// Which elements are images (a bin's bit set), written by `prepare`.
    pub(super) const IMAGES: u64 = 320;
    /// The bins' bit sets.
    pub(super) const BINS: u64 = 832;
}

// One occlusion workgroup holds every source (it unions their rectangles); the WGSL structs
// hold 64 sources and 4096 elements.
const _: () = assert!(MAX_FLARE_SOURCES == 64 && MAX_INSTANCES == 4096);

/// The bins of a `width` × `height` target for `elements` elements: side (pixels, a power of
/// two from [`TILE`] up), bins across, bins down, words per bin (one bit per element).
fn bin_grid((width, height): (u32, u32), elements: u32) -> [u32; 4] {
    let mut side = TILE;
    while width.div_ceil(side) * height.div_ceil(side) > MAX_BINS {
        side *= 2;
    }
    [side, width.div_ceil(side), height.div_ceil(side), elements.div_ceil(32)]
}

/// Binding numbers of the four pipelines: those `shaders/flare/bindings.wgsl` declares (a test
/// compares the two).
mod binding {
    /// The frame uniforms (all).
    pub(super) const FRAME: u32 = 0;
    /// The sources and elements (the compute passes).
    pub(super) const RECORDS: u32 = 1;
    /// The state buffer, written (occlusion, binning).
    pub(super) const STATE: u32 = 2;
    /// The depth buffer (occlusion).
    pub(super) const DEPTH: u32 = 3;
    /// The state buffer, read (elements).
    pub(super) const ELEMENT_STATE: u32 = 4;
    /// The element images (elements).
    pub(super) const IMAGES: u32 = 5;
    /// Their sampler (elements).
    pub(super) const IMAGE_SAMPLER: u32 = 6;
    /// The pass's own target, written (elements).
    pub(super) const ACCUMULATED_OUT: u32 = 7;
    /// The pass's own target, read (composite).
    pub(super) const ACCUMULATED: u32 = 8;
}

/// Lens flares of a frame's suns and lights.
#[derive(Debug)]
pub struct FlarePass {
    occlusion: wgpu::ComputePipeline,
    occlusion_layout: wgpu::BindGroupLayout,
    /// Rebuilt by [`Self::bind_depth`].
    occlusion_bind_group: Option<wgpu::BindGroup>,
    /// Uses the occlusion pipeline's layout and bind group.
    binning: wgpu::ComputePipeline,
    elements: wgpu::ComputePipeline,
    elements_layout: wgpu::BindGroupLayout,
    /// Rebuilt by [`Self::bind_depth`] and when the flare's images change.
    elements_bind_group: Option<wgpu::BindGroup>,
    composite: wgpu::RenderPipeline,
    composite_layout: wgpu::BindGroupLayout,
    /// Rebuilt by [`Self::bind_depth`].
    composite_bind_group: Option<wgpu::BindGroup>,
    /// The pass's own target, the depth buffer's size: the elements' light summed per pixel.
    accumulation: Option<wgpu::TextureView>,
    images: FlareImageArray,
    image_sampler: wgpu::Sampler,
    frame_uniforms: wgpu::Buffer,
    /// `FlareRecords`: the kept sources, then their elements.
    records: wgpu::Buffer,
    /// `FlareState`: each source's visible share (kept between frames for smoothing), the
    /// indirect arguments and lit rectangle the occlusion pass writes, the bins.
    state: wgpu::Buffer,
    source_count: u32,
    instance_count: u32,
    /// [`bin_grid`] of the last `prepare`.
    grid: [u32; 4],
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

/// The element pass's bind group: frame uniforms, records, state, images and their sampler and
/// the pass's own target.
fn elements_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    pass: &FlarePass,
    accumulation: &wgpu::TextureView,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("firmament FlarePass element bind group"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: binding::FRAME,
                resource: pass.frame_uniforms.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: binding::ELEMENT_STATE,
                resource: pass.state.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: binding::IMAGES,
                resource: wgpu::BindingResource::TextureView(&pass.images.view),
            },
            wgpu::BindGroupEntry {
                binding: binding::IMAGE_SAMPLER,
                resource: wgpu::BindingResource::Sampler(&pass.image_sampler),
            },
            wgpu::BindGroupEntry {
                binding: binding::RECORDS,
                resource: pass.records.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: binding::ACCUMULATED_OUT,
                resource: wgpu::BindingResource::TextureView(accumulation),
            },
        ],
    })
}

impl FlarePass {
    /// Builds the four pipelines for [`HDR_FORMAT`] targets.
    pub fn new(device: &wgpu::Device) -> Self {
        Self::with_format(device, HDR_FORMAT)
    }

    /// Builds the four pipelines, the composite's for colour targets of `format`.
    pub fn with_format(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        use wgpu::ShaderStages as S;
        let frame_uniforms = uniform_buffer::<FlareFrameUniforms>(device, "firmament FlarePass frame uniforms");
        let records = buffer(
            device,
            "firmament FlarePass records",
            records::ELEMENTS as usize + MAX_INSTANCES * std::mem::size_of::<FlareInstance>(),
            wgpu::BufferUsages::STORAGE,
        );
        let state = buffer(
            device,
            "firmament FlarePass state",
            (state::BINS + u64::from(MAX_BINS) * MAX_INSTANCES as u64 / 8) as usize,
            wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::INDIRECT
                | wgpu::BufferUsages::VERTEX
                | wgpu::BufferUsages::COPY_SRC,
        );
        let pipeline_layout = |name: &str, layout: &wgpu::BindGroupLayout| {
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(&format!("firmament FlarePass {name} pipeline layout")),
                bind_group_layouts: &[Some(layout)],
                immediate_size: 0,
            })
        };
        let compute_pipeline =
            |name: &str, layout: &wgpu::PipelineLayout, module: &wgpu::ShaderModule, entry_point: &str| {
                device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(&format!("firmament FlarePass {name} pipeline")),
                    layout: Some(layout),
                    module,
                    entry_point: Some(entry_point),
                    compilation_options: Default::default(),
                    cache: None,
                })
            };

        let occlusion_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("firmament FlarePass occlusion bind group layout"),
            entries: &[
                uniform_entry_in(binding::FRAME, S::COMPUTE),
                storage_entry(binding::RECORDS, S::COMPUTE, true),
                storage_entry(binding::STATE, S::COMPUTE, false),
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
        let occlusion_pipeline_layout = pipeline_layout("occlusion", &occlusion_layout);
        let occlusion = compute_pipeline("occlusion", &occlusion_pipeline_layout, &module, "cs_main");
        let binning = compute_pipeline("binning", &occlusion_pipeline_layout, &module, "cs_bin");

        let elements_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("firmament FlarePass element bind group layout"),
            entries: &[
                uniform_entry_in(binding::FRAME, S::COMPUTE),
                storage_entry(binding::RECORDS, S::COMPUTE, true),
                storage_entry(binding::ELEMENT_STATE, S::COMPUTE, true),
                wgpu::BindGroupLayoutEntry {
                    binding: binding::IMAGES,
                    visibility: S::COMPUTE,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2Array,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: binding::IMAGE_SAMPLER,
                    visibility: S::COMPUTE,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: binding::ACCUMULATED_OUT,
                    visibility: S::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: ACCUMULATION_FORMAT,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("firmament FlarePass element shader"),
            source: wgpu::ShaderSource::Wgsl(shaders::FLARE.source().into()),
        });
        let elements = compute_pipeline(
            "element",
            &pipeline_layout("element", &elements_layout),
            &module,
            "cs_elements",
        );

        let composite_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("firmament FlarePass composite bind group layout"),
            entries: &[
                uniform_entry_in(binding::FRAME, S::VERTEX),
                wgpu::BindGroupLayoutEntry {
                    binding: binding::ACCUMULATED,
                    visibility: S::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
        });
        let composite = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("firmament FlarePass composite pipeline"),
            layout: Some(&pipeline_layout("composite", &composite_layout)),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_composite"),
                compilation_options: Default::default(),
                // The lit rectangle, read from the state buffer.
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: 16,
                    step_mode: wgpu::VertexStepMode::Instance,
                    attributes: &wgpu::vertex_attr_array![0 => Uint32x4],
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
                entry_point: Some("fs_composite"),
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
        Self {
            occlusion,
            occlusion_layout,
            occlusion_bind_group: None,
            binning,
            elements,
            elements_layout,
            elements_bind_group: None,
            composite,
            composite_layout,
            composite_bind_group: None,
            accumulation: None,
            images,
            image_sampler,
            frame_uniforms,
            records,
            state,
            source_count: 0,
            instance_count: 0,
            grid: [0; 4],
            depth_size: (0, 0),
            interval: None,
            convention: DepthConvention::Reversed,
        }
    }

    /// Binds the depth buffer (`width` × `height`, in the convention of
    /// [`Self::set_depth_convention`]; reversed-Z by default) whose geometry hides sources, and
    /// sizes the pass's own target to it: the colour targets of [`Self::record`] and
    /// [`Self::draw`] must be that size. Call again when the depth texture changes, before
    /// [`Self::prepare`].
    pub fn bind_depth(&mut self, device: &wgpu::Device, depth: &wgpu::TextureView, width: u32, height: u32) {
        self.occlusion_bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament FlarePass occlusion bind group"),
            layout: &self.occlusion_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: binding::FRAME,
                    resource: self.frame_uniforms.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: binding::RECORDS,
                    resource: self.records.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: binding::STATE,
                    resource: self.state.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: binding::DEPTH,
                    resource: wgpu::BindingResource::TextureView(depth),
                },
            ],
        }));
        if self.accumulation.is_some() && self.depth_size == (width, height) {
            return;
        }
        self.depth_size = (width, height);
        let accumulation = device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some("firmament FlarePass accumulation"),
                size: wgpu::Extent3d {
                    width: width.max(1),
                    height: height.max(1),
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: ACCUMULATION_FORMAT,
                usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
            .create_view(&wgpu::TextureViewDescriptor {
                label: Some("firmament FlarePass accumulation view"),
                ..Default::default()
            });
        self.composite_bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament FlarePass composite bind group"),
            layout: &self.composite_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: binding::FRAME,
                    resource: self.frame_uniforms.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: binding::ACCUMULATED,
                    resource: wgpu::BindingResource::TextureView(&accumulation),
                },
            ],
        }));
        self.elements_bind_group = Some(elements_bind_group(device, &self.elements_layout, self, &accumulation));
        self.accumulation = Some(accumulation);
    }

    /// Lays out `layer`'s flares for `camera` (whose aspect must be the target's): which sources
    /// can flare (in front, within the margin), where each element goes, its colour over the
    /// display's `exposure` multiplier (so 1 is white on screen), and the pixels of the bound
    /// depth buffer's size it can light ([`FlareInstance::clipped`]; elements too faint to
    /// matter are dropped). `planet`, when the sky has one, hides sources behind it. Visibility
    /// fades at the flare's rates over the interval of [`Self::set_interval`]. Sources and
    /// elements past the limits are dropped (scenes validate the counts).
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
            if let Some(accumulation) = &self.accumulation {
                self.elements_bind_group = Some(elements_bind_group(device, &self.elements_layout, self, accumulation));
            }
        }
        let lens_elements = flare.lens_elements();
        let positions: Vec<f64> = lens_elements.iter().map(|e| e.position).collect();
        let scale = flare.intensity / if exposure > 0.0 { exposure } else { 1.0 };
        let mut sources = Vec::new();
        let mut instances = Vec::new();
        for source in layer.sources.iter().take(MAX_FLARE_SOURCES) {
            let Some(at) = on_screen(camera, source, flare.margin) else {
                continue;
            };
            let index = sources.len() as u32;
            let centers = element_centers(camera, source, &positions);
            let mut lit = PixelRect::default();
            for (element, center) in lens_elements.iter().take(MAX_FLARE_ELEMENTS).zip(centers) {
                let Some(center) = center else {
                    continue;
                };
                let color = element.color * source.color * element.intensity * scale;
                let instance = FlareInstance::new(element, center, color, at.edge_fade, index);
                if let Some((instance, rect)) = instance.clipped(self.depth_size) {
                    instances.push(instance);
                    lit = lit.union(rect);
                }
            }
            sources.push(FlareSourceGpu::in_convention(camera, source, &at, self.convention).with_rect(lit));
        }
        let uniforms = FlareFrameUniforms::new(
            camera,
            planet,
            flare,
            sources.len() as u32,
            self.depth_size,
            self.interval,
        )
        .for_depth_convention(self.convention)
        .with_elements(instances.len() as u32);
        queue.write_buffer(&self.frame_uniforms, 0, bytemuck::bytes_of(&uniforms));
        if !sources.is_empty() {
            queue.write_buffer(&self.records, records::SOURCES, bytemuck::cast_slice(&sources));
        }
        if !instances.is_empty() {
            queue.write_buffer(&self.records, records::ELEMENTS, bytemuck::cast_slice(&instances));
        }
        self.grid = bin_grid(self.depth_size, instances.len() as u32);
        let mut images = [0u32; MAX_INSTANCES / 32];
        for (k, instance) in instances.iter().enumerate() {
            if instance.shape[0] == codes::FLARE_IMAGE as f32 {
                images[k / 32] |= 1 << (k % 32);
            }
        }
        queue.write_buffer(&self.state, state::GRID, bytemuck::cast_slice(&self.grid));
        queue.write_buffer(&self.state, state::IMAGES, bytemuck::cast_slice(&images));
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

    /// Whether the last `prepare` left no element that could light the target.
    pub fn is_empty(&self) -> bool {
        self.instance_count == 0
    }

    /// Encodes the occlusion pass: each source's visible share from the bound depth buffer,
    /// after the geometry that hides sources is drawn, and the element and composite passes'
    /// indirect arguments. Nothing without [`Self::bind_depth`].
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
        // One workgroup of MAX_FLARE_SOURCES invocations.
        pass.dispatch_workgroups(1, 1, 1);
    }

    /// Encodes the binning and element passes, after [`Self::record_occlusion`]: the seen
    /// sources' elements summed into the pass's own target over the rectangle they light (no
    /// element work when none is seen).
    pub fn record_elements(&self, encoder: &mut wgpu::CommandEncoder) {
        let (Some(occlusion), Some(elements)) = (&self.occlusion_bind_group, &self.elements_bind_group) else {
            return;
        };
        if self.instance_count == 0 {
            return;
        }
        let [_, across, down, words] = self.grid;
        let bins = u64::from(across * down * words) * 4;
        encoder.clear_buffer(&self.state, state::BINS, Some(bins));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("firmament FlarePass elements"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.binning);
        pass.set_bind_group(0, occlusion, &[]);
        pass.dispatch_workgroups(self.instance_count.div_ceil(64), 1, 1);
        pass.set_pipeline(&self.elements);
        pass.set_bind_group(0, elements, &[]);
        pass.dispatch_workgroups_indirect(&self.state, state::DISPATCH);
    }

    /// Adds the elements' light to a render pass the caller already began on a target of the
    /// bound depth buffer's size (additive; no depth), after [`Self::record_occlusion`] and
    /// [`Self::record_elements`]: one quad over the lit rectangle, none when no source is seen.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        let Some(bind_group) = &self.composite_bind_group else {
            return;
        };
        if self.instance_count == 0 {
            return;
        }
        pass.set_pipeline(&self.composite);
        pass.set_bind_group(0, bind_group, &[]);
        pass.set_vertex_buffer(0, self.state.slice(state::RECT..state::RECT + 16));
        pass.draw_indirect(&self.state, state::DRAW);
    }

    /// Encodes occlusion and the elements, then adds them onto `color` (loaded, e.g. the HDR
    /// target, the bound depth buffer's size).
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView) {
        if self.instance_count == 0 {
            return;
        }
        self.record_occlusion(encoder);
        self.record_elements(encoder);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("firmament FlarePass composite"),
            color_attachments: &[Some(super::common::load_color_attachment(color))],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        self.draw(&mut pass);
    }

    /// The buffer whose first bytes are the visibilities (one `f32` per prepared source, in the
    /// order they were kept), for tests and tools that copy them out; the rendering path never
    /// reads it back.
    pub fn visibility_buffer(&self) -> &wgpu::Buffer {
        &self.state
    }

    /// How many sources the last `prepare` kept.
    pub fn source_count(&self) -> u32 {
        self.source_count
    }
}

#[cfg(test)]
mod tests {
    use super::{MAX_BINS, TILE, bin_grid, binding, records, state};

    #[test]
    fn the_binding_numbers_are_those_of_the_wgsl() {
        let mut rust: Vec<(String, u32)> = [
            ("frame", binding::FRAME),
            ("records", binding::RECORDS),
            ("state", binding::STATE),
            ("depth_buffer", binding::DEPTH),
            ("element_state", binding::ELEMENT_STATE),
            ("images", binding::IMAGES),
            ("image_sampler", binding::IMAGE_SAMPLER),
            ("accumulated_out", binding::ACCUMULATED_OUT),
            ("accumulated", binding::ACCUMULATED),
        ]
        .map(|(name, number)| (name.to_owned(), number))
        .into();
        rust.sort();
        assert_eq!(crate::shaders::declared_bindings("flare/bindings"), rust);
    }

    /// `name`'s members and their byte offsets in `module`.
    fn members(module: &naga::Module, name: &str) -> Vec<(String, u64)> {
        let (_, ty) = module
            .types
            .iter()
            .find(|(_, ty)| ty.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("{name}"));
        let naga::TypeInner::Struct { members, .. } = &ty.inner else {
            panic!("{name} is a struct");
        };
        members
            .iter()
            .map(|m| (m.name.clone().unwrap_or_default(), u64::from(m.offset)))
            .collect()
    }

    /// The literal value of the constant `name` in `module`.
    fn constant(module: &naga::Module, name: &str) -> naga::Literal {
        let (_, c) = module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("{name}"));
        match module.global_expressions[c.init] {
            naga::Expression::Literal(literal) => literal,
            ref other => panic!("{name} = {other:?}"),
        }
    }

    #[test]
    fn the_offsets_and_constants_are_those_of_the_wgsl() {
        let parse = |shader: &crate::shaders::Shader| {
            naga::front::wgsl::parse_str(shader.source()).unwrap_or_else(|e| panic!("{e}"))
        };
        let occlusion = parse(&crate::shaders::FLARE_OCCLUSION);
        let flare = parse(&crate::shaders::FLARE);
        let named = |list: &[(&str, u64)]| -> Vec<(String, u64)> {
            list.iter().map(|&(n, o)| (n.to_owned(), o)).collect()
        };
        let state = named(&[
            ("visibility", state::VISIBILITY),
            ("dispatch", state::DISPATCH),
            ("draw", state::DRAW),
            ("rect", state::RECT),
            ("grid", state::GRID),
            ("images", state::IMAGES),
            ("bins", state::BINS),
        ]);
        assert_eq!(members(&occlusion, "FlareState"), state);
        assert_eq!(members(&flare, "FlareStateView"), state);
        let records = named(&[("sources", records::SOURCES), ("elements", records::ELEMENTS)]);
        assert_eq!(members(&occlusion, "FlareRecords"), records);
        assert_eq!(constant(&flare, "FLARE_TILE"), naga::Literal::U32(TILE));
        assert_eq!(constant(&flare, "MAX_INSTANCES"), naga::Literal::U32(4096));
        // `1.0 / 8192.0` folds to a literal.
        let naga::Literal::F32(negligible) = constant(&occlusion, "NEGLIGIBLE") else {
            panic!("NEGLIGIBLE is an f32");
        };
        assert_eq!(f64::from(negligible), crate::gpu_types::flare::FLARE_NEGLIGIBLE);
    }

    #[test]
    fn bins_grow_with_the_target_to_stay_within_their_buffer() {
        assert_eq!(bin_grid((1280, 720), 1024), [16, 80, 45, 32]);
        assert_eq!(bin_grid((1920, 1080), 4096), [16, 120, 68, 128]);
        assert_eq!(bin_grid((3840, 2160), 1), [32, 120, 68, 1]);
        for size in [(1, 1), (1536, 1536), (16384, 16384), (65535, 3)] {
            let [side, across, down, _] = bin_grid(size, 16);
            assert!(side.is_power_of_two() && side >= TILE, "{size:?}");
            assert!(across * down <= MAX_BINS, "{size:?}");
            assert!(across * side >= size.0 && down * side >= size.1, "{size:?}");
        }
    }
}
