//! The object pass: a frame's [`ObjectLayer`] — triangle meshes, optionally textured — lit by the
//! OpenGL fixed-function equations (or unlit) and fogged, into a colour target with reversed-Z
//! depth.
//!
//! Meshes and textures are uploaded once and kept while frames keep naming the same `Arc`s, so a
//! time-lapse or the viewer uploads only per-object uniforms each frame.
//!
//! Under a physical sky the layer may carry the ground near the camera (drawn after the objects,
//! shadowed, casting nothing) and sun shadows (`shadow_maps.rs`: maps drawn by
//! [`ObjectPass::record_shadows`] before the objects, sampled per fragment).

mod gpu_mesh;
mod shadow_maps;

pub(crate) use self::shadow_maps::sampling_layout as shadow_sampling_layout;

use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use firmament_core::Camera;
use firmament_core::classic::mesh::Mesh;
use firmament_core::classic::scene::{ObjectLayer, ObjectLighting, Shading};
use firmament_core::texture::TextureFilter;
use firmament_core::texture::TextureImage;

pub use self::gpu_mesh::GpuMesh;
use self::gpu_mesh::{GpuTexture, SHADE_ATTRIBUTES, VERTEX_ATTRIBUTES, VERTEX_STRIDE, sampler};
use self::shadow_maps::ShadowMaps;
use crate::gpu_types::shadow::CLOUD_ROWS;
use crate::gpu_types::{ClassicFrameUniforms, ClassicObjectUniforms};
use crate::passes::common::{PassPipeline, begin_load_pass, uniform_buffer, uniform_entry};
use crate::shaders;
use crate::targets::{DEPTH_FORMAT, HDR_FORMAT};

/// A mesh uploaded for one shading style, kept alive with the `Arc` it was made from.
#[derive(Debug)]
struct CachedMesh {
    _source: Arc<Mesh>,
    gpu: GpuMesh,
}

/// A texture kept alive with the `Arc` it was made from.
#[derive(Debug)]
struct CachedTexture {
    _source: Arc<TextureImage>,
    gpu: GpuTexture,
}

/// Identity of a cached mesh: the `Arc`'s address and whether it was expanded for flat shading.
type MeshKey = (usize, bool);
/// Identity of an object's texture binding: the `Arc`'s address (0 = none) and the filter.
type TextureKey = (usize, TextureFilter);

/// One object's draw: its uniforms, bind group and mesh.
#[derive(Debug)]
struct ObjectDraw {
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    texture: TextureKey,
    mesh: MeshKey,
}

/// Draws a frame's objects.
#[derive(Debug)]
pub struct ObjectPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    frame_uniforms: wgpu::Buffer,
    /// Bound where an object has no texture (the shader ignores it then).
    white: GpuTexture,
    nearest: wgpu::Sampler,
    linear: wgpu::Sampler,
    meshes: HashMap<MeshKey, CachedMesh>,
    textures: HashMap<usize, CachedTexture>,
    /// The layer's objects, then its ground (if any).
    draws: Vec<ObjectDraw>,
    shadows: ShadowMaps,
    /// The clouds' shadow map's axes for the next `prepare` (all zero: no cloud shadows).
    cloud_axes: [[f32; 4]; CLOUD_ROWS],
}

impl ObjectPass {
    /// Builds the pipeline for [`HDR_FORMAT`] colour and [`DEPTH_FORMAT`] depth.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        Self::with_formats(device, queue, HDR_FORMAT, DEPTH_FORMAT)
    }

    /// Builds the pipeline for other colour and depth formats.
    pub fn with_formats(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        color: wgpu::TextureFormat,
        depth: wgpu::TextureFormat,
    ) -> Self {
        let texture_entry = wgpu::BindGroupLayoutEntry {
            binding: 2,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        };
        let sampler_entry = wgpu::BindGroupLayoutEntry {
            binding: 3,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            count: None,
        };
        let shadows = ShadowMaps::new(device);
        let (pipeline, layout) = PassPipeline {
            owner: "ObjectPass",
            source: &shaders::CLASSIC_LIGHTING,
            entries: &[uniform_entry(0), uniform_entry(1), texture_entry, sampler_entry],
            color,
            depth_stencil: Some(wgpu::DepthStencilState {
                format: depth,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Greater),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            vertex_buffers: &[
                Some(wgpu::VertexBufferLayout {
                    array_stride: VERTEX_STRIDE,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &VERTEX_ATTRIBUTES,
                }),
                Some(wgpu::VertexBufferLayout {
                    array_stride: VERTEX_STRIDE,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &SHADE_ATTRIBUTES,
                }),
            ],
            // No culling: two-sided lighting needs the back faces; GL's default front face is CCW.
            primitive: wgpu::PrimitiveState {
                front_face: wgpu::FrontFace::Ccw,
                cull_mode: None,
                ..Default::default()
            },
            constants: &[],
        }
        .build_with_groups(device, None, &[shadows.sample_layout()]);
        let white = TextureImage {
            width: 1,
            height: 1,
            texels: vec![[255; 4]],
        };
        Self {
            pipeline,
            layout,
            frame_uniforms: uniform_buffer::<ClassicFrameUniforms>(device, "firmament ObjectPass frame uniforms"),
            white: GpuTexture::new(device, queue, &white),
            nearest: sampler(device, TextureFilter::Nearest),
            linear: sampler(device, TextureFilter::Linear),
            meshes: HashMap::new(),
            textures: HashMap::new(),
            draws: Vec::new(),
            shadows,
            cloud_axes: [[0.0; 4]; CLOUD_ROWS],
        }
    }

    /// Makes `view` the clouds' shadow map the objects' suns are dimmed by (the atmosphere pass's
    /// `shaders/clouds/shadow.wgsl`), read with the axes of the next
    /// [`set_cloud_shadow_axes`](Self::set_cloud_shadow_axes).
    pub(crate) fn bind_cloud_shadow_map(&mut self, device: &wgpu::Device, view: &wgpu::TextureView) {
        self.shadows.bind_cloud_shadow_map(device, view);
    }

    /// The clouds' shadow map's axes in the next prepared frame's eye space
    /// ([`cloud_shadow_axes`](crate::gpu_types::shadow::cloud_shadow_axes); all zero: no clouds).
    pub(crate) fn set_cloud_shadow_axes(&mut self, axes: [[f32; 4]; CLOUD_ROWS]) {
        self.cloud_axes = axes;
    }

    /// Uploads what `layer` needs to be seen by `camera` (whose aspect must be the target's):
    /// new meshes and textures once, lights and every object's uniforms each call. Meshes and
    /// textures no longer named are dropped.
    pub fn prepare(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, layer: &ObjectLayer, camera: &Camera) {
        let view = camera.view_matrix();
        let mut frame = ClassicFrameUniforms::new(
            &layer.lighting,
            &layer.fog,
            &view,
            &camera.projection_matrix(),
            camera.position.z,
        );
        let ground = match (&layer.lighting, &layer.ground) {
            (ObjectLighting::Sky(_), Some(ground)) => Some(ground),
            _ => None,
        };
        if let Some(ground) = ground {
            frame = frame.with_ground(ground, &view);
        }
        queue.write_buffer(&self.frame_uniforms, 0, bytemuck::bytes_of(&frame));
        let flat = layer.lighting.equations().is_some_and(|c| c.shading == Shading::Flat);

        let mut used_meshes = HashSet::new();
        let mut used_textures = HashSet::new();
        let drawn = layer.objects.iter().chain(ground.map(|g| &g.object));
        self.draws.truncate(layer.objects.len() + usize::from(ground.is_some()));
        for (i, object) in drawn.enumerate() {
            let mesh_key = (Arc::as_ptr(&object.mesh) as usize, flat);
            if !self.meshes.contains_key(&mesh_key)
                && let Some(gpu) = GpuMesh::new(device, &object.mesh, flat)
            {
                let cached = CachedMesh {
                    _source: Arc::clone(&object.mesh),
                    gpu,
                };
                self.meshes.insert(mesh_key, cached);
            }
            used_meshes.insert(mesh_key);
            let texture_key = match &object.texture {
                None => (0, TextureFilter::Nearest),
                Some(t) => {
                    let key = Arc::as_ptr(&t.image) as usize;
                    self.textures.entry(key).or_insert_with(|| CachedTexture {
                        _source: Arc::clone(&t.image),
                        gpu: GpuTexture::new(device, queue, &t.image),
                    });
                    used_textures.insert(key);
                    (key, t.filter)
                }
            };
            if self.draws.get(i).is_none_or(|d| d.texture != texture_key) {
                let uniforms = match self.draws.get(i) {
                    Some(d) => d.uniforms.clone(),
                    None => uniform_buffer::<ClassicObjectUniforms>(device, "firmament ObjectPass object uniforms"),
                };
                let draw = ObjectDraw {
                    bind_group: self.bind_group(device, &uniforms, texture_key),
                    uniforms,
                    texture: texture_key,
                    mesh: mesh_key,
                };
                if i < self.draws.len() {
                    self.draws[i] = draw;
                } else {
                    self.draws.push(draw);
                }
            }
            let draw = &mut self.draws[i];
            draw.mesh = mesh_key;
            let uniforms = ClassicObjectUniforms::new(object, &view);
            queue.write_buffer(&draw.uniforms, 0, bytemuck::bytes_of(&uniforms));
        }
        let casters: Vec<MeshKey> = self.draws.iter().take(layer.objects.len()).map(|d| d.mesh).collect();
        self.shadows.prepare(device, queue, layer, camera, &casters, &self.cloud_axes);
        self.meshes.retain(|key, _| used_meshes.contains(key));
        self.textures.retain(|key, _| used_textures.contains(key));
    }

    fn bind_group(&self, device: &wgpu::Device, uniforms: &wgpu::Buffer, texture: TextureKey) -> wgpu::BindGroup {
        let view = match self.textures.get(&texture.0) {
            Some(t) => &t.gpu.view,
            None => &self.white.view,
        };
        let sampler = match texture.1 {
            TextureFilter::Nearest => &self.nearest,
            TextureFilter::Linear => &self.linear,
        };
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament ObjectPass object bind group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.frame_uniforms.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: uniforms.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(view),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::Sampler(sampler),
                },
            ],
        })
    }

    /// Whether the last `prepare` left anything to draw.
    pub fn is_empty(&self) -> bool {
        self.draws.is_empty()
    }

    /// Draws the prepared objects into a render pass the caller already began (with a depth
    /// attachment).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(1, self.shadows.sample_bind_group(), &[]);
        for draw in &self.draws {
            // Absent only when the mesh could not be uploaded (no triangles).
            let Some(mesh) = self.meshes.get(&draw.mesh) else {
                continue;
            };
            pass.set_bind_group(0, &draw.bind_group, &[]);
            mesh.gpu.draw(pass);
        }
    }

    /// Whether the prepared frame has shadow maps to draw.
    pub fn has_shadows(&self) -> bool {
        !self.shadows.is_empty()
    }

    /// The bind group through which the light shafts sample the prepared frame's shadow maps
    /// (`shadow/sampling.wgsl`), when it has any.
    pub(crate) fn shadow_bind_group(&self) -> Option<&wgpu::BindGroup> {
        self.has_shadows().then(|| self.shadows.sample_bind_group())
    }

    /// Draws the sun shadow maps of the prepared frame (nothing when it has no shadows): before
    /// [`draw`](Self::draw) or [`record`](Self::record), in the same or an earlier encoder.
    pub fn record_shadows(&self, encoder: &mut wgpu::CommandEncoder) {
        if !self.shadows.is_empty() {
            self.shadows
                .record(encoder, |key| self.meshes.get(key).map(|m| &m.gpu));
        }
    }

    /// Draws the prepared objects into `color` and `depth`, both loaded (clear them first).
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView, depth: &wgpu::TextureView) {
        self.record_shadows(encoder);
        let mut pass = begin_load_pass(encoder, "firmament ObjectPass", color, depth);
        self.draw(&mut pass);
    }
}
