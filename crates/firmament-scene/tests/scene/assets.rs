//! `firmament_scene::assets`: OBJ, glTF and image fixtures written to a temporary folder.

use std::path::{Path, PathBuf};

use base64::Engine as _;
use base64::engine::general_purpose::STANDARD as BASE64;
use firmament_scene::SceneError;
use firmament_scene::assets::{LoadedMesh, load_model, load_texture};
use glam::{DMat4, DVec3};
use image::{ImageFormat, Rgba, RgbaImage};
use serde_json::{Value, json};
use tempfile::TempDir;

const KEY: &str = "objects[0].mesh.file";
const RED: [u8; 4] = [255, 0, 0, 255];
const BLUE: [u8; 4] = [0, 0, 255, 200];

fn write(dir: &TempDir, name: &str, contents: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.path().join(name);
    std::fs::write(&path, contents).expect("writes fixture");
    path
}

fn load(path: &Path) -> Vec<LoadedMesh> {
    let meshes = load_model(KEY, path).unwrap_or_else(|e| panic!("{e}"));
    for m in &meshes {
        m.mesh.validate().expect("valid mesh");
    }
    meshes
}

/// The reason of the `SceneError::Asset` that `result` must be.
fn reason<T: std::fmt::Debug>(result: Result<T, SceneError>, path: &Path) -> String {
    match result {
        Err(SceneError::Asset { key, path: p, reason }) => {
            assert_eq!(key, KEY);
            assert_eq!(p, path.display().to_string());
            reason
        }
        other => panic!("expected SceneError::Asset, got {other:?}"),
    }
}

/// A 1 × 2 PNG: red on top, blue (alpha 200) below, in file order.
fn red_over_blue_png() -> Vec<u8> {
    let image = RgbaImage::from_fn(1, 2, |_, y| Rgba(if y == 0 { RED } else { BLUE }));
    let mut bytes = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut bytes), ImageFormat::Png)
        .expect("encodes");
    bytes
}

fn close(a: [f32; 3], b: DVec3) -> bool {
    (DVec3::from(a.map(f64::from)) - b).length() < 1e-6
}

// ---------------------------------------------------------------------------------------------
// OBJ

const QUAD_POSITIONS: [[f32; 3]; 4] = [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]];

#[test]
fn obj_quad_with_normals_material_and_texture() {
    let dir = TempDir::new().expect("temp dir");
    write(&dir, "tex.png", red_over_blue_png());
    write(&dir, "quad.mtl", "newmtl red\nKd 0.8 0.1 0.2\nd 0.5\nmap_Kd tex.png\n");
    let path = write(
        &dir,
        "Quad.OBJ",
        "mtllib quad.mtl\no quad\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n\
         usemtl red\nf 1/1/1 2/2/1 3/3/1 4/4/1\n",
    );
    let meshes = load(&path);
    assert_eq!(meshes.len(), 1);
    let m = &meshes[0];
    assert_eq!(m.mesh.positions, QUAD_POSITIONS);
    assert_eq!(m.mesh.indices, [0, 1, 2, 0, 2, 3]);
    assert!(m.mesh.normals.iter().all(|n| *n == [0.0, 0.0, 1.0]));
    // OBJ texture coordinates are already OpenGL's: no flip.
    assert_eq!(m.mesh.tex_coords, [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    assert_eq!(m.transform, DMat4::IDENTITY);
    assert_eq!(m.base_color, Some([0.8_f32, 0.1, 0.2, 0.5].map(f64::from)));
    let texture = m.texture.as_ref().expect("map_Kd loaded");
    assert_eq!((texture.width, texture.height), (1, 2));
    assert_eq!(texture.texel(0, 0), Some(BLUE), "row 0 is the bottom of the picture");
    assert_eq!(texture.texel(0, 1), Some(RED));
}

#[test]
fn obj_without_normals_gets_area_weighted_normals() {
    let dir = TempDir::new().expect("temp dir");
    // A quad facing +z, and a tent: vertex 5 is shared by a triangle of area 2 facing +z and one
    // of area 0.5 facing +y, so its normal is (0, 0.5·2, 2·2) normalised = (0, 1, 4)/√17.
    let path = write(
        &dir,
        "nonormals.obj",
        "o quad\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n\
         o tent\nv 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 1\nv 1 0 0\nf 5 6 7\nf 5 8 9\n",
    );
    let meshes = load(&path);
    assert_eq!(meshes.len(), 2);
    let quad = &meshes[0].mesh;
    assert_eq!(quad.positions, QUAD_POSITIONS);
    assert!(quad.normals.iter().all(|n| *n == [0.0, 0.0, 1.0]), "{:?}", quad.normals);
    assert!(quad.tex_coords.iter().all(|t| *t == [0.0, 0.0]));
    assert_eq!(meshes[0].base_color, None);
    assert_eq!(meshes[0].texture, None);

    let tent = &meshes[1].mesh;
    assert_eq!(tent.positions[0], [0.0, 0.0, 0.0]);
    assert!(
        close(tent.normals[0], DVec3::new(0.0, 1.0, 4.0).normalize()),
        "{:?}",
        tent.normals[0]
    );
    assert!(close(tent.normals[1], DVec3::Z));
    assert!(close(tent.normals[3], DVec3::Y));
}

#[test]
fn obj_normals_are_repaired_and_degenerate_triangles_dropped() {
    let dir = TempDir::new().expect("temp dir");
    // Normal 1 is too long (normalised), normal 2 is zero (replaced by the computed one); the
    // third face repeats a vertex and is dropped.
    let path = write(
        &dir,
        "repair.obj",
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0 2\nvn 0 0 0\n\
         f 1//1 2//1 3//2\nf 1//1 3//2 4//1\nf 1//1 1//1 2//1\n",
    );
    let meshes = load(&path);
    let mesh = &meshes[0].mesh;
    assert_eq!(mesh.triangle_count(), 2);
    assert!(mesh.normals.iter().all(|n| *n == [0.0, 0.0, 1.0]), "{:?}", mesh.normals);
}

#[test]
fn obj_with_missing_mtl_still_loads() {
    let dir = TempDir::new().expect("temp dir");
    let path = write(
        &dir,
        "nomtl.obj",
        "mtllib missing.mtl\nusemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    let meshes = load(&path);
    assert_eq!(meshes.len(), 1);
    assert_eq!(meshes[0].base_color, None);
    assert_eq!(meshes[0].mesh.normals, [[0.0, 0.0, 1.0]; 3]);
}

#[test]
fn obj_material_without_texture_file_still_loads_with_colour() {
    let dir = TempDir::new().expect("temp dir");
    // Grey `Kd` with one value; the map is missing.
    write(&dir, "m.mtl", "newmtl grey\nKd 0.5\nmap_Kd missing.png\n");
    let path = write(
        &dir,
        "m.obj",
        "mtllib m.mtl\nusemtl grey\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    let meshes = load(&path);
    assert_eq!(meshes[0].base_color, Some([0.5, 0.5, 0.5, 1.0]));
    assert_eq!(meshes[0].texture, None);
}

#[test]
fn broken_obj_files_are_errors() {
    let dir = TempDir::new().expect("temp dir");
    let check = |name: &str, text: &str, expected: &str| {
        let path = write(&dir, name, text);
        let reason = reason(load_model(KEY, &path), &path);
        assert!(reason.contains(expected), "{name}: {reason}");
    };
    check(
        "parse.obj",
        "v 0 0 0\nv 1 0 x\nv 0 1 0\nf 1 2 3\n",
        "line 2: position parse error: `v 1 0 x`",
    );
    check(
        "range.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n",
        "line 4: vertex index 7 is out of range",
    );
    check(
        "nan.obj",
        "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
        "vertex 1 has a non-finite position",
    );
    check(
        "flat.obj",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
        "all 1 are degenerate",
    );
    check("empty.obj", "# nothing\nv 0 0 0\n", "has no faces");
}

// ---------------------------------------------------------------------------------------------
// glTF

fn le_bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// A triangle's buffer: positions (36 bytes at 0), TEXCOORD_0 (24 at 36), u16 indices (6 at
/// 60), padded to 68 bytes.
fn triangle_buffer() -> Vec<u8> {
    let mut data = le_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    data.extend(le_bytes(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]));
    data.extend([0_u16, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    data.extend([0, 0]);
    data
}

const HALF_SQRT_2: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// A glTF document drawing [`triangle_buffer`] (buffer 0, given as `buffer`) through three nodes:
/// a translation (1, 2, 3), a matrix turning 90° about z, and a uniform scale 2 with the mesh.
fn triangle_document(buffer: Value) -> Value {
    json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [
            { "translation": [1.0, 2.0, 3.0], "children": [1] },
            { "matrix": [0.0, 1.0, 0.0, 0.0,  -1.0, 0.0, 0.0, 0.0,  0.0, 0.0, 1.0, 0.0,  0.0, 0.0, 0.0, 1.0],
              "children": [2] },
            { "scale": [2.0, 2.0, 2.0], "mesh": 0, "name": "leaf" }
        ],
        "meshes": [{
            "name": "triangle",
            "primitives": [{
                "attributes": { "POSITION": 0, "TEXCOORD_0": 1 },
                "indices": 2,
                "material": 0
            }]
        }],
        "materials": [{ "pbrMetallicRoughness": { "baseColorFactor": [0.5, 0.25, 1.0, 1.0] } }],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
              "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0] },
            { "bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2" },
            { "bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR" }
        ],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 36 },
            { "buffer": 0, "byteOffset": 36, "byteLength": 24 },
            { "buffer": 0, "byteOffset": 60, "byteLength": 6 }
        ],
        "buffers": [buffer]
    })
}

fn embedded_buffer(data: &[u8]) -> Value {
    json!({
        "byteLength": data.len(),
        "uri": format!("data:application/octet-stream;base64,{}", BASE64.encode(data))
    })
}

/// Checks the one mesh [`triangle_document`] gives.
fn check_triangle(meshes: &[LoadedMesh]) {
    assert_eq!(meshes.len(), 1);
    let m = &meshes[0];
    assert_eq!(m.mesh.positions, [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    assert_eq!(m.mesh.indices, [0, 1, 2]);
    // No normals in the file: computed, the triangle faces +z.
    assert_eq!(m.mesh.normals, [[0.0, 0.0, 1.0]; 3]);
    // glTF v = 0 is the top: t = 1 − v.
    assert_eq!(m.mesh.tex_coords, [[0.0, 1.0], [1.0, 1.0], [0.0, 0.0]]);
    assert_eq!(m.base_color, Some([0.5, 0.25, 1.0, 1.0]));
    // translate(1, 2, 3) · rotate_z(90°) · scale(2).
    let expected = DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0))
        * DMat4::from_rotation_z(std::f64::consts::FRAC_PI_2)
        * DMat4::from_scale(DVec3::splat(2.0));
    assert!(m.transform.abs_diff_eq(expected, 1e-12), "{}", m.transform);
    let corner = m.transform.transform_point3(DVec3::X);
    assert!((corner - DVec3::new(1.0, 4.0, 3.0)).length() < 1e-12, "{corner}");
    let top = m.transform.transform_point3(DVec3::Y);
    assert!((top - DVec3::new(-1.0, 2.0, 3.0)).length() < 1e-12, "{top}");
}

#[test]
fn gltf_with_embedded_buffer_and_node_hierarchy() {
    let dir = TempDir::new().expect("temp dir");
    let document = triangle_document(embedded_buffer(&triangle_buffer()));
    let path = write(&dir, "triangle.gltf", document.to_string());
    check_triangle(&load(&path));
}

#[test]
fn gltf_with_external_buffer_and_trs_rotation() {
    let dir = TempDir::new().expect("temp dir");
    write(&dir, "tri data.bin", triangle_buffer());
    let mut document = triangle_document(json!({ "byteLength": 68, "uri": "tri%20data.bin" }));
    // The same rotation as a quaternion instead of a matrix.
    document["nodes"][1] = json!({ "rotation": [0.0, 0.0, HALF_SQRT_2, HALF_SQRT_2], "children": [2] });
    let path = write(&dir, "external.GLTF", document.to_string());
    check_triangle(&load(&path));

    std::fs::remove_file(dir.path().join("tri data.bin")).expect("removes");
    let reason = reason(load_model(KEY, &path), &path);
    assert!(
        reason.contains("tri data.bin") && reason.contains("does not exist"),
        "{reason}"
    );
}

/// A GLB file: `document` as the JSON chunk and `bin` as the binary chunk.
fn glb(document: &Value, bin: &[u8]) -> Vec<u8> {
    let mut json = document.to_string().into_bytes();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2_u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

#[test]
fn glb_with_embedded_texture() {
    let dir = TempDir::new().expect("temp dir");
    let png = red_over_blue_png();
    let mut bin = triangle_buffer();
    let png_offset = bin.len();
    bin.extend(&png);
    let mut document = triangle_document(json!({ "byteLength": bin.len() }));
    document["bufferViews"]
        .as_array_mut()
        .expect("array")
        .push(json!({ "buffer": 0, "byteOffset": png_offset, "byteLength": png.len() }));
    document["images"] = json!([{ "bufferView": 3, "mimeType": "image/png" }]);
    document["textures"] = json!([{ "source": 0 }]);
    document["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
    let path = write(&dir, "textured.glb", glb(&document, &bin));
    let meshes = load(&path);
    check_triangle(&meshes);
    let texture = meshes[0].texture.as_ref().expect("base colour texture");
    assert_eq!((texture.width, texture.height), (1, 2));
    assert_eq!(texture.texel(0, 0), Some(BLUE), "row 0 is the bottom of the picture");
    assert_eq!(texture.texel(0, 1), Some(RED));

    // Cut short: an error, not a panic.
    let bytes = glb(&document, &bin);
    let path = write(&dir, "short.glb", &bytes[..bytes.len() - 40]);
    let reason = reason(load_model(KEY, &path), &path);
    assert!(reason.contains("malformed GLB"), "{reason}");
}

#[test]
fn gltf_mesh_instanced_twice_and_given_normals() {
    let dir = TempDir::new().expect("temp dir");
    let mut data = triangle_buffer();
    // Normals at 68: not unit length (normalised), the last one zero (replaced).
    data.extend(le_bytes(&[0.0, 0.0, 3.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]));
    let mut document = triangle_document(embedded_buffer(&data));
    document["accessors"]
        .as_array_mut()
        .expect("array")
        .push(json!({ "bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3" }));
    document["bufferViews"]
        .as_array_mut()
        .expect("array")
        .push(json!({ "buffer": 0, "byteOffset": 68, "byteLength": 36 }));
    document["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = json!(3);
    // No scene: every root node is drawn (node 3 is a second root using the same mesh).
    document.as_object_mut().expect("object").remove("scene");
    document.as_object_mut().expect("object").remove("scenes");
    document["nodes"]
        .as_array_mut()
        .expect("array")
        .push(json!({ "mesh": 0, "translation": [0.0, 0.0, -5.0] }));
    let path = write(&dir, "twice.gltf", document.to_string());
    let meshes = load(&path);
    assert_eq!(meshes.len(), 2);
    assert_eq!(meshes[0].mesh, meshes[1].mesh);
    assert_eq!(meshes[0].mesh.normals, [[0.0, 0.0, 1.0]; 3]);
    assert_eq!(meshes[1].transform, DMat4::from_translation(DVec3::new(0.0, 0.0, -5.0)));
}

#[test]
fn gltf_fog_coordinates_come_from_the_fog_coord_attribute() {
    let dir = TempDir::new().expect("temp dir");
    let mut data = triangle_buffer();
    // _FOG_COORD at 68: one scalar per vertex (GL_FOG_COORD).
    data.extend(le_bytes(&[0.5, -1.0, 7.25]));
    let mut document = triangle_document(embedded_buffer(&data));
    document["accessors"]
        .as_array_mut()
        .expect("array")
        .push(json!({ "bufferView": 3, "componentType": 5126, "count": 3, "type": "SCALAR" }));
    document["bufferViews"]
        .as_array_mut()
        .expect("array")
        .push(json!({ "buffer": 0, "byteOffset": 68, "byteLength": 12 }));
    document["meshes"][0]["primitives"][0]["attributes"]["_FOG_COORD"] = json!(3);
    let path = write(&dir, "fogged.gltf", document.to_string());
    assert_eq!(load(&path)[0].mesh.fog_coords, [0.5, -1.0, 7.25]);
    // Without the attribute there are none.
    let plain = write(
        &dir,
        "plain.gltf",
        triangle_document(embedded_buffer(&triangle_buffer())).to_string(),
    );
    assert!(load(&plain)[0].mesh.fog_coords.is_empty());
    // A vector where a scalar belongs is an error naming the attribute.
    document["accessors"][3]["type"] = json!("VEC3");
    document["accessors"][3]["count"] = json!(1);
    let path = write(&dir, "bad_fog.gltf", document.to_string());
    let message = reason(load_model(KEY, &path), &path);
    assert!(message.contains("_FOG_COORD"), "{message}");
}

#[test]
fn broken_gltf_files_are_errors() {
    let dir = TempDir::new().expect("temp dir");
    let good = triangle_document(embedded_buffer(&triangle_buffer()));
    let check = |name: &str, contents: &str, expected: &str| {
        let path = write(&dir, name, contents);
        let reason = reason(load_model(KEY, &path), &path);
        assert!(reason.contains(expected), "{name}: {reason}");
    };

    let text = good.to_string();
    check("truncated.gltf", &text[..text.len() / 2], "malformed glTF JSON");

    let mut document = good.clone();
    document["accessors"][0]["count"] = json!(4);
    check("overrun.gltf", &document.to_string(), "do not fit in buffer view 0");

    let mut document = good.clone();
    document["accessors"][0]["count"] = json!(0);
    check("empty.gltf", &document.to_string(), "count 0");

    let mut document = good.clone();
    document["accessors"][0]["type"] = json!("VEC2");
    check(
        "vec2.gltf",
        &document.to_string(),
        "POSITION (accessor 0) is Vec2 of F32",
    );

    let mut document = good.clone();
    document["meshes"][0]["primitives"][0]["mode"] = json!(0);
    check("points.gltf", &document.to_string(), "no triangles");

    let mut document = good.clone();
    document["nodes"][2]["children"] = json!([0]);
    check("cycle.gltf", &document.to_string(), "node 0 is reached twice");

    let mut document = good.clone();
    document["meshes"][0]["primitives"][0]
        .as_object_mut()
        .expect("object")
        .remove("indices");
    document["accessors"][0]["max"] = json!([1.0, 0.0, 0.0]);
    let mut data = triangle_buffer();
    data[28..32].copy_from_slice(&0.0_f32.to_le_bytes());
    document["buffers"][0] = embedded_buffer(&data);
    check("collinear.gltf", &document.to_string(), "all 1 are degenerate");

    let mut document = good;
    document["meshes"][0]["primitives"][0]["attributes"]
        .as_object_mut()
        .expect("object")
        .remove("POSITION");
    check("nopositions.gltf", &document.to_string(), "invalid glTF");
}

// ---------------------------------------------------------------------------------------------
// Dispatch and textures

#[test]
fn missing_files_and_unknown_extensions_are_errors() {
    let dir = TempDir::new().expect("temp dir");
    let missing = dir.path().join("missing.obj");
    let reason_missing = reason(load_model(KEY, &missing), &missing);
    assert!(reason_missing.contains("does not exist"), "{reason_missing}");

    let stl = write(&dir, "model.stl", "solid x\nendsolid x\n");
    let unknown = reason(load_model(KEY, &stl), &stl);
    assert!(
        unknown.contains("`.stl`") && unknown.contains(".obj, .gltf, .glb"),
        "{unknown}"
    );
    let bare = write(&dir, "model", "");
    assert!(reason(load_model(KEY, &bare), &bare).contains("no extension"));

    let message = load_model(KEY, &stl).expect_err("unknown").to_string();
    assert!(
        message.starts_with(&format!("{KEY}: cannot load {}", stl.display())),
        "{message}"
    );
}

#[test]
fn textures_are_flipped_and_checked() {
    let dir = TempDir::new().expect("temp dir");
    let path = write(&dir, "tex.PNG", red_over_blue_png());
    let texture = load_texture(KEY, &path).expect("loads");
    texture.validate().expect("valid");
    assert_eq!((texture.width, texture.height), (1, 2));
    assert_eq!(texture.texels, [BLUE, RED]);

    let wide = RgbaImage::new(firmament_core::texture::MAX_TEXTURE_SIDE + 1, 1);
    let path = dir.path().join("wide.png");
    wide.save(&path).expect("saves");
    let too_wide = reason(load_texture(KEY, &path), &path);
    assert!(too_wide.contains("8193") && too_wide.contains("8192"), "{too_wide}");

    let missing = dir.path().join("missing.png");
    assert!(reason(load_texture(KEY, &missing), &missing).contains("does not exist"));
    let garbage = write(&dir, "garbage.png", "not a png");
    assert!(reason(load_texture(KEY, &garbage), &garbage).contains("cannot decode"));
}
