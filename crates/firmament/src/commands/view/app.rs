//! The viewer's window and event loop (winit): input to the session, a frame per redraw,
//! screenshots, saves, and the automation flags' exit.

use firmament_render::wgpu;
use std::collections::HashSet;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result};
use glam::DVec2;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use super::fault::InjectedFault;
use super::gpu::{EguiFrame, Gpu, Presented};
use super::input::{self, Command};
use super::options::ViewOptions;
use super::panel::{self, FrameInfo, PanelState, Request};
use super::session::Session;
use crate::output::{write_exr, write_png};

/// Surfaces lost in a row before the viewer gives up.
const MAX_SURFACES_LOST: u32 = 3;

/// Frame times kept for the summary printed on closing.
const FRAME_TIMES_KEPT: usize = 10_000;

/// Pixels of mouse-wheel travel per notch, for touchpads that scroll in pixels.
const PIXELS_PER_NOTCH: f64 = 50.0;

/// The running viewer.
pub(crate) struct App {
    options: ViewOptions,
    instance: wgpu::Instance,
    session: Session,
    panel: PanelState,
    gpu: Option<Gpu>,
    egui_ctx: egui::Context,
    egui_state: Option<egui_winit::State>,
    /// Keys held down, for the flight actions.
    held: HashSet<KeyCode>,
    shift: bool,
    /// Where the cursor was, while a mouse button is held for looking around.
    look_from: Option<DVec2>,
    last_frame: Option<Instant>,
    info: FrameInfo,
    frames: u64,
    /// Surfaces lost since the last frame shown.
    surfaces_lost: u32,
    /// Wall time between frames, seconds (the last [`FRAME_TIMES_KEPT`]), for the summary.
    frame_times: std::collections::VecDeque<f64>,
    /// The error that ended the viewer, if one did.
    pub(crate) error: Option<anyhow::Error>,
}

impl App {
    /// A viewer of `session`, drawing with `instance`'s adapters.
    pub(crate) fn new(options: ViewOptions, instance: wgpu::Instance, session: Session) -> Self {
        let panel = PanelState::new(options.save_path.display().to_string(), options.render_scale);
        let mut session = session;
        session.clock.paused = options.paused;
        if options.nehe {
            session.flight.set_mode(super::flight::FlightMode::NeHe);
        }
        Self {
            options,
            instance,
            session,
            panel,
            gpu: None,
            egui_ctx: egui::Context::default(),
            egui_state: None,
            held: HashSet::new(),
            shift: false,
            look_from: None,
            last_frame: None,
            info: FrameInfo::default(),
            frames: 0,
            surfaces_lost: 0,
            frame_times: std::collections::VecDeque::new(),
            error: None,
        }
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error.get_or_insert(error);
        event_loop.exit();
    }

    /// One frame: time and flight, the panel, the scene, the automation flags.
    fn redraw(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let now = Instant::now();
        let dt = self.last_frame.map_or(0.0, |t| now.duration_since(t).as_secs_f64());
        self.last_frame = Some(now);
        if dt > 0.0 {
            if self.frame_times.len() == FRAME_TIMES_KEPT {
                self.frame_times.pop_front();
            }
            self.frame_times.push_back(dt);
        }
        let ms = dt * 1000.0;
        self.info.frame_ms = if self.info.frame_ms == 0.0 {
            ms
        } else {
            0.9 * self.info.frame_ms + 0.1 * ms
        };

        let typing = self.egui_ctx.egui_wants_keyboard_input();
        let held = if typing {
            Vec::new()
        } else {
            input::held_actions(&self.held, self.session.flight.mode)
        };
        self.session.advance(&held, dt);

        let (Some(gpu), Some(egui_state)) = (self.gpu.as_mut(), self.egui_state.as_mut()) else {
            return Ok(());
        };
        if let Some(fault) = gpu.fault() {
            anyhow::bail!("{fault}");
        }
        self.info.pass_ms = gpu.pass_times();
        self.info.luts_rebuilding = gpu.luts_rebuilding();
        self.info.scene_size = gpu.scene_size(self.panel.render_scale);

        let raw = egui_state.take_egui_input(&gpu.window);
        let (session, panel_state, info) = (&mut self.session, &mut self.panel, &self.info);
        let mut requests = Vec::new();
        let mut output = self.egui_ctx.run_ui(raw, |ui| {
            if panel_state.show_info {
                panel::info_overlay(ui.ctx(), session, info);
            }
            if panel_state.visible {
                requests = panel::side_panel(ui, session, panel_state, info);
            }
        });
        egui_state.handle_platform_output(&gpu.window, std::mem::take(&mut output.platform_output));
        let frame = match self.session.frame(self.info.scene_size) {
            Ok(frame) => frame,
            Err(error) => {
                // egui's texture changes must be applied or cleared, never dropped (a panic).
                output.textures_delta.clear();
                return Err(error);
            }
        };
        let ui = EguiFrame {
            primitives: self.egui_ctx.tessellate(output.shapes, output.pixels_per_point),
            textures: output.textures_delta,
            pixels_per_point: output.pixels_per_point,
        };
        if let Some(fault) = self.options.fault
            && fault.after_frames() == self.frames
        {
            // The frame then fails, or finds the surface lost, as it would after a driver's.
            self.options.fault = None;
            tracing::warn!("injecting {fault:?}");
            match fault {
                InjectedFault::DeviceLost(_) => gpu.lose_device(),
                InjectedFault::SurfaceLost(_) => gpu.lose_surface(),
            }
        }
        gpu.set_frame_interval((dt > 0.0).then_some(dt));
        match gpu.draw(&frame, self.info.scene_size, ui)? {
            Presented::Shown => {
                self.frames += 1;
                self.surfaces_lost = 0;
            }
            Presented::Skipped => {}
            Presented::Lost => {
                // A new surface, a few times in a row at most: a surface that keeps getting lost
                // is a driver problem to report, not to spin on.
                self.surfaces_lost += 1;
                if self.surfaces_lost > MAX_SURFACES_LOST {
                    anyhow::bail!(
                        "the window's surface was lost {MAX_SURFACES_LOST} times in a row; restart the viewer"
                    );
                }
                tracing::warn!("the window's surface was lost; making a new one");
                gpu.recreate_surface(&self.instance)?;
            }
        }
        for request in requests {
            self.handle(request);
        }
        if self.options.frames.is_some_and(|n| self.frames >= n) {
            if let Some(path) = self.options.screenshot.clone() {
                self.screenshot_to(&path)?;
            }
            if self.options.save_at_exit {
                let path = self.options.save_path.clone();
                self.session.save(&path, self.info.scene_size)?;
                tracing::info!("saved {}", path.display());
            }
            event_loop.exit();
        }
        Ok(())
    }

    /// "N frames, median M ms per frame" over the frames kept, for the log on closing.
    pub(crate) fn summary(&self) -> String {
        let mut times: Vec<f64> = self.frame_times.iter().copied().collect();
        times.sort_by(f64::total_cmp);
        match times.get(times.len() / 2) {
            Some(median) => format!(
                "{} frames, median {:.1} ms per frame over the last {} (first frame excluded), scene {}x{}",
                self.frames,
                median * 1000.0,
                times.len(),
                self.info.scene_size.0,
                self.info.scene_size.1
            ),
            None => format!("{} frames", self.frames),
        }
    }

    fn handle(&mut self, request: Request) {
        let outcome = match request {
            Request::Save(path) => self
                .session
                .save(&path, self.info.scene_size)
                .map(|()| format!("saved {}", path.display())),
            Request::Screenshot { exr } => self.screenshot(exr),
        };
        self.panel.status = Some(match outcome {
            Ok(done) => {
                tracing::info!("{done}");
                done
            }
            Err(error) => {
                tracing::error!("{error:#}");
                format!("{error:#}")
            }
        });
    }

    /// Saves a screenshot next to the working directory, named by the time.
    fn screenshot(&mut self, exr: bool) -> Result<String> {
        let stamp = self.session.describe_moment().replace([':', '+'], "-");
        let path = PathBuf::from(format!(
            "firmament-{stamp}-{}.{}",
            self.frames,
            if exr { "exr" } else { "png" }
        ));
        self.screenshot_to(&path)?;
        Ok(format!("wrote {}", path.display()))
    }

    /// Writes the last scene drawn to `path` (PNG or EXR by its extension; atomically).
    fn screenshot_to(&self, path: &std::path::Path) -> Result<()> {
        let gpu = self.gpu.as_ref().context("no window to take a screenshot of")?;
        match crate::output::OutputFormat::from_path(path)? {
            crate::output::OutputFormat::Png => write_png(path, &gpu.read_ldr()?),
            crate::output::OutputFormat::Exr => write_exr(path, &gpu.read_hdr()?, self.options.exr_compression),
        }
        .with_context(|| format!("cannot write the screenshot {}", path.display()))
    }

    fn command(&mut self, event_loop: &ActiveEventLoop, command: Command) {
        let clock = &mut self.session.clock;
        match command {
            Command::TogglePause => clock.toggle_pause(),
            Command::Faster => clock.faster(),
            Command::Slower => clock.slower(),
            Command::ResetTime => clock.offset_seconds = 0.0,
            Command::ToggleMode => self.session.flight.toggle_mode(),
            Command::GoToGround => self.session.go_to_ground(),
            Command::GoToOrbit => {
                if !self.session.go_to_orbit() {
                    self.panel.status = Some("no planet to orbit under this sky".to_owned());
                }
            }
            Command::TogglePanel => self.panel.visible = !self.panel.visible,
            Command::ShowInfo(show) => self.panel.show_info = show,
            Command::NeHeVelocity(velocity) => {
                let altitude = self.session.altitude();
                self.session.flight.set_nehe_velocity(velocity, altitude);
            }
            Command::Screenshot { exr } => self.handle(Request::Screenshot { exr }),
            Command::Quit => event_loop.exit(),
        }
    }

    fn open_window(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let (width, height) = self.options.size;
        let attributes = Window::default_attributes()
            .with_title(format!("firmament — {}", self.options.title))
            .with_inner_size(PhysicalSize::new(width, height));
        let window = Arc::new(event_loop.create_window(attributes).context("cannot open a window")?);
        let gpu = Gpu::new(&self.instance, window.clone(), self.options.backend)?;
        self.egui_state = Some(egui_winit::State::new(
            self.egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.max_texture_side()),
        ));
        self.info.adapter = gpu.adapter();
        tracing::info!("viewer on {}", self.info.adapter);
        self.gpu = Some(gpu);
        window.request_redraw();
        Ok(())
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gpu.is_none()
            && let Err(error) = self.open_window(event_loop)
        {
            self.fail(event_loop, error);
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(gpu) = self.gpu.as_mut() else { return };
        let consumed = match self.egui_state.as_mut() {
            Some(state) => state.on_window_event(&gpu.window, &event).consumed,
            None => false,
        };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                gpu.resize(size.width, size.height);
                gpu.window.request_redraw();
            }
            WindowEvent::RedrawRequested => {
                if let Err(error) = self.redraw(event_loop) {
                    self.fail(event_loop, error);
                } else if let Some(gpu) = &self.gpu {
                    gpu.window.request_redraw();
                }
            }
            WindowEvent::ModifiersChanged(modifiers) => self.shift = modifiers.state().shift_key(),
            WindowEvent::KeyboardInput { event, .. } => {
                let PhysicalKey::Code(code) = event.physical_key else {
                    return;
                };
                match event.state {
                    ElementState::Pressed => {
                        let typing = self.egui_ctx.egui_wants_keyboard_input();
                        if !event.repeat
                            && !typing
                            && let Some(command) = input::command(code, self.shift, self.session.flight.mode)
                        {
                            self.command(event_loop, command);
                        }
                        if !typing {
                            self.held.insert(code);
                        }
                    }
                    ElementState::Released => {
                        self.held.remove(&code);
                    }
                }
            }
            WindowEvent::Focused(false) => self.held.clear(),
            WindowEvent::MouseInput { state, button, .. } => {
                let look_button = matches!(button, MouseButton::Left | MouseButton::Right);
                match state {
                    ElementState::Pressed if look_button && !consumed && !self.egui_ctx.egui_wants_pointer_input() => {
                        self.look_from = Some(DVec2::NAN);
                    }
                    ElementState::Released if look_button => self.look_from = None,
                    _ => {}
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                let at = DVec2::new(position.x, position.y);
                if let Some(from) = self.look_from {
                    if from.is_finite() {
                        self.session.flight.look(at - from);
                    }
                    self.look_from = Some(at);
                }
            }
            WindowEvent::MouseWheel { delta, .. } if !consumed => {
                let notches = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / PIXELS_PER_NOTCH,
                };
                self.session.flight.wheel(notches);
            }
            _ => {}
        }
    }
}
