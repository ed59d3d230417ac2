//! The viewer's GPU side: the window's surface, the renderer the CLI uses (drawing the scene into
//! an offscreen 8-bit sRGB texture, exactly what `firmament render` writes to PNG), a blit of that
//! texture to the surface, and egui over it.

use firmament_render::wgpu;
use std::sync::{Arc, Mutex};

use anyhow::{Context, Result, anyhow, bail};
use firmament_core::Frame;
use firmament_render::headless::{Image, LDR_FORMAT, ldr_texture};
use firmament_render::headless::{decode_f16, read_texture};
use firmament_render::{Backend, GpuContext, Renderer};
use winit::window::Window;

/// What a frame did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Presented {
    /// Drawn and shown.
    Shown,
    /// Nothing to draw into now (minimised, occluded, a timeout, a reconfigured surface): try
    /// again next frame.
    Skipped,
    /// The surface was lost: make a new one ([`Gpu::recreate_surface`]) and try again.
    Lost,
}

/// The egui part of a frame: what to draw and at what scale.
pub(crate) struct EguiFrame {
    /// Tessellated shapes.
    pub(crate) primitives: Vec<egui::ClippedPrimitive>,
    /// Texture uploads and frees.
    pub(crate) textures: egui::TexturesDelta,
    /// Physical pixels per egui point.
    pub(crate) pixels_per_point: f32,
}

/// The surface, the device and the passes.
pub(crate) struct Gpu {
    pub(crate) window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// The format the scene is copied in (the surface's, as an sRGB view).
    view_format: wgpu::TextureFormat,
    /// The format egui draws in (the surface's, as a plain view).
    egui_format: wgpu::TextureFormat,
    pub(crate) ctx: GpuContext,
    renderer: Renderer,
    /// The scene, drawn by `renderer` into [`LDR_FORMAT`].
    scene_target: Option<wgpu::Texture>,
    blitter: wgpu::util::TextureBlitter,
    egui: egui_wgpu::Renderer,
    /// The first uncaptured GPU error or device loss, reported by wgpu's callbacks.
    fault: Arc<Mutex<Option<String>>>,
    timing: bool,
    /// Report the surface lost at the next frame (an injected fault).
    lose_surface: bool,
}

impl Gpu {
    /// Opens a device for `window`'s surface on `backend`.
    pub(crate) fn new(instance: &wgpu::Instance, window: Arc<Window>, backend: Backend) -> Result<Self> {
        // With no backend of `backend` on this system there is no surface either: say so.
        let surface = instance.create_surface(window.clone()).map_err(|e| {
            anyhow!(
                "no GPU adapter for --backend {backend} can draw into this window (no surface: {e}); \
                 try another --backend, or render headless with `firmament render`"
            )
        })?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            apply_limit_buckets: false,
        }))
        .map_err(|e| {
            anyhow!(
                "no GPU adapter for --backend {backend} can draw into this window ({e}); \
                 try another --backend, or render headless with `firmament render`"
            )
        })?;
        let ctx = GpuContext::from_adapter(&adapter)?;
        let fault = Arc::new(Mutex::new(None));
        watch_faults(&ctx.device, &fault);

        let caps = surface.get_capabilities(&adapter);
        let Some(&format) = caps
            .formats
            .iter()
            .find(|f| f.is_srgb())
            .or_else(|| caps.formats.first())
        else {
            bail!("the window's surface offers no texture format on this adapter");
        };
        // The scene is copied through an sRGB view (the texture holds sRGB-encoded bytes, as the
        // PNGs do); egui blends in gamma space and wants a plain one. Views of another format
        // than the surface's need SURFACE_VIEW_FORMATS (not on GL): then both draw in the
        // surface's own format, an sRGB one where offered.
        let reinterpret = adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::SURFACE_VIEW_FORMATS);
        let (view_format, egui_format) = if reinterpret {
            (format.add_srgb_suffix(), format.remove_srgb_suffix())
        } else {
            if !format.is_srgb() {
                tracing::warn!("the window offers no sRGB format ({format:?}): colours will look too dark");
            }
            (format, format)
        };
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: wgpu::PresentMode::AutoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: [view_format, egui_format]
                .into_iter()
                .filter(|f| *f != format)
                .collect(),
            // The window shows sRGB, as the PNGs `render` writes.
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&ctx.device, &config);

        let mut renderer = Renderer::new(&ctx, LDR_FORMAT);
        // A change of planet or medium rebuilds its LUTs over a dozen frames, not in one that
        // would freeze the window for seconds on a software adapter.
        renderer.set_incremental_lut_rebuild(true);
        let timing = renderer.enable_pass_timing(&ctx);
        let blitter = wgpu::util::TextureBlitter::new(&ctx.device, view_format);
        let egui = egui_wgpu::Renderer::new(&ctx.device, egui_format, egui_wgpu::RendererOptions::default());
        Ok(Self {
            window,
            surface,
            config,
            view_format,
            egui_format,
            ctx,
            renderer,
            scene_target: None,
            blitter,
            egui,
            fault,
            timing,
            lose_surface: false,
        })
    }

    /// The adapter, for the info panel.
    pub(crate) fn adapter(&self) -> String {
        self.ctx.adapter_summary()
    }

    /// The largest texture side egui may use.
    pub(crate) fn max_texture_side(&self) -> usize {
        self.ctx.device.limits().max_texture_dimension_2d as usize
    }

    /// Reconfigures the surface for the window's new size (nothing while it is minimised).
    pub(crate) fn resize(&mut self, width: u32, height: u32) {
        if width == 0 || height == 0 {
            return;
        }
        self.config.width = width;
        self.config.height = height;
        self.surface.configure(&self.ctx.device, &self.config);
    }

    /// Makes a new surface for the window after the old one was lost, configured as before.
    pub(crate) fn recreate_surface(&mut self, instance: &wgpu::Instance) -> Result<()> {
        self.surface = instance
            .create_surface(self.window.clone())
            .context("the window's surface was lost and a new one could not be made")?;
        self.surface.configure(&self.ctx.device, &self.config);
        Ok(())
    }

    /// Destroys the device, as a driver reset would lose it (an injected fault, for tests).
    pub(crate) fn lose_device(&self) {
        self.ctx.device.destroy();
        // Lets wgpu run the device-lost callback now rather than at some later call.
        let _ = self.ctx.device.poll(wgpu::PollType::Poll);
    }

    /// Reports the surface lost at the next frame, as a driver would (an injected fault).
    pub(crate) fn lose_surface(&mut self) {
        self.lose_surface = true;
    }

    /// An error wgpu reported since the last check (a device loss, a validation error).
    pub(crate) fn fault(&self) -> Option<String> {
        self.fault.lock().ok().and_then(|f| f.clone())
    }

    /// The scene's size for `scale` of the window's pixels.
    pub(crate) fn scene_size(&self, scale: f32) -> (u32, u32) {
        let scale = f64::from(scale.clamp(0.05, 1.0));
        let side = |s: u32| ((f64::from(s) * scale).round() as u32).max(1);
        (side(self.config.width), side(self.config.height))
    }

    /// Whether the atmosphere's medium LUTs are being rebuilt over the coming frames.
    pub(crate) fn luts_rebuilding(&self) -> bool {
        self.renderer.medium_lut_builds().1
    }

    /// Sets the flares' fade rate and auto-exposure's adaptation for frames `interval` seconds
    /// apart.
    pub(crate) fn set_frame_interval(&mut self, interval: Option<f64>) {
        self.renderer.set_flare_interval(interval);
        self.renderer.set_exposure_interval(interval);
    }

    /// Draws `frame` at `scene_size`, blits it over the window and draws `ui` over that. egui's
    /// texture changes are applied even when the frame is skipped.
    pub(crate) fn draw(&mut self, frame: &Frame, scene_size: (u32, u32), mut ui: EguiFrame) -> Result<Presented> {
        for (id, deltas) in ui.textures.set.drain() {
            for delta in deltas {
                self.egui.update_texture(&self.ctx.device, &self.ctx.queue, id, &delta);
            }
        }
        let freed: Vec<egui::TextureId> = ui.textures.free.drain().collect();
        let presented = self.draw_frame(frame, scene_size, &ui);
        for id in &freed {
            self.egui.free_texture(id);
        }
        presented
    }

    fn draw_frame(&mut self, frame: &Frame, scene_size: (u32, u32), ui: &EguiFrame) -> Result<Presented> {
        let size = self.window.inner_size();
        if size.width == 0 || size.height == 0 {
            return Ok(Presented::Skipped);
        }
        if std::mem::take(&mut self.lose_surface) {
            return Ok(Presented::Lost);
        }
        let surface_texture = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t) => t,
            wgpu::CurrentSurfaceTexture::Suboptimal(t) => {
                // Show this one; reconfigure for the next.
                self.surface.configure(&self.ctx.device, &self.config);
                t
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                return Ok(Presented::Skipped);
            }
            wgpu::CurrentSurfaceTexture::Outdated => {
                self.resize(size.width, size.height);
                return Ok(Presented::Skipped);
            }
            wgpu::CurrentSurfaceTexture::Lost => return Ok(Presented::Lost),
            wgpu::CurrentSurfaceTexture::Validation => match self.fault() {
                // A lost device fails here first: say that, not what it broke.
                Some(fault) => bail!("{fault}"),
                None => bail!("the window's surface could not give a texture (a validation error)"),
            },
        };
        let scene_view = self.scene_view(scene_size);
        self.renderer.prepare(&self.ctx, frame, scene_size.0, scene_size.1)?;
        let surface_view = surface_texture.texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("firmament viewer surface view"),
            format: Some(self.view_format),
            ..Default::default()
        });
        let panel_view = surface_texture.texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("firmament viewer panel view"),
            format: Some(self.egui_format),
            ..Default::default()
        });
        let device = &self.ctx.device;
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("firmament viewer frame"),
        });
        self.renderer.record(&mut encoder, &scene_view);
        self.blitter.copy(device, &mut encoder, &scene_view, &surface_view);

        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [self.config.width, self.config.height],
            pixels_per_point: ui.pixels_per_point,
        };
        let extra = self
            .egui
            .update_buffers(device, &self.ctx.queue, &mut encoder, &ui.primitives, &screen);
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("firmament viewer panel"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &panel_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            let mut pass = pass.forget_lifetime();
            self.egui.render(&mut pass, &ui.primitives, &screen);
        }
        self.ctx
            .queue
            .submit(extra.into_iter().chain(std::iter::once(encoder.finish())));
        self.window.pre_present_notify();
        self.ctx.queue.present(surface_texture);
        Ok(Presented::Shown)
    }

    /// The last frame's GPU time per pass, milliseconds, where the adapter has timestamps.
    pub(crate) fn pass_times(&self) -> Option<Vec<(&'static str, f64)>> {
        if !self.timing {
            return None;
        }
        self.renderer
            .pass_times(&self.ctx)
            .map(|t| t.phases.iter().map(|p| (p.name, p.milliseconds)).collect())
    }

    /// The last scene drawn, as `firmament render` writes PNGs (8-bit sRGB after exposure and tone
    /// curve), at the scene's size.
    pub(crate) fn read_ldr(&self) -> Result<Image<u8>> {
        let texture = self.scene_target.as_ref().context("nothing drawn yet")?;
        Ok(Image {
            width: texture.width(),
            height: texture.height(),
            pixels: read_texture(&self.ctx, texture)?,
        })
    }

    /// The last scene drawn as linear radiance (as `firmament render` writes EXRs).
    pub(crate) fn read_hdr(&self) -> Result<Image<f32>> {
        let targets = self.renderer.targets().context("nothing drawn yet")?;
        let (width, height) = targets.size();
        Ok(Image {
            width,
            height,
            pixels: decode_f16(&read_texture(&self.ctx, &targets.hdr)?),
        })
    }

    /// A view of the scene texture at `size`, made anew when the size changed.
    fn scene_view(&mut self, (width, height): (u32, u32)) -> wgpu::TextureView {
        let texture = match &self.scene_target {
            Some(t) if (t.width(), t.height()) == (width, height) => t.clone(),
            _ => {
                let t = ldr_texture(
                    &self.ctx.device,
                    "firmament viewer scene",
                    (width, height),
                    wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC,
                );
                self.scene_target = Some(t.clone());
                t
            }
        };
        texture.create_view(&wgpu::TextureViewDescriptor::default())
    }
}

/// Records the first uncaptured error and a device loss, instead of wgpu's default (a panic).
fn watch_faults(device: &wgpu::Device, fault: &Arc<Mutex<Option<String>>>) {
    let on_error = fault.clone();
    device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
        if let Ok(mut slot) = on_error.lock() {
            slot.get_or_insert_with(|| format!("GPU error: {error}"));
        }
    }));
    let on_lost = fault.clone();
    device.set_device_lost_callback(move |reason, message| {
        if let Ok(mut slot) = on_lost.lock() {
            let detail = if message.is_empty() {
                String::new()
            } else {
                format!(": {message}")
            };
            slot.get_or_insert_with(|| {
                format!("the GPU device was lost ({reason:?}{detail}); restart the viewer (the driver may have reset)")
            });
        }
    });
}
