//! Environment maps into the caller's own GPU textures, with no read-back: the six faces are
//! rendered by the ordinary frame path (one frame, one submission each), their HDR images copied
//! side by side into an atlas, then compute kernels (`shaders/envmap/write.wgsl`) write each cube
//! layer or the equirectangular map from it into a plain 2D texture of the target's format,
//! adding the suns' disc pieces texel by texel exactly as the CPU path ([`super::discs`]) does,
//! and each is copied into its layer of the caller's texture.

use std::collections::HashMap;

use firmament_core::Frame;

use super::discs::{Target, TexelRuns, texel_runs};
use super::{SunDiscs, for_each_face_frame, suns_at_eye};
use crate::context::GpuContext;
use crate::error::{RenderError, pop_error_scopes};
use crate::gpu_types::EnvmapParamsUniforms;
use crate::headless::HeadlessRenderer;
use crate::shaders;
use crate::targets::HDR_FORMAT;

/// The formats [`EnvironmentMapPass`] renders into: linear float RGBA. The suns' discs
/// ([`SunDiscs::Included`]) need `Rgba32Float`: a noon Sun's ~1.6·10⁹ cd/m² overflows half floats.
pub const ENVMAP_FORMATS: [wgpu::TextureFormat; 2] =
    [wgpu::TextureFormat::Rgba16Float, wgpu::TextureFormat::Rgba32Float];

/// Bytes between the per-layer uniform slots (wgpu's largest uniform offset alignment).
const SLOT: u64 = 256;

/// The faces in the atlas: 3 across, 2 down.
const ATLAS_FACES: (u32, u32) = (3, 2);

/// The sky kernels' workgroup side (`@workgroup_size(8, 8)` in `envmap/write.wgsl`).
const SKY_GROUP: u32 = 8;
/// The disc kernels' workgroup size (`@workgroup_size(64)`).
const DISC_GROUP: u32 = 64;

/// The `output` declaration of `envmap/write.wgsl`, whose format word [`write_source`] replaces.
const OUTPUT_DECLARATION: &str = "var output: texture_storage_2d<rgba16float, write>;";

/// `envmap/write.wgsl` with its output in `format` ([`ENVMAP_FORMATS`]).
pub(crate) fn write_source(format: wgpu::TextureFormat) -> String {
    let source = shaders::ENVMAP_WRITE.source();
    match format {
        wgpu::TextureFormat::Rgba32Float => source.replacen(
            OUTPUT_DECLARATION,
            &OUTPUT_DECLARATION.replace("rgba16float", "rgba32float"),
            1,
        ),
        _ => source.to_owned(),
    }
}

/// What the pass writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Layout {
    Cube,
    Equirect,
}

/// The kernels writing one output format, and their bind group layout.
#[derive(Debug)]
struct Kernels {
    layout: wgpu::BindGroupLayout,
    cube_sky: wgpu::ComputePipeline,
    equirect_sky: wgpu::ComputePipeline,
    cube_disc: wgpu::ComputePipeline,
    equirect_disc: wgpu::ComputePipeline,
}

impl Kernels {
    fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&format!("firmament EnvironmentMapPass shader ({format:?})")),
            source: wgpu::ShaderSource::Wgsl(write_source(format).into()),
        });
        let compute = wgpu::ShaderStages::COMPUTE;
        let read_only = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: compute,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("firmament EnvironmentMapPass bind group layout ({format:?})")),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: binding::PARAMS,
                    visibility: compute,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: true,
                        min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<EnvmapParamsUniforms>() as u64),
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: binding::FACES,
                    visibility: compute,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                read_only(binding::PIECES),
                read_only(binding::DISC_TEXELS),
                wgpu::BindGroupLayoutEntry {
                    binding: binding::OUTPUT,
                    visibility: compute,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&format!("firmament EnvironmentMapPass pipeline layout ({format:?})")),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let kernel = |entry_point: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&format!("firmament EnvironmentMapPass {entry_point} ({format:?})")),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry_point),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        Self {
            cube_sky: kernel("cube_sky_kernel"),
            equirect_sky: kernel("equirect_sky_kernel"),
            cube_disc: kernel("cube_disc_kernel"),
            equirect_disc: kernel("equirect_disc_kernel"),
            layout,
        }
    }

    /// The sky and disc kernels of `layout`.
    fn of(&self, layout: Layout) -> (&wgpu::ComputePipeline, &wgpu::ComputePipeline) {
        match layout {
            Layout::Cube => (&self.cube_sky, &self.cube_disc),
            Layout::Equirect => (&self.equirect_sky, &self.equirect_disc),
        }
    }
}

/// Renders environment maps into the caller's textures: six square cube layers
/// ([`render_cube`](Self::render_cube)) or an equirectangular map
/// ([`render_equirect`](Self::render_equirect)), the same texels as
/// [`HeadlessRenderer::render_cube_faces`] and
/// [`render_equirect`](HeadlessRenderer::render_equirect) give in memory (see the
/// [module](super) for the layouts and units).
///
/// Each call renders six frames with the [`HeadlessRenderer`] it is given (each a submission of
/// its own), then one submission that writes the target; it returns once they are submitted (the
/// GPU's queue orders whatever the caller submits later). The map is computed into the pass's own
/// plain 2D texture of the target's format and copied into the target (`COPY_DST`): wgpu's GL
/// backend cannot draw into `Rgba32Float`, nor write a square six-layer texture (a cube map to
/// it) as storage, but copies into its layers. Kernels are built on first use of a format and
/// kept, like the faces' atlas (`3·size × 2·size` half floats) and the output texture for the
/// next map of the same size.
///
/// ```
/// use firmament_render::envmap::{EnvironmentMapPass, SunDiscs};
/// use firmament_render::{Backend, GpuContext, headless::HeadlessRenderer, wgpu};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let scene = firmament_scene::load(firmament_scene::SceneSource::Preset("earth-noon"), None, &[])?;
/// let frame = scene.frame_at(None)?;
/// let ctx = GpuContext::headless(Backend::Auto)?;
/// // Your cube texture: six square layers, sampled as a cube by your shaders.
/// let cube = |format| {
///     ctx.device.create_texture(&wgpu::TextureDescriptor {
///         label: Some("my sky cube"),
///         size: wgpu::Extent3d { width: 16, height: 16, depth_or_array_layers: 6 },
///         mip_level_count: 1,
///         sample_count: 1,
///         dimension: wgpu::TextureDimension::D2,
///         format,
///         usage: wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::TEXTURE_BINDING,
///         view_formats: &[],
///     })
/// };
/// let mut headless = HeadlessRenderer::new(&ctx);
/// let mut pass = EnvironmentMapPass::new(&ctx);
/// let sky = cube(wgpu::TextureFormat::Rgba32Float);
/// pass.render_cube(&ctx, &mut headless, &frame, &sky, SunDiscs::Included)?; // 6 frames, 16²
/// // Half floats cannot hold a disc: refused, naming the rule.
/// let half = cube(wgpu::TextureFormat::Rgba16Float);
/// let refused = pass.render_cube(&ctx, &mut headless, &frame, &half, SunDiscs::Included);
/// assert!(refused.is_err_and(|e| e.to_string().contains("needs Rgba32Float")));
/// pass.render_cube(&ctx, &mut headless, &frame, &half, SunDiscs::Omitted)?;
/// # Ok(())
/// # }
/// ```
#[derive(Debug)]
pub struct EnvironmentMapPass {
    kernels: HashMap<wgpu::TextureFormat, Kernels>,
    /// One [`EnvmapParamsUniforms`] per cube layer, [`SLOT`] bytes apart.
    uniforms: wgpu::Buffer,
    /// The six faces' HDR images as the face cameras drew them, and their side.
    atlas: Option<(wgpu::Texture, u32)>,
    /// The map (or one cube layer) as computed, before its copy into the target.
    output: Option<wgpu::Texture>,
}

impl EnvironmentMapPass {
    /// Makes the pass (its kernels are built on first use of each format).
    pub fn new(ctx: &GpuContext) -> Self {
        let uniforms = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("firmament EnvironmentMapPass uniforms"),
            size: SLOT * 6,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            kernels: HashMap::new(),
            uniforms,
            atlas: None,
            output: None,
        }
    }

    /// Renders the six faces around `frame`'s camera position into layers 0–5 (mip 0) of
    /// `target`, in OpenGL's order `+X, −X, +Y, −Y, +Z, −Z` of the Y-up frame (`x` east, `y` up,
    /// `z` south), each texel what [`HeadlessRenderer::render_cube_faces`] gives for it.
    ///
    /// `target`: a 2D texture of 6 square layers, one sample, format one of [`ENVMAP_FORMATS`]
    /// (`Rgba32Float` for [`SunDiscs::Included`]), usage `COPY_DST` (and yours, e.g.
    /// `TEXTURE_BINDING` to sample it as a cube). Anything else is a
    /// [`RenderError::EnvironmentMapTarget`] naming the rule, with nothing rendered.
    pub fn render_cube(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut HeadlessRenderer,
        frame: &Frame,
        target: &wgpu::Texture,
        discs: SunDiscs,
    ) -> Result<(), RenderError> {
        self.render(ctx, renderer, frame, target, (Layout::Cube, discs))
    }

    /// Renders the equirectangular map around `frame`'s camera position into mip 0 of `target`,
    /// `width` × `width / 2` (`width` even, at least 4), each pixel what
    /// [`HeadlessRenderer::render_equirect`] gives for it: bilinear from faces of side
    /// `⌈width / 4⌉`, the discs added into the map's own pixels.
    ///
    /// `target`: a 2D texture of one layer, one sample, twice as wide as high, format one of
    /// [`ENVMAP_FORMATS`] (`Rgba32Float` for [`SunDiscs::Included`]), usage `COPY_DST` (and
    /// yours). Anything else is a
    /// [`RenderError::EnvironmentMapTarget`] naming the rule, with nothing rendered.
    pub fn render_equirect(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut HeadlessRenderer,
        frame: &Frame,
        target: &wgpu::Texture,
        discs: SunDiscs,
    ) -> Result<(), RenderError> {
        self.render(ctx, renderer, frame, target, (Layout::Equirect, discs))
    }

    /// Checks `target`, renders the faces and writes the map as `layout` says.
    fn render(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut HeadlessRenderer,
        frame: &Frame,
        target: &wgpu::Texture,
        (layout, discs): (Layout, SunDiscs),
    ) -> Result<(), RenderError> {
        let size = check_target(ctx, target, layout, discs)?;
        let runs = match (discs, layout) {
            (SunDiscs::Omitted, _) => TexelRuns::default(),
            (SunDiscs::Included, Layout::Cube) => texel_runs(&suns_at_eye(frame), Target::Cube { size }),
            (SunDiscs::Included, Layout::Equirect) => {
                let (width, height) = (target.width(), target.height());
                texel_runs(&suns_at_eye(frame), Target::Equirect { width, height })
            }
        };
        self.draw_faces(ctx, renderer, frame, size)?;
        self.write_target(ctx, target, layout, &runs)
    }

    /// Renders the six faces of side `size` and copies each frame's HDR image into the atlas, in
    /// that frame's submission.
    fn draw_faces(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut HeadlessRenderer,
        frame: &Frame,
        size: u32,
    ) -> Result<(), RenderError> {
        if self.atlas.as_ref().map(|(_, side)| *side) != Some(size) {
            self.atlas = None;
            let atlas = crate::targets::texture_2d(
                &ctx.device,
                "firmament EnvironmentMapPass faces atlas",
                (ATLAS_FACES.0 * size, ATLAS_FACES.1 * size),
                HDR_FORMAT,
                wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::TEXTURE_BINDING,
            );
            self.atlas = Some((atlas, size));
        }
        let Some((atlas, _)) = &self.atlas else {
            return Err(RenderError::Readback("no environment-map atlas".into()));
        };
        for_each_face_frame(frame, |face, face_frame| {
            let k = face.index() as u32;
            let origin = wgpu::Origin3d {
                x: (k % ATLAS_FACES.0) * size,
                y: (k / ATLAS_FACES.0) * size,
                z: 0,
            };
            renderer.render_then(ctx, face_frame, (size, size), |encoder, _, targets| {
                encoder.copy_texture_to_texture(
                    targets.hdr.as_image_copy(),
                    wgpu::TexelCopyTextureInfo {
                        texture: atlas,
                        mip_level: 0,
                        origin,
                        aspect: wgpu::TextureAspect::All,
                    },
                    wgpu::Extent3d {
                        width: size,
                        height: size,
                        depth_or_array_layers: 1,
                    },
                );
                Ok(())
            })?;
            Ok(())
        })
    }

    /// Computes the target's layers (the cube's six, or the one map) from the atlas with the disc
    /// pieces of `runs`, each into the pass's output texture and copied from there into mip 0 of
    /// its layer of `target`, in one submission.
    fn write_target(
        &mut self,
        ctx: &GpuContext,
        target: &wgpu::Texture,
        layout: Layout,
        runs: &TexelRuns,
    ) -> Result<(), RenderError> {
        let device = &ctx.device;
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let oom = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let (format, width, height) = (target.format(), target.width(), target.height());
        let Some((atlas, size)) = &self.atlas else {
            return Err(RenderError::Readback("no environment-map atlas".into()));
        };
        let kernels = self
            .kernels
            .entry(format)
            .or_insert_with(|| Kernels::new(device, format));
        let output = match self.output.take() {
            Some(output) if (output.format(), output.width(), output.height()) == (format, width, height) => output,
            _ => crate::targets::texture_2d(
                device,
                "firmament EnvironmentMapPass output",
                (width, height),
                format,
                wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
            ),
        };
        let layers = match layout {
            Layout::Cube => 6,
            Layout::Equirect => 1,
        };
        for face in 0..layers {
            let params = EnvmapParamsUniforms {
                face,
                size: *size,
                width,
                height,
            };
            ctx.queue
                .write_buffer(&self.uniforms, u64::from(face) * SLOT, bytemuck::bytes_of(&params));
        }
        let buffer = |what: &str, bytes: &[u8]| {
            // Never empty: a binding holds at least one element (a zero disc texel has no pieces).
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("firmament EnvironmentMapPass {what}")),
                size: (bytes.len() as u64).max(32).next_multiple_of(4),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            ctx.queue.write_buffer(&buffer, 0, bytes);
            buffer
        };
        let pieces = buffer("disc pieces", bytemuck::cast_slice(&runs.pieces));
        let disc_texels = buffer("disc texels", bytemuck::cast_slice(&runs.texels));
        let atlas_view = atlas.create_view(&wgpu::TextureViewDescriptor::default());
        let output_view = output.create_view(&wgpu::TextureViewDescriptor::default());
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("firmament EnvironmentMapPass bind group"),
            layout: &kernels.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: binding::PARAMS,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &self.uniforms,
                        offset: 0,
                        size: wgpu::BufferSize::new(std::mem::size_of::<EnvmapParamsUniforms>() as u64),
                    }),
                },
                wgpu::BindGroupEntry {
                    binding: binding::FACES,
                    resource: wgpu::BindingResource::TextureView(&atlas_view),
                },
                wgpu::BindGroupEntry {
                    binding: binding::PIECES,
                    resource: pieces.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: binding::DISC_TEXELS,
                    resource: disc_texels.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: binding::OUTPUT,
                    resource: wgpu::BindingResource::TextureView(&output_view),
                },
            ],
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("firmament EnvironmentMapPass encoder"),
        });
        let (sky, disc) = kernels.of(layout);
        let texels = runs.texels.len() as u32;
        for face in 0..layers {
            let offset = [face * SLOT as u32];
            let mut dispatch = |kernel: &wgpu::ComputePipeline, groups: (u32, u32)| {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("firmament EnvironmentMapPass"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(kernel);
                pass.set_bind_group(0, &bind_group, &offset);
                pass.dispatch_workgroups(groups.0, groups.1, 1);
            };
            dispatch(sky, (width.div_ceil(SKY_GROUP), height.div_ceil(SKY_GROUP)));
            if texels > 0 {
                // After the sky, in a pass of its own: the texels the discs fall in, overwritten.
                dispatch(disc, (texels.div_ceil(DISC_GROUP), 1));
            }
            encoder.copy_texture_to_texture(
                output.as_image_copy(),
                wgpu::TexelCopyTextureInfo {
                    texture: target,
                    mip_level: 0,
                    origin: wgpu::Origin3d { x: 0, y: 0, z: face },
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
            );
        }
        ctx.queue.submit([encoder.finish()]);
        self.output = Some(output);
        pop_error_scopes(oom, validation, "rendering an environment map")
    }
}

/// The pass's binding numbers (declared in `envmap/from_faces.wgsl` and `envmap/write.wgsl`; a
/// test compares them).
mod binding {
    pub(super) const PARAMS: u32 = 0;
    pub(super) const FACES: u32 = 1;
    pub(super) const PIECES: u32 = 2;
    pub(super) const DISC_TEXELS: u32 = 3;
    pub(super) const OUTPUT: u32 = 4;
}

/// The faces' side for `target` drawn as `layout` with `discs`, or the rule it breaks.
fn check_target(ctx: &GpuContext, target: &wgpu::Texture, layout: Layout, discs: SunDiscs) -> Result<u32, RenderError> {
    let (width, height, layers) = (target.width(), target.height(), target.depth_or_array_layers());
    let format = target.format();
    let what = match layout {
        Layout::Cube => "a cube map",
        Layout::Equirect => "an equirectangular map",
    };
    let refuse = |rule: String| {
        Err(RenderError::EnvironmentMapTarget(format!(
            "{what} into a {width}x{height}, {layers}-layer {:?} {format:?} texture: {rule}",
            target.dimension()
        )))
    };
    if !ENVMAP_FORMATS.contains(&format) {
        return refuse("the format must be Rgba16Float or Rgba32Float (linear float radiance)".into());
    }
    if discs == SunDiscs::Included && format != wgpu::TextureFormat::Rgba32Float {
        return refuse(
            "the suns' discs (a noon Sun is about 1.6e9 cd/m²) overflow half floats (at most 65504): \
             SunDiscs::Included needs Rgba32Float; Rgba16Float takes SunDiscs::Omitted"
                .into(),
        );
    }
    if target.dimension() != wgpu::TextureDimension::D2 {
        return refuse("the texture must be 2D".into());
    }
    if target.sample_count() != 1 {
        return refuse(format!("the texture must have 1 sample, not {}", target.sample_count()));
    }
    if !target.usage().contains(wgpu::TextureUsages::COPY_DST) {
        return refuse("the texture's usage must include COPY_DST (the map is copied into it)".into());
    }
    let size = match layout {
        Layout::Cube => {
            if layers != 6 {
                return refuse("a cube map needs exactly 6 array layers (+X, −X, +Y, −Y, +Z, −Z)".into());
            }
            if width != height {
                return refuse("a cube map's layers must be square".into());
            }
            width
        }
        Layout::Equirect => {
            if layers != 1 {
                return refuse("an equirectangular map needs exactly 1 layer".into());
            }
            if width < 4 || !width.is_multiple_of(2) || height != width / 2 {
                return refuse("the width must be even, at least 4, and the height half of it".into());
            }
            width.div_ceil(4)
        }
    };
    // The faces are rendered at `size` and kept in a 3 × 2 atlas.
    ctx.check_image_size(ATLAS_FACES.0 * size, ATLAS_FACES.1 * size)?;
    Ok(size)
}

#[cfg(test)]
mod tests {
    use super::binding;

    #[test]
    fn the_binding_numbers_are_those_of_the_wgsl() {
        let rust: Vec<(String, u32)> = [
            ("disc_texels", binding::DISC_TEXELS),
            ("faces", binding::FACES),
            ("output", binding::OUTPUT),
            ("params", binding::PARAMS),
            ("pieces", binding::PIECES),
        ]
        .map(|(name, number)| (name.to_owned(), number))
        .into();
        assert_eq!(crate::shaders::declared_bindings("envmap/write"), rust);
    }
}
