//! firmament's fuzz targets, as plain functions of the input bytes.
//!
//! Each target feeds arbitrary bytes to one parser or loader of `firmament-scene` and checks
//! that it answers with a value or an error, never a panic, a hang or an unbounded allocation.
//! The cargo-fuzz crate in `fuzz/` (run by `scripts/fuzz.sh`, libFuzzer on the nightly toolchain)
//! calls these functions; so does this crate's stable test `tests/fuzz_smoke.rs`, which runs every
//! target over its seed corpus (`seeds/<target>/`), its past crash inputs
//! (`regressions/<target>/`) and a few thousand deterministic mutations of them in
//! `cargo test --workspace`. A panic anywhere, even one a loader catches, is a failure:
//! libFuzzer's panic hook aborts, and the smoke test's hook records it.
//!
//! The targets are listed in [`TARGETS`]; see `docs/RELIABILITY.md` ("Fuzzing and loader limits") for how long each ran.

use std::path::Path;

use firmament_core::astro::CivilDateTime;
use firmament_scene::{SceneDocument, SceneSource, add_seconds, parse_date_time};

/// One fuzz target: its name (the cargo-fuzz target's, and its seed and regression folders') and
/// its function.
#[derive(Debug, Clone, Copy)]
pub struct Target {
    /// The name, as given to `cargo fuzz run` and `scripts/fuzz.sh`.
    pub name: &'static str,
    /// What the bytes are.
    pub input: &'static str,
    /// Runs the target on one input; panics only on a bug.
    pub run: fn(&[u8]),
}

/// Every target.
pub const TARGETS: &[Target] = &[
    Target {
        name: "scene_toml",
        input: "a scene file (UTF-8 TOML), loaded, validated and saved again",
        run: scene_toml,
    },
    Target {
        name: "scene_set",
        input: "a preset name on the first line, then one `--set` override a line",
        run: scene_set,
    },
    Target {
        name: "obj",
        input: "a Wavefront OBJ file",
        run: obj,
    },
    Target {
        name: "gltf",
        input: "a glTF file: JSON (.gltf) or binary (.glb)",
        run: gltf,
    },
    Target {
        name: "glb",
        input: "a GLB's JSON chunk and binary chunk: 2 bytes of JSON length (little-endian), the JSON, the binary",
        run: glb,
    },
    Target {
        name: "texture",
        input: "an image file (PNG, JPEG or OpenEXR)",
        run: texture,
    },
    Target {
        name: "date_time",
        input: "8 bytes of f64 seconds (little-endian), then ISO 8601 text",
        run: date_time,
    },
];

/// The most `--set` overrides [`scene_set`] applies from one input.
const MAX_OVERRIDES: usize = 64;

/// Where the file targets say their input comes from: a folder that does not exist, so the files
/// an input names by relative path are not found (absolute paths are read as a user's would be).
const FUZZ_FOLDER: &str = "/nonexistent-firmament-fuzz";

/// The target named `name`.
pub fn target(name: &str) -> Option<&'static Target> {
    TARGETS.iter().find(|t| t.name == name)
}

/// A scene file: [`SceneDocument::load`] and [`SceneDocument::scene`] (parse, layer over its
/// preset, validate); a scene that loads is saved as text and loaded again, and must give the same
/// scene.
pub fn scene_toml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let origin = format!("{FUZZ_FOLDER}/scene.toml");
    let source = SceneSource::Text { text, origin: &origin };
    let Ok(document) = SceneDocument::load(source, None, &[]) else {
        return;
    };
    check_round_trip(&document, &origin);
}

/// `--set` overrides on a preset: the first line names the preset, each further line is one
/// `key.path=value` (at most 64).
pub fn scene_set(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let mut lines = text.split('\n');
    let preset = lines.next().unwrap_or_default().trim();
    let overrides: Vec<String> = lines.take(MAX_OVERRIDES).map(str::to_owned).collect();
    let Ok(document) = SceneDocument::load(SceneSource::Preset(preset), None, &overrides) else {
        return;
    };
    check_round_trip(&document, &format!("{FUZZ_FOLDER}/{preset}.toml"));
}

/// A document that builds a scene must save to text that builds the same scene (but for the
/// informational `preset`, which the text leaves out, and `base_dir`, the reloaded text's folder).
fn check_round_trip(document: &SceneDocument, origin: &str) {
    let Ok(scene) = document.scene() else {
        return;
    };
    let saved = document.to_toml_string();
    let mut reloaded = SceneDocument::load(SceneSource::Text { text: &saved, origin }, None, &[])
        .and_then(|d| d.scene())
        .unwrap_or_else(|e| panic!("a valid scene saves to text that does not load: {e}\n{saved}"));
    reloaded.preset.clone_from(&scene.preset);
    reloaded.base_dir.clone_from(&scene.base_dir);
    assert!(
        scene == reloaded,
        "a valid scene saves to text that loads as another scene:\n{saved}\nbefore: {scene:?}\nafter: {reloaded:?}"
    );
}

/// An OBJ file, through [`firmament_scene::assets::load_model_bytes`].
pub fn obj(data: &[u8]) {
    model(data, "model.obj");
}

/// A `.gltf` or `.glb` file, through [`firmament_scene::assets::load_model_bytes`].
pub fn gltf(data: &[u8]) {
    model(data, "model.gltf");
}

/// A GLB container built around the input's JSON and binary chunks (so that the fuzzer works
/// on what they say, not on the container's lengths), then loaded as [`gltf`] does.
pub fn glb(data: &[u8]) {
    model(&glb_container(data), "model.glb");
}

/// The GLB file of a [`glb`] input: 2 bytes of JSON length, the JSON, then the binary chunk (no
/// binary chunk when empty). Chunks are padded to 4 bytes as the format asks.
pub fn glb_container(data: &[u8]) -> Vec<u8> {
    let (length, rest) = data.split_at(data.len().min(2));
    let length = match length {
        [a, b] => usize::from(u16::from_le_bytes([*a, *b])),
        _ => 0,
    };
    let (json, bin) = rest.split_at(length.min(rest.len()));
    let padded = |bytes: &[u8], pad: u8| {
        let mut out = bytes.to_vec();
        out.resize(bytes.len().next_multiple_of(4), pad);
        out
    };
    let json = padded(json, b' ');
    let bin = padded(bin, 0);
    let chunk_length = |chunk: &[u8]| u32::try_from(chunk.len()).unwrap_or(u32::MAX).to_le_bytes();
    let total = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2_u32.to_le_bytes());
    out.extend_from_slice(&u32::try_from(total).unwrap_or(u32::MAX).to_le_bytes());
    out.extend_from_slice(&chunk_length(&json));
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    if !bin.is_empty() {
        out.extend_from_slice(&chunk_length(&bin));
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
    }
    out
}

/// Loads `data` as the model file `name` in [`FUZZ_FOLDER`]; every mesh it gives must be valid.
fn model(data: &[u8], name: &str) {
    let path = Path::new(FUZZ_FOLDER).join(name);
    if let Ok(meshes) = firmament_scene::assets::load_model_bytes("fuzz", &path, data) {
        for loaded in meshes {
            if let Err(e) = loaded.mesh.validate() {
                panic!("the loader returned an invalid mesh: {e}");
            }
            if let Some(texture) = &loaded.texture {
                if let Err(e) = texture.validate() {
                    panic!("the loader returned an invalid texture: {e}");
                }
            }
        }
    }
}

/// An image file, through [`firmament_scene::assets::load_texture_bytes`]; a texture it gives
/// must be valid.
pub fn texture(data: &[u8]) {
    let path = Path::new(FUZZ_FOLDER).join("texture.png");
    if let Ok(texture) = firmament_scene::assets::load_texture_bytes("fuzz", &path, data) {
        if let Err(e) = texture.validate() {
            panic!("the loader returned an invalid texture: {e}");
        }
    }
}

/// ISO 8601 text through [`parse_date_time`] (a date it accepts must be valid), moved by the
/// input's seconds with [`add_seconds`]; the same seconds also move a date-time made of the
/// input's raw bytes, which need not be valid.
pub fn date_time(data: &[u8]) {
    let (head, rest) = data.split_at(data.len().min(8));
    let mut seconds = [0_u8; 8];
    seconds[..head.len()].copy_from_slice(head);
    let seconds = f64::from_le_bytes(seconds);
    if let Ok(text) = std::str::from_utf8(rest) {
        if let Ok(civil) = parse_date_time(text) {
            if let Err(e) = civil.validate() {
                panic!("parse_date_time({text:?}) gave an invalid date-time {civil:?}: {e}");
            }
            let moved = add_seconds(&civil, seconds);
            let _ = moved.julian_date();
            if seconds.is_finite() && seconds.abs() < 1.0e9 {
                // Far inside chrono's range: the result must be a valid date-time too.
                let back = add_seconds(&moved, -seconds);
                if let Err(e) = moved.validate().and(back.validate()) {
                    panic!("add_seconds({civil:?}, {seconds}) gave {moved:?}, back {back:?}: {e}");
                }
            }
        }
    }
    // Any civil date-time, as a caller may build one: add_seconds must not panic.
    let word = |i: usize| {
        let mut bytes = [0_u8; 4];
        for (j, b) in bytes.iter_mut().enumerate() {
            *b = rest.get(i * 4 + j).copied().unwrap_or(0);
        }
        bytes
    };
    let float = |i: usize| f64::from(f32::from_le_bytes(word(i)));
    let raw = CivilDateTime {
        year: i32::from_le_bytes(word(0)),
        month: u32::from_le_bytes(word(1)),
        day: u32::from_le_bytes(word(2)),
        hour: u32::from_le_bytes(word(3)),
        minute: u32::from_le_bytes(word(4)),
        second: float(5),
        offset_hours: float(6),
    };
    let moved = add_seconds(&raw, seconds);
    let _ = moved.julian_date();
}
