//! The light the atmosphere gives users' own materials at the camera: each sun's direction and
//! colour after the atmosphere's transmittance, and the sky's radiance as spherical harmonics of
//! bands 0–2, from which the irradiance on any normal follows (Ramamoorthi & Hanrahan 2001, "An
//! Efficient Representation for Irradiance Environment Maps", SIGGRAPH 2001).
//!
//! The GPU fills a [`SkyLightingGpu`] each frame (`atmosphere/sky_lighting.wgsl`); users' shaders
//! read it through `shaders/include/firmament_lighting.wgsl`. The `f64` functions here evaluate
//! the same quantities on the CPU, from a buffer read back or for tests.
//!
//! # Conventions
//! - Directions: unit vectors in the world frame (firmament's camera and suns).
//! - Units: linear sRGB whose Y is the photometric quantity — radiance in cd/m² (the sky firmament
//!   draws), irradiance in lux (lm/m² = cd·sr/m²). A Lambertian surface of albedo ρ under
//!   irradiance E has the radiance ρ·E/π, in the sky's units.
//! - Spherical harmonics: the real basis of Ramamoorthi & Hanrahan's eq. 3 ([`sh_basis`]),
//!   coefficient `l(l + 1) + m` for m = −l … l: `Y_00 = 1/(2√π)`, `Y_1m = √(3/4π)·(y, z, x)`,
//!   `Y_2m = √(15/4π)·xy, √(15/4π)·yz, √(5/16π)·(3z² − 1), √(15/4π)·xz, √(15/16π)·(x² − y²)`.
//!   The stored coefficients are those of the *radiance*, `L_lm = ∫ L(ω)·Y_lm(ω) dω`; the
//!   irradiance multiplies band l by `Â_l` ([`IRRADIANCE_BAND_FACTORS`]).

use bytemuck::{Pod, Zeroable};
use firmament_core::Camera;
use firmament_core::frame::{AtmosphereSky, MAX_SUNS};
use glam::{DMat3, DMat4, DVec3};

use super::planet_view::FAR_CAMERA_RADII;

/// Spherical-harmonic coefficients of bands 0–2.
pub const SKY_SH_COEFFICIENTS: usize = 9;

/// The sky grid of `atmosphere/sky_lighting.wgsl`: azimuth cells × rows (uniform in the cosine of
/// the zenith angle about the camera's local up, so every cell spans the same solid angle).
pub const SKY_LIGHTING_GRID: (u32, u32) = (256, 128);

/// The cosine lobe's spherical-harmonic factors `Â_l` for bands 0, 1, 2: π, 2π/3, π/4
/// (Ramamoorthi & Hanrahan 2001, eq. 8). The irradiance is `E(n) = Σ Â_l·L_lm·Y_lm(n)`.
pub const IRRADIANCE_BAND_FACTORS: [f64; 3] = [
    std::f64::consts::PI,
    2.0 * std::f64::consts::PI / 3.0,
    std::f64::consts::FRAC_PI_4,
];

/// The real spherical harmonics `Y_lm(d)` of bands 0–2 at index `l(l + 1) + m` (Ramamoorthi &
/// Hanrahan 2001, eq. 3), `d` a unit vector.
pub fn sh_basis(d: DVec3) -> [f64; SKY_SH_COEFFICIENTS] {
    use std::f64::consts::PI;
    let band0 = 0.5 / PI.sqrt();
    let band1 = (3.0 / (4.0 * PI)).sqrt();
    let band2 = (15.0 / (4.0 * PI)).sqrt();
    let band2_zonal = (5.0 / (16.0 * PI)).sqrt();
    let band2_sectoral = (15.0 / (16.0 * PI)).sqrt();
    [
        band0,
        band1 * d.y,
        band1 * d.z,
        band1 * d.x,
        band2 * d.x * d.y,
        band2 * d.y * d.z,
        band2_zonal * (3.0 * d.z * d.z - 1.0),
        band2 * d.x * d.z,
        band2_sectoral * (d.x * d.x - d.y * d.y),
    ]
}

/// The band `l` of coefficient `k = l(l + 1) + m`.
fn band(k: usize) -> usize {
    match k {
        0 => 0,
        1..=3 => 1,
        _ => 2,
    }
}

/// The irradiance on unit normal `n` of a radiance known by its coefficients `sh` (one value per
/// coefficient, of any type that scales: a channel, a colour): `Σ Â_l·L_lm·Y_lm(n)`, unclamped.
pub fn sh_irradiance(sh: &[DVec3; SKY_SH_COEFFICIENTS], n: DVec3) -> DVec3 {
    sh_basis(n)
        .iter()
        .enumerate()
        .map(|(k, y)| sh[k] * (IRRADIANCE_BAND_FACTORS[band(k)] * y))
        .sum()
}

/// One sun as the lighting buffer holds it (mirrors `SkyLightingSun` in
/// `atmosphere/bindings.wgsl` and `FirmamentSun` in `include/firmament_lighting.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Pod, Zeroable)]
pub struct SkyLightingSunGpu {
    /// Unit direction towards the sun, world frame; `w` = its angular radius, radians.
    pub direction: [f32; 4],
    /// Its irradiance at the camera on a surface facing it, after the atmosphere's
    /// transmittance: `E·T`, linear sRGB with Y in lux; `w` = 0.
    pub color: [f32; 4],
}

/// The per-frame lighting buffer (416 bytes; mirrors `SkyLighting` in
/// `atmosphere/bindings.wgsl` and `FirmamentSkyLighting` in `include/firmament_lighting.wgsl`).
/// See the module docs for frames, units and the spherical-harmonic convention.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Pod, Zeroable)]
pub struct SkyLightingGpu {
    /// `x` = number of suns (at most [`MAX_SUNS`]); `y`, `z`, `w` = 0.
    pub sun_count: [u32; 4],
    /// The suns; the first `sun_count[0]` are set, the others zero.
    pub suns: [SkyLightingSunGpu; MAX_SUNS],
    /// The sky's radiance (sky and lit ground, no sun discs) as real spherical harmonics of bands
    /// 0–2 in the world frame: `rgb` = `L_lm` at index `l(l + 1) + m`, linear sRGB whose Y is in
    /// cd/m²; `w` = 0.
    pub sky_sh: [[f32; 4]; SKY_SH_COEFFICIENTS],
}

impl SkyLightingGpu {
    /// The lighting read back from the buffer's bytes (at least `size_of::<Self>()` of them).
    pub fn from_bytes(bytes: &[u8]) -> Option<Self> {
        bytes
            .get(..std::mem::size_of::<Self>())
            .map(bytemuck::pod_read_unaligned)
    }

    /// The number of suns.
    pub fn sun_count(&self) -> usize {
        (self.sun_count[0] as usize).min(MAX_SUNS)
    }

    /// The sky's coefficients `L_lm` as `f64` colours.
    pub fn sky_sh(&self) -> [DVec3; SKY_SH_COEFFICIENTS] {
        self.sky_sh
            .map(|c| DVec3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2])))
    }

    /// The sky's irradiance (lux, linear sRGB) on a surface of unit world normal `n`, as
    /// `firmament_sky_irradiance` computes it in the WGSL include (in `f64`, clamped at zero).
    pub fn sky_irradiance(&self, n: DVec3) -> DVec3 {
        sh_irradiance(&self.sky_sh(), n).max(DVec3::ZERO)
    }

    /// Sun `i`'s unit world direction.
    pub fn sun_direction(&self, i: usize) -> DVec3 {
        let d = self.suns[i].direction;
        DVec3::new(f64::from(d[0]), f64::from(d[1]), f64::from(d[2]))
    }

    /// Sun `i`'s `E·T` at the camera (lux, linear sRGB).
    pub fn sun_color(&self, i: usize) -> DVec3 {
        let c = self.suns[i].color;
        DVec3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2]))
    }
}

/// Mirrors `SkyLightingParams` in `atmosphere/bindings.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct SkyLightingParamsUniforms {
    /// Rotation from the planet frame to the world frame.
    pub planet_to_world: [[f32; 4]; 4],
    /// `x` = 1 when the sky gives no light (the camera is farther than [`FAR_CAMERA_RADII`]
    /// top-of-atmosphere radii from the planet centre, where `f32` positions no longer resolve
    /// the air); `y`, `z`, `w` unused.
    pub flags: [f32; 4],
}

impl SkyLightingParamsUniforms {
    /// The parameters of `sky` seen from `camera`.
    pub fn new(sky: &AtmosphereSky, camera: &Camera) -> Self {
        let planet = &sky.atmosphere.planet;
        let top = planet.radii.max_element() + planet.atmosphere_height;
        let far = (camera.position - planet.center).length() > FAR_CAMERA_RADII * top;
        let rotation = DMat3::from_quat(planet.orientation.normalize());
        Self {
            planet_to_world: DMat4::from_mat3(rotation).as_mat4().to_cols_array_2d(),
            flags: [if far { 1.0 } else { 0.0 }, 0.0, 0.0, 0.0],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The projection `atmosphere/sky_lighting.wgsl` makes, in `f64`, of a radiance about the
    /// local up `z`: one sample at the centre of each equal-area cell.
    fn project(radiance: impl Fn(DVec3) -> f64) -> [DVec3; SKY_SH_COEFFICIENTS] {
        let (columns, rows) = SKY_LIGHTING_GRID;
        let cell = 4.0 * PI / f64::from(columns * rows);
        let mut sh = [DVec3::ZERO; SKY_SH_COEFFICIENTS];
        for row in 0..rows {
            let z = 1.0 - (f64::from(row) + 0.5) * 2.0 / f64::from(rows);
            for column in 0..columns {
                let phi = (f64::from(column) + 0.5) * 2.0 * PI / f64::from(columns);
                let s = (1.0 - z * z).sqrt();
                let d = DVec3::new(s * phi.cos(), s * phi.sin(), z);
                let l = radiance(d);
                for (c, y) in sh.iter_mut().zip(sh_basis(d)) {
                    *c += DVec3::splat(l * y * cell);
                }
            }
        }
        sh
    }

    #[test]
    fn the_basis_is_orthonormal() {
        for i in 0..SKY_SH_COEFFICIENTS {
            let sh = project(|d| sh_basis(d)[i]);
            for (j, c) in sh.iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((c.x - want).abs() < 2e-3, "<Y{i}, Y{j}> = {}", c.x);
            }
        }
    }

    #[test]
    fn a_uniform_sky_gives_pi_times_its_radiance_on_every_normal() {
        let sh = project(|_| 2.0);
        for n in [DVec3::Z, DVec3::X, -DVec3::Y, DVec3::new(1.0, -2.0, 3.0).normalize()] {
            let e = sh_irradiance(&sh, n);
            // The midpoint rule leaves ~1e-4 in band 2 (of 3z² − 1 over the rows).
            assert!((e.x / (2.0 * PI) - 1.0).abs() < 1e-3, "{n}: {e}");
        }
    }

    #[test]
    fn bands_one_and_two_convolve_exactly() {
        // L = 1 + z: E(n) = π + (2π/3)·n_z.
        let sh = project(|d| 1.0 + d.z);
        for n in [DVec3::Z, -DVec3::Z, DVec3::X, DVec3::new(0.3, 0.4, -0.5).normalize()] {
            let want = PI + 2.0 * PI / 3.0 * n.z;
            let e = sh_irradiance(&sh, n).x;
            assert!((e - want).abs() < 1e-3 * PI, "{n}: {e} vs {want}");
        }
        // L = z²: E(up) = π/2 and E(horizontal) = π/4 (the integrals done by hand).
        let sh = project(|d| d.z * d.z);
        for (n, want) in [(DVec3::Z, PI / 2.0), (DVec3::Y, PI / 4.0), (-DVec3::Z, PI / 2.0)] {
            let e = sh_irradiance(&sh, n).x;
            assert!((e - want).abs() < 1e-3 * PI, "{n}: {e} vs {want}");
        }
    }

    #[test]
    fn a_clamped_cosine_sky_is_within_ramamoorthi_and_hanrahan_s_error() {
        // A sky of radiance max(z, 0) (bright overhead, black below the horizon): the exact
        // irradiance of the up normal is 2π/3; bands 0-2 hold it to a few per cent.
        let sh = project(|d| d.z.max(0.0));
        let e = sh_irradiance(&sh, DVec3::Z).x;
        let want = 2.0 * PI / 3.0;
        assert!((e / want - 1.0).abs() < 0.05, "{e} vs {want}");
    }
}
