//! The Yingxiuwan underground powerhouse (paper §4, Fig. 6, Table 1) as a preset of the
//! parametric cavern: the dimensions the paper gives, the ones it does not (chosen and
//! justified in docs/yingxiuwan.md), two mesh variants, the anti-seismic measures of §6
//! as case variants, and the whole case file that goes with the mesh: materials,
//! interfaces, rock bolts, the static stage (K0 in-situ stress under the overburden,
//! excavation by benches from the crown down, the arch lining cast after the top heading,
//! the rest of the concrete after the last bench), the seismic stage (viscous-spring base
//! with the outcrop input, free-field sides, a buried top), outputs and checkpoints.

use super::cavern::{CavernGeometry, Density, RockZones};

/// Mesh variants: `Full` near the paper's 171,432 hex8 / 189,187 nodes, `Ci` ≈ 10⁴
/// elements for runs in continuous integration (same geometry, coarser cells).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variant {
    Full,
    Ci,
}

impl Variant {
    pub fn name(self) -> &'static str {
        match self {
            Variant::Full => "full",
            Variant::Ci => "ci",
        }
    }

    /// Parse "full" or "ci".
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "full" => Some(Variant::Full),
            "ci" => Some(Variant::Ci),
            _ => None,
        }
    }

    /// Cell sizes. Full: the paper's largest element, 7.0 m, is the cap; the core cell 1.3 m
    /// gives the paper's mesh size (171,562 hex8 and 186,563 nodes in the file, excavated
    /// rock and the interfaces' duplicated nodes included, against the paper's 171,432 and
    /// 189,187; docs/yingxiuwan.md, "Mesh"). CI: the far field coarser (cap 12 m), a
    /// smoke-and-physics model, not a converged one.
    pub fn density(self) -> Density {
        match self {
            Variant::Full => Density {
                h_core: 1.3,
                growth: 1.25,
                h_max: 7.0,
            },
            Variant::Ci => Density {
                h_core: 6.0,
                growth: 2.0,
                h_max: 12.0,
            },
        }
    }
}

/// The anti-seismic measures of paper §6, each a case variant (any combination).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Measures {
    /// A reinforced (grouted, stiffer and stronger) rock zone around the excavation.
    pub reinforced_rock: bool,
    /// Anchorage of the upper structure: bars through the arch and upper sidewall lining
    /// into the rock.
    pub upper_anchorage: bool,
    /// A soft isolation layer between the lower structure and the rock.
    pub isolation_layer: bool,
}

/// Thickness of the reinforced rock zone (m): beyond the 6 m system bolts.
pub const REINFORCED_ZONE: f64 = 8.0;

impl Measures {
    /// The names accepted by [`Measures::parse`].
    pub const NAMES: [&'static str; 3] = ["reinforced_rock", "upper_anchorage", "isolation_layer"];

    /// Parse a comma-separated list of measure names, "none" or "all".
    pub fn parse(s: &str) -> Option<Self> {
        let mut m = Measures::default();
        for name in s.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            match name {
                "none" => {}
                "all" => {
                    m = Measures {
                        reinforced_rock: true,
                        upper_anchorage: true,
                        isolation_layer: true,
                    }
                }
                "reinforced_rock" => m.reinforced_rock = true,
                "upper_anchorage" => m.upper_anchorage = true,
                "isolation_layer" => m.isolation_layer = true,
                _ => return None,
            }
        }
        Some(m)
    }

    /// File-name suffix: "" for the base case, else `_` and the measures joined by `+`.
    pub fn suffix(self) -> String {
        let names: Vec<&str> = [
            (self.reinforced_rock, "reinforced_rock"),
            (self.upper_anchorage, "upper_anchorage"),
            (self.isolation_layer, "isolation_layer"),
        ]
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, n)| *n)
        .collect();
        if names.is_empty() {
            String::new()
        } else {
            format!("_{}", names.join("+"))
        }
    }

    /// The rock zones these measures need in the mesh.
    pub fn zones(self) -> RockZones {
        RockZones {
            reinforced: self.reinforced_rock.then_some(REINFORCED_ZONE),
            isolation: self.isolation_layer,
        }
    }
}

/// The preset geometry (m). Paper: model 96.0 × 88.2 × 147.7 m, powerhouse 52.8 m long,
/// 17.0 m wide, 37.2 m high (§4.2); three units (§4.1). Everything else: docs/yingxiuwan.md.
pub fn geometry() -> CavernGeometry {
    CavernGeometry {
        model: [96.0, 88.2, 147.7],
        origin: [48.0, 17.7, 55.0],
        width: 17.0,
        length: 52.8,
        height: 37.2,
        arch_rise: 4.0,
        lining: 1.0,
        erection_bay: 10.8,
        units: 3,
        unit_spacing: 14.0,
        turbine_floor_bottom: 9.0,
        turbine_floor: 1.0,
        generator_floor_bottom: 16.0,
        generator_floor: 1.0,
        end_wall: 1.0,
        pedestal: 10.0,
        pit: 6.0,
        column_y: 2.0,
        corbel_bottom: 25.5,
        corbel_height: 2.0,
        corbel_depth: 2.5,
        tunnel_width: 4.0,
        tunnel_height: 5.0,
        tunnel_lining: 1.0,
        tunnel_length: 12.0,
    }
}

/// Lower levels of the excavation benches from the crown down (cavern frame): the top
/// heading to the corbel top, the bench to the generator floor bottom, the turbine layer,
/// the pits and the bottom.
pub fn benches() -> Vec<f64> {
    vec![27.5, 16.0, 9.0, f64::NEG_INFINITY]
}

/// Rock above the model's top (m): the ground surface lies this far above it (assumption,
/// docs/yingxiuwan.md: the crown is then 155.5 m deep).
pub const OVERBURDEN: f64 = 100.0;

/// Rock density (kg/m³) and the gravity used for the overburden's weight.
pub const ROCK_DENSITY: f64 = 2700.0;
pub const GRAVITY: f64 = 9.81;

/// Time settings the generator fills in once the model's stable step is known.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    /// Time step (s); `None`: the solver's default (safety × critical).
    pub dt: Option<f64>,
    /// Steps between two field outputs (0: only the last step).
    pub vtu_every: u64,
    /// Steps between two checkpoints.
    pub checkpoint_every: u64,
}

/// Duration of the seismic stage (s): the paper's 60 s (the 20–80 s window of Wolong).
pub const DURATION: f64 = 60.0;

/// Interval of the field outputs (s).
pub const FRAME_INTERVAL: f64 = 0.1;

/// Interval of the checkpoints (s).
pub const CHECKPOINT_INTERVAL: f64 = 5.0;

/// Interval of the anchor bars' frames of the full variant (s).
pub const ANCHORS_INTERVAL: f64 = 2.5;

impl Timing {
    /// Field outputs every [`FRAME_INTERVAL`] exactly and checkpoints every
    /// [`CHECKPOINT_INTERVAL`]: the step is the largest that divides the frame interval and
    /// does not exceed `stable_dt`.
    pub fn from_stable_step(stable_dt: f64) -> Self {
        let per_frame = (FRAME_INTERVAL / stable_dt).ceil().max(1.0) as u64;
        Timing {
            dt: Some(FRAME_INTERVAL / per_frame as f64),
            vtu_every: per_frame,
            checkpoint_every: per_frame * (CHECKPOINT_INTERVAL / FRAME_INTERVAL).round() as u64,
        }
    }

    /// Steps between two whole-mesh frames (`[output.frames] full_every`): every frame for
    /// the CI variant, whose few seconds the physics checks read frame by frame
    /// (reports/yingxiuwan_checks.py: the damage against the yield surface, the bolts
    /// against the rock's displacement, 31 frames of 7 MB for 3 s); every checkpoint
    /// interval for the full variant, whose 600 whole-mesh frames of ≈ 24 MB would exceed
    /// the issue's 3 GB for the run's outputs (13 frames instead).
    pub fn full_every(&self, variant: Variant) -> u64 {
        match variant {
            Variant::Ci => self.vtu_every,
            Variant::Full => self.checkpoint_every,
        }
    }

    /// Steps between two frames of the anchor bars (`[output.frames] anchors_every`): every
    /// frame for the CI variant, whose 3 s the anchor checks read frame by frame; every
    /// [`ANCHORS_INTERVAL`] for the full variant, whose ≈ 146,000 bars (mats in the lining
    /// and the inner structure, ties, crane-beam anchors, bolts) write at least ≈ 19 MB a
    /// frame at ≈ 129 bytes a segment (measured on the CI variant's frames: 5.0 MB for
    /// 38,730 segments; end points, connectivity and three Float64 fields in base64): ≥ 11 GB
    /// in 600 frames, beyond the issue's 3 GB for the run's outputs; 25 frames ≥ 0.5 GB
    /// (docs/yingxiuwan.md). A multiple of `vtu_every` by construction, and a divisor of the
    /// whole-mesh interval, so that every whole-mesh frame has its anchors frame.
    pub fn anchors_every(&self, variant: Variant) -> u64 {
        match variant {
            Variant::Ci => self.vtu_every,
            Variant::Full => self.vtu_every * (ANCHORS_INTERVAL / FRAME_INTERVAL).round() as u64,
        }
    }
}

/// What goes into the case file.
#[derive(Clone, Debug, PartialEq)]
pub struct CaseSpec {
    pub variant: Variant,
    pub measures: Measures,
    /// The Gmsh file, relative to the case file.
    pub mesh_file: String,
    pub timing: Timing,
    /// End time of the seismic stage (s).
    pub end: f64,
    /// How the critical step is bounded (`time.stable_step`).
    pub stable_step: crate::model::StepBound,
}

/// The case file of `spec`.
pub fn case_toml(spec: &CaseSpec) -> String {
    let geo = geometry();
    let m = spec.measures;
    let top = geo.model[2];
    let overburden_pressure = ROCK_DENSITY * GRAVITY * OVERBURDEN;
    let mut s = String::new();
    let measures = if spec.measures == Measures::default() {
        "base case".to_string()
    } else {
        spec.measures
            .suffix()
            .trim_start_matches('_')
            .replace('+', ", ")
    };
    s += &format!(
        r#"# Yingxiuwan underground powerhouse, {variant} variant, {measures} — written by
# `dcfm mesh yingxiuwan`. Paper: Yang, Chen & Xiao (2014) §4–6; every dimension and choice
# not in the paper: docs/yingxiuwan.md. Run: `dcfm run THIS_FILE`; post-processing:
# `dcfm post yingxiuwan RUN_DIR`.
title = "Yingxiuwan underground powerhouse ({variant} mesh, {measures})"

[time]
end = {end:?}
"#,
        variant = spec.variant.name(),
        end = spec.end,
    );
    if spec.stable_step != crate::model::StepBound::default() {
        s += &format!(
            "stable_step = \"{}\"      # docs/case_format.md\n",
            spec.stable_step.name()
        );
    }
    if let Some(dt) = spec.timing.dt {
        s += &format!("dt = {dt:e}                 # frames every {FRAME_INTERVAL} s exactly\n");
    }
    s += &format!(
        r#"
# Fields every {FRAME_INTERVAL} s, histories (energies, damaged volume per region, contact
# state areas, anchor forces) every step, a checkpoint every {CHECKPOINT_INTERVAL} s (`dcfm run --resume`).
[output]
vtu_every = {vtu}
history_every = 1
checkpoint_every = {ckpt}
damage_threshold = 0.1          # docs/plastic_damage.md §5
damaged_volume = "point"

# Compact frames (docs/outputs.md): case.pvd holds the concrete (its nodes carry the
# interfaces' contact fields) in Float32 every frame, anchors.pvd the bars' axial force
# per segment every {anchors_s} s, full.pvd the whole mesh (every field, Float64,
# zlib-compressed; full_encoding = "base64" for plain XML) every {full_s} s and at the end.
[output.frames]
regions = ["lining", "inner"]
full_every = {full}
anchors = true
anchors_every = {anchors_every}

# ---- Mesh: regions rock{zones} / lining / inner / excavated (the excavated volume, as rock,
# removed bench by bench in the static stage; the concrete overlaps it and is placed after).
# The interfaces' nodes are already duplicated: face sets lining-rock, rock-lining,
# inner-rock, rock-inner, lining-inner, inner-lining. Element sets: excavation_1 (crown) …
# excavation_4 (bottom), concrete_1 … concrete_4 (concrete by bench), the survey sets
# arch, upper_sidewalls, generator_floor, turbine_floor, pedestal_inner_wall,
# crane_beam_corbels, junctions (and pedestals, turbine_layer_columns,
# turbine_layer_walls, mass_concrete, tunnel_lining). Face sets: excavation (the rock
# surface), bolts_arch, bolts_upper_sidewalls (its parts behind the arch and upper
# sidewall lining), lining_face_arch, lining_face_upper_sidewalls, crane_beam_face (the
# corbels' vertical faces towards the cavern), lining_surface, inner_surface, xmin … zmax.
# ----------------------------------------------------------------------------------------
[mesh]
gmsh = "{mesh}"

# ---- Materials: Table 1 of the paper with the plastic-damage mapping of
# docs/plastic_damage.md §4; densities chosen in docs/yingxiuwan.md. ------------------
[materials.rock]
model = "plastic_damage"
young = 10.0e9
poisson = 0.25
density = {rho:?}
[materials.rock.plastic_damage]
ft0 = 1.97e6
cohesion = 2.18e6
friction_angle_deg = 41.6

[materials.concrete]
model = "plastic_damage"
young = 25.0e9
poisson = 0.17
density = 2450.0
[materials.concrete.plastic_damage]
ft0 = 1.30e6
cohesion = 2.0e6
friction_angle_deg = 46.0
# The consistent stiffness recovery (docs/plastic_damage.md §7): with eq. (24)'s rule the
# cracked lining self-excites with no input at all (docs/yingxiuwan.md, status).
recovery = "consistent"
"#,
        vtu = spec.timing.vtu_every,
        ckpt = spec.timing.checkpoint_every,
        full = spec.timing.full_every(spec.variant),
        anchors_every = spec.timing.anchors_every(spec.variant),
        anchors_s = match spec.variant {
            Variant::Ci => FRAME_INTERVAL,
            Variant::Full => ANCHORS_INTERVAL,
        },
        full_s = match spec.variant {
            Variant::Ci => FRAME_INTERVAL,
            Variant::Full => CHECKPOINT_INTERVAL,
        },
        zones = match (m.reinforced_rock, m.isolation_layer) {
            (false, false) => "",
            (true, false) => " / rock_reinforced",
            (false, true) => " / rock_isolation",
            (true, true) => " / rock_reinforced / rock_isolation",
        },
        mesh = spec.mesh_file,
        rho = ROCK_DENSITY,
    );
    if m.reinforced_rock {
        s += &format!(
            r#"
# Measure: reinforced rock within {REINFORCED_ZONE} m of the excavation (consolidation grouting
# and bolting): modulus +50 %, cohesion and tensile strength +20 % (docs/yingxiuwan.md).
[materials.rock_reinforced]
model = "plastic_damage"
young = 15.0e9
poisson = 0.25
density = {ROCK_DENSITY:?}
[materials.rock_reinforced.plastic_damage]
ft0 = 2.364e6
cohesion = 2.616e6
friction_angle_deg = 41.6
"#
        );
    }
    if m.isolation_layer {
        s += r#"
# Measure: a soft isolation layer (one cell of the rock around the lower structure):
# elastic, E = 1 GPa (a 0.1 m layer of E ≈ 85 MPa spread over the ≈ 1.2 m cell of the full
# mesh has the same stiffness per area; docs/yingxiuwan.md).
[materials.isolation]
model = "elastic"
young = 1.0e9
poisson = 0.3
density = 1800.0
"#;
    }
    s += r#"
# Rock: one-point integration with hourglass control (the paper's mesh size); concrete:
# full 2×2×2 (thin members bend). Rayleigh damping α = 0.6 1/s (5 % at 1 Hz, 1.6 % at
# 3 Hz; mass-proportional only, so the step is not reduced); the free field follows it.
[[regions]]
name = "rock"
material = "rock"
integration = "one_point"
damping = { alpha = 0.6 }
"#;
    if m.reinforced_rock {
        s += r#"
[[regions]]
name = "rock_reinforced"
material = "rock_reinforced"
integration = "one_point"
damping = { alpha = 0.6 }
"#;
    }
    if m.isolation_layer {
        s += r#"
[[regions]]
name = "rock_isolation"
material = "isolation"
integration = "one_point"
damping = { alpha = 0.6 }
"#;
    }
    s += r#"
[[regions]]
name = "lining"
material = "concrete"
integration = "full"
damping = { alpha = 0.6 }

[[regions]]
name = "inner"
material = "concrete"
integration = "full"
damping = { alpha = 0.6 }

[[regions]]
name = "excavated"
material = "rock"
integration = "one_point"
damping = { alpha = 0.6 }

# ---- Interfaces (dynamic contact force method, paper §2): concrete on rock and the
# lining on the inner structure; friction and cohesion chosen in docs/yingxiuwan.md. ---
[[interfaces]]
name = "lining_rock"
surface_a = "lining-rock"
surface_b = "rock-lining"
mu_s = 1.0
mu_d = 0.7
cohesion = 0.9e6

[[interfaces]]
name = "inner_rock"
surface_a = "inner-rock"
surface_b = "rock-inner"
mu_s = 1.0
mu_d = 0.7
cohesion = 0.9e6

[[interfaces]]
name = "lining_inner"
surface_a = "lining-inner"
surface_b = "inner-lining"
mu_s = 1.0
mu_d = 0.75
cohesion = 1.0e6

# ---- Rock bolts (docs/anchors.md; typical Chinese practice for powerhouse caverns,
# docs/yingxiuwan.md): fully grouted φ25 HRB335 bars at 1.5 m × 1.5 m, 6 m in the arch,
# 5 m in the upper sidewalls, from the excavated rock surface into the rock. Installed
# when the seismic stage starts (in the static stage's final configuration). -----------
[[anchors.patterns]]
name = "bolts_arch"
face_set = "bolts_arch"
length = 6.0
spacing = 1.5
diameter = 0.025
young = 200e9
yield_stress = 335e6

[[anchors.patterns]]
name = "bolts_upper_sidewalls"
face_set = "bolts_upper_sidewalls"
length = 5.0
spacing = 1.5
diameter = 0.025
young = 200e9
yield_stress = 335e6

# Reinforcement of the lining (paper §3: steel bars embedded in the concrete, their
# stiffness superposed on its elements; docs/anchors.md "Mats"): two-way mats of φ25 HRB335
# bars at 0.2 m under both faces of the arch, the sidewall lining, the corbels and the
# tunnel linings — the free faces (lining_surface) and those on the rock (lining-rock) —
# with 0.06 m from the face to the bars' axes (50 mm clear cover). -------------------------
[[anchors.mats]]
name = "lining_mat_inner"
face_set = "lining_surface"
cover = 0.06
spacing = 0.2
diameter = 0.025
young = 200e9
yield_stress = 335e6

[[anchors.mats]]
name = "lining_mat_outer"
face_set = "lining-rock"
cover = 0.06
spacing = 0.2
diameter = 0.025
young = 200e9
yield_stress = 335e6

# Ties between the lining's two mats (the through-thickness bars of a wall with two
# layers of reinforcement): φ12 HPB300 at 0.6 m × 0.6 m from the inner mat (0.06 m below
# the free face) to the outer one (0.06 m from the rock), 0.88 m across the 1.0 m lining.
# The mats lie parallel to the faces and cross no crack parallel to them: without ties a
# fully cracked 1 m element opens through the thickness (docs/yingxiuwan.md). -----------
[[anchors.patterns]]
name = "lining_ties"
face_set = "lining_surface"
depth = 0.06
length = 0.88
spacing = 0.6
diameter = 0.012
young = 200e9
yield_stress = 300e6

# Rock-anchored crane beams (typical Chinese practice for powerhouse caverns of the period,
# docs/yingxiuwan.md): the beam and its corbel tied to the rock wall by fully grouted φ36
# HRB400 anchors at 0.75 m × 0.75 m, 12 m long from the beam's face through the corbel
# (2.5 m), the lining (1 m) and 8.5 m into the rock. Without them the plain-concrete
# corbel hangs on the lining alone and falls once its root cracks through. --------------
[[anchors.patterns]]
name = "anchors_crane_beam"
face_set = "crane_beam_face"
length = 12.0
spacing = 0.75
diameter = 0.036
young = 200e9
yield_stress = 400e6

# The inner structure (floors, pedestals, walls, columns, mass concrete) is reinforced
# concrete too: the same mats under its free faces (inner_surface) and its faces on the
# rock (inner-rock). Without them the plain-concrete generator floor's mid-span falls from
# ≈ 6.1 s of the Wolong-like input (docs/yingxiuwan.md, "Status of the case"). ---------
[[anchors.mats]]
name = "inner_mat_free"
face_set = "inner_surface"
cover = 0.06
spacing = 0.2
diameter = 0.025
young = 200e9
yield_stress = 335e6

[[anchors.mats]]
name = "inner_mat_rock"
face_set = "inner-rock"
cover = 0.06
spacing = 0.2
diameter = 0.025
young = 200e9
yield_stress = 335e6

# Ties in the inner structure, as in the lining: φ12 HPB300 at 0.6 m × 0.6 m from 0.06 m
# below each free face, 0.88 m inwards. Its floors and walls are 1.0 m thick (docs/
# yingxiuwan.md), so a tie ends 0.06 m short of the opposite face; a 1 m member with two
# free faces gets them from both (twice the ties across a crack parallel to its faces);
# in the 2 m pedestal walls and the mass concrete they reach 0.94 m in. Without them the
# generator floor opens through its thickness between its mats after ≈ 9 s of the
# Wolong-like input and its underside falls (docs/yingxiuwan.md). ----------------------
[[anchors.patterns]]
name = "inner_ties"
face_set = "inner_surface"
depth = 0.06
length = 0.88
spacing = 0.6
diameter = 0.012
young = 200e9
yield_stress = 300e6
"#;
    if m.upper_anchorage {
        s += r#"
# Measure: anchorage of the upper structure — φ32 HRB400 bars at 1.5 m × 1.5 m from the
# lining's inner face through the lining (1 m) and 7 m into the rock, tying the arch and
# the upper sidewall lining to the rock across the interface.
[[anchors.patterns]]
name = "anchorage_arch"
face_set = "lining_face_arch"
length = 8.0
spacing = 1.5
diameter = 0.032
young = 200e9
yield_stress = 400e6

[[anchors.patterns]]
name = "anchorage_upper_sidewalls"
face_set = "lining_face_upper_sidewalls"
length = 8.0
spacing = 1.5
diameter = 0.032
young = 200e9
yield_stress = 400e6
"#;
    }
    s += &format!(
        r#"
[loads.gravity]
acceleration = [0.0, 0.0, -{GRAVITY}]

# ---- Seismic stage (paper §4.4–4.5): viscous-spring base through which the input enters,
# free-field sides, the model's top {OVERBURDEN} m below the ground surface coupled to the free
# field (columns and walls continue through the overburden). Input: the Wolong-like
# synthetic preset (docs/motion.md) as rock-outcrop motion, x = EW, y = NS, z = UD; any
# record in a standard format replaces it (change [motions.wolong]). --------------------
[motions.wolong]
synthetic = {{ preset = "wolong", seed = 1 }}

[[boundary.absorbing]]
set = "outer.zmin"
kind = "viscous_spring"
input = true

[boundary.free_field]
sides = ["outer.xmin", "outer.xmax", "outer.ymin", "outer.ymax"]
top = "outer.zmax"

[seismic]
quantity = "acceleration"
definition = "outcrop"
x = {{ type = "motion", motion = "wolong", component = "x" }}
y = {{ type = "motion", motion = "wolong", component = "y" }}
z = {{ type = "motion", motion = "wolong", component = "z" }}

[[seismic.overburden]]
thickness = {OVERBURDEN:?}
material = "rock"

# ---- Static stage (paper §4.6: excavation and concrete before the earthquake): K0 = 1
# in-situ stress below the ground surface at z = {surface} m (the overburden's weight on the
# model's top), excavation in four benches from the crown down, the arch lining cast after
# the top heading (arch-first method), the rest of the concrete after the last bench.
# Rollers on the sides, fixed base; dynamic relaxation where the rock yields. ----------
[static]
solver = "relaxation"
tolerance = 1e-4
max_iterations = 200000

[[static.fixed]]
set = "outer.zmin"
dofs = "xyz"
[[static.fixed]]
set = "outer.xmin"
dofs = "x"
[[static.fixed]]
set = "outer.xmax"
dofs = "x"
[[static.fixed]]
set = "outer.ymin"
dofs = "y"
[[static.fixed]]
set = "outer.ymax"
dofs = "y"

[[static.loads]]
set = "outer.zmax"
pressure = {p:e}            # ρ g × {OVERBURDEN} m

[static.in_situ]
method = "k0"
solver = "direct"
ground_surface = {surface:?}
k0 = 1.0

[[static.steps]]
name = "top heading"
excavate = ["excavation_1"]

[[static.steps]]
name = "arch lining"
activate = ["concrete_1"]

[[static.steps]]
name = "bench 2 (to the generator floor)"
excavate = ["excavation_2"]

[[static.steps]]
name = "bench 3 (turbine layer)"
excavate = ["excavation_3"]

[[static.steps]]
name = "bench 4 (pits and bottom)"
excavate = ["excavation_4"]

[[static.steps]]
name = "sidewall lining, corbels, tunnel linings, inner structure"
activate = ["concrete_2", "concrete_3", "concrete_4"]
"#,
        surface = top + OVERBURDEN,
        p = overburden_pressure,
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generators::cavern::generate;
    use crate::mesh::hex8_shape::check_jacobian;

    /// The arch lining is one lining thick normal to its surfaces everywhere: the inner
    /// arch is the circle concentric with the excavated one, `lining` inside it, and it
    /// meets the sidewall lining's face 0.3697 m below the springline (the closed form for
    /// a 17.0 m span rising 4.0 m: R = (8.5² + 4²)/8 = 11.03125 m, the inner circle of
    /// radius R − 1 at |x| = 7.5 m, √(10.03125² − 7.5²) − (R − 4) = −0.36972 m).
    #[test]
    fn arch_lining_inner_face_is_concentric_one_lining_inside() {
        let geo = geometry();
        let c = geo.half_width();
        let f = geo.arch_rise;
        let radius = (c * c + f * f) / (2.0 * f);
        let centre = geo.springline() + f - radius;
        for i in 0..=30 {
            let x = (c - geo.lining) * i as f64 / 30.0;
            let outer = ((geo.outer_arch(x) - centre).powi(2) + x * x).sqrt();
            let inner = ((geo.inner_arch(x) - centre).powi(2) + x * x).sqrt();
            assert!(
                (outer - radius).abs() < 1e-9,
                "outer arch off its circle at x = {x}"
            );
            assert!(
                (outer - inner - geo.lining).abs() < 1e-9,
                "arch lining {} m thick at x = {x}, expected {}",
                outer - inner,
                geo.lining
            );
        }
        let drop = geo.springline() - geo.inner_springing();
        assert!(
            (drop - 0.3697).abs() < 1e-4,
            "inner springing {drop} m below the springline"
        );
    }

    /// The CI variant: every element valid, all sets present, sizes within the variant's
    /// cap, the paper's outer dimensions, the three interfaces, the survey sets where they
    /// belong, the excavated volume meshed and overlapped by the concrete.
    #[test]
    fn ci_variant_is_valid_and_complete() {
        let geo = geometry();
        let d = Variant::Ci.density();
        let model = generate(&geo, &d, &benches(), &RockZones::default()).unwrap();
        let m = &model.mesh;
        for e in 0..m.n_elements() {
            check_jacobian(&m.element_coords(e)).unwrap();
        }
        let q = &model.quality;
        assert!(q.max_edge <= d.h_max + 1e-9, "{q:?}");
        assert!(q.min_scaled_jacobian > 0.3, "{q:?}");
        for dim in 0..3 {
            let lo = m
                .coords
                .iter()
                .map(|x| x[dim])
                .fold(f64::INFINITY, f64::min);
            let hi = m
                .coords
                .iter()
                .map(|x| x[dim])
                .fold(-f64::INFINITY, f64::max);
            assert!(
                lo.abs() < 1e-9 && (hi - geo.model[dim]).abs() < 1e-9,
                "axis {dim}: {lo}..{hi}"
            );
        }
        for name in [
            "xmin",
            "xmax",
            "ymin",
            "ymax",
            "zmin",
            "zmax",
            "excavation",
            "bolts_arch",
            "bolts_upper_sidewalls",
            "lining_face_arch",
            "lining_face_upper_sidewalls",
            "crane_beam_face",
            "lining-rock",
            "rock-lining",
            "inner-rock",
            "rock-inner",
            "lining-inner",
            "inner-lining",
        ] {
            assert!(!m.face_sets[name].is_empty(), "{name}");
        }
        // Benches: excavated rock and concrete, every concrete element in one bench set.
        let mut concrete: Vec<u32> = Vec::new();
        for b in 1..=4 {
            assert!(
                !m.element_sets[&format!("excavation_{b}")].is_empty(),
                "{b}"
            );
            concrete.extend(&m.element_sets[&format!("concrete_{b}")]);
        }
        concrete.sort_unstable();
        let mut all: Vec<u32> = m.element_sets["lining"].clone();
        all.extend(&m.element_sets["inner"]);
        all.sort_unstable();
        assert_eq!(concrete, all);
        // Every concrete element overlaps an excavated one (same corners).
        let corners = |e: u32| {
            let mut c: Vec<[i64; 3]> = m
                .element_coords(e as usize)
                .iter()
                .map(|p| p.map(|v| (v * 1e6).round() as i64))
                .collect();
            c.sort_unstable();
            c
        };
        let excavated: std::collections::HashSet<Vec<[i64; 3]>> = m.element_sets["excavated"]
            .iter()
            .map(|&e| corners(e))
            .collect();
        assert!(concrete.iter().all(|&e| excavated.contains(&corners(e))));
        // The excavation sets from the crown down: bench 1 lies above bench 2, etc.
        let zc = |e: u32| {
            m.element_coords(e as usize)
                .iter()
                .map(|p| p[2])
                .sum::<f64>()
                / 8.0
                - geo.origin[2]
        };
        let levels = benches();
        for b in 1..=4 {
            for &e in &m.element_sets[&format!("excavation_{b}")] {
                let z = zc(e);
                assert!(z >= levels[b - 1] - 1e-9, "bench {b}: {z}");
                if b > 1 {
                    assert!(z < levels[b - 2], "bench {b}: {z}");
                }
            }
        }
        // The survey sets lie where the geometry puts them (cavern frame).
        let centre = |e: u32| {
            let x = m.element_coords(e as usize);
            let mut c = [0.0; 3];
            for p in x {
                for dim in 0..3 {
                    c[dim] += 0.125 * (p[dim] - geo.origin[dim]);
                }
            }
            c
        };
        for &e in &m.element_sets["arch"] {
            assert!(
                centre(e)[2] > geo.springline() - geo.lining,
                "arch element {e}"
            );
        }
        // The crane beams' faces (the start of their anchors): corbel elements, every node
        // on the plane |x| = half width − lining − corbel depth within the corbel's height,
        // both walls along the whole length (2 × height × length of face area).
        let corbels = &m.element_sets["crane_beam_corbels"];
        let beam_face = |x: f64| geo.half_width() - geo.lining - geo.corbel_depth - x.abs();
        let mut area = 0.0;
        for f in &m.face_sets["crane_beam_face"] {
            assert!(corbels.binary_search(&f.element).is_ok(), "{f:?}");
            let p: Vec<[f64; 3]> = m
                .face_nodes(*f)
                .iter()
                .map(|&n| std::array::from_fn(|d| m.coords[n as usize][d] - geo.origin[d]))
                .collect();
            for q in &p {
                assert!(beam_face(q[0]).abs() < 1e-9, "{f:?} node at {q:?}");
                assert!(
                    q[2] > geo.corbel_bottom - 1e-9
                        && q[2] < geo.corbel_bottom + geo.corbel_height + 1e-9,
                    "{f:?} node at {q:?}"
                );
            }
            let (dy, dz) = (
                p.iter().map(|q| q[1]).fold(f64::NEG_INFINITY, f64::max)
                    - p.iter().map(|q| q[1]).fold(f64::INFINITY, f64::min),
                p.iter().map(|q| q[2]).fold(f64::NEG_INFINITY, f64::max)
                    - p.iter().map(|q| q[2]).fold(f64::INFINITY, f64::min),
            );
            area += dy * dz;
        }
        let expected = 2.0 * geo.corbel_height * geo.length;
        assert!(
            (area - expected).abs() < 1e-6 * expected,
            "{area} m² of crane-beam face, expected {expected}"
        );
        // No concrete above the excavated crown.
        for &e in &all {
            let c = centre(e);
            assert!(c[2] < geo.outer_arch(c[0]), "concrete element {e} at {c:?}");
        }
        for &e in &m.element_sets["generator_floor"] {
            let z = centre(e)[2];
            assert!(z > 16.0 && z < 17.0, "generator floor element {e} at {z}");
        }
        for &e in &m.element_sets["junctions"] {
            assert!(
                centre(e)[0] > geo.half_width() - geo.lining - 1e-9,
                "junction element {e}"
            );
        }
        // Concrete shares no node with the rock or with the excavated rock (interfaces and
        // overlap), the excavated rock shares its boundary with the rock.
        let rock = m.nodes_of("rock").unwrap();
        let exc = m.nodes_of("excavated").unwrap();
        for concrete in ["lining", "inner"] {
            let nodes = m.nodes_of(concrete).unwrap();
            assert!(
                nodes
                    .iter()
                    .all(|n| rock.binary_search(n).is_err() && exc.binary_search(n).is_err()),
                "{concrete}"
            );
        }
        assert!(exc.iter().any(|n| rock.binary_search(n).is_ok()));
    }

    /// The measures' zones: the reinforced zone surrounds the excavation (all concrete
    /// touches reinforced rock only), the isolation layer wraps the inner structure.
    #[test]
    fn measure_zones_wrap_the_concrete() {
        let geo = geometry();
        let all = Measures::parse("all").unwrap();
        assert_eq!(
            all.suffix(),
            "_reinforced_rock+upper_anchorage+isolation_layer"
        );
        assert_eq!(Measures::parse("bogus"), None);
        let model = generate(&geo, &Variant::Ci.density(), &benches(), &all.zones()).unwrap();
        let m = &model.mesh;
        let region_of_face = |f: &crate::mesh::Face| {
            m.region_names[m.element_region[f.element as usize] as usize].as_str()
        };
        let inner_side: Vec<&str> = m.face_sets["rock-inner"]
            .iter()
            .map(region_of_face)
            .collect();
        assert!(
            inner_side.iter().all(|r| *r == "rock_isolation"),
            "{inner_side:?}"
        );
        // Plain rock behind the lining: name the first such face's cell, its centre
        // (cavern frame) and its distance to the excavation.
        let plain: Vec<String> = m.face_sets["rock-lining"]
            .iter()
            .filter(|f| region_of_face(f) == "rock")
            .map(|f| {
                let x = m.element_coords(f.element as usize);
                let c: [f64; 3] = std::array::from_fn(|d| {
                    x.iter().map(|p| p[d]).sum::<f64>() / 8.0 - geo.origin[d]
                });
                let corners: Vec<[f64; 3]> = x
                    .iter()
                    .map(|p| std::array::from_fn(|d| p[d] - geo.origin[d]))
                    .collect();
                format!(
                    "element {} face {} at {c:.2?} ({:.2} m from the excavation), corners {corners:.2?}",
                    f.element,
                    f.local,
                    geo.distance_to_excavation(c[0], c[1], c[2])
                )
            })
            .collect();
        assert!(
            plain.is_empty(),
            "{} plain rock faces behind the lining, first {:?}",
            plain.len(),
            plain.first()
        );
    }

    #[test]
    fn timing_divides_the_frame_interval() {
        let t = Timing::from_stable_step(1.3e-4);
        let dt = t.dt.unwrap();
        assert!(dt <= 1.3e-4);
        assert!((dt * t.vtu_every as f64 - FRAME_INTERVAL).abs() < 1e-15);
        assert_eq!(t.checkpoint_every, 50 * t.vtu_every);
        // Whole-mesh frames: every frame for CI, every checkpoint for the full variant.
        assert_eq!(t.full_every(Variant::Ci), t.vtu_every);
        assert_eq!(t.full_every(Variant::Full), t.checkpoint_every);
        // Anchor frames: every frame for CI, every 2.5 s (25 frames) for the full variant,
        // which divides the whole-mesh interval.
        assert_eq!(t.anchors_every(Variant::Ci), t.vtu_every);
        assert_eq!(t.anchors_every(Variant::Full), 25 * t.vtu_every);
        assert_eq!(
            t.full_every(Variant::Full) % t.anchors_every(Variant::Full),
            0
        );
    }
}
