//! Auto-exposure: what the camera's meter reads and how the exposure follows it, as the `f64`
//! reference for the GPU histogram (`firmament-render`'s exposure pass).
//!
//! The meter reads a frame's luminance `Y` (Rec. 709 weights of linear RGB; cd/m² for the
//! physical sky) in cells of [`METERING_CELL`]² pixels, as a camera's metering zones: each cell's
//! mean over its pixels that are not within [`METERING_DISC_MARGIN`] angular radii of a sun's
//! disc. On a log scale, cells darker than `2^METERING_LOG2_MIN` are left out (black space, unlit
//! ground at night: no light to meter); the rest are clamped below `2^METERING_LOG2_MAX`, the
//! darkest [`METERING_DARK_FRACTION`] and brightest [`METERING_BRIGHT_FRACTION`] of them dropped,
//! and the geometric mean of what remains is the metered luminance `L` (none left: the exposure
//! opens up to its lowest EV100, as a camera's does in the dark). The exposure that puts `L` on
//! middle grey is the reflected-light meter's `EV100 = log2(L · 100 / K)` with `K = 12.5`
//! (ISO 2720; Lagarde & de Rousiers, "Moving Frostbite to PBR", 2014, §5.1), less the
//! compensation, clamped to the bounds. Time-lapses and viewers move towards it at a limited
//! speed in EV per second, as an eye or a camera's meter does (Unreal's "auto exposure speed").

use glam::DVec3;

use crate::color::LinearRgb;
use crate::frame::Sky;

/// The lowest metered luminance, log2 of cd/m² (2^-16 ≈ 1.5e-5 cd/m², a tenth of a moonless
/// sky's); darker pixels are not metered.
pub const METERING_LOG2_MIN: f64 = -16.0;
/// The highest metered luminance, log2 of cd/m² (2^22 ≈ 4.2e6 cd/m², above sunlit snow).
pub const METERING_LOG2_MAX: f64 = 22.0;
/// The share of metered pixels, darkest first, that the meter ignores.
pub const METERING_DARK_FRACTION: f64 = 0.05;
/// The share of metered pixels, brightest first, that the meter ignores.
pub const METERING_BRIGHT_FRACTION: f64 = 0.05;
/// Pixels closer to a sun's centre than this many of its angular radii are not metered.
pub const METERING_DISC_MARGIN: f64 = 1.5;
/// The side of the meter's cells, pixels.
pub const METERING_CELL: u32 = 4;
/// The reflected-light meter's calibration constant `K` (ISO 2720), cd·s/m².
pub const METER_CALIBRATION: f64 = 12.5;

/// Auto-exposure's bounds, compensation and speeds (`[display]`'s `auto_*` keys).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutoExposure {
    /// The lowest EV100 the meter may choose (a moonless sky at a dark site meters about −9.5).
    pub ev100_min: f64,
    /// The highest EV100 the meter may choose (noon is about 15).
    pub ev100_max: f64,
    /// Exposure compensation, EV: positive brightens the picture (lowers the EV100).
    pub compensation_ev: f64,
    /// How fast the EV100 rises when the scene brightens, EV per second, > 0.
    pub speed_up_ev_per_s: f64,
    /// How fast the EV100 falls when the scene darkens, EV per second, > 0.
    pub speed_down_ev_per_s: f64,
}

impl Default for AutoExposure {
    /// From a moonless night to a snowfield at noon; an eye's pace: 3 EV/s up, 1 EV/s down
    /// (Unreal's defaults).
    fn default() -> Self {
        Self {
            ev100_min: -10.0,
            ev100_max: 18.0,
            compensation_ev: 0.0,
            speed_up_ev_per_s: 3.0,
            speed_down_ev_per_s: 1.0,
        }
    }
}

impl AutoExposure {
    /// The EV100 that puts `metered_luminance` (cd/m²) on middle grey: the meter's EV100, less
    /// the compensation, within the bounds; the lowest for nothing metered (`None`).
    pub fn target_ev100(&self, metered_luminance: Option<f64>) -> f64 {
        match metered_luminance {
            Some(l) => (ev100_for_luminance(l) - self.compensation_ev).clamp(self.ev100_min, self.ev100_max),
            None => self.ev100_min,
        }
    }

    /// Moves `current` towards `target` by at most the speed times `seconds`; `None` (a still,
    /// or the first frame) jumps there at once. Within reach it arrives at `target` exactly
    /// (`current + (target − current)` can miss it by a rounding), so a frame that adapts within
    /// its step equals one metered afresh.
    pub fn adapt(&self, current: f64, target: f64, seconds: Option<f64>) -> f64 {
        match seconds {
            None => target,
            Some(dt) => {
                let (down, up) = (self.speed_down_ev_per_s * dt, self.speed_up_ev_per_s * dt);
                let step = target - current;
                if (-down..=up).contains(&step) {
                    target
                } else {
                    current + step.clamp(-down, up)
                }
            }
        }
    }
}

/// Whether the exposure is the scene's own or the meter's.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ExposureMode {
    /// The scene's `ev100` (or plain multiplier).
    #[default]
    Manual,
    /// Metered from each frame.
    Auto(AutoExposure),
}

/// The reflected-light meter: `EV100 = log2(L · 100 / K)` for a luminance `L` in cd/m².
pub fn ev100_for_luminance(luminance: f64) -> f64 {
    (luminance * 100.0 / METER_CALIBRATION).log2()
}

/// Rec. 709 luminance of linear RGB (cd/m² when the RGB is).
pub fn luminance(c: LinearRgb) -> f64 {
    0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b
}

/// The metered luminance of `luminances` (cd/m²; pixels on a sun's disc already left out): those
/// below the metering range (black, NaN, negative) left out, the rest clamped to its top, the
/// darkest and brightest shares dropped — fractions of a pixel at the cuts — and the geometric
/// mean of the rest. `None` when no pixel is left.
pub fn metered_luminance(luminances: &[f64]) -> Option<f64> {
    let mut logs: Vec<f64> = luminances
        .iter()
        .filter(|&&l| l >= METERING_LOG2_MIN.exp2())
        .map(|&l| l.log2().min(METERING_LOG2_MAX))
        .collect();
    if logs.is_empty() {
        return None;
    }
    logs.sort_by(f64::total_cmp);
    let n = logs.len() as f64;
    let (low, high) = (METERING_DARK_FRACTION * n, (1.0 - METERING_BRIGHT_FRACTION) * n);
    let (mut weight, mut sum) = (0.0, 0.0);
    for (i, log) in logs.iter().enumerate() {
        let kept = (high.min(i as f64 + 1.0) - low.max(i as f64)).max(0.0);
        weight += kept;
        sum += kept * log;
    }
    Some((sum / weight).exp2())
}

/// The cosine of the angle within which the meter leaves a disc of `angular_radius` out.
pub fn masked_cos(angular_radius: f64) -> f64 {
    (METERING_DISC_MARGIN * angular_radius).min(std::f64::consts::PI).cos()
}

/// The suns whose discs the meter leaves out, unit world direction and angular radius (radians):
/// the physical atmosphere's drawn discs and the gradient sky's sun. (The Moon and the stars are
/// left to the bright share the meter drops.)
pub fn sun_discs(frame: &crate::Frame) -> Vec<(DVec3, f64)> {
    match &frame.sky {
        Sky::Atmosphere(sky) => sky
            .suns
            .iter()
            .filter(|sun| sun.disc)
            .map(|sun| (sun.direction.normalize(), sun.angular_radius))
            .collect(),
        Sky::Gradient(sky) => vec![(sky.sun.direction.normalize(), sky.sun.angular_radius)],
        Sky::Empirical(_) | Sky::Clear(_) => Vec::new(),
    }
}

/// Whether the meter leaves out a view direction: within [`METERING_DISC_MARGIN`] angular radii
/// of a disc of [`sun_discs`].
pub fn is_masked(discs: &[(DVec3, f64)], view: DVec3) -> bool {
    discs
        .iter()
        .any(|(direction, radius)| view.normalize().dot(*direction) >= masked_cos(*radius))
}

/// The metered luminance of an image of `frame` (row-major, top row first, `width` pixels wide)
/// seen by `camera` (aspect set): [`metered_luminance`] of its cells' mean luminances, each over
/// the cell's pixels whose centres' view rays miss the masked sun discs (a cell with none is
/// left out). `None` for no cell left.
pub fn meter_image(frame: &crate::Frame, camera: &crate::Camera, radiance: &[LinearRgb], width: u32) -> Option<f64> {
    let discs = sun_discs(frame);
    let width = width.max(1);
    let height = radiance.len() as u32 / width;
    let cells_x = width.div_ceil(METERING_CELL);
    let mut cells = vec![(0.0, 0_u32); (cells_x * height.div_ceil(METERING_CELL)) as usize];
    for (i, c) in radiance.iter().enumerate() {
        let (x, y) = (i as u32 % width, i as u32 / width);
        let ndc = glam::DVec2::new(
            (f64::from(x) + 0.5) / f64::from(width) * 2.0 - 1.0,
            1.0 - (f64::from(y) + 0.5) / f64::from(height) * 2.0,
        );
        if !is_masked(&discs, camera.view_direction(ndc)) {
            let cell = &mut cells[((y / METERING_CELL) * cells_x + x / METERING_CELL) as usize];
            cell.0 += luminance(*c);
            cell.1 += 1;
        }
    }
    let means: Vec<f64> = cells
        .iter()
        .filter(|(_, n)| *n > 0)
        .map(|(sum, n)| sum / f64::from(*n))
        .collect();
    metered_luminance(&means)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn middle_grey_at_the_meters_ev() {
        // 2^12 cd/m² meters EV100 15, the sunny-16 daylight exposure.
        assert!((ev100_for_luminance(4096.0) - 15.0).abs() < 1e-12);
        // A moonless night sky at a dark site, about 1.7e-4 cd/m² (22 V mag/arcsec²), meters
        // about −9.5.
        assert!((ev100_for_luminance(1.7e-4) + 9.52).abs() < 0.01);
    }

    #[test]
    fn the_meter_drops_the_extremes_and_takes_the_geometric_mean() {
        // 90 pixels at 4, 5 at 1e-3 (dark), 5 at 1e6 (bright): only the 4s count.
        let mut pixels = vec![4.0; 90];
        pixels.extend([1e-3; 5]);
        pixels.extend([1e6; 5]);
        assert!((metered_luminance(&pixels).unwrap() - 4.0).abs() < 1e-12);
        // Half at 1, half at 16: geometric mean 4.
        let pixels: Vec<f64> = (0..1000).map(|i| if i % 2 == 0 { 1.0 } else { 16.0 }).collect();
        assert!((metered_luminance(&pixels).unwrap() - 4.0).abs() < 1e-9);
        assert_eq!(metered_luminance(&[]), None);
        // Black, NaN and negative pixels are not metered.
        assert_eq!(metered_luminance(&[0.0, f64::NAN, -1.0, 1e-9]), None);
        assert!((metered_luminance(&[0.0, 2.0, f64::NAN]).unwrap() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn adaptation_is_limited_by_the_speeds_and_the_bounds() {
        let auto = AutoExposure::default();
        assert_eq!(auto.adapt(5.0, 10.0, None), 10.0);
        assert!((auto.adapt(5.0, 10.0, Some(0.5)) - 6.5).abs() < 1e-12);
        assert!((auto.adapt(5.0, 0.0, Some(0.5)) - 4.5).abs() < 1e-12);
        assert!((auto.adapt(5.0, 5.2, Some(1.0)) - 5.2).abs() < 1e-12);
        assert_eq!(auto.target_ev100(Some(1e-12)), auto.ev100_min);
        assert_eq!(auto.target_ev100(Some(1e12)), auto.ev100_max);
        assert_eq!(auto.target_ev100(None), auto.ev100_min);
        let brighter = AutoExposure {
            compensation_ev: 1.0,
            ..auto
        };
        assert!((brighter.target_ev100(Some(4096.0)) - 14.0).abs() < 1e-12);
    }
}
