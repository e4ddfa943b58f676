//! A whole run of a case: the dynamic stage with outputs (VTU + PVD, histories, summary),
//! progress and checkpoints for resuming.

use std::path::{Path, PathBuf};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget};
use serde::Serialize;

use dcfm::case::fingerprint::CaseFingerprint;
use dcfm::case::probes::Probes;
use dcfm::case::{Case, CaseWarning, OutputSection, WholeMeshEncoding};
use dcfm::error::{DcfmError, Result};
use dcfm::stage::checkpoint::{read_checkpoint, write_checkpoint};
use dcfm::stage::checkpoint_seal::{open_checkpoint, SealedWriter};
use dcfm::stage::static_stage::StaticResult;
use dcfm::stage::{Energies, Simulation, StepSchedule};

use crate::output::{
    write_atomic_with, write_summary, write_vtu, write_vtu_compressed, HistoryWriter, Precision,
    PvdCollection, VtuField, VtuStrings,
};
use crate::peaks::{read_peaks, update_peaks, write_peaks, Peak};

/// How to run.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Output directory.
    pub out: PathBuf,
    /// Continue from `out/checkpoint.bin` if it exists.
    pub resume: bool,
    /// Resume even when the case or its mesh changed since the checkpoint was written
    /// (`--resume-with-changed-case`); the changes are reported.
    pub resume_with_changed_case: bool,
    /// Run a case of more steps than its step budget `time.max_steps` (`--allow-long`).
    pub allow_long: bool,
    /// Draw a progress bar (on stderr, when it is a terminal).
    pub progress: bool,
}

/// `summary.json`.
#[derive(Clone, Debug, Serialize)]
pub struct RunSummary {
    pub case: String,
    /// "completed", or "failed" when the run stopped on an error after its model was
    /// built (the other fields then describe the state where it stopped).
    pub status: &'static str,
    /// The error that stopped a failed run; None for a completed one.
    pub error: Option<String>,
    /// The failure frame of a failed run (a VTU listed last in case.pvd), if written.
    pub failure_frame: Option<String>,
    /// The case's plausibility warnings (values far outside what their fields mean).
    pub warnings: Vec<CaseWarning>,
    pub title: String,
    pub nodes: usize,
    /// Elements of the mesh.
    pub elements: usize,
    /// Elements the dynamic stage computes (those of the element groups: the mesh's less
    /// the ones excavated, or not placed, by the static stage); `element_updates_per_s`
    /// counts these.
    pub active_elements: usize,
    pub threads: usize,
    pub steps: u64,
    pub dt: f64,
    /// Length of the last step (s): `dt`, or the shortened step that lands on `end`.
    pub last_dt: f64,
    pub critical_dt: f64,
    /// How the critical step was bounded (`time.stable_step`): "element" or "shared_mass".
    pub stable_step: &'static str,
    pub limiting_element: usize,
    /// The case's `time.end` (s).
    pub end_requested: f64,
    /// Time of the last state (s): `end_requested` exactly, except with absorbing
    /// boundaries (full steps only: the first step at or after the end).
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
    /// Steps (of this run, since its start or resume) in which interfaces that meet did not
    /// settle to their tolerance and were accepted, and the largest relative force change
    /// left (docs/contact.md §5a); (0, 0) when every step settled.
    pub contact_unsettled_steps: (u64, f64),
    /// Work of the joint solves of interfaces that meet (docs/contact.md §5a), counted since
    /// the model was built or restored: group steps, how many the direct solve settled and
    /// how many fell back to the sweeps, the largest system; absent without contact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_joint: Option<dcfm::contact::JointStats>,
    /// What changed in the case or mesh since the checkpoint the run resumed from
    /// (`--resume-with-changed-case`); empty otherwise.
    pub resumed_with_changes: Vec<String>,
    /// The probes of histories.csv and how each was found (node chosen for a point and
    /// its distance, the set of a mean).
    pub probes: Probes,
    /// The levels of the multi-time-step integration (`time.subcycling`) and the element
    /// evaluations it saves; absent without it. `element_updates_per_s` counts the
    /// single-step equivalent (every element every step), so it includes the saving.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub subcycling: Option<dcfm::stage::subcycling::SubcyclingSummary>,
    /// The selective mass scaling (`time.mass_scaling`): elements made heavier, the mass
    /// added (total and by region) and the largest factor; absent without it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass_scaling: Option<dcfm::mass_scaling::MassScalingSummary>,
}

/// Turn on the case's subcycling (`time.subcycling`) for the dynamic stage: refused when
/// checkpoints would fall between synchronous steps (`output.checkpoint_every` not a
/// multiple of the cycle), or when resuming from a checkpoint written off the cycle (by
/// a run without subcycling or with other levels).
fn enable_subcycling(
    sim: &mut Simulation,
    max_level: u8,
    safety: f64,
    output: &OutputSection,
    label: &str,
) -> Result<()> {
    sim.enable_subcycling(max_level, safety)
        .map_err(|e| e.in_file(label))?;
    let cycle = sim.cycle_steps();
    if !output.checkpoint_every.is_multiple_of(cycle) {
        return Err(DcfmError::invalid(
            label,
            "output.checkpoint_every",
            output.checkpoint_every,
            format!(
                "a multiple of the subcycling cycle of {cycle} steps (time.subcycling: \
                 checkpoints are written at synchronous steps only)"
            ),
        ));
    }
    if !sim.step.is_multiple_of(cycle) {
        return Err(DcfmError::invalid(
            label,
            "time.subcycling",
            format!("{{ max_level = {max_level} }}"),
            format!(
                "the setting the checkpoint was written with: it holds step {}, not a \
                 multiple of the cycle of {cycle} steps",
                sim.step
            ),
        ));
    }
    Ok(())
}

/// The probes' column groups and what they read, resolved once before the step loop so
/// that a history row allocates nothing.
struct HistoryColumns {
    probes: Probes,
    /// Per node probe: its contact record (interface, record, sign) when it is a single
    /// node on a contact interface (`ContactSystem::locate_node`).
    contact_of: Vec<Option<(usize, usize, f64)>>,
    /// Per element probe: the volume of each of its elements (m³), for a volume mean.
    volumes: Vec<Vec<f64>>,
    /// Number of contact interfaces.
    interfaces: usize,
    /// Anchor segments' history groups, resolved once.
    anchors: Option<dcfm::element::anchor_bar::AnchorHistoryLayout>,
}

/// Names of the columns of a node probe's contact record (`ContactSystem::node_record`).
const CONTACT_COLUMNS: [&str; 10] = [
    "contact_state",
    "gap",
    "normal_force",
    "ftx",
    "fty",
    "ftz",
    "slipx",
    "slipy",
    "slipz",
    "slip_acc",
];

impl HistoryColumns {
    fn new(probes: &Probes, sim: &Simulation) -> Self {
        let model = &sim.model;
        let contact_of = probes
            .nodes
            .iter()
            .map(|p| match (&model.contact, p.mean) {
                (Some(c), false) => c.locate_node(p.nodes[0]),
                _ => None,
            })
            .collect();
        let volumes = probes
            .elements
            .iter()
            .map(|p| {
                p.elements
                    .iter()
                    .map(|&e| {
                        let (g, le) = model.element_location[e as usize];
                        model
                            .groups
                            .get(g as usize)
                            .and_then(|g| g.volume.get(le as usize))
                            .copied()
                            .unwrap_or(0.0)
                    })
                    .collect()
            })
            .collect();
        Self {
            probes: probes.clone(),
            contact_of,
            volumes,
            interfaces: model
                .contact
                .as_ref()
                .map_or(0, |c| c.interface_names().len()),
            anchors: model.anchors.as_ref().map(|a| a.history_layout()),
        }
    }

    /// Column names: energies, node probes (`{name}_ux` … `{name}_az`, then the contact
    /// record of a node on an interface), element probes (`{name}_sxx` … `{name}_szx`),
    /// damaged volumes, anchor bar groups (largest axial force, yielded segments), contact
    /// areas per state and friction work.
    fn header(&self, sim: &Simulation) -> Vec<String> {
        let mut h: Vec<String> = [
            "time", "kinetic", "internal", "damping", "contact", "external", "input", "boundary",
            "residual",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        for (p, contact) in self.probes.nodes.iter().zip(&self.contact_of) {
            for q in ["u", "v", "a"] {
                for d in ["x", "y", "z"] {
                    h.push(format!("{}_{q}{d}", p.label));
                }
            }
            if contact.is_some() {
                for c in CONTACT_COLUMNS {
                    h.push(format!("{}_{c}", p.label));
                }
            }
        }
        for p in &self.probes.elements {
            for c in ["xx", "yy", "zz", "xy", "yz", "zx"] {
                h.push(format!("{}_s{c}", p.label));
            }
        }
        for g in sim.model.groups.iter().filter(|g| g.material.has_damage()) {
            for k in ["tension", "compression", "total"] {
                h.push(format!("damaged_volume_{k}_{}", g.name));
            }
        }
        if let Some(a) = &sim.model.anchors {
            h.extend(a.history_names());
        }
        if let Some(c) = &sim.model.contact {
            for name in c.interface_names() {
                for k in ["bonded", "stick", "slide", "separated", "surface"] {
                    h.push(format!("area_{k}_{name}"));
                }
            }
            h.push("contact_friction_work".into());
        }
        h
    }

    fn row(&self, sim: &Simulation, output: &OutputSection, row: &mut Vec<f64>) {
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
        for (p, contact) in self.probes.nodes.iter().zip(&self.contact_of) {
            for field in [&sim.u, &sim.v, &sim.a] {
                let mut m = [0.0; 3];
                for &n in &p.nodes {
                    for (md, x) in m.iter_mut().zip(field[n as usize]) {
                        *md += x;
                    }
                }
                row.extend(m.map(|x| x / p.nodes.len() as f64));
            }
            if let (Some((k, j, sign)), Some(c)) = (contact, &sim.model.contact) {
                row.extend(c.node_record(*k, *j, *sign));
            }
        }
        for (p, volumes) in self.probes.elements.iter().zip(&self.volumes) {
            if let ([e], false) = (p.elements.as_slice(), p.mean) {
                row.extend(sim.model.element_strain_stress(*e as usize, &sim.u).1);
                continue;
            }
            let mut m = [0.0; 6];
            let mut total = 0.0;
            for (&e, &vol) in p.elements.iter().zip(volumes) {
                let (_, s) = sim.model.element_strain_stress(e as usize, &sim.u);
                for (md, x) in m.iter_mut().zip(s) {
                    *md += vol * x;
                }
                total += vol;
            }
            row.extend(m.map(|x| x / total));
        }
        for g in sim.model.groups.iter().filter(|g| g.material.has_damage()) {
            let per_element = output.damaged_volume == dcfm::case::DamagedVolumeMeasure::Element;
            row.extend(g.damaged_volume(output.damage_threshold, per_element));
        }
        if let (Some(a), Some(layout)) = (&sim.model.anchors, &self.anchors) {
            a.history_values(layout, row);
        }
        if let Some(c) = &sim.model.contact {
            for k in 0..self.interfaces {
                row.extend(c.state_area_split(k));
            }
            row.push(c.friction_work());
        }
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
    let encoding = whole_mesh_encoding(frames.as_deref());
    match frames {
        None => write_state_vtu(sim, out, pvd, encoding),
        Some(f) => {
            f.write(sim, out, pvd, first, last)?;
            if f.full_due(sim.step, first, last) {
                write_state_vtu(sim, out, f.full_collection(), encoding)?;
            }
            Ok(())
        }
    }
}

/// How the whole-mesh frames are written: as `[output.frames]` says, else (every frame
/// the whole mesh) base64 (docs/outputs.md).
fn whole_mesh_encoding(frames: Option<&crate::frames::CompactFrames>) -> WholeMeshEncoding {
    frames.map_or(WholeMeshEncoding::Base64, |f| f.full_encoding)
}

/// Write one VTU of the current state and add it to the collection.
fn write_state_vtu(
    sim: &Simulation,
    out: &Path,
    pvd: &mut PvdCollection,
    encoding: WholeMeshEncoding,
) -> Result<()> {
    write_state_vtu_named(
        sim,
        out,
        pvd,
        &format!("mesh_{:06}.vtu", sim.step),
        encoding,
    )
}

/// Write the VTU of the current state as `name` in `encoding` (Float64 either way) and add
/// it to the collection.
fn write_state_vtu_named(
    sim: &Simulation,
    out: &Path,
    pvd: &mut PvdCollection,
    name: &str,
    encoding: WholeMeshEncoding,
) -> Result<()> {
    let model = &sim.model;
    let ne = model.n_elements();
    let mut stress = vec![0.0; 6 * ne];
    let mut strain = vec![0.0; 6 * ne];
    let mut damage = vec![0.0; 11 * ne];
    // `region`: the number of the cell's region in the `[[regions]]` order, whose names
    // are the field data `region_names`; inactive cells (excavated, not yet placed) keep
    // region −1 and active 0.
    let mut region = vec![-1.0; ne];
    let (cell_active, point_active) = crate::output::activity::activity_fields(model);
    for (gi, g) in model.groups.iter().enumerate() {
        let ss = g.element_strain_stress(&sim.u);
        let dmg = g.element_damage_fields();
        let number = model.region_number(gi) as f64;
        for (le, &e) in g.elements.iter().enumerate() {
            let e = e as usize;
            strain[6 * e..6 * e + 6].copy_from_slice(&ss[le].0);
            stress[6 * e..6 * e + 6].copy_from_slice(&ss[le].1);
            if let Some(d) = &dmg {
                damage[11 * e..11 * e + 11].copy_from_slice(&d[le]);
            }
            region[e] = number;
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
        VtuField::new("displacement", 3, &u),
        VtuField::new("velocity", 3, &v),
        VtuField::new("acceleration", 3, &a),
        VtuField::new("active", 1, &point_active),
    ];
    for (name, components, values) in &contact_fields {
        point_fields.push(VtuField::new(name, *components, values));
    }
    let cell_fields = [
        VtuField::new("stress", 6, &stress),
        VtuField::new("strain", 6, &strain),
        VtuField::new("damage", 1, &d),
        VtuField::new("damage_tension", 1, &dt),
        VtuField::new("damage_compression", 1, &dc),
        VtuField::new("kappa_tension", 1, &kt),
        VtuField::new("kappa_compression", 1, &kc),
        VtuField::new("plastic_strain", 6, &ep),
        VtuField::new("region", 1, &region),
        VtuField::new("active", 1, &cell_active),
    ];
    let field_data = [VtuStrings {
        name: "region_names",
        values: &model.region_names,
    }];
    let (path, coords, cells) = (out.join(name), &model.mesh.coords, &model.mesh.elements);
    match encoding {
        WholeMeshEncoding::Base64 => write_vtu(
            &path,
            coords,
            cells,
            &point_fields,
            &cell_fields,
            &field_data,
        ),
        WholeMeshEncoding::Zlib => write_vtu_compressed(
            &path,
            Precision::Float64,
            coords,
            cells,
            &point_fields,
            &cell_fields,
            &field_data,
        ),
    }?;
    pvd.add(sim.time, name)
}

/// Write `checkpoint.bin` (atomically): the sealed file of
/// [`dcfm::stage::checkpoint_seal`] around the static block, the dynamic state and the
/// peaks.
fn write_checkpoint_file(
    path: &Path,
    fingerprint: &CaseFingerprint,
    static_result: Option<&StaticResult>,
    sim: &Simulation,
    peaks: &[Peak; 2],
) -> Result<()> {
    write_atomic_with(path, |w| {
        let mut s = SealedWriter::begin(w, fingerprint)?;
        crate::static_run::write_static(&mut s, static_result, &sim.model)?;
        write_checkpoint(&mut s, sim)?;
        write_peaks(&mut s, peaks)?;
        s.finish()?;
        Ok(())
    })
}

/// Most changes listed in the refusal of a checkpoint written for another case.
const MAX_LISTED_CHANGES: usize = 8;

/// The changes of the case as one line: the first few, then how many more.
fn list_changes(changes: &[String]) -> String {
    let mut s = changes
        .iter()
        .take(MAX_LISTED_CHANGES)
        .cloned()
        .collect::<Vec<_>>()
        .join("; ");
    if changes.len() > MAX_LISTED_CHANGES {
        s += &format!("; and {} more", changes.len() - MAX_LISTED_CHANGES);
    }
    s
}

/// Step of a VTU frame written by [`write_state_vtu`] (`mesh_000120.vtu` → 120) or, with
/// `[output.frames]`, by [`crate::frames::CompactFrames`] (`frame_000120.vtu`,
/// `anchors_000120.vtu`).
pub(crate) fn frame_step(file: &str) -> Option<u64> {
    let digits = ["mesh_", "frame_", "anchors_"]
        .iter()
        .find_map(|prefix| file.strip_prefix(prefix))?
        .strip_suffix(".vtu")?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}

/// Step of the failure frame of a failed run (`mesh_000120_failed.vtu` → 120).
fn failure_frame_step(file: &str) -> Option<u64> {
    frame_step(&file.replace("_failed.vtu", ".vtu")).filter(|_| file.ends_with("_failed.vtu"))
}

/// Write the failure frame of a run stopped by `error` (docs/outputs.md, "A failed
/// run"): after an instability, the state the failed step reached (the diverging motion;
/// [`Simulation::adopt_failed_step`]), else the last state; as `mesh_NNNNNN_failed.vtu`,
/// written atomically in `encoding` and listed last in `pvd` (replacing a frame of the
/// same time).
fn write_failure_frame(
    sim: &mut Simulation,
    error: &DcfmError,
    out: &Path,
    pvd: &mut PvdCollection,
    encoding: WholeMeshEncoding,
) -> Result<String> {
    if matches!(error, DcfmError::Unstable { .. }) {
        sim.adopt_failed_step();
    }
    let t = sim.time;
    if pvd.entries().last().is_some_and(|e| e.time >= t) {
        pvd.retain(|e| e.time < t)?;
    }
    let name = format!("mesh_{:06}_failed.vtu", sim.step);
    write_state_vtu_named(sim, out, pvd, &name, encoding)?;
    Ok(name)
}

/// The summary of a run that stopped on `error` before its dynamic stage had a state
/// (the static stage or the setup of the dynamic one): what it was and why it stopped.
#[derive(Serialize)]
struct EarlyFailure<'a> {
    case: &'a str,
    title: &'a str,
    status: &'static str,
    error: String,
    warnings: &'a [CaseWarning],
}

/// Write summary.json for a run that stopped on `error` before its dynamic stage had a
/// state; the error is returned as it was (a failure to write the summary is added to its
/// text on stderr only, the run's own error matters more).
fn early_failure(
    out: &Path,
    label: &str,
    title: &str,
    warnings: &[CaseWarning],
    error: DcfmError,
) -> DcfmError {
    let summary = EarlyFailure {
        case: label,
        title,
        status: "failed",
        error: error.to_string(),
        warnings,
    };
    if let Err(e) = write_summary(&out.join("summary.json"), &summary) {
        eprintln!("note: the summary of the failed run could not be written: {e}");
    }
    error
}

/// Remove from `out` the VTU frames that `pvd` does not list (left by an earlier run in
/// the same folder, or written after the checkpoint a run resumes from) and the temporary
/// files of atomic writes that a killed process left (`.<name>.<pid>.<n>.tmp`, another
/// pid), so that the folder holds exactly this run's frames. `others`: with
/// `[output.frames]` the collections of the whole-mesh and anchor frames (`full.pvd`,
/// `anchors.pvd`), whose files are this run's too (the first whole-mesh frame, written
/// before this cleanup, was removed as stale before).
fn remove_stale_files(out: &Path, pvd: &PvdCollection, others: &[&PvdCollection]) -> Result<()> {
    let io = |e| DcfmError::io(out.display().to_string(), e);
    let own = format!(".{}.", std::process::id());
    for entry in std::fs::read_dir(out).map_err(io)? {
        let entry = entry.map_err(io)?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let stale_frame = (frame_step(&name).is_some() || failure_frame_step(&name).is_some())
            && !pvd
                .entries()
                .iter()
                .chain(others.iter().flat_map(|c| c.entries()))
                .any(|e| e.file == name);
        let killed_write = name.starts_with('.') && name.ends_with(".tmp") && !name.contains(&own);
        if (stale_frame || killed_write) && entry.file_type().map_err(io)?.is_file() {
            std::fs::remove_file(entry.path()).map_err(io)?;
        }
    }
    Ok(())
}

/// Run a case to its end time, writing outputs under `opts.out`.
pub fn run_case(case: Case, opts: &RunOptions) -> Result<RunSummary> {
    // A runaway (end time or step mistyped) is refused before anything is written.
    case.checked_step_count(opts.allow_long)?;
    let out = &opts.out;
    std::fs::create_dir_all(out).map_err(|e| DcfmError::io(out.display().to_string(), e))?;
    let label = case.file.display().to_string();
    let title = case.title.clone();
    let dt = case.dt;
    let output = case.output.clone();
    let end = case.end;
    let schedule = StepSchedule::new(end, dt);
    let total_steps = schedule.steps;
    let fingerprint = case.fingerprint.clone();
    let checkpoint = out.join("checkpoint.bin");
    let ckpt_label = checkpoint.display().to_string();
    let resume_bytes = if opts.resume && checkpoint.exists() {
        Some(std::fs::read(&checkpoint).map_err(|e| DcfmError::io(&ckpt_label, e))?)
    } else {
        None
    };
    // A corrupted checkpoint, one of an older format, or one written for another case or
    // mesh is refused before anything is read from it (docs/outputs.md, "Checkpoints").
    let sealed = match &resume_bytes {
        Some(b) => Some(open_checkpoint(b, &ckpt_label)?),
        None => None,
    };
    let changes = sealed
        .as_ref()
        .map(|s| fingerprint.changes_since(&s.fingerprint))
        .unwrap_or_default();
    if !changes.is_empty() {
        if !opts.resume_with_changed_case {
            return Err(DcfmError::Parse {
                file: ckpt_label,
                message: format!(
                    "written for another version of {label}: {}. Run with \
                     --resume-with-changed-case to continue from it with the case as it is \
                     now, or without --resume to start again",
                    list_changes(&changes)
                ),
            });
        }
        eprintln!(
            "note: {ckpt_label}: resuming with a changed case ({})",
            list_changes(&changes)
        );
    }
    let payload = sealed.map(|s| s.payload);
    let warnings = case.warnings.clone();
    // From here on the run can fail on its own (the static stage, an instability, a
    // contact solve that does not settle, a write): summary.json then says so
    // (docs/outputs.md, "A failed run").
    let early = |e: DcfmError| early_failure(out, &label, &title, &warnings, e);
    // ---- static stage (owner: static; docs/static_stage.md) ---------------------------
    // Run it (writing static.vtu, static_histories.csv, static_summary.json) or restore it
    // from the checkpoint; the dynamic stage starts from its state. Every checkpoint's
    // payload begins with its block (`static_run::write_static`).
    let staged = crate::static_run::run_static_stage(
        case.model,
        case.static_plan.as_ref(),
        out,
        payload.map(|b| (b, ckpt_label.as_str())),
        &label,
    )
    .map_err(early)?;
    let static_result = staged.result;
    let mut sim = crate::static_run::start(staged.model, static_result.as_ref(), dt, case.safety)
        .map_err(early)?;
    if staged.fresh {
        write_checkpoint_file(
            &checkpoint,
            &fingerprint,
            static_result.as_ref(),
            &sim,
            &[Peak::default(); 2],
        )
        .map_err(early)?;
    }
    // ---- end of the static stage hook ---------------------------------------------------
    let columns = HistoryColumns::new(&case.probes, &sim);
    let header = columns.header(&sim);
    let mut resumed_from = None;
    if let Some(bytes) = payload {
        read_checkpoint(&bytes[staged.dynamic_offset..], &ckpt_label, &mut sim).map_err(early)?;
        resumed_from = Some(sim.step);
    }
    if let Some(max_level) = case.subcycling {
        enable_subcycling(&mut sim, max_level, case.safety, &output, &label).map_err(early)?;
    }
    let mut frames = match &output.frames {
        Some(f) => Some(
            crate::frames::CompactFrames::new(
                f,
                &sim,
                out,
                output.vtu_every,
                resumed_from.is_some(),
            )
            .map_err(early)?,
        ),
        None => None,
    };
    let pvd_path = out.join("case.pvd");
    let hist_path = out.join("histories.csv");
    let mut opened = || -> Result<(PvdCollection, HistoryWriter)> {
        Ok(if resumed_from.is_some() {
            // Keep the frames this run's schedule writes up to the restart (not the end frame
            // of the interrupted run), so that the collection is that of an uninterrupted run.
            let mut p = PvdCollection::resume(&pvd_path)?;
            p.truncate_after(sim.time)?;
            let restart = sim.step;
            // A failure frame of an earlier run is not a frame of this one (`frame_step`
            // does not read it).
            p.retain(|e| {
                frame_step(&e.file).is_some_and(|s| {
                    s == 0 || (s <= restart && output.vtu_every > 0 && s % output.vtu_every == 0)
                })
            })?;
            (
                p,
                HistoryWriter::open_append_after(&hist_path, &header, sim.time)?,
            )
        } else {
            let mut h = HistoryWriter::create(&hist_path, &header)?;
            let mut row = Vec::new();
            columns.row(&sim, &output, &mut row);
            h.append(&row)?;
            let mut p = PvdCollection::create(&pvd_path)?;
            write_frame(&sim, out, &mut p, frames.as_mut(), true, false)?;
            (p, h)
        })
    };
    let (mut pvd, mut hist) = opened().map_err(early)?;
    let others = frames.as_ref().map(|f| f.collections()).unwrap_or_default();
    remove_stale_files(out, &pvd, &others).map_err(early)?;
    let bar = if opts.progress {
        crate::progress::run_bar(ProgressDrawTarget::stderr(), total_steps, sim.step, dt)
    } else {
        ProgressBar::hidden()
    };
    let n_elements = sim.model.n_elements();
    let n_active: usize = sim.model.groups.iter().map(|g| g.len()).sum();
    let mut peaks = payload.map_or([Peak::default(); 2], read_peaks);
    let mut row = Vec::with_capacity(header.len());
    let start_step = sim.step;
    let t0 = Instant::now();
    let mut stepping = || -> Result<()> {
        while sim.step < total_steps {
            // The last step lands on `end` (shortened when `end` is not a multiple of Δt).
            let last = sim.step + 1 == total_steps;
            if last
                && schedule.shortened(dt)
                && sim.can_shorten_steps()
                && output.checkpoint_every > 0
                && sim.step % output.checkpoint_every != 0
            {
                // The state after a shortened step is off the step grid and gets no
                // checkpoint: checkpoint the last full step instead, so that a run resumed to
                // a later end starts one step before this end.
                hist.flush()?;
                write_checkpoint_file(
                    &checkpoint,
                    &fingerprint,
                    static_result.as_ref(),
                    &sim,
                    &peaks,
                )?;
            }
            let taken = if last { sim.step_to(end) } else { sim.step() };
            taken.inspect_err(|_| {
                let _ = hist.flush();
            })?;
            if sim.step % output.history_every == 0 || sim.step == total_steps {
                columns.row(&sim, &output, &mut row);
                hist.append(&row)?;
                update_peaks(&mut peaks, &sim.u, &sim.v, sim.time);
            }
            if (output.vtu_every > 0 && sim.step % output.vtu_every == 0) || sim.step == total_steps
            {
                let last = sim.step == total_steps;
                write_frame(&sim, out, &mut pvd, frames.as_mut(), false, last)?;
            }
            // A shortened last step is off the step grid: no checkpoint there (a run resumed
            // to a later end continues from the last full-step checkpoint).
            if output.checkpoint_every > 0
                && sim.step % output.checkpoint_every == 0
                && sim.on_grid()
            {
                hist.flush()?;
                write_checkpoint_file(
                    &checkpoint,
                    &fingerprint,
                    static_result.as_ref(),
                    &sim,
                    &peaks,
                )?;
            }
            if sim.step % 64 == 0 {
                let el = t0.elapsed().as_secs_f64().max(1e-9);
                let rate = (sim.step - start_step) as f64 * n_active as f64 / el;
                crate::progress::update(&bar, sim.step, rate);
            }
        }
        Ok(())
    };
    let outcome = stepping();
    bar.finish_and_clear();
    let wall = t0.elapsed().as_secs_f64();
    // A failed run: its histories up to the failure, its failing state as the last frame,
    // and summary.json saying why (docs/outputs.md, "A failed run").
    let (status, error, failure_frame) = match &outcome {
        Ok(()) => ("completed", None, None),
        Err(e) => {
            let mut text = e.to_string();
            if let Err(h) = hist.flush() {
                text += &format!("; histories.csv could not be completed: {h}");
            }
            let encoding = whole_mesh_encoding(frames.as_ref());
            let frame = match write_failure_frame(&mut sim, e, out, &mut pvd, encoding) {
                Ok(name) => Some(name),
                Err(f) => {
                    text += &format!("; the failure frame could not be written: {f}");
                    None
                }
            };
            ("failed", Some(text), frame)
        }
    };
    if outcome.is_ok() {
        hist.finish()?;
    }
    let steps_run = sim.step - start_step;
    let last_dt = sim.last_step();
    let summary = RunSummary {
        case: label,
        status,
        error,
        failure_frame,
        warnings: warnings.clone(),
        title,
        nodes: sim.u.len(),
        elements: n_elements,
        active_elements: n_active,
        threads: rayon::current_num_threads(),
        steps: sim.step,
        dt,
        last_dt,
        critical_dt: sim.model.critical_step_with_damping(),
        stable_step: sim.model.step_bound.name(),
        limiting_element: sim.model.stable.element,
        end_requested: end,
        end_time: sim.time,
        wall_s: wall,
        steps_per_s: steps_run as f64 / wall.max(1e-9),
        element_updates_per_s: steps_run as f64 * n_active as f64 / wall.max(1e-9),
        bytes_per_element: sim.model.bytes_per_element(),
        energies: sim.energies,
        energy_residual: sim.energies.residual(),
        energy_residual_relative: sim.energies.relative_residual(),
        peak_displacement: peaks[0],
        peak_velocity: peaks[1],
        resumed_from_step: resumed_from,
        contact_unsettled_steps: sim
            .model
            .contact
            .as_ref()
            .map_or((0, 0.0), |c| c.unsettled_joint_steps()),
        contact_joint: sim.model.contact.as_ref().map(|c| c.joint_stats()),
        resumed_with_changes: changes,
        probes: columns.probes,
        subcycling: sim.subcycling().cloned(),
        mass_scaling: sim.model.mass_scaling.clone(),
    };
    write_summary(&out.join("summary.json"), &summary)?;
    outcome.map(|()| summary)
}
