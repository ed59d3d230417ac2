//! Fog: the OpenGL 2.1 fixed-function fog (specification §3.10, equations 3.16–3.18) and an
//! exponential height fog integrated in closed form along the view ray (the model of Unreal
//! Engine's exponential height fog; see Wenzel, "Real-time Atmospheric Effects in Games", 2006).

use glam::{DVec3, DVec4};

/// The fixed-function fog equations. The result is the factor `f` in `[0, 1]` that keeps the
/// fragment's colour: `C = f·C_r + (1 − f)·C_f`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FogMode {
    /// `GL_LINEAR`: `f = (end − c) / (end − start)`.
    Linear {
        /// `GL_FOG_START`.
        start: f64,
        /// `GL_FOG_END`.
        end: f64,
    },
    /// `GL_EXP`: `f = exp(−density · c)`.
    Exp {
        /// `GL_FOG_DENSITY`, >= 0.
        density: f64,
    },
    /// `GL_EXP2`: `f = exp(−(density · c)²)`.
    Exp2 {
        /// `GL_FOG_DENSITY`, >= 0.
        density: f64,
    },
}

/// Which distance feeds the fog equation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FogCoordinate {
    /// `|z_eye|`, the eye-plane depth: what most fixed-function implementations used.
    #[default]
    EyePlaneDepth,
    /// The true eye distance `|p_eye|` (no extra haze at the edges of a wide field of view).
    EyeDistance,
    /// `GL_FOG_COORD`: the vertex's own fog coordinate, used as it is (no absolute value): the
    /// mesh's per-vertex array, or the object's current fog coordinate where the mesh has none.
    Vertex,
}

impl FogCoordinate {
    /// The fog coordinate of a vertex at eye-space `eye_position` whose own fog coordinate
    /// (`glFogCoord`) is `vertex`.
    pub fn of(self, eye_position: DVec3, vertex: f64) -> f64 {
        match self {
            Self::EyePlaneDepth => eye_position.z.abs(),
            Self::EyeDistance => eye_position.length(),
            Self::Vertex => vertex,
        }
    }
}

impl FogMode {
    /// The fog factor for fog coordinate `c`, clamped to `[0, 1]` as GL does. A linear fog with
    /// `start == end` keeps everything nearer than `end` and fogs the rest fully.
    pub fn factor(self, c: f64) -> f64 {
        let f = match self {
            Self::Linear { start, end } if end == start => {
                if c < end {
                    1.0
                } else {
                    0.0
                }
            }
            Self::Linear { start, end } => (end - c) / (end - start),
            Self::Exp { density } => (-density * c).exp(),
            Self::Exp2 { density } => (-(density * c).powi(2)).exp(),
        };
        if f.is_nan() { 0.0 } else { f.clamp(0.0, 1.0) }
    }

    /// Blends `color` towards `fog_color` for fog coordinate `c`; alpha is untouched, as in GL.
    pub fn apply(self, color: DVec4, fog_color: DVec4, c: f64) -> DVec4 {
        let f = self.factor(c);
        let rgb = color.truncate() * f + fog_color.truncate() * (1.0 - f);
        rgb.extend(color.w)
    }
}

/// Fixed-function fog as a whole: equation, coordinate and colour (`glFog`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fog {
    /// The equation and its parameters.
    pub mode: FogMode,
    /// Which distance feeds it.
    pub coordinate: FogCoordinate,
    /// `GL_FOG_COLOR`.
    pub color: DVec4,
}

/// Fog whose density falls exponentially with height: `σ(h) = density · exp(−falloff · (h − base))`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeightFog {
    /// Extinction at `base_height`, 1/m, >= 0.
    pub density: f64,
    /// How fast the density falls with height, 1/m, >= 0 (0 = uniform fog).
    pub falloff: f64,
    /// Height where the density equals `density`, metres (world +z).
    pub base_height: f64,
}

impl HeightFog {
    /// The optical depth `∫ σ(h(t)) dt` along the segment from `from` to `to` (world frame, +z up),
    /// in closed form: `σ(h₀) · (1 − exp(−k·Δh)) / (k·Δh/L)`, with the limit `σ(h₀)·L` when the
    /// segment is level or `falloff = 0`.
    pub fn optical_depth(&self, from: DVec3, to: DVec3) -> f64 {
        let length = (to - from).length();
        let rise = to.z - from.z;
        let sigma0 = self.density * (-self.falloff * (from.z - self.base_height)).exp();
        let x = self.falloff * rise;
        // (1 − e^(−x)) / x → 1 as x → 0; use the series near 0 to avoid cancellation.
        let ratio = if x.abs() < 1e-6 {
            1.0 - x / 2.0 + x * x / 6.0
        } else {
            -(-x).exp_m1() / x
        };
        sigma0 * length * ratio
    }

    /// The fraction of light that survives the segment (`exp(−optical depth)`): the factor `f`
    /// that keeps the surface's colour.
    pub fn transmittance(&self, from: DVec3, to: DVec3) -> f64 {
        (-self.optical_depth(from, to)).exp()
    }
}

/// Sunlight scattered towards the eye by a height fog, strongest looking at the sun: the fog's
/// in-scattered colour becomes `color + sun.color · max(v·l, 0)^exponent` for a view direction
/// `v` and a direction to the sun `l` (Unreal Engine's directional in-scattering of its
/// exponential height fog, a Henyey-Greenstein-like lobe without normalisation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FogSun {
    /// Unit direction towards the sun, world frame.
    pub direction: DVec3,
    /// Colour added at the centre of the lobe (the fog colour's units).
    pub color: DVec4,
    /// Lobe exponent, >= 1 (larger = tighter around the sun).
    pub exponent: f64,
}

impl FogSun {
    /// The in-scattered colour seen along unit world direction `view` through a fog of colour
    /// `fog_color`; alpha is the fog colour's.
    pub fn inscattered(&self, fog_color: DVec4, view: DVec3) -> DVec4 {
        let lobe = view.dot(self.direction).max(0.0).powf(self.exponent);
        (fog_color.truncate() + self.color.truncate() * lobe).extend(fog_color.w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_function_equations() {
        let linear = FogMode::Linear { start: 10.0, end: 30.0 };
        assert_eq!(linear.factor(5.0), 1.0);
        assert_eq!(linear.factor(20.0), 0.5);
        assert_eq!(linear.factor(40.0), 0.0);
        let exp = FogMode::Exp { density: 0.1 };
        assert!((exp.factor(10.0) - (-1f64).exp()).abs() < 1e-15);
        let exp2 = FogMode::Exp2 { density: 0.1 };
        assert!((exp2.factor(20.0) - (-4f64).exp()).abs() < 1e-15);
        assert_eq!(FogMode::Linear { start: 5.0, end: 5.0 }.factor(4.0), 1.0);
        assert_eq!(FogMode::Exp { density: f64::NAN }.factor(1.0), 0.0);
        let c = linear.apply(DVec4::new(1.0, 0.0, 0.0, 0.3), DVec4::new(0.0, 0.0, 1.0, 1.0), 20.0);
        assert_eq!(c, DVec4::new(0.5, 0.0, 0.5, 0.3));
    }

    #[test]
    fn eye_distance_versus_plane_depth() {
        let p = DVec3::new(3.0, 0.0, -4.0);
        assert_eq!(FogCoordinate::EyePlaneDepth.of(p, 7.0), 4.0);
        assert_eq!(FogCoordinate::EyeDistance.of(p, 7.0), 5.0);
        assert_eq!(FogCoordinate::Vertex.of(p, -7.0), -7.0);
        // A negative coordinate is kept; the factor's clamp keeps the colour.
        assert_eq!(FogMode::Exp { density: 0.5 }.factor(-7.0), 1.0);
    }

    #[test]
    fn height_fog_matches_numerical_integration() {
        let fog = HeightFog {
            density: 0.02,
            falloff: 0.01,
            base_height: 5.0,
        };
        for (from, to) in [
            (DVec3::new(0.0, 0.0, 2.0), DVec3::new(300.0, 40.0, 120.0)),
            (DVec3::new(0.0, 0.0, 200.0), DVec3::new(-50.0, 10.0, 0.0)),
            (DVec3::new(0.0, 0.0, 7.0), DVec3::new(500.0, 0.0, 7.0)),
            (DVec3::new(0.0, 0.0, 7.0), DVec3::new(500.0, 0.0, 7.000_000_01)),
        ] {
            let n = 200_000;
            let step = (to - from) / f64::from(n);
            let mut sum = 0.0;
            for i in 0..n {
                let p = from + step * (f64::from(i) + 0.5);
                sum += fog.density * (-fog.falloff * (p.z - fog.base_height)).exp() * step.length();
            }
            let closed = fog.optical_depth(from, to);
            assert!(((closed - sum) / sum).abs() < 1e-8, "{from} → {to}: {closed} vs {sum}");
        }
        let uniform = HeightFog { falloff: 0.0, ..fog };
        let sun = FogSun {
            direction: DVec3::X,
            color: DVec4::new(1.0, 0.5, 0.0, 0.0),
            exponent: 4.0,
        };
        let grey = DVec4::new(0.2, 0.2, 0.2, 1.0);
        assert_eq!(sun.inscattered(grey, DVec3::X), DVec4::new(1.2, 0.7, 0.2, 1.0));
        assert_eq!(sun.inscattered(grey, DVec3::NEG_X), grey);
        let half = sun.inscattered(grey, DVec3::new(1.0, 1.0, 0.0).normalize());
        assert!((half.x - (0.2 + 0.25)).abs() < 1e-12, "{half}");
        assert!(
            (uniform.transmittance(DVec3::ZERO, DVec3::new(0.0, 100.0, 50.0)) - (-0.02 * 125f64.sqrt() * 10.0).exp())
                .abs()
                < 1e-12
        );
    }
}
