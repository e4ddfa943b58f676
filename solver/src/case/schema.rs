//! Serde types of the case file. Unknown fields are rejected.

use std::collections::BTreeMap;

use serde::Deserialize;

use crate::boundary::MotionKind;
use crate::element::Integration;
use crate::load::TimeFunction;
use crate::mesh::{BlockSpec, BoxMeshSpec};

/// The whole case file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    /// Free text shown in outputs.
    #[serde(default)]
    pub title: String,
    pub time: TimeSection,
    #[serde(default)]
    pub output: OutputSection,
    pub mesh: MeshSection,
    pub materials: BTreeMap<String, MaterialSection>,
    pub regions: Vec<RegionSection>,
    #[serde(default)]
    pub node_sets: BTreeMap<String, NodeSetSection>,
    #[serde(default)]
    pub boundary: BoundarySection,
    #[serde(default)]
    pub loads: LoadSection,
    #[serde(default)]
    pub damping: DampingSection,
    #[serde(default)]
    pub initial: InitialSection,
    /// Contact interfaces (`[[interfaces]]`), see docs/contact.md.
    #[serde(default)]
    pub interfaces: Vec<crate::contact::InterfaceSpec>,
    /// Seismic input motion (`[seismic]`), see docs/boundaries.md.
    #[serde(default)]
    pub seismic: Option<crate::boundary::seismic_input::SeismicSection>,
    /// Anchor bars (`[anchors]`), see docs/anchors.md.
    #[serde(default)]
    pub anchors: crate::element::anchor_bar::AnchorSection,
    /// Ground motions (`[motions.NAME]`), see docs/motion.md.
    #[serde(default)]
    pub motions: BTreeMap<String, crate::motion::MotionSpec>,
    /// The static stage (`[static]`), see docs/static_stage.md.
    #[serde(default, rename = "static")]
    pub static_stage: Option<crate::case::static_schema::StaticSection>,
}

/// `[time]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSection {
    /// End time (s).
    pub end: f64,
    /// Time step (s); default: `safety` × the critical step.
    #[serde(default)]
    pub dt: Option<f64>,
    /// Safety factor on the critical step.
    #[serde(default = "default_safety")]
    pub safety: f64,
    /// Step budget: `dcfm run` refuses a case of more steps unless given `--allow-long`
    /// (default [`DEFAULT_MAX_STEPS`]).
    #[serde(default)]
    pub max_steps: Option<f64>,
    /// Multi-time-step integration: `"off"` (default) or `{ max_level = N }`, N in 1..=7
    /// (`stage::subcycling`); checked by `case::build::time::subcycling_level`.
    #[serde(default)]
    pub subcycling: Option<toml::Value>,
    /// Selective mass scaling: `"off"` (default) or `{ min_element_step = Δt_min,
    /// max_added_fraction = 0.05 }` (`crate::mass_scaling`); checked by
    /// `case::build::time::mass_scaling_settings`.
    #[serde(default)]
    pub mass_scaling: Option<toml::Value>,
    /// How the critical step is bounded: `"element"` (default, each element with its own
    /// lumped masses) or `"shared_mass"` (`element::shared_mass_step`); checked by
    /// `case::build::time::step_bound`.
    #[serde(default)]
    pub stable_step: Option<String>,
}

/// Default step budget of `[time] max_steps`.
pub const DEFAULT_MAX_STEPS: u64 = 100_000_000;

fn default_safety() -> f64 {
    0.9
}

/// `[output]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    /// Write a VTU file every this many steps (0: only the last step).
    #[serde(default)]
    pub vtu_every: u64,
    /// Write a row of histories every this many steps.
    #[serde(default = "one")]
    pub history_every: u64,
    /// Nodes whose displacement, velocity and acceleration go to histories.csv.
    #[serde(default)]
    pub nodes: Vec<u32>,
    /// Elements whose stress goes to histories.csv.
    #[serde(default)]
    pub elements: Vec<u32>,
    /// Write a checkpoint every this many steps (0: never), for `dcfm run --resume`.
    #[serde(default)]
    pub checkpoint_every: u64,
    /// An integration point counts in the damaged volume (eq. 27) when its D_t or D_c is
    /// at least this (docs/plastic_damage.md §5).
    #[serde(default = "default_damage_threshold")]
    pub damage_threshold: f64,
    /// Count the damaged volume per integration point ("point", default) or per element
    /// from its volume-averaged damage ("element").
    #[serde(default)]
    pub damaged_volume: DamagedVolumeMeasure,
    /// Node probes by name: a point, a node id or a set (`[[output.probes]]`).
    #[serde(default)]
    pub probes: Vec<NodeProbeSpec>,
    /// Element probes by name: a point, an element id or a set (`[[output.element_probes]]`).
    #[serde(default)]
    pub element_probes: Vec<ElementProbeSpec>,
    /// Compact field frames (`[output.frames]`, added on the yingxiuwan branch): when
    /// given, the frames every `vtu_every` steps hold the elements of `regions` only,
    /// Float32 and compressed, and the whole mesh is written every `full_every` steps.
    #[serde(default)]
    pub frames: Option<FramesSection>,
}

/// How a probe on a set reports.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ProbeReduce {
    /// One group of columns per node (element) of the set.
    #[default]
    Each,
    /// The mean over the set (displacement, velocity, acceleration; stress).
    Mean,
}

/// `[[output.probes]]`: a named node probe; exactly one of `at`, `node`, `set`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct NodeProbeSpec {
    /// Column prefix (`crest` → `crest_ux`, …).
    pub name: String,
    /// A point (m): the nearest node of the model.
    #[serde(default)]
    pub at: Option<[f64; 3]>,
    /// A node id.
    #[serde(default)]
    pub node: Option<u32>,
    /// A node, face or element set or a region.
    #[serde(default)]
    pub set: Option<String>,
    /// For a set: every node ("each", default) or the mean ("mean").
    #[serde(default)]
    pub reduce: ProbeReduce,
}

/// `[[output.element_probes]]`: a named element probe; exactly one of `at`, `element`,
/// `set`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ElementProbeSpec {
    /// Column prefix (`crown` → `crown_sxx`, …).
    pub name: String,
    /// A point (m): the element that contains it.
    #[serde(default)]
    pub at: Option<[f64; 3]>,
    /// An element id.
    #[serde(default)]
    pub element: Option<u32>,
    /// An element set or a region.
    #[serde(default)]
    pub set: Option<String>,
    /// For a set: every element ("each", default) or the volume mean ("mean").
    #[serde(default)]
    pub reduce: ProbeReduce,
}

/// `[output.frames]`: what the compact frames hold (docs/outputs.md).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FramesSection {
    /// Regions or element sets whose elements every frame holds (e.g. the concrete,
    /// whose nodes carry the contact fields of the interfaces).
    pub regions: Vec<String>,
    /// Steps between two frames of the whole mesh (Float64, every field); 0: the first
    /// and the last step only.
    #[serde(default)]
    pub full_every: u64,
    /// How the whole-mesh frames are stored (default zlib-compressed).
    #[serde(default)]
    pub full_encoding: WholeMeshEncoding,
    /// A frame of the anchor bars (line cells with their axial force) with the frames.
    #[serde(default = "yes")]
    pub anchors: bool,
    /// Steps between two frames of the anchor bars (a multiple of `output.vtu_every`);
    /// 0: with every frame. The first and the last step always get one.
    #[serde(default)]
    pub anchors_every: u64,
}

fn yes() -> bool {
    true
}

/// `[output.frames] full_encoding`: the storage of the whole-mesh frames (`full.pvd`),
/// both Float64, both read by VTK, ParaView and PyVista (docs/outputs.md).
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum WholeMeshEncoding {
    /// zlib-compressed raw appended data (VTK's `vtkZLibDataCompressor`): ≈ 0.3 of the
    /// base64 file on the Yingxiuwan full mesh; generic XML parsers cannot read it.
    #[default]
    Zlib,
    /// Appended base64, as the frames of a run without `[output.frames]`: plain XML.
    Base64,
}

/// How the damaged volume of eq. (27) is measured.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum DamagedVolumeMeasure {
    /// Volume of the integration points whose damage reaches the threshold.
    #[default]
    Point,
    /// Volume of the elements whose averaged damage reaches the threshold.
    Element,
}

fn default_damage_threshold() -> f64 {
    0.1
}

impl Default for OutputSection {
    fn default() -> Self {
        Self {
            vtu_every: 0,
            history_every: 1,
            nodes: Vec::new(),
            elements: Vec::new(),
            checkpoint_every: 0,
            damage_threshold: default_damage_threshold(),
            damaged_volume: DamagedVolumeMeasure::Point,
            probes: Vec::new(),
            element_probes: Vec::new(),
            frames: None,
        }
    }
}

fn one() -> u64 {
    1
}

/// `[mesh]`: either a Gmsh file or structured blocks.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSection {
    /// Gmsh 4.1 file, relative to the case file.
    #[serde(default)]
    pub gmsh: Option<String>,
    /// Structured blocks.
    #[serde(default)]
    pub blocks: Vec<BlockSpec>,
    /// Region pairs whose shared nodes are duplicated (contact interfaces).
    #[serde(default)]
    pub split: Vec<[String; 2]>,
    /// Relative node-merge tolerance for blocks.
    #[serde(default)]
    pub merge_tolerance: Option<f64>,
    /// A plate with a circular hole (O-grid), see docs/static_stage.md.
    #[serde(default)]
    pub plate_with_hole: Option<crate::mesh::generators::PlateWithHoleSpec>,
}

impl MeshSection {
    /// The block mesh spec, if blocks are given.
    pub fn box_spec(&self) -> BoxMeshSpec {
        BoxMeshSpec {
            blocks: self.blocks.clone(),
            split: self.split.clone(),
            merge_tolerance: self.merge_tolerance.unwrap_or(1e-6),
        }
    }
}

/// Constitutive model name.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ModelKind {
    Elastic,
    PlasticDamage,
}

/// `[materials.NAME]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    pub model: ModelKind,
    /// Young's modulus (Pa).
    pub young: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Parameters of the plastic-damage model (model = "plastic_damage").
    #[serde(default)]
    pub plastic_damage: Option<crate::material::plastic_damage::PlasticDamageParams>,
}

/// `[[regions]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSection {
    pub name: String,
    pub material: String,
    #[serde(default)]
    pub integration: Integration,
    /// Hourglass coefficient ε_hg (one-point).
    #[serde(default = "default_hourglass")]
    pub hourglass: f64,
    /// The region's own Rayleigh damping (default: `[damping]`).
    #[serde(default)]
    pub damping: Option<DampingSection>,
}

fn default_hourglass() -> f64 {
    0.05
}

/// `[node_sets.NAME]`: explicit nodes or the nodes inside a box.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeSetSection {
    #[serde(default)]
    pub nodes: Vec<u32>,
    /// `[[x0, y0, z0], [x1, y1, z1]]`: nodes with x0 ≤ x ≤ x1 etc. (inclusive, 1e-9 slack).
    #[serde(default, rename = "box")]
    pub bounds: Option<[[f64; 3]; 2]>,
}

/// `[boundary]`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundarySection {
    #[serde(default)]
    pub fixed: Vec<FixedSection>,
    #[serde(default)]
    pub prescribed: Vec<PrescribedSection>,
    /// Absorbing boundaries (`[[boundary.absorbing]]`).
    #[serde(default)]
    pub absorbing: Vec<crate::boundary::AbsorbingSpec>,
    /// Free-field coupling (`[boundary.free_field]`).
    #[serde(default)]
    pub free_field: Option<crate::boundary::free_field::FreeFieldSection>,
}

/// `[[boundary.fixed]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixedSection {
    /// Node set, face set, element set or region.
    pub set: String,
    /// Any of "x", "y", "z", e.g. "xyz" or "z".
    pub dofs: String,
}

/// `[[boundary.prescribed]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrescribedSection {
    pub set: String,
    /// "x", "y" or "z".
    pub dof: String,
    pub kind: MotionKind,
    pub history: TimeFunction,
}

/// `[loads]`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSection {
    #[serde(default)]
    pub nodal: Vec<NodalLoadSection>,
    #[serde(default)]
    pub gravity: Option<GravitySection>,
}

/// `[[loads.nodal]]`: `force` on every node of `set`, times `history` (default 1).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodalLoadSection {
    pub set: String,
    pub force: [f64; 3],
    #[serde(default)]
    pub history: Option<TimeFunction>,
}

/// `[loads.gravity]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GravitySection {
    pub acceleration: [f64; 3],
    #[serde(default)]
    pub history: Option<TimeFunction>,
}

/// `[damping]`: Rayleigh C = αM + βK0.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DampingSection {
    #[serde(default)]
    pub alpha: f64,
    #[serde(default)]
    pub beta: f64,
}

/// `[initial]`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSection {
    #[serde(default)]
    pub velocity: Vec<InitialVelocitySection>,
}

/// `[[initial.velocity]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialVelocitySection {
    pub set: String,
    pub value: [f64; 3],
}
