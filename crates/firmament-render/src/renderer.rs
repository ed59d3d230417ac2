//! The frame renderer: the objects' sun shadows, objects, then the sky behind them and the stars and the Moon added over
//! it, into HDR targets; aerial perspective over the objects when the sky is an atmosphere; lens
//! flares over everything; the camera's auto-exposure meter and bloom; the output pass → the
//! caller's view.

use std::collections::HashMap;

use firmament_core::Frame;
use firmament_core::frame::Sky;

use crate::context::GpuContext;
use crate::error::RenderError;
use crate::pass_timing::{
    FrameTiming, PHASE_AERIAL_PERSPECTIVE, PHASE_CLOUDS, PHASE_FLARES, PHASE_LUTS, PHASE_SHADOWS,
    PHASE_SKY_AND_OBJECTS, PHASE_TONEMAP, PassTimer, PassTimes,
};
use crate::passes::SkyTarget;
use crate::passes::atmosphere::AerialPerspectiveBindings;
use crate::passes::camera::CameraPasses;
use crate::passes::{
    AtmospherePass, EmpiricalSkyPass, ExposurePass, FlarePass, GradientSkyPass, NightSkyPass, ObjectPass, TonemapPass,
    begin_clear_pass, begin_load_pass,
};
use crate::targets::{DEPTH_CLEAR, EmbedTarget, FrameTargets};

/// The sky passes a frame can use.
#[derive(Debug, Clone, Copy, PartialEq)]
enum SkyKind {
    Gradient,
    Atmosphere,
    Empirical,
    /// A clear colour (linear, as given).
    Clear(wgpu::Color),
}

/// The passes that draw the sky, the night sky, aerial perspective and the flares into one kind
/// of target: a colour format, a depth format and its convention.
#[derive(Debug)]
struct SkyPasses {
    gradient: GradientSkyPass,
    atmosphere: AtmospherePass,
    empirical: EmpiricalSkyPass,
    night: NightSkyPass,
    flares: FlarePass,
}

impl SkyPasses {
    fn new(ctx: &GpuContext, key: SkyTarget, interval: Option<f64>) -> Self {
        let device = &ctx.device;
        let mut flares = FlarePass::with_format(device, key.color);
        flares.set_depth_convention(key.convention);
        flares.set_interval(interval);
        Self {
            gradient: GradientSkyPass::for_target(device, key),
            atmosphere: AtmospherePass::for_target(device, key),
            empirical: EmpiricalSkyPass::for_target(device, key),
            night: NightSkyPass::for_target(device, key),
            flares,
        }
    }

    /// Binds the depth buffer the aerial perspective and the flares read.
    fn bind_depth(&mut self, device: &wgpu::Device, depth: &wgpu::TextureView, (width, height): (u32, u32)) {
        self.atmosphere.bind_depth(device, depth);
        self.flares.bind_depth(device, depth, width, height);
    }

    /// Uploads the sky, the night sky and the flares of `frame` seen by `camera`; which sky.
    fn prepare(
        &mut self,
        ctx: &GpuContext,
        frame: &Frame,
        camera: &firmament_core::Camera,
        size: (u32, u32),
    ) -> SkyKind {
        let sky = match &frame.sky {
            Sky::Gradient(sky) => {
                self.gradient.prepare(&ctx.queue, sky, camera);
                SkyKind::Gradient
            }
            Sky::Atmosphere(sky) => {
                self.atmosphere.prepare(&ctx.queue, sky, camera);
                SkyKind::Atmosphere
            }
            Sky::Empirical(sky) => {
                self.empirical.prepare(&ctx.queue, sky, camera);
                SkyKind::Empirical
            }
            Sky::Clear(c) => SkyKind::Clear(wgpu::Color {
                r: c.r,
                g: c.g,
                b: c.b,
                a: 1.0,
            }),
        };
        self.night.prepare(&ctx.device, &ctx.queue, &frame.night, camera, size);
        let planet = match &frame.sky {
            Sky::Atmosphere(sky) => Some(&sky.atmosphere.planet),
            _ => None,
        };
        self.flares.prepare(
            &ctx.device,
            &ctx.queue,
            &frame.flares,
            camera,
            frame.display.exposure.multiplier,
            planet,
        );
        sky
    }

    /// Draws the sky of kind `sky` (not a clear colour) into a pass with the depth attachment.
    fn draw_sky(&self, pass: &mut wgpu::RenderPass<'_>, sky: SkyKind) {
        match sky {
            SkyKind::Gradient => self.gradient.draw(pass),
            SkyKind::Atmosphere => self.atmosphere.draw(pass),
            SkyKind::Empirical => self.empirical.draw(pass),
            SkyKind::Clear(_) => {}
        }
    }
}

/// Renders [`Frame`]s into any texture view of the output format it was built for
/// ([`prepare`](Self::prepare), [`record`](Self::record)), or into a frame of the caller's own —
/// an HDR colour target and the depth buffer holding the caller's geometry
/// ([`prepare_into`](Self::prepare_into), [`record_into`](Self::record_into)).
#[derive(Debug)]
pub struct Renderer {
    /// The sky passes for the renderer's own targets.
    own: SkyPasses,
    /// The sky passes for callers' targets, built on first use for each kind and kept.
    embedded: HashMap<SkyTarget, SkyPasses>,
    /// The caller's target kind of the last `prepare_into`, `None` after a `prepare`.
    active: Option<SkyTarget>,
    /// Which sky the last `prepare` chose.
    sky: SkyKind,
    objects: ObjectPass,
    /// The camera: auto-exposure's meter and bloom, run on the frame's HDR image when its
    /// display asks.
    camera: CameraPasses,
    tonemap: TonemapPass,
    /// The output passes for callers' output views, one per format, built on first use.
    embedded_tonemaps: HashMap<wgpu::TextureFormat, TonemapPass>,
    /// The output format of the last `prepare_into`'s target, if it had an output view.
    embedded_output: Option<wgpu::TextureFormat>,
    /// Set by [`Renderer::record_lighting`]: the next `record` or `record_into` skips the LUTs.
    lighting_recorded: std::cell::Cell<bool>,
    targets: Option<FrameTargets>,
    /// Build the aerial-perspective volume in every atmosphere frame, objects or not
    /// ([`Renderer::set_aerial_perspective_for_users`]).
    aerial_volume_wanted: bool,
    /// The flares' frame interval ([`Renderer::set_flare_interval`]).
    flare_interval: Option<f64>,
    /// The size of the caller's target at the last `prepare_into`.
    embedded_size: (u32, u32),
    /// Per-pass GPU timing, when on ([`Renderer::enable_pass_timing`]).
    pass_timer: Option<PassTimer>,
    /// Why `new`'s output format cannot be drawn into, if it cannot (`prepare` refuses it).
    output_format_error: Option<String>,
    /// The device's features, for `record_into`'s check of its target.
    features: wgpu::Features,
}

impl Renderer {
    /// Builds every pipeline once, for output views of `output_format`. A format the output pass
    /// cannot draw into ([`check_output_format`](crate::targets::check_output_format)) is
    /// refused by every [`prepare`](Self::prepare) with [`RenderError::OutputFormat`].
    pub fn new(ctx: &GpuContext, output_format: wgpu::TextureFormat) -> Self {
        let output_format_error = crate::targets::check_output_format(output_format, ctx.device.features()).err();
        // A pipeline for an unusable format would be a wgpu validation panic: build a valid one.
        let tonemap_format = match output_format_error {
            None => output_format,
            Some(_) => crate::targets::HDR_FORMAT,
        };
        let own = SkyPasses::new(ctx, SkyTarget::OWN, None);
        let mut objects = ObjectPass::new(&ctx.device, &ctx.queue);
        objects.bind_cloud_shadow_map(&ctx.device, own.atmosphere.cloud_shadow_map_view());
        Self {
            own,
            embedded: HashMap::new(),
            active: None,
            sky: SkyKind::Gradient,
            objects,
            camera: CameraPasses::new(&ctx.device),
            tonemap: TonemapPass::new(&ctx.device, tonemap_format),
            embedded_tonemaps: HashMap::new(),
            embedded_output: None,
            lighting_recorded: std::cell::Cell::new(false),
            targets: None,
            aerial_volume_wanted: false,
            flare_interval: None,
            embedded_size: (0, 0),
            pass_timer: None,
            output_format_error,
            features: ctx.device.features(),
        }
    }

    /// The sky passes of the last `prepare` or `prepare_into`.
    fn passes(&self) -> &SkyPasses {
        self.active.and_then(|key| self.embedded.get(&key)).unwrap_or(&self.own)
    }

    /// Uploads everything `frame` needs and (re)creates the HDR targets at `width` × `height`.
    /// The camera's aspect ratio is taken from the size.
    pub fn prepare(&mut self, ctx: &GpuContext, frame: &Frame, width: u32, height: u32) -> Result<(), RenderError> {
        if let Some(reason) = &self.output_format_error {
            return Err(RenderError::OutputFormat(reason.clone()));
        }
        ctx.check_image_size(width, height)?;
        if self.targets.as_ref().map(FrameTargets::size) != Some((width, height)) {
            let targets = FrameTargets::new(&ctx.device, width, height);
            self.own.bind_depth(&ctx.device, &targets.depth_view, (width, height));
            self.own
                .atmosphere
                .bind_sky_target(&ctx.device, &targets.hdr, &targets.depth_view);
            self.targets = Some(targets);
        }
        let camera = firmament_core::Camera {
            aspect: f64::from(width) / f64::from(height),
            ..frame.camera
        };
        self.active = None;
        self.lighting_recorded.set(false);
        self.sky = self.own.prepare(ctx, frame, &camera, (width, height));
        let cloud_axes = match &frame.sky {
            Sky::Atmosphere(sky) => crate::gpu_types::shadow::cloud_shadow_axes(sky, &camera),
            _ => [[0.0; 4]; crate::gpu_types::shadow::CLOUD_ROWS],
        };
        self.objects.set_cloud_shadow_axes(cloud_axes);
        self.objects.prepare(&ctx.device, &ctx.queue, &frame.objects, &camera);
        if let Some(targets) = &self.targets {
            let hdr = &targets.hdr_view;
            self.camera.prepare(ctx, Some((frame, &camera)), hdr, (width, height));
            let images = self.camera.images();
            self.tonemap
                .prepare(&ctx.device, &ctx.queue, &frame.display, hdr, images);
        }
        Ok(())
    }

    /// Encodes the frame: clear the HDR and depth targets, draw the objects, the sky behind
    /// them and the stars and the Moon over the sky, aerial perspective over the objects in an
    /// atmosphere, lens flares, tone-map into `output`.
    /// Does nothing before the first `prepare`, or after a `prepare_into` (prepare again).
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, output: &wgpu::TextureView) {
        let Some(targets) = &self.targets else {
            tracing::warn!("Renderer::record before prepare: nothing drawn");
            return;
        };
        if self.active.is_some() {
            tracing::warn!("Renderer::record after prepare_into: nothing drawn (call prepare first)");
            return;
        }
        let own = &self.own;
        let mut timing = FrameTiming::begin(self.pass_timer.as_ref(), encoder);
        if self.sky == SkyKind::Atmosphere && !self.lighting_recorded.replace(false) {
            own.atmosphere.record_luts(encoder);
            timing.mark(encoder, PHASE_LUTS);
        }
        if self.objects.has_shadows() {
            self.objects.record_shadows(encoder);
            timing.mark(encoder, PHASE_SHADOWS);
        }
        if self.sky == SkyKind::Atmosphere && !self.objects.is_empty() {
            // The objects' suns are dimmed by the clouds' shadow map: it goes before them.
            own.atmosphere.record_cloud_shadow_map(encoder);
        }
        let clear = match self.sky {
            SkyKind::Clear(color) => color,
            _ => wgpu::Color::BLACK,
        };
        {
            let mut pass = begin_clear_pass(
                encoder,
                "firmament Renderer main pass",
                Some((&targets.hdr_view, clear)),
                &targets.depth_view,
                DEPTH_CLEAR,
            );
            // Opaque objects first; the sky then fills only what is left.
            self.objects.draw(&mut pass);
            if self.sky != SkyKind::Atmosphere {
                own.draw_sky(&mut pass, self.sky);
                // Stars and the Moon, added over the sky where nothing nearer was drawn.
                own.night.draw(&mut pass);
            }
        }
        if self.sky == SkyKind::Atmosphere {
            // The atmosphere's sky is a compute pass on the renderer's own targets (fragment work
            // runs on a few SMs of data-centre GPUs), then the stars and the Moon over it.
            own.atmosphere.record_sky(encoder);
            let mut pass = begin_load_pass(
                encoder,
                "firmament Renderer night-sky pass",
                &targets.hdr_view,
                &targets.depth_view,
            );
            own.night.draw(&mut pass);
        }
        timing.mark(encoder, PHASE_SKY_AND_OBJECTS);
        if self.sky == SkyKind::Atmosphere {
            if !self.objects.is_empty() {
                // Builds the volume too; compute on the own targets (bound in `prepare`).
                let shadows = self.objects.shadow_bind_group();
                if !own.atmosphere.record_aerial_perspective_with_shafts(encoder, shadows) {
                    own.atmosphere.record_aerial_perspective(encoder, &targets.hdr_view);
                }
                timing.mark(encoder, PHASE_AERIAL_PERSPECTIVE);
            } else if self.aerial_volume_wanted {
                own.atmosphere.record_aerial_perspective_volume(encoder);
                timing.mark(encoder, PHASE_AERIAL_PERSPECTIVE);
            }
            if own.atmosphere.has_clouds() {
                // The volume lights the air in front of the clouds.
                if self.objects.is_empty() && !self.aerial_volume_wanted {
                    own.atmosphere.record_aerial_perspective_volume(encoder);
                }
                own.atmosphere.record_clouds_on_target(encoder);
                timing.mark(encoder, PHASE_CLOUDS);
            }
        }
        // Flares last, over everything, hidden by what the depth buffer holds.
        own.flares.record(encoder, &targets.hdr_view);
        timing.mark(encoder, PHASE_FLARES);
        self.camera.record(encoder, &mut timing);
        self.tonemap.record(encoder, output);
        timing.mark(encoder, PHASE_TONEMAP);
        timing.finish(encoder);
    }

    /// Prepares `frame` for [`record_into`](Self::record_into) the caller's `target`: checks the
    /// target ([`EmbedTarget`]'s rules; an error names what is needed), builds the pipelines for
    /// its colour format, depth format and depth convention on first use (kept for later
    /// frames), binds its depth buffer and uploads the frame. The camera's aspect ratio is taken
    /// from the target's size, its near and far planes from `frame.camera` — the projection the
    /// caller's geometry must be drawn with is
    /// [`Camera::projection_matrix_for`](firmament_core::Camera::projection_matrix_for)`(convention)`.
    /// The renderer's own objects (`frame.objects`) are not drawn on this path.
    pub fn prepare_into(
        &mut self,
        ctx: &GpuContext,
        frame: &Frame,
        target: &EmbedTarget<'_>,
    ) -> Result<(), RenderError> {
        let (width, height) = target.check(ctx)?;
        let key = sky_target(target);
        let interval = self.flare_interval;
        let passes = self
            .embedded
            .entry(key)
            .or_insert_with(|| SkyPasses::new(ctx, key, interval));
        passes.bind_depth(&ctx.device, target.depth, (width, height));
        let camera = firmament_core::Camera {
            aspect: f64::from(width) / f64::from(height),
            ..frame.camera
        };
        self.sky = passes.prepare(ctx, frame, &camera, (width, height));
        passes.atmosphere.bind_clouds_into(&ctx.device, target.depth);
        self.active = Some(key);
        self.lighting_recorded.set(false);
        self.embedded_size = (width, height);
        self.embedded_output = target.output.map(|view| view.texture().format());
        let with_output = self.embedded_output.is_some().then_some((frame, &camera));
        self.camera.prepare(ctx, with_output, target.color, (width, height));
        if let Some(format) = self.embedded_output {
            let images = self.camera.images();
            let tonemap = self
                .embedded_tonemaps
                .entry(format)
                .or_insert_with(|| TonemapPass::new(&ctx.device, format));
            tonemap.prepare(&ctx.device, &ctx.queue, &frame.display, target.color, images);
        }
        Ok(())
    }

    /// Encodes the frame prepared by [`prepare_into`](Self::prepare_into) into the caller's
    /// `target` (the same one, its depth buffer holding the caller's geometry, drawn earlier in
    /// this encoder or before): the sky behind that geometry where the depth buffer still holds
    /// the far plane, the stars and the Moon over the sky, aerial perspective over the geometry
    /// (`colour · T + S`, with distances from the depth buffer) when the sky is an atmosphere
    /// (unless [`EmbedTarget::without_aerial_perspective`]), the cloud layers in front of the
    /// geometry, and the lens flares, hidden by the geometry, over everything. Colour is loaded and
    /// blended, never cleared; depth is tested, never written. Linear radiance in the sky's
    /// units: tone-map it yourself, or give the target an output view
    /// ([`EmbedTarget::with_output`]) and firmament's output pass writes the finished image
    /// there. A frame whose sky is a clear colour (`Sky::Clear`) draws no background: that is
    /// yours.
    ///
    /// An error when the target breaks [`EmbedTarget`]'s rules, or nothing was prepared for a
    /// target of its kind and size (nothing encoded).
    pub fn record_into(&self, encoder: &mut wgpu::CommandEncoder, target: &EmbedTarget<'_>) -> Result<(), RenderError> {
        let size = target.check_with(self.features)?;
        let output = target.output.map(|view| view.texture().format());
        if self.active != Some(sky_target(target)) || size != self.embedded_size || output != self.embedded_output {
            return Err(RenderError::InvalidTarget(format!(
                "record_into a {:?} target of {}x{} ({:?}, {:?} depth, output {:?}): prepare_into it first",
                sky_target(target).color,
                size.0,
                size.1,
                target.convention,
                sky_target(target).depth,
                output
            )));
        }
        let passes = self.passes();
        let mut timing = FrameTiming::begin(self.pass_timer.as_ref(), encoder);
        if self.sky == SkyKind::Atmosphere && !self.lighting_recorded.replace(false) {
            passes.atmosphere.record_luts(encoder);
            timing.mark(encoder, PHASE_LUTS);
        }
        {
            let mut pass = begin_load_pass(encoder, "firmament Renderer embedded sky", target.color, target.depth);
            // A clear-colour sky leaves the background to the caller.
            passes.draw_sky(&mut pass, self.sky);
            passes.night.draw(&mut pass);
        }
        timing.mark(encoder, PHASE_SKY_AND_OBJECTS);
        if self.sky == SkyKind::Atmosphere && target.aerial_perspective {
            passes.atmosphere.record_aerial_perspective(encoder, target.color);
            timing.mark(encoder, PHASE_AERIAL_PERSPECTIVE);
        }
        if self.sky == SkyKind::Atmosphere && passes.atmosphere.has_clouds() {
            // The volume lights the air in front of the clouds.
            if !target.aerial_perspective {
                passes.atmosphere.record_aerial_perspective_volume(encoder);
            }
            passes.atmosphere.record_clouds_into(encoder, target.color);
            timing.mark(encoder, PHASE_CLOUDS);
        }
        passes.flares.record(encoder, target.color);
        timing.mark(encoder, PHASE_FLARES);
        if let (Some(view), Some(tonemap)) = (target.output, output.and_then(|f| self.embedded_tonemaps.get(&f))) {
            self.camera.record(encoder, &mut timing);
            tonemap.record(encoder, view);
            timing.mark(encoder, PHASE_TONEMAP);
        }
        timing.finish(encoder);
        Ok(())
    }

    /// Encodes this frame's lighting for your own shaders before you draw your geometry: the
    /// atmosphere's LUTs with the [`sky_lighting_buffer`](Self::sky_lighting_buffer) (and, after
    /// [`set_aerial_perspective_for_users(true)`](Self::set_aerial_perspective_for_users), the
    /// aerial-perspective volume). The next [`record`](Self::record) or
    /// [`record_into`](Self::record_into) then skips the LUTs. Without it, those values are the
    /// last recorded frame's when your shaders read them. Nothing for a sky that is not an
    /// atmosphere. Call after `prepare` / `prepare_into`, in the same or an earlier encoder.
    pub fn record_lighting(&self, encoder: &mut wgpu::CommandEncoder) {
        if self.sky != SkyKind::Atmosphere {
            return;
        }
        let passes = self.passes();
        passes.atmosphere.record_luts(encoder);
        if self.aerial_volume_wanted {
            passes.atmosphere.record_aerial_perspective_volume(encoder);
        }
        self.lighting_recorded.set(true);
    }

    /// Spreads rebuilds of the atmosphere's medium LUTs (after a change of planet or medium) over
    /// successive frames of the renderer's own targets, the sky drawing from the previous medium
    /// meanwhile (a viewer's panel stays responsive); off by default — stills build in the frame
    /// of the change.
    pub fn set_incremental_lut_rebuild(&mut self, incremental: bool) {
        self.own.atmosphere.set_incremental_rebuild(incremental);
    }

    /// The complete builds of the atmosphere's medium LUTs the renderer's own targets encoded
    /// since it was made, and whether one is under way.
    pub fn medium_lut_builds(&self) -> (u64, bool) {
        (self.own.atmosphere.medium_builds(), self.own.atmosphere.rebuilding())
    }

    /// Sets the time between frames for the lens flares' fade-in and fade-out rates (a viewer's
    /// frame interval, seconds); `None` (the default) takes each frame's visibility at once, as
    /// stills and time-lapses should.
    pub fn set_flare_interval(&mut self, seconds: Option<f64>) {
        self.flare_interval = seconds;
        self.own.flares.set_interval(seconds);
        for passes in self.embedded.values_mut() {
            passes.flares.set_interval(seconds);
        }
    }

    /// Sets the time between frames over which auto-exposure adapts at the display's speeds (a
    /// viewer's frame interval, a time-lapse's time per frame, seconds); `None` (the default)
    /// meters every frame afresh, as stills should. Frames are adapted in the order recorded.
    pub fn set_exposure_interval(&mut self, seconds: Option<f64>) {
        self.camera.exposure.set_interval(seconds);
    }

    /// The auto-exposure pass (its state buffer, for tests and tools).
    pub fn exposure(&self) -> &ExposurePass {
        &self.camera.exposure
    }

    /// The lens-flare pass (its visibility buffer, for tests and tools).
    pub fn flares(&self) -> &FlarePass {
        &self.passes().flares
    }

    /// The night-sky pass (how many stars it drew, for tests and tools).
    pub fn night_sky(&self) -> &NightSkyPass {
        &self.passes().night
    }

    /// The per-frame lighting values for users' own shaders ([`SkyLightingGpu`]: each sun's
    /// direction and colour at the camera, the sky's radiance as spherical harmonics), when the
    /// last frame's sky was a physical atmosphere. Bind it with
    /// [`sky_lighting_layout_entry`](crate::sky_lighting_layout_entry) and sample it with
    /// [`FIRMAMENT_LIGHTING_WGSL`](crate::FIRMAMENT_LIGHTING_WGSL).
    ///
    /// [`SkyLightingGpu`]: crate::SkyLightingGpu
    pub fn sky_lighting_buffer(&self) -> Option<&wgpu::Buffer> {
        (self.sky == SkyKind::Atmosphere).then(|| self.passes().atmosphere.sky_lighting_buffer())
    }

    /// The aerial-perspective volume for users' own shaders (bind
    /// [`AerialPerspectiveBindings::bind_group_entries`] in a layout of
    /// [`aerial_perspective_layout_entries`](crate::aerial_perspective_layout_entries), include
    /// [`FIRMAMENT_AERIAL_PERSPECTIVE_WGSL`](crate::FIRMAMENT_AERIAL_PERSPECTIVE_WGSL)), when the
    /// last frame's sky was a physical atmosphere.
    ///
    /// The rule for its cost: [`record`](Self::record) builds the volume (one 32 × 32 compute
    /// dispatch) in every atmosphere frame with firmament objects, which need it themselves, and —
    /// after [`set_aerial_perspective_for_users(true)`](Self::set_aerial_perspective_for_users) —
    /// in every atmosphere frame, objects or not, so a renderer whose user never asks pays nothing
    /// for it. The bindings stay valid for the renderer's life; the volume holds a frame's air for
    /// commands encoded after that frame's `record`.
    pub fn aerial_perspective_bindings(&self) -> Option<AerialPerspectiveBindings<'_>> {
        (self.sky == SkyKind::Atmosphere).then(|| self.passes().atmosphere.aerial_perspective_bindings())
    }

    /// Whether [`record`](Self::record) builds the aerial-perspective volume in every atmosphere
    /// frame (for users' shaders, [`Self::aerial_perspective_bindings`]) or only in frames with
    /// firmament objects (the default).
    pub fn set_aerial_perspective_for_users(&mut self, every_frame: bool) {
        self.aerial_volume_wanted = every_frame;
    }

    /// Turns on per-pass GPU timing of [`record`](Self::record) and
    /// [`record_into`](Self::record_into) ([`PassTimes`](crate::PassTimes)): builds a timestamp query set
    /// and a few small read-back buffers. `true` when timing is on (it already was, or the device
    /// has [`TIMESTAMP_FEATURES`](crate::TIMESTAMP_FEATURES)); `false`, and timing stays
    /// off, where the device has no timestamps inside encoders
    /// ([`pass_timing_supported`](crate::pass_timing_supported)). Timing changes no pixel.
    pub fn enable_pass_timing(&mut self, ctx: &GpuContext) -> bool {
        if self.pass_timer.is_none() {
            self.pass_timer = PassTimer::new(ctx);
        }
        self.pass_timer.is_some()
    }

    /// Turns per-pass GPU timing off (the default) and frees its GPU objects; the times already
    /// read are forgotten.
    pub fn disable_pass_timing(&mut self) {
        self.pass_timer = None;
    }

    /// Whether per-pass GPU timing is on ([`enable_pass_timing`](Self::enable_pass_timing)).
    pub fn pass_timing_enabled(&self) -> bool {
        self.pass_timer.is_some()
    }

    /// The GPU time of each phase of the newest timed frame whose timestamps have come back —
    /// milliseconds of GPU time, phases in the order they ran ([`PassTimes`]); `None` while timing
    /// is off or before any timed frame finished.
    ///
    /// Never blocks: it polls the device once without waiting (`wgpu::PollType::Poll`), so the
    /// times are usually one or two frames old. Nothing needs calling after `queue.submit`: the
    /// read-back is mapped on submission. Call it once a frame (or at least now and then): a
    /// frame is not timed while all of the few read-back buffers hold results not yet collected
    /// (here or by the next `record`) or still on the GPU.
    pub fn pass_times(&self, ctx: &GpuContext) -> Option<PassTimes> {
        self.pass_timer.as_ref()?.pass_times(ctx)
    }

    /// The HDR and depth targets of the last `prepare` (for EXR output and tests).
    pub fn targets(&self) -> Option<&FrameTargets> {
        self.targets.as_ref()
    }
}

/// What the sky pipelines for `target` depend on: its colour format, depth format and convention.
fn sky_target(target: &EmbedTarget<'_>) -> SkyTarget {
    SkyTarget::new(
        target.color.texture().format(),
        target.depth.texture().format(),
        target.convention,
    )
}
