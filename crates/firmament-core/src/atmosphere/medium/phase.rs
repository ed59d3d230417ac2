//! Phase functions of the medium's terms: how much of the light a term scatters goes into each
//! direction, sr⁻¹, normalised to 1 over the sphere.
//!
//! `nu` is the cosine of the scattering angle, between the propagation directions (`nu = 1` is
//! straight on). Each phase function also gives its Legendre coefficients `a_l`, through which
//! the GPU's multiple scattering sees it (`atmosphere/luts.wgsl`).

use std::f64::consts::PI;
use std::sync::Arc;

use crate::atmosphere::clouds::DualHenyeyGreenstein;
use crate::error::CoreError;

/// The phase function of one term of the medium.
#[derive(Debug, Clone, PartialEq)]
pub enum Phase {
    /// Rayleigh's `3/(16π)·(1 + ν²)`: molecules.
    Rayleigh,
    /// Cornette & Shanks, "Physically reasonable analytic expression for the single-scattering
    /// phase function", Applied Optics 31(16), 1992 — as Bruneton 2017 and Hillaire 2020 use.
    CornetteShanks {
        /// Asymmetry parameter, in (−1, 1).
        g: f64,
    },
    /// Henyey & Greenstein, "Diffuse radiation in the galaxy", ApJ 93, 1941.
    HenyeyGreenstein {
        /// Asymmetry parameter, in (−1, 1).
        g: f64,
    },
    /// Two Henyey–Greenstein lobes: a forward peak and a backward one.
    DualHenyeyGreenstein(DualHenyeyGreenstein),
    /// A table of angles and values, linear in the angle between them, normalised on load.
    Table(PhaseTable),
}

impl Phase {
    /// The asymmetry parameter of the one-lobed analytic phase functions, the mean cosine
    /// otherwise.
    pub fn g(&self) -> f64 {
        match self {
            Self::CornetteShanks { g } | Self::HenyeyGreenstein { g } => *g,
            _ => self.legendre_coefficient(1),
        }
    }

    /// Phase function value, sr⁻¹, for the cosine `nu` of the scattering angle.
    pub fn eval(&self, nu: f64) -> f64 {
        match self {
            Self::Rayleigh => rayleigh_phase(nu),
            Self::CornetteShanks { g } => cornette_shanks(*g, nu),
            Self::HenyeyGreenstein { g } => henyey_greenstein(*g, nu),
            Self::DualHenyeyGreenstein(dual) => dual.eval(nu),
            Self::Table(table) => table.eval(nu),
        }
    }

    /// The Legendre coefficient `a_l` of the phase function, which is
    /// `Σ (2l + 1)/(4π)·a_l·P_l(ν)` (`a_0 = 1`; `a_1` is the mean cosine).
    ///
    /// Rayleigh's are `a_2 = 1/10` and nothing else past `a_0`; Henyey–Greenstein's are `g^l`.
    /// Cornette–Shanks is Henyey–Greenstein times `3(1 + ν²)/(2(2 + g²))`, and
    /// `ν²P_l = α_l P_{l+2} + β_l P_l + γ_l P_{l−2}` with
    /// `α_l = (l+1)(l+2)/((2l+1)(2l+3))`, `β_l = (2l² + 2l − 1)/((2l−1)(2l+3))`,
    /// `γ_l = l(l−1)/((2l−1)(2l+1))`, so its coefficients are
    /// `3/(2(2 + g²))·(g^l + α_l g^{l+2} + β_l g^l + γ_l g^{l−2})` — for `g = 0.8`: 0.844, 0.710,
    /// 0.577, 0.465, 0.374 for l = 1…5, against `g^l`'s 0.8, 0.64, 0.512, 0.410, 0.328.
    /// A table's are integrated when it is made, for `l` up to [`TABLE_LEGENDRE_ORDERS`].
    pub fn legendre_coefficient(&self, l: u32) -> f64 {
        match self {
            Self::Rayleigh => match l {
                0 => 1.0,
                2 => 0.1,
                _ => 0.0,
            },
            Self::HenyeyGreenstein { g } => g.powi(l as i32),
            Self::CornetteShanks { g } => {
                let g = *g;
                let n = f64::from(l);
                let alpha = (n + 1.0) * (n + 2.0) / ((2.0 * n + 1.0) * (2.0 * n + 3.0));
                let beta = (2.0 * n * n + 2.0 * n - 1.0) / ((2.0 * n - 1.0) * (2.0 * n + 3.0));
                let gamma = n * (n - 1.0) / ((2.0 * n - 1.0) * (2.0 * n + 1.0));
                // γ_l vanishes for l ≤ 1, where g^{l−2} would be a negative power.
                let below = if l >= 2 { gamma * g.powi(l as i32 - 2) } else { 0.0 };
                3.0 / (2.0 * (2.0 + g * g)) * ((1.0 + beta) * g.powi(l as i32) + alpha * g.powi(l as i32 + 2) + below)
            }
            Self::DualHenyeyGreenstein(d) => {
                d.blend * d.g_forward.powi(l as i32) + (1.0 - d.blend) * d.g_back.powi(l as i32)
            }
            Self::Table(table) => table.legendre.get(l as usize).copied().unwrap_or(0.0),
        }
    }

    /// Checks `g` in (−1, 1) (and the dual lobes' blend in [0, 1]), naming `field`
    /// (`atmosphere.terms[1].phase`) in the error.
    pub fn validate(&self, field: &str) -> Result<(), CoreError> {
        match self {
            Self::CornetteShanks { g } | Self::HenyeyGreenstein { g } if !(*g > -1.0 && *g < 1.0) => {
                Err(CoreError::InvalidItem {
                    field: format!("{field}.g"),
                    value: g.to_string(),
                    rule: "must lie strictly between -1 and 1",
                })
            }
            Self::DualHenyeyGreenstein(dual) => dual.validate(field),
            _ => Ok(()),
        }
    }
}

/// How many Legendre coefficients a [`PhaseTable`] keeps: `a_0` … `a_5`, the bands the GPU's
/// multiple scattering holds and the delta-M forward peak after them.
pub const TABLE_LEGENDRE_ORDERS: usize = 6;

/// A phase function tabulated at scattering angles from 0° to 180°, linear in the angle between
/// them and normalised to 1 over the sphere when made.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseTable {
    /// Scattering angles, radians, from 0 to π, strictly increasing.
    angles: Arc<[f64]>,
    /// The phase function there, sr⁻¹ (normalised).
    values: Arc<[f64]>,
    /// `a_0` … `a_5` of the normalised table.
    legendre: [f64; TABLE_LEGENDRE_ORDERS],
    /// The cumulative share of the sphere's directions up to each of [`SAMPLING_BINS`] + 1
    /// angles evenly spread from 0 to π, for drawing directions ([`PhaseTable::sample`]).
    cdf: Arc<[f64]>,
}

/// Bins of the piecewise-constant density in the angle that [`PhaseTable::sample`] draws from:
/// 0.1° each, so a forward peak tabulated at 1° is followed closely and the path tracer's
/// weights `p / pdf` stay near 1 (Henyey–Greenstein with the table's mean cosine, the proposal
/// before, was off by up to 9× in Titan's haze's peak, and its weights multiplied along paths).
const SAMPLING_BINS: usize = 1800;

/// The angle, radians, where sampling bin `j` begins.
fn bin_edge(j: usize) -> f64 {
    j as f64 * PI / SAMPLING_BINS as f64
}

/// Midpoints per table interval for the integrals over the sphere: the table is linear in the
/// angle, so the rule's error is that of `sin θ·P_l(cos θ)` alone (below 1e-6 at 1° knots).
const TABLE_QUADRATURE_POINTS: usize = 32;

impl PhaseTable {
    /// The table of `(scattering angle °, value)` pairs, scaled so it integrates to 1 over the
    /// sphere; `field` names it in errors (`atmosphere.terms[1].phase_table`).
    pub fn new(field: &str, pairs: &[(f64, f64)]) -> Result<Self, CoreError> {
        let invalid = |rule| CoreError::InvalidItem {
            field: field.to_owned(),
            value: format!("{pairs:?}"),
            rule,
        };
        super::check_table(field, pairs)?;
        if pairs[0].0 != 0.0 || pairs[pairs.len() - 1].0 != 180.0 {
            return Err(invalid("angles must run from 0 to 180 degrees"));
        }
        let mut table = Self {
            angles: pairs.iter().map(|p| p.0.to_radians()).collect(),
            values: pairs.iter().map(|p| p.1).collect(),
            legendre: [0.0; TABLE_LEGENDRE_ORDERS],
            cdf: Arc::from([]),
        };
        let total = table.integrate(|_| 1.0);
        if !(total.is_finite() && total > 0.0) {
            return Err(invalid("the values must integrate to more than 0 over the sphere"));
        }
        table.values = table.values.iter().map(|v| v / total).collect();
        for l in 0..TABLE_LEGENDRE_ORDERS {
            table.legendre[l] = table.integrate(|nu| legendre_polynomial(l as u32, nu));
        }
        table.cdf = table.sampling_cdf();
        Ok(table)
    }

    /// The CDF of [`sample`](Self::sample): each bin's share is the largest of the table at its
    /// ends and middle times the bin's solid angle, so a bin where the table is above 0
    /// anywhere has a share above 0.
    fn sampling_cdf(&self) -> Arc<[f64]> {
        let mut cdf = Vec::with_capacity(SAMPLING_BINS + 1);
        let mut sum = 0.0;
        cdf.push(0.0);
        for j in 0..SAMPLING_BINS {
            let (a, b) = (bin_edge(j), bin_edge(j + 1));
            let peak = self.at_angle(a).max(self.at_angle(0.5 * (a + b))).max(self.at_angle(b));
            sum += peak * (a.cos() - b.cos());
            cdf.push(sum);
        }
        cdf.iter().map(|c| c / sum).collect()
    }

    /// The cosine of a scattering angle drawn from a density close to the table, constant over
    /// each bin's solid angle (`u` uniform in [0, 1));
    /// [`sampling_pdf`](Self::sampling_pdf) is that density.
    pub(crate) fn sample(&self, u: f64) -> f64 {
        let cdf = &self.cdf;
        let j = (cdf.partition_point(|&c| c <= u).max(1) - 1).min(SAMPLING_BINS - 1);
        let share = cdf[j + 1] - cdf[j];
        let t = if share > 0.0 {
            ((u - cdf[j]) / share).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let (near, far) = (bin_edge(j).cos(), bin_edge(j + 1).cos());
        near + t * (far - near)
    }

    /// The density, sr⁻¹, of directions at cosine `nu` from the scattering axis that
    /// [`sample`](Self::sample) draws.
    pub(crate) fn sampling_pdf(&self, nu: f64) -> f64 {
        let theta = nu.clamp(-1.0, 1.0).acos();
        let j = ((theta / bin_edge(1)) as usize).min(SAMPLING_BINS - 1);
        let solid_angle = 2.0 * PI * (bin_edge(j).cos() - bin_edge(j + 1).cos());
        (self.cdf[j + 1] - self.cdf[j]) / solid_angle
    }

    /// The phase function at `nu`, sr⁻¹.
    pub fn eval(&self, nu: f64) -> f64 {
        self.at_angle(nu.clamp(-1.0, 1.0).acos())
    }

    /// The phase function at the scattering angle `theta` radians, sr⁻¹.
    pub fn at_angle(&self, theta: f64) -> f64 {
        let (angles, values) = (&self.angles, &self.values);
        let i = angles.partition_point(|&a| a <= theta).clamp(1, angles.len() - 1);
        let t = ((theta - angles[i - 1]) / (angles[i] - angles[i - 1])).clamp(0.0, 1.0);
        values[i - 1] + t * (values[i] - values[i - 1])
    }

    /// `∫ p(ν)·f(ν) dω` over the sphere, `2π Σ ∫ p(θ) f(cos θ) sin θ dθ` by the midpoint rule
    /// within each interval.
    fn integrate(&self, f: impl Fn(f64) -> f64) -> f64 {
        let mut sum = 0.0;
        for i in 1..self.angles.len() {
            let (a, b) = (self.angles[i - 1], self.angles[i]);
            let step = (b - a) / TABLE_QUADRATURE_POINTS as f64;
            for k in 0..TABLE_QUADRATURE_POINTS {
                let theta = a + (k as f64 + 0.5) * step;
                sum += self.at_angle(theta) * f(theta.cos()) * theta.sin() * step;
            }
        }
        2.0 * PI * sum
    }
}

/// The Legendre polynomial `P_l(x)`, by Bonnet's recursion.
pub(crate) fn legendre_polynomial(l: u32, x: f64) -> f64 {
    let (mut previous, mut current) = (1.0, x);
    if l == 0 {
        return previous;
    }
    for n in 1..l {
        let n = f64::from(n);
        (previous, current) = (current, ((2.0 * n + 1.0) * x * current - n * previous) / (n + 1.0));
    }
    current
}

/// Rayleigh's phase function `3/(16π)·(1 + ν²)`, sr⁻¹.
pub fn rayleigh_phase(nu: f64) -> f64 {
    3.0 / (16.0 * PI) * (1.0 + nu * nu)
}

/// Henyey–Greenstein phase function, sr⁻¹.
pub fn henyey_greenstein(g: f64, nu: f64) -> f64 {
    let denominator = 1.0 + g * g - 2.0 * g * nu;
    (1.0 - g * g) / (4.0 * PI * denominator * denominator.sqrt())
}

/// Cornette–Shanks phase function, sr⁻¹.
pub fn cornette_shanks(g: f64, nu: f64) -> f64 {
    let denominator = 1.0 + g * g - 2.0 * g * nu;
    3.0 / (8.0 * PI) * (1.0 - g * g) * (1.0 + nu * nu) / ((2.0 + g * g) * denominator * denominator.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn integrate_sphere(f: impl Fn(f64) -> f64) -> f64 {
        // ∫ f(ν) dω = 2π ∫_{-1}^{1} f(ν) dν, midpoint rule.
        let n = 200_000;
        (0..n).map(|i| f(-1.0 + (i as f64 + 0.5) * 2.0 / n as f64)).sum::<f64>() * 2.0 / n as f64 * 2.0 * PI
    }

    fn rayleigh_table(step_degrees: usize, scale: f64) -> PhaseTable {
        let pairs: Vec<(f64, f64)> = (0..=180)
            .step_by(step_degrees)
            .map(|d| (d as f64, scale * rayleigh_phase((d as f64).to_radians().cos())))
            .collect();
        PhaseTable::new("table", &pairs).unwrap()
    }

    #[test]
    fn a_table_s_directions_are_drawn_with_the_density_it_reports() {
        // Titan's haze at 600 nm (Tomasko et al. 2008): a peak 1700× its backscatter.
        let pairs = [
            (0.0, 362.8),
            (2.0, 239.9),
            (5.0, 64.74),
            (10.0, 14.5),
            (30.0, 1.857),
            (90.0, 0.1679),
            (180.0, 0.2092),
        ];
        let table = PhaseTable::new("table", &pairs).unwrap();
        // The density integrates to 1 over the sphere and follows the table within its bins.
        assert!((integrate_sphere(|nu| table.sampling_pdf(nu)) - 1.0).abs() < 1e-3);
        for degrees in [0.5, 3.0, 20.0, 100.0, 179.0] {
            let nu = f64::cos(f64::to_radians(degrees));
            let ratio = table.eval(nu) / table.sampling_pdf(nu);
            assert!((ratio - 1.0).abs() < 0.05, "{degrees}°: p/pdf {ratio}");
        }
        // Draws fall in cosine bands as often as the density says.
        let bands = [-1.0, 0.0, 0.9, 0.99, 0.999, 1.0];
        let draws = 200_000;
        let mut counts = [0usize; 5];
        for i in 0..draws {
            let nu = table.sample((i as f64 + 0.5) / draws as f64);
            counts[bands.partition_point(|&b| b <= nu).clamp(1, 5) - 1] += 1;
        }
        for k in 0..5 {
            let (a, b) = (bands[k], bands[k + 1]);
            let n = 4000;
            let expected: f64 = (0..n)
                .map(|i| table.sampling_pdf(a + (i as f64 + 0.5) * (b - a) / n as f64))
                .sum::<f64>()
                * (b - a)
                / n as f64
                * 2.0
                * PI;
            let got = counts[k] as f64 / draws as f64;
            assert!(
                (got - expected).abs() < 2e-3,
                "band {a}..{b}: {got} drawn, {expected} expected"
            );
        }
    }

    #[test]
    fn legendre_coefficients_match_quadrature() {
        let dual = Phase::DualHenyeyGreenstein(DualHenyeyGreenstein {
            g_forward: 0.7,
            g_back: -0.3,
            blend: 0.8,
        });
        let mut phases = vec![Phase::Rayleigh, dual];
        for g in [-0.6, 0.0, 0.5, 0.8, 0.9] {
            phases.push(Phase::CornetteShanks { g });
            phases.push(Phase::HenyeyGreenstein { g });
        }
        for phase in phases {
            for l in 0..=6 {
                let quadrature = integrate_sphere(|nu| phase.eval(nu) * legendre_polynomial(l, nu));
                let closed = phase.legendre_coefficient(l);
                assert!(
                    (closed - quadrature).abs() < 1e-6,
                    "{phase:?} l = {l}: {closed} vs {quadrature}"
                );
            }
        }
    }

    #[test]
    fn phase_functions_are_normalised() {
        assert!((integrate_sphere(rayleigh_phase) - 1.0).abs() < 1e-9);
        for g in [-0.5, 0.0, 0.3, 0.8] {
            assert!(
                (integrate_sphere(|nu| henyey_greenstein(g, nu)) - 1.0).abs() < 1e-6,
                "HG {g}"
            );
            assert!(
                (integrate_sphere(|nu| cornette_shanks(g, nu)) - 1.0).abs() < 1e-6,
                "CS {g}"
            );
        }
    }

    #[test]
    fn a_table_of_rayleigh_is_normalised_back_to_rayleigh() {
        // Ten times too large at every 2°: the load scales it back, and the linear pieces stay
        // within 0.1 % of the curve between knots.
        let table = Phase::Table(rayleigh_table(2, 10.0));
        for i in 0..=1000 {
            let nu = -1.0 + 2.0 * i as f64 / 1000.0;
            let (got, want) = (table.eval(nu), rayleigh_phase(nu));
            assert!((got / want - 1.0).abs() < 1e-3, "ν = {nu}: {got} vs {want}");
        }
        assert!((table.legendre_coefficient(0) - 1.0).abs() < 1e-9);
        assert!((table.legendre_coefficient(2) - 0.1).abs() < 1e-4);
        for l in [1, 3, 4, 5] {
            assert!(table.legendre_coefficient(l).abs() < 1e-4, "a_{l}");
        }
    }

    #[test]
    fn bad_phase_tables_name_their_rule() {
        for (pairs, rule) in [
            (&[(0.0, 1.0)][..], "at least two"),
            (&[(0.0, 1.0), (90.0, 1.0)][..], "0 to 180"),
            (
                &[(0.0, 1.0), (90.0, 1.0), (90.0, 1.0), (180.0, 1.0)][..],
                "increase strictly",
            ),
            (&[(0.0, -1.0), (180.0, 2.0)][..], ">= 0"),
            (&[(0.0, 0.0), (180.0, 0.0)][..], "integrate"),
        ] {
            let error = PhaseTable::new("atmosphere.terms[0].phase_table", pairs).unwrap_err();
            assert!(error.to_string().contains(rule), "{error}");
        }
    }
}
