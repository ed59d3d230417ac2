//! [`SceneDocument`]: a scene's fully layered TOML table, edited key by key, built into a
//! [`Scene`] and saved as a complete scene file. It is what the viewer's panel edits and what its
//! "save scene" writes; [`load`] goes through it too, so there is one path from text to
//! scene.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use firmament_core::atmosphere::clouds::CloudLayer;

use crate::assets::Confinement;
use crate::error::SceneError;
use crate::model::Scene;
use crate::{layers, model, presets, validate};

/// The first line of every saved scene file.
const HEADER: &str = "# Written by firmament: a complete scene, every key resolved; it needs no preset.";

/// Where a scene comes from before overrides.
#[derive(Debug, Clone, Copy)]
pub enum SceneSource<'a> {
    /// A built-in preset, by name.
    Preset(&'a str),
    /// TOML text read from `origin` (a path, for messages). A `preset` given alongside replaces
    /// the file's own `preset` key.
    Text {
        /// The TOML text.
        text: &'a str,
        /// Where it came from, for messages (usually the file path).
        origin: &'a str,
    },
}

/// Builds and validates a scene: `source`, with an optional preset to start from, then
/// `overrides` (each `key.path=value`, the value in TOML syntax or a bare string). The same as
/// [`SceneDocument::load`] then [`SceneDocument::scene`].
pub fn load(source: SceneSource<'_>, preset: Option<&str>, overrides: &[String]) -> Result<Scene, SceneError> {
    SceneDocument::load(source, preset, overrides)?.scene()
}

/// Reads a scene file from disk and builds it like [`load`]; relative asset paths resolve against
/// the file's folder. The same as [`SceneDocument::load_file`] then [`SceneDocument::scene`].
pub fn load_file(path: &Path, preset: Option<&str>, overrides: &[String]) -> Result<Scene, SceneError> {
    SceneDocument::load_file(path, preset, overrides)?.scene()
}

impl Scene {
    /// The built-in preset `name` as a scene, to change in code (see the crate docs); an unknown
    /// name is an error with a "did you mean".
    pub fn preset(name: &str) -> Result<Self, SceneError> {
        load(SceneSource::Preset(name), None, &[])
    }
}

/// Where a [`SceneDocument`] came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SceneOrigin {
    /// A built-in preset, by name (the one used: a `preset` given alongside replaces the source's).
    Preset(String),
    /// TOML text with this label, for messages (usually the path it was read from).
    Text(String),
    /// A scene file read from this path by [`SceneDocument::load_file`].
    File(PathBuf),
}

impl std::fmt::Display for SceneOrigin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Preset(name) => write!(f, "preset `{name}`"),
            Self::Text(origin) => f.write_str(origin),
            Self::File(path) => write!(f, "{}", path.display()),
        }
    }
}

/// A scene as its resolved TOML table: every layer (the `default` preset, the named preset, the
/// file, the overrides) merged into one table that holds every key, plus where it came from.
///
/// Edit it with [`set`](Self::set) or [`apply_override`](Self::apply_override) (the `--set`
/// addressing: dotted keys, array indices, one past the end appends), or through
/// [`table_mut`](Self::table_mut); [`scene`](Self::scene) parses and validates the result exactly
/// as [`load`] does. [`save`](Self::save) writes the whole table, so the file gives the
/// identical scene on its own, whatever presets it was built from.
#[derive(Debug, Clone)]
pub struct SceneDocument {
    /// The table as edited.
    table: toml::Table,
    /// The table as loaded (overrides applied), for [`reset`](Self::reset).
    loaded: toml::Table,
    /// Where it came from.
    origin: SceneOrigin,
    /// The folder relative asset paths resolve against; empty: the working directory.
    base_dir: PathBuf,
    /// The folder and limits the scene is held to, when it is a stranger's.
    confinement: Option<Confinement>,
}

impl SceneDocument {
    /// Layers `source` (with an optional preset to start from; it replaces a file's own `preset`
    /// key) and then `overrides` (each `key.path=value`, the value in TOML syntax or a bare
    /// string), without parsing the result into a [`Scene`] yet.
    ///
    /// # Errors
    /// Unknown presets, TOML syntax errors and overrides that cannot be applied. Unknown keys and
    /// broken rules are found by [`scene`](Self::scene).
    pub fn load(source: SceneSource<'_>, preset: Option<&str>, overrides: &[String]) -> Result<Self, SceneError> {
        let (table, origin, base_dir) = match source {
            SceneSource::Preset(name) => {
                let name = preset.unwrap_or(name);
                (
                    presets::resolved_table(name)?,
                    SceneOrigin::Preset(name.to_owned()),
                    PathBuf::new(),
                )
            }
            SceneSource::Text { text, origin } => (
                presets::layer_file(text, origin, preset)?,
                SceneOrigin::Text(origin.to_owned()),
                folder_of(Path::new(origin)),
            ),
        };
        Self::with_overrides(table, origin, base_dir, overrides)
    }

    /// Reads a scene file and layers it like [`load`](Self::load); relative asset paths resolve
    /// against the file's folder.
    ///
    /// # Errors
    /// [`SceneError::Read`] when the file cannot be read, then as [`load`](Self::load).
    pub fn load_file(path: &Path, preset: Option<&str>, overrides: &[String]) -> Result<Self, SceneError> {
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
            path: shown.clone(),
            reason: source.to_string(),
        })?;
        let table = presets::layer_file(&text, &shown, preset)?;
        Self::with_overrides(table, SceneOrigin::File(path.to_path_buf()), folder_of(path), overrides)
    }

    fn with_overrides(
        mut table: toml::Table,
        origin: SceneOrigin,
        base_dir: PathBuf,
        overrides: &[String],
    ) -> Result<Self, SceneError> {
        for item in overrides {
            layers::apply_override(&mut table, item)?;
        }
        Ok(Self {
            loaded: table.clone(),
            table,
            origin,
            base_dir,
            confinement: None,
        })
    }

    /// Holds the scenes this document gives to `confinement` (untrusted mode): every file they
    /// name must resolve inside its folder, and files keep within its limits. Set it before
    /// [`scene`](Self::scene), which then checks the paths before anything is read.
    pub fn confine(&mut self, confinement: Confinement) {
        self.confinement = Some(confinement);
    }

    /// Parses and validates the table as it stands into a [`Scene`] (its `base_dir` is
    /// [`base_dir`](Self::base_dir), its confinement the one given to
    /// [`confine`](Self::confine)); the document is unchanged.
    ///
    /// # Errors
    /// Unknown keys (with a "did you mean"), wrong types and broken rules, each naming the key
    /// path, exactly as [`load`] reports them.
    pub fn scene(&self) -> Result<Scene, SceneError> {
        let mut scene = model::from_table(self.table.clone())?;
        scene.base_dir.clone_from(&self.base_dir);
        scene.confinement.clone_from(&self.confinement);
        validate::validate(&scene)?;
        Ok(scene)
    }

    /// The resolved table: every key of the scene, including `preset` (the name it was built on,
    /// informational: changing it does not re-layer anything).
    pub fn table(&self) -> &toml::Table {
        &self.table
    }

    /// The resolved table, for editors that walk it; [`scene`](Self::scene) checks what they do.
    pub fn table_mut(&mut self) -> &mut toml::Table {
        &mut self.table
    }

    /// The value at a dotted key path, array elements by index (`suns.0.elevation`,
    /// `sky.gradient.keyframes.2.time`); `None` when there is none.
    pub fn get(&self, path: &str) -> Option<&toml::Value> {
        let mut keys = path.split('.');
        let mut node = self.table.get(keys.next()?)?;
        for key in keys {
            node = match node {
                toml::Value::Table(t) => t.get(key)?,
                toml::Value::Array(items) => items.get(key.parse::<usize>().ok()?)?,
                _ => return None,
            };
        }
        Some(node)
    }

    /// Sets the value at a dotted key path, addressed as `--set` does: missing tables are created,
    /// numeric keys index arrays, and the index one past the end appends a table when keys are
    /// left to set in it (`suns.1.azimuth` on a list of one sun). The value is taken as given;
    /// whether it is right for the key is checked by [`scene`](Self::scene).
    ///
    /// # Errors
    /// [`SceneError::BadOverride`] (worded like `--set path=value`) when the path cannot be
    /// reached: an empty part, an index that is no number or past the end, a key inside a value
    /// that is no table. The document is then unchanged.
    pub fn set(&mut self, path: &str, value: toml::Value) -> Result<(), SceneError> {
        let shown = value.to_string();
        layers::set_path(&mut self.table, path, value).map_err(|rule| SceneError::BadOverride {
            item: format!("{path}={shown}"),
            rule,
        })
    }

    /// Applies one `key.path=value` override, exactly as `--set` does (the value in TOML syntax,
    /// else a bare string).
    ///
    /// # Errors
    /// [`SceneError::BadOverride`] as for `--set`.
    pub fn apply_override(&mut self, item: &str) -> Result<(), SceneError> {
        layers::apply_override(&mut self.table, item)
    }

    /// Puts the table back as it was loaded (overrides included), undoing every edit.
    pub fn reset(&mut self) {
        self.table.clone_from(&self.loaded);
    }

    /// Whether the table differs from the one loaded (an edit set back to its old value is no
    /// change).
    pub fn is_modified(&self) -> bool {
        self.table != self.loaded
    }

    /// The folder relative mesh, texture, flare image and coverage map paths resolve against, as
    /// [`Scene::base_dir`]: the scene file's folder; empty (the working directory) for presets.
    pub fn base_dir(&self) -> &Path {
        &self.base_dir
    }

    /// Where the document came from.
    pub fn origin(&self) -> &SceneOrigin {
        &self.origin
    }

    /// The whole resolved table as TOML: a one-line header, then every key, without `preset`.
    /// Layered over `default` (as any scene file is) it gives the identical scene. Asset paths are
    /// written as they stand (relative ones relative to [`base_dir`](Self::base_dir));
    /// [`save`](Self::save) makes them absolute when it writes elsewhere.
    pub fn to_toml_string(&self) -> String {
        render(&self.table)
    }

    /// Writes [`to_toml_string`](Self::to_toml_string) to `path`, atomically: the text goes to a
    /// temporary file in the same folder, which then replaces `path`, so a failed save never
    /// leaves a truncated file. A new file is readable by everyone (0644 on Unix); a file that is
    /// replaced keeps its permissions. The document is not validated (call
    /// [`scene`](Self::scene) first) and is unchanged: it keeps its origin and `base_dir`.
    ///
    /// Relative asset paths (`objects.N.mesh.path`, `objects.N.texture.file`,
    /// `flare.elements.N.file`, `clouds.N.coverage_map`) are rewritten as absolute paths (joined with
    /// [`base_dir`](Self::base_dir) and the working directory) when `path`'s folder is not
    /// `base_dir`, so the saved file names the same files; saved into `base_dir` they stay
    /// relative. Absolute paths are kept as they are.
    ///
    /// # Errors
    /// [`SceneError::Write`] naming `path` and the reason: the folder does not exist or cannot be
    /// written, or an asset path is not valid UTF-8 once made absolute.
    pub fn save(&self, path: &Path) -> Result<(), SceneError> {
        let error = |reason: String| SceneError::Write {
            path: path.display().to_string(),
            reason,
        };
        let folder = match path.parent() {
            Some(folder) if !folder.as_os_str().is_empty() => folder,
            _ => Path::new("."),
        };
        let mut table = self.table.clone();
        if !same_folder(folder, &self.base_dir) {
            absolute_asset_paths(&mut table, &self.base_dir).map_err(error)?;
        }
        let text = render(&table);

        let mut temp = tempfile::Builder::new()
            .prefix(".firmament-scene-")
            .suffix(".tmp")
            .tempfile_in(folder)
            .map_err(|e| {
                error(if folder.is_dir() {
                    format!("cannot create a file in {}: {e}", folder.display())
                } else {
                    format!("{} is not an existing folder", folder.display())
                })
            })?;
        temp.write_all(text.as_bytes())
            .and_then(|()| temp.as_file().sync_all())
            .map_err(|e| error(format!("cannot write the temporary file: {e}")))?;
        let permissions = match std::fs::metadata(path) {
            Ok(existing) => Some(existing.permissions()),
            Err(_) => new_file_permissions(),
        };
        if let Some(permissions) = permissions {
            temp.as_file()
                .set_permissions(permissions)
                .map_err(|e| error(format!("cannot set the file's permissions: {e}")))?;
        }
        temp.persist(path).map_err(|e| error(e.error.to_string()))?;
        Ok(())
    }

    /// The key path of `key` in the table at `path` (`path.key`; `key` alone at the top level,
    /// `path` `""`), as [`get`](Self::get) and [`set`](Self::set) address it.
    pub fn key_path(path: &str, key: &str) -> String {
        if path.is_empty() {
            key.to_owned()
        } else {
            format!("{path}.{key}")
        }
    }

    /// The keys the scene format accepts in the table at `path` (`""`: the top level; `planet`,
    /// `atmosphere`, `suns.0`, `flare.elements.0`), in the format's order: its own answer to a
    /// key it does not know (serde's "unknown field, expected one of"). `None` when the path is no
    /// table of fixed keys, or when another error in the document comes first.
    pub fn known_keys(&self, path: &str) -> Option<Vec<String>> {
        let mut probe = self.table.clone();
        layers::set_path(&mut probe, &Self::key_path(path, PROBE_KEY), toml::Value::Boolean(true)).ok()?;
        let error = serde_path_to_error::deserialize::<_, Scene>(toml::Value::Table(probe)).err()?;
        let message = error.inner().message();
        let expected = message.strip_prefix(&format!("unknown field `{PROBE_KEY}`"))?;
        Some(expected.split('`').skip(1).step_by(2).map(str::to_owned).collect())
    }

    /// The keys [`known_keys`](Self::known_keys) names that the table at `path` leaves out
    /// (taking their defaults): what an editor can add there.
    pub fn missing_keys(&self, path: &str) -> Vec<String> {
        let present = match path {
            "" => Some(&self.table),
            _ => self.get(path).and_then(toml::Value::as_table),
        };
        self.known_keys(path)
            .unwrap_or_default()
            .into_iter()
            .filter(|key| present.is_none_or(|table| !table.contains_key(key)))
            .collect()
    }

    /// Adds the missing key `path` (e.g. `atmosphere.rayleigh_scattering`) with the value it
    /// takes now where the scene gives it (the body's radii and coefficients for `planet.*` and
    /// `atmosphere.*`), else a value of the type the key wants (the first name of a key with a
    /// fixed set, 0, false, an empty list…), which validation may then ask to change. Returns
    /// the value set.
    ///
    /// # Errors
    /// [`SceneError::BadOverride`] as [`set`](Self::set) has it.
    pub fn add_key(&mut self, path: &str) -> Result<toml::Value, SceneError> {
        let value = self
            .scene()
            .ok()
            .and_then(|scene| effective_value(&scene, path))
            .or_else(|| self.value_of_the_right_type(path))
            .unwrap_or(toml::Value::Float(0.0));
        self.set(path, value.clone())?;
        self.fill_required(path)?;
        Ok(self.get(path).cloned().unwrap_or(value))
    }

    /// Adds the keys serde says a table under `path` requires (a mesh's `type`, …), each as
    /// [`add_key`](Self::add_key) fills it.
    fn fill_required(&mut self, path: &str) -> Result<(), SceneError> {
        for _ in 0..MAX_REQUIRED_KEYS {
            match self.first_missing_key() {
                Some(key) if key.starts_with(path) => {
                    let value = self.value_of_the_right_type(&key).unwrap_or(toml::Value::Float(0.0));
                    self.set(&key, value)?;
                }
                _ => break,
            }
        }
        Ok(())
    }

    /// Appends an entry to the list of tables at `path` (`suns`, `clouds`, `lights`, `objects`,
    /// `flare.elements`, `sky.gradient.keyframes`): a copy of the last, or for an empty list a
    /// table of the keys an entry requires (each as [`add_key`](Self::add_key) fills it).
    ///
    /// # Errors
    /// [`SceneError::BadOverride`] when `path` is no list of tables.
    pub fn add_entry(&mut self, path: &str) -> Result<(), SceneError> {
        let bad = |rule: &str| SceneError::BadOverride {
            item: format!("{path}=[…]"),
            rule: rule.to_owned(),
        };
        let mut items = match self.get(path) {
            Some(toml::Value::Array(items)) if items.iter().all(toml::Value::is_table) => items.clone(),
            _ => return Err(bad("the key is no list of tables")),
        };
        let entry = match items.last() {
            Some(last) => last.clone(),
            None => ENTRY_TEMPLATES
                .iter()
                .find(|(list, _)| *list == path)
                .and_then(|(_, text)| text.parse::<toml::Table>().ok())
                .map_or_else(|| toml::Value::Table(toml::Table::new()), toml::Value::Table),
        };
        items.push(entry);
        let index = items.len() - 1;
        self.set(path, toml::Value::Array(items))?;
        self.fill_required(&format!("{path}.{index}"))
    }

    /// The key path of the first required key the table lacks, as serde reports it.
    fn first_missing_key(&self) -> Option<String> {
        let error = serde_path_to_error::deserialize::<_, Scene>(toml::Value::Table(self.table.clone())).err()?;
        let field = error
            .inner()
            .message()
            .strip_prefix("missing field `")?
            .split('`')
            .next()?;
        Some(Self::key_path(&dotted(&error.path().to_string()), field))
    }

    /// The names the string key at `path` accepts, when it has a fixed set (models, tone
    /// curves, fog modes…): the scene format's own answer to a name it does not know ("unknown
    /// variant `…`, expected one of `a`, `b`"). `None` for free text.
    pub fn accepted_names(&self, path: &str) -> Option<Vec<String>> {
        let mut probe = self.clone();
        probe.set(path, toml::Value::String("\u{1}".to_owned())).ok()?;
        let message = probe.scene().err()?.to_string();
        let (_, rest) = message.split_once("unknown variant")?;
        let (_, expected) = rest.split_once("expected ")?;
        let names: Vec<String> = expected.split('`').skip(1).step_by(2).map(str::to_owned).collect();
        (!names.is_empty()).then_some(names)
    }

    /// A value of the type the key at `path` wants: the first that parses there.
    fn value_of_the_right_type(&self, path: &str) -> Option<toml::Value> {
        let names = self.accepted_names(path).and_then(|names| names.into_iter().next());
        let zeros = toml::Value::Array(vec![toml::Value::Float(0.0); 3]);
        let candidates = names.map(toml::Value::String).into_iter().chain([
            toml::Value::Float(0.0),
            toml::Value::Integer(0),
            toml::Value::Boolean(false),
            toml::Value::Table(toml::Table::new()),
            zeros,
            toml::Value::Array(Vec::new()),
            toml::Value::String(String::new()),
        ]);
        candidates.into_iter().find(|candidate| {
            let mut probe = self.table.clone();
            layers::set_path(&mut probe, path, candidate.clone()).is_ok()
                && match serde_path_to_error::deserialize::<_, Scene>(toml::Value::Table(probe)) {
                    Ok(_) => true,
                    // A table missing keys is of the right type: they are filled next.
                    Err(error) => {
                        let at = dotted(&error.path().to_string());
                        let missing = error.inner().message().starts_with("missing field");
                        if at == path || at.starts_with(&format!("{path}.")) {
                            candidate.is_table() && missing
                        } else if path.starts_with(&format!("{at}.")) {
                            // Inside a tagged enum serde only names the enum: the value parsed
                            // if what is left is a key not yet given.
                            missing
                        } else {
                            true
                        }
                    }
                }
        })
    }
}

/// The key [`SceneDocument::known_keys`] asks the format about (no scene has it).
const PROBE_KEY: &str = "\u{1}probe";

/// What the first entry of an empty list starts from where the keys serde requires do not make
/// a valid one (a sun needs a direction); other lists start from those keys alone.
const ENTRY_TEMPLATES: &[(&str, &str)] = &[
    ("suns", "name = \"Sun\"\nazimuth = 180.0\nelevation = 30.0"),
    ("flare.elements", "kind = \"glow\"\nsize = 0.2"),
    (
        "clouds",
        "bottom = 1500.0\ntop = 3000.0\ncoverage = 0.4\ndensity = 0.05\nkind = \"cumulus\"",
    ),
    ("bodies", "preset = \"moon\"\nposition = [384400000.0, 0.0, 0.0]"),
];

/// Required keys [`SceneDocument::add_entry`] fills at most (more would be a loop).
const MAX_REQUIRED_KEYS: usize = 16;

/// A serde path (`suns[0].azimuth`; `.` for the top) as a document key path (`suns.0.azimuth`).
fn dotted(serde_path: &str) -> String {
    if serde_path == "." {
        return String::new();
    }
    serde_path.replace('[', ".").replace(']', "")
}

/// The value the missing key `path` takes in `scene` now, for the keys whose value the scene
/// derives from the body (the planet's shape and the atmosphere's medium) or from other keys
/// (`shadows.enabled`, from the lighting).
fn effective_value(scene: &Scene, path: &str) -> Option<toml::Value> {
    if path == "shadows.enabled" {
        // Absent, it follows the lighting: its value then is what the scene does now.
        return Some(toml::Value::Boolean(scene.shadows_enabled()));
    }
    let float = toml::Value::Float;
    if let Some(rest) = path.strip_prefix("clouds.") {
        // A cloud layer's optional keys: the defaults the entry took.
        let (index, key) = rest.split_once('.')?;
        let entry = scene.clouds.get(index.parse::<usize>().ok()?)?;
        let numbers = |values: &[f64]| toml::Value::Array(values.iter().copied().map(float).collect());
        return Some(match key {
            "wind" => numbers(&entry.wind_mps),
            "seed" => toml::Value::Integer(i64::from(entry.seed)),
            "albedo" => float(entry.albedo),
            "phase" => {
                let default = CloudLayer::new(0.0, 1.0, 0.0, 0.0, entry.kind).phase;
                let [g_forward, g_back, blend] =
                    entry
                        .phase
                        .unwrap_or([default.g_forward, default.g_back, default.blend]);
                numbers(&[g_forward, g_back, blend])
            }
            _ => return None,
        });
    }
    let triple = |v: firmament_core::atmosphere::Spectrum| toml::Value::Array(v.to_array().map(float).to_vec());
    let atmosphere = scene.atmosphere_sky().ok()?.atmosphere;
    let (planet, medium) = (&atmosphere.planet, &atmosphere.medium);
    // The shorthand keys read the three constituents; a medium of free-form terms has none.
    let air = medium.constituents();
    let scale_height = |profile: &firmament_core::atmosphere::DensityProfile| profile.scale_height().map(float);
    Some(match path {
        "planet.equatorial_radius" | "planet.radius" => float(planet.radii.x),
        "planet.polar_radius" => float(planet.radii.z),
        "planet.atmosphere_height" => float(planet.atmosphere_height),
        "atmosphere.rayleigh_scattering" => triple(air?.rayleigh.scattering),
        "atmosphere.rayleigh_scale_height" => scale_height(&air?.rayleigh.density)?,
        "atmosphere.mie_scattering" => triple(air?.mie.scattering),
        "atmosphere.mie_extinction" => triple(air?.mie.extinction),
        "atmosphere.mie_scale_height" => scale_height(&air?.mie.density)?,
        "atmosphere.mie_g" => float(air?.mie.phase.g()),
        "atmosphere.ozone_absorption" => triple(air?.absorber.absorption),
        "atmosphere.ground_albedo" => triple(medium.ground_albedo),
        "atmosphere.wavelengths" => toml::Value::Array(atmosphere.wavelengths.0.map(float).to_vec()),
        _ => return None,
    })
}

/// The folder of a scene file, as [`Scene::base_dir`] has it (empty when the path has none).
fn folder_of(path: &Path) -> PathBuf {
    path.parent().map(Path::to_path_buf).unwrap_or_default()
}

/// The header and the table without `preset`, as TOML (short arrays inline, arrays of tables as
/// `[[...]]` sections).
fn render(table: &toml::Table) -> String {
    let mut table = table.clone();
    table.remove("preset");
    // A table of TOML values always serialises: its keys are strings and it holds no `None`.
    let body = toml::to_string(&table).expect("a TOML table serialises as TOML");
    format!("{HEADER}\n\n{body}")
}

/// `folder` as an absolute path (empty: the working directory), without touching the disk.
fn absolute(folder: &Path) -> std::io::Result<PathBuf> {
    if folder.as_os_str().is_empty() {
        std::env::current_dir()
    } else {
        std::path::absolute(folder)
    }
}

/// Whether two folders are the same: compared resolved (symbolic links followed) when both
/// exist, else as absolute paths.
fn same_folder(a: &Path, b: &Path) -> bool {
    let resolved = |p: &Path| absolute(p).and_then(std::fs::canonicalize);
    match (resolved(a), resolved(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => matches!((absolute(a), absolute(b)), (Ok(a), Ok(b)) if a == b),
    }
}

/// Makes every relative asset path in `table` absolute, joined with `base_dir` (and the working
/// directory when that is relative); `.` parts are dropped, nothing else is resolved.
fn absolute_asset_paths(table: &mut toml::Table, base_dir: &Path) -> Result<(), String> {
    for (key, path) in asset_paths_mut(table) {
        if Path::new(path.as_str()).is_absolute() {
            continue;
        }
        let joined = absolute(&base_dir.join(path.as_str()))
            .map_err(|e| format!("{key}: cannot make {path:?} an absolute path: {e}"))?;
        *path = joined
            .to_str()
            .ok_or_else(|| format!("{key}: the absolute path {} is not valid UTF-8", joined.display()))?
            .to_owned();
    }
    Ok(())
}

/// The string values that name files, with their key paths: `objects.N.mesh.path`,
/// `objects.N.texture.file`, `flare.elements.N.file`, `clouds.N.coverage_map`,
/// `planet.albedo_map`, `planet.water_map` and `bodies.N.albedo_map`.
fn asset_paths_mut(table: &mut toml::Table) -> Vec<(String, &mut String)> {
    let mut paths = Vec::new();
    for (section, value) in table.iter_mut() {
        match (section.as_str(), value) {
            ("objects", toml::Value::Array(objects)) => {
                for (i, object) in objects.iter_mut().enumerate() {
                    let Some(object) = object.as_table_mut() else { continue };
                    for (key, value) in object.iter_mut() {
                        let field = match key.as_str() {
                            "mesh" => "path",
                            "texture" => "file",
                            _ => continue,
                        };
                        if let Some(toml::Value::String(path)) = value.as_table_mut().and_then(|t| t.get_mut(field)) {
                            paths.push((format!("objects.{i}.{key}.{field}"), path));
                        }
                    }
                }
            }
            ("flare", toml::Value::Table(flare)) => {
                if let Some(toml::Value::Array(elements)) = flare.get_mut("elements") {
                    for (i, element) in elements.iter_mut().enumerate() {
                        if let Some(toml::Value::String(path)) = element.as_table_mut().and_then(|t| t.get_mut("file"))
                        {
                            paths.push((format!("flare.elements.{i}.file"), path));
                        }
                    }
                }
            }
            ("planet", toml::Value::Table(planet)) => {
                for (key, value) in planet.iter_mut() {
                    if let ("albedo_map" | "water_map", toml::Value::String(path)) = (key.as_str(), value) {
                        paths.push((format!("planet.{key}"), path));
                    }
                }
            }
            ("bodies", toml::Value::Array(bodies)) => {
                for (i, body) in bodies.iter_mut().enumerate() {
                    if let Some(toml::Value::String(path)) = body.as_table_mut().and_then(|t| t.get_mut("albedo_map")) {
                        paths.push((format!("bodies.{i}.albedo_map"), path));
                    }
                }
            }
            ("clouds", toml::Value::Array(layers)) => {
                for (i, layer) in layers.iter_mut().enumerate() {
                    if let Some(toml::Value::String(path)) =
                        layer.as_table_mut().and_then(|t| t.get_mut("coverage_map"))
                    {
                        paths.push((format!("clouds.{i}.coverage_map"), path));
                    }
                }
            }
            _ => {}
        }
    }
    paths
}

/// Permissions for a newly saved file: readable by everyone, writable by its owner.
#[cfg(unix)]
fn new_file_permissions() -> Option<std::fs::Permissions> {
    use std::os::unix::fs::PermissionsExt as _;
    Some(std::fs::Permissions::from_mode(0o644))
}

/// Permissions for a newly saved file: the temporary file's own.
#[cfg(not(unix))]
fn new_file_permissions() -> Option<std::fs::Permissions> {
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_builds_and_validates() {
        for preset in presets::PRESETS {
            let scene = load(SceneSource::Preset(preset.name), None, &[]);
            assert!(scene.is_ok(), "{}: {scene:?}", preset.name);
        }
    }

    #[test]
    fn fields_in_degrees_keep_their_file_keys() {
        let document = SceneDocument::load(SceneSource::Preset("default"), None, &[]).expect("default");
        let cases: [(&str, &[&str]); 6] = [
            ("camera", &["heading", "pitch", "roll", "fov_y"]),
            ("sun", &["latitude", "declination", "angular_radius", "glow_falloff"]),
            ("sky.gradient", &["zenith_start", "horizon_half_width", "ground_start"]),
            ("planet", &["latitude", "longitude"]),
            ("suns.0", &["azimuth", "elevation", "angular_radius"]),
            ("lights.0", &["spot_cutoff"]),
        ];
        for (path, keys) in cases {
            let known = document.known_keys(path).expect(path);
            assert!(
                keys.iter().all(|key| known.iter().any(|k| k == key)),
                "{path}: {known:?}"
            );
            assert!(known.iter().all(|k| !k.ends_with("_deg")), "{path}: {known:?}");
        }
        let error = load(
            SceneSource::Preset("default"),
            None,
            &["camera.fov_y_deg=40".to_owned()],
        )
        .expect_err("the Rust name is no key");
        assert_eq!(
            error.to_string(),
            "camera.fov_y_deg: unknown key (did you mean `fov_y`?)"
        );
    }
}
