//! Scene files and asset files the CLI tests write.

/// A scene file with `[[objects]]` of one mesh file.
pub(crate) fn mesh_scene(path: &str) -> String {
    format!("[[objects]]\nmesh = {{ kind = \"file\", path = \"{path}\" }}\n")
}

/// A scene file with one cube textured by an image file.
pub(crate) fn texture_scene(file: &str) -> String {
    format!("[[objects]]\nmesh = {{ kind = \"cube\", size = 1.0 }}\ntexture = {{ file = \"{file}\" }}\n")
}

/// A scene file over `earth-clouds` whose one cloud layer has `extra` added (a key it already
/// has replaces the preset's).
pub(crate) fn cloud_scene(extra: &str) -> String {
    format!(
        "preset = \"earth-clouds\"\n[[clouds]]\nkind = \"cumulus\"\nbottom = 1500.0\ntop = 3000.0\n\
         coverage = 0.4\ndensity = 0.05\n{extra}\n"
    )
}

/// A scene file whose cloud layer reads its coverage from `file`.
pub(crate) fn coverage_map_scene(file: &str) -> String {
    cloud_scene(&format!("coverage_map = \"{file}\""))
}

/// An 8×8 red PNG, whole.
pub(crate) fn png_bytes() -> Vec<u8> {
    let image = image::RgbImage::from_pixel(8, 8, image::Rgb([255, 0, 0]));
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::Png)
        .expect("PNG encodes");
    bytes.into_inner()
}

/// A glTF triangle whose index buffer (external, `tri.bin`) names vertices 0, 1 and `last` of
/// 3 (7: out of range).
pub(crate) fn gltf_triangle(last: u16) -> (String, Vec<u8>) {
    let mut bin: Vec<u8> = [0.0_f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    bin.extend([0_u16, 1, last].iter().flat_map(|i| i.to_le_bytes()));
    bin.extend([0, 0]);
    let document = r#"{
        "asset": { "version": "2.0" }, "scene": 0, "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
              "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR" }
        ],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 36 },
            { "buffer": 0, "byteOffset": 36, "byteLength": 6 }
        ],
        "buffers": [{ "byteLength": 44, "uri": "tri.bin" }]
    }"#;
    (document.to_owned(), bin)
}
