//! The keyframed gradient sky (seed 002): colour by elevation in five bands, interpolated over
//! the day between keyframes.
//!
//! Elevation `e` (radians, above the horizon) picks the colour:
//!
//! | elevation                          | colour                                            |
//! |------------------------------------|---------------------------------------------------|
//! | `e >= zenith_start`                | `zenith`                                          |
//! | `horizon_half_width <= e < zenith_start` | upper gradient: `upper` → `zenith`          |
//! | `-horizon_half_width <= e < horizon_half_width` | horizon band: `lower` → `horizon` (at 0) → `upper` |
//! | `ground_start < e < -horizon_half_width` | lower gradient: `lower` → `ground`           |
//! | `e <= ground_start`                | `ground`                                          |
//!
//! Each gradient's weight is `t^exponent`, then (with [`Blend::Smooth`]) a Hermite smoothstep, so
//! the colour is continuous everywhere and, when smooth, has no visible kinks at band edges.

use crate::color::LinearRgb;
use crate::error::CoreError;
use crate::sky::time_of_day::TimeOfDay;

/// How a weight in [0, 1] is shaped before it mixes two colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Blend {
    /// Straight linear mix: continuous, with kinks at the ends.
    Linear,
    /// Hermite smoothstep: continuous with a continuous first derivative.
    #[default]
    Smooth,
}

impl Blend {
    /// The shaped weight for `t` in [0, 1].
    pub fn shape(self, t: f64) -> f64 {
        let t = t.clamp(0.0, 1.0);
        match self {
            Self::Linear => t,
            Self::Smooth => t * t * (3.0 - 2.0 * t),
        }
    }
}

/// Where the bands lie and how the gradients are curved. Angles are elevations in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GradientShape {
    /// Elevation where the upper gradient ends and the zenith colour begins, radians, in
    /// (`horizon_half_width`, π/2].
    pub zenith_start: f64,
    /// Half-height of the horizon band, radians, in (0, π/2).
    pub horizon_half_width: f64,
    /// Elevation where the lower gradient ends and the ground colour begins, radians, in
    /// [-π/2, -`horizon_half_width`).
    pub ground_start: f64,
    /// Exponent on the upper gradient's weight (< 1 reaches the zenith colour sooner), > 0.
    pub upper_exponent: f64,
    /// Exponent on the lower gradient's weight, > 0.
    pub lower_exponent: f64,
    /// How weights are shaped, in every band.
    pub blend: Blend,
}

impl Default for GradientShape {
    fn default() -> Self {
        Self {
            zenith_start: 70f64.to_radians(),
            horizon_half_width: 4f64.to_radians(),
            ground_start: -30f64.to_radians(),
            upper_exponent: 0.6,
            lower_exponent: 1.0,
            blend: Blend::Smooth,
        }
    }
}

impl GradientShape {
    /// Checks every rule in the field docs.
    pub fn validate(&self) -> Result<(), CoreError> {
        let invalid = |field, value: f64, rule| {
            Err(CoreError::Invalid {
                field,
                value: value.to_degrees().to_string(),
                rule,
            })
        };
        let hw = self.horizon_half_width;
        if !(hw > 0.0 && hw < std::f64::consts::FRAC_PI_2) {
            return invalid("horizon_half_width", hw, "must be in (0, 90) degrees");
        }
        if !(self.zenith_start > hw && self.zenith_start <= std::f64::consts::FRAC_PI_2) {
            return invalid(
                "zenith_start",
                self.zenith_start,
                "must be above the horizon band and at most 90 degrees",
            );
        }
        if !(self.ground_start < -hw && self.ground_start >= -std::f64::consts::FRAC_PI_2) {
            return invalid(
                "ground_start",
                self.ground_start,
                "must be below the horizon band and at least -90 degrees",
            );
        }
        for (field, e) in [
            ("upper_exponent", self.upper_exponent),
            ("lower_exponent", self.lower_exponent),
        ] {
            if !(e.is_finite() && e > 0.0) {
                return Err(CoreError::Invalid {
                    field,
                    value: e.to_string(),
                    rule: "must be a finite number > 0",
                });
            }
        }
        Ok(())
    }
}

/// The colours of every band (and of the sun) at one moment. All linear RGB radiance.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SkyBands {
    /// Straight up, and everything above `zenith_start`.
    pub zenith: LinearRgb,
    /// The top of the horizon band, where the upper gradient starts.
    pub upper: LinearRgb,
    /// Exactly at the horizon (elevation 0).
    pub horizon: LinearRgb,
    /// The bottom of the horizon band, where the lower gradient starts.
    pub lower: LinearRgb,
    /// Straight down, and everything below `ground_start`.
    pub ground: LinearRgb,
    /// The sun's colour (multiplied by the disc and glow intensities).
    pub sun: LinearRgb,
}

impl SkyBands {
    /// The sky colour at an elevation (radians) for a band layout.
    pub fn color_at(&self, shape: &GradientShape, elevation: f64) -> LinearRgb {
        let hw = shape.horizon_half_width;
        let blend = shape.blend;
        if elevation >= shape.zenith_start {
            self.zenith
        } else if elevation >= hw {
            let t = (elevation - hw) / (shape.zenith_start - hw);
            self.upper.lerp(self.zenith, blend.shape(t.powf(shape.upper_exponent)))
        } else if elevation >= 0.0 {
            self.horizon.lerp(self.upper, blend.shape(elevation / hw))
        } else if elevation >= -hw {
            self.horizon.lerp(self.lower, blend.shape(-elevation / hw))
        } else if elevation > shape.ground_start {
            let t = (-hw - elevation) / (-hw - shape.ground_start);
            self.lower.lerp(self.ground, blend.shape(t.powf(shape.lower_exponent)))
        } else {
            self.ground
        }
    }

    /// Every colour mixed towards `other` by `t` (0 → `self`, 1 → `other`).
    pub fn lerp(&self, other: &Self, t: f64) -> Self {
        Self {
            zenith: self.zenith.lerp(other.zenith, t),
            upper: self.upper.lerp(other.upper, t),
            horizon: self.horizon.lerp(other.horizon, t),
            lower: self.lower.lerp(other.lower, t),
            ground: self.ground.lerp(other.ground, t),
            sun: self.sun.lerp(other.sun, t),
        }
    }
}

/// The sky's colours at one time of day.
#[derive(Debug, Clone, PartialEq)]
pub struct SkyKeyframe {
    /// When these colours hold exactly.
    pub time: TimeOfDay,
    /// The colours at that time.
    pub bands: SkyBands,
}

/// A day/night cycle: keyframes around the clock, interpolated with wrap-around at midnight.
#[derive(Debug, Clone, PartialEq)]
pub struct DayCycle {
    keyframes: Vec<SkyKeyframe>,
    blend: Blend,
}

impl DayCycle {
    /// A cycle from keyframes in any order. Needs at least one keyframe and distinct times.
    pub fn new(mut keyframes: Vec<SkyKeyframe>, blend: Blend) -> Result<Self, CoreError> {
        if keyframes.is_empty() {
            return Err(CoreError::NoKeyframes);
        }
        let mut order: Vec<usize> = (0..keyframes.len()).collect();
        order.sort_by(|&a, &b| keyframes[a].time.seconds().total_cmp(&keyframes[b].time.seconds()));
        for pair in order.windows(2) {
            if keyframes[pair[0]].time == keyframes[pair[1]].time {
                let (first, second) = (pair[0].min(pair[1]), pair[0].max(pair[1]));
                let time = keyframes[first].time.to_string();
                return Err(CoreError::DuplicateKeyframeTime { first, second, time });
            }
        }
        keyframes.sort_by(|a, b| a.time.seconds().total_cmp(&b.time.seconds()));
        Ok(Self { keyframes, blend })
    }

    /// The keyframes, sorted by time.
    pub fn keyframes(&self) -> &[SkyKeyframe] {
        &self.keyframes
    }

    /// The band colours at `time`: a blend of the keyframes before and after it, wrapping past
    /// midnight (the last keyframe of the day blends into the first of the next).
    pub fn bands_at(&self, time: TimeOfDay) -> SkyBands {
        let n = self.keyframes.len();
        // The last keyframe at or before `time`, counting backwards past midnight.
        let next_index = self.keyframes.partition_point(|k| k.time.seconds() <= time.seconds());
        let prev = &self.keyframes[(next_index + n - 1) % n];
        let next = &self.keyframes[next_index % n];
        let span = prev.time.seconds_until(next.time);
        if span == 0.0 {
            return prev.bands; // a single keyframe holds all day
        }
        let t = prev.time.seconds_until(time) / span;
        prev.bands.lerp(&next.bands, self.blend.shape(t))
    }
}

/// A gradient sky ready to draw: band layout plus the colours of one moment and the sun.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GradientSkyState {
    /// Where the bands lie.
    pub shape: GradientShape,
    /// Their colours now.
    pub bands: SkyBands,
    /// The sun drawn over the bands.
    pub sun: crate::sky::sun::SunDisc,
}

impl GradientSkyState {
    /// The radiance seen along a unit view direction (local frame, +Z up): band colour plus sun.
    pub fn radiance(&self, view: glam::DVec3) -> LinearRgb {
        let elevation = view.z.clamp(-1.0, 1.0).asin();
        self.bands.color_at(&self.shape, elevation) + self.sun.radiance(view)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(v: f64) -> LinearRgb {
        LinearRgb::new(v, v, v)
    }

    fn bands(base: f64) -> SkyBands {
        SkyBands {
            zenith: grey(base + 0.1),
            upper: grey(base + 0.2),
            horizon: grey(base + 0.3),
            lower: grey(base + 0.4),
            ground: grey(base + 0.5),
            sun: grey(base),
        }
    }

    fn at(h: f64) -> TimeOfDay {
        TimeOfDay::from_hours(h).expect("finite")
    }

    #[test]
    fn band_colours_hold_at_their_stops() {
        let shape = GradientShape::default();
        let b = bands(0.0);
        assert_eq!(b.color_at(&shape, std::f64::consts::FRAC_PI_2), b.zenith);
        assert_eq!(b.color_at(&shape, shape.zenith_start), b.zenith);
        assert_eq!(b.color_at(&shape, shape.horizon_half_width), b.upper);
        assert_eq!(b.color_at(&shape, 0.0), b.horizon);
        assert_eq!(b.color_at(&shape, -shape.horizon_half_width), b.lower);
        assert_eq!(b.color_at(&shape, shape.ground_start), b.ground);
        assert_eq!(b.color_at(&shape, -std::f64::consts::FRAC_PI_2), b.ground);
    }

    #[test]
    fn colour_is_continuous_in_elevation() {
        for blend in [Blend::Linear, Blend::Smooth] {
            let shape = GradientShape {
                blend,
                ..GradientShape::default()
            };
            let b = bands(0.0);
            let steps = 100_000;
            let mut prev = b.color_at(&shape, -std::f64::consts::FRAC_PI_2);
            for i in 1..=steps {
                let e = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * f64::from(i) / f64::from(steps);
                let c = b.color_at(&shape, e);
                assert!(c.max_abs_diff(prev) < 1e-3, "jump at {e}");
                prev = c;
            }
        }
    }

    #[test]
    fn keyframes_hold_exactly_and_wrap_past_midnight() {
        let cycle = DayCycle::new(
            vec![
                SkyKeyframe {
                    time: at(22.0),
                    bands: bands(0.0),
                },
                SkyKeyframe {
                    time: at(2.0),
                    bands: bands(1.0),
                },
                SkyKeyframe {
                    time: at(12.0),
                    bands: bands(2.0),
                },
            ],
            Blend::Linear,
        )
        .expect("valid");
        assert_eq!(cycle.bands_at(at(2.0)), bands(1.0));
        assert_eq!(cycle.bands_at(at(12.0)), bands(2.0));
        // Midnight is halfway from 22:00 to 02:00.
        assert!(cycle.bands_at(at(0.0)).zenith.max_abs_diff(grey(0.6)) < 1e-12);
        // No pop across midnight: the colour just before equals the colour just after.
        let before = cycle.bands_at(TimeOfDay::from_seconds(86_399.999).expect("finite"));
        let after = cycle.bands_at(TimeOfDay::MIDNIGHT);
        assert!(before.zenith.max_abs_diff(after.zenith) < 1e-6);
    }

    #[test]
    fn one_keyframe_holds_all_day_and_bad_cycles_fail() {
        let one = DayCycle::new(
            vec![SkyKeyframe {
                time: at(5.0),
                bands: bands(0.3),
            }],
            Blend::Smooth,
        );
        assert_eq!(one.expect("valid").bands_at(at(17.0)), bands(0.3));
        assert_eq!(DayCycle::new(vec![], Blend::Smooth), Err(CoreError::NoKeyframes));
        let dup = DayCycle::new(
            vec![
                SkyKeyframe {
                    time: at(5.0),
                    bands: bands(0.0),
                },
                SkyKeyframe {
                    time: at(6.0),
                    bands: bands(0.0),
                },
                SkyKeyframe {
                    time: at(5.0),
                    bands: bands(0.0),
                },
            ],
            Blend::Smooth,
        );
        assert!(matches!(
            dup,
            Err(CoreError::DuplicateKeyframeTime {
                first: 0,
                second: 2,
                ..
            })
        ));
    }

    #[test]
    fn shape_validation() {
        assert!(GradientShape::default().validate().is_ok());
        let bad = GradientShape {
            zenith_start: 0.01,
            ..GradientShape::default()
        };
        assert!(bad.validate().is_err());
        let bad = GradientShape {
            upper_exponent: f64::NAN,
            ..GradientShape::default()
        };
        assert!(bad.validate().is_err());
    }
}
