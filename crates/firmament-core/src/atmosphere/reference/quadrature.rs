//! Quadrature rules: adaptive Simpson for spectrum-valued integrands, and Gauss–Legendre with
//! the integration matrix of its nodes.

use std::f64::consts::PI;

use crate::atmosphere::spectrum::Spectrum;

/// `∫_a^b f(t) dt` to a relative accuracy of about `relative_tolerance` (on the largest
/// component): 16 Simpson panels, each refined until its Richardson error estimate is below its
/// share of the tolerance, or 24 halvings deep.
pub(crate) fn adaptive_simpson(f: &impl Fn(f64) -> Spectrum, a: f64, b: f64, relative_tolerance: f64) -> Spectrum {
    if b <= a {
        return Spectrum::ZERO;
    }
    const PANELS: usize = 16;
    let h = (b - a) / PANELS as f64;
    let samples: Vec<Spectrum> = (0..=2 * PANELS).map(|i| f(a + 0.5 * h * i as f64)).collect();
    let wholes: Vec<Spectrum> = (0..PANELS)
        .map(|k| (samples[2 * k] + 4.0 * samples[2 * k + 1] + samples[2 * k + 2]) * (h / 6.0))
        .collect();
    let magnitude = wholes.iter().copied().sum::<Spectrum>().abs().max_element();
    if magnitude == 0.0 || !magnitude.is_finite() {
        return wholes.into_iter().sum();
    }
    let tolerance = relative_tolerance * magnitude / PANELS as f64;
    (0..PANELS)
        .map(|k| {
            let x = a + h * k as f64;
            let (fa, fm, fb) = (samples[2 * k], samples[2 * k + 1], samples[2 * k + 2]);
            refine(f, x, x + h, fa, fm, fb, wholes[k], tolerance, 24)
        })
        .sum()
}

#[expect(
    clippy::too_many_arguments,
    reason = "the recursion carries the panel's cached samples"
)]
fn refine(
    f: &impl Fn(f64) -> Spectrum,
    a: f64,
    b: f64,
    fa: Spectrum,
    fm: Spectrum,
    fb: Spectrum,
    whole: Spectrum,
    tolerance: f64,
    depth: u32,
) -> Spectrum {
    let m = 0.5 * (a + b);
    let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
    let (flm, frm) = (f(lm), f(rm));
    let left = (fa + 4.0 * flm + fm) * ((m - a) / 6.0);
    let right = (fm + 4.0 * frm + fb) * ((b - m) / 6.0);
    let error = (left + right - whole).abs().max_element();
    if depth == 0 || error <= 15.0 * tolerance {
        return left + right + (left + right - whole) / 15.0;
    }
    refine(f, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1)
        + refine(f, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1)
}

/// Gauss–Legendre nodes and weights on [−1, 1], and the integration matrix of the nodes.
#[derive(Debug, Clone)]
pub(crate) struct GaussRule {
    pub(crate) nodes: Vec<f64>,
    pub(crate) weights: Vec<f64>,
    /// `partial[j·n + k] = ∫_{−1}^{x_j} ℓ_k(x) dx`, `ℓ_k` the Lagrange basis polynomials of the
    /// nodes: integrating a function's interpolant from −1 to each node.
    pub(super) partial: Vec<f64>,
}

impl GaussRule {
    pub(crate) fn new(n: usize) -> Self {
        let n = n.max(1);
        let mut nodes = Vec::with_capacity(n);
        let mut weights = Vec::with_capacity(n);
        for i in 0..n {
            // Newton's method on P_n from the usual estimate of its i-th root (Numerical
            // Recipes' gauleg), largest first.
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            for _ in 0..100 {
                let (p, dp) = legendre(n, x);
                let step = p / dp;
                x -= step;
                if step.abs() < 1e-16 || !step.is_finite() {
                    break;
                }
            }
            let (_, dp) = legendre(n, x);
            nodes.push(-x);
            weights.push(2.0 / ((1.0 - x * x) * dp * dp));
        }
        let lagrange = |k: usize, x: f64| {
            (0..n)
                .filter(|&m| m != k)
                .map(|m| (x - nodes[m]) / (nodes[k] - nodes[m]))
                .product::<f64>()
        };
        // The interpolant has degree n − 1, which the n-point rule on [−1, x_j] integrates exactly.
        let mut partial = vec![0.0; n * n];
        for j in 0..n {
            let half = 0.5 * (nodes[j] + 1.0);
            for k in 0..n {
                partial[j * n + k] = (0..n)
                    .map(|m| weights[m] * half * lagrange(k, -1.0 + half * (nodes[m] + 1.0)))
                    .sum();
            }
        }
        Self {
            nodes,
            weights,
            partial,
        }
    }

    pub(super) fn len(&self) -> usize {
        self.nodes.len()
    }
}

/// The Legendre polynomial `P_n(x)` and its derivative.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut previous, mut current) = (1.0, x);
    for k in 1..n {
        let k = k as f64;
        (previous, current) = (current, ((2.0 * k + 1.0) * x * current - k * previous) / (k + 1.0));
    }
    if n == 0 {
        return (1.0, 0.0);
    }
    (current, n as f64 * (x * current - previous) / (x * x - 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_a_sharp_exponential() {
        let f = |t: f64| Spectrum::new((-t / 1200.0).exp(), (-t / 8000.0).exp(), 1.0);
        let got = adaptive_simpson(&f, 0.0, 60_000.0, 1e-11);
        let want = Spectrum::new(
            1200.0 * (1.0 - (-50.0_f64).exp()),
            8000.0 * (1.0 - (-7.5_f64).exp()),
            60_000.0,
        );
        assert!(((got - want) / want).abs().max_element() < 1e-10, "{got} {want}");
    }
}
