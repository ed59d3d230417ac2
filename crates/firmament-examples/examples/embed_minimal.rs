//! firmament inside your own winit + wgpu app: your pipeline draws a cube into your HDR target
//! and depth buffer, lit by firmament's sun and sky; firmament adds the sky behind it, the air in
//! front of it (aerial perspective from your depth buffer), the sun's lens flare, and writes the
//! finished image to your window. The firmament part is 17 lines of Rust, each ending in a
//! `// firmament` comment (the cube's WGSL reads firmament's light in 3 more, and its camera is
//! the firmament frame's).
//!
//! ```sh
//! cargo run -p firmament-examples --example embed_minimal -- [PRESET] [FRAMES]
//! ```
//!
//! Defaults: `earth-sunset`, running until the window closes (FRAMES: close after that many).

use std::error::Error;
use std::sync::Arc;

use firmament_render::wgpu::util::DeviceExt;
use firmament_render::{DepthConvention, EmbedTarget, GpuContext, Renderer, wgpu}; // firmament
use glam::{DVec3, Mat4, Vec3Swizzles};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::{Window, WindowId};

/// Your cube's shader: Lambert under firmament's suns plus its sky's irradiance (the include
/// `FIRMAMENT_LIGHTING_WGSL` goes before it, its buffer at group 0, binding 1).
const CUBE_WGSL: &str = r"
@group(0) @binding(0) var<uniform> view_proj: mat4x4<f32>; // camera-relative → clip (reversed Z)

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) normal: vec3<f32>,
}

@vertex
fn vs_main(@location(0) relative: vec3<f32>, @location(1) normal: vec3<f32>) -> Out {
    return Out(view_proj * vec4<f32>(relative, 1.0), normal);
}

@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    let n = normalize(in.normal);
    var irradiance = firmament_sky_irradiance(n);
    for (var i = 0u; i < firmament_sun_count(); i++) {
        irradiance += firmament_sun_color(i) * max(dot(n, firmament_sun_direction(i)), 0.0);
    }
    return vec4<f32>(vec3<f32>(0.5, 0.35, 0.25) / 3.14159265 * irradiance, 1.0);
}
";

/// Your window, device and cube, and firmament's renderer.
struct App {
    preset: String,
    frames_left: Option<u64>,
    state: Option<State>,
    error: Option<Box<dyn Error>>,
}

struct State {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    ctx: GpuContext, // firmament: your device, wrapped
    pipeline: wgpu::RenderPipeline,
    camera_buffer: wgpu::Buffer,
    layout: wgpu::BindGroupLayout,
    /// Made at the first frame: firmament's lighting buffer exists once it has a frame.
    bind_group: Option<wgpu::BindGroup>,
    cube: (wgpu::Buffer, u32),
    targets: (wgpu::TextureView, wgpu::TextureView),
    frame: firmament_core::Frame, // firmament: the scene's frame
    sky: Renderer,                // firmament: its renderer
}

/// Your HDR colour target and depth buffer at the window's size (`TEXTURE_BINDING` on both:
/// firmament reads them).
fn targets(device: &wgpu::Device, width: u32, height: u32) -> (wgpu::TextureView, wgpu::TextureView) {
    let make = |label, format| {
        device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
            .create_view(&Default::default())
    };
    (
        make("my HDR target", wgpu::TextureFormat::Rgba16Float),
        make("my depth", wgpu::TextureFormat::Depth32Float),
    )
}

/// A 2 m cube 12 m in front of `eye` along `forward`, as (camera-relative position, normal).
fn cube(eye: DVec3, forward: DVec3) -> Vec<[f32; 6]> {
    let centre = eye + DVec3::new(forward.x, forward.y, 0.0).normalize_or(DVec3::Y) * 12.0;
    let mut vertices = Vec::new();
    for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
        let (u, v) = (axis.yzx(), axis.zxy());
        for normal in [-axis, axis] {
            let corner = |a: f64, b: f64| {
                let p = (centre + normal + u * a + v * b - eye).as_vec3();
                [p.x, p.y, p.z, normal.x as f32, normal.y as f32, normal.z as f32]
            };
            let quad = [
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
            ];
            vertices.extend([quad[0], quad[1], quad[2], quad[0], quad[2], quad[3]]);
        }
    }
    vertices
}

impl State {
    fn new(event_loop: &ActiveEventLoop, preset: &str) -> Result<Self, Box<dyn Error>> {
        let window = Arc::new(event_loop.create_window(Window::default_attributes().with_title("embed_minimal"))?);
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle(Box::new(
            event_loop.owned_display_handle(),
        )));
        let surface = instance.create_surface(window.clone())?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            compatible_surface: Some(&surface),
            ..Default::default()
        }))?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            required_features: firmament_render::required_features(), // firmament: what it needs
            required_limits: firmament_render::required_limits().using_resolution(adapter.limits()), // firmament
            ..Default::default()
        }))?;
        let caps = surface.get_capabilities(&adapter);
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| f.is_srgb())
            .unwrap_or(caps.formats[0]);
        let size = window.inner_size();
        let config = surface
            .get_default_config(&adapter, size.width.max(1), size.height.max(1))
            .ok_or("the window's surface does not suit this adapter")?;
        let config = wgpu::SurfaceConfiguration { format, ..config };
        surface.configure(&device, &config);

        let ctx = GpuContext::from_device(device.clone(), queue.clone())?; // firmament: your device
        let scene = firmament_scene::load(firmament_scene::SceneSource::Preset(preset), None, &[])?; // firmament
        let frame = scene.frame_at(None)?; // firmament: the sky, suns and camera to draw
        let sky = Renderer::new(&ctx, format); // firmament: its passes, built once

        // Your pipeline: firmament's lighting include before your shader, its buffer in your group.
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("my cube"),
            // firmament: its lighting include (group 0, binding 1) before your shader.
            source: wgpu::ShaderSource::Wgsl(
                format!("{}\n{CUBE_WGSL}", firmament_render::firmament_lighting_wgsl(0, 1)).into(), // firmament
            ),
        });
        let camera_entry = wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("my cube"),
            entries: &[camera_entry, firmament_render::sky_lighting_layout_entry(1)], // firmament
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("my cube"),
            layout: Some(&device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("my cube"),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            })),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: 24,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
                })],
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::TextureFormat::Rgba16Float.into())],
            }),
            primitive: Default::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: wgpu::TextureFormat::Depth32Float,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Greater), // reversed Z
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        });
        let camera_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("my camera"),
            size: 64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let vertices = cube(frame.camera.position, frame.camera.forward());
        let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("my cube"),
            contents: bytemuck::cast_slice(&vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        Ok(Self {
            targets: targets(&device, config.width, config.height),
            window,
            surface,
            config,
            ctx,
            pipeline,
            camera_buffer,
            layout,
            bind_group: None,
            cube: (vertex_buffer, vertices.len() as u32),
            frame,
            sky,
        })
    }

    fn resize(&mut self, width: u32, height: u32) {
        if width > 0 && height > 0 {
            (self.config.width, self.config.height) = (width, height);
            self.surface.configure(&self.ctx.device, &self.config);
            self.targets = targets(&self.ctx.device, width, height);
        }
    }

    fn draw(&mut self) -> Result<(), Box<dyn Error>> {
        let surface_texture = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t) | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Outdated => {
                self.surface.configure(&self.ctx.device, &self.config);
                return Ok(());
            }
            _ => return Ok(()), // occluded, a timeout: next frame
        };
        let output = surface_texture.texture.create_view(&Default::default());
        let (color, depth) = &self.targets;
        let target = EmbedTarget::new(color, depth, DepthConvention::Reversed).with_output(&output); // firmament
        self.sky.prepare_into(&self.ctx, &self.frame, &target)?; // firmament: upload the frame

        // Your camera: firmament's, camera-relative, in the depth convention above.
        let camera = firmament_core::Camera {
            aspect: f64::from(self.config.width) / f64::from(self.config.height),
            ..self.frame.camera
        };
        let view_proj: Mat4 =
            (camera.projection_matrix_for(DepthConvention::Reversed) * camera.view_rotation()).as_mat4();
        self.ctx
            .queue
            .write_buffer(&self.camera_buffer, 0, bytemuck::cast_slice(&view_proj.to_cols_array()));

        if self.bind_group.is_none() {
            let lighting = self.sky.sky_lighting_buffer().ok_or("the preset has no physical sky")?; // firmament
            self.bind_group = Some(self.ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("my cube"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: self.camera_buffer.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: lighting.as_entire_binding(),
                    },
                ],
            }));
        }

        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        self.sky.record_lighting(&mut encoder); // firmament: this frame's sun and sky light
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("my cube"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: color,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(DepthConvention::Reversed.far_depth() as f32),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, self.bind_group.as_ref(), &[]);
            pass.set_vertex_buffer(0, self.cube.0.slice(..));
            pass.draw(0..self.cube.1, 0..1);
        }
        self.sky.record_into(&mut encoder, &target)?; // firmament: sky, air, flares → your window
        self.ctx.queue.submit([encoder.finish()]);
        self.window.pre_present_notify();
        self.ctx.queue.present(surface_texture);
        Ok(())
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.state.is_none() {
            match State::new(event_loop, &self.preset) {
                Ok(state) => {
                    state.window.request_redraw();
                    self.state = Some(state);
                }
                Err(error) => {
                    self.error = Some(error);
                    event_loop.exit();
                }
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(state) = self.state.as_mut() else { return };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => state.resize(size.width, size.height),
            WindowEvent::RedrawRequested => {
                if let Err(error) = state.draw() {
                    self.error = Some(error);
                    event_loop.exit();
                    return;
                }
                if let Some(left) = self.frames_left.as_mut() {
                    *left = left.saturating_sub(1);
                    if *left == 0 {
                        event_loop.exit();
                    }
                }
                state.window.request_redraw();
            }
            _ => {}
        }
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut app = App {
        preset: args.first().cloned().unwrap_or_else(|| "earth-sunset".to_owned()),
        frames_left: args.get(1).map(|n| n.parse()).transpose()?,
        state: None,
        error: None,
    };
    EventLoop::new()?.run_app(&mut app)?;
    app.error.map_or(Ok(()), Err)
}
