//! W9 — one contact pair, one step, exact to round-off, through `ContactSystem::compute`.
//!
//! Goal: the pair law of eqs. (5)–(15) (trial stick force, bond, tension, sliding,
//! separation) gives the table of docs/verification_references.md §W9 exactly.
//!
//! ```text
//!   ┌────────┐ top (surface b side): nodes of mass 3
//!   ├────────┤ split interface, 4 pairs, control area 1 m² each, normal +z
//!   └────────┘ base (surface a side): nodes of mass 1, loaded
//! ```
//!
//! Two 2 × 2 × 1 m single-element blocks, split; the inverse masses passed to `compute`
//! are set by hand (1 on surface a, 1/3 on surface b), so each pair is W9's isolated pair.
//! One step from rest with load f on every node of a: predictor V̄ = Δt w f, Ū = Δt² w f.
//! Parameters: Δt = 1 ms, c = 5 Pa on 1 m² (cA = 5 N), μs = 0.5, μd = 0.4.
//! Reference: docs/verification_references.md §W9, eqs. (6)–(7): R = m_i m_j/((m_i + m_j) Δt²)(ũ_j − ũ_i).
//! Signs (docs/contact.md §2): compression on a is −z (towards b), R on a.
//! Tolerance 1e-10 relative (round-off; absolute 1e-10 N for zero references).

use dcfm::contact::{geom, ContactStepInput, ContactSystem, InterfaceSpec};
use dcfm::mesh::{BoxMeshSpec, Mesh};
use dcfm::Result;

use crate::models::contact_blocks::block;
use crate::record::{CaseOutput, Check};

/// The case title (the `case` of its rows).
pub const TITLE: &str = "W9 one pair one step";

const SOURCE: &str = "docs/verification_references.md §W9, eqs. (6)–(15)";
const DT: f64 = 1e-3;
const TOL: f64 = 1e-10;

/// (R on a, R on b) of the first pair, state counts, largest difference between pairs.
type StepOutcome = ([f64; 3], [f64; 3], [usize; 4], f64);

struct Rig {
    mesh: Mesh,
    sys: ContactSystem,
    w: Vec<f64>,
    r: Vec<[f64; 3]>,
}

impl Rig {
    fn new() -> Result<Rig> {
        let mesh = BoxMeshSpec {
            blocks: vec![
                block("base", [0.0; 3], [2.0, 2.0, 1.0], [1, 1, 1]),
                block("top", [0.0, 0.0, 1.0], [2.0, 2.0, 1.0], [1, 1, 1]),
            ],
            split: vec![["base".into(), "top".into()]],
            merge_tolerance: 1e-6,
        }
        .build("w09")?;
        let spec = InterfaceSpec::new("w9", "base-top", "top-base", 0.5, 0.4, 5.0);
        let sys = ContactSystem::new(&mesh, &[spec], "w09")?;
        let mut w = vec![1.0; mesh.n_nodes()];
        for (a, b, _, _) in sys.pairs(0) {
            w[a as usize] = 1.0;
            w[b as usize] = 1.0 / 3.0;
        }
        let r = vec![[0.0; 3]; mesh.n_nodes()];
        Ok(Rig { mesh, sys, w, r })
    }

    /// One step from rest with load `f` on every node of a: (R on a, R on b) of the first
    /// pair, the state counts, and the largest difference between pairs.
    fn step(&mut self, f: [f64; 3]) -> Result<StepOutcome> {
        let n = self.mesh.n_nodes();
        for &k in self.sys.touched_nodes() {
            self.r[k as usize] = [0.0; 3];
        }
        let zero = vec![[0.0; 3]; n];
        let mut u_pred = zero.clone();
        let mut v_pred = zero.clone();
        let pairs = self.sys.pairs(0);
        for &(a, _, _, _) in &pairs {
            let wa = self.w[a as usize];
            v_pred[a as usize] = geom::scale(DT * wa, f);
            u_pred[a as usize] = geom::scale(DT * DT * wa, f);
        }
        let inp = ContactStepInput {
            step: 1,
            time: 0.0,
            dt: DT,
            inv_mass: &self.w,
            coords: &self.mesh.coords,
            u_old: &zero,
            u_pred: &u_pred,
            v_pred: &v_pred,
        };
        self.sys.compute(&inp, &mut self.r)?;
        let ra = self.r[pairs[0].0 as usize];
        let rb = self.r[pairs[0].1 as usize];
        let spread = pairs
            .iter()
            .map(|&(a, _, _, _)| geom::norm(geom::sub(self.r[a as usize], ra)))
            .fold(0.0, f64::max);
        Ok((ra, rb, self.sys.state_counts(0).0, spread))
    }
}

fn state_name(c: [usize; 4]) -> f64 {
    // All four pairs in one state: its code (0 bonded, 1 stick, 2 sliding, 3 separated).
    c.iter().position(|&k| k == 4).map_or(-1.0, |s| s as f64)
}

/// Run W9 (every line of the table).
pub fn run() -> Result<CaseOutput> {
    let mut ch = Check::new(TITLE);
    let mut rig = Rig::new()?;
    let (ra, rb, c, s) = rig.step([0.0, 0.0, 20.0])?;
    ch.relative("20 N compressive: R_n on a (N)", -15.0, ra[2], TOL, SOURCE)
        .relative("20 N compressive: R_n on b (N)", 15.0, rb[2], TOL, SOURCE)
        .relative(
            "20 N compressive: acceleration of a (m/s²)",
            5.0,
            20.0 + ra[2],
            TOL,
            SOURCE,
        )
        .relative(
            "20 N compressive: acceleration of b (m/s²)",
            5.0,
            rb[2] / 3.0,
            TOL,
            SOURCE,
        )
        .absolute(
            "20 N compressive: state (0 bonded)",
            0.0,
            state_name(c),
            0.0,
            SOURCE,
        )
        .absolute("pairs agree (N)", 0.0, s, TOL, SOURCE);

    let mut rig = Rig::new()?;
    let (ra, _, c, _) = rig.step([0.0, 0.0, -10.0])?;
    ch.absolute(
        "10 N apart, bonded: |R| (N)",
        0.0,
        geom::norm(ra),
        TOL,
        SOURCE,
    )
    .absolute(
        "10 N apart, bonded: state (3 separated)",
        3.0,
        state_name(c),
        0.0,
        SOURCE,
    );
    let (ra, _, c, _) = rig.step([0.0, 0.0, -4.0])?;
    ch.absolute(
        "4 N apart, unbonded: |R| (N)",
        0.0,
        geom::norm(ra),
        TOL,
        SOURCE,
    )
    .absolute(
        "4 N apart, unbonded: state (3 separated)",
        3.0,
        state_name(c),
        0.0,
        SOURCE,
    );
    let (ra, rb, c, _) = rig.step([0.0, 16.0, 20.0])?;
    ch.relative(
        "20 + 16 N, unbonded: R_t on a (N)",
        -6.0,
        ra[1],
        TOL,
        SOURCE,
    )
    .relative(
        "20 + 16 N, unbonded: R_n on a (N)",
        -15.0,
        ra[2],
        TOL,
        SOURCE,
    )
    .relative(
        "20 + 16 N, unbonded: tangential acceleration of a (m/s²)",
        10.0,
        16.0 + ra[1],
        TOL,
        SOURCE,
    )
    .relative(
        "20 + 16 N, unbonded: tangential acceleration of b (m/s²)",
        2.0,
        rb[1] / 3.0,
        TOL,
        SOURCE,
    )
    .absolute(
        "20 + 16 N, unbonded: state (2 sliding)",
        2.0,
        state_name(c),
        0.0,
        SOURCE,
    );
    let (ra, _, c, _) = rig.step([0.0, 8.0, 20.0])?;
    ch.relative("20 + 8 N, unbonded: R_t on a (N)", -6.0, ra[1], TOL, SOURCE)
        .absolute(
            "20 + 8 N, unbonded: state (1 stick)",
            1.0,
            state_name(c),
            0.0,
            SOURCE,
        );

    let mut rig = Rig::new()?;
    let (ra, _, c, _) = rig.step([0.0, 0.0, -4.0])?;
    ch.relative("4 N apart, bonded: R_n on a (N)", 3.0, ra[2], TOL, SOURCE)
        .absolute(
            "4 N apart, bonded: state (0 bonded)",
            0.0,
            state_name(c),
            0.0,
            SOURCE,
        );
    let (ra, _, _, _) = rig.step([0.0, 8.0, 20.0])?;
    ch.relative("20 + 8 N, bonded: R_t on a (N)", -6.0, ra[1], TOL, SOURCE);
    let (ra, _, c, _) = rig.step([0.0, 16.0, 20.0])?;
    ch.relative(
        "20 + 16 N, bonded: R_t on a (12 N < 7.5 + 5 N)",
        -12.0,
        ra[1],
        TOL,
        SOURCE,
    )
    .absolute(
        "20 + 16 N, bonded: state (0 bonded)",
        0.0,
        state_name(c),
        0.0,
        SOURCE,
    );
    let (ra, _, c, _) = rig.step([0.0, 18.0, 20.0])?;
    ch.relative(
        "20 + 18 N, bonded: R_t on a = μd·15 N (N)",
        -6.0,
        ra[1],
        TOL,
        SOURCE,
    )
    .absolute(
        "20 + 18 N, bonded: state (2 sliding)",
        2.0,
        state_name(c),
        0.0,
        SOURCE,
    );
    Ok(ch.finish().into())
}
