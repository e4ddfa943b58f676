//! A point mass M at the junction of two semi-infinite rods of impedance Z = ρ c A, hit by
//! an incident velocity pulse v_i(t) (docs/verification_references.md §W13, mass scaling).
//!
//! The left rod pushes the mass with Z (2 v_i − v), the right rod (transmitting only) holds
//! it back with Z v, so M dv/dt = 2Z (v_i − v), i.e. τ v′ + v = v_i with τ = M / 2Z
//! (Graff, *Wave Motion in Elastic Solids*, 1975, §1.6); the transmitted wave carries v.
//! For the sin² pulse v_i = v0 sin²(πt/T) = (v0/2)(1 − cos ωt), ω = 2π/T, 0 ≤ t ≤ T, from
//! rest:
//!
//! v/v0 = ½ − (cos ωt + ωτ sin ωt) / (2(1 + ω²τ²)) − (½ − 1/(2(1 + ω²τ²))) e^{−t/τ},
//!
//! and after the pulse v decays as v(T) e^{−(t−T)/τ}, so the peak lies in [0, T].

/// The transmitted velocity per unit v0 at time `t` (s) of a sin² pulse of duration
/// `period` (s) through a junction of time constant `tau` = M/2Z (s).
pub fn transmitted_velocity(t: f64, tau: f64, period: f64) -> f64 {
    if t <= 0.0 {
        return 0.0;
    }
    let omega = 2.0 * std::f64::consts::PI / period;
    let wt = omega * tau;
    let a = 1.0 / (2.0 * (1.0 + wt * wt));
    let s = t.min(period);
    let v = 0.5 - a * ((omega * s).cos() + wt * (omega * s).sin()) - (0.5 - a) * (-s / tau).exp();
    if t <= period {
        v
    } else {
        v * (-(t - period) / tau).exp()
    }
}

/// The peak transmitted velocity per unit v0 (the largest of 200,001 samples over [0, T]:
/// the peak is smooth, the sampling error ~1e-10).
pub fn peak_transmitted(tau: f64, period: f64) -> f64 {
    let n = 200_000;
    (0..=n)
        .map(|k| transmitted_velocity(period * k as f64 / n as f64, tau, period))
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form against RK4 of τ v′ + v = v_i (20,000 steps over 2 T).
    #[test]
    fn closed_form_solves_the_equation_of_motion() {
        let (tau, period) = (1.75e-3, 7.07e-3);
        let incident = |t: f64| {
            if (0.0..period).contains(&t) {
                (std::f64::consts::PI * t / period).sin().powi(2)
            } else {
                0.0
            }
        };
        let rate = |t: f64, v: f64| (incident(t) - v) / tau;
        let steps = 20_000;
        let h = 2.0 * period / steps as f64;
        let (mut t, mut v) = (0.0, 0.0f64);
        let mut worst = 0.0f64;
        for _ in 0..steps {
            let k1 = rate(t, v);
            let k2 = rate(t + 0.5 * h, v + 0.5 * h * k1);
            let k3 = rate(t + 0.5 * h, v + 0.5 * h * k2);
            let k4 = rate(t + h, v + h * k3);
            v += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
            t += h;
            worst = worst.max((v - transmitted_velocity(t, tau, period)).abs());
        }
        assert!(worst < 1e-8, "{worst}");
        let peak = peak_transmitted(tau, period);
        assert!(peak > 0.7 && peak < 0.8, "{peak}");
        // No mass: the pulse passes whole; a heavy mass holds it back.
        assert!((peak_transmitted(1e-9, period) - 1.0).abs() < 1e-5);
        assert!(peak_transmitted(10.0 * period, period) < 0.05);
    }
}
