//! The classic lighting pass: triangle meshes lit by the OpenGL fixed-function equations.
//!
//! Groundwork for classic scenes (issue 5): the pass and its GPU-vs-core test exist; scene-file
//! objects, textures, fog and flat shading are still to come.

use glam::DVec3;
use wgpu::util::DeviceExt;

use crate::gpu_types::ClassicFrameUniforms;
use crate::passes::{PassPipeline, begin_load_pass, uniform_buffer, uniform_entry};
use crate::shaders;
use crate::targets::{DEPTH_FORMAT, HDR_FORMAT};

/// A triangle mesh on the GPU: interleaved `f32` positions and normals, `u32` indices.
#[derive(Debug)]
pub struct GpuMesh {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
}

/// Bytes per vertex: position and normal, three `f32` each.
const VERTEX_STRIDE: u64 = 24;

impl GpuMesh {
    /// Uploads a mesh (object space, metres; counter-clockwise front faces). `None` when the
    /// normals do not match the positions, an index is out of range, or the mesh is empty.
    pub fn new(device: &wgpu::Device, positions: &[DVec3], normals: &[DVec3], indices: &[u32]) -> Option<Self> {
        let in_range = indices.iter().all(|&i| (i as usize) < positions.len());
        if positions.len() != normals.len() || indices.is_empty() || !indices.len().is_multiple_of(3) || !in_range {
            return None;
        }
        let data: Vec<f32> = positions
            .iter()
            .zip(normals)
            .flat_map(|(p, n)| {
                let (p, n) = (p.as_vec3(), n.as_vec3());
                [p.x, p.y, p.z, n.x, n.y, n.z]
            })
            .collect();
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("firmament GpuMesh vertices"),
            contents: bytemuck::cast_slice(&data),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let indices_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("firmament GpuMesh indices"),
            contents: bytemuck::cast_slice(indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        Some(Self {
            vertices,
            indices: indices_buffer,
            index_count: u32::try_from(indices.len()).ok()?,
        })
    }
}

/// Draws [`GpuMesh`]es with classic lighting into a colour target with reversed-Z depth.
#[derive(Debug)]
pub struct ClassicMeshPass {
    pipeline: wgpu::RenderPipeline,
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

impl ClassicMeshPass {
    /// Builds the pipeline for [`HDR_FORMAT`] colour and [`DEPTH_FORMAT`] depth.
    pub fn new(device: &wgpu::Device) -> Self {
        Self::with_formats(device, HDR_FORMAT, DEPTH_FORMAT)
    }

    /// Builds the pipeline for other colour and depth formats.
    pub fn with_formats(device: &wgpu::Device, color: wgpu::TextureFormat, depth: wgpu::TextureFormat) -> Self {
        let (pipeline, layout) = PassPipeline {
            owner: "ClassicMeshPass",
            source: shaders::CLASSIC_LIGHTING,
            entries: &[uniform_entry(0)],
            color,
            depth_stencil: Some(wgpu::DepthStencilState {
                format: depth,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Greater),
                stencil: wgpu::StencilState::default(),
                bias: wgpu::DepthBiasState::default(),
            }),
            vertex_buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: VERTEX_STRIDE,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
            })],
            // No culling: two-sided lighting needs the back faces; GL's default front face is CCW.
            primitive: wgpu::PrimitiveState {
                front_face: wgpu::FrontFace::Ccw,
                cull_mode: None,
                ..Default::default()
            },
            constants: &[],
        }
        .build(device);
        let uniforms = uniform_buffer::<ClassicFrameUniforms>(device, "firmament ClassicMeshPass uniforms");
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament ClassicMeshPass bind group"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniforms.as_entire_binding(),
            }],
        });
        Self {
            pipeline,
            uniforms,
            bind_group,
        }
    }

    /// Uploads the matrices, lights and materials for the next draw.
    pub fn prepare(&self, queue: &wgpu::Queue, frame: &ClassicFrameUniforms) {
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(frame));
    }

    /// Draws `mesh` into a render pass the caller already began (with a depth attachment).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, mesh: &GpuMesh) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.set_vertex_buffer(0, mesh.vertices.slice(..));
        pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..mesh.index_count, 0, 0..1);
    }

    /// Draws `mesh` into `color` and `depth`, both loaded (clear them first).
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        mesh: &GpuMesh,
    ) {
        let mut pass = begin_load_pass(encoder, "firmament ClassicMeshPass", color, depth);
        self.draw(&mut pass, mesh);
    }
}
