//! The assembled model: mesh, element groups, masses, constraints, loads, damping and the
//! stable time step — everything the stages need, built once and validated.

use crate::boundary::Constraints;
use crate::element::colouring::colour_elements;
use crate::element::groups::ElementGroup;
use crate::element::lumped_mass::element_masses;
use crate::element::Integration;
use crate::error::{DcfmError, Result};
use crate::load::{Gravity, NodalLoad};
use crate::material::Material;
use crate::mesh::Mesh;

/// How one region is discretised.
#[derive(Clone, Debug)]
pub struct RegionSetup {
    /// Region name (as in the mesh).
    pub region: String,
    /// Its constitutive model.
    pub material: Material,
    /// Its integration rule.
    pub integration: Integration,
    /// Hourglass coefficient ε_hg (one-point elements).
    pub hourglass: f64,
}

/// Rayleigh damping C = αM + βK0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rayleigh {
    /// Mass-proportional coefficient α (1/s).
    pub alpha: f64,
    /// Stiffness-proportional coefficient β (s).
    pub beta: f64,
}

/// How the critical step is bounded (`time.stable_step`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum StepBound {
    /// Each element with its own lumped masses: min over the elements of their own steps
    /// (the default).
    #[default]
    Element,
    /// The nodal masses shared among the elements by balanced weights
    /// (`element::shared_mass_step`): still a bound, larger where small elements sit
    /// among larger ones.
    SharedMass,
}

impl StepBound {
    /// What a case or command line may give, with what each means (for errors).
    pub const CHOICES: &'static str = "\"element\" (each element with its own lumped masses) or \
         \"shared_mass\" (the nodal masses shared among the elements)";

    /// The bound named `name` (`time.stable_step`, `--stable-step`), if there is one.
    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "element" => Some(Self::Element),
            "shared_mass" => Some(Self::SharedMass),
            _ => None,
        }
    }

    /// The name [`StepBound::parse`] reads back.
    pub fn name(self) -> &'static str {
        match self {
            Self::Element => "element",
            Self::SharedMass => "shared_mass",
        }
    }
}

/// The stable time step and the element that limits it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StableStep {
    /// min_e min(L_e / c_p,e, 2/ω_max,e) (s), without safety factor.
    pub critical: f64,
    /// Limiting element (global id).
    pub element: usize,
    /// Its effective length c_p · Δt_e (m): V/A_max, or less where the element's own
    /// eigenvalue bound governs.
    pub length: f64,
    /// Its P-wave speed (m/s).
    pub speed: f64,
}

/// The own step of every element of the mesh, min(L_e/c_p, 2/ω_max,e) (global element
/// order), the eigenvalue computed once per distinct element shape (structured meshes
/// repeat a few shapes).
fn element_steps(
    mesh: &Mesh,
    groups: &[ElementGroup],
    regions: &[RegionSetup],
) -> Result<Vec<f64>> {
    use crate::element::stable_step::element_max_eigenvalue;
    let mut steps = vec![f64::INFINITY; mesh.n_elements()];
    for g in groups {
        let c = g.material.elastic().p_wave_speed();
        let hourglass = regions
            .iter()
            .find(|s| s.region == g.name)
            .map_or(0.0, |s| s.hourglass);
        let mut cache: std::collections::HashMap<[i64; 24], f64> = std::collections::HashMap::new();
        for (le, &l) in g.char_length.iter().enumerate() {
            let e = g.elements[le] as usize;
            let x = mesh.element_coords(e);
            // Shape key: coordinates relative to node 0, quantised at 1e-9 of the length.
            let key: [i64; 24] = std::array::from_fn(|k| {
                let (a, d) = (k / 3, k % 3);
                ((x[a][d] - x[0][d]) / (l * 1e-9)).round() as i64
            });
            let omega2 = match cache.get(&key) {
                Some(&w) => w,
                None => {
                    let w = element_max_eigenvalue(&x, &g.material, g.integration, hourglass)
                        .ok_or_else(|| DcfmError::BadElement {
                            element: e,
                            reason: "no positive stiffness eigenvalue (degenerate)".into(),
                        })?;
                    cache.insert(key, w);
                    w
                }
            };
            steps[e] = (l / c).min(2.0 / omega2.sqrt());
        }
    }
    Ok(steps)
}

/// The model.
#[derive(Debug)]
pub struct Model {
    pub mesh: Mesh,
    pub groups: Vec<ElementGroup>,
    pub n_colours: usize,
    /// Lumped nodal masses (kg).
    pub mass: Vec<f64>,
    /// 1/M per node, 0 where all three DOFs are constrained (infinite mass for contact).
    pub inv_mass: Vec<f64>,
    pub constraints: Constraints,
    pub nodal_loads: Vec<NodalLoad>,
    pub gravity: Option<Gravity>,
    /// Rayleigh damping of every region without its own.
    pub damping: Rayleigh,
    /// Regions with their own Rayleigh damping (by region name).
    pub region_damping: std::collections::BTreeMap<String, Rayleigh>,
    /// Initial velocities: (nodes, value).
    pub initial_velocity: Vec<(Vec<u32>, [f64; 3])>,
    pub stable: StableStep,
    /// (group, index in group) of every element.
    pub element_location: Vec<(u32, u32)>,
    /// Contact interfaces (dynamic contact force method), if any.
    pub contact: Option<crate::contact::ContactSystem>,
    /// Absorbing and free-field boundaries and the seismic input, if any.
    pub boundaries: Option<crate::boundary::BoundarySystem>,
    /// Anchor bars superposed on their host elements, if any.
    pub anchors: Option<crate::element::anchor_bar::AnchorBars>,
    /// Own step min(L_e/c_p, 2/ω_max,e) of every element (s), global element order: what
    /// [`Model::refresh_stable_step`] takes the minimum of.
    pub element_steps: Vec<f64>,
    /// Stiffness added on top of the elements (anchor bars), as a bound on its ω²
    /// (`Model::include_extra_stiffness`), folded into `stable` whenever it is recomputed.
    pub extra_omega_squared: f64,
    /// Region names in the order of the case's `[[regions]]` (the order of the setups
    /// given to [`Model::new`]): the numbering of the `region` field of the outputs
    /// (`Model::region_number`), whose names the VTU files carry (docs/outputs.md).
    pub region_names: Vec<String>,
    /// Density factor of every element from `time.mass_scaling` (global element order;
    /// empty without mass scaling: every factor 1), see `crate::mass_scaling`.
    pub mass_factor: Vec<f64>,
    /// What the mass scaling did, if the case asked for it.
    pub mass_scaling: Option<crate::mass_scaling::MassScalingSummary>,
    /// How the critical step is bounded (`time.stable_step`).
    pub step_bound: StepBound,
}

impl Model {
    /// Assemble a model. Every region of the mesh must have a setup; every node must belong
    /// to an element.
    pub fn new(mesh: Mesh, regions: &[RegionSetup], file: &str) -> Result<Self> {
        mesh.validate()?;
        let colours = colour_elements(&mesh.elements, mesh.n_nodes());
        let n_colours = colours.iter().copied().max().map_or(0, |c| c as usize + 1);
        let mut groups = Vec::new();
        for (r, name) in mesh.region_names.iter().enumerate() {
            let Some(setup) = regions.iter().find(|s| &s.region == name) else {
                return Err(DcfmError::invalid(
                    file,
                    "regions",
                    name,
                    "every mesh region needs a [[regions]] entry naming its material",
                ));
            };
            if !(setup.hourglass.is_finite() && (0.0..=0.5).contains(&setup.hourglass)) {
                return Err(DcfmError::invalid(
                    file,
                    format!("regions.{name}.hourglass"),
                    setup.hourglass,
                    "must be in [0, 0.5]",
                ));
            }
            groups.push(ElementGroup::new(
                &mesh,
                r,
                setup.material.clone(),
                setup.integration,
                setup.hourglass,
                &colours,
            )?);
        }
        for s in regions {
            if mesh.region_index(&s.region).is_none() {
                return Err(DcfmError::invalid(
                    file,
                    "regions",
                    &s.region,
                    format!(
                        "no such region in the mesh (regions: {:?})",
                        mesh.region_names
                    ),
                ));
            }
        }
        let mut element_location = vec![(0, 0); mesh.n_elements()];
        for (gi, g) in groups.iter().enumerate() {
            for (le, &e) in g.elements.iter().enumerate() {
                element_location[e as usize] = (gi as u32, le as u32);
            }
        }
        let n = mesh.n_nodes();
        let mut region_names: Vec<String> = Vec::with_capacity(regions.len());
        for s in regions {
            if !region_names.contains(&s.region) {
                region_names.push(s.region.clone());
            }
        }
        let mut model = Self {
            region_names,
            contact: None,
            boundaries: None,
            anchors: None,
            element_location,
            mesh,
            groups,
            n_colours,
            inv_mass: Vec::new(),
            mass: Vec::new(),
            constraints: Constraints::new(n),
            nodal_loads: Vec::new(),
            gravity: None,
            damping: Rayleigh::default(),
            region_damping: std::collections::BTreeMap::new(),
            initial_velocity: Vec::new(),
            stable: StableStep {
                critical: f64::INFINITY,
                element: 0,
                length: 0.0,
                speed: 0.0,
            },
            element_steps: Vec::new(),
            extra_omega_squared: 0.0,
            mass_factor: Vec::new(),
            mass_scaling: None,
            step_bound: StepBound::Element,
        };
        model.mass = model.lumped_masses();
        if let Some(n) = model.mass.iter().position(|&m| m.is_nan() || m <= 0.0) {
            return Err(DcfmError::Mesh(format!(
                "node {n} belongs to no element (zero mass)"
            )));
        }
        model.inv_mass = model.mass.iter().map(|m| 1.0 / m).collect();
        model.element_steps = element_steps(&model.mesh, &model.groups, regions)?;
        model.refresh_stable_step();
        Ok(model)
    }

    /// Whether every node of element `e` has all three DOFs fixed or prescribed: such an
    /// element (a driven base, a belt) moves as it is told, its stiffness acts only
    /// between constrained DOFs and it has no dynamics of its own.
    pub fn element_fully_prescribed(&self, e: usize) -> bool {
        self.mesh.elements[e]
            .iter()
            .all(|&n| self.constraints.constrained[n as usize] & 0b111 == 0b111)
    }

    /// Recompute the stable step from the elements that move, once the constraints are
    /// known: the minimum of the elements' own steps over the elements of the groups with
    /// at least one free DOF — a fully prescribed element
    /// ([`Model::element_fully_prescribed`]) adds no stiffness to the equations of the
    /// free DOFs and does not shrink the step; a partly prescribed one keeps its own step
    /// (its stiffness on the free DOFs is a principal submatrix of its stiffness, whose
    /// largest eigenvalue is at most the element's). When every element is fully
    /// prescribed the minimum over all of them is kept. The anchors' stiffness
    /// (`extra_omega_squared`) is folded in afterwards.
    pub fn refresh_stable_step(&mut self) {
        self.stable = self.stable_step_now();
    }

    /// The stable step of [`Model::refresh_stable_step`] for the current constraints and
    /// groups, without storing it (a stage with its own supports, the static relaxation).
    pub fn stable_step_now(&self) -> StableStep {
        let mut stable = StableStep {
            critical: f64::INFINITY,
            element: 0,
            length: 0.0,
            speed: 0.0,
        };
        for (g, e) in self.moving_elements() {
            let dt = self.element_steps[e];
            if dt < stable.critical {
                // The length that gives this step at the P-wave speed.
                let c = self.groups[g].material.elastic().p_wave_speed();
                stable = StableStep {
                    critical: dt,
                    element: e,
                    length: dt * c,
                    speed: c,
                };
            }
        }
        if self.step_bound == StepBound::SharedMass {
            self.shared_mass_step(&mut stable);
        }
        let folded = self.fold_extra_stiffness(stable.critical);
        if folded != stable.critical {
            stable.critical = folded;
            stable.length = folded * stable.speed;
        }
        stable
    }

    /// Replace the elements' own bound in `stable` by the shared-mass bound
    /// (`element::shared_mass_step`) over the same elements, with the model's nodal masses
    /// (anchor steel included) and free DOFs; kept only where it is the larger step.
    fn shared_mass_step(&self, stable: &mut StableStep) {
        use crate::element::shared_mass_step::{shared_mass_bound, SharedElement};
        let moving = self.moving_elements();
        let elements: Vec<SharedElement> = moving
            .iter()
            .map(|&(g, e)| {
                let x = self.mesh.element_coords(e);
                let rho = self.groups[g].material.density() * self.mass_factor_of(e);
                SharedElement {
                    conn: self.mesh.elements[e],
                    own_mass: crate::element::lumped_mass::element_masses(&x, rho),
                    own_bound: (2.0 / self.element_steps[e]).powi(2),
                }
            })
            .collect();
        let free: Vec<u8> = self
            .constraints
            .constrained
            .iter()
            .map(|&c| !c & 0b111)
            .collect();
        let stiffness = |i: usize| {
            let (g, e) = moving[i];
            self.groups[g].element_stiffness(self.element_location[e].1 as usize)
        };
        let bound = shared_mass_bound(&elements, &self.mass, &free, stiffness);
        let dt = 2.0 / bound.omega_squared.sqrt();
        if dt > stable.critical {
            let (g, e) = moving[bound.element];
            let c = self.groups[g].material.elastic().p_wave_speed();
            *stable = StableStep {
                critical: dt,
                element: e,
                length: dt * c,
                speed: c,
            };
        }
    }

    /// The elements the critical step is taken over, as (group, element) in the groups'
    /// order: those with at least one free DOF ([`Model::element_fully_prescribed`]
    /// leaves the others out), or every element when none has one.
    pub fn moving_elements(&self) -> Vec<(usize, usize)> {
        let all = || {
            self.groups
                .iter()
                .enumerate()
                .flat_map(|(g, group)| group.elements.iter().map(move |&e| (g, e as usize)))
        };
        let moving: Vec<(usize, usize)> = all()
            .filter(|&(_, e)| !self.element_fully_prescribed(e))
            .collect();
        if moving.is_empty() {
            all().collect()
        } else {
            moving
        }
    }

    /// An element step `dt` with the anchors' stiffness folded in (Weyl's bound on the
    /// largest eigenvalue of a sum: ω²_max ≤ (2/Δt)² + ω²_extra, so the step becomes
    /// 2/√((2/Δt)² + ω²_extra)); `dt` itself when there are no anchors or it is infinite.
    pub fn fold_extra_stiffness(&self, dt: f64) -> f64 {
        let extra = self.extra_omega_squared;
        if extra > 0.0 && dt.is_finite() {
            let w = 2.0 / dt;
            2.0 / (w * w + extra).sqrt()
        } else {
            dt
        }
    }

    /// Density factor of global element `e` from `time.mass_scaling` (1 without it).
    pub fn mass_factor_of(&self, e: usize) -> f64 {
        self.mass_factor.get(e).copied().unwrap_or(1.0)
    }

    /// Lumped nodal masses of the current element groups (ρ × the element's mass factor;
    /// anchor bars not included): what `Model::new` builds, and the static stage's
    /// activation rebuilds after an excavation. Zero at a node of no element.
    pub fn lumped_masses(&self) -> Vec<f64> {
        let mut mass = vec![0.0; self.mesh.n_nodes()];
        for g in &self.groups {
            let rho = g.material.density();
            for (le, &e) in g.elements.iter().enumerate() {
                let e = e as usize;
                let m = element_masses(&self.mesh.element_coords(e), rho * self.mass_factor_of(e));
                for (a, &n) in g.conn[le].iter().enumerate() {
                    mass[n as usize] += m[a];
                }
            }
        }
        mass
    }

    /// Recompute `inv_mass` after constraints change: 0 where all DOFs are constrained.
    pub fn refresh_inverse_mass(&mut self) {
        for (i, w) in self.inv_mass.iter_mut().enumerate() {
            *w = if self.constraints.constrained[i] == 0b111 {
                0.0
            } else {
                1.0 / self.mass[i]
            };
        }
    }

    /// Number of element group `g`'s region in [`Model::region_names`] (the `[[regions]]`
    /// order), what the outputs' `region` field holds.
    pub fn region_number(&self, g: usize) -> usize {
        let name = &self.groups[g].name;
        self.region_names
            .iter()
            .position(|r| r == name)
            .unwrap_or(self.groups[g].region)
    }

    /// Volume-averaged (strain, stress) of global element `e` for displacements `u`.
    pub fn element_strain_stress(
        &self,
        e: usize,
        u: &[[f64; 3]],
    ) -> (crate::material::Voigt, crate::material::Voigt) {
        let (g, le) = self.element_location[e];
        self.groups[g as usize].strain_stress_of(le as usize, u)
    }

    /// Rayleigh damping of element group `g` (its region's own, else the model's).
    pub fn group_damping(&self, g: usize) -> Rayleigh {
        self.region_damping
            .get(&self.groups[g].name)
            .copied()
            .unwrap_or(self.damping)
    }

    /// Rayleigh damping of global element `e`.
    pub fn element_damping(&self, e: usize) -> Rayleigh {
        self.group_damping(self.element_location[e].0 as usize)
    }

    /// Largest α and largest β over the groups (for the stable step).
    pub fn max_damping(&self) -> (f64, f64) {
        (0..self.groups.len())
            .map(|g| self.group_damping(g))
            .fold((self.damping.alpha, self.damping.beta), |(a, b), d| {
                (a.max(d.alpha), b.max(d.beta))
            })
    }

    /// α of every node when regions differ in α: Σ_e α_e M_e,a / M_a (the nodal mass
    /// proportional damping of C = Σ_e α_e M_e), 0 at a node without mass; `None` when
    /// every region has the same α.
    pub fn node_alpha(&self) -> Option<Vec<f64>> {
        let uniform =
            (0..self.groups.len()).all(|g| self.group_damping(g).alpha == self.damping.alpha);
        if uniform {
            return None;
        }
        let mut am = vec![0.0; self.mesh.n_nodes()];
        for (gi, g) in self.groups.iter().enumerate() {
            let alpha = self.group_damping(gi).alpha;
            let rho = g.material.density();
            for &e in &g.elements {
                let m = element_masses(
                    &self.mesh.element_coords(e as usize),
                    rho * self.mass_factor_of(e as usize),
                );
                for (a, &n) in self.mesh.elements[e as usize].iter().enumerate() {
                    am[n as usize] += alpha * m[a];
                }
            }
        }
        // A node of no active element (dormant after an excavation) has no mass and no
        // damping: 0, not 0/0.
        Some(
            am.iter()
                .zip(&self.mass)
                .map(|(a, &m)| if m > 0.0 { a / m } else { 0.0 })
                .collect(),
        )
    }

    /// Material of global element `e`.
    pub fn element_material(&self, e: usize) -> &crate::material::Material {
        &self.groups[self.element_location[e].0 as usize].material
    }

    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.mesh.n_elements()
    }

    /// Bytes per element held by the element groups (geometry, connectivity, state),
    /// weighted over the groups.
    pub fn bytes_per_element(&self) -> f64 {
        let total: f64 = self
            .groups
            .iter()
            .map(|g| g.bytes_per_element() * g.len() as f64)
            .sum();
        total / self.n_elements().max(1) as f64
    }

    /// The time step of a run: `requested` if given, else `safety` × the critical step
    /// with damping; a requested step above that is refused with the limiting element.
    /// The one place where a step is checked (case files and programs alike).
    pub fn time_step(&self, requested: Option<f64>, safety: f64) -> Result<f64> {
        if !(safety.is_finite() && safety > 0.0 && safety <= 1.0) {
            return Err(DcfmError::invalid(
                "",
                "time.safety",
                safety,
                "must be in (0, 1]",
            ));
        }
        let stable = safety * self.critical_step_with_damping();
        let dt = requested.unwrap_or(stable);
        if !(dt.is_finite() && dt > 0.0) {
            return Err(DcfmError::invalid(
                "",
                "time.dt",
                dt,
                "must be finite and > 0 (s)",
            ));
        }
        if dt > stable * (1.0 + 1e-12) {
            return Err(DcfmError::TimeStepTooLarge {
                file: String::new(),
                requested: dt,
                stable,
                element: self.stable.element,
                length: self.stable.length,
                speed: self.stable.speed,
            });
        }
        Ok(dt)
    }

    /// Critical step of the undamped model: the element bound 2/ω with
    /// ω² = (2/Δt_elements)² + the springs' ω² (boundary springs), and not above the
    /// free-field grids' own critical step.
    pub fn critical_step(&self) -> f64 {
        let mut dt = self.stable.critical;
        if let Some(b) = &self.boundaries {
            let w2 = (2.0 / dt).powi(2) + b.spring_omega_squared(&self.mass);
            dt = 2.0 / w2.sqrt();
            if let Some(ff) = b.free_field_critical_step() {
                dt = dt.min(ff);
            }
        }
        dt
    }

    /// Fold a stiffness added on top of the elements (anchor bars, springs) into the
    /// critical step: with ω²_extra a bound on the largest eigenvalue of M^{-1/2} K_extra
    /// M^{-1/2}, Weyl's inequality bounds the model's ω²_max by ω²_elements + ω²_extra, so
    /// the step becomes 2/√((2/Δt)² + ω²_extra).
    pub fn include_extra_stiffness(&mut self, omega_squared: f64) {
        if omega_squared > 0.0 && omega_squared.is_finite() {
            self.extra_omega_squared += omega_squared;
            self.refresh_stable_step();
        }
    }

    /// Critical step with Rayleigh damping C = αM + βK, both terms taking the lagged
    /// velocity V^{n−½}: for a mode ω the leapfrog is stable while ω²Δt² + 2(α + βω²)Δt < 4
    /// (Jury's conditions on λ² − (2 − ω²Δt² − cΔt)λ + 1 − cΔt, c = α + βω²), i.e.
    /// Δt ≤ (2/ω)(√(1+ξ²) − ξ) with ξ = (α/ω + βω)/2 (Belytschko et al. 2000, eq. 6.2.23,
    /// with the mass-proportional part included), the left side growing with ω so that
    /// ω = ω_max = 2/Δt_crit governs.
    pub fn critical_step_with_damping(&self) -> f64 {
        let dt = self.critical_step();
        let omega = 2.0 / dt;
        let (alpha, beta) = self.max_damping();
        let xi = 0.5 * (alpha / omega + beta * omega);
        (2.0 / omega) * ((1.0 + xi * xi).sqrt() - xi)
    }
}
