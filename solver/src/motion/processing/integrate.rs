//! Integration of a uniformly sampled acceleration to velocity and displacement, exact for
//! the piecewise-linear acceleration through the samples (the same assumption as the
//! Nigam–Jennings recursion and as the time functions that evaluate a motion):
//!
//! v_{i+1} = v_i + Δt (a_i + a_{i+1})/2,
//! u_{i+1} = u_i + Δt v_i + Δt² (2a_i + a_{i+1})/6,
//!
//! from rest (v_0 = u_0 = 0). Between samples, with s = t − t_i and δ = (a_{i+1} − a_i)/Δt:
//! a = a_i + δs, v = v_i + a_i s + δs²/2, u = u_i + v_i s + a_i s²/2 + δs³/6.

/// Velocity and displacement of `acceleration` sampled at `dt`, from rest.
pub fn integrate(acceleration: &[f64], dt: f64) -> (Vec<f64>, Vec<f64>) {
    let n = acceleration.len();
    let mut v = vec![0.0; n];
    let mut u = vec![0.0; n];
    for i in 1..n {
        let (a0, a1) = (acceleration[i - 1], acceleration[i]);
        v[i] = v[i - 1] + dt * 0.5 * (a0 + a1);
        u[i] = u[i - 1] + dt * v[i - 1] + dt * dt * (2.0 * a0 + a1) / 6.0;
    }
    (v, u)
}

/// Remove the linear acceleration α + βt that makes the final velocity and displacement
/// zero (the two end conditions v(T) = u(T) = 0 solved exactly; the correction is the
/// minimal-order polynomial that meets them). Returns (α, β).
pub fn zero_end_motion(acceleration: &mut [f64], dt: f64) -> (f64, f64) {
    let n = acceleration.len();
    if n < 2 {
        return (0.0, 0.0);
    }
    let (v, u) = integrate(acceleration, dt);
    let t_end = (n - 1) as f64 * dt;
    // [T, T²/2; T²/2, T³/6] [α; β] = [v(T); u(T)], determinant −T⁴/12.
    let (a11, a12, a22) = (t_end, 0.5 * t_end * t_end, t_end * t_end * t_end / 6.0);
    let det = a11 * a22 - a12 * a12;
    let (rv, ru) = (v[n - 1], u[n - 1]);
    let alpha = (rv * a22 - a12 * ru) / det;
    let beta = (a11 * ru - a12 * rv) / det;
    for (i, a) in acceleration.iter_mut().enumerate() {
        *a -= alpha + beta * (i as f64 * dt);
    }
    (alpha, beta)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_for_linear_acceleration() {
        // a = 1 + 2t: v = t + t², u = t²/2 + t³/3 exactly.
        let dt = 0.1;
        let a: Vec<f64> = (0..11).map(|i| 1.0 + 2.0 * i as f64 * dt).collect();
        let (v, u) = integrate(&a, dt);
        let t: f64 = 1.0;
        assert!((v[10] - (t + t * t)).abs() < 1e-13);
        assert!((u[10] - (0.5 * t * t + t * t * t / 3.0)).abs() < 1e-13);
    }

    #[test]
    fn end_correction_zeroes_final_velocity_and_displacement() {
        let dt = 0.01;
        let mut a: Vec<f64> = (0..1000).map(|i| (0.37 * i as f64).sin() + 0.05).collect();
        zero_end_motion(&mut a, dt);
        let (v, u) = integrate(&a, dt);
        assert!(
            v[999].abs() < 1e-12 && u[999].abs() < 1e-12,
            "{} {}",
            v[999],
            u[999]
        );
    }
}
