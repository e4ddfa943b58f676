//! Anderson acceleration of a fixed-point iteration x ← G(x) (Walker & Ni 2011, "Anderson
//! acceleration for fixed-point iterations", SIAM J. Numer. Anal. 49(4), 1715–1735; the
//! variant with mixing β = 1, their Algorithm AA).
//!
//! With gₖ = G(xₖ), the residual fₖ = gₖ − xₖ and the differences of the last `mₖ ≤ DEPTH`
//! iterations ΔFₖ = [fₖ₋ₘ₊₁ − fₖ₋ₘ, …, fₖ − fₖ₋₁], ΔGₖ likewise,
//!
//! ```text
//!   γₖ = argmin ‖fₖ − ΔFₖ γ‖₂,        xₖ₊₁ = gₖ − ΔGₖ γₖ
//! ```
//!
//! For a linear G this is GMRES applied to the fixed-point equation (Walker & Ni, §2.2);
//! for the projected Gauss–Seidel polish of a contact system (`surface.rs`) it turns the
//! slow linear convergence of sweeps whose modes no longer change (≈ 0.967 per sweep on
//! the Yingxiuwan meshes, docs/benchmarks.md) into a short Krylov-like one. The least
//! squares are solved through the normal equations ΔFᵀΔF γ = ΔFᵀ fₖ, whose Gram matrix is
//! kept column by column (O(m n) work per iteration), by a Cholesky factorisation; a Gram
//! matrix too ill-conditioned to factor drops its oldest columns.
//!
//! The buffers grow to the largest system seen and are reused: no allocation once warm.

/// Most differences kept.
pub(super) const DEPTH: usize = 6;

/// Smallest pivot of the Cholesky factorisation of the Gram matrix, relative to its
/// largest diagonal entry, below which the oldest column is dropped.
const PIVOT: f64 = 1e-14;

/// The state of one accelerated iteration (the last `cols` differences and the last
/// iterate's g and f).
#[derive(Clone, Debug, Default)]
pub(super) struct Anderson {
    n: usize,
    /// gₖ₋₁ and fₖ₋₁ of the previous iteration (valid when `has_prev`).
    g_prev: Vec<f64>,
    f_prev: Vec<f64>,
    has_prev: bool,
    /// ΔF and ΔG columns in a ring of `DEPTH` slots, slot s at `s * n ..`.
    df: Vec<f64>,
    dg: Vec<f64>,
    /// Slots in use, oldest first.
    order: [usize; DEPTH],
    cols: usize,
    /// Gram matrix of the ΔF columns by slot.
    gram: [[f64; DEPTH]; DEPTH],
}

impl Anderson {
    /// Forget every previous iteration (the map G changed); vectors of length `n` from now.
    pub(super) fn reset(&mut self, n: usize) {
        self.n = n;
        self.has_prev = false;
        self.cols = 0;
        for v in [&mut self.g_prev, &mut self.f_prev] {
            v.clear();
            v.resize(n, 0.0);
        }
        for v in [&mut self.df, &mut self.dg] {
            v.clear();
            v.resize(DEPTH * n, 0.0);
        }
    }

    /// Differences kept.
    #[cfg(test)]
    pub(super) fn columns(&self) -> usize {
        self.cols
    }

    /// One iteration: `x` holds xₖ on entry, `g` holds gₖ = G(xₖ); on return `x` holds
    /// xₖ₊₁ (gₖ itself while no difference is kept). Returns whether xₖ₊₁ differs from gₖ.
    pub(super) fn step(&mut self, x: &mut [f64], g: &[f64]) -> bool {
        let n = self.n;
        debug_assert!(x.len() == n && g.len() == n);
        if self.has_prev {
            // The newest difference goes into a free slot, or the oldest one's.
            let slot = if self.cols < DEPTH {
                let used = &self.order[..self.cols];
                (0..DEPTH).find(|s| !used.contains(s)).unwrap_or(0)
            } else {
                let s = self.order[0];
                self.drop_oldest();
                s
            };
            for i in 0..n {
                let f = g[i] - x[i];
                self.df[slot * n + i] = f - self.f_prev[i];
                self.dg[slot * n + i] = g[i] - self.g_prev[i];
            }
            self.order[self.cols] = slot;
            self.cols += 1;
            for c in 0..self.cols {
                let other = self.order[c];
                let d = dot(self.column(slot), self.column(other));
                self.gram[slot][other] = d;
                self.gram[other][slot] = d;
            }
        }
        for i in 0..n {
            self.f_prev[i] = g[i] - x[i];
            self.g_prev[i] = g[i];
        }
        self.has_prev = true;
        let mut gamma = [0.0; DEPTH];
        loop {
            if self.cols == 0 {
                x.copy_from_slice(g);
                return false;
            }
            if self.solve(&mut gamma) {
                break;
            }
            // Too ill-conditioned: drop the oldest difference and try again.
            self.drop_oldest();
        }
        x.copy_from_slice(g);
        for c in 0..self.cols {
            let s = self.order[c];
            let dg = &self.dg[s * n..(s + 1) * n];
            for (xi, d) in x.iter_mut().zip(dg) {
                *xi -= gamma[c] * d;
            }
        }
        true
    }

    /// Forget the oldest kept difference (its slot becomes free).
    fn drop_oldest(&mut self) {
        self.order.copy_within(1..DEPTH, 0);
        self.cols -= 1;
    }

    fn column(&self, slot: usize) -> &[f64] {
        &self.df[slot * self.n..(slot + 1) * self.n]
    }

    /// γ of the normal equations over the kept columns (in `order`); false if the Gram
    /// matrix has a pivot below [`PIVOT`] of its largest diagonal entry.
    fn solve(&self, gamma: &mut [f64; DEPTH]) -> bool {
        let m = self.cols;
        let mut a = [[0.0; DEPTH]; DEPTH];
        let mut b = [0.0; DEPTH];
        let mut diag: f64 = 0.0;
        for r in 0..m {
            for c in 0..m {
                a[r][c] = self.gram[self.order[r]][self.order[c]];
            }
            diag = diag.max(a[r][r]);
            b[r] = dot(self.column(self.order[r]), &self.f_prev);
        }
        if diag <= 0.0 || !diag.is_finite() {
            return false;
        }
        // Cholesky a = L Lᵀ in place (lower triangle).
        for j in 0..m {
            let mut d = a[j][j];
            for k in 0..j {
                d -= a[j][k] * a[j][k];
            }
            if d <= PIVOT * diag {
                return false;
            }
            let l = d.sqrt();
            a[j][j] = l;
            for i in j + 1..m {
                let mut v = a[i][j];
                for k in 0..j {
                    v -= a[i][k] * a[j][k];
                }
                a[i][j] = v / l;
            }
        }
        // L y = b, then Lᵀ γ = y.
        for i in 0..m {
            let mut v = b[i];
            for k in 0..i {
                v -= a[i][k] * b[k];
            }
            b[i] = v / a[i][i];
        }
        for i in (0..m).rev() {
            let mut v = b[i];
            for k in i + 1..m {
                v -= a[k][i] * gamma[k];
            }
            gamma[i] = v / a[i][i];
        }
        gamma[..m].iter().all(|g| g.is_finite())
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear fixed-point iteration whose rates (the eigenvalues of its map) lie in
    /// [0.83, 0.97]: a change below 1e-12 takes 779 plain iterations; accelerated (n + 1
    /// would do in exact arithmetic with unlimited depth: GMRES), 44 with depth 6.
    #[test]
    fn accelerates_a_slow_linear_iteration_to_its_fixed_point() {
        let n = 12;
        // G(x) = M x + c with M = Q diag(rates) Qᵀ, Q a Householder reflection; fixed
        // point x* = (I − M)⁻¹ c.
        let rates: Vec<f64> = (0..n).map(|i| 0.97 - 0.15 * i as f64 / n as f64).collect();
        let v: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
        let vv = dot(&v, &v);
        let q = |i: usize, j: usize| f64::from(u8::from(i == j)) - 2.0 * v[i] * v[j] / vv;
        let m: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| (0..n).map(|k| q(i, k) * rates[k] * q(j, k)).sum())
                    .collect()
            })
            .collect();
        let c: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let apply = |x: &[f64]| -> Vec<f64> {
            (0..n)
                .map(|i| c[i] + (0..n).map(|j| m[i][j] * x[j]).sum::<f64>())
                .collect()
        };
        // The fixed point, by the plain iteration run to the end.
        let mut exact = vec![0.0; n];
        for _ in 0..5000 {
            exact = apply(&exact);
        }
        let residual = |x: &[f64], g: &[f64]| {
            g.iter()
                .zip(x)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max)
        };
        // Iterations until the change falls below 1e-12 (0: not within `limit`), and the
        // last iterate; accelerated or plain.
        let settle = |accelerate: bool, limit: usize| -> (usize, Vec<f64>, usize) {
            let mut aa = Anderson::default();
            aa.reset(n);
            let mut x = vec![0.0; n];
            for k in 1..=limit {
                let g = apply(&x);
                if residual(&x, &g) < 1e-12 {
                    return (k, x, aa.columns());
                }
                if accelerate {
                    aa.step(&mut x, &g);
                } else {
                    x = g;
                }
            }
            (0, x, aa.columns())
        };
        let (plain, _, _) = settle(false, 5000);
        let (iterations, x, columns) = settle(true, 200);
        assert!(plain > 500, "plain iteration: {plain} iterations");
        assert!(
            iterations > 0 && iterations < plain / 5,
            "{iterations} accelerated iterations against {plain} plain"
        );
        let err = residual(&x, &exact);
        assert!(err < 1e-9, "error {err}");
        assert!(columns <= DEPTH);
    }
}
