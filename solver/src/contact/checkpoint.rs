//! The evolving state of the contact interfaces as a flat list of numbers, for checkpoints
//! (a resumed run must know which pairs lost their cohesion, which slide, which moved to
//! point-to-surface contact and where).

use super::pair::PairState;
use super::ContactSystem;

/// Values stored per node of surface a.
const PER_NODE: usize = 20;

impl ContactSystem {
    /// Every interface node's state, plus the friction work, as numbers.
    pub fn state_values(&self) -> Vec<f64> {
        let mut out = vec![self.friction_work];
        for iface in &self.interfaces {
            for s in &iface.slaves {
                out.extend([
                    s.state.code() as f64,
                    if s.surface { 1.0 } else { 0.0 },
                    s.partner as f64,
                    s.gap,
                    s.slip[0],
                    s.slip[1],
                    s.slip[2],
                    s.acc_slip,
                    s.normal_force,
                    s.tangential[0],
                    s.tangential[1],
                    s.tangential[2],
                    s.face as f64,
                    s.xi[0],
                    s.xi[1],
                    if s.active { 1.0 } else { 0.0 },
                    s.rel0[0],
                    s.rel0[1],
                    s.rel0[2],
                    0.0,
                ]);
            }
        }
        out
    }

    /// Restore what [`ContactSystem::state_values`] wrote for the same interfaces; the
    /// error says what does not match.
    pub fn restore_state(&mut self, values: &[f64]) -> Result<(), String> {
        let nodes: usize = self.interfaces.iter().map(|i| i.slaves.len()).sum();
        if values.len() != 1 + PER_NODE * nodes {
            return Err(format!(
                "contact state has {} values, the case's interfaces need {}",
                values.len(),
                1 + PER_NODE * nodes
            ));
        }
        self.friction_work = values[0];
        let mut chunks = values[1..].chunks_exact(PER_NODE);
        for iface in self.interfaces.iter_mut() {
            for s in iface.slaves.iter_mut() {
                let v = chunks.next().ok_or("contact state too short")?;
                s.state = match v[0] as u8 {
                    0 => PairState::Bonded,
                    1 => PairState::Stick,
                    2 => PairState::Sliding,
                    3 => PairState::Separated,
                    other => return Err(format!("unknown contact state code {other}")),
                };
                s.surface = v[1] != 0.0;
                s.partner = v[2] as u32;
                s.gap = v[3];
                s.slip = [v[4], v[5], v[6]];
                s.acc_slip = v[7];
                s.normal_force = v[8];
                s.tangential = [v[9], v[10], v[11]];
                s.face = v[12] as u32;
                s.xi = [v[13], v[14]];
                s.active = v[15] != 0.0;
                s.rel0 = [v[16], v[17], v[18]];
            }
        }
        Ok(())
    }
}
