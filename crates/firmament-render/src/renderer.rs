//! The frame renderer: objects, then the sky behind them and the stars and the Moon added over
//! it, into HDR targets; aerial perspective over the objects when the sky is an atmosphere; lens
//! flares over everything; tonemap → the caller's view.

use firmament_core::Frame;
use firmament_core::frame::Sky;

use crate::context::GpuContext;
use crate::error::RenderError;
use crate::passes::atmosphere::AerialPerspectiveBindings;
use crate::passes::{
    AtmospherePass, FlarePass, GradientSkyPass, NightSkyPass, ObjectPass, SeedSkyPass, TonemapPass, begin_clear_pass,
};
use crate::targets::{DEPTH_CLEAR, FrameTargets};

/// The sky passes a frame can use.
#[derive(Debug, Clone, Copy, PartialEq)]
enum SkyKind {
    Gradient,
    Atmosphere,
    Seed,
    /// A clear colour (linear, as given).
    Clear(wgpu::Color),
}

/// Renders [`Frame`]s into any texture view of the output format it was built for.
#[derive(Debug)]
pub struct Renderer {
    sky_gradient: GradientSkyPass,
    atmosphere: AtmospherePass,
    seed: SeedSkyPass,
    /// Which sky the last `prepare` chose.
    sky: SkyKind,
    objects: ObjectPass,
    night: NightSkyPass,
    flares: FlarePass,
    tonemap: TonemapPass,
    targets: Option<FrameTargets>,
    /// Build the aerial-perspective volume in every atmosphere frame, objects or not
    /// ([`Renderer::set_aerial_perspective_for_users`]).
    aerial_volume_wanted: bool,
}

impl Renderer {
    /// Builds every pipeline once, for output views of `output_format`.
    pub fn new(ctx: &GpuContext, output_format: wgpu::TextureFormat) -> Self {
        Self {
            sky_gradient: GradientSkyPass::new(&ctx.device),
            atmosphere: AtmospherePass::new(&ctx.device),
            seed: SeedSkyPass::new(&ctx.device),
            sky: SkyKind::Gradient,
            objects: ObjectPass::new(&ctx.device, &ctx.queue),
            night: NightSkyPass::new(&ctx.device),
            flares: FlarePass::new(&ctx.device),
            tonemap: TonemapPass::new(&ctx.device, output_format),
            targets: None,
            aerial_volume_wanted: false,
        }
    }

    /// Uploads everything `frame` needs and (re)creates the HDR targets at `width` × `height`.
    /// The camera's aspect ratio is taken from the size.
    pub fn prepare(&mut self, ctx: &GpuContext, frame: &Frame, width: u32, height: u32) -> Result<(), RenderError> {
        ctx.check_image_size(width, height)?;
        if self.targets.as_ref().map(FrameTargets::size) != Some((width, height)) {
            let targets = FrameTargets::new(&ctx.device, width, height);
            self.atmosphere.bind_depth(&ctx.device, &targets.depth_view);
            self.flares.bind_depth(&ctx.device, &targets.depth_view, width, height);
            self.targets = Some(targets);
        }
        let camera = firmament_core::Camera {
            aspect: f64::from(width) / f64::from(height),
            ..frame.camera
        };
        match &frame.sky {
            Sky::Gradient(sky) => {
                self.sky_gradient.prepare(&ctx.queue, sky, &camera);
                self.sky = SkyKind::Gradient;
            }
            Sky::Atmosphere(sky) => {
                self.atmosphere.prepare(&ctx.queue, sky, &camera);
                self.sky = SkyKind::Atmosphere;
            }
            Sky::Seed(sky) => {
                self.seed.prepare(&ctx.queue, sky, &camera);
                self.sky = SkyKind::Seed;
            }
            Sky::Clear(c) => {
                self.sky = SkyKind::Clear(wgpu::Color {
                    r: c.r,
                    g: c.g,
                    b: c.b,
                    a: 1.0,
                });
            }
        }
        self.objects.prepare(&ctx.device, &ctx.queue, &frame.objects, &camera);
        self.night
            .prepare(&ctx.device, &ctx.queue, &frame.night, &camera, (width, height));
        let planet = match &frame.sky {
            Sky::Atmosphere(sky) => Some(&sky.atmosphere.planet),
            _ => None,
        };
        self.flares.prepare(
            &ctx.device,
            &ctx.queue,
            &frame.flares,
            &camera,
            frame.display.exposure.multiplier,
            planet,
        );
        if let Some(targets) = &self.targets {
            self.tonemap
                .prepare(&ctx.device, &ctx.queue, &frame.display, &targets.hdr_view);
        }
        Ok(())
    }

    /// Encodes the frame: clear the HDR and depth targets, draw the objects, the sky behind
    /// them and the stars and the Moon over the sky, aerial perspective over the objects in an
    /// atmosphere, lens flares, tone-map into `output`.
    /// Does nothing before the first `prepare`.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, output: &wgpu::TextureView) {
        let Some(targets) = &self.targets else {
            tracing::warn!("Renderer::record before prepare: nothing drawn");
            return;
        };
        if self.sky == SkyKind::Atmosphere {
            self.atmosphere.record_luts(encoder);
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
            match self.sky {
                SkyKind::Gradient => self.sky_gradient.draw(&mut pass),
                SkyKind::Atmosphere => self.atmosphere.draw(&mut pass),
                SkyKind::Seed => self.seed.draw(&mut pass),
                SkyKind::Clear(_) => {}
            }
            // Stars and the Moon, added over the sky where nothing nearer was drawn.
            self.night.draw(&mut pass);
        }
        if self.sky == SkyKind::Atmosphere {
            if !self.objects.is_empty() {
                // Builds the volume too.
                self.atmosphere.record_aerial_perspective(encoder, &targets.hdr_view);
            } else if self.aerial_volume_wanted {
                self.atmosphere.record_aerial_perspective_volume(encoder);
            }
        }
        // Flares last, over everything, hidden by what the depth buffer holds.
        self.flares.record(encoder, &targets.hdr_view);
        self.tonemap.record(encoder, output);
    }

    /// Sets the time between frames for the lens flares' fade-in and fade-out rates (a viewer's
    /// frame interval, seconds); `None` (the default) takes each frame's visibility at once, as
    /// stills and time-lapses should.
    pub fn set_flare_interval(&mut self, seconds: Option<f64>) {
        self.flares.set_interval(seconds);
    }

    /// The lens-flare pass (its visibility buffer, for tests and tools).
    pub fn flares(&self) -> &FlarePass {
        &self.flares
    }

    /// The night-sky pass (how many stars it drew, for tests and tools).
    pub fn night_sky(&self) -> &NightSkyPass {
        &self.night
    }

    /// The per-frame lighting values for users' own shaders ([`SkyLightingGpu`]: each sun's
    /// direction and colour at the camera, the sky's radiance as spherical harmonics), when the
    /// last frame's sky was a physical atmosphere. Bind it with
    /// [`sky_lighting_layout_entry`](crate::sky_lighting_layout_entry) and sample it with
    /// [`FIRMAMENT_LIGHTING_WGSL`](crate::FIRMAMENT_LIGHTING_WGSL).
    ///
    /// [`SkyLightingGpu`]: crate::SkyLightingGpu
    pub fn sky_lighting_buffer(&self) -> Option<&wgpu::Buffer> {
        (self.sky == SkyKind::Atmosphere).then(|| self.atmosphere.sky_lighting_buffer())
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
        (self.sky == SkyKind::Atmosphere).then(|| self.atmosphere.aerial_perspective_bindings())
    }

    /// Whether [`record`](Self::record) builds the aerial-perspective volume in every atmosphere
    /// frame (for users' shaders, [`Self::aerial_perspective_bindings`]) or only in frames with
    /// firmament objects (the default).
    pub fn set_aerial_perspective_for_users(&mut self, every_frame: bool) {
        self.aerial_volume_wanted = every_frame;
    }

    /// The HDR and depth targets of the last `prepare` (for EXR output and tests).
    pub fn targets(&self) -> Option<&FrameTargets> {
        self.targets.as_ref()
    }
}
