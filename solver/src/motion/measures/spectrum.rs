//! Elastic response of a linear oscillator to a sampled excitation, by the exact
//! piecewise-linear recursion of Nigam & Jennings (1969, "Calculation of response spectra
//! from strong-motion earthquake records", BSSA 59(2), 909–922), and the response spectrum
//! built on it.
//!
//! The oscillator ü + 2ξωu̇ + ω²u = p(t), with p linear inside each step, is solved exactly
//! from step to step:
//!
//! u_{i+1} = A u_i + B u̇_i + C p_i + D p_{i+1},
//! u̇_{i+1} = A′u_i + B′u̇_i + C′p_i + D′p_{i+1}
//!
//! (the same recursion as Chopra, *Dynamics of Structures*, §5.2, eq. 5.2.5). The eight
//! coefficients are the entries of the exact propagator exp(NωΔt) of the augmented state
//! [u, u̇/ω, p/ω², ṗ/ω³] with N = [[0,1,0,0],[−1,−2ξ,1,0],[0,0,0,1],[0,0,0,0]], computed by
//! scaling and squaring of its Taylor series (Moler & Van Loan 2003, SIAM Rev. 45, method 3)
//! — exact to round-off for every ωΔt and every ξ ≥ 0 (under-, critically and over-damped),
//! free of the cancellation that the closed-form C, D suffer when ωΔt is small, and made of
//! IEEE operations only (bit-identical on every platform; the synthetic generator relies on
//! it). A unit test checks the coefficients against Chopra's closed forms.
//!
//! For a ground acceleration a_g, p = −a_g and u is the relative displacement. Spectral
//! values: SD = max|u|, SV = max|u̇|, SA = max|ü + a_g| = max|2ξωu̇ + ω²u| (absolute
//! acceleration), PSV = ωSD, PSA = ω²SD.

use rayon::prelude::*;

/// The recursion's coefficients for one oscillator and one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SdofCoefficients {
    pub omega: f64,
    pub damping: f64,
    /// u_{i+1} = a u + b v + c p_i + d p_{i+1}.
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    /// v_{i+1} = ap u + bp v + cp p_i + dp p_{i+1}.
    pub ap: f64,
    pub bp: f64,
    pub cp: f64,
    pub dp: f64,
}

impl SdofCoefficients {
    /// Coefficients for circular frequency `omega` > 0 (rad/s), damping ratio ≥ 0 and step
    /// `dt` > 0.
    pub fn new(omega: f64, damping: f64, dt: f64) -> Self {
        let h = omega * dt;
        let e = propagator(damping, h);
        let w2 = omega * omega;
        Self {
            omega,
            damping,
            a: e[0][0],
            b: e[0][1] / omega,
            c: (e[0][2] - e[0][3] / h) / w2,
            d: e[0][3] / (h * w2),
            ap: omega * e[1][0],
            bp: e[1][1],
            cp: (e[1][2] - e[1][3] / h) / omega,
            dp: e[1][3] / (h * omega),
        }
    }

    /// One step from (u, v) under p going linearly from p0 to p1.
    #[inline(always)]
    pub fn step(&self, u: f64, v: f64, p0: f64, p1: f64) -> (f64, f64) {
        (
            self.a * u + self.b * v + self.c * p0 + self.d * p1,
            self.ap * u + self.bp * v + self.cp * p0 + self.dp * p1,
        )
    }
}

/// exp(N h) for the augmented oscillator matrix N(ξ), by scaling and squaring a Taylor
/// series (terms to order 18 on a matrix of norm ≤ 1/4: truncation below 10⁻²⁰).
fn propagator(damping: f64, h: f64) -> [[f64; 4]; 4] {
    let mut x = [[0.0; 4]; 4];
    x[0][1] = h;
    x[1][0] = -h;
    x[1][1] = -2.0 * damping * h;
    x[1][2] = h;
    x[2][3] = h;
    let norm = x
        .iter()
        .map(|r| r.iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mut squarings = 0u32;
    let mut scale = 1.0;
    while norm * scale > 0.25 && squarings < 200 {
        scale *= 0.5;
        squarings += 1;
    }
    for r in x.iter_mut() {
        for v in r.iter_mut() {
            *v *= scale;
        }
    }
    // Σ Xᵏ/k!, k = 0 … 18.
    let mut sum = identity();
    let mut term = identity();
    for k in 1..=18 {
        term = mul(&term, &x);
        let inv = 1.0 / k as f64;
        for r in term.iter_mut() {
            for v in r.iter_mut() {
                *v *= inv;
            }
        }
        for i in 0..4 {
            for j in 0..4 {
                sum[i][j] += term[i][j];
            }
        }
    }
    for _ in 0..squarings {
        sum = mul(&sum, &sum);
    }
    sum
}

fn identity() -> [[f64; 4]; 4] {
    let mut m = [[0.0; 4]; 4];
    for (i, r) in m.iter_mut().enumerate() {
        r[i] = 1.0;
    }
    m
}

fn mul(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let mut c = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            let mut s = 0.0;
            for k in 0..4 {
                s += a[i][k] * b[k][j];
            }
            c[i][j] = s;
        }
    }
    c
}

/// Response (u, u̇) of ü + 2ξωu̇ + ω²u = p(t) to `p` sampled at `dt` (linear between
/// samples), from u(0) = u0, u̇(0) = v0.
pub fn sdof_response(
    p: &[f64],
    dt: f64,
    omega: f64,
    damping: f64,
    u0: f64,
    v0: f64,
) -> (Vec<f64>, Vec<f64>) {
    let k = SdofCoefficients::new(omega, damping, dt);
    let mut u = Vec::with_capacity(p.len());
    let mut v = Vec::with_capacity(p.len());
    let (mut ui, mut vi) = (u0, v0);
    if p.is_empty() {
        return (u, v);
    }
    u.push(ui);
    v.push(vi);
    for w in p.windows(2) {
        (ui, vi) = k.step(ui, vi, w[0], w[1]);
        u.push(ui);
        v.push(vi);
    }
    (u, v)
}

/// One ordinate of a response spectrum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpectrumPoint {
    /// Period (s).
    pub period: f64,
    /// Spectral displacement max|u| (m).
    pub sd: f64,
    /// Spectral (relative) velocity max|u̇| (m/s).
    pub sv: f64,
    /// Spectral absolute acceleration max|ü + a_g| (m/s²).
    pub sa: f64,
    /// Pseudo-velocity ωSD (m/s).
    pub psv: f64,
    /// Pseudo-acceleration ω²SD (m/s²).
    pub psa: f64,
}

/// Response spectrum of ground acceleration `a` (m/s², step `dt`) at `periods` (s, > 0;
/// a period of 0 gives the rigid oscillator: SA = PSA = PGA, SD = SV = 0) and damping ratio
/// `damping`. The oscillator starts at rest and the record is followed by nothing (the
/// peak of the free vibration after the record is not sought, as in Nigam & Jennings).
/// Periods run in parallel; each is independent, so the result does not depend on the
/// number of threads.
pub fn response_spectrum(a: &[f64], dt: f64, periods: &[f64], damping: f64) -> Vec<SpectrumPoint> {
    periods
        .par_chunks(LANES)
        .flat_map_iter(|group| spectrum_group(a, dt, group, damping))
        .collect()
}

/// Oscillators stepped together: independent recursions interleaved in one loop, so the
/// latency of each one's dependency chain is hidden (and the lanes vectorise). Every lane
/// does exactly the scalar arithmetic, so results do not depend on the grouping.
const LANES: usize = 8;

fn spectrum_group(a: &[f64], dt: f64, periods: &[f64], damping: f64) -> Vec<SpectrumPoint> {
    let pga = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut k = [[0.0f64; LANES]; 8];
    let mut cv = [0.0f64; LANES];
    let mut cu = [0.0f64; LANES];
    let mut omega = [0.0f64; LANES];
    for l in 0..LANES {
        // Unused lanes and rigid oscillators (T ≤ 0) run a harmless 1 s oscillator.
        let t = periods.get(l).copied().filter(|&t| t > 0.0).unwrap_or(1.0);
        omega[l] = 2.0 * std::f64::consts::PI / t;
        let c = SdofCoefficients::new(omega[l], damping, dt);
        for (row, v) in k
            .iter_mut()
            .zip([c.a, c.b, c.c, c.d, c.ap, c.bp, c.cp, c.dp])
        {
            row[l] = v;
        }
        cv[l] = 2.0 * damping * omega[l];
        cu[l] = omega[l] * omega[l];
    }
    let [ka, kb, kc, kd, kap, kbp, kcp, kdp] = k;
    let mut u = [0.0f64; LANES];
    let mut v = [0.0f64; LANES];
    let mut sd = [0.0f64; LANES];
    let mut sv = [0.0f64; LANES];
    let mut sa = [0.0f64; LANES];
    for w in a.windows(2) {
        let (p0, p1) = (-w[0], -w[1]);
        for l in 0..LANES {
            let un = ka[l] * u[l] + kb[l] * v[l] + kc[l] * p0 + kd[l] * p1;
            let vn = kap[l] * u[l] + kbp[l] * v[l] + kcp[l] * p0 + kdp[l] * p1;
            u[l] = un;
            v[l] = vn;
            sd[l] = sd[l].max(un.abs());
            sv[l] = sv[l].max(vn.abs());
            sa[l] = sa[l].max((cv[l] * vn + cu[l] * un).abs());
        }
    }
    periods
        .iter()
        .enumerate()
        .map(|(l, &period)| {
            if period <= 0.0 {
                SpectrumPoint {
                    period,
                    sd: 0.0,
                    sv: 0.0,
                    sa: pga,
                    psv: 0.0,
                    psa: pga,
                }
            } else {
                SpectrumPoint {
                    period,
                    sd: sd[l],
                    sv: sv[l],
                    sa: sa[l],
                    psv: omega[l] * sd[l],
                    psa: omega[l] * omega[l] * sd[l],
                }
            }
        })
        .collect()
}

/// `n` periods spaced logarithmically from `t_min` to `t_max` (s).
pub fn log_periods(t_min: f64, t_max: f64, n: usize) -> Vec<f64> {
    if n <= 1 {
        return vec![t_min];
    }
    let r = (t_max / t_min).ln() / (n - 1) as f64;
    (0..n).map(|i| t_min * (r * i as f64).exp()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Chopra (Dynamics of Structures, Table 5.2.1) closed-form coefficients, m = 1, k = ω².
    fn chopra(omega: f64, xi: f64, dt: f64) -> [f64; 8] {
        let wd = omega * (1.0 - xi * xi).sqrt();
        let e = (-xi * omega * dt).exp();
        let (s, c) = ((wd * dt).sin(), (wd * dt).cos());
        let r = xi / (1.0 - xi * xi).sqrt();
        let k = omega * omega;
        let a = e * (r * s + c);
        let b = e * s / wd;
        let cc = (2.0 * xi / (omega * dt)
            + e * (((1.0 - 2.0 * xi * xi) / (wd * dt) - r) * s
                - (1.0 + 2.0 * xi / (omega * dt)) * c))
            / k;
        let d = (1.0 - 2.0 * xi / (omega * dt)
            + e * ((2.0 * xi * xi - 1.0) / (wd * dt) * s + 2.0 * xi / (omega * dt) * c))
            / k;
        let ap = -e * omega / (1.0 - xi * xi).sqrt() * s;
        let bp = e * (c - r * s);
        let cp = (-1.0 / dt + e * ((omega / (1.0 - xi * xi).sqrt() + r / dt) * s + c / dt)) / k;
        let dp = (1.0 - e * (r * s + c)) / (k * dt);
        [a, b, cc, d, ap, bp, cp, dp]
    }

    #[test]
    fn coefficients_match_the_closed_forms() {
        for &(t, xi, dt) in &[
            (1.0, 0.05, 0.01),
            (0.1, 0.0, 0.005),
            (3.0, 0.2, 0.02),
            (0.05, 0.05, 0.02),
        ] {
            let omega = 2.0 * std::f64::consts::PI / t;
            let k = SdofCoefficients::new(omega, xi, dt);
            let ours = [k.a, k.b, k.c, k.d, k.ap, k.bp, k.cp, k.dp];
            let theirs = chopra(omega, xi, dt);
            for (i, (x, y)) in ours.iter().zip(theirs).enumerate() {
                let scale = y.abs().max(1e-300);
                assert!(
                    (x - y).abs() <= 1e-9 * scale + 1e-15,
                    "T {t} ξ {xi} dt {dt} coefficient {i}: {x} vs {y}"
                );
            }
        }
    }
}
