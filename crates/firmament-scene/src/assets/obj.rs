//! Wavefront OBJ (with MTL materials) → [`LoadedMesh`]es, through `tobj`.
//!
//! Faces are triangulated as fans, and every distinct position/texture-coordinate/normal triple
//! becomes one vertex (`tobj`'s `single_index`). Each object or group (`o`, `g`), split again
//! where the material changes, is one mesh with the identity transform. Points and lines are
//! ignored. OBJ texture coordinates already have `(0, 0)` at the lower left: they are used as
//! given.
//!
//! Materials: `Kd` is the base colour (alpha from `d`, else 1) and `map_Kd` the texture, read
//! relative to the OBJ file's folder (a Windows `\` path is tried with `/` as well; leading
//! `-option`s are skipped by taking the last word). `Ka`/`Kd`/`Ks`/`Ke` with a single value
//! mean grey (`r r r`), as in the MTL format. A material library or diffuse map that is missing
//! or malformed is logged (`warn`) and left out; the geometry still loads.
//!
//! Before `tobj` parses the file, face indices are checked against the vertex counts (out of
//! range indices make `tobj` panic or index the wrong vertex), and a parse error is located to
//! its line for the message.

use std::cell::RefCell;
use std::collections::HashMap;
use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use firmament_core::texture::TextureImage;
use glam::DMat4;

use super::limits::Budget;
use super::mesh::{LoadedMesh, RawMesh, finish_mesh};
use super::paths::note_outside;
use super::texture_file;

/// Triangulated, one index per vertex, no points or lines: `tobj`'s `GPU_LOAD_OPTIONS`
/// (`single_index`, `triangulate`, `ignore_points`, `ignore_lines`).
const OPTIONS: tobj::LoadOptions = tobj::GPU_LOAD_OPTIONS;

/// Loads an OBJ file (its contents `bytes`) and the materials it names.
pub(super) fn load(path: &Path, bytes: &[u8], budget: &mut Budget) -> Result<Vec<LoadedMesh>, String> {
    let (positions, indices) = check_face_indices(bytes)?;
    // Bound what `tobj` allocates before it parses: every `v` line, and the fans of every face.
    budget
        .clone()
        .take_mesh(positions, indices, "the file's `v` and `f` lines")?;
    let folder = path.parent().unwrap_or(Path::new(""));
    let problems = RefCell::new(Vec::new());
    // A file out of an untrusted scene's folder is refused, not skipped.
    let refused = RefCell::new(None);
    let shared = RefCell::new(std::mem::replace(budget, Budget::new()));
    let parsed = tobj::load_obj_buf(&mut Cursor::new(bytes), &OPTIONS, |library| {
        let file = folder.join(library);
        if let Err(refusal) = shared.borrow().confined(&file, "material library") {
            refused.borrow_mut().get_or_insert(refusal);
            return Err(tobj::LoadError::OpenFileFailed);
        }
        note_outside(path, &file, "material library");
        load_library(&file, &problems, &mut shared.borrow_mut())
    });
    *budget = shared.into_inner();
    if let Some(refusal) = refused.into_inner() {
        return Err(refusal);
    }
    let (models, materials) = parsed.map_err(|e| describe_error(bytes, e))?;
    for problem in problems.into_inner() {
        tracing::warn!("{}: {problem}; going on without its materials", path.display());
    }
    // A library that failed is in `problems`, already logged.
    let materials = materials.unwrap_or_default();

    // By resolved path: materials that share an image share one decoded texture.
    let mut textures: HashMap<PathBuf, Option<Arc<TextureImage>>> = HashMap::new();
    let mut meshes = Vec::with_capacity(models.len());
    let mut refused_map = None;
    for (i, model) in models.into_iter().enumerate() {
        let label = if model.name.is_empty() {
            format!("object #{i}")
        } else {
            format!("object `{}`", model.name)
        };
        let m = model.mesh;
        if m.indices.is_empty() {
            // `tobj` ends the file with an empty model when the last faces were points or lines.
            continue;
        }
        let n = m.positions.len() / 3;
        budget.take_meshes(1)?;
        budget.take_mesh(n, m.indices.len(), &label)?;
        let normals = match m.normals.len() {
            0 => None,
            len if len == 3 * n => Some(m.normals.chunks_exact(3).map(|v| [v[0], v[1], v[2]]).collect()),
            _ => {
                tracing::warn!(
                    "{}: {label}: only some faces give normals; computing smooth normals for all",
                    path.display()
                );
                None
            }
        };
        let tex_coords = match m.texcoords.len() {
            0 => None,
            len if len == 2 * n => Some(m.texcoords.chunks_exact(2).map(|t| [t[0], t[1]]).collect()),
            _ => {
                tracing::warn!(
                    "{}: {label}: only some faces give texture coordinates; using (0, 0) for all",
                    path.display()
                );
                None
            }
        };
        let raw = RawMesh {
            positions: m.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(),
            normals,
            tex_coords,
            indices: m.indices,
            fog_coords: None,
        };
        let mesh = finish_mesh(raw, path, &label)?;

        let material = m
            .material_id
            .and_then(|id| materials.get(id).map(|material| (id, material)));
        let base_color = material.and_then(|(_, material)| base_color(path, material));
        let texture = material.and_then(|(_, material)| {
            let (file, given) = diffuse_map_path(folder, material)?;
            if let Some(texture) = textures.get(&file) {
                return texture.clone();
            }
            if let Err(refusal) = budget.confined(&file, "diffuse map") {
                refused_map.get_or_insert(refusal);
                return None;
            }
            let texture = diffuse_map(path, material, &file, given, budget).map(Arc::new);
            textures.insert(file, texture.clone());
            texture
        });
        if let Some(refusal) = refused_map.take() {
            return Err(refusal);
        }
        meshes.push(LoadedMesh {
            mesh: Arc::new(mesh),
            transform: DMat4::IDENTITY,
            base_color,
            texture,
        });
    }
    if meshes.is_empty() {
        return Err("the OBJ file has no faces (`f` lines; points and lines are ignored)".to_owned());
    }
    Ok(meshes)
}

/// `Kd` with alpha `d` (else 1), if the material gives a finite one.
fn base_color(path: &Path, material: &tobj::Material) -> Option<[f64; 4]> {
    let [r, g, b] = material.diffuse?;
    let color = [r, g, b, material.dissolve.unwrap_or(1.0)].map(f64::from);
    if color.iter().all(|c| c.is_finite()) {
        Some(color)
    } else {
        tracing::warn!(
            "{}: material `{}`: colour {color:?} is not finite; ignored",
            path.display(),
            material.name
        );
        None
    }
}

/// The file of the material's `map_Kd` image, and the name as given, if it has one.
fn diffuse_map_path<'m>(folder: &Path, material: &'m tobj::Material) -> Option<(PathBuf, &'m str)> {
    let given = material.diffuse_texture.as_deref()?;
    // `map_Kd -s 1 1 1 -bm 0.5 file.png`: options come first, the file name last.
    let name = if given.starts_with('-') {
        given.split_whitespace().last().unwrap_or(given)
    } else {
        given
    };
    let mut file = folder.join(name);
    // Only a name with a backslash is looked up here (an untrusted scene's names are looked up
    // by its confinement, inside the folder, before they are read).
    if name.contains('\\') && !file.exists() {
        file = folder.join(name.replace('\\', "/"));
    }
    Some((file, given))
}

/// The material's `map_Kd` image `file` (`given` in the material), or `None` (logged) when it
/// cannot be loaded.
fn diffuse_map(
    path: &Path,
    material: &tobj::Material,
    file: &Path,
    given: &str,
    budget: &mut Budget,
) -> Option<TextureImage> {
    note_outside(path, file, "diffuse map");
    let loaded = budget
        .read_file(file, "image file")
        .and_then(|bytes| texture_file::decode(&bytes, texture_file::FormatHint::from_path(file), budget));
    match loaded {
        Ok(texture) => Some(texture),
        Err(reason) => {
            tracing::warn!(
                "{}: material `{}`: diffuse map `{given}`: {reason}; going on without it",
                path.display(),
                material.name
            );
            None
        }
    }
}

/// Reads a material library for `tobj`, recording why it could not be read in `problems`.
fn load_library(path: &Path, problems: &RefCell<Vec<String>>, budget: &mut Budget) -> tobj::MTLLoadResult {
    let loaded = budget.read_file(path, "material library").and_then(|bytes| {
        let text = expand_grey_colors(&String::from_utf8_lossy(&bytes))
            .map_err(|e| format!("material library {} is malformed: {e}", path.display()))?;
        tobj::load_mtl_buf(&mut Cursor::new(text))
            .map_err(|e| format!("material library {} is malformed: {e}", path.display()))
    });
    loaded.map_err(|problem| {
        problems.borrow_mut().push(problem);
        tobj::LoadError::OpenFileFailed
    })
}

/// Rewrites `Kd 0.5` as `Kd 0.5 0.5 0.5` (also `Ka`, `Ks`, `Ke`): a single value is allowed by
/// the MTL format, and `tobj` panics on fewer than three.
fn expand_grey_colors(text: &str) -> Result<String, String> {
    let mut out = String::with_capacity(text.len() + 16);
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let keyword = words.next();
        if matches!(keyword, Some("Ka" | "Kd" | "Ks" | "Ke")) {
            let values: Vec<&str> = words.collect();
            match values.as_slice() {
                [grey] if grey.parse::<f32>().is_ok() => {
                    out.push_str(&format!("{} {grey} {grey} {grey}\n", keyword.unwrap_or_default()));
                    continue;
                }
                [_, _, _, ..] => {}
                _ => return Err(format!("line {}: `{}` needs r g b", number + 1, line.trim())),
            }
        }
        out.push_str(line);
        out.push('\n');
    }
    Ok(out)
}

/// Checks every face index against the vertex counts, as `tobj` resolves them (positive: from 1
/// over the whole file; negative: back from the last one read so far). `tobj` does not check
/// them all itself and can panic on huge ones. Returns the number of positions (`v` lines) and
/// of the triangle indices the faces give once triangulated as fans.
fn check_face_indices(bytes: &[u8]) -> Result<(usize, usize), String> {
    const KINDS: [&str; 3] = ["vertex", "texture coordinate", "normal"];
    let kind_of = |keyword: &str| ["v", "vt", "vn"].iter().position(|k| *k == keyword);
    let lines = || {
        bytes
            .split(|b| *b == b'\n')
            .map(|line| std::str::from_utf8(line).unwrap_or(""))
    };
    let mut totals = [0_i64; 3];
    for line in lines() {
        if let Some(kind) = line.split_whitespace().next().and_then(kind_of) {
            totals[kind] += 1;
        }
    }
    let mut so_far = [0_i64; 3];
    let mut indices = 0_usize;
    for (number, line) in lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("f") => {
                let corners = words.clone().count();
                indices = indices.saturating_add(3 * corners.saturating_sub(2));
            }
            Some("l") => {}
            Some(keyword) => {
                if let Some(kind) = kind_of(keyword) {
                    so_far[kind] += 1;
                }
                continue;
            }
            None => continue,
        }
        for word in words {
            for (kind, part) in word.split('/').enumerate().take(3) {
                // Unparsable parts are `tobj`'s to report.
                let Ok(index) = part.parse::<i64>() else { continue };
                let resolved = if index < 0 { so_far[kind] + index } else { index - 1 };
                if index == 0 || resolved < 0 || resolved >= totals[kind] {
                    let rule = if index == 0 {
                        "OBJ indices start at 1".to_owned()
                    } else if index < 0 {
                        format!("only {} are defined before it", so_far[kind])
                    } else {
                        format!("the file has {}", totals[kind])
                    };
                    return Err(format!(
                        "malformed OBJ at line {}: {} index {index} is out of range ({rule}): `{}`",
                        number + 1,
                        KINDS[kind],
                        shorten(line)
                    ));
                }
            }
        }
    }
    Ok((usize::try_from(totals[0]).unwrap_or(usize::MAX), indices))
}

/// The largest OBJ file whose parse errors are located to their line: locating parses about
/// log₂(lines) prefixes of the file, seconds for a file of this size.
const LOCATE_MAX_BYTES: usize = 32 << 20;

/// `tobj`'s error, with the first line at which parsing fails (found by parsing ever shorter
/// prefixes: `tobj` reports no line numbers; not for files over [`LOCATE_MAX_BYTES`]).
fn describe_error(bytes: &[u8], error: tobj::LoadError) -> String {
    if bytes.len() > LOCATE_MAX_BYTES {
        return format!("malformed OBJ: {error} (the file is too large to find the line)");
    }
    let mut ends: Vec<usize> = bytes
        .iter()
        .enumerate()
        .filter(|(_, b)| **b == b'\n')
        .map(|(i, _)| i + 1)
        .collect();
    if ends.last() != Some(&bytes.len()) {
        ends.push(bytes.len());
    }
    let fails = |lines: usize| {
        let prefix = &bytes[..ends[lines - 1]];
        tobj::load_obj_buf(&mut Cursor::new(prefix), &OPTIONS, |_| Ok(Default::default())).is_err()
    };
    if !fails(ends.len()) {
        return format!("malformed OBJ: {error}");
    }
    // The smallest number of lines that fails.
    let (mut low, mut high) = (1, ends.len());
    while low < high {
        let middle = (low + high) / 2;
        if fails(middle) {
            high = middle;
        } else {
            low = middle + 1;
        }
    }
    let start = if high >= 2 { ends[high - 2] } else { 0 };
    let line = String::from_utf8_lossy(&bytes[start..ends[high - 1]]);
    format!("malformed OBJ at line {high}: {error}: `{}`", shorten(&line))
}

/// A line for a message: trimmed, at most 80 characters.
fn shorten(line: &str) -> String {
    let line = line.trim();
    match line.char_indices().nth(80) {
        Some((cut, _)) => format!("{}…", &line[..cut]),
        None => line.to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grey_colours_are_expanded() {
        let text = expand_grey_colors("newmtl a\nKd 0.5\nKs 1 2 3\nd 0.5\n").expect("valid");
        assert_eq!(text, "newmtl a\nKd 0.5 0.5 0.5\nKs 1 2 3\nd 0.5\n");
        assert!(expand_grey_colors("Kd 1 2").expect_err("two").contains("line 1"));
        assert!(expand_grey_colors("newmtl a\nKa").expect_err("none").contains("line 2"));
    }

    #[test]
    fn face_indices_are_checked() {
        let ok = b"v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\nf -3 -2 -1\nvt 0 0\nf 1/1 2/-1 3/1\n";
        assert_eq!(check_face_indices(ok), Ok((3, 9)));
        let error = check_face_indices(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n").expect_err("4");
        assert!(
            error.contains("line 4: vertex index 4 is out of range (the file has 3)"),
            "{error}"
        );
        let error = check_face_indices(b"v 0 0 0\nf -2 1 1\nv 0 0 0\n").expect_err("-2");
        assert!(error.contains("only 1 are defined before it"), "{error}");
        let error = check_face_indices(b"v 0 0 0\nvt 0 0\nf 1/0 1/1 1/1\n").expect_err("0");
        assert!(error.contains("texture coordinate index 0"), "{error}");
        let huge = b"v 0 0 0\nvt 0 0\nf 1/-9223372036854775807 1/1 1/1\n";
        assert!(check_face_indices(huge).is_err());
    }

    #[test]
    fn parse_errors_name_their_line() {
        let text = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 x\nf 1 2 3\n";
        let error = describe_error(text, tobj::LoadError::NormalParseError);
        assert_eq!(error, "malformed OBJ at line 4: normal parse error: `vn 0 0 x`");
    }
}
