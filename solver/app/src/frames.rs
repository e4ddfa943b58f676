//! Compact field frames (`[output.frames]`, docs/outputs.md): what a user needs every
//! frame of a long run — the elements of some regions (the concrete of the Yingxiuwan
//! case, whose nodes carry the contact fields of its interfaces) with displacement,
//! velocity, contact fields, stress and damage in Float32, zlib-compressed
//! ([`crate::output::write_vtu_compressed`]), and the anchor bars with their axial forces.
//! The frames form the run's time series (`case.pvd`); the anchor frames their own
//! (`anchors.pvd`), every `anchors_every` steps (a multiple of `vtu_every`; 0: with every
//! frame). The run driver writes the whole mesh less often (`full.pvd`, Float64,
//! zlib-compressed unless `full_encoding = "base64"`).

use std::path::Path;

use dcfm::case::{FramesSection, WholeMeshEncoding};
use dcfm::error::Result;
use dcfm::stage::Simulation;

use crate::output::{
    write_vtu_compressed, write_vtu_lines, CellSubset, Precision, PvdCollection, VtuField,
    VtuStrings,
};

/// The compact frames of a run.
pub struct CompactFrames {
    subset: CellSubset,
    region: Vec<f64>,
    anchors: Option<PvdCollection>,
    full: PvdCollection,
    /// Steps between two frames of the whole mesh (0: first and last only).
    pub full_every: u64,
    /// How the whole-mesh frames are stored.
    pub full_encoding: WholeMeshEncoding,
    /// Steps between two frames of the anchor bars (`anchors_every`, or `vtu_every` when
    /// that is 0; 0: first and last only).
    pub anchors_every: u64,
}

impl CompactFrames {
    /// The frames of `section` for the model of `sim` (its active elements in the listed
    /// regions or sets), with the compact frames every `vtu_every` steps. `resumed`: a
    /// resumed run, whose `sim` is the state of the checkpoint it starts from — the
    /// collections keep only the frames this run's schedule writes up to that step (not
    /// the last frame of the interrupted run, nor later ones), as an uninterrupted run.
    pub fn new(
        section: &FramesSection,
        sim: &Simulation,
        out: &Path,
        vtu_every: u64,
        resumed: bool,
    ) -> Result<Self> {
        let mesh = &sim.model.mesh;
        let mut wanted = vec![false; mesh.n_elements()];
        for name in &section.regions {
            if let Some(set) = mesh.element_sets.get(name) {
                for &e in set {
                    wanted[e as usize] = true;
                }
            }
            if let Some(r) = mesh.region_index(name) {
                for (e, &er) in mesh.element_region.iter().enumerate() {
                    if er as usize == r {
                        wanted[e] = true;
                    }
                }
            }
        }
        let mut selected = Vec::new();
        let mut region_of = vec![f64::NAN; mesh.n_elements()];
        for (gi, g) in sim.model.groups.iter().enumerate() {
            let number = sim.model.region_number(gi) as f64;
            for &e in &g.elements {
                region_of[e as usize] = number;
                if wanted[e as usize] {
                    selected.push(e);
                }
            }
        }
        selected.sort_unstable();
        let subset = CellSubset::new(&mesh.coords, &mesh.elements, &selected);
        let region = selected.iter().map(|&e| region_of[e as usize]).collect();
        let anchors_every = if section.anchors_every > 0 {
            section.anchors_every
        } else {
            vtu_every
        };
        let (restart, time) = (sim.step, sim.time);
        let open = |name: &str, every: u64| -> Result<PvdCollection> {
            let path = out.join(name);
            if !resumed {
                return PvdCollection::create(&path);
            }
            let mut p = PvdCollection::resume(&path)?;
            p.truncate_after(time)?;
            p.retain(|e| {
                crate::run::frame_step(&e.file)
                    .is_some_and(|s| s == 0 || (s <= restart && due(s, every)))
            })?;
            Ok(p)
        };
        let anchors = match (&sim.model.anchors, section.anchors) {
            (Some(a), true) if !a.is_empty() => Some(open("anchors.pvd", anchors_every)?),
            _ => None,
        };
        Ok(Self {
            subset,
            region,
            anchors,
            full: open("full.pvd", section.full_every)?,
            full_every: section.full_every,
            full_encoding: section.full_encoding,
            anchors_every,
        })
    }

    /// Number of cells in every frame.
    pub fn cells(&self) -> usize {
        self.subset.cells.len()
    }

    /// The collection of the whole-mesh frames.
    pub fn full_collection(&mut self) -> &mut PvdCollection {
        &mut self.full
    }

    /// The collections beside `case.pvd`: the whole-mesh frames and, when written, the
    /// anchor frames.
    pub fn collections(&self) -> Vec<&PvdCollection> {
        std::iter::once(&self.full)
            .chain(self.anchors.as_ref())
            .collect()
    }

    /// Whether the whole mesh is due at `step` (`last`: the run's last step).
    pub fn full_due(&self, step: u64, first: bool, last: bool) -> bool {
        first || last || due(step, self.full_every)
    }

    /// Whether a frame of the anchor bars is due at `step` (`last`: the run's last step).
    pub fn anchors_due(&self, step: u64, first: bool, last: bool) -> bool {
        first || last || due(step, self.anchors_every)
    }

    /// Write the frame of the current state into `out` and add it to `pvd`, with the
    /// anchor bars' frame when due (`first`, `last`: the run's first or last step).
    pub fn write(
        &mut self,
        sim: &Simulation,
        out: &Path,
        pvd: &mut PvdCollection,
        first: bool,
        last: bool,
    ) -> Result<()> {
        let model = &sim.model;
        let s = &self.subset;
        let ne = model.n_elements();
        let mut stress = vec![0.0; 6 * ne];
        let mut damage = vec![0.0; 3 * ne];
        for g in &model.groups {
            if !g
                .elements
                .iter()
                .any(|&e| s.elements.binary_search(&e).is_ok())
            {
                continue;
            }
            let ss = g.element_strain_stress(&sim.u);
            let dmg = g.element_damage_fields();
            for (le, &e) in g.elements.iter().enumerate() {
                let e = e as usize;
                stress[6 * e..6 * e + 6].copy_from_slice(&ss[le].1);
                if let Some(d) = &dmg {
                    damage[3 * e..3 * e + 3].copy_from_slice(&d[le][..3]);
                }
            }
        }
        let flat = |f: &[[f64; 3]]| -> Vec<f64> {
            s.nodes
                .iter()
                .flat_map(|&n| f[n as usize].iter().copied())
                .collect()
        };
        let (u, v) = (flat(&sim.u), flat(&sim.v));
        let contact: Vec<(String, usize, Vec<f64>)> = model
            .contact
            .as_ref()
            .map(|c| {
                c.node_fields(model.mesh.n_nodes())
                    .into_iter()
                    .map(|(name, k, values)| (name, k, s.gather_points(&values, k)))
                    .collect()
            })
            .unwrap_or_default();
        let mut point_fields = vec![
            VtuField::new("displacement", 3, &u),
            VtuField::new("velocity", 3, &v),
        ];
        for (name, k, values) in &contact {
            point_fields.push(VtuField::new(name, *k, values));
        }
        let pick = |k: usize| -> Vec<f64> {
            s.elements
                .iter()
                .map(|&e| damage[3 * e as usize + k])
                .collect()
        };
        let (d, dt, dc) = (pick(0), pick(1), pick(2));
        let stress = s.gather_cells(&stress, 6);
        let ids: Vec<f64> = s.elements.iter().map(|&e| e as f64).collect();
        let name = format!("frame_{:06}.vtu", sim.step);
        write_vtu_compressed(
            &out.join(&name),
            Precision::Float32,
            &s.coords,
            &s.cells,
            &point_fields,
            &[
                VtuField::new("damage", 1, &d),
                VtuField::new("damage_tension", 1, &dt),
                VtuField::new("damage_compression", 1, &dc),
                VtuField::new("stress", 6, &stress),
                VtuField::new("region", 1, &self.region),
                VtuField::new("element_id", 1, &ids),
            ],
            &[VtuStrings {
                name: "region_names",
                values: &model.region_names,
            }],
        )?;
        pvd.add(sim.time, &name)?;
        let anchors_due = self.anchors_due(sim.step, first, last);
        if let (Some(apvd), Some(a), true) =
            (self.anchors.as_mut(), model.anchors.as_ref(), anchors_due)
        {
            let lines = a.lines();
            let name = format!("anchors_{:06}.vtu", sim.step);
            write_vtu_lines(
                &out.join(&name),
                &lines.points,
                &lines.lines,
                &[],
                &[
                    VtuField::new("axial_force", 1, &lines.force),
                    VtuField::new("plastic_strain", 1, &lines.plastic_strain),
                    VtuField::new("bar", 1, &lines.bar),
                ],
            )?;
            apvd.add(sim.time, &name)?;
        }
        Ok(())
    }
}

/// Whether a frame with an interval of `every` steps is due at `step` (0: never, only the
/// first and last frames).
fn due(step: u64, every: u64) -> bool {
    every > 0 && step.is_multiple_of(every)
}
