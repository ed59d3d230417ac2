//! glTF 2.0 (`.gltf` JSON with external or base64 `data:` buffers, or binary `.glb`) →
//! [`LoadedMesh`]es.
//!
//! The `gltf` crate parses and validates the document; buffers, accessors and images are read
//! here, with every offset and length checked (a malformed file is an error, never a panic).
//!
//! The node hierarchy of the default scene (else the first scene; else every node that is no
//! node's child) is walked from its roots, each node's transform (a matrix, or
//! translation · rotation · scale with the rotation normalised) composed onto its parent's. Every
//! triangle-list primitive of a node's mesh gives one [`LoadedMesh`] with the node's world matrix
//! as its transform (a mesh used by several nodes appears once per node). Other primitive modes
//! are skipped (`warn`); skins and morph targets are ignored (`warn`): meshes are drawn in their
//! bind pose with the node's transform.
//!
//! Attributes read: `POSITION` (float VEC3), `NORMAL` (float VEC3), the `TEXCOORD_n` set that
//! the base colour texture names (`TEXCOORD_0` without one; float, or normalised unsigned byte
//! or short, VEC2) with `t = 1 − v`, and the indices (unsigned byte, short or int; `0..count`
//! without). Sparse accessors are applied. The material's `baseColorFactor` is the base colour
//! (none without a material) and its base colour texture's image the texture (PNG or JPEG);
//! samplers, `KHR_texture_transform` and the other material properties are ignored. A file that
//! *requires* any extension is refused.

use std::borrow::Cow;
use std::collections::{HashMap, HashSet};
use std::path::Path;
use std::sync::Arc;

use super::texture_file::FormatHint;
use ::gltf::accessor::sparse::IndexType;
use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::mesh::{Mode, Semantic};
use ::gltf::scene::Transform;
use ::gltf::{Accessor, Document, Gltf, Node, Primitive};
use base64::Engine as _;
use base64::alphabet;
use base64::engine::{DecodePaddingMode, GeneralPurpose, GeneralPurposeConfig};
use firmament_core::classic::mesh::Mesh;
use firmament_core::texture::TextureImage;
use glam::{DMat4, DQuat, DVec3};

use super::limits::Budget;
use super::mesh::{LoadedMesh, RawMesh, finish_mesh};
use super::paths::note_outside;
use super::texture_file;

/// Standard base64, padding optional (exporters differ).
const BASE64: GeneralPurpose = GeneralPurpose::new(
    &alphabet::STANDARD,
    GeneralPurposeConfig::new().with_decode_padding_mode(DecodePaddingMode::Indifferent),
);

/// The most components one accessor may hold (2 GiB as `f64`s).
const MAX_ACCESSOR_VALUES: usize = 1 << 28;

/// The most validation problems quoted in a message.
const MAX_PROBLEMS_SHOWN: usize = 5;

/// Loads a `.gltf` or `.glb` file whose contents are `bytes`.
pub(super) fn load(path: &Path, bytes: &[u8], budget: &mut Budget) -> Result<Vec<LoadedMesh>, String> {
    check_glb_length(bytes)?;
    let Gltf { document, blob } = Gltf::from_slice_without_validation(bytes).map_err(describe_parse_error)?;
    let root = document.into_json();
    check_position_accessors(&root)?;
    check_image_sources(&root)?;
    let document = Document::from_json(root).map_err(describe_parse_error)?;
    if let Some(extension) = document.extensions_required().next() {
        return Err(format!(
            "the file requires the glTF extension {extension}, which firmament does not support"
        ));
    }

    // The nodes that draw a mesh, with their world matrices, before any data is read.
    let roots: Vec<Node<'_>> = match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            let children: HashSet<usize> = document.nodes().flat_map(|n| n.children()).map(|c| c.index()).collect();
            document.nodes().filter(|n| !children.contains(&n.index())).collect()
        }
    };
    let mut visited = vec![false; document.nodes().len()];
    let mut stack: Vec<(Node<'_>, DMat4)> = roots.into_iter().rev().map(|n| (n, DMat4::IDENTITY)).collect();
    let mut drawn: Vec<(::gltf::Mesh<'_>, usize, DMat4)> = Vec::new();
    while let Some((node, parent)) = stack.pop() {
        let seen = visited
            .get_mut(node.index())
            .ok_or_else(|| format!("node {} does not exist", node.index()))?;
        if std::mem::replace(seen, true) {
            return Err(format!(
                "node {} is reached twice from the scene's roots (glTF node hierarchies must be trees: a cycle, or \
                 a node with two parents)",
                node.index()
            ));
        }
        let world = parent * local_transform(&node)?;
        if let Some(mesh) = node.mesh() {
            if node.skin().is_some() {
                tracing::warn!(
                    "{}: node {}: skinning is ignored; its mesh is drawn in the bind pose",
                    path.display(),
                    node.index()
                );
            }
            let triangle_lists = mesh.primitives().filter(|p| p.mode() == Mode::Triangles).count();
            budget.take_meshes(triangle_lists)?;
            drawn.push((mesh, node.index(), world));
        }
        let children: Vec<Node<'_>> = node.children().collect();
        stack.extend(children.into_iter().rev().map(|c| (c, world)));
    }

    let buffers = load_buffers(&document, path, blob, budget)?;
    let mut loader = Loader {
        path,
        buffers,
        budget,
        primitives: HashMap::new(),
        images: HashMap::new(),
    };
    let (mut meshes, mut skipped) = (Vec::new(), 0_usize);
    for (mesh, _, world) in drawn {
        for primitive in mesh.primitives() {
            match loader.primitive(&mesh, &primitive)? {
                Some(loaded) => meshes.push(LoadedMesh {
                    transform: world,
                    ..loaded
                }),
                None => skipped += 1,
            }
        }
    }
    if meshes.is_empty() {
        return Err(if skipped > 0 {
            format!("the scene has no triangles: its {skipped} primitives are points, lines, strips or fans")
        } else {
            "the scene has no meshes".to_owned()
        });
    }
    Ok(meshes)
}

/// Checks that a GLB header's length covers at least the header: `gltf` subtracts the header's
/// size from it unchecked (an overflow panic in builds with overflow checks).
fn check_glb_length(bytes: &[u8]) -> Result<(), String> {
    if let Some([b'g', b'l', b'T', b'F', _, _, _, _, a, b, c, d, ..]) = bytes.get(..12) {
        let length = u32::from_le_bytes([*a, *b, *c, *d]);
        if length < 12 {
            return Err(format!(
                "malformed GLB file: its header gives a length of {length} bytes, less than the header's 12"
            ));
        }
    }
    Ok(())
}

/// Checks that every `POSITION` attribute names an accessor that exists: `gltf`'s validation
/// looks that accessor up before checking the index, and panics on a bad one.
fn check_position_accessors(root: &::gltf::json::Root) -> Result<(), String> {
    let positions = ::gltf::json::validation::Checked::Valid(Semantic::Positions);
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            if let Some(index) = primitive.attributes.get(&positions) {
                if index.value() >= root.accessors.len() {
                    return Err(format!(
                        "invalid glTF: meshes[{m}].primitives[{p}].attributes.POSITION: accessor {} does not exist \
                         (the file has {})",
                        index.value(),
                        root.accessors.len()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Checks that every image has a source `gltf` can give: a `uri`, or a `bufferView` with a
/// `mimeType` (`gltf` unwraps both without checking, and panics on an image without).
fn check_image_sources(root: &::gltf::json::Root) -> Result<(), String> {
    for (i, image) in root.images.iter().enumerate() {
        match (&image.uri, &image.buffer_view, &image.mime_type) {
            (_, Some(_), None) => {
                return Err(format!(
                    "invalid glTF: images[{i}]: an image in a buffer view needs a mimeType"
                ));
            }
            (None, None, _) => {
                return Err(format!("invalid glTF: images[{i}] has neither a uri nor a bufferView"));
            }
            _ => {}
        }
    }
    Ok(())
}

/// `gltf`'s parse error, labelled, with at most [`MAX_PROBLEMS_SHOWN`] validation problems.
fn describe_parse_error(error: ::gltf::Error) -> String {
    match error {
        ::gltf::Error::Validation(problems) => {
            let shown: Vec<String> = problems
                .iter()
                .take(MAX_PROBLEMS_SHOWN)
                .map(|(path, problem)| format!("{path}: {problem}"))
                .collect();
            let more = problems.len().saturating_sub(MAX_PROBLEMS_SHOWN);
            let more = if more > 0 {
                format!(" (and {more} more)")
            } else {
                String::new()
            };
            format!("invalid glTF: {}{more}", shown.join("; "))
        }
        ::gltf::Error::Binary(e) => format!("malformed GLB file: {e}"),
        ::gltf::Error::Deserialize(e) => format!("malformed glTF JSON: {e}"),
        other => format!("cannot parse the glTF file: {other}"),
    }
}

/// A node's own transform.
fn local_transform(node: &Node<'_>) -> Result<DMat4, String> {
    let matrix = match node.transform() {
        Transform::Matrix { matrix } => DMat4::from_cols_array_2d(&matrix.map(|column| column.map(f64::from))),
        Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            let rotation = DQuat::from_array(rotation.map(f64::from));
            let length = rotation.length();
            if !(length.is_finite() && length > 0.0) {
                return Err(format!("node {}: rotation {rotation} is not a rotation", node.index()));
            }
            DMat4::from_scale_rotation_translation(
                DVec3::from(scale.map(f64::from)),
                rotation * length.recip(),
                DVec3::from(translation.map(f64::from)),
            )
        }
    };
    if matrix.is_finite() {
        Ok(matrix)
    } else {
        Err(format!("node {}: its transform is not finite", node.index()))
    }
}

/// The data of every buffer: the GLB binary chunk, a `data:` URI or a file.
fn load_buffers(
    document: &Document,
    path: &Path,
    mut blob: Option<Vec<u8>>,
    budget: &mut Budget,
) -> Result<Vec<Vec<u8>>, String> {
    document
        .buffers()
        .map(|buffer| {
            let what = format!("buffer {}", buffer.index());
            let data = match buffer.source() {
                ::gltf::buffer::Source::Bin => blob
                    .take()
                    .ok_or_else(|| format!("{what} is the GLB binary chunk, which the file does not have"))?,
                ::gltf::buffer::Source::Uri(uri) => read_uri(uri, path, &what, budget)?.0,
            };
            if data.len() < buffer.length() {
                return Err(format!(
                    "{what} holds {} bytes, less than the {} the file declares",
                    data.len(),
                    buffer.length()
                ));
            }
            Ok(data)
        })
        .collect()
}

/// The bytes a URI names (a base64 `data:` URI, or a file relative to the folder of the glTF
/// file `path` or as a `file:` URI) and the image format its media type or file extension
/// suggests; what is decoded or read is taken from `budget`.
pub(super) fn read_uri(
    uri: &str,
    path: &Path,
    what: &str,
    budget: &mut Budget,
) -> Result<(Vec<u8>, Option<FormatHint>), String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((header, payload)) = rest.split_once(',') else {
            return Err(format!("{what}: malformed data URI (no `,`)"));
        };
        let Some(media_type) = header.strip_suffix(";base64") else {
            return Err(format!("{what}: only base64 data URIs are supported"));
        };
        let payload = payload.trim();
        // Three bytes for every four characters, at most.
        budget.take_bytes((payload.len() as u64).div_ceil(4) * 3, &format!("{what}'s data URI"))?;
        let bytes = BASE64
            .decode(payload)
            .map_err(|e| format!("{what}: bad base64 in its data URI: {e}"))?;
        return Ok((bytes, FormatHint::from_mime_type(media_type)));
    }
    let relative = match uri_scheme(uri) {
        None => true,
        Some(scheme) if scheme.eq_ignore_ascii_case("file") => false,
        Some(scheme) => {
            return Err(format!(
                "{what}: URI scheme `{scheme}:` is not supported (only relative paths, file: and data: URIs)"
            ));
        }
    };
    let folder = path.parent().unwrap_or(Path::new(""));
    let file = if relative {
        folder.join(percent_decode(uri).map_err(|e| format!("{what}: URI `{uri}`: {e}"))?)
    } else {
        // `file:///abs/path` or `file:/abs/path`.
        let rest = &uri[5..];
        let rest = rest.strip_prefix("//").unwrap_or(rest);
        Path::new(&percent_decode(rest).map_err(|e| format!("{what}: URI `{uri}`: {e}"))?).to_path_buf()
    };
    note_outside(path, &file, what);
    let bytes = budget.read_file(&file, &format!("the file of {what}"))?;
    Ok((bytes, FormatHint::from_path(&file)))
}

/// A URI's scheme (`http` in `http://…`), if it has one. A single letter is taken for a
/// Windows drive, not a scheme.
fn uri_scheme(uri: &str) -> Option<&str> {
    let (scheme, _) = uri.split_once(':')?;
    let mut chars = scheme.chars();
    let valid = chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'));
    (valid && scheme.len() > 1).then_some(scheme)
}

/// Decodes `%xx` escapes; the result must be UTF-8.
fn percent_decode(text: &str) -> Result<String, String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("bad percent escape at byte {i}"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "not UTF-8 once percent escapes are decoded".to_owned())
}

/// Which component types an attribute may have.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Components {
    /// `FLOAT` only.
    Float,
    /// `FLOAT`, or normalised `UNSIGNED_BYTE` or `UNSIGNED_SHORT` (texture coordinates).
    FloatOrUnsignedNormalized,
    /// `UNSIGNED_BYTE`, `UNSIGNED_SHORT` or `UNSIGNED_INT`, not normalised (indices).
    Index,
}

impl Components {
    fn allow(self, data_type: DataType, normalized: bool) -> bool {
        match self {
            Self::Float => data_type == DataType::F32,
            Self::FloatOrUnsignedNormalized => {
                data_type == DataType::F32 || (normalized && matches!(data_type, DataType::U8 | DataType::U16))
            }
            Self::Index => !normalized && matches!(data_type, DataType::U8 | DataType::U16 | DataType::U32),
        }
    }

    fn describe(self) -> &'static str {
        match self {
            Self::Float => "FLOAT",
            Self::FloatOrUnsignedNormalized => "FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT",
            Self::Index => "UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT",
        }
    }
}

/// A file's buffers, and the primitives and images read so far.
struct Loader<'a> {
    /// The glTF file, for messages and the folder of its URIs.
    path: &'a Path,
    /// Every buffer's data.
    buffers: Vec<Vec<u8>>,
    /// What the file may still allocate.
    budget: &'a mut Budget,
    /// By (mesh, primitive) index; `None` for skipped primitives. Transform left at identity.
    primitives: HashMap<(usize, usize), Option<LoadedMesh>>,
    /// By image index.
    images: HashMap<usize, Arc<TextureImage>>,
}

impl Loader<'_> {
    /// A primitive as a [`LoadedMesh`] (identity transform), or `None` when it is skipped.
    fn primitive(&mut self, mesh: &::gltf::Mesh<'_>, primitive: &Primitive<'_>) -> Result<Option<LoadedMesh>, String> {
        let key = (mesh.index(), primitive.index());
        if let Some(loaded) = self.primitives.get(&key) {
            return Ok(loaded.clone());
        }
        let label = match mesh.name() {
            Some(name) => format!("mesh {} (`{name}`) primitive {}", mesh.index(), primitive.index()),
            None => format!("mesh {} primitive {}", mesh.index(), primitive.index()),
        };
        let loaded = if primitive.mode() == Mode::Triangles {
            Some(self.read_primitive(primitive, &label)?)
        } else {
            tracing::warn!(
                "{}: {label}: skipping a {:?} primitive (only triangle lists are drawn)",
                self.path.display(),
                primitive.mode()
            );
            None
        };
        self.primitives.insert(key, loaded.clone());
        Ok(loaded)
    }

    fn read_primitive(&mut self, primitive: &Primitive<'_>, label: &str) -> Result<LoadedMesh, String> {
        let Some(positions) = primitive.get(&Semantic::Positions) else {
            return Err(format!("{label} has no POSITION attribute"));
        };
        let count = positions.count();
        // The declared sizes, before any of them is read.
        let index_count = primitive.indices().map_or(count, |indices| indices.count());
        self.budget.take_mesh(count, index_count, label)?;
        if primitive.morph_targets().len() > 0 {
            tracing::warn!("{}: {label}: morph targets are ignored", self.path.display());
        }
        let attribute =
            |semantic, dimensions, components| self.attribute(primitive, label, semantic, dimensions, components);
        let positions: Vec<[f32; 3]> = attribute(Semantic::Positions, Dimensions::Vec3, Components::Float)?
            .unwrap_or_default()
            .chunks_exact(3)
            .map(|p| [p[0] as f32, p[1] as f32, p[2] as f32])
            .collect();
        let normals: Option<Vec<[f32; 3]>> =
            attribute(Semantic::Normals, Dimensions::Vec3, Components::Float)?.map(|n| {
                n.chunks_exact(3)
                    .map(|n| [n[0] as f32, n[1] as f32, n[2] as f32])
                    .collect()
            });

        let material = primitive.material();
        let pbr = material.pbr_metallic_roughness();
        let base_color = material.index().map(|_| pbr.base_color_factor().map(f64::from));
        let info = pbr.base_color_texture();
        let set = info.as_ref().map_or(0, |info| info.tex_coord());
        let texture = match &info {
            Some(info) => Some(self.image(&info.texture().source())?),
            None => None,
        };
        let tex_coords = self
            .attribute(
                primitive,
                label,
                Semantic::TexCoords(set),
                Dimensions::Vec2,
                Components::FloatOrUnsignedNormalized,
            )?
            .map(|t| t.chunks_exact(2).map(|t| [t[0] as f32, (1.0 - t[1]) as f32]).collect());
        if tex_coords.is_none() && texture.is_some() {
            tracing::warn!(
                "{}: {label}: the base colour texture uses TEXCOORD_{set}, which the primitive does not have; \
                 using (0, 0)",
                self.path.display()
            );
        }
        let indices = match primitive.indices() {
            Some(accessor) => self
                .read(
                    &accessor,
                    &format!("{label}: indices"),
                    Dimensions::Scalar,
                    Components::Index,
                )?
                .into_iter()
                // Whole numbers below 2³² (read from unsigned integers).
                .map(|i| i as u32)
                .collect(),
            None => {
                let count = u32::try_from(count)
                    .map_err(|_| format!("{label}: {count} vertices without indices are too many"))?;
                (0..count).collect()
            }
        };

        let fog_coords = self
            .attribute(
                primitive,
                label,
                Semantic::Extras("FOG_COORD".to_owned()),
                Dimensions::Scalar,
                Components::Float,
            )?
            .map(|c| c.into_iter().map(|c| c as f32).collect());
        let raw = RawMesh {
            positions,
            normals,
            tex_coords,
            indices,
            fog_coords,
        };
        let mesh: Mesh = finish_mesh(raw, self.path, label)?;
        Ok(LoadedMesh {
            mesh: Arc::new(mesh),
            transform: DMat4::IDENTITY,
            base_color,
            texture,
        })
    }

    /// A vertex attribute's values, if the primitive has it (as many as it has positions).
    fn attribute(
        &self,
        primitive: &Primitive<'_>,
        label: &str,
        semantic: Semantic,
        dimensions: Dimensions,
        components: Components,
    ) -> Result<Option<Vec<f64>>, String> {
        let Some(accessor) = primitive.get(&semantic) else {
            return Ok(None);
        };
        let name = semantic.to_string();
        let count = primitive.get(&Semantic::Positions).map_or(0, |p| p.count());
        if accessor.count() != count {
            return Err(format!(
                "{label}: {name} has {} elements but POSITION has {count}",
                accessor.count()
            ));
        }
        self.read(&accessor, &format!("{label}: {name}"), dimensions, components)
            .map(Some)
    }

    /// An accessor's values as `f64`s (normalised integers mapped to `[0, 1]` or `[−1, 1]`),
    /// after checking its type.
    fn read(
        &self,
        accessor: &Accessor<'_>,
        what: &str,
        dimensions: Dimensions,
        components: Components,
    ) -> Result<Vec<f64>, String> {
        let what = format!("{what} (accessor {})", accessor.index());
        if accessor.dimensions() != dimensions || !components.allow(accessor.data_type(), accessor.normalized()) {
            return Err(format!(
                "{what} is {:?} of {:?}{}; firmament reads {dimensions:?} of {}",
                accessor.dimensions(),
                accessor.data_type(),
                if accessor.normalized() { " (normalized)" } else { "" },
                components.describe()
            ));
        }
        read_accessor(accessor, &self.buffers).map_err(|e| format!("{what}: {e}"))
    }

    /// An image, decoded and flipped (bottom row first).
    fn image(&mut self, image: &::gltf::image::Image<'_>) -> Result<Arc<TextureImage>, String> {
        if let Some(texture) = self.images.get(&image.index()) {
            return Ok(texture.clone());
        }
        let what = match image.name() {
            Some(name) => format!("image {} (`{name}`)", image.index()),
            None => format!("image {}", image.index()),
        };
        let (bytes, hint): (Cow<'_, [u8]>, Option<FormatHint>) = match image.source() {
            ::gltf::image::Source::View { view, mime_type } => (
                Cow::Borrowed(view_bytes(&view, &self.buffers).map_err(|e| format!("{what}: {e}"))?),
                FormatHint::from_mime_type(mime_type),
            ),
            ::gltf::image::Source::Uri { uri, mime_type } => {
                let (bytes, hint) = read_uri(uri, self.path, &what, self.budget)?;
                (
                    Cow::Owned(bytes),
                    mime_type.and_then(FormatHint::from_mime_type).or(hint),
                )
            }
        };
        let texture = Arc::new(texture_file::decode(&bytes, hint, self.budget).map_err(|e| format!("{what}: {e}"))?);
        self.images.insert(image.index(), Arc::clone(&texture));
        Ok(texture)
    }
}

/// The bytes of a buffer view.
fn view_bytes<'b>(view: &::gltf::buffer::View<'_>, buffers: &'b [Vec<u8>]) -> Result<&'b [u8], String> {
    let buffer = buffers
        .get(view.buffer().index())
        .ok_or_else(|| format!("buffer view {} names a missing buffer", view.index()))?;
    view.offset()
        .checked_add(view.length())
        .and_then(|end| buffer.get(view.offset()..end))
        .ok_or_else(|| {
            format!(
                "buffer view {} (bytes {} to {} + {}) does not fit in buffer {} ({} bytes)",
                view.index(),
                view.offset(),
                view.offset(),
                view.length(),
                view.buffer().index(),
                buffer.len()
            )
        })
}

/// Every component of an accessor, sparse substitutions applied, bounds checked.
fn read_accessor(accessor: &Accessor<'_>, buffers: &[Vec<u8>]) -> Result<Vec<f64>, String> {
    let data_type = accessor.data_type();
    let normalized = accessor.normalized();
    let components = accessor.dimensions().multiplicity();
    let element = components * data_type.size();
    let count = accessor.count();
    if count == 0 {
        return Err("it has no elements (count 0)".to_owned());
    }
    let total = count
        .checked_mul(components)
        .filter(|total| *total <= MAX_ACCESSOR_VALUES)
        .ok_or_else(|| format!("{count} elements are too many"))?;

    let mut values = match accessor.view() {
        // Sparse-only accessors start from zeros.
        None => vec![0.0; total],
        Some(view) => {
            let data = view_bytes(&view, buffers)?;
            let stride = view.stride().unwrap_or(element);
            if stride < element {
                return Err(format!(
                    "buffer view {} has a byte stride of {stride}, less than its {element}-byte elements",
                    view.index()
                ));
            }
            let offset = accessor.offset();
            let fits = (count - 1)
                .checked_mul(stride)
                .and_then(|n| n.checked_add(element))
                .and_then(|n| n.checked_add(offset))
                .is_some_and(|end| end <= data.len());
            if !fits {
                return Err(format!(
                    "{count} elements of {element} bytes every {stride} from byte {offset} do not fit in buffer view {} \
                     ({} bytes)",
                    view.index(),
                    data.len()
                ));
            }
            let mut values = Vec::with_capacity(total);
            for i in 0..count {
                for c in 0..components {
                    values.push(component(
                        data,
                        offset + i * stride + c * data_type.size(),
                        data_type,
                        normalized,
                    )?);
                }
            }
            values
        }
    };

    if let Some(sparse) = accessor.sparse() {
        let substitutions = sparse.count();
        if substitutions == 0 || substitutions > count {
            return Err(format!("sparse count {substitutions} is not in 1..={count}"));
        }
        let indices = sparse.indices();
        let (index_type, index_size) = match indices.index_type() {
            IndexType::U8 => (DataType::U8, 1),
            IndexType::U16 => (DataType::U16, 2),
            IndexType::U32 => (DataType::U32, 4),
        };
        let index_data = sized(
            view_bytes(&indices.view(), buffers)?,
            indices.offset(),
            substitutions,
            index_size,
        )
        .ok_or("the sparse indices do not fit in their buffer view")?;
        let value_data = sized(
            view_bytes(&sparse.values().view(), buffers)?,
            sparse.values().offset(),
            substitutions,
            element,
        )
        .ok_or("the sparse values do not fit in their buffer view")?;
        for j in 0..substitutions {
            let index = component(index_data, j * index_size, index_type, false)? as usize;
            if index >= count {
                return Err(format!("sparse index {index} is out of range (count {count})"));
            }
            for c in 0..components {
                values[index * components + c] =
                    component(value_data, j * element + c * data_type.size(), data_type, normalized)?;
            }
        }
    }
    Ok(values)
}

/// `count` tightly packed `size`-byte elements of `data` from `offset`, if they fit.
fn sized(data: &[u8], offset: usize, count: usize, size: usize) -> Option<&[u8]> {
    let end = count.checked_mul(size)?.checked_add(offset)?;
    data.get(offset..end)
}

/// One little-endian component at `offset`.
fn component(data: &[u8], offset: usize, data_type: DataType, normalized: bool) -> Result<f64, String> {
    let b = offset
        .checked_add(data_type.size())
        .and_then(|end| data.get(offset..end))
        .ok_or_else(|| format!("byte {offset} is out of range"))?;
    let value = match data_type {
        DataType::I8 => f64::from(i8::from_le_bytes([b[0]])),
        DataType::U8 => f64::from(b[0]),
        DataType::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
        DataType::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
        DataType::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        DataType::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
    };
    if !normalized {
        return Ok(value);
    }
    // glTF 2.0 § 3.11, "Animations": the normalised integer → float mappings.
    Ok(match data_type {
        DataType::I8 => (value / 127.0).max(-1.0),
        DataType::U8 => value / 255.0,
        DataType::I16 => (value / 32767.0).max(-1.0),
        DataType::U16 => value / 65535.0,
        DataType::U32 => value / f64::from(u32::MAX),
        DataType::F32 => value,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uris_are_decoded() {
        assert_eq!(percent_decode("a%20b%C3%A9.bin"), Ok("a bé.bin".to_owned()));
        assert!(percent_decode("a%FF.bin").is_err());
        assert!(percent_decode("a%2").is_err());
        assert_eq!(uri_scheme("http://x/y.bin"), Some("http"));
        assert_eq!(uri_scheme("C:/x.bin"), None);
        assert_eq!(uri_scheme("dir/x.bin"), None);
        let (bytes, hint) = read_uri(
            "data:image/png;base64,AAEC",
            Path::new("m.gltf"),
            "buffer 0",
            &mut Budget::new(),
        )
        .expect("valid");
        assert_eq!((bytes, hint), (vec![0, 1, 2], Some(FormatHint::Png)));
        // Padding optional.
        let (bytes, _) = read_uri(
            "data:application/octet-stream;base64,AAE",
            Path::new("m.gltf"),
            "b",
            &mut Budget::new(),
        )
        .expect("valid");
        assert_eq!(bytes, [0, 1]);
        assert!(
            read_uri("data:,abc", Path::new("m.gltf"), "b", &mut Budget::new())
                .expect_err("not base64")
                .contains("only base64")
        );
        assert!(
            read_uri(
                "https://example.invalid/a.bin",
                Path::new("m.gltf"),
                "b",
                &mut Budget::new()
            )
            .expect_err("remote")
            .contains("https")
        );
    }

    #[test]
    fn glb_lengths_below_the_header_are_errors() {
        let mut glb = b"glTF\x02\0\0\0\x0b\0\0\0\x08\0\0\0JSON{}      ".to_vec();
        let error = check_glb_length(&glb).expect_err("11 bytes");
        assert!(error.contains("a length of 11 bytes"), "{error}");
        glb[8] = 12;
        assert_eq!(check_glb_length(&glb), Ok(()));
        assert_eq!(check_glb_length(b"glTF"), Ok(()));
        assert_eq!(check_glb_length(b"{}"), Ok(()));
    }

    #[test]
    fn normalized_components() {
        let data = [0x7f, 0x80, 0xff, 0xff];
        assert_eq!(component(&data, 0, DataType::I8, true), Ok(1.0));
        assert_eq!(component(&data, 1, DataType::I8, true), Ok(-1.0));
        assert_eq!(component(&data, 2, DataType::U8, true), Ok(1.0));
        assert_eq!(component(&data, 2, DataType::U16, true), Ok(1.0));
        assert_eq!(component(&data, 2, DataType::U16, false), Ok(65535.0));
        assert!(component(&data, 3, DataType::U16, false).is_err());
        assert!(component(&data, usize::MAX, DataType::U16, false).is_err());
    }
}
