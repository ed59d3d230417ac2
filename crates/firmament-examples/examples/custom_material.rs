//! Your own WGSL material under firmament's sky: a Lambert + ambient shader of yours, drawn with
//! your own pipeline into your own HDR target and depth buffer, lit by firmament's suns
//! (`firmament_sun_direction/color`) and sky (`firmament_sky_irradiance`) and fogged by its aerial
//! perspective (`firmament_apply_aerial_perspective`); firmament's renderer then draws the sky
//! behind your geometry (`Renderer::record_into`, leaving the air over it to your shader).
//! Headless: the HDR image is tone-mapped on the CPU and saved as a PNG.
//!
//! ```sh
//! cargo run -p firmament-examples --example custom_material -- [OUT.png] [WIDTH HEIGHT]
//! ```
//!
//! Defaults: `custom_material.png`, 640 × 360. The sky is the `earth-objects` preset's (45° N, the
//! Sun 20° up in the south-west); two boxes of the same grey stand north of the camera, one 60 m
//! away and one 5 km away, bluer and paler from the air in front of it.

use std::error::Error;
use std::path::Path;

use firmament_core::Camera;
use firmament_core::color::{LinearRgb, linear_to_srgb};
use firmament_render::headless::{decode_f16, read_texture};
use firmament_render::wgpu::util::DeviceExt;
use firmament_render::{DEPTH_FORMAT, DepthConvention, EmbedTarget, GpuContext, HDR_FORMAT, Renderer, wgpu};
use glam::DVec3;

/// Your material: Lambert under firmament's suns plus its sky's irradiance as the ambient term,
/// then the air in front of the surface. firmament's two includes go before it; their bindings
/// sit in group 1 (lighting at binding 0, aerial perspective at 1 … 5), yours in group 0.
const MATERIAL_WGSL: &str = r"
struct Camera {
    view_proj: mat4x4<f32>, // camera-relative positions → clip space (reversed Z)
}
@group(0) @binding(0) var<uniform> camera: Camera;

struct VertexOut {
    @builtin(position) position: vec4<f32>,
    @location(0) relative: vec3<f32>, // world position − camera position (m)
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
    @location(3) clip: vec4<f32>,
}

@vertex
fn vs_main(@location(0) relative: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) albedo: vec3<f32>) -> VertexOut {
    var out: VertexOut;
    out.clip = camera.view_proj * vec4<f32>(relative, 1.0);
    out.position = out.clip;
    out.relative = relative;
    out.normal = normal;
    out.albedo = albedo;
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let n = normalize(in.normal);
    // Lambert: each sun's colour at the camera times the cosine, plus the sky's irradiance.
    var irradiance = firmament_sky_irradiance(n);
    for (var i = 0u; i < firmament_sun_count(); i++) {
        irradiance += firmament_sun_color(i) * max(dot(n, firmament_sun_direction(i)), 0.0);
    }
    let radiance = in.albedo / 3.14159265 * irradiance; // cd/m², the sky's units
    // The air between the camera and the surface.
    let ndc = in.clip.xy / in.clip.w;
    return vec4<f32>(firmament_apply_aerial_perspective(radiance, ndc, length(in.relative)), 1.0);
}
";

/// Your scene: boxes standing on the ground, as (centre of the base, size, albedo), world
/// metres (east, north, up from the ground under the camera).
pub(crate) const BOXES: [([f64; 3], [f64; 3], [f32; 3]); 2] = [
    ([-15.0, 60.0, 0.0], [10.0, 10.0, 10.0], [0.15, 0.15, 0.15]),
    // Its base sunk 20 m: the ground falls away with the planet's curvature.
    ([1200.0, 5000.0, -20.0], [400.0, 400.0, 600.0], [0.15, 0.15, 0.15]),
];

/// One vertex of your mesh: position relative to the camera, normal, albedo.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Vertex {
    relative: [f32; 3],
    normal: [f32; 3],
    albedo: [f32; 3],
}

/// The six faces of each box as triangles, relative to `eye` (in f64 first, so far boxes keep
/// their precision).
fn box_vertices(eye: DVec3) -> Vec<Vertex> {
    let mut vertices = Vec::new();
    for (base, size, albedo) in BOXES {
        let half = DVec3::from(size) / 2.0;
        let centre = DVec3::from(base) + DVec3::Z * half.z;
        let axes = [DVec3::X, DVec3::Y, DVec3::Z];
        for axis in 0..3 {
            let (u, v) = (axes[(axis + 1) % 3], axes[(axis + 2) % 3]);
            for normal in [-axes[axis], axes[axis]] {
                let corner = |a: f64, b: f64| Vertex {
                    relative: (centre + (normal + u * a + v * b) * half - eye).as_vec3().to_array(),
                    normal: normal.as_vec3().to_array(),
                    albedo,
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
    }
    vertices
}

/// Renders the custom material under the `earth-objects` sky at `width` × `height` to the PNG
/// `path`; returns the camera it used.
pub(crate) fn render(path: &Path, width: u32, height: u32) -> Result<Camera, Box<dyn Error>> {
    let adapter = pollster::block_on(wgpu::Instance::default().request_adapter(&Default::default()))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_features: firmament_render::required_features(),
        // firmament's needs, plus this example's: a second bind group, and four uniform buffers
        // in the vertex stage (your camera; firmament's lighting, view and medium).
        required_limits: wgpu::Limits {
            max_bind_groups: 2,
            max_uniform_buffers_per_shader_stage: 4,
            ..firmament_render::required_limits().using_resolution(adapter.limits())
        },
        ..Default::default()
    }))?;
    let ctx = GpuContext::from_device(device.clone(), queue.clone())?;

    // firmament: the sky and camera of a preset, and its renderer, asked to build the
    // aerial-perspective volume for your shader in every frame.
    let frame =
        firmament_scene::load(firmament_scene::SceneSource::Preset("earth-objects"), None, &[])?.frame_at(None)?;
    let camera = Camera {
        aspect: f64::from(width) / f64::from(height),
        ..frame.camera
    };
    let mut sky = Renderer::new(&ctx, wgpu::TextureFormat::Rgba8UnormSrgb);
    sky.set_aerial_perspective_for_users(true);

    // Your targets: linear HDR colour and reversed-Z depth, in the formats the pass was built for.
    let target = |label, format, usage| {
        device.create_texture(&wgpu::TextureDescriptor {
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
            usage,
            view_formats: &[],
        })
    };
    let hdr = target(
        "my HDR target",
        HDR_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    );
    let depth = target(
        "my depth",
        DEPTH_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
    );
    let (hdr_view, depth_view) = (
        hdr.create_view(&Default::default()),
        depth.create_view(&Default::default()),
    );
    // Your frame for firmament: your shader applies the air itself, so firmament does not.
    let target = EmbedTarget::new(&hdr_view, &depth_view, DepthConvention::Reversed).without_aerial_perspective();
    sky.prepare_into(&ctx, &frame, &target)?;

    // Your pipeline: your shader after firmament's includes; group 0 yours, group 1 firmament's.
    let source = format!(
        "{}\n{}\n{MATERIAL_WGSL}",
        firmament_render::FIRMAMENT_LIGHTING_WGSL,
        firmament_render::FIRMAMENT_AERIAL_PERSPECTIVE_WGSL
    );
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("my material"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let camera_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("my camera"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    });
    let mut firmament_entries = vec![firmament_render::sky_lighting_layout_entry(0)];
    firmament_entries.extend(firmament_render::aerial_perspective_layout_entries(1));
    let firmament_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("firmament lighting and aerial perspective"),
        entries: &firmament_entries,
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("my material"),
        layout: Some(&device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("my material"),
            bind_group_layouts: &[Some(&camera_layout), Some(&firmament_layout)],
            immediate_size: 0,
        })),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3],
            })],
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(HDR_FORMAT.into())],
        }),
        primitive: wgpu::PrimitiveState::default(), // no culling: the winding does not matter
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Greater), // reversed Z
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });

    // Your data: the camera-relative view-projection and the boxes.
    let view_proj = (camera.projection_matrix() * camera.view_rotation()).as_mat4();
    let camera_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("my camera"),
        contents: bytemuck::cast_slice(&view_proj.to_cols_array()),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let vertices = box_vertices(camera.position);
    let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("my boxes"),
        contents: bytemuck::cast_slice(&vertices),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let camera_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("my camera"),
        layout: &camera_layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: camera_buffer.as_entire_binding(),
        }],
    });
    // firmament's buffers and textures last as long as the renderer draws into targets of this
    // kind: one bind group serves every frame.
    let (Some(lighting), Some(air)) = (sky.sky_lighting_buffer(), sky.aerial_perspective_bindings()) else {
        return Err("the preset has no physical sky".into());
    };
    let mut firmament_resources = vec![wgpu::BindGroupEntry {
        binding: 0,
        resource: lighting.as_entire_binding(),
    }];
    firmament_resources.extend(air.bind_group_entries(1));
    let firmament_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("firmament lighting and aerial perspective"),
        layout: &firmament_layout,
        entries: &firmament_resources,
    });

    // The frame: firmament's lighting and aerial-perspective volume, your boxes, then the sky
    // behind them.
    let mut encoder = device.create_command_encoder(&Default::default());
    sky.record_lighting(&mut encoder);
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("my boxes"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &hdr_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            ..Default::default()
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &camera_group, &[]);
        pass.set_bind_group(1, &firmament_group, &[]);
        pass.set_vertex_buffer(0, vertex_buffer.slice(..));
        pass.draw(0..vertices.len() as u32, 0..1);
    }
    sky.record_into(&mut encoder, &target)?;
    queue.submit([encoder.finish()]);

    // Your tone mapping, here on the CPU: the preset's exposure and curve, then sRGB.
    let radiance = decode_f16(&read_texture(&ctx, &hdr)?);
    let pixels: Vec<u8> = radiance
        .chunks_exact(4)
        .flat_map(|p| {
            let c = frame
                .display
                .display_linear(LinearRgb::new(p[0].into(), p[1].into(), p[2].into()));
            [c.r, c.g, c.b]
                .map(|v| (linear_to_srgb(v.clamp(0.0, 1.0)) * 255.0).round() as u8)
                .into_iter()
                .chain([255])
        })
        .collect();
    image::save_buffer(path, &pixels, width, height, image::ExtendedColorType::Rgba8)?;
    Ok(camera)
}

/// `[OUT.png] [WIDTH HEIGHT]`, each optional from the end.
pub(crate) fn run(args: impl IntoIterator<Item = String>) -> Result<Camera, Box<dyn Error>> {
    let args: Vec<String> = args.into_iter().collect();
    let output = args.first().map_or("custom_material.png", String::as_str);
    let (width, height) = match (args.get(1), args.get(2)) {
        (Some(w), Some(h)) => (w.parse()?, h.parse()?),
        (None, None) => (640, 360),
        _ => return Err("give both WIDTH and HEIGHT".into()),
    };
    let camera = render(Path::new(output), width, height)?;
    println!("wrote {output} ({width}x{height})");
    Ok(camera)
}

fn main() -> Result<(), Box<dyn Error>> {
    run(std::env::args().skip(1)).map(|_| ())
}
