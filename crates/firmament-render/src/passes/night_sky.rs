//! The night-sky pass: the stars (an instanced Gaussian footprint each) and the Moon (a disc
//! shaded per pixel with the Lommel–Seeliger law) added to the HDR target over the sky, where
//! nothing nearer was drawn. See `shaders/night_sky.wgsl` for the footprint and the disc's
//! geometry, and [`firmament_core::sky::night`] for the units.
//!
//! Depth: both are drawn at the far plane (reversed-Z depth 0) with the sky passes' depth state,
//! `GreaterEqual` and no writes (`far_plane_depth_state`): against a depth buffer
//! cleared to 0 that passes exactly where the depth is still 0, i.e. nothing was drawn. An
//! `Equal` test would say the same, but `GreaterEqual` is what the sky passes already rely on,
//! on every backend including GL/llvmpipe, and it does not hinge on an exact float comparison.
//! Blending is additive, so the daylight sky swamps the stars by itself.

use firmament_core::Camera;
use firmament_core::sky::night::NightLayer;

use crate::gpu_types::{MoonDraw, NightSkyUniforms, StarInstance};
use crate::passes::common::SkyTarget;
use crate::passes::common::{begin_load_pass, far_depth_constant, far_plane_depth_state, uniform_buffer, uniform_entry};
use crate::shaders;

/// Stars the instance buffer holds at first (it grows when a layer has more): the naked-eye
/// catalogue's 8867 fit.
const INITIAL_STAR_CAPACITY: usize = 9216;

/// Draws a frame's [`NightLayer`]: stars and the Moon.
#[derive(Debug)]
pub struct NightSkyPass {
    star_pipeline: wgpu::RenderPipeline,
    moon_pipeline: wgpu::RenderPipeline,
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    instances: wgpu::Buffer,
    /// Stars the instance buffer can hold.
    capacity: usize,
    /// The layer's stars uploaded by the last `prepare`.
    star_count: u32,
    /// Instances to draw: the stars, and the Moon when it is drawn as a star.
    instance_count: u32,
    moon_draw: MoonDraw,
}

fn instance_buffer(device: &wgpu::Device, stars: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("firmament NightSkyPass star instances"),
        size: (stars * std::mem::size_of::<StarInstance>()) as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

impl NightSkyPass {
    /// Builds the star and Moon pipelines for an HDR target of [`HDR_FORMAT`](crate::HDR_FORMAT) and depth of
    /// [`DEPTH_FORMAT`](crate::DEPTH_FORMAT).
    pub fn new(device: &wgpu::Device) -> Self {
        Self::for_target(device, SkyTarget::OWN)
    }

    /// Builds the pipelines for `target`'s colour and depth formats and depth convention (drawn at
    /// its far plane, tested against it).
    pub fn for_target(device: &wgpu::Device, target: SkyTarget) -> Self {
        let SkyTarget {
            color,
            depth,
            convention,
        } = target;
        let constants = [far_depth_constant(convention)];
        let options = || wgpu::PipelineCompilationOptions {
            constants: &constants,
            ..Default::default()
        };
        let uniforms = uniform_buffer::<NightSkyUniforms>(device, "firmament NightSkyPass uniforms");
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("firmament NightSkyPass bind group layout"),
            entries: &[uniform_entry(0)],
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament NightSkyPass bind group"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniforms.as_entire_binding(),
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("firmament NightSkyPass pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("firmament NightSkyPass shader"),
            source: wgpu::ShaderSource::Wgsl(shaders::NIGHT_SKY.source().into()),
        });
        let star_buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<StarInstance>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4],
        })];
        let pipeline = |what: &str, vertex: &str, fragment: &str, buffers: &[Option<wgpu::VertexBufferLayout<'_>>]| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&format!("firmament NightSkyPass {what} pipeline")),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(vertex),
                    compilation_options: options(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::TriangleStrip,
                    ..Default::default()
                },
                depth_stencil: Some(far_plane_depth_state(depth, convention)),
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(fragment),
                    compilation_options: options(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: color,
                        blend: Some(super::common::ADDITIVE),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        Self {
            star_pipeline: pipeline("star", "vs_star", "fs_star", &star_buffers),
            moon_pipeline: pipeline("moon", "vs_moon", "fs_moon", &[]),
            uniforms,
            bind_group,
            instances: instance_buffer(device, INITIAL_STAR_CAPACITY),
            capacity: INITIAL_STAR_CAPACITY,
            star_count: 0,
            instance_count: 0,
            moon_draw: MoonDraw::Hidden,
        }
    }

    /// Uploads `layer` as `camera` (whose aspect must be the target's) sees it on a target of
    /// `size` = (width, height) pixels. Stars with a non-finite or zero direction, a non-finite
    /// colour or no light are skipped (negative channels count as 0); the Moon is skipped when
    /// malformed or not wholly in front of the camera, and drawn as a star when it is smaller
    /// than [`MIN_MOON_DISC_RADIUS_PX`](crate::gpu_types::night_sky::MIN_MOON_DISC_RADIUS_PX).
    /// Stars behind the camera are culled on the GPU, so every kept star is uploaded.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layer: &NightLayer,
        camera: &Camera,
        size: (u32, u32),
    ) {
        let mut instances: Vec<StarInstance> = layer.stars.iter().filter_map(StarInstance::new).collect();
        self.star_count = instances.len() as u32;
        let (uniforms, moon) = NightSkyUniforms::new(camera, size.0.max(1), size.1.max(1), layer.moon.as_ref());
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&uniforms));
        if let MoonDraw::Point(point) = moon {
            instances.push(point);
        }
        self.moon_draw = moon;
        if instances.len() > self.capacity {
            self.capacity = instances.len().next_power_of_two();
            self.instances = instance_buffer(device, self.capacity);
        }
        if !instances.is_empty() {
            queue.write_buffer(&self.instances, 0, bytemuck::cast_slice(&instances));
        }
        self.instance_count = instances.len() as u32;
    }

    /// How many stars the last `prepare` uploaded (every star of the layer but malformed or dark
    /// ones; those behind the camera or off screen are clipped on the GPU).
    pub fn star_count(&self) -> u32 {
        self.star_count
    }

    /// How the last `prepare` left the Moon to be drawn.
    pub fn moon(&self) -> MoonDraw {
        self.moon_draw
    }

    /// Whether the last `prepare` left nothing to draw.
    pub fn is_empty(&self) -> bool {
        self.instance_count == 0 && self.moon_draw != MoonDraw::Disc
    }

    /// Draws into a render pass the caller already began, with the HDR target and the frame's
    /// reversed-Z depth buffer attached.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        if self.is_empty() {
            return;
        }
        pass.set_bind_group(0, &self.bind_group, &[]);
        if self.instance_count > 0 {
            pass.set_pipeline(&self.star_pipeline);
            pass.set_vertex_buffer(0, self.instances.slice(..));
            pass.draw(0..4, 0..self.instance_count);
        }
        if self.moon_draw == MoonDraw::Disc {
            pass.set_pipeline(&self.moon_pipeline);
            pass.draw(0..4, 0..1);
        }
    }

    /// Adds the stars and the Moon to `color` (loaded) where `depth` (loaded) is still at the
    /// far plane.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView, depth: &wgpu::TextureView) {
        if self.is_empty() {
            return;
        }
        let mut pass = begin_load_pass(encoder, "firmament NightSkyPass", color, depth);
        self.draw(&mut pass);
    }
}
