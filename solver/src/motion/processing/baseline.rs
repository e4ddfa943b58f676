//! Baseline correction of an acceleration series: remove its mean, or the least-squares
//! polynomial of a given order (Boore & Bommer 2005, "Processing of strong-motion
//! accelerograms: needs, options and consequences", Soil Dyn. Earthq. Eng. 25, §3).
//!
//! The polynomial is fitted in the Legendre basis P_k(x) on x = 2t/T − 1 ∈ [−1, 1], which
//! keeps the normal equations well conditioned for any record length.

use nalgebra::{DMatrix, DVector};

/// Subtract the mean. Returns the mean removed.
pub fn remove_mean(a: &mut [f64]) -> f64 {
    if a.is_empty() {
        return 0.0;
    }
    let mean = a.iter().sum::<f64>() / a.len() as f64;
    for x in a.iter_mut() {
        *x -= mean;
    }
    mean
}

/// Subtract the least-squares polynomial of degree `order` in t. Returns the fitted
/// coefficients in the Legendre basis.
pub fn remove_polynomial(a: &mut [f64], order: usize) -> Vec<f64> {
    let n = a.len();
    if n == 0 {
        return Vec::new();
    }
    let m = order + 1;
    let x_of = |i: usize| {
        if n == 1 {
            0.0
        } else {
            2.0 * i as f64 / (n - 1) as f64 - 1.0
        }
    };
    // Normal equations G c = r with G_jk = Σ P_j P_k, r_j = Σ P_j a.
    let mut g = DMatrix::<f64>::zeros(m, m);
    let mut r = DVector::<f64>::zeros(m);
    let mut p = vec![0.0; m];
    for (i, &ai) in a.iter().enumerate() {
        legendre(x_of(i), &mut p);
        for j in 0..m {
            r[j] += p[j] * ai;
            for k in 0..m {
                g[(j, k)] += p[j] * p[k];
            }
        }
    }
    let c = match g.clone().cholesky() {
        Some(ch) => ch.solve(&r),
        // Fewer samples than coefficients: the pseudo-inverse fit.
        None => g
            .pseudo_inverse(1e-12)
            .map(|gi| gi * &r)
            .unwrap_or(DVector::zeros(m)),
    };
    for (i, ai) in a.iter_mut().enumerate() {
        legendre(x_of(i), &mut p);
        *ai -= (0..m).map(|j| c[j] * p[j]).sum::<f64>();
    }
    c.iter().copied().collect()
}

/// P_0 … P_{len−1} at x by Bonnet's recursion (k+1)P_{k+1} = (2k+1)xP_k − kP_{k−1}.
fn legendre(x: f64, p: &mut [f64]) {
    if p.is_empty() {
        return;
    }
    p[0] = 1.0;
    if p.len() > 1 {
        p[1] = x;
    }
    for k in 1..p.len().saturating_sub(1) {
        let kf = k as f64;
        p[k + 1] = ((2.0 * kf + 1.0) * x * p[k] - kf * p[k - 1]) / (kf + 1.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_trend_is_removed_exactly() {
        let mut a: Vec<f64> = (0..500)
            .map(|i| {
                let t = i as f64 * 0.01;
                (7.0 * t).sin() * 0.0 + 0.3 - 0.2 * t + 0.05 * t * t
            })
            .collect();
        remove_polynomial(&mut a, 2);
        assert!(a.iter().all(|x| x.abs() < 1e-12));
        let mut b = vec![2.0, 4.0];
        assert_eq!(remove_mean(&mut b), 3.0);
        assert_eq!(b, vec![-1.0, 1.0]);
    }
}
