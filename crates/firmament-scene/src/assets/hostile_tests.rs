//! Hostile model and image files, made in the tests: huge declared sizes, cyclic node graphs,
//! out-of-range indices, oversized data URIs and files, devices for files. Each must fail with
//! an error that names what is wrong (and the limit, for an over-limit one) before anything of
//! the declared size is allocated.

use std::path::Path;
use std::sync::Arc;

use base64::Engine as _;
use base64::engine::general_purpose::STANDARD as BASE64;
use serde_json::{Value, json};

use super::*;

const KEY: &str = "objects[0].mesh.path";

fn f32_bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

fn data_uri(bytes: &[u8]) -> String {
    format!("data:application/octet-stream;base64,{}", BASE64.encode(bytes))
}

/// A triangle (positions at 0, u16 indices at 36) in a data URI, drawn by node 0 of scene 0.
fn triangle() -> Value {
    let mut buffer = f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    buffer.extend([0_u16, 1, 2, 0].iter().flat_map(|i| i.to_le_bytes()));
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": buffer.len(), "uri": data_uri(&buffer)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 6}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
        ]
    })
}

/// The reason a `.gltf` document fails to load from `folder` (a folder that does not exist
/// when `None`).
fn gltf_reason(document: &Value, folder: Option<&Path>) -> String {
    let bytes = serde_json::to_vec(document).expect("serialises");
    let path = folder
        .unwrap_or(Path::new("/nonexistent-firmament-test"))
        .join("hostile.gltf");
    match load_model_bytes(KEY, &path, &bytes) {
        Err(SceneError::Asset { key, reason, .. }) => {
            assert_eq!(key, KEY);
            reason
        }
        other => panic!("expected an asset error, got {other:?}"),
    }
}

#[test]
fn the_triangle_loads() {
    let bytes = serde_json::to_vec(&triangle()).expect("serialises");
    let meshes = load_model_bytes(KEY, Path::new("/nonexistent/t.gltf"), &bytes).expect("loads");
    assert_eq!(meshes[0].mesh.indices, [0, 1, 2]);
}

#[test]
fn huge_declared_buffers_are_refused_without_allocating() {
    let mut document = triangle();
    document["buffers"][0]["byteLength"] = json!(1_u64 << 40);
    let reason = gltf_reason(&document, None);
    assert!(
        reason.contains("buffer 0 holds 44 bytes, less than the 1099511627776 the file declares"),
        "{reason}"
    );

    // An accessor of 2^30 elements on a 36-byte view: over the vertex limit before it is read.
    let mut document = triangle();
    document["accessors"][0]["count"] = json!(1_u64 << 30);
    let reason = gltf_reason(&document, None);
    assert!(reason.contains("MAX_MODEL_VERTICES"), "{reason}");
    assert!(reason.contains("16777216"), "{reason}");

    // Within the limit, but not within its buffer view.
    let mut document = triangle();
    document["accessors"][0]["count"] = json!(1000);
    let reason = gltf_reason(&document, None);
    assert!(
        reason.contains("1000 elements of 12 bytes every 12 from byte 0 do not fit in buffer view 0 (36 bytes)"),
        "{reason}"
    );

    // Sparse-only accessors have no buffer to be measured against: only the limits bound them.
    let mut document = triangle();
    document["accessors"][1] = json!({"componentType": 5125, "count": 1_u64 << 31, "type": "SCALAR",
        "sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5123}, "values": {"bufferView": 1}}});
    let reason = gltf_reason(&document, None);
    assert!(reason.contains("MAX_MODEL_INDICES"), "{reason}");
}

#[test]
fn cyclic_and_shared_node_graphs_are_errors() {
    for (nodes, roots) in [
        (json!([{"mesh": 0, "children": [0]}]), json!([0])),
        (json!([{"mesh": 0, "children": [1]}, {"children": [0]}]), json!([0])),
        (
            json!([{"children": [1, 2]}, {"children": [2]}, {"mesh": 0}]),
            json!([0]),
        ),
        (json!([{"mesh": 0}]), json!([0, 0])),
    ] {
        let mut document = triangle();
        document["nodes"] = nodes.clone();
        document["scenes"][0]["nodes"] = roots;
        let reason = gltf_reason(&document, None);
        assert!(
            reason.contains("reached twice") || reason.contains("invalid glTF"),
            "{nodes}: {reason}"
        );
    }
    // Without a scene, a cycle has no root: nothing to draw, and no endless walk.
    let mut document = triangle();
    document["nodes"] = json!([{"mesh": 0, "children": [1]}, {"mesh": 0, "children": [0]}]);
    if let Some(object) = document.as_object_mut() {
        object.remove("scene");
        object.remove("scenes");
    }
    let reason = gltf_reason(&document, None);
    assert!(
        reason.contains("no meshes") || reason.contains("invalid glTF"),
        "{reason}"
    );
}

#[test]
fn a_deep_node_chain_is_walked_without_recursion() {
    let mut document = triangle();
    let depth = 20_000;
    let nodes: Vec<Value> = (0..depth)
        .map(|i| {
            if i + 1 < depth {
                json!({"children": [i + 1]})
            } else {
                json!({"mesh": 0})
            }
        })
        .collect();
    document["nodes"] = Value::Array(nodes);
    let bytes = serde_json::to_vec(&document).expect("serialises");
    let meshes = load_model_bytes(KEY, Path::new("/nonexistent/deep.gltf"), &bytes).expect("loads");
    assert_eq!(meshes.len(), 1);
}

#[test]
fn instancing_a_mesh_past_the_mesh_limit_is_refused_before_loading() {
    // 300 nodes drawing a mesh of 300 primitives: 90 000 meshes from a 20 kB file.
    let mut document = triangle();
    let primitive = document["meshes"][0]["primitives"][0].clone();
    document["meshes"][0]["primitives"] = Value::Array(vec![primitive; 300]);
    document["nodes"] = Value::Array(vec![json!({"mesh": 0}); 300]);
    document["scenes"][0]["nodes"] = Value::Array((0..300).map(|i| json!(i)).collect());
    let reason = gltf_reason(&document, None);
    assert!(reason.contains("MAX_MODEL_MESHES"), "{reason}");
    assert!(reason.contains("65536"), "{reason}");

    // Below the limit, instances share one mesh.
    document["meshes"][0]["primitives"] = Value::Array(vec![document["meshes"][0]["primitives"][0].clone()]);
    let bytes = serde_json::to_vec(&document).expect("serialises");
    let meshes = load_model_bytes(KEY, Path::new("/nonexistent/i.gltf"), &bytes).expect("loads");
    assert_eq!(meshes.len(), 300);
    assert!(meshes.iter().all(|m| Arc::ptr_eq(&m.mesh, &meshes[0].mesh)));
}

#[test]
fn out_of_range_indices_are_errors() {
    let mut buffer = f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    buffer.extend([0_u16, 1, 7, 0].iter().flat_map(|i| i.to_le_bytes()));
    let mut document = triangle();
    document["buffers"][0]["uri"] = json!(data_uri(&buffer));
    let reason = gltf_reason(&document, None);
    assert!(
        reason.contains("index 7 is out of range (the mesh has 3 vertices)"),
        "{reason}"
    );

    // An accessor index past the end of the file's accessors.
    let mut document = triangle();
    document["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(99);
    let reason = gltf_reason(&document, None);
    assert!(reason.contains("accessor 99 does not exist"), "{reason}");
}

#[test]
fn data_uris_and_files_past_the_byte_limit_are_refused_before_reading() {
    // A data URI counts its decoded size before it is decoded.
    let mut budget = Budget::new();
    budget.bytes = 100;
    let uri = data_uri(&[7_u8; 300]);
    let error = gltf::read_uri(&uri, Path::new("m.gltf"), "buffer 0", &mut budget).expect_err("over budget");
    assert!(error.contains("MAX_ASSET_BYTES"), "{error}");
    assert!(error.contains("1073741824 bytes"), "{error}");

    // A buffer file larger than the limit (sparse: nothing is written) is refused by its size.
    let dir = tempfile::TempDir::new().expect("temp dir");
    let big = std::fs::File::create(dir.path().join("big.bin")).expect("creates");
    big.set_len(MAX_ASSET_BYTES + 1).expect("sets the length");
    let mut document = triangle();
    document["buffers"][0] = json!({"byteLength": 44, "uri": "big.bin"});
    let reason = gltf_reason(&document, Some(dir.path()));
    assert!(reason.contains("is 1073741825 bytes"), "{reason}");
    assert!(reason.contains("MAX_ASSET_BYTES"), "{reason}");

    // Every file read counts, the same file twice too.
    std::fs::write(dir.path().join("small.bin"), [0_u8; 60]).expect("writes");
    let mut budget = Budget::new();
    budget.bytes = 100;
    budget
        .read_file(&dir.path().join("small.bin"), "buffer")
        .expect("60 of 100");
    let error = budget
        .read_file(&dir.path().join("small.bin"), "buffer")
        .expect_err("120 of 100");
    assert!(error.contains("is 60 bytes (after 1073741784 bytes"), "{error}");
}

#[cfg(unix)]
#[test]
fn devices_and_folders_are_not_read() {
    for uri in ["/dev/zero", "file:///dev/zero", "."] {
        let mut document = triangle();
        document["buffers"][0] = json!({"byteLength": 44, "uri": uri});
        let reason = gltf_reason(&document, Some(&std::env::temp_dir()));
        assert!(reason.contains("is not a regular file"), "{uri}: {reason}");
    }
    // A texture file that is a device.
    let error = load_texture(KEY, Path::new("/dev/zero")).expect_err("a device");
    assert!(error.to_string().contains("is not a regular file"), "{error}");
    // An OBJ whose material library is a device loads without it.
    let obj = b"mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let meshes = load_model_bytes(KEY, Path::new("/nonexistent/m.obj"), obj).expect("loads without materials");
    assert_eq!(meshes.len(), 1);
}

#[test]
fn obj_counts_are_bounded_before_parsing() {
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\n";
    let path = Path::new("/nonexistent/m.obj");
    let mut budget = Budget::new();
    budget.vertices = 3;
    let error = obj::load(path, obj, &mut budget).expect_err("4 positions");
    assert!(error.contains("4 vertices"), "{error}");
    assert!(error.contains("MAX_MODEL_VERTICES"), "{error}");
    let mut budget = Budget::new();
    budget.indices = 5;
    let error = obj::load(path, obj, &mut budget).expect_err("6 indices");
    assert!(error.contains("6 triangle indices"), "{error}");
    assert!(error.contains("MAX_MODEL_INDICES"), "{error}");
    let mut budget = Budget::new();
    budget.meshes = 1;
    let two = b"v 0 0 0\nv 1 0 0\nv 0 1 0\no a\nf 1 2 3\no b\nf 1 2 3\n";
    let error = obj::load(path, two, &mut budget).expect_err("2 meshes");
    assert!(error.contains("MAX_MODEL_MESHES"), "{error}");
    assert!(obj::load(path, obj, &mut Budget::new()).is_ok());
}

/// A PNG of `width` × `height` RGBA8 whose header is all there is (an empty IDAT, no pixels).
fn png_header(width: u32, height: u32) -> Vec<u8> {
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = 0xffff_ffff_u32;
        for &b in bytes {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 == 1 {
                    (crc >> 1) ^ 0xedb8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }
    let mut header = b"IHDR".to_vec();
    header.extend(width.to_be_bytes());
    header.extend(height.to_be_bytes());
    header.extend([8, 6, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    for chunk in [header, b"IDAT".to_vec(), b"IEND".to_vec()] {
        png.extend(u32::try_from(chunk.len() - 4).expect("short").to_be_bytes());
        png.extend(&chunk);
        png.extend(crc32(&chunk).to_be_bytes());
    }
    png
}

#[test]
fn image_sizes_are_checked_from_the_header() {
    let path = Path::new("/nonexistent/t.png");
    let error = load_texture_bytes(KEY, path, &png_header(1 << 20, 1)).expect_err("too wide");
    let message = error.to_string();
    assert!(message.contains("width is 1048576 pixels"), "{message}");
    assert!(message.contains("MAX_TEXTURE_SIDE"), "{message}");
    assert!(message.contains(&path.display().to_string()), "{message}");

    // The texels of a model's images are counted from their headers before decoding.
    let mut budget = Budget::new();
    budget.texels = 1000;
    let error = texture_file::decode(&png_header(8192, 8192), None, &mut budget).expect_err("over budget");
    assert!(error.contains("MAX_MODEL_TEXELS"), "{error}");
    assert!(error.contains("8192 × 8192"), "{error}");

    // Within every limit, a header without pixels is a decoding error.
    let error = load_texture_bytes(KEY, path, &png_header(64, 64)).expect_err("no pixels");
    assert!(error.to_string().contains("cannot decode the Png image"), "{error}");
}
