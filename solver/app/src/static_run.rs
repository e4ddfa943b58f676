//! The static stage inside a run (`docs/static_stage.md`): run it before the dynamic stage,
//! or restore it from the checkpoint of an earlier run of the same case, and write its
//! outputs — `static.vtu` (the active elements at the end of the stage), the convergence
//! history `static_histories.csv` and `static_summary.json`. The run driver (`run.rs`)
//! calls [`run_static_stage`], starts the dynamic stage with [`start`] and prefixes every
//! checkpoint with [`write_static`].

use std::path::Path;

use serde::Serialize;

use dcfm::error::{DcfmError, Result};
use dcfm::model::Model;
use dcfm::stage::checkpoint::{read_static_block, write_static_block};
use dcfm::stage::static_stage::{
    self, HistoryRow, OutOfBalance, StaticPlan, StaticResult, StepReport,
};
use dcfm::stage::Simulation;

use crate::output::{write_summary, write_vtu, HistoryWriter, VtuField, VtuStrings};

/// The model after the static stage.
pub struct Staged {
    pub model: Model,
    /// The static state (None: the case has no static stage).
    pub result: Option<StaticResult>,
    /// Where the dynamic block of the resumed checkpoint starts (0 without static block).
    pub dynamic_offset: usize,
    /// The stage ran now (false: restored from the checkpoint, or no stage).
    pub fresh: bool,
}

/// `static_summary.json`.
#[derive(Serialize)]
struct StaticSummary<'a> {
    steps: &'a [StepReport],
    initial_field_out_of_balance: Option<OutOfBalance>,
    out_of_balance: OutOfBalance,
    /// Damaged volume of eq. (27) at the end of the stage (m³): tension, compression, either.
    damaged_volume: [f64; 3],
    /// Σ of the reactions of the static supports (N).
    reaction_total: [f64; 3],
    active_elements: usize,
    wall_s: f64,
}

/// Run the static stage of `plan` on `model` (or restore it from `checkpoint` = (bytes,
/// label) when resuming) and write its outputs under `out`; `case` names the case file in
/// the errors of a step.
pub fn run_static_stage(
    mut model: Model,
    plan: Option<&StaticPlan>,
    out: &Path,
    checkpoint: Option<(&[u8], &str)>,
    case: &str,
) -> Result<Staged> {
    let Some(plan) = plan else {
        return Ok(Staged {
            model,
            result: None,
            dynamic_offset: 0,
            fresh: false,
        });
    };
    if let Some((bytes, label)) = checkpoint {
        let (result, offset) = read_static_block(bytes, label, &mut model, plan)?;
        let Some(result) = result else {
            return Err(DcfmError::Parse {
                file: label.to_string(),
                message: "the checkpoint has no static stage but the case has one \
                          (it was written by another case or an older version): run without --resume"
                    .into(),
            });
        };
        return Ok(Staged {
            model,
            result: Some(result),
            dynamic_offset: offset,
            fresh: false,
        });
    }
    let t0 = std::time::Instant::now();
    let (model, result) = static_stage::run(model, plan).map_err(|e| match e {
        DcfmError::Static { step, message } => DcfmError::Static {
            step: format!("{case}: {step}"),
            message,
        },
        other => other,
    })?;
    let wall_s = t0.elapsed().as_secs_f64();
    write_outputs(&model, &result, out, wall_s)?;
    Ok(Staged {
        model,
        result: Some(result),
        dynamic_offset: 0,
        fresh: true,
    })
}

/// The dynamic stage's simulation: from the static state if there is one.
pub fn start(
    model: Model,
    result: Option<&StaticResult>,
    dt: f64,
    safety: f64,
) -> Result<Simulation> {
    match result {
        Some(r) => static_stage::start_dynamic(model, r, dt, safety),
        None => Simulation::new(model, dt, safety),
    }
}

/// The static block that starts every checkpoint of a case with a static stage.
pub fn write_static(
    w: &mut impl std::io::Write,
    result: Option<&StaticResult>,
    model: &Model,
) -> std::io::Result<()> {
    match result {
        Some(r) => write_static_block(w, r, model),
        None => Ok(()),
    }
}

fn write_outputs(model: &Model, result: &StaticResult, out: &Path, wall_s: f64) -> Result<()> {
    let header: Vec<String> = HistoryRow::HEADER.iter().map(|s| s.to_string()).collect();
    let mut h = HistoryWriter::create(&out.join("static_histories.csv"), &header)?;
    for row in &result.history {
        h.append(&row.values())?;
    }
    h.finish()?;
    let mut total = [0.0; 3];
    for (_, r) in &result.reactions {
        for d in 0..3 {
            total[d] += r[d];
        }
    }
    write_summary(
        &out.join("static_summary.json"),
        &StaticSummary {
            steps: &result.steps,
            initial_field_out_of_balance: result.initial_field_out_of_balance,
            out_of_balance: result.out_of_balance,
            damaged_volume: result.damaged_volume,
            reaction_total: total,
            active_elements: result.active.iter().filter(|&&a| a).count(),
            wall_s,
        },
    )?;
    write_static_vtu(model, result, &out.join("static.vtu"))
}

/// `static.vtu`: the active elements (dormant nodes are in no cell), with the
/// displacements, the displacements since the in-situ step, the reactions, and per cell
/// the stress, strain, damage D, region (`[[regions]]` order, names in the field data
/// `region_names`) and global element id.
fn write_static_vtu(model: &Model, result: &StaticResult, path: &Path) -> Result<()> {
    let mut cells = Vec::new();
    let mut ids = Vec::new();
    let mut stress = Vec::new();
    let mut strain = Vec::new();
    let mut damage = Vec::new();
    let mut region = Vec::new();
    for (gi, g) in model.groups.iter().enumerate() {
        let number = model.region_number(gi) as f64;
        let ss = g.element_strain_stress(&result.u);
        let dmg = g.element_damage_fields();
        for (le, &e) in g.elements.iter().enumerate() {
            cells.push(model.mesh.elements[e as usize]);
            ids.push(e as f64);
            strain.extend_from_slice(&ss[le].0);
            stress.extend_from_slice(&ss[le].1);
            damage.push(dmg.as_ref().map_or(0.0, |d| d[le][0]));
            region.push(number);
        }
    }
    let flat = |f: &[[f64; 3]]| -> Vec<f64> { f.iter().flatten().copied().collect() };
    let u = flat(&result.u);
    let du = flat(&result.displacement_since_in_situ());
    let mut reaction = vec![0.0; 3 * model.mesh.n_nodes()];
    for (n, r) in &result.reactions {
        reaction[3 * *n as usize..3 * *n as usize + 3].copy_from_slice(r);
    }
    write_vtu(
        path,
        &model.mesh.coords,
        &cells,
        &[
            VtuField::new("displacement", 3, &u),
            VtuField::new("displacement_since_in_situ", 3, &du),
            VtuField::new("reaction", 3, &reaction),
        ],
        &[
            VtuField::new("stress", 6, &stress),
            VtuField::new("strain", 6, &strain),
            VtuField::new("damage", 1, &damage),
            VtuField::new("region", 1, &region),
            VtuField::new("element", 1, &ids),
        ],
        &[VtuStrings {
            name: "region_names",
            values: &model.region_names,
        }],
    )
}
