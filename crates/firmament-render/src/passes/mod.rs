//! One module per pass. Each pass builds its pipeline in `new`, uploads per-frame data in
//! `prepare` and encodes commands in `record` (into its own render pass) or `draw` (into one the
//! caller already began).

pub mod sky_gradient;
pub mod tonemap;

pub use sky_gradient::GradientSkyPass;
pub use tonemap::TonemapPass;

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
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}
