//! The two baselines every benchmark is measured against, on the same device in the same run: a
//! full-screen fragment pass that writes a constant into a target of the frame's size and HDR
//! format, and a compute pass that writes the same constant into the same texture.
//!
//! Data-centre GPUs (H100, H200) run fragment work on a few of their SMs and compute on all of
//! them, so a pass's time alone says little across devices; its ratio to each baseline says how
//! far it is from the cheapest work of its kind on that device (docs/PERFORMANCE.md).

use firmament_render::{GpuContext, HDR_FORMAT, wgpu};

use super::measure::median_ms;

/// The constant both baselines write.
const BASELINE_WGSL: &str = "
const VALUE: vec4<f32> = vec4<f32>(0.25, 0.5, 0.75, 1.0);

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_main() -> @location(0) vec4<f32> {
    return VALUE;
}

@group(0) @binding(0) var target_texture: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(target_texture);
    if id.x < size.x && id.y < size.y {
        textureStore(target_texture, vec2<i32>(id.xy), VALUE);
    }
}
";

/// Compute workgroup side, texels (`@workgroup_size(8, 8)` above).
const WORKGROUP_SIDE: u32 = 8;

/// Median milliseconds of each baseline at one image size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Baselines {
    /// The full-screen fragment pass writing a constant.
    pub(crate) fragment_ms: f64,
    /// The compute pass writing the same constant into the same texture.
    pub(crate) compute_ms: f64,
}

impl Baselines {
    /// Times both baselines at `width` × `height`, median of `frames`, as the benchmarks time
    /// their passes.
    pub(crate) fn measure(ctx: &GpuContext, width: u32, height: u32, frames: u32) -> Self {
        let device = &ctx.device;
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("firmament bench baseline target"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: HDR_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("firmament bench baseline shader"),
            source: wgpu::ShaderSource::Wgsl(BASELINE_WGSL.into()),
        });

        let fragment = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("firmament bench baseline fragment pipeline"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(HDR_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let draw = |encoder: &mut wgpu::CommandEncoder| {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("firmament bench baseline fragment pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        // Every pixel is written: nothing to load or clear.
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            pass.set_pipeline(&fragment);
            pass.draw(0..3, 0..1);
        };
        // One untimed run first: the first submission of a pipeline pays for its compilation
        // on some drivers (llvmpipe's GL).
        median_ms(ctx, 1, &texture, draw);
        let fragment_ms = median_ms(ctx, frames, &texture, draw);

        let compute = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("firmament bench baseline compute pipeline"),
            layout: None,
            module: &module,
            entry_point: Some("cs_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament bench baseline compute bind group"),
            layout: &compute.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&view),
            }],
        });
        let dispatch = |encoder: &mut wgpu::CommandEncoder| {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("firmament bench baseline compute pass"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&compute);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(width.div_ceil(WORKGROUP_SIDE), height.div_ceil(WORKGROUP_SIDE), 1);
        };
        median_ms(ctx, 1, &texture, dispatch);
        let compute_ms = median_ms(ctx, frames, &texture, dispatch);
        Self {
            fragment_ms,
            compute_ms,
        }
    }

    /// `ms` over each baseline: (to the fragment pass, to the compute pass).
    pub(crate) fn ratios(&self, ms: f64) -> (f64, f64) {
        (ms / self.fragment_ms, ms / self.compute_ms)
    }

    /// Prints the baselines, then each `(name, ms)` with its ratio to each.
    pub(crate) fn print_rows(&self, rows: &[(impl AsRef<str>, f64)]) {
        println!(
            "  {:<62} {:>10.3} ms",
            "baseline: full-screen fragment pass (a constant)", self.fragment_ms
        );
        println!(
            "  {:<62} {:>10.3} ms",
            "baseline: compute pass (the same texture)", self.compute_ms
        );
        println!("  {:<62} {:>13}  {:>10}  {:>10}", "", "", "/ fragment", "/ compute");
        for (name, ms) in rows {
            let (name, ms) = (name.as_ref(), *ms);
            let (fragment, compute) = self.ratios(ms);
            println!("  {name:<62} {ms:>10.3} ms  {fragment:>9.1}x  {compute:>9.1}x");
        }
    }

    /// The baselines' JSON fields, and `ratios`: for each `(name, ms)`, its ratio to each
    /// baseline (`{"name": {"fragment": …, "compute": …}}`).
    pub(crate) fn json_fields(&self, rows: &[(impl AsRef<str>, f64)]) -> [(&'static str, serde_json::Value); 3] {
        let ratios: serde_json::Map<String, serde_json::Value> = rows
            .iter()
            .map(|(name, ms)| {
                let (fragment, compute) = self.ratios(*ms);
                (
                    name.as_ref().to_owned(),
                    serde_json::json!({ "fragment": fragment, "compute": compute }),
                )
            })
            .collect();
        [
            ("baseline_fragment_ms", self.fragment_ms.into()),
            ("baseline_compute_ms", self.compute_ms.into()),
            ("ratios", ratios.into()),
        ]
    }
}
