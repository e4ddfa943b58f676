//! Bonded = monolithic: a bonded split interface reproduces the merged-node mesh to
//! round-off while a P pulse crosses it, is reflected at the free top (tension) and
//! crosses it again.
//!
//! Goal: the pair correction U += Δt² w R with R = (ū_b − ū_a)/((w_a + w_b) Δt²)
//! (eqs. (6)–(9)) gives both nodes of a pair the momentum-weighted mean of their predictors,
//! which is what a merged node of mass M_a + M_b gets: splitting a mesh and bonding it back
//! must change nothing.
//!
//! ```text
//!   ┌─┐ z = 200 m  free top: the compression pulse comes back as tension
//!   │ │ upper block
//!   ├─┤ z = 100 m  split "lower-upper" / "upper-lower", c = 1e12 Pa (never fails)
//!   │ │ lower block, one 1 m element wide, lateral DOFs fixed (P wave)
//!   └─┘ z = 0: prescribed velocity v0 sin(πt/T), v0 = 0.1 m/s, T = 0.02 s
//! ```
//!
//! Parameters: W1 rock (E 20 GPa, ν 0.25, ρ 2700), h = 1 m, Δt = 0.9 h/c_p, run to
//! t = 2H/c_p (the pulse crosses the interface twice, compression then tension).
//! Reference: the same model with the two blocks merged (no split, no contact).
//! Measured: max over steps and nodes of |u_split − u_merged| (nodes matched by coordinates;
//! both nodes of a pair compared) relative to the largest |u|; the states stay bonded.
//! Tolerance: 1e-12 relative (round-off: the two updates differ only by floating-point
//! association).

use dcfm::boundary::{MotionKind, Prescribed};
use dcfm::contact::{ContactSystem, InterfaceSpec};
use dcfm::load::TimeFunction;
use dcfm::material::Elastic;
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::Model;
use dcfm::stage::Simulation;
use dcfm::{DcfmError, Result};

use crate::models::contact_blocks::{block, elastic};
use crate::record::{CaseOutput, Check};

/// The case title (the `case` of its rows).
pub const TITLE: &str = "bonded = monolithic";

const SOURCE: &str = "merged-node mesh (same model without split)";
const H: f64 = 200.0;

fn build(split: bool) -> Result<Simulation> {
    let n = (H / 2.0) as usize;
    let mesh = BoxMeshSpec {
        blocks: vec![
            block("lower", [0.0; 3], [1.0, 1.0, H / 2.0], [1, 1, n]),
            block("upper", [0.0, 0.0, H / 2.0], [1.0, 1.0, H / 2.0], [1, 1, n]),
        ],
        split: if split {
            vec![["lower".into(), "upper".into()]]
        } else {
            vec![]
        },
        merge_tolerance: 1e-6,
    }
    .build("bonded")?;
    let regions = [
        elastic("lower", 20e9, 0.25, 2700.0)?,
        elastic("upper", 20e9, 0.25, 2700.0)?,
    ];
    let mut model = Model::new(mesh, &regions, "bonded")?;
    let all: Vec<u32> = (0..model.mesh.n_nodes() as u32).collect();
    model.constraints.fix(&all, 0b011);
    let base = model.mesh.node_sets["lower.zmin"].clone();
    model
        .constraints
        .prescribe(Prescribed {
            nodes: base,
            dof: 2,
            kind: MotionKind::Velocity,
            history: TimeFunction::HalfSine {
                amplitude: 0.1,
                period: 0.02,
                start: 0.0,
            },
        })
        .map_err(|n| DcfmError::Mesh(format!("node {n} constrained twice")))?;
    if split {
        let spec = InterfaceSpec::new("bond", "lower-upper", "upper-lower", 0.6, 0.5, 1e12);
        model.contact = Some(ContactSystem::new(&model.mesh, &[spec], "bonded")?);
    }
    // The column moves along z only (x, y fixed): its stable limit is the 1D h/c_p, above
    // the model's 3D element bound, so the step is set from the 1D Courant number 0.9.
    let c = Elastic::new("rock", 20e9, 0.25, 2700.0)?.p_wave_speed();
    let dt = 0.9 * 1.0 / c;
    Ok(Simulation::new_unchecked(model, dt))
}

/// (max |u_split − u_merged| / max |u|, number of pairs not bonded at the end, steps).
pub fn measure() -> Result<(f64, usize, u64)> {
    let mut merged = build(false)?;
    let mut split = build(true)?;
    // Node of the merged mesh at the coordinates of each split-mesh node.
    let key = |x: [f64; 3]| x.map(|c| (c * 1e6).round() as i64);
    let index: std::collections::HashMap<[i64; 3], usize> = merged
        .model
        .mesh
        .coords
        .iter()
        .enumerate()
        .map(|(i, &x)| (key(x), i))
        .collect();
    let map: Vec<usize> = split
        .model
        .mesh
        .coords
        .iter()
        .map(|&x| index[&key(x)])
        .collect();
    let c = Elastic::new("rock", 20e9, 0.25, 2700.0)?.p_wave_speed();
    let (mut max_diff, mut max_u) = (0.0f64, 0.0f64);
    while merged.time < 2.0 * H / c {
        merged.step()?;
        split.step()?;
        for (i, &j) in map.iter().enumerate() {
            let (a, b) = (split.u[i][2], merged.u[j][2]);
            max_diff = max_diff.max((a - b).abs());
            max_u = max_u.max(b.abs());
        }
    }
    let counts = split
        .model
        .contact
        .as_ref()
        .expect("contact")
        .state_counts(0)
        .0;
    Ok((
        max_diff / max_u,
        counts[1] + counts[2] + counts[3],
        merged.step,
    ))
}

/// Run the comparison.
pub fn run() -> Result<CaseOutput> {
    let (diff, not_bonded, _) = measure()?;
    let mut ch = Check::new(TITLE);
    ch.absolute(
        "max |u_split − u_merged| / max |u| over the run",
        0.0,
        diff,
        1e-12,
        SOURCE,
    )
    .absolute(
        "pairs not bonded at the end",
        0.0,
        not_bonded as f64,
        0.0,
        SOURCE,
    );
    Ok(ch.finish().into())
}
