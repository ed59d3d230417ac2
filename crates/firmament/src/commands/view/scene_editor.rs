//! The panel's tree of every key of the scene document: numbers drag, flags tick, `#rrggbb`
//! colours open a colour picker, keys with a fixed set of names (models, tone curves, fog modes…)
//! offer those names, lists of tables grow (empty ones too, from a template) and shrink, and
//! every table offers the keys the scene format knows there that it leaves out (coefficients,
//! radii, fog, material keys…), added with the value they take now where the scene has it. Edits
//! go to the document, whose validation says what a bad value breaks.

use std::collections::HashMap;

use firmament_scene::SceneDocument;

use super::session::Session;

/// The tree's state between frames.
#[derive(Debug, Default)]
pub(crate) struct SceneEditor {
    /// The names a string key accepts, by key path (`None`: free text), found once per path.
    variants: HashMap<String, Option<Vec<String>>>,
    /// The keys the format knows in the table at each path, found once per document change.
    known: HashMap<String, Vec<String>>,
}

/// A change to the document's shape, made after the walk.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Grow {
    /// Add the missing key at this path, with its current value.
    Key(String),
    /// Append an entry to the list of tables at this path.
    Entry(String),
}

impl SceneEditor {
    /// Draws the tree; applies an edit to the session's document and rebuilds the scene.
    pub(crate) fn show(&mut self, ui: &mut egui::Ui, session: &mut Session) {
        egui::CollapsingHeader::new("Scene").default_open(true).show(ui, |ui| {
            if let Some(error) = &session.edit_error {
                ui.colored_label(egui::Color32::from_rgb(255, 120, 100), error);
            }
            if session.doc.is_modified() {
                ui.label("modified (save to keep)");
            }
            let mut table = session.doc.table().clone();
            let mut changed = false;
            let mut tree = Tree {
                doc: &session.doc,
                variants: &mut self.variants,
                known: &mut self.known,
                grow: None,
            };
            for (key, value) in table.iter_mut() {
                if key == "preset" {
                    continue;
                }
                changed |= tree.value(ui, key, key, value);
            }
            tree.add_key_menu(ui, "", &table);
            let grow = tree.grow.take();
            if changed {
                *session.doc.table_mut() = table;
            }
            if let Some(grow) = grow {
                let done = match &grow {
                    Grow::Key(path) => session.doc.add_key(path).map(drop),
                    Grow::Entry(path) => session.doc.add_entry(path),
                };
                match done {
                    Ok(()) => changed = true,
                    Err(error) => session.edit_error = Some(error.to_string()),
                }
            }
            if changed {
                self.known.clear();
                session.document_changed();
            }
        });
    }
}

/// One frame's walk over the tree.
struct Tree<'a> {
    doc: &'a SceneDocument,
    variants: &'a mut HashMap<String, Option<Vec<String>>>,
    known: &'a mut HashMap<String, Vec<String>>,
    /// The key or entry asked for this frame.
    grow: Option<Grow>,
}

impl Tree<'_> {
    /// An editor for one TOML value at `path`; whether it changed.
    fn value(&mut self, ui: &mut egui::Ui, label: &str, path: &str, value: &mut toml::Value) -> bool {
        match value {
            toml::Value::Table(table) => egui::CollapsingHeader::new(label)
                .id_salt(path)
                .show(ui, |ui| {
                    let mut changed = false;
                    for (key, child) in table.iter_mut() {
                        changed |= self.value(ui, key, &SceneDocument::key_path(path, key), child);
                    }
                    self.add_key_menu(ui, path, table);
                    changed
                })
                .body_returned
                .unwrap_or(false),
            toml::Value::Array(items) if items.iter().all(toml::Value::is_table) => {
                egui::CollapsingHeader::new(format!("{label} ({})", items.len()))
                    .id_salt(path)
                    .show(ui, |ui| self.list(ui, path, items))
                    .body_returned
                    .unwrap_or(false)
            }
            other => {
                ui.horizontal(|ui| {
                    ui.label(label);
                    self.leaf(ui, path, other)
                })
                .inner
            }
        }
    }

    /// A list of tables (suns, lights, keyframes, objects): each one, and add or remove.
    fn list(&mut self, ui: &mut egui::Ui, path: &str, items: &mut Vec<toml::Value>) -> bool {
        let mut changed = false;
        let mut remove = None;
        for (i, item) in items.iter_mut().enumerate() {
            changed |= self.value(ui, &format!("[{i}]"), &format!("{path}.{i}"), item);
            if ui.small_button(format!("remove [{i}]")).clicked() {
                remove = Some(i);
            }
        }
        if let Some(i) = remove {
            items.remove(i);
            changed = true;
        }
        let add = if items.is_empty() {
            "add an entry"
        } else {
            "add (a copy of the last)"
        };
        if ui.small_button(add).clicked() {
            self.grow = Some(Grow::Entry(path.to_owned()));
        }
        changed
    }

    /// A menu of the keys the format knows in the table at `path` (`""`: the top) that `table`
    /// leaves out.
    fn add_key_menu(&mut self, ui: &mut egui::Ui, path: &str, table: &toml::Table) {
        let doc = self.doc;
        let known = self
            .known
            .entry(path.to_owned())
            .or_insert_with(|| doc.known_keys(path).unwrap_or_default());
        let missing: Vec<&String> = known.iter().filter(|key| !table.contains_key(*key)).collect();
        if missing.is_empty() {
            return;
        }
        egui::ComboBox::from_id_salt(("add key", path))
            .selected_text("add key…")
            .show_ui(ui, |ui| {
                for key in missing {
                    if ui.selectable_label(false, key.as_str()).clicked() {
                        self.grow = Some(Grow::Key(SceneDocument::key_path(path, key)));
                    }
                }
            });
    }

    /// An editor for a number, a flag, a text or a list of plain values.
    fn leaf(&mut self, ui: &mut egui::Ui, path: &str, value: &mut toml::Value) -> bool {
        match value {
            toml::Value::Float(x) => {
                let speed = (x.abs() * 0.01).max(1e-3);
                ui.add(egui::DragValue::new(x).speed(speed).max_decimals(9)).changed()
            }
            toml::Value::Integer(i) => ui.add(egui::DragValue::new(i).speed(1.0)).changed(),
            toml::Value::Boolean(b) => ui.checkbox(b, "").changed(),
            toml::Value::String(text) => self.text(ui, path, text),
            toml::Value::Array(items) => {
                let mut changed = false;
                for (i, item) in items.iter_mut().enumerate() {
                    changed |= self.leaf(ui, &format!("{path}.{i}"), item);
                }
                changed
            }
            toml::Value::Datetime(d) => {
                ui.label(d.to_string());
                false
            }
            toml::Value::Table(_) => false,
        }
    }

    /// A string: a choice among the names the key accepts, a colour, or free text.
    fn text(&mut self, ui: &mut egui::Ui, path: &str, text: &mut String) -> bool {
        let names = self
            .variants
            .entry(path.to_owned())
            .or_insert_with(|| self.doc.accepted_names(path));
        if let Some(names) = names {
            let before = text.clone();
            egui::ComboBox::from_id_salt(path)
                .selected_text(text.as_str())
                .show_ui(ui, |ui| {
                    for name in names.iter() {
                        ui.selectable_value(text, name.clone(), name);
                    }
                });
            return *text != before;
        }
        let mut changed = false;
        if let Some(mut rgb) = hex_colour(text)
            && ui.color_edit_button_srgb(&mut rgb).changed()
        {
            *text = format!("#{:02x}{:02x}{:02x}", rgb[0], rgb[1], rgb[2]);
            changed = true;
        }
        let response = ui.add(egui::TextEdit::singleline(text).desired_width(140.0).id_salt(path));
        changed | response.changed()
    }
}

/// The sRGB bytes of a `#rrggbb` colour.
fn hex_colour(text: &str) -> Option<[u8; 3]> {
    let hex = text.strip_prefix('#')?;
    if hex.len() != 6 || !hex.is_ascii() {
        return None;
    }
    let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
    Some([byte(0)?, byte(2)?, byte(4)?])
}

#[cfg(test)]
mod tests {
    use firmament_scene::SceneSource;

    use super::*;

    #[test]
    fn hex_colours_parse() {
        assert_eq!(hex_colour("#ff8000"), Some([255, 128, 0]));
        assert_eq!(hex_colour("ff8000"), None);
        assert_eq!(hex_colour("#ff80"), None);
        assert_eq!(hex_colour("#gg0000"), None);
    }

    #[test]
    fn keys_with_fixed_names_offer_them_and_free_text_does_not() {
        let doc = SceneDocument::load(SceneSource::Preset("default"), None, &[]).expect("preset");
        assert_eq!(
            doc.accepted_names("sky.model"),
            Some(vec!["gradient".to_owned(), "atmosphere".to_owned(), "clear".to_owned()])
        );
        let curves = doc.accepted_names("display.tone_curve").expect("tone curves");
        assert!(curves.contains(&"aces_fitted".to_owned()), "{curves:?}");
        assert_eq!(doc.accepted_names("time.time_of_day"), None);
        assert_eq!(doc.accepted_names("sky.gradient.keyframes.0.zenith"), None);
    }
}
