//! The static stage in a checkpoint, so that a resumed run does not recompute it: a block
//! (magic `DCFMSTA1`, little-endian) written before the dynamic block of
//! `stage/checkpoint.rs`, holding the post-static configuration (active elements, the
//! groups' initial strains and references) and the [`StaticResult`]. Reading it rebuilds
//! the configuration of a model freshly built from the same case; the dynamic block that
//! follows restores the displacements, velocities, point states and contact states.

use std::io::Write;

use super::activation::Activation;
use super::forces::OutOfBalance;
use super::history::HistoryRow;
use super::linear_solver::LinearSolverChoice;
use super::plan::{StaticPlan, StepSolver};
use super::result::{StaticResult, StepReport};
use crate::error::{DcfmError, Result};
use crate::model::Model;

const MAGIC: &[u8; 8] = b"DCFMSTA1";

fn put_u64(w: &mut impl Write, x: u64) -> std::io::Result<()> {
    w.write_all(&x.to_le_bytes())
}

fn put_f64s(w: &mut impl Write, xs: &[f64]) -> std::io::Result<()> {
    for x in xs {
        w.write_all(&x.to_le_bytes())?;
    }
    Ok(())
}

fn oob_values(o: &OutOfBalance) -> [f64; 6] {
    [
        o.ratio,
        o.norm,
        o.reference,
        o.max,
        o.node as f64,
        o.dof as f64,
    ]
}

fn oob_from(v: &[f64]) -> OutOfBalance {
    OutOfBalance {
        ratio: v[0],
        norm: v[1],
        reference: v[2],
        max: v[3],
        node: v[4] as usize,
        dof: v[5] as usize,
    }
}

fn put_node_vectors(w: &mut impl Write, list: &[(u32, [f64; 3])]) -> std::io::Result<()> {
    put_u64(w, list.len() as u64)?;
    for (n, v) in list {
        put_f64s(w, &[*n as f64, v[0], v[1], v[2]])?;
    }
    Ok(())
}

/// Write the static block of `result` for the post-static `model`.
pub fn write_static_block(
    w: &mut impl Write,
    result: &StaticResult,
    model: &Model,
) -> std::io::Result<()> {
    w.write_all(MAGIC)?;
    put_u64(w, result.active.len() as u64)?;
    w.write_all(
        &result
            .active
            .iter()
            .map(|&a| u8::from(a))
            .collect::<Vec<u8>>(),
    )?;
    put_u64(w, model.groups.len() as u64)?;
    for g in &model.groups {
        let e0: Vec<f64> = g
            .initial_strain
            .as_ref()
            .map(|v| v.iter().flatten().copied().collect())
            .unwrap_or_default();
        put_u64(w, e0.len() as u64)?;
        put_f64s(w, &e0)?;
        let r: Vec<f64> = g
            .reference
            .as_ref()
            .map(|v| v.iter().flatten().flatten().copied().collect())
            .unwrap_or_default();
        put_u64(w, r.len() as u64)?;
        put_f64s(w, &r)?;
    }
    put_u64(w, result.u.len() as u64)?;
    for field in [&result.u, &result.u_in_situ] {
        for x in field.iter() {
            put_f64s(w, x)?;
        }
    }
    put_node_vectors(w, &result.reactions)?;
    put_node_vectors(w, &result.static_loads)?;
    put_f64s(w, &oob_values(&result.out_of_balance))?;
    put_f64s(w, &result.damaged_volume)?;
    match &result.initial_field_out_of_balance {
        Some(o) => {
            put_u64(w, 1)?;
            put_f64s(w, &oob_values(o))?;
        }
        None => put_u64(w, 0)?,
    }
    put_u64(w, result.steps.len() as u64)?;
    for s in &result.steps {
        put_u64(w, s.name.len() as u64)?;
        w.write_all(s.name.as_bytes())?;
        put_u64(w, u64::from(s.solver == StepSolver::Relaxation))?;
        put_u64(w, s.iterations as u64)?;
        put_f64s(w, &oob_values(&s.initial))?;
        put_f64s(w, &oob_values(&s.out_of_balance))?;
        put_u64(w, s.active_elements as u64)?;
        put_f64s(w, &s.damaged_volume)?;
        put_u64(w, s.equations as u64)?;
        put_u64(w, s.stiffness_nonzeros as u64)?;
        put_u64(w, s.factor_nonzeros as u64)?;
        // 0 / 1: Cholesky simplicial / supernodal (or a relaxation step), 2: conjugate
        // gradients (its iterations in `iterations`).
        let code = if s.linear_solver == Some(LinearSolverChoice::ConjugateGradients) {
            2
        } else {
            u64::from(s.supernodal)
        };
        put_u64(w, code)?;
        put_f64s(w, &s.seconds)?;
    }
    put_u64(w, result.history.len() as u64)?;
    for h in &result.history {
        put_f64s(w, &h.values())?;
    }
    Ok(())
}

struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
    file: &'a str,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8]> {
        if self.pos + n > self.bytes.len() {
            return Err(DcfmError::Parse {
                file: self.file.to_string(),
                message: format!(
                    "static block of the checkpoint truncated at byte {}",
                    self.pos
                ),
            });
        }
        let s = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }
    fn u64(&mut self) -> Result<u64> {
        Ok(u64::from_le_bytes(
            self.take(8)?.try_into().expect("8 bytes"),
        ))
    }
    fn f64(&mut self) -> Result<f64> {
        Ok(f64::from_le_bytes(
            self.take(8)?.try_into().expect("8 bytes"),
        ))
    }
    fn f64s(&mut self, n: usize) -> Result<Vec<f64>> {
        (0..n).map(|_| self.f64()).collect()
    }
    fn node_vectors(&mut self) -> Result<Vec<(u32, [f64; 3])>> {
        let n = self.u64()? as usize;
        (0..n)
            .map(|_| {
                let v = self.f64s(4)?;
                Ok((v[0] as u32, [v[1], v[2], v[3]]))
            })
            .collect()
    }
}

/// Read the static block at the start of `bytes`, if there is one: rebuild the
/// post-static configuration of `model` (freshly built from the case whose static stage is
/// `plan`) and return the result and the offset of the dynamic block. Without a static
/// block: `(None, 0)` and the model unchanged.
pub fn read_static_block(
    bytes: &[u8],
    file: &str,
    model: &mut Model,
    plan: &StaticPlan,
) -> Result<(Option<StaticResult>, usize)> {
    if bytes.len() < 8 || &bytes[..8] != MAGIC {
        return Ok((None, 0));
    }
    let mismatch = |what: &str, found: usize, expected: usize| {
        DcfmError::Parse {
        file: file.to_string(),
        message: format!(
            "checkpoint's static stage has {found} {what}, the case has {expected}: it belongs to another case"
        ),
    }
    };
    let mut r = Reader {
        bytes,
        pos: 8,
        file,
    };
    let ne = r.u64()? as usize;
    if ne != model.n_elements() {
        return Err(mismatch("elements", ne, model.n_elements()));
    }
    let active: Vec<bool> = r.take(ne)?.iter().map(|&b| b != 0).collect();
    let ng = r.u64()? as usize;
    if ng != model.groups.len() {
        return Err(mismatch("element groups", ng, model.groups.len()));
    }
    let mut per_group = Vec::with_capacity(ng);
    for _ in 0..ng {
        let n0 = r.u64()? as usize;
        let e0 = r.f64s(n0)?;
        let nr = r.u64()? as usize;
        let refs = r.f64s(nr)?;
        per_group.push((e0, refs));
    }
    let nn = r.u64()? as usize;
    if nn != model.mesh.n_nodes() {
        return Err(mismatch("nodes", nn, model.mesh.n_nodes()));
    }
    let mut fields = [Vec::with_capacity(nn), Vec::with_capacity(nn)];
    for f in fields.iter_mut() {
        for _ in 0..nn {
            let v = r.f64s(3)?;
            f.push([v[0], v[1], v[2]]);
        }
    }
    let [u, u_in_situ] = fields;
    let reactions = r.node_vectors()?;
    let static_loads = r.node_vectors()?;
    let out_of_balance = oob_from(&r.f64s(6)?);
    let dv = r.f64s(3)?;
    let initial_field_out_of_balance = match r.u64()? {
        0 => None,
        _ => Some(oob_from(&r.f64s(6)?)),
    };
    let ns = r.u64()? as usize;
    let mut steps = Vec::with_capacity(ns);
    for _ in 0..ns {
        let len = r.u64()? as usize;
        let name = String::from_utf8_lossy(r.take(len)?).to_string();
        let solver = if r.u64()? == 1 {
            StepSolver::Relaxation
        } else {
            StepSolver::Direct
        };
        let iterations = r.u64()? as usize;
        let initial = oob_from(&r.f64s(6)?);
        let final_oob = oob_from(&r.f64s(6)?);
        let active_elements = r.u64()? as usize;
        let d = r.f64s(3)?;
        let equations = r.u64()? as usize;
        let stiffness_nonzeros = r.u64()? as usize;
        let factor_nonzeros = r.u64()? as usize;
        let code = r.u64()?;
        let supernodal = code == 1;
        let linear_solver = match (solver, code) {
            (StepSolver::Relaxation, _) => None,
            (_, 2) => Some(LinearSolverChoice::ConjugateGradients),
            _ => Some(LinearSolverChoice::Cholesky),
        };
        let t = r.f64s(3)?;
        steps.push(StepReport {
            name,
            solver,
            iterations,
            initial,
            out_of_balance: final_oob,
            active_elements,
            damaged_volume: [d[0], d[1], d[2]],
            equations,
            stiffness_nonzeros,
            factor_nonzeros,
            supernodal,
            linear_solver,
            seconds: [t[0], t[1], t[2]],
        });
    }
    let nh = r.u64()? as usize;
    let mut history = Vec::with_capacity(nh);
    for _ in 0..nh {
        let v = r.f64s(8)?;
        history.push(HistoryRow {
            step: v[0] as usize,
            substep: v[1] as usize,
            iteration: v[2] as usize,
            ratio: v[3],
            max_force: v[4],
            node: v[5] as usize,
            dof: v[6] as usize,
            kinetic: v[7],
        });
    }
    // Rebuild the configuration.
    let dynamic = model.constraints.clone();
    let mut act = Activation::new(model);
    act.active.clone_from(&active);
    act.apply(model, &plan.constraints, &u, &[]);
    for (g, (e0, refs)) in model.groups.iter_mut().zip(per_group) {
        let np = g.integration.points();
        if !e0.is_empty() {
            if e0.len() != 6 * np * g.len() {
                return Err(mismatch(
                    "initial-strain values in a group",
                    e0.len(),
                    6 * np * g.len(),
                ));
            }
            g.initial_strain = Some(
                e0.chunks_exact(6)
                    .map(|c| std::array::from_fn(|i| c[i]))
                    .collect(),
            );
        }
        if !refs.is_empty() {
            if refs.len() != 24 * g.len() {
                return Err(mismatch(
                    "reference values in a group",
                    refs.len(),
                    24 * g.len(),
                ));
            }
            g.reference = Some(
                refs.chunks_exact(24)
                    .map(|c| std::array::from_fn(|a| std::array::from_fn(|d| c[3 * a + d])))
                    .collect(),
            );
        }
    }
    act.constrain(model, &dynamic);
    let result = StaticResult {
        u,
        u_in_situ,
        reactions,
        static_loads,
        initial_field_out_of_balance,
        steps,
        out_of_balance,
        damaged_volume: [dv[0], dv[1], dv[2]],
        history,
        active,
    };
    Ok((Some(result), r.pos))
}
