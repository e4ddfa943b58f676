//! The benchmark model: a structured elastic cube of n³ hex8 elements, its base fixed and
//! every other node given an initial velocity, so that a shear and a compression wave run
//! up from the base and every element strains after a few steps.

use dcfm::element::Integration;
use dcfm::material::plastic_damage::PlasticDamageParams;
use dcfm::material::{Elastic, Material, PlasticDamage};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup};
use dcfm::stage::Simulation;

/// Name of the cube's block / region.
pub const REGION: &str = "rock";

/// Safety factor on the critical step: dt = `SAFETY` × critical.
pub const SAFETY: f64 = 0.9;

/// Constitutive model of the cube.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CubeMaterial {
    /// Linear elastic rock.
    Elastic,
    /// Lee–Fenves plastic-damage with the W10 concrete strengths (f_t0 2.9 MPa, f_c0 13,
    /// f_c 24.1 MPa) on the same elastic constants; the motion stays below first yield.
    PlasticDamageElastic,
    /// The same model with a 50× stronger initial velocity: the base layers yield and
    /// damage, so most updates take the plastic return.
    PlasticDamageDamaging,
    /// Damage in one block, the mix of the Yingxiuwan case (issue #11 item 4: the
    /// damaging work concentrated in a few blocks): a linear elastic host with the case's
    /// integration (the rock mass, which stays elastic) around a weak core — the central
    /// `max(1, n/4)`³ elements, ≈ 1.6 % of the 40³ cube, region [`WEAK_REGION`], always
    /// fully integrated (the concrete) — of the plastic-damage model with [`WEAK_FACTOR`]
    /// times W10's strengths and fracture energies, at the elastic regime's velocity: the
    /// core cracks throughout, the host carries the waves.
    PlasticDamageLocalised,
}

/// Region of the weak core of [`CubeMaterial::PlasticDamageLocalised`].
pub const WEAK_REGION: &str = "weak_core";

/// The weak core's strengths and fracture energies over the host's: f_t0 0.145 MPa, well
/// below the ≈ 0.5 MPa of the shear wave the initial velocity sends through it.
pub const WEAK_FACTOR: f64 = 0.05;

impl CubeMaterial {
    /// Suffix of the case name.
    pub fn suffix(self) -> &'static str {
        match self {
            CubeMaterial::Elastic => "",
            CubeMaterial::PlasticDamageElastic => "_pd_elastic",
            CubeMaterial::PlasticDamageDamaging => "_pd_damaging",
            CubeMaterial::PlasticDamageLocalised => "_pd_localised",
        }
    }
}

/// A cube to benchmark.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubeSpec {
    /// Elements along each edge (n³ elements in all).
    pub divisions: usize,
    /// Integration rule of every element.
    pub integration: Integration,
    /// Edge length (m).
    pub edge: f64,
    /// Flanagan–Belytschko hourglass coefficient (one-point elements).
    pub hourglass: f64,
    /// Initial velocity of every node not on the base (m/s).
    pub velocity: [f64; 3],
    /// Constitutive model.
    pub material: CubeMaterial,
    /// Instead of a cube: a slab of divisions × divisions × 4 elements split at mid-height
    /// into two regions joined by a bonded DCFM interface of (divisions + 1)² node pairs.
    pub interface: bool,
    /// Instead of the fixed base: a viscous-spring absorbing base through which a seismic
    /// input enters and free-field walls on the four sides (issue #7: the boundaries'
    /// cost per step).
    pub boundaries: bool,
}

impl CubeSpec {
    /// A 10 m rock cube of `divisions`³ elements moving at (0.1, 0.05, −0.02) m/s.
    pub fn new(divisions: usize, integration: Integration) -> Self {
        Self {
            divisions,
            integration,
            edge: 10.0,
            hourglass: 0.05,
            velocity: [0.1, 0.05, -0.02],
            material: CubeMaterial::Elastic,
            interface: false,
            boundaries: false,
        }
    }

    /// The same cube on seismic boundaries (see [`CubeSpec::boundaries`]).
    pub fn with_boundaries(mut self) -> Self {
        self.boundaries = true;
        self
    }

    /// The interface slab of `divisions`² × 4 elements (see [`CubeSpec::interface`]).
    pub fn interface_slab(divisions: usize) -> Self {
        Self {
            interface: true,
            ..Self::new(divisions, Integration::OnePoint)
        }
    }

    /// The same cube with another constitutive model (the damaging regime also raises the
    /// initial velocity 50×).
    pub fn with_material(mut self, material: CubeMaterial) -> Self {
        self.material = material;
        if material == CubeMaterial::PlasticDamageDamaging {
            self.velocity = self.velocity.map(|v| 50.0 * v);
        }
        self
    }

    /// Number of elements.
    pub fn elements(&self) -> usize {
        if self.interface {
            4 * self.divisions.pow(2)
        } else {
            self.divisions.pow(3)
        }
    }

    /// Case name used in records and filters, e.g. `cube40_one_point`.
    pub fn name(&self) -> String {
        if self.interface {
            return format!(
                "slab{}_interface_{}",
                self.divisions,
                self.integration.name()
            );
        }
        format!(
            "cube{}_{}{}{}",
            self.divisions,
            self.integration.name(),
            self.material.suffix(),
            if self.boundaries { "_boundaries" } else { "" }
        )
    }

    /// Build the model: rock (E 20 GPa, ν 0.25, ρ 2700 kg/m³), base face `rock.zmin`
    /// fixed in x, y and z, initial velocity on all nodes (zeroed on the base). With
    /// [`CubeSpec::boundaries`] the base is free and the boundaries of
    /// [`CubeSpec::add_boundaries`] hold the cube instead.
    pub fn model(&self) -> dcfm::Result<Model> {
        if self.interface {
            return self.slab_model();
        }
        let n = self.divisions;
        let mut mesh = BoxMeshSpec::single(REGION, [0.0; 3], [self.edge; 3], [n, n, n])
            .build("benchmark cube")?;
        dcfm::mesh::outer_faces::add_bounding_box_face_sets(&mut mesh);
        let host = match self.material {
            CubeMaterial::PlasticDamageLocalised => CubeMaterial::Elastic,
            m => m,
        };
        let material = Self::material_of(REGION, host, 1.0)?;
        let mut setups = vec![RegionSetup {
            region: REGION.to_string(),
            material,
            integration: self.integration,
            hourglass: self.hourglass,
        }];
        if self.material == CubeMaterial::PlasticDamageLocalised {
            Self::mark_weak_core(&mut mesh, n, self.edge);
            setups.push(RegionSetup {
                region: WEAK_REGION.to_string(),
                material: Self::material_of(WEAK_REGION, self.material, WEAK_FACTOR)?,
                integration: Integration::Full,
                ..setups[0].clone()
            });
        }
        let setup = &setups[0];
        let mut model = Model::new(mesh, &setups, "benchmark cube")?;
        if self.boundaries {
            Self::add_boundaries(&mut model, &setup.material)?;
        } else {
            let base = model.mesh.node_sets[&format!("{REGION}.zmin")].clone();
            model.constraints.fix(&base, 0b111);
        }
        let all: Vec<u32> = (0..model.mesh.n_nodes() as u32).collect();
        model.initial_velocity.push((all, self.velocity));
        Ok(model)
    }

    /// The cube's rock (E 20 GPa, ν 0.25, ρ 2700 kg/m³) under `material`, its strengths and
    /// fracture energies (W10's concrete: f_t0 2.9, f_c0 13, f_c 24.1 MPa, G_t 200 N/m,
    /// G_c 10 kN/m) times `strength_factor`.
    fn material_of(
        region: &str,
        material: CubeMaterial,
        strength_factor: f64,
    ) -> dcfm::Result<Material> {
        let elastic = Elastic::new(region, 20e9, 0.25, 2700.0)?;
        if material == CubeMaterial::Elastic {
            return Ok(Material::Elastic(elastic));
        }
        let [ft0, fc0, fc, gt, gc] = [2.9e6, 13e6, 24.1e6, 200.0, 1e4].map(|x| strength_factor * x);
        Ok(Material::PlasticDamage(Box::new(PlasticDamage::new(
            region,
            elastic,
            &PlasticDamageParams::from_strengths(ft0, fc0, fc, gt, gc),
        )?)))
    }

    /// Move the central `max(1, n/4)`³ elements of the n³ cube of edge `edge` to the region
    /// [`WEAK_REGION`] (by their centroids' cell indices).
    fn mark_weak_core(mesh: &mut dcfm::mesh::Mesh, n: usize, edge: f64) {
        let m = (n / 4).max(1);
        let first = (n - m) / 2;
        let core = first..first + m;
        let weak = mesh.region_names.len() as u16;
        mesh.region_names.push(WEAK_REGION.to_string());
        let h = edge / n as f64;
        for e in 0..mesh.n_elements() {
            let x = mesh.element_coords(e);
            let inside = (0..3).all(|c| {
                let centroid = x.iter().map(|p| p[c]).sum::<f64>() / 8.0;
                core.contains(&((centroid / h).floor() as usize))
            });
            if inside {
                mesh.element_region[e] = weak;
            }
        }
    }

    /// The boundaries of `cases/seismic_rock_box.toml` on the cube: a viscous-spring base
    /// (`outer.zmin`, α_N 1.33, α_T 0.67) through which an outcrop acceleration of
    /// 1 m/s² at 2 Hz along x enters, and free-field walls with their 1D columns on
    /// `outer.xmin`, `outer.xmax`, `outer.ymin`, `outer.ymax`.
    fn add_boundaries(model: &mut Model, material: &Material) -> dcfm::Result<()> {
        use dcfm::boundary::absorbing::SetNames;
        use dcfm::boundary::free_field::FreeFieldSection;
        use dcfm::boundary::seismic_input::{MotionDefinition, SeismicSection};
        use dcfm::boundary::MotionKind;
        use dcfm::boundary::{AbsorbingKind, AbsorbingSpec, BoundaryInputs, BoundarySystem};
        use dcfm::load::TimeFunction;
        let absorbing = [AbsorbingSpec {
            set: SetNames::One("outer.zmin".to_string()),
            kind: AbsorbingKind::ViscousSpring,
            material: None,
            alpha_n: 1.33,
            alpha_t: 0.67,
            distance: None,
            source: None,
            input: true,
        }];
        let free_field = FreeFieldSection {
            sides: ["xmin", "xmax", "ymin", "ymax"]
                .iter()
                .map(|s| SetNames::One(format!("outer.{s}")))
                .collect(),
            top: None,
        };
        let seismic = SeismicSection {
            x: Some(TimeFunction::Sine {
                amplitude: 1.0,
                frequency: 2.0,
                phase: 0.0,
            }),
            y: None,
            z: None,
            quantity: MotionKind::Acceleration,
            definition: MotionDefinition::Outcrop,
            profile_at: None,
            overburden: Vec::new(),
        };
        let materials = std::collections::BTreeMap::from([(REGION.to_string(), material.clone())]);
        let inputs = BoundaryInputs {
            absorbing: &absorbing,
            free_field: Some(&free_field),
            seismic: Some(&seismic),
            materials: &materials,
        };
        model.boundaries = BoundarySystem::build(model, &inputs, "benchmark cube")?;
        Ok(())
    }

    /// The interface slab: lower block `rock`, upper block `lining`, split between them,
    /// bonded interface (cohesion 2 MPa, μs 0.6, μd 0.5), base fixed, the upper block given
    /// the initial velocity.
    fn slab_model(&self) -> dcfm::Result<Model> {
        use dcfm::contact::{ContactSystem, InterfaceSpec};
        use dcfm::mesh::BlockSpec;
        let n = self.divisions;
        let h = self.edge / n as f64;
        let block = |name: &str, z0: f64| BlockSpec {
            name: name.to_string(),
            region: None,
            origin: [0.0, 0.0, z0],
            size: [self.edge, self.edge, 2.0 * h],
            divisions: [n, n, 2],
            grading: [1.0; 3],
        };
        let spec = BoxMeshSpec {
            blocks: vec![block(REGION, 0.0), block("lining", 2.0 * h)],
            split: vec![[REGION.to_string(), "lining".to_string()]],
            merge_tolerance: 1e-6,
        };
        let mesh = spec.build("interface slab")?;
        let elastic = Elastic::new(REGION, 20e9, 0.25, 2700.0)?;
        let setups: Vec<RegionSetup> = [REGION, "lining"]
            .iter()
            .map(|r| RegionSetup {
                region: r.to_string(),
                material: Material::Elastic(elastic),
                integration: self.integration,
                hourglass: self.hourglass,
            })
            .collect();
        let mut model = Model::new(mesh, &setups, "interface slab")?;
        let base = model.mesh.node_sets[&format!("{REGION}.zmin")].clone();
        model.constraints.fix(&base, 0b111);
        let top = model.mesh.nodes_of("lining").unwrap_or_default();
        model.initial_velocity.push((top, self.velocity));
        let interface = InterfaceSpec::new(
            "slab",
            &format!("lining-{REGION}"),
            &format!("{REGION}-lining"),
            0.6,
            0.5,
            2e6,
        );
        model.contact = Some(ContactSystem::new(
            &model.mesh,
            &[interface],
            "interface slab",
        )?);
        Ok(model)
    }

    /// The model in motion with dt = [`SAFETY`] × the critical step (boundary springs
    /// and the free-field columns included).
    pub fn simulation(&self) -> dcfm::Result<Simulation> {
        let model = self.model()?;
        let dt = model.time_step(None, SAFETY)?;
        Simulation::new(model, dt, SAFETY)
    }
}
