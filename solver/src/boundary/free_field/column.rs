//! A one-dimensional free-field column: the response of a laterally uniform, layered
//! half-space to vertically incident P (z), SV/SH (x, y) waves, stepped with the same
//! explicit leapfrog as the main grid.
//!
//! Per unit plan area, a level l at height z_l carries the lumped mass Σ ρ_e h_e / 2 of
//! its elements; element e between levels l and l+1 (height h_e) has the strains
//! γ_zx = Δu_x/h_e, γ_yz = Δu_y/h_e, ε_zz = Δu_z/h_e (uniaxial strain), hence the stress
//! tensor σ_zx = G γ_zx, σ_yz = G γ_yz, σ_zz = (λ+2G) ε_zz, σ_xx = σ_yy = λ ε_zz,
//! σ_xy = 0 — the lumped two-node element of W1, exact at Courant 1 in 1D. Rayleigh
//! damping C = αM + βK acts with the lagged velocity V^{n−½}, as in the main grid.
//!
//! The base is either **transmitting** (the underlying half-space, of the deepest
//! layer's material, replaced by a centred Lysmer dashpot C = diag(ρc_s, ρc_s, ρc_p)
//! loaded with 2 C v_in(t): exact for 1D plane waves, Joyner & Chen 1975) or **rigid**
//! (the base follows a prescribed "within" motion). The top is a free surface (the
//! ground surface). The column is independent of the main grid: the main grid reads its
//! displacements, full-step velocities and stresses (one-way coupling, as in FLAC3D's
//! free field).

use nalgebra::Matrix3;

use crate::boundary::centred_dashpot::CentredDashpotNode;
use crate::material::{Elastic, Voigt};

/// One element (layer slice) of a column.
#[derive(Clone, Copy, Debug)]
pub struct ColumnElement {
    /// Height (m).
    pub height: f64,
    /// Material (elastic constants, density).
    pub material: Elastic,
    /// Rayleigh damping of the element: mass-proportional α (1/s), stiffness-proportional β (s).
    pub alpha: f64,
    pub beta: f64,
}

/// How the base of a column is driven.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColumnBase {
    /// Half-space below: dashpot plus 2 C v_in (incident, upgoing motion).
    Transmitting,
    /// The base follows a prescribed (within) motion.
    Rigid,
}

/// The input of one step at the column's base.
#[derive(Clone, Copy, Debug)]
pub enum BaseDrive {
    /// Incident (upgoing) particle velocity at tⁿ (for a transmitting base).
    Incident([f64; 3]),
    /// Prescribed V^{n+½} of the base level (for a rigid base).
    HalfStepVelocity([f64; 3]),
}

/// A free-field column.
#[derive(Clone, Debug)]
pub struct Column {
    /// Level heights z_l, increasing from the base (m).
    pub levels: Vec<f64>,
    /// Elements between consecutive levels.
    pub elements: Vec<ColumnElement>,
    /// Lumped mass per unit area of each level (kg/m²).
    pub mass: Vec<f64>,
    base: ColumnBase,
    /// Base dashpot per unit area (ρc_s, ρc_s, ρc_p of the deepest layer).
    base_dashpot: [f64; 3],
    base_node: CentredDashpotNode,
    /// Mass-proportional α of each level: Σ_e α_e M_e / M.
    alpha: Vec<f64>,
    /// Any element with β > 0.
    any_beta: bool,
    /// Uⁿ.
    pub u: Vec<[f64; 3]>,
    /// V^{n−½} (before the step), V^{n+½} after.
    pub v: Vec<[f64; 3]>,
    /// V^{n−½} of the last step (to form the full-step velocity).
    v_prev: Vec<[f64; 3]>,
    /// U^{n} of the last step (after the step, `u` holds U^{n+1}).
    u_prev: Vec<[f64; 3]>,
    /// Stress of every element at tⁿ of the last step (Voigt).
    stress: Vec<Voigt>,
    /// Stiffness-proportional damping traction β (σ_zx, σ_yz, σ_zz)(V^{n−½}) of every
    /// element at tⁿ of the last step.
    damping_traction: Vec<[f64; 3]>,
    /// Δt of the last step.
    dt: f64,
    /// Force per unit area that the ground below exerts on the base level at tⁿ.
    base_traction: [f64; 3],
    /// Scratch: internal and damping forces per level.
    f_int: Vec<[f64; 3]>,
    f_damp: Vec<[f64; 3]>,
    /// Steps taken.
    steps: u64,
}

impl Column {
    /// A column with the given levels (increasing) and elements (one fewer), base
    /// condition and time step.
    pub fn new(levels: Vec<f64>, elements: Vec<ColumnElement>, base: ColumnBase, dt: f64) -> Self {
        assert_eq!(
            levels.len(),
            elements.len() + 1,
            "one element between levels"
        );
        let n = levels.len();
        let mut mass = vec![0.0; n];
        let mut alpha = vec![0.0; n];
        for (e, el) in elements.iter().enumerate() {
            let m = 0.5 * el.material.density * el.height;
            mass[e] += m;
            mass[e + 1] += m;
            alpha[e] += el.alpha * m;
            alpha[e + 1] += el.alpha * m;
        }
        for (a, m) in alpha.iter_mut().zip(&mass) {
            *a /= m;
        }
        let any_beta = elements.iter().any(|e| e.beta > 0.0);
        let half_space = elements[0].material;
        let (rcs, rcp) = (
            half_space.density * half_space.s_wave_speed(),
            half_space.density * half_space.p_wave_speed(),
        );
        let base_dashpot = [rcs, rcs, rcp];
        let c = match base {
            ColumnBase::Transmitting => Matrix3::from_diagonal(&base_dashpot.into()),
            ColumnBase::Rigid => Matrix3::zeros(),
        };
        let constrained = if base == ColumnBase::Rigid { 0b111 } else { 0 };
        Self {
            base_node: CentredDashpotNode::new(mass[0], c, constrained, dt),
            levels,
            elements,
            mass,
            base,
            base_dashpot,
            alpha,
            any_beta,
            u: vec![[0.0; 3]; n],
            v: vec![[0.0; 3]; n],
            v_prev: vec![[0.0; 3]; n],
            u_prev: vec![[0.0; 3]; n],
            stress: vec![[0.0; 6]; n - 1],
            damping_traction: vec![[0.0; 3]; n - 1],
            dt,
            base_traction: [0.0; 3],
            f_int: vec![[0.0; 3]; n],
            f_damp: vec![[0.0; 3]; n],
            steps: 0,
        }
    }

    /// Number of levels.
    pub fn n_levels(&self) -> usize {
        self.levels.len()
    }

    /// The base condition.
    pub fn base(&self) -> ColumnBase {
        self.base
    }

    /// The level at height `z` (within `tol`), if any.
    pub fn level_at(&self, z: f64, tol: f64) -> Option<usize> {
        let i = self.levels.partition_point(|&l| l < z - tol);
        (i < self.levels.len() && (self.levels[i] - z).abs() <= tol).then_some(i)
    }

    /// Stable step of the column: min h_e / c_p,e (the 1D lumped two-node element, whose
    /// ω_max = 2 c_p / h).
    pub fn critical_step(&self) -> f64 {
        self.elements
            .iter()
            .map(|e| e.height / e.material.p_wave_speed())
            .fold(f64::INFINITY, f64::min)
    }

    /// Element stress from the displacements `u` (Voigt xx, yy, zz, xy, yz, zx).
    fn element_stress(&self, e: usize, u: &[[f64; 3]]) -> Voigt {
        let el = &self.elements[e];
        let h = el.height;
        let (lam, g) = (el.material.lambda, el.material.mu);
        let gzx = (u[e + 1][0] - u[e][0]) / h;
        let gyz = (u[e + 1][1] - u[e][1]) / h;
        let ezz = (u[e + 1][2] - u[e][2]) / h;
        [
            lam * ezz,
            lam * ezz,
            (lam + 2.0 * g) * ezz,
            0.0,
            g * gyz,
            g * gzx,
        ]
    }

    /// One step tⁿ → tⁿ⁺¹ with the base driven by `drive`.
    pub fn step(&mut self, drive: BaseDrive, dt: f64) {
        let n = self.levels.len();
        for f in self.f_int.iter_mut().chain(self.f_damp.iter_mut()) {
            *f = [0.0; 3];
        }
        for e in 0..n - 1 {
            let s = self.element_stress(e, &self.u);
            self.stress[e] = s;
            // Traction on the element's top face (normal +z): (σ_zx, σ_yz, σ_zz).
            let t = [s[5], s[4], s[2]];
            for d in 0..3 {
                self.f_int[e + 1][d] += t[d];
                self.f_int[e][d] -= t[d];
            }
            let beta = self.elements[e].beta;
            if self.any_beta && beta > 0.0 {
                let sd = self.element_stress(e, &self.v);
                let td = [beta * sd[5], beta * sd[4], beta * sd[2]];
                self.damping_traction[e] = td;
                for d in 0..3 {
                    self.f_damp[e + 1][d] += td[d];
                    self.f_damp[e][d] -= td[d];
                }
            }
        }
        self.u_prev.copy_from_slice(&self.u);
        self.v_prev.copy_from_slice(&self.v);
        for l in 0..n {
            let m = self.mass[l];
            let force: [f64; 3] = std::array::from_fn(|d| {
                -self.f_int[l][d] - self.f_damp[l][d] - self.alpha[l] * m * self.v_prev[l][d]
            });
            let vn = if l == 0 {
                match drive {
                    BaseDrive::Incident(vin) => {
                        let input: [f64; 3] =
                            std::array::from_fn(|d| force[d] + 2.0 * self.base_dashpot[d] * vin[d]);
                        let vn =
                            self.base_node
                                .half_step_velocity(self.v_prev[0], input, [0.0; 3], dt);
                        let fd = self.base_node.dashpot_force(self.v_prev[0], vn, dt);
                        self.base_traction =
                            std::array::from_fn(|d| 2.0 * self.base_dashpot[d] * vin[d] + fd[d]);
                        vn
                    }
                    BaseDrive::HalfStepVelocity(vb) => {
                        // Reaction of the prescribed base: M (V^{n+½} − V^{n−½})/Δt − F.
                        self.base_traction = std::array::from_fn(|d| {
                            m * (vb[d] - self.v_prev[0][d]) / dt - force[d]
                        });
                        vb
                    }
                }
            } else {
                std::array::from_fn(|d| self.v_prev[l][d] + dt * force[d] / m)
            };
            self.v[l] = vn;
            for d in 0..3 {
                self.u[l][d] += dt * vn[d];
            }
        }
        self.steps += 1;
    }

    /// Displacement of level `l` at tⁿ of the last step.
    #[inline]
    pub fn displacement(&self, l: usize) -> [f64; 3] {
        self.u_prev[l]
    }

    /// Full-step velocity ½(V^{n−½} + V^{n+½}) of level `l` at tⁿ of the last step.
    #[inline]
    pub fn velocity(&self, l: usize) -> [f64; 3] {
        std::array::from_fn(|d| 0.5 * (self.v_prev[l][d] + self.v[l][d]))
    }

    /// Stress at tⁿ of the element between levels `e` and `e + 1`.
    #[inline]
    pub fn stress(&self, e: usize) -> Voigt {
        self.stress[e]
    }

    /// Force per unit area that the ground below exerts on the base level at tⁿ (the
    /// traction σ·n of the half-space, n = −z).
    #[inline]
    pub fn base_traction(&self) -> [f64; 3] {
        self.base_traction
    }

    /// Force per unit area that the part of the column above level `l` exerts on the part
    /// below, at tⁿ of the last step, in the discrete system: the traction of the element
    /// above (with its stiffness-proportional damping) less the inertia and mass damping
    /// of the half of its mass lumped at level l,
    /// F = t_l + β t_d,l − M_a (Aⁿ + α_a V^{n−½}), M_a = ½ ρ_a h_a.
    /// A grid that ends at level l and takes this force follows the column exactly
    /// (a top face below the ground surface).
    pub fn force_from_above(&self, l: usize) -> [f64; 3] {
        if l + 1 >= self.levels.len() {
            return [0.0; 3];
        }
        let el = &self.elements[l];
        let ma = 0.5 * el.material.density * el.height;
        let s = self.stress[l];
        let t = [s[5], s[4], s[2]];
        let td = self.damping_traction[l];
        std::array::from_fn(|d| {
            let a = (self.v[l][d] - self.v_prev[l][d]) / self.dt;
            t[d] + td[d] - ma * (a + el.alpha * self.v_prev[l][d])
        })
    }

    /// Energy per unit area at tⁿ of the last step: ½ Σ M |Vⁿ|² + ½ Σ σ:ε h (J/m²).
    pub fn energy(&self) -> f64 {
        let kinetic: f64 = (0..self.levels.len())
            .map(|l| {
                let v = self.velocity(l);
                0.5 * self.mass[l] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
            })
            .sum();
        let strain: f64 = self
            .elements
            .iter()
            .enumerate()
            .map(|(e, el)| {
                let s = self.stress[e];
                let (g, m) = (el.material.mu, el.material.p_modulus());
                0.5 * el.height * (s[5] * s[5] / g + s[4] * s[4] / g + s[2] * s[2] / m)
            })
            .sum();
        kinetic + strain
    }

    /// The state to checkpoint: u, v, u_prev, v_prev, stresses, base traction.
    pub fn state_values(&self, out: &mut Vec<f64>) {
        for f in [&self.u, &self.v, &self.u_prev, &self.v_prev] {
            out.extend(f.iter().flatten());
        }
        out.extend(self.stress.iter().flatten());
        out.extend(self.base_traction);
    }

    /// Restore what [`Column::state_values`] wrote; returns the values consumed.
    pub fn restore_state(&mut self, values: &[f64]) -> Result<usize, String> {
        let n = self.levels.len();
        let need = 4 * 3 * n + 6 * (n - 1) + 3;
        if values.len() < need {
            return Err(format!(
                "free-field column state too short ({} values, {need} needed)",
                values.len()
            ));
        }
        let mut it = values.iter().copied();
        for f in [&mut self.u, &mut self.v, &mut self.u_prev, &mut self.v_prev] {
            for x in f.iter_mut().flatten() {
                *x = it.next().unwrap_or_default();
            }
        }
        for x in self.stress.iter_mut().flatten() {
            *x = it.next().unwrap_or_default();
        }
        for x in self.base_traction.iter_mut() {
            *x = it.next().unwrap_or_default();
        }
        Ok(need)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rock() -> Elastic {
        Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap()
    }

    fn uniform(n: usize, h: f64, dt: f64, base: ColumnBase) -> Column {
        let levels = (0..=n).map(|l| l as f64 * h).collect();
        let elements = vec![
            ColumnElement {
                height: h,
                material: rock(),
                alpha: 0.0,
                beta: 0.0,
            };
            n
        ];
        Column::new(levels, elements, base, dt)
    }

    /// An incident S half-sine (v0 0.1 m/s, T 0.02 s) doubles at the free surface (W1:
    /// 2 v0), and once the pulse reflected down has crossed the transmitting base the
    /// column holds almost none of the ρ c_s v0² T/2 = 464.76 J/m² that came in.
    #[test]
    fn incident_pulse_doubles_at_the_surface_and_leaves_through_the_base() {
        let m = rock();
        let c = m.s_wave_speed();
        let n = 200;
        let dt = 0.9 / m.p_wave_speed();
        let mut col = uniform(n, 1.0, dt, ColumnBase::Transmitting);
        let (v0, period) = (0.1, 0.02);
        let mut top_peak = 0.0f64;
        let mut peak_energy = 0.0f64;
        let mut t = 0.0;
        while t < 2.0 * n as f64 / c + period + 0.1 {
            let vin = if t < period {
                v0 * (std::f64::consts::PI * t / period).sin()
            } else {
                0.0
            };
            col.step(BaseDrive::Incident([vin, 0.0, 0.0]), dt);
            top_peak = top_peak.max(col.velocity(n)[0].abs());
            peak_energy = peak_energy.max(col.energy());
            t += dt;
        }
        let carried = m.density * c * v0 * v0 * period / 2.0;
        assert!((top_peak / v0 - 2.0).abs() < 0.03, "surface {top_peak}");
        assert!(
            (peak_energy / carried - 1.0).abs() < 0.01,
            "{peak_energy} vs {carried}"
        );
        assert!(
            col.energy() < 0.005 * carried,
            "left in the column: {}",
            col.energy()
        );
    }
}
