//! How a medium term's density varies with altitude: Bruneton's two-layer profiles, or a table.
//!
//! Densities are dimensionless: a term's coefficients are its values at density 1 times the
//! density at the altitude `h` (metres above the ellipsoid surface).

use std::sync::Arc;

use crate::error::CoreError;

/// One layer of a density profile (Bruneton 2017). Altitude `h` in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DensityLayer {
    /// Where this layer ends, metres above the surface (only the first layer's is used).
    pub width: f64,
    /// Factor of the exponential term, dimensionless.
    pub exp_term: f64,
    /// Rate of the exponential term, m⁻¹ (−1/scale height).
    pub exp_scale: f64,
    /// Slope of the linear term, m⁻¹.
    pub linear_term: f64,
    /// Constant term, dimensionless.
    pub constant_term: f64,
}

impl DensityLayer {
    /// No constituent at all.
    pub const EMPTY: Self = Self {
        width: 0.0,
        exp_term: 0.0,
        exp_scale: 0.0,
        linear_term: 0.0,
        constant_term: 0.0,
    };

    /// `e^(−h/scale_height)`.
    pub fn exponential(scale_height: f64) -> Self {
        Self {
            exp_term: 1.0,
            exp_scale: -1.0 / scale_height,
            ..Self::EMPTY
        }
    }

    /// Density 1 at every height.
    pub fn constant() -> Self {
        Self {
            constant_term: 1.0,
            ..Self::EMPTY
        }
    }

    /// The layer's density at altitude `h` metres, clamped to [0, 1].
    pub fn density(&self, h: f64) -> f64 {
        (self.exp_term * (self.exp_scale * h).exp() + self.linear_term * h + self.constant_term).clamp(0.0, 1.0)
    }
}

/// A two-layer density profile: Bruneton's piecewise linear-exponential density.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DensityProfile {
    /// `layers[0]` below `layers[0].width`, `layers[1]` above.
    pub layers: [DensityLayer; 2],
}

impl DensityProfile {
    /// One layer everywhere.
    pub fn single(layer: DensityLayer) -> Self {
        Self {
            layers: [DensityLayer::EMPTY, layer],
        }
    }

    /// A tent: 0 at `bottom`, rising linearly to 1 at `peak`, back to 0 at `top` (metres).
    pub fn tent(bottom: f64, peak: f64, top: f64) -> Self {
        let rise = 1.0 / (peak - bottom);
        let fall = 1.0 / (top - peak);
        Self {
            layers: [
                DensityLayer {
                    width: peak,
                    linear_term: rise,
                    constant_term: -bottom * rise,
                    ..DensityLayer::EMPTY
                },
                DensityLayer {
                    linear_term: -fall,
                    constant_term: top * fall,
                    ..DensityLayer::EMPTY
                },
            ],
        }
    }

    /// Density at altitude `h` metres, in [0, 1].
    pub fn density(&self, h: f64) -> f64 {
        if h < self.layers[0].width {
            self.layers[0].density(h)
        } else {
            self.layers[1].density(h)
        }
    }

    /// The scale height of the upper layer, metres, where it is a pure exponential.
    pub fn scale_height(&self) -> Option<f64> {
        let rate = self.layers[1].exp_scale;
        (rate < 0.0).then(|| -1.0 / rate)
    }

    fn validate(&self, field: &str) -> Result<(), CoreError> {
        let all_finite = self.layers.iter().all(|l| {
            [l.width, l.exp_term, l.exp_scale, l.linear_term, l.constant_term]
                .iter()
                .all(|v| v.is_finite())
        });
        if all_finite {
            Ok(())
        } else {
            Err(CoreError::InvalidItem {
                field: field.to_owned(),
                value: format!("{self:?}"),
                rule: "every density layer term must be finite",
            })
        }
    }
}

/// A density given at altitudes, linear in between and held at the end values beyond them.
#[derive(Debug, Clone, PartialEq)]
pub struct DensityTable {
    /// Altitudes, metres, strictly increasing.
    altitudes: Arc<[f64]>,
    /// Densities there, dimensionless, >= 0.
    densities: Arc<[f64]>,
}

impl DensityTable {
    /// The table of `(altitude m, density)` pairs; `field` names them in errors
    /// (`atmosphere.terms[1].profile_table`).
    pub fn new(field: &str, pairs: &[(f64, f64)]) -> Result<Self, CoreError> {
        super::check_table(field, pairs)?;
        Ok(Self {
            altitudes: pairs.iter().map(|p| p.0).collect(),
            densities: pairs.iter().map(|p| p.1).collect(),
        })
    }

    /// Density at altitude `h` metres.
    pub fn density(&self, h: f64) -> f64 {
        let (hs, ds) = (&self.altitudes, &self.densities);
        let i = hs.partition_point(|&x| x <= h);
        if i == 0 {
            return ds[0];
        }
        if i == hs.len() {
            return ds[hs.len() - 1];
        }
        let t = (h - hs[i - 1]) / (hs[i] - hs[i - 1]);
        ds[i - 1] + t * (ds[i] - ds[i - 1])
    }

    /// The `(altitude m, density)` pairs.
    pub fn pairs(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.altitudes.iter().copied().zip(self.densities.iter().copied())
    }
}

/// How a term's density varies with altitude.
#[derive(Debug, Clone, PartialEq)]
pub enum Density {
    /// Bruneton's two-layer profile (exponential, tent, constant or any linear-exponential pair).
    Profile(DensityProfile),
    /// A table of altitudes and densities.
    Table(DensityTable),
}

impl Density {
    /// Density at altitude `h` metres.
    pub fn at(&self, h: f64) -> f64 {
        match self {
            Self::Profile(p) => p.density(h),
            Self::Table(t) => t.density(h),
        }
    }

    pub(super) fn validate(&self, field: &str) -> Result<(), CoreError> {
        match self {
            Self::Profile(p) => p.validate(field),
            // A table is checked when it is made.
            Self::Table(_) => Ok(()),
        }
    }
}

impl From<DensityProfile> for Density {
    fn from(profile: DensityProfile) -> Self {
        Self::Profile(profile)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tent_profile_matches_bruneton_ozone() {
        let tent = DensityProfile::tent(10_000.0, 25_000.0, 40_000.0);
        // Bruneton's demo: layer 0 width 25 km, linear 1/15 km, constant −2/3; layer 1 −1/15 km, 8/3.
        assert!((tent.layers[0].constant_term + 2.0 / 3.0).abs() < 1e-12);
        assert!((tent.layers[1].constant_term - 8.0 / 3.0).abs() < 1e-12);
        for (h, d) in [
            (0.0, 0.0),
            (10_000.0, 0.0),
            (17_500.0, 0.5),
            (25_000.0, 1.0),
            (32_500.0, 0.5),
            (45_000.0, 0.0),
        ] {
            assert!((tent.density(h) - d).abs() < 1e-12, "{h}");
        }
    }

    #[test]
    fn tables_interpolate_linearly_and_hold_their_ends() {
        let table = DensityTable::new("t", &[(0.0, 2.0), (1000.0, 1.0), (3000.0, 0.0)]).unwrap();
        for (h, d) in [
            (-5.0, 2.0),
            (0.0, 2.0),
            (500.0, 1.5),
            (2000.0, 0.5),
            (3000.0, 0.0),
            (9e9, 0.0),
        ] {
            assert!((table.density(h) - d).abs() < 1e-12, "{h}");
        }
    }

    #[test]
    fn bad_tables_name_their_rule() {
        for (pairs, rule) in [
            (&[(0.0, 1.0)][..], "at least two"),
            (&[(0.0, 1.0), (0.0, 2.0)][..], "increase strictly"),
            (&[(0.0, -1.0), (1.0, 2.0)][..], ">= 0"),
            (&[(0.0, f64::NAN), (1.0, 2.0)][..], ">= 0"),
        ] {
            let error = DensityTable::new("atmosphere.terms[0].profile_table", pairs).unwrap_err();
            assert!(error.to_string().contains(rule), "{error}");
            assert!(
                error.to_string().contains("atmosphere.terms[0].profile_table"),
                "{error}"
            );
        }
    }
}
