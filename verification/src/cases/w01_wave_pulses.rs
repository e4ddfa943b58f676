//! W1 — 1D P and S pulses in a column (d'Alembert).
//!
//! Goal: the explicit hex8 core propagates plane P and S pulses with the right speed,
//! amplitude and boundary reflections.
//!
//! ```text
//!   ┌─┐ z = 200 m  free (velocity doubles) or fixed (stress doubles)
//!   │ │ one 1 m element wide, 200 elements high, lateral DOFs constrained
//!   │ │ ← mid-height element: incident stress ρ c v0, net displacement 2 v0 T/π
//!   └─┘ z = 0: prescribed velocity v0 sin(πt/T), v0 = 0.1 m/s, T = 0.02 s
//! ```
//!
//! Default rock E 20 GPa, ν 0.25, ρ 2700 kg/m³ (c_p 2981.42, c_s 1721.33 m/s); Δt = 0.9 h/c_p
//! (P Courant 0.9, S Courant 0.52); ≥ 34 elements per pulse length.
//! Reference: d'Alembert's solution, docs/verification_references.md §W1 (σ = ρ c v0: P 0.8050 MPa,
//! S 0.4648 MPa; free end 2 v0 and 2.5465 mm; fixed end 2ρ c v0; net 1.2732 mm).
//! Tolerances (W1): peaks ±3 % (lumped-mass central difference disperses ≤ 2 % at ≥ 20
//! elements per pulse), arrival ±2Δt, doubling 2.00 ± 0.06, net displacement ±1 %.

use dcfm::Result;

use crate::analytic::HalfSinePulse1D;
use crate::models::column::{element_at, node_at, ColumnSetup, TopEnd, Wave};
use crate::record::{CaseOutput, Check, Series};

/// The case title (the `case` of its rows).
pub const TITLE: &str = "W1 1D P and S pulses";

const SOURCE: &str = "docs/verification_references.md §W1 (d'Alembert)";

/// What one column run measured.
#[derive(Clone, Debug, Default)]
pub struct ColumnMeasures {
    /// Peak |stress| at the mid-height element before the top reflection returns (Pa).
    pub mid_peak_stress: f64,
    /// Time of that peak (s).
    pub mid_peak_time: f64,
    /// Height of the mid element's centre (m).
    pub mid_z: f64,
    /// Net displacement at the mid node after the pulse passed (m).
    pub mid_net_displacement: f64,
    /// Peak |velocity| at the top node (m/s).
    pub top_peak_velocity: f64,
    /// Top displacement after the reflection (m).
    pub top_displacement: f64,
    /// Peak |stress| in the top element (Pa).
    pub top_peak_stress: f64,
    /// L2 (in time) error of the mid-node displacement vs d'Alembert, relative to the net
    /// displacement, over the incident passage.
    pub mid_displacement_l2_error: f64,
    pub dt: f64,
    /// Largest |energy residual| over the run / largest energy over the run (W12).
    pub energy_residual: f64,
    /// Time of every step (s), with the mid-node displacement and d'Alembert's there
    /// (incident and reflected waves), and
    /// the top-node velocity and d'Alembert's free-end velocity there (for the plots).
    pub times: Vec<f64>,
    pub mid_displacement: Vec<f64>,
    pub mid_displacement_reference: Vec<f64>,
    pub top_velocity: Vec<f64>,
    pub top_velocity_reference: Vec<f64>,
}

/// Run one column and measure it.
pub fn measure(setup: &ColumnSetup) -> Result<ColumnMeasures> {
    let mut sim = setup.build()?;
    let c = setup.speed();
    let pulse = HalfSinePulse1D::new(setup.v0, setup.period, c, setup.density)
        .expect("valid pulse")
        .with_shape(setup.shape);
    let h = setup.height;
    let (dof, stress_index) = match setup.wave {
        Wave::P => (2, 2),
        Wave::S => (0, 5),
    };
    let mid_e = element_at(setup, 0.5 * h);
    let top_e = element_at(setup, h);
    let mid_n = node_at(setup, 0.5 * h);
    let top_n = node_at(setup, h);
    let mut m = ColumnMeasures {
        mid_z: (mid_e as f64 + 0.5) * setup.element_size,
        dt: sim.dt,
        ..Default::default()
    };
    let z_mid_node = sim.model.mesh.coords[mid_n][2];
    let reflection = if setup.top == TopEnd::Free { 1.0 } else { -1.0 };
    let t_end = 2.0 * h / c;
    let mut l2 = 0.0;
    let mut l2_n = 0usize;
    let mut max_residual = 0.0f64;
    let mut max_scale = 0.0f64;
    while sim.time < t_end {
        sim.step()?;
        let t = sim.time;
        let (_, s_mid) = sim.model.element_strain_stress(mid_e, &sim.u);
        if t <= 1.2 * h / c && s_mid[stress_index].abs() > m.mid_peak_stress {
            m.mid_peak_stress = s_mid[stress_index].abs();
            m.mid_peak_time = t;
        }
        let (_, s_top) = sim.model.element_strain_stress(top_e, &sim.u);
        m.top_peak_stress = m.top_peak_stress.max(s_top[stress_index].abs());
        m.top_peak_velocity = m.top_peak_velocity.max(sim.v[top_n][dof].abs());
        if t <= h / c {
            m.mid_net_displacement = sim.u[mid_n][dof];
            let e = sim.u[mid_n][dof] - pulse.displacement(z_mid_node, t);
            l2 += e * e;
            l2_n += 1;
        }
        if t <= 2.0 * h / c {
            m.top_displacement = sim.u[top_n][dof];
        }
        m.times.push(t);
        m.mid_displacement.push(sim.u[mid_n][dof]);
        // Incident wave plus its reflection at the top (image source at 2H − z; same sign
        // at a free end, opposite at a fixed one).
        m.mid_displacement_reference.push(
            pulse.displacement(z_mid_node, t)
                + reflection * pulse.displacement(2.0 * h - z_mid_node, t),
        );
        // Half-step velocity V^{n−½} against the doubled incident velocity at the free
        // end (d'Alembert: incident + reflected), sampled at t − Δt/2.
        m.top_velocity.push(sim.v[top_n][dof]);
        m.top_velocity_reference
            .push(2.0 * pulse.velocity(h, t - 0.5 * sim.dt));
        max_residual = max_residual.max(sim.energies.residual().abs());
        max_scale = max_scale.max(sim.energies.scale());
    }
    m.energy_residual = max_residual / max_scale;
    m.mid_displacement_l2_error = (l2 / l2_n.max(1) as f64).sqrt() / pulse.net_displacement();
    Ok(m)
}

/// Run W1: P and S, free and fixed top.
pub fn run() -> Result<CaseOutput> {
    let mut check = Check::new(TITLE);
    let mut series = Vec::new();
    for wave in [Wave::P, Wave::S] {
        let name = if wave == Wave::P { "P" } else { "S" };
        let free = ColumnSetup::w1(wave, TopEnd::Free);
        let c = free.speed();
        let pulse =
            HalfSinePulse1D::new(free.v0, free.period, c, free.density).expect("valid pulse");
        let mf = measure(&free)?;
        series.push(Series::new(
            TITLE,
            &format!(
                "{name}, free top: displacement at z = {:.0} m",
                0.5 * free.height
            ),
            ("time (s)", "displacement (m)"),
            mf.times.clone(),
            mf.mid_displacement.clone(),
            Some(mf.mid_displacement_reference.clone()),
        ));
        series.push(Series::new(
            TITLE,
            &format!("{name}, free top: velocity of the top node"),
            ("time (s)", "velocity (m/s)"),
            mf.times.clone(),
            mf.top_velocity.clone(),
            Some(mf.top_velocity_reference.clone()),
        ));
        check
            .relative(
                &format!("{name}: incident stress ρcv0 (Pa)"),
                pulse.peak_stress(),
                mf.mid_peak_stress,
                0.03,
                SOURCE,
            )
            .absolute(
                &format!("{name}: arrival of the peak at z = {:.1} m (s)", mf.mid_z),
                mf.mid_z / c + 0.5 * free.period,
                mf.mid_peak_time,
                2.0 * mf.dt,
                SOURCE,
            )
            .relative(
                &format!("{name}: net displacement 2v0T/π (m)"),
                pulse.net_displacement(),
                mf.mid_net_displacement,
                0.01,
                SOURCE,
            )
            .absolute(
                &format!("{name}: free-end velocity / v0"),
                2.0,
                mf.top_peak_velocity / free.v0,
                0.06,
                SOURCE,
            )
            .relative(
                &format!("{name}: free-end displacement after reflection (m)"),
                2.0 * pulse.net_displacement(),
                mf.top_displacement,
                0.01,
                SOURCE,
            );
        let fixed = ColumnSetup::w1(wave, TopEnd::Fixed);
        let mx = measure(&fixed)?;
        check.relative(
            &format!("{name}: fixed-end stress 2ρcv0 (Pa)"),
            2.0 * pulse.peak_stress(),
            mx.top_peak_stress,
            0.03,
            SOURCE,
        );
        for (end, m) in [("free", &mf), ("fixed", &mx)] {
            check.absolute(
                &format!("{name}, {end} top: max |energy residual| / largest energy"),
                0.0,
                m.energy_residual,
                0.01,
                "docs/verification_references.md §W12 (residual ≤ 1–2 %)",
            );
        }
    }
    Ok(CaseOutput {
        rows: check.finish(),
        series,
    })
}
