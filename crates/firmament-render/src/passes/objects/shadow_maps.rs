//! The object pass's sun shadows: one depth map per cascade of each casting sun (layers of one
//! `Depth32Float` array texture), drawn from the objects' meshes, and the bind group (the object
//! pass's group 1) through which lit fragments sample them.
//!
//! `prepare` fits the cascades (`firmament_core::classic::shadow::fit_cascades`) and uploads
//! one matrix per caster and cascade into a dynamic-offset uniform buffer; `record` draws every
//! cascade. The maps are remade only when their size or layer count changes.

use std::collections::HashMap;

use firmament_core::Camera;
use firmament_core::classic::scene::ObjectLayer;
use firmament_core::classic::shadow::fit_cascades;
use glam::DVec3;

use super::MeshKey;
use super::gpu_mesh::{GpuMesh, VERTEX_STRIDE};
use crate::gpu_types::shadow::CLOUD_ROWS;
use crate::gpu_types::{ShadowCasterUniform, ShadowFrameUniforms};
use crate::passes::common::uniform_buffer;
use crate::shaders;

/// The shadow maps' depth format (linear depth from an orthographic light: float keeps it).
const SHADOW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Bytes between caster matrices in the dynamic-offset buffer (WebGPU's minimum alignment).
const CASTER_STRIDE: u64 = 256;

/// The maps themselves, for one size and layer count.
#[derive(Debug)]
struct Maps {
    size: u32,
    layers: u32,
    /// One view per layer, to draw into.
    layer_views: Vec<wgpu::TextureView>,
    /// The whole array, to sample.
    array_view: wgpu::TextureView,
}

/// The casters of one cascade: (mesh, offset of its matrix).
type LayerDraws = Vec<(MeshKey, u32)>;

/// Shadow maps of a frame's casting suns, and how the object pass samples them.
#[derive(Debug)]
pub(crate) struct ShadowMaps {
    pipeline: wgpu::RenderPipeline,
    caster_layout: wgpu::BindGroupLayout,
    caster_buffer: wgpu::Buffer,
    caster_bind_group: wgpu::BindGroup,
    /// The object pass's group 1: frame uniforms, the map array with its comparison sampler, and
    /// the array again as floats.
    sample_layout: wgpu::BindGroupLayout,
    sample_bind_group: wgpu::BindGroup,
    frame_uniforms: wgpu::Buffer,
    compare: wgpu::Sampler,
    maps: Maps,
    /// The clouds' shadow map the lit objects read (a texel of nothing until one is bound).
    cloud_map: wgpu::TextureView,
    draws: Vec<LayerDraws>,
    /// Object-space bounding spheres of the meshes (centre, radius), by mesh.
    bounds: HashMap<MeshKey, (DVec3, f64)>,
}

fn make_maps(device: &wgpu::Device, size: u32, layers: u32) -> Maps {
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("firmament ObjectPass shadow maps"),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: SHADOW_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    let layer_views = (0..layers)
        .map(|layer| {
            texture.create_view(&wgpu::TextureViewDescriptor {
                label: Some("firmament ObjectPass shadow map layer"),
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_array_layer: layer,
                array_layer_count: Some(1),
                ..Default::default()
            })
        })
        .collect();
    let array_view = texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some("firmament ObjectPass shadow map array"),
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    });
    Maps {
        size,
        layers,
        layer_views,
        array_view,
    }
}

fn caster_buffer(device: &wgpu::Device, casters: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("firmament ObjectPass shadow casters"),
        size: casters.max(1) * CASTER_STRIDE,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn caster_bind_group(device: &wgpu::Device, layout: &wgpu::BindGroupLayout, buffer: &wgpu::Buffer) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("firmament ObjectPass shadow caster bind group"),
        layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: 0,
                size: wgpu::BufferSize::new(std::mem::size_of::<ShadowCasterUniform>() as u64),
            }),
        }],
    })
}

/// The layout of the bind group through which shaders sample the maps (`shadow/sampling.wgsl`,
/// group 1): the object pass's, and the light shafts' in the atmosphere pass. Built alike in both,
/// so one bind group serves both pipelines.
pub(crate) fn sampling_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let visible = wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE;
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("firmament shadow sampling layout"),
        entries: &[
            crate::passes::common::uniform_entry_in(0, visible),
            depth_array_entry(1, visible),
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: visible,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                count: None,
            },
            // Depth formats bind as unfilterable floats too (WebGPU's texture format
            // capabilities), which every backend can load from.
            wgpu::BindGroupLayoutEntry {
                binding: 3,
                visibility: visible,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2Array,
                    multisampled: false,
                },
                count: None,
            },
            // The clouds' shadow map (the atmosphere pass's), read with textureLoad.
            wgpu::BindGroupLayoutEntry {
                binding: 4,
                visibility: visible,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            },
        ],
    })
}

/// A layout entry for the map array, seen by `stages`.
fn depth_array_entry(binding: u32, stages: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: stages,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Depth,
            view_dimension: wgpu::TextureViewDimension::D2Array,
            multisampled: false,
        },
        count: None,
    }
}

/// The bounding sphere of a mesh's positions (centre of the box, farthest vertex), metres.
fn mesh_bounds(mesh: &firmament_core::classic::mesh::Mesh) -> (DVec3, f64) {
    let points = || mesh.positions.iter().map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into()));
    let (lo, hi) = points().fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| {
        (lo.min(p), hi.max(p))
    });
    let centre = (lo + hi) * 0.5;
    let radius = points().map(|p| p.distance(centre)).fold(0.0, f64::max);
    (centre, radius)
}

impl ShadowMaps {
    pub(crate) fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("firmament ObjectPass shadow map shader"),
            source: wgpu::ShaderSource::Wgsl((&*shaders::SHADOW_MAP).into()),
        });
        let caster_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("firmament ObjectPass shadow caster layout"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: true,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("firmament ObjectPass shadow map pipeline layout"),
            bind_group_layouts: &[Some(&caster_layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("firmament ObjectPass shadow map pipeline"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: VERTEX_STRIDE,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
                })],
            },
            // Both faces: meshes need not be closed, and the biases keep lit faces clean.
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: SHADOW_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            multisample: wgpu::MultisampleState::default(),
            fragment: None,
            multiview_mask: None,
            cache: None,
        });
        let sample_layout = sampling_layout(device);
        let compare = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("firmament ObjectPass shadow comparison sampler"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        let frame_uniforms = uniform_buffer::<ShadowFrameUniforms>(device, "firmament ObjectPass shadow uniforms");
        let maps = make_maps(device, 1, 1);
        // No clouds' shadow map until the renderer binds the atmosphere's (and none is read
        // while the frame's cloud rows are zero).
        let cloud_map = crate::targets::hdr_placeholder(device, "firmament ObjectPass no cloud shadow map");
        let sample_bind_group =
            Self::make_sample_bind_group(device, &sample_layout, &frame_uniforms, &maps, &compare, &cloud_map);
        let caster_buffer = caster_buffer(device, 1);
        let caster_bind_group = caster_bind_group(device, &caster_layout, &caster_buffer);
        Self {
            pipeline,
            caster_layout,
            caster_buffer,
            caster_bind_group,
            sample_layout,
            sample_bind_group,
            frame_uniforms,
            compare,
            maps,
            cloud_map,
            draws: Vec::new(),
            bounds: HashMap::new(),
        }
    }

    fn make_sample_bind_group(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        uniforms: &wgpu::Buffer,
        maps: &Maps,
        compare: &wgpu::Sampler,
        cloud_map: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament ObjectPass shadow sampling bind group"),
            layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniforms.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&maps.array_view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(compare),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&maps.array_view),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::TextureView(cloud_map),
                },

            ],
        })
    }

    fn rebuild_sample_bind_group(&mut self, device: &wgpu::Device) {
        self.sample_bind_group = Self::make_sample_bind_group(
            device,
            &self.sample_layout,
            &self.frame_uniforms,
            &self.maps,
            &self.compare,
            &self.cloud_map,
        );
    }

    /// Makes `view` (the atmosphere pass's, `shaders/clouds/shadow.wgsl`) the clouds' shadow map
    /// the lit objects read.
    pub(crate) fn bind_cloud_shadow_map(&mut self, device: &wgpu::Device, view: &wgpu::TextureView) {
        self.cloud_map = view.clone();
        self.rebuild_sample_bind_group(device);
    }

    /// The layout of the object pass's group 1.
    pub(crate) fn sample_layout(&self) -> &wgpu::BindGroupLayout {
        &self.sample_layout
    }

    /// The object pass's group 1 (and the light shafts').
    pub(crate) fn sample_bind_group(&self) -> &wgpu::BindGroup {
        &self.sample_bind_group
    }

    /// Fits the cascades of `layer`'s casting suns to `camera`'s view and uploads what the maps
    /// and the lit fragments need, with the clouds' shadow map's axes `clouds`
    /// ([`cloud_shadow_axes`](crate::gpu_types::shadow::cloud_shadow_axes)); `casters` are the
    /// objects' meshes (key and mesh, in the layer's order; the ground is not among them).
    /// Shadows off: only the "off" uniforms and the clouds'.
    pub(crate) fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layer: &ObjectLayer,
        camera: &Camera,
        casters: &[MeshKey],
        clouds: &[[f32; 4]; CLOUD_ROWS],
    ) {
        self.draws.clear();
        let (Some(mut settings), true) = (layer.shadows.settings, layer.shadows.any()) else {
            let uniforms = ShadowFrameUniforms {
                clouds: *clouds,
                ..ShadowFrameUniforms::off()
            };
            queue.write_buffer(&self.frame_uniforms, 0, bytemuck::bytes_of(&uniforms));
            return;
        };
        // A quality setting, not a promise: a device with smaller textures gets its largest.
        let largest = device.limits().max_texture_dimension_2d;
        if settings.map_size > largest {
            tracing::warn!(
                "shadows.map_size {} is more than this device's largest texture; using {largest}",
                settings.map_size
            );
            settings.map_size = largest;
        }
        let lights = &layer.shadows.lights[..layer.shadows.lights.len().min(settings.max_lights as usize)];
        let spheres: Vec<(DVec3, f64)> = layer
            .objects
            .iter()
            .zip(casters)
            .map(|(object, key)| {
                let (centre, radius) = *self.bounds.entry(*key).or_insert_with(|| mesh_bounds(&object.mesh));
                // The mesh's sphere, grown by the model's longest axis.
                let m = &object.model;
                let scale = [m.x_axis, m.y_axis, m.z_axis]
                    .map(|axis| axis.truncate().length())
                    .into_iter()
                    .fold(0.0, f64::max);
                (object.model.transform_point3(centre), radius * scale)
            })
            .collect();
        let cascades = fit_cascades(camera, &settings, lights, &spheres);
        let layers = lights.len() as u32 * settings.cascades;
        if self.maps.size != settings.map_size || self.maps.layers != layers {
            self.maps = make_maps(device, settings.map_size, layers);
            self.rebuild_sample_bind_group(device);
        }
        let mut uniforms = ShadowFrameUniforms::new(&settings, lights, &cascades);
        uniforms.clouds = *clouds;
        // Nothing shades the air above the highest caster (for a sun above the horizon): the
        // light shafts march no higher.
        let up = layer.ground.as_ref().map_or(DVec3::Z, |g| g.up);
        let top = spheres.iter().map(|&(c, r)| c.dot(up) + r).fold(f64::NEG_INFINITY, f64::max);
        uniforms.bias[2] = (top - camera.position.dot(up)) as f32;
        queue.write_buffer(&self.frame_uniforms, 0, bytemuck::bytes_of(&uniforms));

        // One matrix per caster and cascade, each at its own aligned offset.
        let mut matrices = Vec::new();
        for per_light in &cascades {
            for cascade in per_light {
                let mut draws = Vec::new();
                for (object, key) in layer.objects.iter().zip(casters) {
                    let offset = (matrices.len() as u64 * CASTER_STRIDE) as u32;
                    matrices.push(ShadowCasterUniform::new(&cascade.world_to_clip, &object.model));
                    draws.push((*key, offset));
                }
                self.draws.push(draws);
            }
        }
        let needed = matrices.len() as u64 * CASTER_STRIDE;
        if self.caster_buffer.size() < needed {
            self.caster_buffer = caster_buffer(device, matrices.len() as u64);
            self.caster_bind_group = caster_bind_group(device, &self.caster_layout, &self.caster_buffer);
        }
        let mut bytes = vec![0u8; needed as usize];
        for (i, m) in matrices.iter().enumerate() {
            let at = i * CASTER_STRIDE as usize;
            bytes[at..at + std::mem::size_of::<ShadowCasterUniform>()].copy_from_slice(bytemuck::bytes_of(m));
        }
        if !bytes.is_empty() {
            queue.write_buffer(&self.caster_buffer, 0, &bytes);
        }
    }

    /// Whether the last `prepare` left maps to draw.
    pub(crate) fn is_empty(&self) -> bool {
        self.draws.is_empty()
    }

    /// Draws every cascade's map from `meshes` (the object pass's uploaded meshes).
    pub(crate) fn record<'m>(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        meshes: impl Fn(&MeshKey) -> Option<&'m GpuMesh>,
    ) {
        for (layer, draws) in self.draws.iter().enumerate() {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("firmament ObjectPass shadow map"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.maps.layer_views[layer],
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            for (key, offset) in draws {
                if let Some(mesh) = meshes(key) {
                    pass.set_bind_group(0, &self.caster_bind_group, &[*offset]);
                    mesh.draw_positions(&mut pass);
                }
            }
        }
    }
}
