//! The physically based atmosphere on the GPU: Hillaire 2020's LUT pipeline ("A Scalable and
//! Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020) around an ellipsoid
//! planet, with up to [`MAX_SUNS`] suns.
//!
//! Per frame, [`AtmospherePass::record_luts`] renders
//! 1. the transmittance LUT (Bruneton 2017's parameterisation; a compute pass) and
//! 2. the multiple-scattering LUT and
//! 3. the ground's sky-irradiance LUT — these three only when the medium changed —, then
//! 4. the sky-view LUT, one tile per sun, at the camera;
//!
//! and [`AtmospherePass::draw`] draws the sky, the lit ground and the sun discs behind whatever
//! the depth buffer holds. Above the atmosphere each pixel marches its own ray instead of reading
//! the sky-view LUT.
//!
//! # Ellipsoids
//! Every ray is intersected with the true ellipsoids and every sample's altitude is the true
//! geodetic height (to millimetres; see `firmament_core::atmosphere::planet`). The transmittance
//! and multiple-scattering LUTs, however, are built for a sphere of the planet's mean radius and
//! looked up with the sample's altitude and its local up: the sun's path is treated as crossing a
//! sphere of that radius. On Earth (flattening 1/298) the local radius of curvature differs from
//! the mean by under 0.7 %; on Saturn (0.098) by up to 10 %, which shifts the terminator and
//! the low sun's air mass slightly.

pub mod luts;

use std::cell::Cell;

use firmament_core::Camera;
use firmament_core::frame::{AtmosphereSky, MAX_SUNS};

use crate::gpu_types::{AtmosphereParamsUniforms, AtmosphereViewUniforms};
use crate::passes::{PassPipeline, begin_load_pass, far_plane_depth_state, uniform_buffer, uniform_entry};
use crate::shaders;
use crate::targets::{DEPTH_FORMAT, HDR_FORMAT};

pub use luts::AtmosphereLuts;
use luts::{IRRADIANCE_FORMAT, MULTISCATTERING_FORMAT, SKY_VIEW_FORMAT, SKY_VIEW_TILE, TRANSMITTANCE_FORMAT};

/// Binding numbers shared by every atmosphere shader.
mod binding {
    pub(super) const PARAMS: u32 = 0;
    pub(super) const VIEW: u32 = 1;
    pub(super) const TRANSMITTANCE: u32 = 2;
    pub(super) const MULTISCATTERING: u32 = 3;
    pub(super) const SKY_VIEW: u32 = 4;
    pub(super) const SAMPLER: u32 = 5;
    pub(super) const TRANSMITTANCE_OUT: u32 = 6;
    pub(super) const IRRADIANCE: u32 = 7;
}

fn texture_entry(binding: u32, filterable: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

fn sampler_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        count: None,
    }
}

/// One of the pass's pipelines with its bind group.
#[derive(Debug)]
struct Stage {
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
}

impl Stage {
    /// Builds a stage whose bind group holds `resources` at the bindings `entries` declare.
    fn new(device: &wgpu::Device, pipeline: PassPipeline<'_>, resources: &[(u32, wgpu::BindingResource<'_>)]) -> Self {
        let owner = pipeline.owner;
        let (pipeline, layout) = pipeline.build(device);
        let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
            .iter()
            .map(|(binding, resource)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: resource.clone(),
            })
            .collect();
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("firmament {owner} bind group")),
            layout: &layout,
            entries: &entries,
        });
        Self { pipeline, bind_group }
    }

    /// Renders the stage's full-screen triangle into `target`, cleared, in `viewport` width.
    fn render(&self, encoder: &mut wgpu::CommandEncoder, label: &str, target: &wgpu::TextureView, width: Option<u32>) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        if let Some(width) = width {
            pass.set_viewport(0.0, 0.0, width as f32, SKY_VIEW_TILE.1 as f32, 0.0, 1.0);
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// The transmittance LUT's compute pipeline and its bind group.
#[derive(Debug)]
struct TransmittanceStage {
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
}

impl TransmittanceStage {
    const OWNER: &str = "AtmospherePass transmittance LUT";

    fn new(device: &wgpu::Device, params: &wgpu::Buffer, target: &wgpu::TextureView) -> Self {
        let owner = Self::OWNER;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&format!("firmament {owner} shader")),
            source: wgpu::ShaderSource::Wgsl(shaders::ATMOSPHERE_TRANSMITTANCE_LUT.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("firmament {owner} bind group layout")),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ..uniform_entry(binding::PARAMS)
                },
                wgpu::BindGroupLayoutEntry {
                    binding: binding::TRANSMITTANCE_OUT,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: TRANSMITTANCE_FORMAT,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&format!("firmament {owner} pipeline layout")),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(&format!("firmament {owner} pipeline")),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("cs_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("firmament {owner} bind group")),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: binding::PARAMS,
                    resource: params.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: binding::TRANSMITTANCE_OUT,
                    resource: wgpu::BindingResource::TextureView(target),
                },
            ],
        });
        Self { pipeline, bind_group }
    }

    fn record(&self, encoder: &mut wgpu::CommandEncoder) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&format!("firmament {}", Self::OWNER)),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        let (width, height) = luts::TRANSMITTANCE_SIZE;
        pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
    }
}

/// How the sky pass finds each pixel's scattered light inside the atmosphere.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SkyMethod {
    /// From the sky-view LUT (the fast path; the per-pixel march above the atmosphere).
    #[default]
    Lut,
    /// A ray march per pixel everywhere: the brute-force baseline for benchmarks and checks.
    March,
}

/// The sky pass's variants (the `SKY_MODE` override of `atmosphere/sky.wgsl`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SkyMode {
    Lut = 0,
    March = 1,
    Blend = 2,
}

impl SkyMode {
    fn owner(self) -> &'static str {
        match self {
            Self::Lut => "AtmospherePass sky (sky-view LUT)",
            Self::March => "AtmospherePass sky (ray march)",
            Self::Blend => "AtmospherePass sky (blend)",
        }
    }
}

/// The atmosphere: LUTs and the sky they feed. Build once; `prepare` every frame.
#[derive(Debug)]
pub struct AtmospherePass {
    luts: AtmosphereLuts,
    params: wgpu::Buffer,
    view: wgpu::Buffer,
    transmittance: TransmittanceStage,
    multiscattering: Stage,
    irradiance: Stage,
    sky_view: Stage,
    /// The sky pipelines, indexed by [`SkyMode`].
    sky: [Stage; 3],
    /// Which sky pipeline this frame uses.
    sky_mode: SkyMode,
    /// The medium the LUTs hold, to rebuild them only when it changes.
    uploaded: Option<AtmosphereParamsUniforms>,
    /// Set by `prepare` when the medium changed; cleared once `record_luts` encoded the rebuild.
    medium_changed: Cell<bool>,
    sun_count: u32,
    method: SkyMethod,
}

impl AtmospherePass {
    /// Builds the pipelines for an HDR target of [`HDR_FORMAT`] and depth of [`DEPTH_FORMAT`].
    pub fn new(device: &wgpu::Device) -> Self {
        Self::with_formats(device, HDR_FORMAT, DEPTH_FORMAT)
    }

    /// Builds the pipelines for other colour and depth formats (for embedding in another renderer).
    pub fn with_formats(device: &wgpu::Device, color: wgpu::TextureFormat, depth: wgpu::TextureFormat) -> Self {
        let luts = AtmosphereLuts::new(device);
        let params = uniform_buffer::<AtmosphereParamsUniforms>(device, "firmament AtmospherePass params");
        let view = uniform_buffer::<AtmosphereViewUniforms>(device, "firmament AtmospherePass view");
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("firmament AtmospherePass LUT sampler"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let lut_pipeline = |owner, source, entries, color| PassPipeline {
            owner,
            source,
            entries,
            color,
            depth_stencil: None,
            vertex_buffers: &[],
            primitive: wgpu::PrimitiveState::default(),
            constants: &[],
        };
        let multiscattering_entries = [
            uniform_entry(binding::PARAMS),
            texture_entry(binding::TRANSMITTANCE, false),
        ];
        let transmittance = TransmittanceStage::new(device, &params, &luts.transmittance.view);
        let multiscattering = Stage::new(
            device,
            lut_pipeline(
                "AtmospherePass multiple-scattering LUT",
                shaders::ATMOSPHERE_MULTISCATTERING_LUT,
                &multiscattering_entries,
                MULTISCATTERING_FORMAT,
            ),
            &[
                (binding::PARAMS, params.as_entire_binding()),
                (
                    binding::TRANSMITTANCE,
                    wgpu::BindingResource::TextureView(&luts.transmittance.view),
                ),
            ],
        );
        let irradiance_entries = [
            uniform_entry(binding::PARAMS),
            texture_entry(binding::TRANSMITTANCE, false),
            texture_entry(binding::MULTISCATTERING, true),
            sampler_entry(binding::SAMPLER),
        ];
        let view_entries = [
            uniform_entry(binding::PARAMS),
            uniform_entry(binding::VIEW),
            texture_entry(binding::TRANSMITTANCE, false),
            texture_entry(binding::MULTISCATTERING, true),
            sampler_entry(binding::SAMPLER),
            texture_entry(binding::IRRADIANCE, true),
            texture_entry(binding::SKY_VIEW, true),
        ];
        let view_resources = [
            (binding::PARAMS, params.as_entire_binding()),
            (binding::VIEW, view.as_entire_binding()),
            (
                binding::TRANSMITTANCE,
                wgpu::BindingResource::TextureView(&luts.transmittance.view),
            ),
            (
                binding::MULTISCATTERING,
                wgpu::BindingResource::TextureView(&luts.multiscattering.view),
            ),
            (binding::SAMPLER, wgpu::BindingResource::Sampler(&sampler)),
            (
                binding::IRRADIANCE,
                wgpu::BindingResource::TextureView(&luts.irradiance.view),
            ),
            (
                binding::SKY_VIEW,
                wgpu::BindingResource::TextureView(&luts.sky_view.view),
            ),
        ];
        let sky_view = Stage::new(
            device,
            lut_pipeline(
                "AtmospherePass sky-view LUT",
                shaders::ATMOSPHERE_SKY_VIEW_LUT,
                &view_entries[..6],
                SKY_VIEW_FORMAT,
            ),
            &view_resources[..6],
        );
        let irradiance = Stage::new(
            device,
            lut_pipeline(
                "AtmospherePass sky irradiance LUT",
                shaders::ATMOSPHERE_IRRADIANCE_LUT,
                &irradiance_entries,
                IRRADIANCE_FORMAT,
            ),
            &view_resources[..1]
                .iter()
                .chain(&view_resources[2..5])
                .cloned()
                .collect::<Vec<_>>(),
        );
        // One pipeline per sky mode, so no pixel pays for the branch it does not take (software
        // rasterizers run both sides of a branch they cannot prove uniform).
        let sky_stage = |mode: SkyMode| {
            Stage::new(
                device,
                PassPipeline {
                    owner: mode.owner(),
                    source: shaders::ATMOSPHERE_SKY,
                    entries: &view_entries,
                    color,
                    depth_stencil: Some(far_plane_depth_state(depth)),
                    vertex_buffers: &[],
                    primitive: wgpu::PrimitiveState::default(),
                    constants: &[("SKY_MODE", f64::from(mode as u32))],
                },
                &view_resources,
            )
        };
        let sky = [SkyMode::Lut, SkyMode::March, SkyMode::Blend].map(sky_stage);
        Self {
            luts,
            params,
            view,
            transmittance,
            multiscattering,
            irradiance,
            sky_view,
            sky,
            uploaded: None,
            medium_changed: Cell::new(false),
            sun_count: 0,
            method: SkyMethod::Lut,
            sky_mode: SkyMode::Lut,
        }
    }

    /// Uploads the medium (when it changed) and this frame's view of `sky` by `camera`.
    pub fn prepare(&mut self, queue: &wgpu::Queue, sky: &AtmosphereSky, camera: &Camera) {
        let params = AtmosphereParamsUniforms::new(&sky.atmosphere);
        if self.uploaded != Some(params) {
            queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
            self.uploaded = Some(params);
            self.medium_changed.set(true);
        }
        let mut view = AtmosphereViewUniforms::new(sky, camera);
        if self.method == SkyMethod::March {
            view.local_up[3] = 1.0;
        }
        self.sky_mode = match view.local_up[3] {
            b if b <= 0.0 => SkyMode::Lut,
            b if b >= 1.0 => SkyMode::March,
            _ => SkyMode::Blend,
        };
        self.sun_count = view.sun_count[0];
        queue.write_buffer(&self.view, 0, bytemuck::bytes_of(&view));
    }

    /// Chooses how the sky is computed from the next `prepare` on.
    pub fn set_method(&mut self, method: SkyMethod) {
        self.method = method;
    }

    /// Encodes the LUT rebuilds: the medium's LUTs when it changed, the sky-view tiles of the
    /// suns always (unless the method is [`SkyMethod::March`]).
    pub fn record_luts(&self, encoder: &mut wgpu::CommandEncoder) {
        if self.medium_changed.replace(false) {
            self.record_medium_luts(encoder);
        }
        if self.method == SkyMethod::Lut {
            self.record_sky_view_lut(encoder);
        }
    }

    /// Encodes the transmittance, multiple-scattering and sky-irradiance LUTs unconditionally.
    pub fn record_medium_luts(&self, encoder: &mut wgpu::CommandEncoder) {
        self.transmittance.record(encoder);
        self.multiscattering.render(
            encoder,
            "firmament AtmospherePass multiple-scattering LUT",
            &self.luts.multiscattering.view,
            None,
        );
        self.irradiance.render(
            encoder,
            "firmament AtmospherePass sky irradiance LUT",
            &self.luts.irradiance.view,
            None,
        );
    }

    /// Encodes the sky-view LUT tiles of this frame's suns.
    pub fn record_sky_view_lut(&self, encoder: &mut wgpu::CommandEncoder) {
        if self.sun_count > 0 {
            self.sky_view.render(
                encoder,
                "firmament AtmospherePass sky-view LUT",
                &self.luts.sky_view.view,
                Some(SKY_VIEW_TILE.0 * self.sun_count.min(MAX_SUNS as u32)),
            );
        }
    }

    /// Draws the sky into a render pass the caller already began (after `record_luts` was
    /// encoded earlier in the same submission).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        let sky = &self.sky[self.sky_mode as usize];
        pass.set_pipeline(&sky.pipeline);
        pass.set_bind_group(0, &sky.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }

    /// Draws the sky into `color` (loaded, not cleared) behind what `depth` already holds.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView, depth: &wgpu::TextureView) {
        let mut pass = begin_load_pass(encoder, "firmament AtmospherePass sky", color, depth);
        self.draw(&mut pass);
    }

    /// The LUTs (for tests and tools).
    pub fn luts(&self) -> &AtmosphereLuts {
        &self.luts
    }
}
