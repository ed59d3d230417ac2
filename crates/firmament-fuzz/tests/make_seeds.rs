//! Writes the seed corpora under `seeds/` (committed; the scene targets also start from the
//! presets). Run again after changing it:
//! `cargo test -p firmament-fuzz --test make_seeds -- --ignored`.

use std::io::Cursor;
use std::path::{Path, PathBuf};

use base64::Engine as _;
use base64::engine::general_purpose::STANDARD as BASE64;
use image::{DynamicImage, ImageBuffer, ImageFormat, Luma, Rgb, Rgba, RgbaImage};
use serde_json::{Value, json};

fn folder(target: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("seeds").join(target);
    std::fs::create_dir_all(&dir).expect("creates the seed folder");
    dir
}

fn write(target: &str, name: &str, bytes: impl AsRef<[u8]>) {
    std::fs::write(folder(target).join(name), bytes).expect("writes a seed");
}

fn encoded(image: &DynamicImage, format: ImageFormat) -> Vec<u8> {
    let mut bytes = Vec::new();
    image.write_to(&mut Cursor::new(&mut bytes), format).expect("encodes");
    bytes
}

fn png_2x2() -> Vec<u8> {
    let image = RgbaImage::from_fn(2, 2, |x, y| Rgba([255 * (x as u8), 255 * (y as u8), 128, 200]));
    encoded(&DynamicImage::ImageRgba8(image), ImageFormat::Png)
}

fn f32_bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

fn data_uri(bytes: &[u8]) -> String {
    format!("data:application/octet-stream;base64,{}", BASE64.encode(bytes))
}

/// A glTF JSON document as text, compact.
fn text(document: &Value) -> String {
    serde_json::to_string(document).expect("serialises")
}

/// A quad: positions, normals, texture coordinates (float) and u16 indices in one buffer.
fn quad_buffer() -> (Vec<u8>, [usize; 4]) {
    let mut bytes = f32_bytes(&[-1.0, -1.0, 0.0, 1.0, -1.0, 0.0, 1.0, 1.0, 0.0, -1.0, 1.0, 0.0]);
    let normals = bytes.len();
    bytes.extend(f32_bytes(&[0.0, 0.0, 1.0].repeat(4)));
    let tex = bytes.len();
    bytes.extend(f32_bytes(&[0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0]));
    let indices = bytes.len();
    bytes.extend([0_u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()));
    (bytes, [0, normals, tex, indices])
}

fn quad_document(buffer: Value, image: Value) -> Value {
    let (bytes, [p, n, t, i]) = quad_buffer();
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "translation": [1.0, 2.0, 3.0], "rotation": [0.0, 0.0, 0.6, 0.8]}],
        "meshes": [{"name": "quad", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
            "indices": 3,
            "material": 0
        }]}],
        "materials": [{"pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.2, 0.1, 1.0],
            "baseColorTexture": {"index": 0}
        }}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{}],
        "images": [image],
        "buffers": [buffer],
        "bufferViews": [
            {"buffer": 0, "byteOffset": p, "byteLength": 48},
            {"buffer": 0, "byteOffset": n, "byteLength": 48},
            {"buffer": 0, "byteOffset": t, "byteLength": 32},
            {"buffer": 0, "byteOffset": i, "byteLength": 12}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-1.0, -1.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}
        ],
        "_len": bytes.len()
    })
}

fn without_len(mut document: Value) -> Value {
    if let Some(object) = document.as_object_mut() {
        object.remove("_len");
    }
    document
}

/// A GLB of `json` and `bin`, as the glb target's input (2 bytes of JSON length first).
fn glb_input(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut out = u16::try_from(json.len()).expect("short JSON").to_le_bytes().to_vec();
    out.extend_from_slice(json.as_bytes());
    out.extend_from_slice(bin);
    out
}

#[test]
#[ignore = "writes the committed seed corpora; run by hand after changing it"]
fn write_seeds() {
    // ---------------------------------------------------------------- OBJ
    write(
        "obj",
        "quad-material",
        "mtllib quad.mtl\no quad\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
         vn 0 0 1\nusemtl red\nf 1/1/1 2/2/1 3/3/1 4/4/1\n",
    );
    write(
        "obj",
        "groups-negative",
        "# two groups, negative indices, a pentagon, points and lines\ng tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\n\
         f -3 -2 -1\ng tent\ns 1\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0.5 1.5 1\nv 0 1 1\nf 4 5 6 7 8\nl 1 2\np 3\n\
         usemtl missing\nf 1//1 2//1 3//1\nvn 0 0 1\n",
    );
    write(
        "obj",
        "textured-normals",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0 0\nvt 1 1\nvt 0 1\nvn 0 0 2\nvn 0 0 0\n\
         f 1/1/1 2/2/1 3/3/2\nf 1/1 3/3 4/4\no second\nv 0 0 5 1.0\nf 1 2 5\n",
    );

    // ---------------------------------------------------------------- glTF (JSON)
    let (quad, _) = quad_buffer();
    let image = json!({"uri": format!("data:image/png;base64,{}", BASE64.encode(png_2x2()))});
    let document = without_len(quad_document(
        json!({"byteLength": quad.len(), "uri": data_uri(&quad)}),
        image,
    ));
    write("gltf", "quad-textured.gltf", text(&document));

    let triangle = f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    let fog = f32_bytes(&[0.5, -1.0, 7.25]);
    let mut buffer = triangle.clone();
    buffer.extend(&fog);
    buffer.extend([0_u8, 0, 255, 0, 0, 255]); // u8 normalised texture coordinates
    buffer.extend([1_u8, 2]); // sparse indices
    buffer.extend([0_u32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    let hierarchy = json!({
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0, 3]}],
        "nodes": [
            {"children": [1, 2], "scale": [2.0, 2.0, 2.0]},
            {"mesh": 0, "matrix": [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 5.0, 0.0, 0.0, 1.0]},
            {"mesh": 0},
            {"mesh": 1}
        ],
        "meshes": [
            {"primitives": [
                {"attributes": {"POSITION": 0, "_FOG_COORD": 1, "TEXCOORD_0": 2}, "indices": 3},
                {"attributes": {"POSITION": 0}, "mode": 1}
            ]},
            {"primitives": [{"attributes": {"POSITION": 4}}]}
        ],
        "buffers": [{"byteLength": buffer.len(), "uri": data_uri(&buffer)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 12},
            {"buffer": 0, "byteOffset": 48, "byteLength": 6},
            {"buffer": 0, "byteOffset": 56, "byteLength": 12},
            {"buffer": 0, "byteOffset": 54, "byteLength": 2},
            {"buffer": 0, "byteOffset": 12, "byteLength": 24}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "SCALAR"},
            {"bufferView": 2, "componentType": 5121, "normalized": true, "count": 3, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": 3, "type": "SCALAR"},
            {"componentType": 5126, "count": 3, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0],
             "sparse": {"count": 2,
                        "indices": {"bufferView": 4, "componentType": 5121},
                        "values": {"bufferView": 5}}}
        ]
    });
    write("gltf", "hierarchy-sparse.gltf", text(&hierarchy));
    let minimal = json!({
        "asset": {"version": "2.0"},
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"byteLength": 36, "uri": data_uri(&triangle)}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]}]
    });
    write("gltf", "triangle.gltf", text(&minimal));

    // ---------------------------------------------------------------- GLB
    let png = png_2x2();
    let mut bin = quad.clone();
    let image_offset = bin.len();
    bin.extend(&png);
    bin.resize(bin.len().next_multiple_of(4), 0);
    let mut document = without_len(quad_document(
        json!({"byteLength": bin.len()}),
        json!({"bufferView": 4, "mimeType": "image/png"}),
    ));
    if let Some(views) = document["bufferViews"].as_array_mut() {
        views.push(json!({"buffer": 0, "byteOffset": image_offset, "byteLength": png.len()}));
    }
    let json_text = text(&document);
    let input = glb_input(&json_text, &bin);
    write("glb", "quad-textured", &input);
    write("gltf", "quad-textured.glb", firmament_fuzz::glb_container(&input));
    let triangle_json = text(&json!({
        "asset": {"version": "2.0"},
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": 44}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
        ]
    }));
    let mut bin = triangle.clone();
    bin.extend([0_u16, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    bin.resize(44, 0);
    write("glb", "triangle", glb_input(&triangle_json, &bin));

    // ---------------------------------------------------------------- textures
    write("texture", "rgba8-png", png_2x2());
    let gray16 = ImageBuffer::<Luma<u16>, _>::from_fn(3, 2, |x, y| Luma([(x * 20000 + y * 3000) as u16]));
    write(
        "texture",
        "gray16-png",
        encoded(&DynamicImage::ImageLuma16(gray16), ImageFormat::Png),
    );
    let rgb = ImageBuffer::<Rgb<u8>, _>::from_fn(8, 8, |x, y| Rgb([(x * 30) as u8, (y * 30) as u8, 90]));
    write(
        "texture",
        "rgb-jpeg",
        encoded(&DynamicImage::ImageRgb8(rgb.clone()), ImageFormat::Jpeg),
    );
    let float = image::Rgba32FImage::from_fn(2, 2, |x, y| Rgba([x as f32, y as f32, 0.5, 1.0]));
    write(
        "texture",
        "rgba32f-exr",
        encoded(&DynamicImage::ImageRgba32F(float), ImageFormat::OpenExr),
    );
    let rgb_float = image::Rgb32FImage::from_fn(3, 1, |x, _| Rgb([x as f32 * 2.0, 0.25, -1.0]));
    write(
        "texture",
        "rgb32f-exr",
        encoded(&DynamicImage::ImageRgb32F(rgb_float), ImageFormat::OpenExr),
    );

    // ---------------------------------------------------------------- dates
    for (name, seconds, text) in [
        ("offset", 45.25, "2003-10-17T12:30:30-07:00"),
        ("zulu", -86_400.0, "2003-10-17T19:30:30Z"),
        ("short-offset", 1.0e6, "2024-06-21T06:15+0530"),
        ("fraction", 0.5, "2024-06-21T06:15:01.25+02"),
        ("leap-second", 0.0, "2016-12-31T23:59:60.5Z"),
        ("no-offset", 3.0e9, "2024-02-29T00:00:00"),
    ] {
        let mut bytes = f64::to_le_bytes(seconds).to_vec();
        bytes.extend_from_slice(text.as_bytes());
        write("date_time", name, bytes);
    }

    // ---------------------------------------------------------------- --set
    for (name, text) in [
        (
            "suns",
            "earth-noon\nsuns.0.elevation=3\nsuns.1.azimuth=90\nsuns.1.elevation=5",
        ),
        (
            "gradient",
            "default\nsky.gradient.keyframes.0.zenith=#ff0000\ncamera.fov_y=75\ndisplay.tone_curve=aces_fitted",
        ),
        (
            "date",
            "midsummer-night\ntime.date_time=2024-06-21T22:00:00+02:00\nplanet.latitude=60\nrender.width=64",
        ),
        (
            "objects",
            "fixed-function-tour\nobjects.0.material.shininess=64\nlights.0.position=[1, 2, 3, 0]",
        ),
        (
            "flare",
            "nehe-flare\nflare.enabled=true\nflare.preset=anamorphic\nflare.samples=16",
        ),
        ("seed", "seed-mars\natmosphere.model=\"seed\"\nsky.model=atmosphere"),
    ] {
        write("scene_set", name, text);
    }
}
