//! Equation numbering of the static solve: one unknown per free DOF of the active nodes.
//! Constrained DOFs (fixed, prescribed) and dormant nodes are eliminated; the nodes of a
//! bonded contact pair are tied (they share their unknowns, the pair's relative
//! displacement being held at its value at the start of the step).

/// "No equation".
pub const NO_EQ: u32 = u32::MAX;

/// Root of `i` in a union-find forest `p` (with path halving).
pub(super) fn find(p: &mut [u32], mut i: u32) -> u32 {
    while p[i as usize] != i {
        let up = p[p[i as usize] as usize];
        p[i as usize] = up;
        i = up;
    }
    i
}

/// Equation of every node DOF.
#[derive(Clone, Debug)]
pub struct DofMap {
    /// `eq[i][d]`: equation of DOF d of node i, or [`NO_EQ`].
    pub eq: Vec<[u32; 3]>,
    /// Tie group of every node (its representative: the smallest node of the group).
    pub group: Vec<u32>,
    /// Number of equations.
    pub n_eq: usize,
    /// For each equation, the representative node and the DOF.
    pub owner: Vec<(u32, u8)>,
}

impl DofMap {
    /// Number the free DOFs. `constrained[i]` is the bit mask of node i's constrained DOFs,
    /// `dormant[i]` marks nodes of no active element, `ties` are node pairs moving together.
    /// A DOF of a tie group is free only when it is free at every node of the group.
    /// Equations are numbered by representative node, then DOF.
    pub fn new(constrained: &[u8], dormant: &[bool], ties: &[(u32, u32)]) -> Self {
        let n = constrained.len();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        for &(a, b) in ties {
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            if ra != rb {
                let (lo, hi) = (ra.min(rb), ra.max(rb));
                parent[hi as usize] = lo;
            }
        }
        let group: Vec<u32> = (0..n as u32).map(|i| find(&mut parent, i)).collect();
        // Constrained mask and activity of every group (a group is active when one of its
        // nodes is).
        let mut mask = vec![0u8; n];
        let mut active = vec![false; n];
        for i in 0..n {
            let g = group[i] as usize;
            if !dormant[i] {
                mask[g] |= constrained[i];
                active[g] = true;
            }
        }
        let mut eq = vec![[NO_EQ; 3]; n];
        let mut owner = Vec::new();
        for g in 0..n {
            if group[g] as usize != g || !active[g] {
                continue;
            }
            for d in 0..3 {
                if mask[g] & (1 << d) == 0 {
                    eq[g][d] = owner.len() as u32;
                    owner.push((g as u32, d as u8));
                }
            }
        }
        for i in 0..n {
            if !dormant[i] {
                eq[i] = eq[group[i] as usize];
            }
        }
        Self {
            n_eq: owner.len(),
            eq,
            group,
            owner,
        }
    }

    /// Sum the node values `f` into one value per equation.
    pub fn gather(&self, f: &[[f64; 3]], out: &mut [f64]) {
        out.fill(0.0);
        for (i, fi) in f.iter().enumerate() {
            for d in 0..3 {
                let e = self.eq[i][d];
                if e != NO_EQ {
                    out[e as usize] += fi[d];
                }
            }
        }
    }

    /// Add the equation values `x` to the node values `u` (every node of a tie group
    /// receives its group's value).
    pub fn scatter_add(&self, x: &[f64], u: &mut [[f64; 3]]) {
        for (i, ui) in u.iter_mut().enumerate() {
            for d in 0..3 {
                let e = self.eq[i][d];
                if e != NO_EQ {
                    ui[d] += x[e as usize];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constrained_dormant_and_tied_dofs() {
        // Node 0 fixed in z, node 1 dormant, nodes 2 and 3 tied with 3 fixed in x.
        let constrained = [0b100, 0, 0, 0b001];
        let dormant = [false, true, false, false];
        let m = DofMap::new(&constrained, &dormant, &[(3, 2)]);
        assert_eq!(m.n_eq, 2 + 2);
        assert_eq!(m.eq[0], [0, 1, NO_EQ]);
        assert_eq!(m.eq[1], [NO_EQ; 3]);
        assert_eq!(m.eq[2], [NO_EQ, 2, 3]);
        assert_eq!(m.eq[3], m.eq[2]);
        let mut g = vec![0.0; 4];
        m.gather(
            &[[1.0; 3], [5.0; 3], [1.0, 2.0, 3.0], [1.0, 2.0, 3.0]],
            &mut g,
        );
        assert_eq!(g, vec![1.0, 1.0, 4.0, 6.0]);
        let mut u = vec![[0.0; 3]; 4];
        m.scatter_add(&[1.0, 2.0, 3.0, 4.0], &mut u);
        assert_eq!(u[3], [0.0, 3.0, 4.0]);
        assert_eq!(u[1], [0.0; 3]);
    }
}
