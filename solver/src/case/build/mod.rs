//! From the parsed case file to a validated [`Model`], with field paths in every error.
//!
//! One function per case section, one file per section; [`build`] calls them in the
//! order the sections depend on each other (mesh → materials → model → interfaces →
//! constraints → loads → absorbing boundaries and seismic input → outputs → time step).

mod anchors;
mod boundary;
mod checks;
mod loads;
mod materials;
mod mesh;
mod motions;
mod output;
mod plausibility;
mod static_stage;
mod time;

pub use materials::build_materials;

use std::path::{Path, PathBuf};

use crate::case::schema::*;
use crate::error::{DcfmError, Result};
use crate::model::Model;

/// A loaded case: the model and the run settings.
#[derive(Debug)]
pub struct Case {
    /// Path of the case file.
    pub file: PathBuf,
    pub title: String,
    pub model: Model,
    /// Time step (s), checked against the stable step.
    pub dt: f64,
    /// End time (s).
    pub end: f64,
    pub safety: f64,
    /// `time.subcycling`'s `max_level` (`None`: single stepping), enabled on the dynamic
    /// stage's simulation (`Simulation::enable_subcycling`).
    pub subcycling: Option<u8>,
    pub output: OutputSection,
    /// The output probes resolved against the model, in the order of their columns.
    pub probes: crate::case::probes::Probes,
    /// The case's ground motions by name (`[motions.NAME]`), for the seismic input.
    pub motions: crate::motion::Motions,
    /// The static stage (`[static]`), run before the dynamic stage.
    pub static_plan: Option<crate::stage::static_stage::StaticPlan>,
    /// Most steps a run may take without being asked to (`time.max_steps`).
    pub max_steps: u64,
    /// Values valid but far outside what their fields mean (units slips), in the order
    /// of the case's sections; `dcfm check` and `dcfm run` print them, summary.json lists
    /// them.
    pub warnings: Vec<crate::case::warnings::CaseWarning>,
    /// Hashes of the case's fields and its mesh, written into checkpoints so that a
    /// resume can refuse a checkpoint of another case.
    pub fingerprint: crate::case::fingerprint::CaseFingerprint,
}

impl Case {
    /// Steps from 0 to the end time: ⌈end/Δt⌉ (a float: a mistyped end time may give more
    /// than a u64 holds).
    pub fn step_count(&self) -> f64 {
        time::step_count(self.end, self.dt)
    }

    /// The step count, checked against the step budget `time.max_steps` (above it an
    /// error naming the fields, unless `allow_long`) and against 2⁵³ (always an error).
    pub fn checked_step_count(&self, allow_long: bool) -> Result<u64> {
        time::check_step_budget(
            &self.file.display().to_string(),
            self.end,
            self.dt,
            self.max_steps,
            allow_long,
        )
    }
}

/// Read, parse and build a case file.
pub fn load_case(path: &Path) -> Result<Case> {
    let label = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| DcfmError::io(&label, e))?;
    parse_case(&text, &label, path.parent().unwrap_or(Path::new(".")))
}

/// Parse and build a case from its text; `label` names it in errors, `dir` resolves
/// relative paths (the Gmsh file).
pub fn parse_case(text: &str, label: &str, dir: &Path) -> Result<Case> {
    parse_case_with_motions(text, label, dir, &crate::motion::Motions::new())
}

/// [`parse_case`] with ground motions made by the caller (the Python module: records
/// read by ObsPy, numpy arrays) available to the case's time functions by name, beside
/// the case's own `[motions.NAME]`; a name may not be in both.
pub fn parse_case_with_motions(
    text: &str,
    label: &str,
    dir: &Path,
    given: &crate::motion::Motions,
) -> Result<Case> {
    let file: CaseFile = toml::from_str(text).map_err(|e| DcfmError::Parse {
        file: label.to_string(),
        message: e.to_string().trim_end().to_string(),
    })?;
    let mut case = build(file, label, dir, given)?;
    case.fingerprint = crate::case::fingerprint::CaseFingerprint::new(text, &case.model.mesh)
        .map_err(|message| DcfmError::Parse {
            file: label.to_string(),
            message,
        })?;
    case.fingerprint.add_motions(&case.motions);
    Ok(case)
}

fn build(
    mut file: CaseFile,
    label: &str,
    dir: &Path,
    given: &crate::motion::Motions,
) -> Result<Case> {
    let max_steps = time::check_time(&file.time, label)?;
    let subcycling = time::subcycling_level(&file.time, label)?;
    let mass_scaling = time::mass_scaling_settings(&file.time, label)?;
    let motions = motions::build_motions(&mut file, label, dir, given)?;
    let mut mesh = mesh::build_mesh(&file.mesh, label, dir)?;
    mesh::add_node_sets(&mut mesh, &file.node_sets, label)?;
    crate::mesh::outer_faces::add_bounding_box_face_sets(&mut mesh);
    let materials = materials::build_materials(&file.materials, label)?;
    let setups = materials::build_regions(&file.regions, &materials, label)?;
    let mut model = Model::new(mesh, &setups, label)?;
    materials::check_element_sizes(&model, label)?;
    if let Some(settings) = &mass_scaling {
        crate::mass_scaling::apply_mass_scaling(&mut model, settings, label)?;
    }
    if !file.interfaces.is_empty() {
        let system = crate::contact::ContactSystem::new(&model.mesh, &file.interfaces, label)?;
        model.contact = Some(system);
    }
    let installed =
        static_stage::active_at_installation(&model, file.static_stage.as_ref(), label)?;
    anchors::build_anchors(&mut model, &file.anchors, installed, label)?;
    boundary::build_boundary(&mut model, &file.boundary, label)?;
    loads::build_loads(&mut model, &file.loads, label)?;
    loads::build_damping(&mut model, &file.damping, &file.regions, label)?;
    loads::build_initial(&mut model, &file.initial, label)?;
    boundary::build_absorbing(&mut model, &file, &materials, label)?;
    let probes = output::build_output(&model, &file.output, label)?;
    let static_plan =
        static_stage::build_static(&model, file.static_stage.as_ref(), &file.output, label)?;
    // Every constraint is known now: the stable step from the elements that move.
    model.step_bound = time::step_bound(&file.time, label)?;
    if model.step_bound == crate::model::StepBound::SharedMass && subcycling.is_some() {
        return Err(DcfmError::invalid(
            label,
            "time.stable_step",
            "\"shared_mass\"",
            "\"element\" with time.subcycling: the levels are taken from each element's \
             own step, not from a bound on the whole mesh",
        ));
    }
    model.refresh_stable_step();
    let dt = model
        .time_step(file.time.dt, file.time.safety)
        .map_err(|e| e.in_file(label))?;
    let critical = model.critical_step_with_damping();
    time::check_vanishing_dt(
        label,
        file.time.dt,
        (dt, file.time.safety),
        file.time.end,
        critical,
        plausibility::SMALL_DT_FRACTION,
    )?;
    let warnings = plausibility::warnings(&file, label, dt, critical);
    Ok(Case {
        file: PathBuf::from(label),
        title: file.title,
        model,
        dt,
        end: file.time.end,
        safety: file.time.safety,
        subcycling,
        output: file.output,
        probes,
        motions,
        static_plan,
        max_steps,
        warnings,
        fingerprint: Default::default(),
    })
}
