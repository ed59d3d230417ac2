//! `firmament._firmament`: the extension module under the `firmament` Python package
//! (`python/firmament/__init__.py` is the documented API; this module is its engine).
//!
//! - Scenes come as TOML text, a path, a dict (written as TOML) or nothing (a preset or the
//!   default scene), layered and checked by `firmament_scene` exactly as scene files are.
//! - Images come back as numpy arrays, `(height, width, 4)`, rows top first: linear
//!   scene-referred `float32` radiance (what `render -o x.exr` writes) or display `uint8` sRGB.
//! - The reports (`sun`, `sky-sample`) run the command line's own code in-process and return its
//!   `--json` text; the package decodes it.
//! - Every failure is a `FirmamentError` carrying the command line's message.
//!
//! The GIL is released while the GPU renders; one GPU context and renderer per backend is kept
//! for the process, so a second render skips the adapter's start-up.

use std::path::PathBuf;
use std::sync::{Mutex, PoisonError};

use firmament_render::envmap::SunDiscs;
use firmament_render::headless::HeadlessRenderer;
use firmament_render::{Backend, GpuContext};
use firmament_scene::{Scene, SceneDocument, SceneSource};
use numpy::{PyArray1, PyArrayMethods as _};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

create_exception!(
    _firmament,
    FirmamentError,
    PyException,
    "A scene, an argument, the GPU or an output failed; the message names the key, flag or rule."
);

/// A `FirmamentError` with `message`.
fn error(message: impl Into<String>) -> PyErr {
    FirmamentError::new_err(message.into())
}

/// The GPU kept between renders: the context and renderer of the backend last asked for.
static GPU: Mutex<Option<(Backend, GpuContext, HeadlessRenderer)>> = Mutex::new(None);

/// `backend` by its command-line name.
fn backend(name: &str) -> PyResult<Backend> {
    match name {
        "auto" => Ok(Backend::Auto),
        "vulkan" => Ok(Backend::Vulkan),
        "gl" => Ok(Backend::Gl),
        "metal" => Ok(Backend::Metal),
        "dx12" => Ok(Backend::Dx12),
        other => Err(error(format!(
            "backend = {other:?}: expected one of \"auto\", \"vulkan\", \"gl\", \"metal\", \"dx12\""
        ))),
    }
}

/// A Python value (from a scene dict) as a TOML value; `key` names it in messages.
fn toml_value(key: &str, value: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        let n: i64 = value
            .extract()
            .map_err(|_| error(format!("{key}: an integer outside TOML's 64 bits")))?;
        return Ok(toml::Value::Integer(n));
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        return Ok(toml::Value::Table(toml_table(key, dict)?));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items = value
            .try_iter()?
            .enumerate()
            .map(|(i, item)| toml_value(&format!("{key}[{i}]"), &item?))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    let kind = value.get_type().name()?;
    Err(error(format!(
        "{key}: a {kind} has no TOML form (use bool, int, float, str, list, tuple or dict)"
    )))
}

/// A Python dict (a scene, or a table in one) as a TOML table; `key` is its path ("" at the top).
fn toml_table(key: &str, dict: &Bound<'_, PyDict>) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (name, value) in dict.iter() {
        let name: String = name
            .extract()
            .map_err(|_| error(format!("{key}: every key of a scene dict must be a str")))?;
        let path = if key.is_empty() {
            name.clone()
        } else {
            format!("{key}.{name}")
        };
        table.insert(name, toml_value(&path, &value)?);
    }
    Ok(table)
}

/// Where a scene comes from, as the package passes it.
enum SceneInput {
    /// A preset (or the default scene).
    None,
    /// TOML text, with the name messages give it.
    Text(String, String),
    /// A scene file.
    File(PathBuf),
}

/// `scene` as the package passes it: `None`, TOML text (`str`), a dict, or a path (`os.PathLike`).
fn scene_input(scene: Option<&Bound<'_, PyAny>>) -> PyResult<SceneInput> {
    let Some(scene) = scene.filter(|s| !s.is_none()) else {
        return Ok(SceneInput::None);
    };
    if let Ok(text) = scene.extract::<String>() {
        return Ok(SceneInput::Text(text, "<scene text>".to_owned()));
    }
    if let Ok(dict) = scene.cast::<PyDict>() {
        let text = toml::to_string(&toml_table("", dict)?).map_err(|e| error(format!("the scene dict: {e}")))?;
        return Ok(SceneInput::Text(text, "<scene dict>".to_owned()));
    }
    if let Ok(path) = scene.extract::<PathBuf>() {
        return Ok(SceneInput::File(path));
    }
    let kind = scene.get_type().name()?;
    Err(error(format!(
        "scene: a {kind}; expected TOML text (str), a dict, a path (pathlib.Path) or None"
    )))
}

/// The scene of `input` on `preset` with `overrides`, checked.
fn load_scene(input: &SceneInput, preset: Option<&str>, overrides: &[String]) -> PyResult<Scene> {
    let document = match input {
        SceneInput::None => SceneDocument::load(SceneSource::Preset(preset.unwrap_or("default")), None, overrides),
        SceneInput::Text(text, origin) => SceneDocument::load(SceneSource::Text { text, origin }, preset, overrides),
        SceneInput::File(path) => SceneDocument::load_file(path, preset, overrides),
    };
    document.and_then(|d| d.scene()).map_err(|e| error(e.to_string()))
}

/// Renders a scene on the GPU: `float32` linear radiance when `hdr`, else `uint8` display sRGB,
/// `(height, width, 4)`.
#[pyfunction]
#[pyo3(signature = (scene=None, *, preset=None, overrides=Vec::new(), width=None, height=None, hdr=false, backend_name="auto"))]
#[expect(
    clippy::too_many_arguments,
    reason = "the Python function's keyword arguments, each once"
)]
fn render<'py>(
    py: Python<'py>,
    scene: Option<&Bound<'py, PyAny>>,
    preset: Option<&str>,
    overrides: Vec<String>,
    width: Option<u32>,
    height: Option<u32>,
    hdr: bool,
    backend_name: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let wanted = backend(backend_name)?;
    let input = scene_input(scene)?;
    let mut all = Vec::new();
    all.extend(width.map(|w| format!("render.width={w}")));
    all.extend(height.map(|h| format!("render.height={h}")));
    all.extend(overrides);
    let scene = load_scene(&input, preset, &all)?;
    let (w, h) = (scene.render.width, scene.render.height);
    firmament_cli::check_render_pixels(w, h).map_err(error)?;
    let frame = scene.frame_at(None).map_err(|e| error(e.to_string()))?;
    let image = with_gpu(py, wanted, |ctx, renderer| {
        if hdr {
            renderer.render_hdr(ctx, &frame, w, h).map(|i| Pixels::Hdr(i.pixels))
        } else {
            renderer.render_ldr(ctx, &frame, w, h).map(|i| Pixels::Ldr(i.pixels))
        }
    })?;
    let shape = [h as usize, w as usize, 4];
    let array = match image {
        Pixels::Hdr(pixels) => PyArray1::from_vec(py, pixels).reshape(shape)?.into_any(),
        Pixels::Ldr(pixels) => PyArray1::from_vec(py, pixels).reshape(shape)?.into_any(),
    };
    Ok(array)
}

/// Runs `draw` on the kept GPU of `backend` (made on first use) with the GIL released.
fn with_gpu<T: Send>(
    py: Python<'_>,
    backend: Backend,
    draw: impl FnOnce(&GpuContext, &mut HeadlessRenderer) -> Result<T, firmament_render::RenderError> + Send,
) -> PyResult<T> {
    py.detach(|| -> Result<T, String> {
        let mut gpu = GPU.lock().unwrap_or_else(PoisonError::into_inner);
        if gpu.as_ref().is_none_or(|(b, _, _)| *b != backend) {
            let ctx = GpuContext::headless(backend).map_err(|e| e.to_string())?;
            let renderer = HeadlessRenderer::new(&ctx);
            *gpu = Some((backend, ctx, renderer));
        }
        let Some((_, ctx, renderer)) = gpu.as_mut() else {
            return Err("no GPU context".to_owned());
        };
        draw(ctx, renderer).map_err(|e| e.to_string())
    })
    .map_err(error)
}

/// Renders the equirectangular environment map around a scene's camera position, `float32`
/// linear radiance `(width / 2, width, 4)`, with or without the suns' discs.
#[pyfunction]
#[pyo3(signature = (scene=None, *, preset=None, overrides=Vec::new(), width=1024, sun=true, backend_name="auto"))]
fn envmap<'py>(
    py: Python<'py>,
    scene: Option<&Bound<'py, PyAny>>,
    preset: Option<&str>,
    overrides: Vec<String>,
    width: u32,
    sun: bool,
    backend_name: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let wanted = backend(backend_name)?;
    let scene = load_scene(&scene_input(scene)?, preset, &overrides)?;
    firmament_cli::check_render_pixels(width, width / 2).map_err(error)?;
    let frame = scene.frame_at(None).map_err(|e| error(e.to_string()))?;
    let discs = if sun { SunDiscs::Included } else { SunDiscs::Omitted };
    let map = with_gpu(py, wanted, |ctx, renderer| {
        renderer.render_equirect(ctx, &frame, width, discs)
    })?;
    let shape = [map.height as usize, map.width as usize, 4];
    Ok(PyArray1::from_vec(py, map.pixels).reshape(shape)?.into_any())
}

/// An image's channels, as read back.
enum Pixels {
    Hdr(Vec<f32>),
    Ldr(Vec<u8>),
}

/// Runs a reporting command of the command line (`["sun", "--time", …]`) in-process and returns
/// the JSON it prints with `--json`.
#[pyfunction]
fn report(py: Python<'_>, args: Vec<String>) -> PyResult<String> {
    let value = py.detach(|| firmament_cli::json_report(&args)).map_err(error)?;
    Ok(value.to_string())
}

/// `scene` (TOML text or a dict) as TOML text, for the reports, which read scene files.
#[pyfunction]
fn scene_toml(scene: &Bound<'_, PyAny>) -> PyResult<String> {
    match scene_input(Some(scene))? {
        SceneInput::Text(text, _) => Ok(text),
        SceneInput::None | SceneInput::File(_) => Err(error("scene_toml takes TOML text or a dict")),
    }
}

/// The module.
#[pymodule]
fn _firmament(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("FirmamentError", m.py().get_type::<FirmamentError>())?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(envmap, m)?)?;
    m.add_function(wrap_pyfunction!(report, m)?)?;
    m.add_function(wrap_pyfunction!(scene_toml, m)?)?;
    Ok(())
}
