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
}

impl CubeMaterial {
    /// Suffix of the case name.
    pub fn suffix(self) -> &'static str {
        match self {
            CubeMaterial::Elastic => "",
            CubeMaterial::PlasticDamageElastic => "_pd_elastic",
            CubeMaterial::PlasticDamageDamaging => "_pd_damaging",
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
        let elastic = Elastic::new(REGION, 20e9, 0.25, 2700.0)?;
        let material = match self.material {
            CubeMaterial::Elastic => Material::Elastic(elastic),
            _ => Material::PlasticDamage(Box::new(PlasticDamage::new(
                REGION,
                elastic,
                &PlasticDamageParams::from_strengths(2.9e6, 13e6, 24.1e6, 200.0, 1e4),
            )?)),
        };
        let setup = RegionSetup {
            region: REGION.to_string(),
            material,
            integration: self.integration,
            hourglass: self.hourglass,
        };
        let mut model = Model::new(mesh, std::slice::from_ref(&setup), "benchmark cube")?;
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
