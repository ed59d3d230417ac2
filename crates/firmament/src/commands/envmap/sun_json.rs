//! The suns left out of a `--no-sun` map, for engines that light with directional lights: each
//! sun's direction in the map's frames and its irradiance at the camera after the air.

use std::io::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use firmament_core::Frame;
use firmament_core::envmap::{SunAtEye, enu_to_y_up};
use firmament_core::frame::Sky;
use firmament_render::envmap::suns_at_eye;

use crate::output::write_atomically;

/// The JSON for `frame`'s suns (`null` irradiances never occur: a set sun has zero).
fn describe(frame: &Frame) -> serde_json::Value {
    let Sky::Atmosphere(sky) = &frame.sky else {
        return serde_json::json!({ "suns": [] });
    };
    let conversion = sky.atmosphere.spectral_conversion();
    let suns: Vec<serde_json::Value> = suns_at_eye(frame)
        .iter()
        .zip(&sky.suns)
        .map(|(seen, sun): (&SunAtEye, _)| {
            let d = seen.direction;
            let elevation = d.z.clamp(-1.0, 1.0).asin();
            let rgb = seen.irradiance_rgb;
            serde_json::json!({
                "direction_enu": d.to_array(),
                "direction_y_up": enu_to_y_up(d).to_array(),
                "azimuth_deg": d.x.atan2(d.y).to_degrees().rem_euclid(360.0),
                "elevation_deg": elevation.to_degrees(),
                "angular_radius_deg": sun.angular_radius.to_degrees(),
                "disc_drawn": sun.disc,
                "transmittance": seen.transmittance.to_array(),
                "irradiance_normal": seen.irradiance.to_array(),
                "irradiance_horizontal": (seen.irradiance * elevation.sin().max(0.0)).to_array(),
                "irradiance_normal_linear_srgb": [rgb.r, rgb.g, rgb.b],
                "illuminance_normal_lux": conversion.luminance(seen.irradiance),
            })
        })
        .collect();
    serde_json::json!({
        "frames": {
            "direction_enu": "x east, y north, z up (firmament's world)",
            "direction_y_up": "x east, y up, z south (the cube faces' frame)",
            "azimuth_deg": "clockwise from north",
        },
        "units": {
            "irradiance": "W/(m^2 nm) at wavelengths_nm, after the air, at the camera",
            "irradiance_normal_linear_srgb": "the map's linear sRGB (cd/m^2) times steradians: lux-scaled",
        },
        "wavelengths_nm": sky.atmosphere.wavelengths.0,
        "camera_position_m": frame.camera.position.to_array(),
        "suns": suns,
    })
}

/// Writes `frame`'s suns to `path` as pretty JSON, atomically.
pub(super) fn write(path: &Path, frame: &Frame) -> Result<()> {
    let text = serde_json::to_string_pretty(&describe(frame)).context("cannot encode the suns as JSON")?;
    write_atomically(path, |writer| {
        writeln!(writer, "{text}").with_context(|| format!("output {}: cannot write the file", path.display()))
    })
}
