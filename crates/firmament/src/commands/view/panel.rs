//! The viewer's panel (egui): time, camera, info, and every key of the scene document, edited
//! live. Edits go through the document and the scene crate's validation, so the panel can set
//! only what a scene file can say, and a value that breaks a rule shows that rule.

use std::path::PathBuf;

use super::flight::FlightMode;

use super::scene_editor::SceneEditor;
use super::session::Session;

/// What the panel asks the app to do after this frame.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Request {
    /// Save the scene (the view on screen) to this file.
    Save(PathBuf),
    /// Save a screenshot: EXR when `true`, else PNG.
    Screenshot {
        /// EXR instead of PNG.
        exr: bool,
    },
}

/// The panel's own state between frames.
#[derive(Debug)]
pub(crate) struct PanelState {
    /// Whether the panel is shown (F1).
    pub(crate) visible: bool,
    /// Whether the info text is shown (NeHe's 1/2).
    pub(crate) show_info: bool,
    /// Where "save scene" writes.
    pub(crate) save_path: String,
    /// The last save's or screenshot's outcome, for the status line.
    pub(crate) status: Option<String>,
    /// Share of the window's pixels the scene is drawn at, in (0, 1] (the panel stays sharp).
    pub(crate) render_scale: f32,
    /// The tree of every scene key.
    editor: SceneEditor,
}

impl PanelState {
    /// A shown panel that saves to `save_path`.
    pub(crate) fn new(save_path: String, render_scale: f32) -> Self {
        Self {
            visible: true,
            show_info: true,
            save_path,
            status: None,
            render_scale,
            editor: SceneEditor::default(),
        }
    }
}

/// What the info section reports about the last frame.
#[derive(Debug, Default, Clone)]
pub(crate) struct FrameInfo {
    /// Wall time per frame, milliseconds, smoothed.
    pub(crate) frame_ms: f64,
    /// GPU time per pass, milliseconds, where the adapter has timestamp queries.
    pub(crate) pass_ms: Option<Vec<(&'static str, f64)>>,
    /// Adapter name, backend and driver.
    pub(crate) adapter: String,
    /// Size the scene is drawn at, pixels.
    pub(crate) scene_size: (u32, u32),
    /// The atmosphere's medium LUTs are being rebuilt (the sky shows the previous medium).
    pub(crate) luts_rebuilding: bool,
}

/// Draws the info text over the scene (top left), NeHe-style.
pub(crate) fn info_overlay(ctx: &egui::Context, session: &Session, info: &FrameInfo) {
    egui::Area::new(egui::Id::unique("firmament info"))
        .anchor(egui::Align2::LEFT_TOP, [8.0, 8.0])
        .interactable(false)
        .show(ctx, |ui| {
            let text = format!(
                "{:.1} ms/frame ({:.0} fps) · {}×{}\n{}  {}\naltitude {}  speed {}/s  heading {:.1}°  pitch {:.1}°",
                info.frame_ms,
                1000.0 / info.frame_ms.max(1e-3),
                info.scene_size.0,
                info.scene_size.1,
                session.describe_moment(),
                session.clock.describe_rate(),
                metres(session.altitude()),
                metres(session.flight.speed(session.altitude())),
                session.flight.heading.to_degrees(),
                session.flight.pitch.to_degrees(),
            );
            ui.label(egui::RichText::new(text).monospace().color(egui::Color32::WHITE));
        });
}

/// Draws the side panel; the requests for the app.
pub(crate) fn side_panel(
    ui: &mut egui::Ui,
    session: &mut Session,
    state: &mut PanelState,
    info: &FrameInfo,
) -> Vec<Request> {
    let mut requests = Vec::new();
    egui::Panel::right("firmament panel")
        .resizable(true)
        .default_size(340.0)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                time_section(ui, session);
                camera_section(ui, session, state);
                info_section(ui, info);
                file_section(ui, session, state, &mut requests);
                state.editor.show(ui, session);
            });
        });
    requests
}

fn time_section(ui: &mut egui::Ui, session: &mut Session) {
    egui::CollapsingHeader::new("Time").default_open(true).show(ui, |ui| {
        ui.label(session.describe_moment());
        ui.horizontal(|ui| {
            let label = if session.clock.paused { "play" } else { "pause" };
            if ui.button(label).clicked() {
                session.clock.toggle_pause();
            }
            if ui.button("slower").clicked() {
                session.clock.slower();
            }
            if ui.button("faster").clicked() {
                session.clock.faster();
            }
            if ui.button("scene's time").clicked() {
                session.clock.offset_seconds = 0.0;
            }
        });
        ui.label(format!("rate {}", session.clock.describe_rate()));
        if let Some(mut hours) = session.hours() {
            // No step: a slider snaps the value it is given, which would stop the clock.
            let slider = egui::Slider::new(&mut hours, 0.0..=24.0).text("time of day, h");
            if ui.add(slider).changed() {
                session.set_hours(hours);
            }
        } else {
            let mut days = session.clock.offset_seconds / 86_400.0;
            let drag = egui::DragValue::new(&mut days)
                .speed(0.01)
                .suffix(" days from the scene's date");
            if ui.add(drag).changed() {
                session.clock.offset_seconds = days * 86_400.0;
            }
            ui.label("(edit time.date_time below for another date)");
        }
    });
}

fn camera_section(ui: &mut egui::Ui, session: &mut Session, state: &mut PanelState) {
    egui::CollapsingHeader::new("Camera").default_open(true).show(ui, |ui| {
        ui.horizontal(|ui| {
            let mut mode = session.flight.mode;
            ui.radio_value(&mut mode, FlightMode::Free, "free (WASD, QE, mouse)");
            ui.radio_value(&mut mode, FlightMode::NeHe, "NeHe (WASD, ZCX)");
            if mode != session.flight.mode {
                session.flight.set_mode(mode);
            }
        });
        ui.horizontal(|ui| {
            if ui.button("go to ground (G)").clicked() {
                session.go_to_ground();
            }
            let orbit = ui.add_enabled(session.planet().is_some(), egui::Button::new("go to orbit (O)"));
            if orbit.clicked() {
                session.go_to_orbit();
            }
        });
        let mut scale = session.flight.speed_scale;
        let speed = egui::Slider::new(&mut scale, 1e-3..=1e3)
            .logarithmic(true)
            .text("speed × (wheel)");
        if ui.add(speed).changed() {
            session.flight.speed_scale = scale;
        }
        let p = session.flight.position;
        ui.label(format!(
            "position [{}, {}, {}]\naltitude {}",
            metres(p.x),
            metres(p.y),
            metres(p.z),
            metres(session.altitude())
        ));
        ui.add(egui::Slider::new(&mut state.render_scale, 0.1..=1.0).text("render scale"));
    });
}

fn info_section(ui: &mut egui::Ui, info: &FrameInfo) {
    egui::CollapsingHeader::new("Info").default_open(true).show(ui, |ui| {
        ui.label(format!(
            "{:.2} ms per frame ({:.1} fps), scene {}×{}",
            info.frame_ms,
            1000.0 / info.frame_ms.max(1e-3),
            info.scene_size.0,
            info.scene_size.1
        ));
        match &info.pass_ms {
            Some(passes) => {
                for (name, ms) in passes {
                    ui.label(format!("  {name}: {ms:.3} ms GPU"));
                }
            }
            None => {
                ui.label("per-pass GPU times: this adapter has no timestamp queries");
            }
        }
        if info.luts_rebuilding {
            ui.label("rebuilding the atmosphere's LUTs (showing the previous medium)…");
        }
        ui.label(&info.adapter);
    });
}

fn file_section(ui: &mut egui::Ui, session: &mut Session, state: &mut PanelState, requests: &mut Vec<Request>) {
    egui::CollapsingHeader::new("Files").default_open(true).show(ui, |ui| {
        ui.horizontal(|ui| {
            ui.add(egui::TextEdit::singleline(&mut state.save_path).desired_width(180.0));
            if ui.button("save scene").clicked() {
                requests.push(Request::Save(PathBuf::from(state.save_path.trim())));
            }
        });
        ui.horizontal(|ui| {
            if ui.button("screenshot PNG (F12)").clicked() {
                requests.push(Request::Screenshot { exr: false });
            }
            if ui.button("EXR (Shift+F12)").clicked() {
                requests.push(Request::Screenshot { exr: true });
            }
        });
        if ui.button("reset scene, camera and time").clicked() {
            session.reset();
            state.status = Some("reset to the scene as loaded".to_owned());
        }
        if let Some(status) = &state.status {
            ui.label(status);
        }
    });
}

/// A length for people: metres, kilometres, or astronomical units.
pub(crate) fn metres(m: f64) -> String {
    const AU: f64 = 1.495_978_707e11;
    let a = m.abs();
    if a >= 0.01 * AU {
        format!("{:.3} AU", m / AU)
    } else if a >= 1e4 {
        format!("{:.1} km", m / 1e3)
    } else {
        format!("{m:.1} m")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_read_well() {
        assert_eq!(metres(2.0), "2.0 m");
        assert_eq!(metres(400_000.0), "400.0 km");
        assert_eq!(metres(1.495_978_707e13), "100.000 AU");
    }
}
