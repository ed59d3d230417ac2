//! Meshes and textures on the GPU for the object pass.

use firmament_core::classic::mesh::Mesh;
use firmament_core::texture::TextureFilter;
use firmament_core::texture::TextureImage;
use wgpu::util::DeviceExt;

/// Bytes per vertex in both vertex buffers: three `f32` position, three normal, two texture
/// coordinates, one fog coordinate (the provoking-vertex buffer leaves the last three unused).
pub(crate) const VERTEX_STRIDE: u64 = 36;

/// Slot 0: position, normal, texture coordinate, fog coordinate (0 where the mesh has none).
pub(crate) const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 4] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 5 => Float32];
/// Slot 1: the position and normal lit for the vertex (itself, or its triangle's provoking vertex).
pub(crate) const SHADE_ATTRIBUTES: [wgpu::VertexAttribute; 2] =
    wgpu::vertex_attr_array![3 => Float32x3, 4 => Float32x3];

/// A triangle mesh on the GPU, ready for smooth or flat shading.
///
/// Smooth: the mesh's vertices and indices as they are; each vertex is lit for itself (slot 1 is
/// the same buffer as slot 0). Flat: every triangle `(a, b, c)` gets three vertices of its own,
/// all lit at `c` — GL's provoking vertex for `GL_TRIANGLES` is the *last* one — so the three
/// carry one colour whatever convention the backend's flat interpolation follows.
#[derive(Debug)]
pub struct GpuMesh {
    vertices: wgpu::Buffer,
    /// Flat shading's per-vertex provoking data; `None` for smooth meshes.
    shade: Option<wgpu::Buffer>,
    /// `None` for flat meshes, drawn unindexed.
    indices: Option<wgpu::Buffer>,
    count: u32,
}

fn vertex(mesh: &Mesh, i: usize) -> [f32; 9] {
    let (p, n, t) = (mesh.positions[i], mesh.normals[i], mesh.tex_coords[i]);
    let fog = mesh.fog_coords.get(i).copied().unwrap_or(0.0);
    [p[0], p[1], p[2], n[0], n[1], n[2], t[0], t[1], fog]
}

impl GpuMesh {
    /// Uploads `mesh` (which must pass [`Mesh::validate`]) for flat (`flat = true`) or smooth
    /// shading. `None` when it has no triangles or more indices than a draw call takes.
    pub fn new(device: &wgpu::Device, mesh: &Mesh, flat: bool) -> Option<Self> {
        let count = u32::try_from(mesh.indices.len()).ok().filter(|&n| n > 0)?;
        let buffer = |label: &str, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        if flat {
            let mut vertices = Vec::with_capacity(mesh.indices.len());
            let mut shade = Vec::with_capacity(mesh.indices.len());
            for t in mesh.indices.chunks_exact(3) {
                let provoking = vertex(mesh, t[2] as usize);
                for &i in t {
                    vertices.push(vertex(mesh, i as usize));
                    shade.push(provoking);
                }
            }
            Some(Self {
                vertices: buffer(
                    "firmament GpuMesh flat vertices",
                    bytemuck::cast_slice(&vertices),
                    wgpu::BufferUsages::VERTEX,
                ),
                shade: Some(buffer(
                    "firmament GpuMesh flat provoking vertices",
                    bytemuck::cast_slice(&shade),
                    wgpu::BufferUsages::VERTEX,
                )),
                indices: None,
                count,
            })
        } else {
            let vertices: Vec<[f32; 9]> = (0..mesh.positions.len()).map(|i| vertex(mesh, i)).collect();
            Some(Self {
                vertices: buffer(
                    "firmament GpuMesh vertices",
                    bytemuck::cast_slice(&vertices),
                    wgpu::BufferUsages::VERTEX,
                ),
                shade: None,
                indices: Some(buffer(
                    "firmament GpuMesh indices",
                    bytemuck::cast_slice(&mesh.indices),
                    wgpu::BufferUsages::INDEX,
                )),
                count,
            })
        }
    }

    /// Binds only the position buffer (slot 0) and draws: for depth-only passes.
    pub(crate) fn draw_positions(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        match &self.indices {
            Some(indices) => {
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..self.count, 0, 0..1);
            }
            None => pass.draw(0..self.count, 0..1),
        }
    }

    /// Binds the buffers and draws (the pipeline and bind group are set by the caller).
    pub(crate) fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_vertex_buffer(1, self.shade.as_ref().unwrap_or(&self.vertices).slice(..));
        match &self.indices {
            Some(indices) => {
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..self.count, 0, 0..1);
            }
            None => pass.draw(0..self.count, 0..1),
        }
    }
}

/// An RGBA8 texture (texels used as stored, `Rgba8Unorm`), bottom row first as in GL.
#[derive(Debug)]
pub(crate) struct GpuTexture {
    pub(crate) view: wgpu::TextureView,
}

impl GpuTexture {
    pub(crate) fn new(device: &wgpu::Device, queue: &wgpu::Queue, image: &TextureImage) -> Self {
        // GL's t = 0 and wgpu's v = 0 both sample row 0 of the data, and TextureImage stores
        // GL's row 0 (the bottom) first, so texture coordinates pass through unchanged.
        let texture = device.create_texture_with_data(
            queue,
            &wgpu::TextureDescriptor {
                label: Some("firmament ObjectPass texture"),
                size: wgpu::Extent3d {
                    width: image.width,
                    height: image.height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba8Unorm,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            bytemuck::cast_slice(&image.texels),
        );
        Self {
            view: texture.create_view(&wgpu::TextureViewDescriptor::default()),
        }
    }
}

/// A repeating sampler with `filter` for magnification and minification (no mipmaps).
pub(crate) fn sampler(device: &wgpu::Device, filter: TextureFilter) -> wgpu::Sampler {
    let mode = match filter {
        TextureFilter::Nearest => wgpu::FilterMode::Nearest,
        TextureFilter::Linear => wgpu::FilterMode::Linear,
    };
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some(&format!("firmament ObjectPass {filter:?} sampler")),
        address_mode_u: wgpu::AddressMode::Repeat,
        address_mode_v: wgpu::AddressMode::Repeat,
        mag_filter: mode,
        min_filter: mode,
        ..Default::default()
    })
}
