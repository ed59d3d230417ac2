//! The physically based atmosphere on the GPU: Hillaire 2020's LUT pipeline ("A Scalable and
//! Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020) around an ellipsoid
//! planet, with up to [`MAX_SUNS`] suns.
//!
//! Per frame, [`AtmospherePass::record_luts`] renders
//! 1. the transmittance LUT (Bruneton 2017's parameterisation; a compute pass) and
//! 2. the multiple-scattering LUT and, from the same rays,
//! 3. the ground's sky-irradiance LUT — these three only when the medium changed, into a set of
//!    their own copied into the one the sky reads when complete: in the same frame, or with
//!    [`AtmospherePass::set_incremental_rebuild`] one step per frame ([`MEDIUM_BUILD_STEPS`]) while
//!    the sky keeps the last complete set and its medium —, then
//! 4. the sky-view LUT, one tile per sun, at the camera, and
//! 5. the light the sky and the suns give at the camera, for users' own materials (each sun's
//!    direction and colour after the atmosphere, the sky's irradiance as spherical harmonics:
//!    [`AtmospherePass::sky_lighting_buffer`], read by `shaders::FIRMAMENT_LIGHTING_WGSL`);
//!
//! [`AtmospherePass::draw`] draws the sky, the lit ground and the sun discs behind whatever
//! the depth buffer holds, and [`AtmospherePass::record_aerial_perspective`] builds the
//! aerial-perspective volume at the camera and lays the air between the camera and that geometry
//! over it (only callers with geometry pay for it). Above the atmosphere each pixel marches its own ray instead of reading
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

mod aerial_perspective;
mod body_air_light;
mod body_maps;
mod clouds;
pub mod luts;
mod multiscattering;
mod rebuild;
mod ring_light;
mod sky_lighting;
mod stages;
mod surface;
mod table_layers;

use firmament_core::frame::{AtmosphereSky, MAX_SUNS};
use firmament_core::{Camera, DepthConvention};

use crate::gpu_types::medium::is_thick_air;
use crate::gpu_types::{AtmosphereParamsUniforms, AtmosphereViewUniforms, codes};
use crate::passes::common::SkyTarget;
use crate::passes::common::{PassPipeline, begin_load_pass, far_depth_constant, far_plane_depth_state, uniform_buffer};
use crate::shaders;

pub use aerial_perspective::{AerialPerspectiveBindings, aerial_perspective_layout_entries};
use aerial_perspective::{AerialPerspectiveResources, AerialPerspectiveStages};
use body_air_light::BodyAirLight;
use ring_light::RingLight;
use body_maps::BodyMaps;
use clouds::CloudStages;
pub use luts::AtmosphereLuts;
use luts::{SKY_VIEW_FORMAT, SKY_VIEW_TILE, TRANSMITTANCE_FORMAT};
pub use multiscattering::MULTISCATTERING_ORDERS;
use multiscattering::{MultiscatteringStages, Tail};
pub use rebuild::MEDIUM_BUILD_STEPS;
use luts::MediumLuts;
use rebuild::{BuildStep, Rebuild};
pub use sky_lighting::sky_lighting_layout_entry;
use sky_lighting::{SkyLightingResources, SkyLightingStage};
use surface::SurfaceTexture;
use stages::{
    ComputeStage, Stage, binding, array_texture_entry, sampler_entry, storage_entry, texture_entry,
    uniform_entry,
};

/// How the sky pass finds each pixel's scattered light inside the atmosphere.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SkyMethod {
    /// From the sky-view LUT (the fast path; the per-pixel march above the atmosphere).
    #[default]
    Lut,
    /// A ray march per pixel everywhere: the brute-force baseline for benchmarks and checks.
    March,
}

/// The sky pass's variants (the `SKY_MODE` override of `atmosphere/sky.wgsl`), in the order of
/// [`AtmospherePass`]'s sky pipelines.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SkyMode {
    Lut,
    March,
    Blend,
}

impl SkyMode {
    /// Its `SKY_MODE`.
    fn code(self) -> u32 {
        match self {
            Self::Lut => codes::SKY_MODE_LUT,
            Self::March => codes::SKY_MODE_MARCH,
            Self::Blend => codes::SKY_MODE_BLEND,
        }
    }

    fn owner(self) -> &'static str {
        match self {
            Self::Lut => "AtmospherePass sky (sky-view LUT)",
            Self::March => "AtmospherePass sky (ray march)",
            Self::Blend => "AtmospherePass sky (blend)",
        }
    }

    fn compute_owner(self) -> &'static str {
        match self {
            Self::Lut => "AtmospherePass compute sky (sky-view LUT)",
            Self::March => "AtmospherePass compute sky (ray march)",
            Self::Blend => "AtmospherePass compute sky (blend)",
        }
    }
}

/// The atmosphere: LUTs and the sky they feed. Build once; `prepare` every frame.
#[derive(Debug)]
pub struct AtmospherePass {
    luts: AtmosphereLuts,
    /// The medium the live LUTs hold (what every stage but the builds reads).
    params: wgpu::Buffer,
    /// The set the medium's LUTs are built into, and the medium being built.
    build: MediumLuts,
    view: wgpu::Buffer,
    transmittance: ComputeStage,
    multiscattering: MultiscatteringStages,
    sky_view: ComputeStage,
    aerial: AerialPerspectiveStages,
    clouds: CloudStages,
    lighting: SkyLightingStage,
    /// The planet's surface map, read by every stage that draws the ground.
    surface: SurfaceTexture,
    /// The bodies' albedo maps, read by the sky stages.
    body_maps: BodyMaps,
    body_air_light: BodyAirLight,
    /// The rings' light on the ground, read by every stage that draws the ground.
    ring_light: RingLight,
    sampler: wgpu::Sampler,
    /// The sky pipelines, indexed by [`SkyMode`].
    sky: [Stage; 3],
    /// The sky as compute passes, one per mode, once a target is bound
    /// ([`bind_sky_target`](Self::bind_sky_target)); and that target's size (pixels).
    sky_compute: Option<([ComputeStage; 3], (u32, u32))>,
    /// Which sky pipeline this frame uses.
    sky_mode: SkyMode,
    /// The medium LUTs' build: in progress, planned, counted.
    rebuild: Rebuild,
    sun_count: u32,
    method: SkyMethod,
    /// The depth buffer's convention the pipelines were built for.
    convention: DepthConvention,
    /// The colour format the draws into a caller's target were built for.
    color: wgpu::TextureFormat,
}

impl AtmospherePass {
    /// Builds the pipelines for an HDR target of [`HDR_FORMAT`](crate::HDR_FORMAT) and depth of [`DEPTH_FORMAT`](crate::DEPTH_FORMAT).
    pub fn new(device: &wgpu::Device) -> Self {
        Self::for_target(device, SkyTarget::OWN)
    }

    /// Builds the pipelines for `target`'s colour and depth formats and depth convention: the sky
    /// at its far plane, tested against it, and aerial perspective turning its depths into
    /// distances with the matching projection.
    pub fn for_target(device: &wgpu::Device, target: SkyTarget) -> Self {
        let SkyTarget {
            color,
            depth,
            convention,
        } = target;
        let luts = AtmosphereLuts::new(device);
        let build = MediumLuts::new(device);
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
        let transmittance = ComputeStage::new(
            device,
            "AtmospherePass transmittance LUT",
            &shaders::ATMOSPHERE_TRANSMITTANCE_LUT,
            &[
                uniform_entry(binding::PARAMS),
                storage_entry(binding::TRANSMITTANCE_OUT, TRANSMITTANCE_FORMAT),
            ],
            &[
                (binding::PARAMS, build.params.as_entire_binding()),
                (
                    binding::TRANSMITTANCE_OUT,
                    wgpu::BindingResource::TextureView(&build.transmittance.view),
                ),
            ],
        );
        let multiscattering = MultiscatteringStages::new(device, &build, &sampler);
        let view_entries = view_entries();
        let surface = SurfaceTexture::new(device);
        let view_resources = view_resources(&params, &view, &luts, &sampler, &surface);
        // The view resources that the bindings in `entries` name.
        let resources_for = |entries: &[wgpu::BindGroupLayoutEntry]| -> Vec<(u32, wgpu::BindingResource<'_>)> {
            view_resources
                .iter()
                .filter(|(b, _)| entries.iter().any(|e| e.binding == *b))
                .cloned()
                .collect()
        };
        let mut sky_view_entries: Vec<_> = view_entries
            .iter()
            .filter(|e| e.binding != binding::SKY_VIEW)
            .copied()
            .collect();
        let mut sky_view_resources = resources_for(&sky_view_entries);
        let ring_light = RingLight::new(device);
        sky_view_entries.push(RingLight::entry());
        sky_view_resources.push(ring_light.resource());
        sky_view_entries.push(storage_entry(binding::SKY_VIEW_OUT, SKY_VIEW_FORMAT));
        sky_view_resources.push((
            binding::SKY_VIEW_OUT,
            wgpu::BindingResource::TextureView(&luts.sky_view.view),
        ));
        let sky_view = ComputeStage::new(
            device,
            "AtmospherePass sky-view LUT",
            &shaders::ATMOSPHERE_SKY_VIEW_LUT,
            &sky_view_entries,
            &sky_view_resources,
        );
        // One pipeline per sky mode, so no pixel pays for the branch it does not take (software
        // rasterizers run both sides of a branch they cannot prove uniform).
        let body_maps = BodyMaps::new(device);
        let body_air_light = BodyAirLight::new(device);
        let sky_entries = [
            view_entries.as_slice(),
            &[BodyMaps::entry(), BodyAirLight::entry(), RingLight::entry()],
        ]
        .concat();
        let mut sky_resources = view_resources.clone();
        sky_resources.push(body_maps.resource());
        sky_resources.push(body_air_light.resource());
        sky_resources.push(ring_light.resource());
        let sky_stage = |mode: SkyMode| {
            Stage::new(
                device,
                PassPipeline {
                    owner: mode.owner(),
                    source: &shaders::ATMOSPHERE_SKY,
                    entries: &sky_entries,
                    color,
                    depth_stencil: Some(far_plane_depth_state(depth, convention)),
                    vertex_buffers: &[],
                    primitive: wgpu::PrimitiveState::default(),
                    constants: &[("SKY_MODE", f64::from(mode.code())), far_depth_constant(convention)],
                },
                &sky_resources,
            )
        };
        let sky = [SkyMode::Lut, SkyMode::March, SkyMode::Blend].map(sky_stage);
        let aerial = AerialPerspectiveStages::new(
            device,
            &AerialPerspectiveResources {
                params: &params,
                view: &view,
                luts: &luts,
                sampler: &sampler,
                surface: &surface,
            },
            color,
        );
        let lighting = SkyLightingStage::new(
            device,
            &SkyLightingResources {
                params: &params,
                view: &view,
                luts: &luts,
                sampler: &sampler,
                surface: &surface,
                ring_light: &ring_light,
            },
        );
        Self {
            aerial,
            clouds: CloudStages::new(device),
            lighting,
            surface,
            body_maps,
            body_air_light,
            ring_light,
            sampler,
            luts,
            params,
            build,
            view,
            transmittance,
            multiscattering,
            sky_view,
            sky,
            sky_compute: None,
            rebuild: Rebuild::default(),
            sun_count: 0,
            method: SkyMethod::Lut,
            sky_mode: SkyMode::Lut,
            convention,
            color,
        }
    }

    /// Uploads the medium (when it changed, starting a build of its LUTs) and this frame's view
    /// of `sky` by `camera` — of the last complete medium's while an incremental build is under
    /// way (with `sky`'s suns and the planet's pose), so the sky stays whole.
    pub fn prepare(&mut self, queue: &wgpu::Queue, sky: &AtmosphereSky, camera: &Camera) {
        self.clouds.prepare(queue, sky);
        self.surface.prepare(queue, sky.surface.as_ref());
        self.body_maps.prepare(queue, sky);
        self.body_air_light.prepare(queue, sky);
        self.ring_light.prepare(queue, sky);
        if !self.rebuild.is_newest(&sky.atmosphere) {
            let planet = &sky.atmosphere.planet;
            let thick = is_thick_air(&sky.atmosphere.medium, planet.atmosphere_height);
            let params = AtmosphereParamsUniforms::with_thickness(&sky.atmosphere, thick);
            queue.write_buffer(&self.build.params, 0, bytemuck::bytes_of(&params));
            self.rebuild.start(sky.atmosphere.clone(), Tail::for_thickness(thick));
        }
        let live_sky;
        let sky = match self.rebuild.plan() {
            Some(live) => {
                let mut atmosphere = live.clone();
                atmosphere.planet.center = sky.atmosphere.planet.center;
                atmosphere.planet.orientation = sky.atmosphere.planet.orientation;
                // For the view's uniforms only: the clouds were uploaded above.
                live_sky = AtmosphereSky {
                    atmosphere,
                    suns: sky.suns.clone(),
                    clouds: Vec::new(),
                    eclipsers: Vec::new(),
                    bodies: Vec::new(),
                    rings: None,
                    surface: sky.surface.clone(),
                };
                &live_sky
            }
            None => sky,
        };
        let mut view = AtmosphereViewUniforms::new(sky, camera).for_depth_convention(camera, self.convention);
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
        self.lighting.prepare(queue, sky, camera);
    }

    /// Builds the medium's LUTs over successive frames, one of [`MEDIUM_BUILD_STEPS`] steps per
    /// `record_luts`, drawing meanwhile from the last complete set (for interactive callers,
    /// whose frames would otherwise stall for the whole build); off by default: each build in
    /// the frame of the change. The first build is always whole.
    pub fn set_incremental_rebuild(&mut self, incremental: bool) {
        self.rebuild.incremental = incremental;
    }

    /// How many complete builds of the medium's LUTs were encoded: one per medium change (or
    /// per [`record_medium_luts`](Self::record_medium_luts)), none for a new sun, camera or time.
    pub fn medium_builds(&self) -> u64 {
        self.rebuild.builds.get()
    }

    /// Whether a build of the medium's LUTs is under way (the sky draws from the previous set).
    pub fn rebuilding(&self) -> bool {
        self.rebuild.in_progress()
    }

    /// Chooses how the sky is computed from the next `prepare` on.
    pub fn set_method(&mut self, method: SkyMethod) {
        self.method = method;
    }

    /// Encodes the LUT rebuilds: the medium's LUTs when it changed, then always the sky-view
    /// tiles of the suns and the sky lighting at the camera that reads them
    /// ([`sky_lighting_buffer`](Self::sky_lighting_buffer); with [`SkyMethod::March`] too, though
    /// the sky pass then does not read the tiles).
    pub fn record_luts(&self, encoder: &mut wgpu::CommandEncoder) {
        if let Some(steps) = self.rebuild.take_planned() {
            for step in steps {
                self.record_build_step(encoder, BuildStep::of(step));
            }
        }
        self.record_sky_view_lut(encoder);
        self.record_sky_lighting(encoder);
    }

    /// Encodes the sky lighting at the camera into
    /// [`sky_lighting_buffer`](Self::sky_lighting_buffer) (part of
    /// [`record_luts`](Self::record_luts), after the sky-view LUT it reads; on its own for
    /// benchmarks).
    pub fn record_sky_lighting(&self, encoder: &mut wgpu::CommandEncoder) {
        self.lighting.record(encoder);
    }

    /// The per-frame lighting for users' own shaders, a
    /// [`SkyLightingGpu`](crate::gpu_types::SkyLightingGpu) (416 bytes): each sun's world
    /// direction and colour after the atmosphere at the camera, and the sky's radiance as
    /// spherical harmonics of bands 0–2 (linear sRGB, Y in cd/m²; irradiance in lux). Written by
    /// [`record_luts`](Self::record_luts) each frame; bind it as a uniform buffer with
    /// [`sky_lighting_layout_entry`] and read it with `shaders::FIRMAMENT_LIGHTING_WGSL`. Usable
    /// as `UNIFORM`, `STORAGE` and `COPY_SRC`.
    pub fn sky_lighting_buffer(&self) -> &wgpu::Buffer {
        self.lighting.buffer()
    }

    /// Encodes the aerial-perspective volume at this frame's camera, after
    /// [`record_luts`](Self::record_luts) (part of
    /// [`record_aerial_perspective`](Self::record_aerial_perspective); on its own for users'
    /// shaders that read it through [`aerial_perspective_bindings`](Self::aerial_perspective_bindings),
    /// and for benchmarks).
    pub fn record_aerial_perspective_volume(&self, encoder: &mut wgpu::CommandEncoder) {
        self.aerial.record_volume(encoder);
    }

    /// The aerial-perspective volume and what its lookup needs, for users' own shaders
    /// (`shaders::FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`): bind
    /// [`AerialPerspectiveBindings::bind_group_entries`] in a layout made with
    /// [`aerial_perspective_layout_entries`]. The volume holds this frame's air once
    /// [`record_aerial_perspective_volume`](Self::record_aerial_perspective_volume) (or
    /// [`record_aerial_perspective`](Self::record_aerial_perspective)) was encoded after
    /// [`record_luts`](Self::record_luts); encode your draws after it. The objects are the pass's
    /// for its whole life, so one bind group serves every frame.
    pub fn aerial_perspective_bindings(&self) -> AerialPerspectiveBindings<'_> {
        AerialPerspectiveBindings {
            view: &self.view,
            params: &self.params,
            scattering: &self.luts.aerial_scattering.view,
            transmittance: &self.luts.aerial_transmittance.view,
            sampler: &self.sampler,
        }
    }

    /// Makes `depth` the depth buffer [`record_aerial_perspective`](Self::record_aerial_perspective)
    /// reads: a reversed-Z depth view (sample type depth) of the colour target's size, drawn with
    /// this frame's camera. Call again whenever the depth view changes; it builds two bind groups.
    pub fn bind_depth(&mut self, device: &wgpu::Device, depth: &wgpu::TextureView) {
        let resources = AerialPerspectiveResources {
            params: &self.params,
            view: &self.view,
            luts: &self.luts,
            sampler: &self.sampler,
            surface: &self.surface,
        };
        self.aerial.bind_depth(device, &resources, depth);
    }

    /// Applies aerial perspective to every pixel of `color` the bound depth buffer covers (not
    /// the far plane): builds the volume at this frame's camera (after `record_luts`, whose
    /// medium LUTs it reads), then `colour · T + S`. Draw the geometry first; the sky may be drawn
    /// before or after (it is left alone).
    pub fn record_aerial_perspective(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView) {
        self.aerial.record_volume(encoder);
        self.aerial.record_apply(encoder, color);
    }

    /// The application alone, from the volume last encoded (for benchmarks).
    pub fn record_aerial_perspective_apply(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
    ) {
        self.aerial.record_apply(encoder, color);
    }

    /// Encodes the transmittance, multiple-scattering and sky-irradiance LUTs of the medium last
    /// prepared unconditionally, whole (for benchmarks and tools).
    pub fn record_medium_luts(&self, encoder: &mut wgpu::CommandEncoder) {
        for step in 0..MEDIUM_BUILD_STEPS {
            self.record_build_step(encoder, BuildStep::of(step));
        }
    }

    /// Encodes a whole build of the medium's LUTs (as [`record_medium_luts`](Self::record_medium_luts))
    /// whose multiple-scattering LUTs hold exactly the light of orders 1 to `orders` (none for 0),
    /// without the geometric tail of the later ones: for measuring the radiance by order, and the
    /// tail against more orders marched. Each order costs what one of a normal build does.
    pub fn record_medium_luts_to_order(&self, encoder: &mut wgpu::CommandEncoder, orders: u32) {
        self.record_build_step(encoder, BuildStep::Transmittance);
        for order in 1..=orders {
            let tail = self.rebuild.tail;
            self.multiscattering.record_order(encoder, &self.build, order == 1, tail);
        }
        self.multiscattering.record_sum(encoder, &self.build, Tail::None);
        self.record_swap(encoder);
    }

    /// Encodes step `step` (0 to [`MEDIUM_BUILD_STEPS`] − 1) of a build of the medium's LUTs
    /// alone, as an incremental rebuild spends one frame on it (for benchmarks and tools; steps
    /// read what the step before wrote).
    pub fn record_medium_lut_step(&self, encoder: &mut wgpu::CommandEncoder, step: u32) {
        self.record_build_step(encoder, BuildStep::of(step.min(MEDIUM_BUILD_STEPS - 1)));
    }

    /// Encodes one step of a build of the medium's LUTs.
    fn record_build_step(&self, encoder: &mut wgpu::CommandEncoder, step: BuildStep) {
        match step {
            BuildStep::Transmittance => {
                let (width, height) = luts::TRANSMITTANCE_SIZE;
                // 32 texels per workgroup (transmittance_lut.wgsl).
                self.transmittance.dispatch(encoder, ((width * height).div_ceil(32), 1, 1));
                self.multiscattering.record_start(encoder);
            }
            BuildStep::Order(order) => {
                let tail = self.rebuild.tail;
                self.multiscattering.record_order(encoder, &self.build, order == 1, tail);
                if order == MULTISCATTERING_ORDERS {
                    self.multiscattering.record_sum(encoder, &self.build, self.rebuild.tail);
                    self.record_swap(encoder);
                }
            }
        }
    }

    /// Encodes the copy of the finished build and its medium into the set the sky reads.
    fn record_swap(&self, encoder: &mut wgpu::CommandEncoder) {
        self.build.copy_into(encoder, &self.luts, &self.params);
        self.rebuild.builds.set(self.rebuild.builds.get() + 1);
    }

    /// Encodes the sky-view LUT tiles of this frame's suns.
    pub fn record_sky_view_lut(&self, encoder: &mut wgpu::CommandEncoder) {
        if self.sun_count > 0 {
            let (width, height) = SKY_VIEW_TILE;
            let suns = self.sun_count.min(MAX_SUNS as u32);
            self.sky_view
                .dispatch(encoder, ((width * suns).div_ceil(8), height.div_ceil(8), 1));
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

    /// Binds the renderer's own target for the compute passes, [`record_sky`](Self::record_sky)
    /// and [`record_aerial_perspective_on_target`](Self::record_aerial_perspective_on_target):
    /// `color` an [`HDR_FORMAT`] texture with `STORAGE_BINDING | TEXTURE_BINDING | COPY_DST`
    /// usage, `depth` a view of the depth buffer of its size the sky stays behind (of this pass's
    /// convention). Rebinding after a resize keeps the pipelines.
    ///
    /// [`HDR_FORMAT`]: crate::targets::HDR_FORMAT
    pub fn bind_sky_target(&mut self, device: &wgpu::Device, color: &wgpu::Texture, depth: &wgpu::TextureView) {
        let size = (color.width(), color.height());
        let aerial_resources = AerialPerspectiveResources {
            params: &self.params,
            view: &self.view,
            luts: &self.luts,
            sampler: &self.sampler,
            surface: &self.surface,
        };
        self.aerial.bind_target(device, &aerial_resources, color, depth);
        self.clouds.bind_target(device, &aerial_resources, color, depth);
        let color = &color.create_view(&wgpu::TextureViewDescriptor::default());
        let mut resources = view_resources(&self.params, &self.view, &self.luts, &self.sampler, &self.surface);
        resources.push((binding::SCENE_DEPTH, wgpu::BindingResource::TextureView(depth)));
        resources.push((binding::SKY_OUT, wgpu::BindingResource::TextureView(color)));
        resources.push(self.body_maps.resource());
        resources.push(self.body_air_light.resource());
        resources.push(self.ring_light.resource());
        match &mut self.sky_compute {
            Some((stages, bound)) => {
                for stage in stages.iter_mut() {
                    stage.rebind(device, &resources);
                }
                *bound = size;
            }
            None => {
                let mut entries = view_entries();
                entries.push(texture_entry(binding::SCENE_DEPTH, false));
                entries.push(storage_entry(binding::SKY_OUT, crate::targets::HDR_FORMAT));
                entries.push(BodyMaps::entry());
                entries.push(BodyAirLight::entry());
                entries.push(RingLight::entry());
                let stages = [SkyMode::Lut, SkyMode::March, SkyMode::Blend].map(|mode| {
                    ComputeStage::with_constants(
                        device,
                        mode.compute_owner(),
                        &shaders::ATMOSPHERE_SKY,
                        &entries,
                        &resources,
                        &[("SKY_MODE", f64::from(mode.code()))],
                    )
                });
                self.sky_compute = Some((stages, size));
            }
        }
    }

    /// Encodes the aerial-perspective volume and its application over the target bound by
    /// [`bind_sky_target`](Self::bind_sky_target) as compute passes (what
    /// [`record_aerial_perspective`](Self::record_aerial_perspective) draws into a caller's
    /// target). Returns false, encoding nothing, when no target is bound.
    pub fn record_aerial_perspective_on_target(&self, encoder: &mut wgpu::CommandEncoder) -> bool {
        self.record_aerial_perspective_with_shafts(encoder, None)
    }

    /// [`record_aerial_perspective_on_target`](Self::record_aerial_perspective_on_target) with
    /// the light shafts of the shadow maps `shadows` binds (the object pass's, laid out as
    /// `shaders/shadow/sampling.wgsl`'s group 1); without them when `None`.
    pub(crate) fn record_aerial_perspective_with_shafts(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        shadows: Option<&wgpu::BindGroup>,
    ) -> bool {
        if !self.aerial.bound_to_target() {
            return false;
        }
        self.aerial.record_volume(encoder);
        self.aerial.record_on_target(encoder, shadows)
    }

    /// The application alone over the bound target, from the volume last encoded (for
    /// benchmarks); false when no target is bound.
    pub fn record_aerial_perspective_apply_on_target(&self, encoder: &mut wgpu::CommandEncoder) -> bool {
        self.aerial.record_on_target(encoder, None)
    }

    /// Encodes the sky as a compute pass into the target bound by
    /// [`bind_sky_target`](Self::bind_sky_target), where its depth buffer holds the far plane
    /// (after `record_luts`, like [`record`](Self::record)). Returns false, encoding nothing,
    /// when no target is bound.
    pub fn record_sky(&self, encoder: &mut wgpu::CommandEncoder) -> bool {
        let Some((stages, (width, height))) = &self.sky_compute else {
            return false;
        };
        stages[self.sky_mode as usize].dispatch(encoder, (width.div_ceil(8), height.div_ceil(8), 1));
        true
    }

    /// Whether the sky last prepared has cloud layers.
    pub fn has_clouds(&self) -> bool {
        self.clouds.any()
    }

    /// Encodes the clouds' shadow map of the sky last prepared ahead of the march, for the objects
    /// drawn before it (`record_clouds_on_target` then does not encode it again); nothing
    /// without clouds.
    pub(crate) fn record_cloud_shadow_map(&self, encoder: &mut wgpu::CommandEncoder) {
        self.clouds.record_shadow_map_ahead(encoder);
    }

    /// The clouds' shadow map (`shaders/clouds/shadow.wgsl`) the object pass reads.
    pub(crate) fn cloud_shadow_map_view(&self) -> &wgpu::TextureView {
        self.clouds.shadow_map_view()
    }

    /// Binds a caller's depth buffer `depth` (of its colour target's size, this pass's depth
    /// convention) for [`record_clouds_into`](Self::record_clouds_into), when the sky last
    /// prepared has clouds. Call after `prepare`, whenever the depth view changes.
    pub fn bind_clouds_into(&mut self, device: &wgpu::Device, depth: &wgpu::TextureView) {
        let resources = AerialPerspectiveResources {
            params: &self.params,
            view: &self.view,
            luts: &self.luts,
            sampler: &self.sampler,
            surface: &self.surface,
        };
        self.clouds.bind_caller(device, &resources, depth, self.color);
    }

    /// Encodes the cloud layers over a caller's `color` target (of the format this pass was built
    /// for; loaded, never cleared), in front of what the depth buffer bound by
    /// [`bind_clouds_into`](Self::bind_clouds_into) holds: after the sky, the geometry and its
    /// aerial perspective, and after the aerial-perspective volume, which lights the air in
    /// front of the clouds. Returns false, encoding nothing, without clouds or a bound depth
    /// buffer.
    pub fn record_clouds_into(&self, encoder: &mut wgpu::CommandEncoder, color: &wgpu::TextureView) -> bool {
        self.clouds.record_into(encoder, color)
    }

    /// Encodes the cloud layers over the target bound by
    /// [`bind_sky_target`](Self::bind_sky_target), after everything else the image holds in the
    /// air (the sky, the objects, their aerial perspective) and after the aerial-perspective
    /// volume, which lights the air in front of them. Returns false, encoding nothing, without
    /// clouds or a bound target.
    pub fn record_clouds_on_target(&self, encoder: &mut wgpu::CommandEncoder) -> bool {
        self.clouds.record_on_target(encoder)
    }

    /// The LUTs (for tests and tools).
    pub fn luts(&self) -> &AtmosphereLuts {
        &self.luts
    }
}

/// The layout entries of every stage that looks through the camera: the medium, the view, the
/// LUTs and their sampler, the surface map and its sampler.
fn view_entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut entries = vec![
        uniform_entry(binding::PARAMS),
        uniform_entry(binding::VIEW),
        texture_entry(binding::TRANSMITTANCE, false),
        sampler_entry(binding::SAMPLER),
        texture_entry(binding::IRRADIANCE, true),
        texture_entry(binding::SKY_VIEW, true),
    ];
    entries.push(array_texture_entry(binding::MULTISCATTERING));
    entries.extend(SurfaceTexture::entries());
    entries
}

/// The resources of [`view_entries`].
fn view_resources<'a>(
    params: &'a wgpu::Buffer,
    view: &'a wgpu::Buffer,
    luts: &'a AtmosphereLuts,
    sampler: &'a wgpu::Sampler,
    surface: &'a SurfaceTexture,
) -> Vec<(u32, wgpu::BindingResource<'a>)> {
    let mut resources = vec![
        (binding::PARAMS, params.as_entire_binding()),
        (binding::VIEW, view.as_entire_binding()),
        (
            binding::TRANSMITTANCE,
            wgpu::BindingResource::TextureView(&luts.transmittance.view),
        ),
        (binding::SAMPLER, wgpu::BindingResource::Sampler(sampler)),
        (
            binding::IRRADIANCE,
            wgpu::BindingResource::TextureView(&luts.irradiance.view),
        ),
        (
            binding::SKY_VIEW,
            wgpu::BindingResource::TextureView(&luts.sky_view.view),
        ),
    ];
    resources.push((
            binding::MULTISCATTERING,
            wgpu::BindingResource::TextureView(&luts.multiscattering.view),
        ));
    resources.extend(surface.resources());
    resources
}
