//! A whole run of a case: the dynamic stage with outputs (VTU + PVD, histories, summary),
//! progress and checkpoints for resuming.

use std::path::{Path, PathBuf};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;

use dcfm::case::{Case, OutputSection};
use dcfm::error::{DcfmError, Result};
use dcfm::stage::checkpoint::{read_checkpoint, write_checkpoint};
use dcfm::stage::{Energies, Simulation};

use crate::output::{
    write_atomic_with, write_summary, write_vtu, HistoryWriter, PvdCollection, VtuField,
};

/// How to run.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Output directory.
    pub out: PathBuf,
    /// Continue from `out/checkpoint.bin` if it exists.
    pub resume: bool,
    /// Draw a progress bar (on stderr, when it is a terminal).
    pub progress: bool,
}

/// Peak of a nodal quantity.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct Peak {
    pub value: f64,
    pub node: usize,
    pub time: f64,
}

/// `summary.json`.
#[derive(Clone, Debug, Serialize)]
pub struct RunSummary {
    pub case: String,
    pub title: String,
    pub nodes: usize,
    pub elements: usize,
    pub threads: usize,
    pub steps: u64,
    pub dt: f64,
    pub critical_dt: f64,
    pub limiting_element: usize,
    pub end_time: f64,
    pub wall_s: f64,
    pub steps_per_s: f64,
    pub element_updates_per_s: f64,
    pub bytes_per_element: f64,
    pub energies: Energies,
    pub energy_residual: f64,
    pub energy_residual_relative: f64,
    pub peak_displacement: Peak,
    pub peak_velocity: Peak,
    pub resumed_from_step: Option<u64>,
}

fn norm(x: &[f64; 3]) -> f64 {
    (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
}

fn history_header(output: &OutputSection, sim: &Simulation) -> Vec<String> {
    let mut h: Vec<String> = [
        "time", "kinetic", "internal", "damping", "contact", "external", "input", "boundary",
        "residual",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    for n in &output.nodes {
        for q in ["u", "v", "a"] {
            for d in ["x", "y", "z"] {
                h.push(format!("node{n}_{q}{d}"));
            }
        }
    }
    for e in &output.elements {
        for c in ["xx", "yy", "zz", "xy", "yz", "zx"] {
            h.push(format!("elem{e}_s{c}"));
        }
    }
    for g in sim.model.groups.iter().filter(|g| g.material.has_damage()) {
        for k in ["tension", "compression", "total"] {
            h.push(format!("damaged_volume_{k}_{}", g.name));
        }
    }
    if let Some(c) = &sim.model.contact {
        for (name, _) in c.state_areas() {
            for k in ["stick", "slide", "separated", "surface"] {
                h.push(format!("area_{k}_{name}"));
            }
        }
        h.push("contact_friction_work".into());
    }
    // Anchor bars (yingxiuwan branch hook): largest axial force and yielded segments.
    if let Some(a) = &sim.model.anchors {
        h.extend(a.history_names());
    }
    h
}

fn history_row(sim: &Simulation, output: &OutputSection, row: &mut Vec<f64>) {
    row.clear();
    let e = &sim.energies;
    row.extend([
        sim.time,
        e.kinetic,
        e.internal,
        e.damping,
        e.contact,
        e.external,
        e.input,
        e.boundary,
        e.residual(),
    ]);
    for &n in &output.nodes {
        let n = n as usize;
        row.extend(sim.u[n]);
        row.extend(sim.v[n]);
        row.extend(sim.a[n]);
    }
    for &el in &output.elements {
        let (_, s) = sim.model.element_strain_stress(el as usize, &sim.u);
        row.extend(s);
    }
    for g in sim.model.groups.iter().filter(|g| g.material.has_damage()) {
        let per_element = output.damaged_volume == dcfm::case::DamagedVolumeMeasure::Element;
        row.extend(g.damaged_volume(output.damage_threshold, per_element));
    }
    if let Some(c) = &sim.model.contact {
        for (_, a) in c.state_areas() {
            row.extend(a);
        }
        row.push(c.friction_work());
    }
    if let Some(a) = &sim.model.anchors {
        a.history_values(row);
    }
}

/// A field frame: the whole mesh, or with `[output.frames]` the compact frame and, when
/// due, the whole mesh into `full.pvd` (yingxiuwan branch hook; `crate::frames`).
fn write_frame(
    sim: &Simulation,
    out: &Path,
    pvd: &mut PvdCollection,
    frames: Option<&mut crate::frames::CompactFrames>,
    first: bool,
    last: bool,
) -> Result<()> {
    match frames {
        None => write_state_vtu(sim, out, pvd),
        Some(f) => {
            f.write(sim, out, pvd)?;
            if f.full_due(sim.step, first, last) {
                write_state_vtu(sim, out, f.full_collection())?;
            }
            Ok(())
        }
    }
}

/// Write one VTU of the current state and add it to the collection.
fn write_state_vtu(sim: &Simulation, out: &Path, pvd: &mut PvdCollection) -> Result<()> {
    let model = &sim.model;
    let ne = model.n_elements();
    let mut stress = vec![0.0; 6 * ne];
    let mut strain = vec![0.0; 6 * ne];
    let mut damage = vec![0.0; 11 * ne];
    let mut region = vec![0.0; ne];
    for g in &model.groups {
        let ss = g.element_strain_stress(&sim.u);
        let dmg = g.element_damage_fields();
        for (le, &e) in g.elements.iter().enumerate() {
            let e = e as usize;
            strain[6 * e..6 * e + 6].copy_from_slice(&ss[le].0);
            stress[6 * e..6 * e + 6].copy_from_slice(&ss[le].1);
            if let Some(d) = &dmg {
                damage[11 * e..11 * e + 11].copy_from_slice(&d[le]);
            }
            region[e] = g.region as f64;
        }
    }
    let pick = |k: usize, n: usize| -> Vec<f64> {
        (0..ne)
            .flat_map(|e| damage[11 * e + k..11 * e + k + n].to_vec())
            .collect()
    };
    let (d, dt, dc, kt, kc, ep) = (
        pick(0, 1),
        pick(1, 1),
        pick(2, 1),
        pick(3, 1),
        pick(4, 1),
        pick(5, 6),
    );
    let flat = |f: &[[f64; 3]]| -> Vec<f64> { f.iter().flatten().copied().collect() };
    let (u, v, a) = (flat(&sim.u), flat(&sim.v), flat(&sim.a));
    let contact_fields = sim
        .model
        .contact
        .as_ref()
        .map(|c| c.node_fields(model.mesh.n_nodes()))
        .unwrap_or_default();
    let mut point_fields = vec![
        VtuField {
            name: "displacement",
            components: 3,
            values: &u,
        },
        VtuField {
            name: "velocity",
            components: 3,
            values: &v,
        },
        VtuField {
            name: "acceleration",
            components: 3,
            values: &a,
        },
    ];
    for (name, components, values) in &contact_fields {
        point_fields.push(VtuField {
            name,
            components: *components,
            values,
        });
    }
    let name = format!("mesh_{:06}.vtu", sim.step);
    write_vtu(
        &out.join(&name),
        &model.mesh.coords,
        &model.mesh.elements,
        &point_fields,
        &[
            VtuField {
                name: "stress",
                components: 6,
                values: &stress,
            },
            VtuField {
                name: "strain",
                components: 6,
                values: &strain,
            },
            VtuField {
                name: "damage",
                components: 1,
                values: &d,
            },
            VtuField {
                name: "damage_tension",
                components: 1,
                values: &dt,
            },
            VtuField {
                name: "damage_compression",
                components: 1,
                values: &dc,
            },
            VtuField {
                name: "kappa_tension",
                components: 1,
                values: &kt,
            },
            VtuField {
                name: "kappa_compression",
                components: 1,
                values: &kc,
            },
            VtuField {
                name: "plastic_strain",
                components: 6,
                values: &ep,
            },
            VtuField {
                name: "region",
                components: 1,
                values: &region,
            },
        ],
    )?;
    pvd.add(sim.time, &name)
}

/// Run a case to its end time, writing outputs under `opts.out`.
pub fn run_case(case: Case, opts: &RunOptions) -> Result<RunSummary> {
    let out = &opts.out;
    std::fs::create_dir_all(out).map_err(|e| DcfmError::io(out.display().to_string(), e))?;
    let label = case.file.display().to_string();
    let title = case.title.clone();
    let end = case.end;
    let dt = case.dt;
    let output = case.output.clone();
    let total_steps = (end / dt).ceil() as u64;
    let checkpoint = out.join("checkpoint.bin");
    let ckpt_label = checkpoint.display().to_string();
    let resume_bytes = if opts.resume && checkpoint.exists() {
        Some(std::fs::read(&checkpoint).map_err(|e| DcfmError::io(&ckpt_label, e))?)
    } else {
        None
    };
    // ---- static stage (owner: static; docs/static_stage.md) ---------------------------
    // Run it (writing static.vtu, static_histories.csv, static_summary.json) or restore it
    // from the checkpoint; the dynamic stage starts from its state. Every checkpoint begins
    // with its block (`static_run::write_static`).
    let staged = crate::static_run::run_static_stage(
        case.model,
        case.static_plan.as_ref(),
        out,
        resume_bytes.as_deref().map(|b| (b, ckpt_label.as_str())),
        &label,
    )?;
    let static_result = staged.result;
    let mut sim = crate::static_run::start(staged.model, static_result.as_ref(), dt, case.safety)?;
    if staged.fresh {
        write_atomic_with(&checkpoint, |w| {
            crate::static_run::write_static(w, static_result.as_ref(), &sim.model)?;
            write_checkpoint(w, &sim)
        })?;
    }
    // ---- end of the static stage hook ---------------------------------------------------
    let header = history_header(&output, &sim);
    let mut resumed_from = None;
    if let Some(bytes) = &resume_bytes {
        read_checkpoint(&bytes[staged.dynamic_offset..], &ckpt_label, &mut sim)?;
        resumed_from = Some(sim.step);
    }
    let mut frames = match &output.frames {
        Some(f) => Some(crate::frames::CompactFrames::new(
            f,
            &sim,
            out,
            resumed_from.map(|_| sim.time),
        )?),
        None => None,
    };
    let pvd_path = out.join("case.pvd");
    let hist_path = out.join("histories.csv");
    let (mut pvd, mut hist) = if resumed_from.is_some() {
        let mut p = PvdCollection::resume(&pvd_path)?;
        p.truncate_after(sim.time)?;
        (
            p,
            HistoryWriter::open_append_after(&hist_path, &header, sim.time)?,
        )
    } else {
        let mut h = HistoryWriter::create(&hist_path, &header)?;
        let mut row = Vec::new();
        history_row(&sim, &output, &mut row);
        h.append(&row)?;
        let mut p = PvdCollection::create(&pvd_path)?;
        write_frame(&sim, out, &mut p, frames.as_mut(), true, false)?;
        (p, h)
    };
    let bar = if opts.progress {
        let b = ProgressBar::with_draw_target(Some(total_steps), ProgressDrawTarget::stderr());
        b.set_style(
            ProgressStyle::with_template("{bar:30} step {pos}/{len} {msg} ETA {eta}")
                .expect("valid template"),
        );
        b.set_position(sim.step);
        b
    } else {
        ProgressBar::hidden()
    };
    let n_elements = sim.model.n_elements();
    let mut peak_u = Peak::default();
    let mut peak_v = Peak::default();
    let mut row = Vec::with_capacity(header.len());
    let start_step = sim.step;
    let t0 = Instant::now();
    while sim.step < total_steps {
        sim.step().inspect_err(|_| {
            let _ = hist.flush();
        })?;
        if sim.step % output.history_every == 0 || sim.step == total_steps {
            history_row(&sim, &output, &mut row);
            hist.append(&row)?;
            for (i, (u, v)) in sim.u.iter().zip(&sim.v).enumerate() {
                let (nu, nv) = (norm(u), norm(v));
                if nu > peak_u.value {
                    peak_u = Peak {
                        value: nu,
                        node: i,
                        time: sim.time,
                    };
                }
                if nv > peak_v.value {
                    peak_v = Peak {
                        value: nv,
                        node: i,
                        time: sim.time,
                    };
                }
            }
        }
        if (output.vtu_every > 0 && sim.step % output.vtu_every == 0) || sim.step == total_steps {
            let last = sim.step == total_steps;
            write_frame(&sim, out, &mut pvd, frames.as_mut(), false, last)?;
        }
        if output.checkpoint_every > 0 && sim.step % output.checkpoint_every == 0 {
            hist.flush()?;
            write_atomic_with(&checkpoint, |w| {
                crate::static_run::write_static(w, static_result.as_ref(), &sim.model)?;
                write_checkpoint(w, &sim)
            })?;
        }
        if sim.step % 64 == 0 {
            let el = t0.elapsed().as_secs_f64().max(1e-9);
            let rate = (sim.step - start_step) as f64 * n_elements as f64 / el;
            bar.set_position(sim.step);
            bar.set_message(format!(
                "t = {:.4e} s, {:.3e} element-updates/s",
                sim.time, rate
            ));
        }
    }
    bar.finish_and_clear();
    hist.finish()?;
    let wall = t0.elapsed().as_secs_f64();
    let steps_run = sim.step - start_step;
    let summary = RunSummary {
        case: label,
        title,
        nodes: sim.u.len(),
        elements: n_elements,
        threads: rayon::current_num_threads(),
        steps: sim.step,
        dt,
        critical_dt: sim.model.critical_step_with_damping(),
        limiting_element: sim.model.stable.element,
        end_time: sim.time,
        wall_s: wall,
        steps_per_s: steps_run as f64 / wall.max(1e-9),
        element_updates_per_s: steps_run as f64 * n_elements as f64 / wall.max(1e-9),
        bytes_per_element: sim.model.bytes_per_element(),
        energies: sim.energies,
        energy_residual: sim.energies.residual(),
        energy_residual_relative: sim.energies.relative_residual(),
        peak_displacement: peak_u,
        peak_velocity: peak_v,
        resumed_from_step: resumed_from,
    };
    write_summary(&out.join("summary.json"), &summary)?;
    Ok(summary)
}
