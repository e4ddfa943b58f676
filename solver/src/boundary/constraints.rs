//! Fixed DOFs and prescribed displacement / velocity / acceleration histories.
//!
//! A constrained DOF gets its half-step velocity from the prescription instead of from
//! the equation of motion; the force needed to impose it (the reaction) does the input
//! work that closes the energy balance.

use serde::Deserialize;

use crate::load::TimeFunction;

/// What a prescribed history gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MotionKind {
    /// u(t) = h(t).
    Displacement,
    /// v(t) = h(t); the displacement is ∫h exactly at every step.
    Velocity,
    /// a(t) = h(t); the half-step velocity is ∫h at the half step.
    Acceleration,
}

/// One prescribed motion: DOF `dof` (0 x, 1 y, 2 z) of `nodes` follows `history`.
#[derive(Clone, Debug)]
pub struct Prescribed {
    pub nodes: Vec<u32>,
    pub dof: usize,
    pub kind: MotionKind,
    pub history: TimeFunction,
}

impl Prescribed {
    /// Half-step velocity V^{n+½} of the DOF at a node whose displacement is `u_now`, for
    /// the step from `t` to `t + dt`.
    #[inline]
    pub fn half_step_velocity(&self, t: f64, dt: f64, u_now: f64) -> f64 {
        match self.kind {
            MotionKind::Displacement => (self.history.value(t + dt) - u_now) / dt,
            MotionKind::Velocity => (self.history.integral(t + dt) - self.history.integral(t)) / dt,
            MotionKind::Acceleration => self.history.integral(t + 0.5 * dt),
        }
    }
}

/// All constraints of a model.
#[derive(Clone, Debug, Default)]
pub struct Constraints {
    /// Bit d set: DOF d of the node is fixed (zero motion).
    pub fixed: Vec<u8>,
    /// Prescribed motions (disjoint from fixed DOFs and from each other).
    pub prescribed: Vec<Prescribed>,
    /// Bit d set: DOF d is fixed or prescribed.
    pub constrained: Vec<u8>,
}

impl Constraints {
    /// No constraint on `n_nodes` nodes.
    pub fn new(n_nodes: usize) -> Self {
        Self {
            fixed: vec![0; n_nodes],
            prescribed: Vec::new(),
            constrained: vec![0; n_nodes],
        }
    }

    /// Fix DOFs `mask` (bits x=1, y=2, z=4) of `nodes`.
    pub fn fix(&mut self, nodes: &[u32], mask: u8) {
        for &n in nodes {
            self.fixed[n as usize] |= mask;
            self.constrained[n as usize] |= mask;
        }
    }

    /// Add a prescribed motion. Returns the first node whose DOF was already constrained.
    pub fn prescribe(&mut self, p: Prescribed) -> Result<(), u32> {
        let bit = 1u8 << p.dof;
        if let Some(&n) = p
            .nodes
            .iter()
            .find(|&&n| self.constrained[n as usize] & bit != 0)
        {
            return Err(n);
        }
        for &n in &p.nodes {
            self.constrained[n as usize] |= bit;
        }
        self.prescribed.push(p);
        Ok(())
    }
}
