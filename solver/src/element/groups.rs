//! Element groups: the elements of one region with their material, integration rule,
//! precomputed geometry and integration-point state, sorted by colour so that every
//! colour is one contiguous range processed in parallel.

use rayon::prelude::*;

use crate::element::colouring::BLOCK;
use crate::element::damage_marks::DamageMarks;
use crate::element::damage_scan::{add_in_order, DamageScan, KNOWN_POINTS};
use crate::element::elastic_matrices::ElasticMatrices;
use crate::element::hex8_full::{self, FullGeometry};
use crate::element::hex8_full_lanes;
use crate::element::hex8_uniform::{self, UniformGeometry};
use crate::element::hex8_uniform_lanes::{self, UniformBlock};
use crate::element::lanes::{self, LaneWork, Simd, LANES};
use crate::element::stable_step::characteristic_length;
use crate::element::uniform_set::UniformSet;
use crate::element::Integration;
use crate::error::{DcfmError, Result};
use crate::material::{Material, PointContext, PointStates, StateAccess, Voigt, MAX_ELEMENT_STATE};
use crate::mesh::Mesh;

/// Elements per parallel task (and per partial sum) of [`ElementGroup::damaged_volume`].
const DAMAGE_CHUNK: usize = 1024;

/// Elements per parallel task of the two-phase force pass (one runtime dispatch each).
const FORCE_CHUNK: usize = 16;

/// Most [`FORCE_CHUNK`]s one unstolen rayon task of the two-phase pass runs in a row.
/// Rayon's adaptive splitter stops splitting a task nobody steals after log₂(threads)
/// halvings, so without a cap the last task of a step can hold a quarter of the group on
/// 2 threads while the other thread has nothing left to steal: cracking elements cost
/// several times an elastic one, and the damage is not spread evenly over the range.
/// 128 elements a task keeps that tail to a fraction of a per cent of the pass.
const FORCE_TASK_CHUNKS: usize = 8;

/// Precomputed geometry of a group's elements.
#[derive(Clone, Debug)]
pub enum GroupGeometry {
    /// One-point elements (element by element, and in lane blocks for
    /// [`hex8_uniform_lanes`]).
    Uniform(UniformSet),
    /// Fully integrated elements.
    Full(Vec<FullGeometry>),
}

/// The elements of one region.
#[derive(Clone, Debug)]
pub struct ElementGroup {
    /// Region index in the mesh.
    pub region: usize,
    /// Region name.
    pub name: String,
    /// Constitutive model.
    pub material: Material,
    /// Integration rule.
    pub integration: Integration,
    /// Global element ids, sorted by colour.
    pub elements: Vec<u32>,
    /// Connectivity, in the group's order (copied for locality).
    pub conn: Vec<[u32; 8]>,
    /// Geometry, in the group's order.
    pub geometry: GroupGeometry,
    /// Characteristic length V / A_max of each element (m).
    pub char_length: Vec<f64>,
    /// Volume of each element (m³).
    pub volume: Vec<f64>,
    /// Element ranges of each colour.
    pub colour_ranges: Vec<std::ops::Range<usize>>,
    /// Runs of elements of one colour and one colouring block (`colouring::BLOCK`
    /// consecutive global elements), in the group's order: each is processed serially by
    /// one thread, the runs of a colour in parallel.
    blocks: Vec<std::ops::Range<usize>>,
    /// Range of `blocks` of each colour.
    colour_blocks: Vec<std::ops::Range<usize>>,
    /// Integration-point state (`integration.points()` points per element); read through
    /// [`ElementGroup::states`], changed by the force passes and the methods that keep
    /// [`ElementGroup::damage_marks`] true.
    states: PointStates,
    /// The elements that may hold damage ([`DamageMarks`]): marked by the force passes,
    /// recomputed whenever the states change otherwise.
    damage_marks: DamageMarks,
    /// What the damaged-volume scan keeps between history rows ([`DamageScan`]):
    /// forgotten whenever the states change other than by a committed force pass.
    damage_scan: DamageScan,
    /// Initial strain ε₀ of every integration point (in-situ stress σ₀ = E₀ : ε₀), added to
    /// the strain of the displacements before the material update; `None` (no cost) for
    /// groups without initial stress (`docs/static_stage.md`).
    pub initial_strain: Option<Vec<Voigt>>,
    /// Reference (stress-free) displacements of every element's nodes: the kernels see
    /// u − u_ref, so that an element activated in a deformed configuration starts
    /// stress-free there (the static stage's activation); `None` for groups without one.
    pub reference: Option<Vec<[[f64; 3]; 8]>>,
    /// Compute the forces in SIMD lanes, bit-identical to the scalar kernels and compiled
    /// for the best instruction set of the CPU: fully integrated elements with their eight
    /// Gauss points in lanes ([`hex8_full_lanes`]), linear elastic one-point elements eight
    /// at a time ([`hex8_uniform_lanes`], in the dynamic stage's in-place passes); `true`
    /// by default. With it, linear elastic fully integrated elements whose geometry
    /// repeats use their stiffness matrices instead ([`ElementGroup::elastic_matrices`]):
    /// the Gauss kernel's forces to round-off, not bit for bit.
    /// `false` runs the scalar kernels of [`hex8_full`] and [`hex8_uniform`], the
    /// reference the tests compare with.
    pub lanes: bool,
    /// The two-phase force pass ([`add_internal_forces`]): every element's forces computed
    /// in parallel element by element into these buffers, then added to the nodes run by
    /// run in the colouring's order. `Some` (the default) for groups whose material is not
    /// linear elastic: a plastic-damage update costs microseconds per point, and where the
    /// damage gathers in a few colouring runs the one-phase pass runs those on one thread
    /// each. `None`: each run computes and adds its elements on one thread. The sums are
    /// the same additions in the same order either way (bit-identical results).
    pub element_forces: Option<ElementForces>,
    /// Stiffness matrices of linear elastic, fully integrated elements whose geometry
    /// repeats ([`ElasticMatrices`]): with [`ElementGroup::lanes`] on and no initial
    /// strain, those elements' internal and damping forces are K u and β K v. `None` for
    /// other groups, and where no geometry repeats.
    matrices: Option<ElasticMatrices>,
}

/// Per-element force buffers of the two-phase force pass (in the group's order).
#[derive(Clone, Debug, Default)]
pub struct ElementForces {
    /// Internal force of each element's eight nodes (N).
    internal: Vec<[[f64; 3]; 8]>,
    /// Stiffness-proportional damping force β K0 v of each element's nodes (N).
    damping: Vec<[[f64; 3]; 8]>,
}

impl ElementForces {
    /// Buffers for `n` elements (allocated once, when the group is built).
    pub fn new(n: usize) -> Self {
        Self {
            internal: vec![[[0.0; 3]; 8]; n],
            damping: vec![[[0.0; 3]; 8]; n],
        }
    }

    /// The default for a group of `material` with `n` elements: buffers for every
    /// material but linear elasticity.
    fn default_for(material: &Material, n: usize) -> Option<Self> {
        (!matches!(material, Material::Elastic(_))).then(|| Self::new(n))
    }
}

/// The internal forces f_int(u) of every element of `groups` into `f_int` (and the
/// stiffness-proportional damping forces β K0 v into `f_damp` for groups with β > 0),
/// `settings(k)` giving group k's β, step and due elements. First, every group with
/// [`ElementGroup::element_forces`] computes all its (due) elements in parallel into its
/// buffers; then, colour by colour and group by group, the runs of the colour add their
/// elements' forces to the nodes (computing them there for the other groups). The
/// additions at every node are the same, in the same order, whatever the number of
/// threads and whichever groups use the buffers.
pub fn add_internal_forces<'a>(
    groups: &mut [ElementGroup],
    n_colours: usize,
    u: &[[f64; 3]],
    v: &[[f64; 3]],
    settings: impl Fn(usize) -> ForceSettings<'a>,
    f_int: &mut [[f64; 3]],
    f_damp: &mut [[f64; 3]],
) {
    for (k, g) in groups.iter_mut().enumerate() {
        g.compute_element_forces(u, v, settings(k));
    }
    for c in 0..n_colours {
        for (k, g) in groups.iter_mut().enumerate() {
            g.add_colour_forces(c, u, v, settings(k), f_int, f_damp);
        }
    }
}

/// The marks of `n` elements of `np` points each whose committed states are `states`: an
/// element is marked when one of its points may hold damage.
fn marks_of(material: &Material, states: &PointStates, np: usize, n: usize) -> DamageMarks {
    let stride = states.stride();
    let current = states.current();
    DamageMarks::from_fn(n, |le| {
        stride > 0
            && current[le * np * stride..(le + 1) * np * stride]
                .chunks_exact(stride)
                .any(|p| material.may_hold_damage(p))
    })
}

/// Raw pointer made shareable across threads; every use writes disjoint indices
/// (guaranteed by the colouring / by element ownership of its state slice).
#[derive(Clone, Copy)]
pub(crate) struct SharedMut<T>(pub(crate) *mut T);
unsafe impl<T> Send for SharedMut<T> {}
unsafe impl<T> Sync for SharedMut<T> {}

impl<T> SharedMut<T> {
    /// # Safety
    /// `i` must be in bounds and no other thread may access index `i` concurrently.
    #[inline(always)]
    pub(crate) unsafe fn at(self, i: usize) -> *mut T {
        self.0.add(i)
    }
}

/// Which elements a step of a subcycled run evaluates (`stage::subcycling`): element `le`
/// of the group is due at fine step `step` when `step` is a multiple of 2^`level[le]`, and
/// it is then evaluated with the step 2^`level[le]` Δt (its strain increment spans its
/// whole period).
#[derive(Clone, Copy, Debug)]
pub struct Due<'a> {
    /// The fine step n.
    pub step: u64,
    /// Period exponent m_e of each element of the group, in the group's order.
    pub level: &'a [u8],
    /// Smallest m_e of each colouring run of the group ([`ElementGroup::run_levels`]): a
    /// run none of whose elements is due is skipped whole.
    pub run_level: &'a [u8],
}

impl Due<'_> {
    /// Whether a period 2^`level` falls on the fine step `step`.
    #[inline(always)]
    pub fn at(step: u64, level: u8) -> bool {
        step & ((1u64 << level) - 1) == 0
    }
}

/// Rayleigh stiffness-proportional damping coefficient and time step, passed to the kernels.
#[derive(Clone, Copy, Debug)]
pub struct ForceSettings<'a> {
    /// β of C = αM + βK (s).
    pub beta: f64,
    /// Time step (s).
    pub dt: f64,
    /// The elements due at this step of a subcycled run (`None`: every element).
    pub due: Option<Due<'a>>,
}

impl ForceSettings<'_> {
    /// The step element `le` of the group is evaluated with at this step: Δt without
    /// subcycling, 2^m_e Δt when it is due, `None` when it is not.
    #[inline(always)]
    fn element_dt(&self, le: usize) -> Option<f64> {
        match self.due {
            None => Some(self.dt),
            Some(due) => {
                let l = due.level[le];
                Due::at(due.step, l).then(|| self.dt * (1u64 << l) as f64)
            }
        }
    }
}

/// The element kernel over group `$g`'s data for one pass (a macro rather than a method
/// so that it borrows the group's fields one by one, beside its colouring runs).
macro_rules! kernel {
    ($g:expr, $u:expr, $v:expr, $beta:expr) => {{
        let stride = $g.state_values_per_element();
        let states = $g.states.access();
        Kernel {
            material: &$g.material,
            conn: &$g.conn,
            lengths: &$g.char_length,
            geometry: &$g.geometry,
            initial: $g.initial_strain.as_deref(),
            reference: $g.reference.as_deref(),
            states,
            stride,
            point_stride: $g.states.stride(),
            marks: &$g.damage_marks,
            changes: $g.damage_scan.changes(),
            beta: $beta,
            lanes: $g.lanes,
            matrices: $g
                .matrices
                .as_ref()
                .filter(|_| $g.lanes && $g.initial_strain.is_none()),
            u: $u,
            v: $v,
        }
    }};
}

impl ElementGroup {
    /// Build the group of `region` with the given material and integration rule.
    pub fn new(
        mesh: &Mesh,
        region: usize,
        material: Material,
        integration: Integration,
        hourglass: f64,
        colours: &[u8],
    ) -> Result<Self> {
        let mut elements: Vec<u32> = (0..mesh.n_elements() as u32)
            .filter(|&e| mesh.element_region[e as usize] as usize == region)
            .collect();
        elements.sort_by_key(|&e| (colours[e as usize], e));
        let n_colours = colours.iter().copied().max().map_or(0, |c| c as usize + 1);
        let mut colour_ranges = vec![0..0; n_colours];
        let mut start = 0;
        for (c, range) in colour_ranges.iter_mut().enumerate() {
            let len = elements[start..]
                .iter()
                .take_while(|&&e| colours[e as usize] as usize == c)
                .count();
            *range = start..start + len;
            start += len;
        }
        let (blocks, colour_blocks) = colouring_blocks(&elements, &colour_ranges);
        let conn: Vec<[u32; 8]> = elements
            .iter()
            .map(|&e| mesh.elements[e as usize])
            .collect();
        let mut char_length = Vec::with_capacity(elements.len());
        let mut volume = Vec::with_capacity(elements.len());
        let bad = |e: u32| DcfmError::BadElement {
            element: e as usize,
            reason: "non-positive Jacobian".into(),
        };
        let geometry = match integration {
            Integration::OnePoint => {
                let mut g = Vec::with_capacity(elements.len());
                for &e in &elements {
                    let x = mesh.element_coords(e as usize);
                    let geo = UniformGeometry::new(&x, material.elastic(), hourglass)
                        .ok_or_else(|| bad(e))?;
                    char_length.push(characteristic_length(&x, geo.volume));
                    volume.push(geo.volume);
                    g.push(geo);
                }
                // Lane blocks only where the pass can use them ([`Self::lane_block`]).
                GroupGeometry::Uniform(UniformSet::new(
                    &g,
                    matches!(material, Material::Elastic(_)),
                ))
            }
            Integration::Full => {
                let mut g = Vec::with_capacity(elements.len());
                for &e in &elements {
                    let x = mesh.element_coords(e as usize);
                    let geo = FullGeometry::new(&x).ok_or_else(|| bad(e))?;
                    char_length.push(characteristic_length(&x, geo.volume()));
                    volume.push(geo.volume());
                    g.push(geo);
                }
                GroupGeometry::Full(g)
            }
        };
        let matrices = match (&material, integration) {
            (Material::Elastic(el), Integration::Full) => {
                let coords: Vec<[[f64; 3]; 8]> = elements
                    .iter()
                    .map(|&e| mesh.element_coords(e as usize))
                    .collect();
                ElasticMatrices::new(&coords, el)
            }
            _ => None,
        };
        let stride = material.state_len();
        let n_points = elements.len() * integration.points();
        let states = PointStates::new(stride, n_points, |_, s| material.init_state(s));
        let element_forces = ElementForces::default_for(&material, elements.len());
        let damage_marks = marks_of(&material, &states, integration.points(), elements.len());
        let damage_scan = DamageScan::new(elements.len());
        Ok(Self {
            region,
            name: mesh.region_names[region].clone(),
            material,
            integration,
            elements,
            conn,
            geometry,
            char_length,
            volume,
            colour_ranges,
            blocks,
            colour_blocks,
            states,
            damage_marks,
            damage_scan,
            initial_strain: None,
            reference: None,
            lanes: true,
            element_forces,
            matrices,
        })
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.elements.len()
    }

    /// True when the group has no element.
    pub fn is_empty(&self) -> bool {
        self.elements.is_empty()
    }

    /// Bytes per element held by the group (geometry, connectivity, lengths, state).
    pub fn bytes_per_element(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        let geo = match &self.geometry {
            // Shared records and the indices (`UniformSet`), per element.
            GroupGeometry::Uniform(g) => g.bytes() as f64 / self.len() as f64,
            GroupGeometry::Full(_) => std::mem::size_of::<FullGeometry>() as f64,
        };
        let fixed = geo + (std::mem::size_of::<[u32; 8]>() + 4 + 2 * 8) as f64;
        let extra = self.initial_strain.as_ref().map_or(0, |v| v.len() * 48)
            + self.reference.as_ref().map_or(0, |v| v.len() * 192)
            + self.element_forces.as_ref().map_or(0, |b| {
                (b.internal.len() + b.damping.len()) * std::mem::size_of::<[[f64; 3]; 8]>()
            })
            + self.matrices.as_ref().map_or(0, |m| m.bytes());
        fixed + (self.states.bytes() + extra) as f64 / self.len() as f64
    }

    /// Phase one of the two-phase pass ([`add_internal_forces`]): the forces of every
    /// (due) element into [`ElementGroup::element_forces`], element by element in
    /// parallel, material states to their pending buffer (or in place). Nothing for
    /// groups without the buffers.
    fn compute_element_forces(
        &mut self,
        u: &[[f64; 3]],
        v: &[[f64; 3]],
        settings: ForceSettings<'_>,
    ) {
        let Some(mut buffers) = self.element_forces.take() else {
            return;
        };
        {
            let beta = settings.beta;
            let kernel = kernel!(self, u, v, beta);
            // The damping buffer is written (and read) only when β > 0.
            let damping = SharedMut(buffers.damping.as_mut_ptr());
            let lanes = kernel.lanes;
            buffers
                .internal
                .par_chunks_mut(FORCE_CHUNK)
                .enumerate()
                .with_max_len(FORCE_TASK_CHUNKS)
                .for_each(|(c, chunk)| {
                    let first = c * FORCE_CHUNK;
                    let work = ChunkForces {
                        kernel: &kernel,
                        settings: &settings,
                        first,
                        out: chunk,
                        damping,
                    };
                    lanes::run_work(work, lanes)
                });
        }
        self.element_forces = Some(buffers);
    }

    /// Add the internal forces of the elements of colour `c` into `f_int` (and the
    /// stiffness-proportional damping forces into `f_damp` when β > 0). Elements of one
    /// colour share no node, so the parallel adds never touch the same node; each run of
    /// one colouring block is added by one thread in the group's order. A group with
    /// [`ElementGroup::element_forces`] adds the forces computed by
    /// [`ElementGroup::compute_element_forces`] (called first, with the same settings);
    /// the others compute them here. Called through [`add_internal_forces`].
    fn add_colour_forces(
        &mut self,
        c: usize,
        u: &[[f64; 3]],
        v: &[[f64; 3]],
        settings: ForceSettings<'_>,
        f_int: &mut [[f64; 3]],
        f_damp: &mut [[f64; 3]],
    ) {
        let Some(block_range) = self.colour_blocks.get(c).cloned() else {
            return;
        };
        if block_range.is_empty() {
            return;
        }
        let f_ptr = SharedMut(f_int.as_mut_ptr());
        let d_ptr = SharedMut(f_damp.as_mut_ptr());
        let n_nodes = f_int.len();
        debug_assert_eq!(f_damp.len(), n_nodes);
        let beta = settings.beta;
        let due = settings.due;
        // Add element le's internal force `fe` and damping force `fd` to its nodes.
        let add = |nodes: &[u32; 8], fe: &[[f64; 3]; 8], fd: &[[f64; 3]; 8]| {
            for a in 0..8 {
                let n = nodes[a] as usize;
                debug_assert!(n < n_nodes);
                // SAFETY: no element of another run of this colour has node n (block
                // colouring), and the elements of a run are added serially by one thread.
                unsafe {
                    let p = &mut *f_ptr.at(n);
                    p[0] += fe[a][0];
                    p[1] += fe[a][1];
                    p[2] += fe[a][2];
                    if beta > 0.0 {
                        let d = &mut *d_ptr.at(n);
                        d[0] += fd[a][0];
                        d[1] += fd[a][1];
                        d[2] += fd[a][2];
                    }
                }
            }
        };
        let blocks = &self.blocks[block_range.clone()];
        let run_levels = due.map(|d| &d.run_level[block_range]);
        // Whether a run has any due element (subcycled: a run none of whose elements is
        // due is skipped whole).
        let run_due = |r: usize| -> bool {
            match (due, run_levels) {
                (Some(due), Some(levels)) => Due::at(due.step, levels[r]),
                _ => true,
            }
        };
        if let Some(buffers) = &self.element_forces {
            let conn = &self.conn;
            blocks.par_iter().enumerate().for_each(|(r, run)| {
                if !run_due(r) {
                    return;
                }
                for le in run.clone() {
                    if settings.element_dt(le).is_some() {
                        add(&conn[le], &buffers.internal[le], &buffers.damping[le]);
                    }
                }
            });
            return;
        }
        let kernel = kernel!(self, u, v, beta);
        let lanes = kernel.lanes;
        blocks.par_iter().enumerate().for_each(|(r, run)| {
            if !run_due(r) {
                return;
            }
            let work = RunForces {
                kernel: &kernel,
                settings: &settings,
                run: run.clone(),
                add: &add,
            };
            lanes::run_work(work, lanes)
        });
    }

    /// Smallest of `level` (one value per element, the group's order) over each colouring
    /// run, in the order of the runs: the `run_level` of [`Due`].
    pub fn run_levels(&self, level: &[u8]) -> Vec<u8> {
        self.blocks
            .iter()
            .map(|run| run.clone().map(|le| level[le]).min().unwrap_or(0))
            .collect()
    }

    /// Commit the material states of the elements evaluated at a subcycled step (`due`);
    /// the others keep their committed state, which their pending buffer does not hold
    /// (nothing to do in place: the elements not due were not written).
    pub fn commit_due(&mut self, due: Due<'_>) {
        let per = self.state_values_per_element();
        if per == 0 {
            return;
        }
        self.states
            .commit_elements(per, |le| Due::at(due.step, due.level[le]));
    }

    /// Volume-averaged strain and stress of the group's element `le` from displacements
    /// `u` and the committed state (changes nothing).
    ///
    /// The strain is that of the displacements (relative to the element's reference, if
    /// any); the stress includes the initial strain ε₀ of the points (in-situ stress).
    pub fn strain_stress_of(&self, le: usize, u: &[[f64; 3]]) -> (Voigt, Voigt) {
        let stride = self.states.stride();
        let state = self.states.current();
        let ue = self.element_displacements(le, u);
        match &self.geometry {
            GroupGeometry::Uniform(g) => {
                let eps = g[le].strain(&ue);
                let s = &state[le * stride..(le + 1) * stride];
                let total = self.with_initial_strain(le, 0, &eps);
                (eps, self.material.stress_from_state(&total, s))
            }
            GroupGeometry::Full(g) => {
                let mut em = [0.0; 6];
                let mut sm = [0.0; 6];
                let vol = g[le].volume();
                for gp in 0..8 {
                    let eps = g[le].strain(gp, &ue);
                    let p = le * 8 + gp;
                    let total = self.with_initial_strain(le, gp, &eps);
                    let s = self
                        .material
                        .stress_from_state(&total, &state[p * stride..(p + 1) * stride]);
                    let w = g[le].wdet[gp] / vol;
                    for i in 0..6 {
                        em[i] += w * eps[i];
                        sm[i] += w * s[i];
                    }
                }
                (em, sm)
            }
        }
    }

    /// [`ElementGroup::strain_stress_of`] for every element, in the group's order.
    pub fn element_strain_stress(&self, u: &[[f64; 3]]) -> Vec<(Voigt, Voigt)> {
        (0..self.len())
            .into_par_iter()
            .map(|le| self.strain_stress_of(le, u))
            .collect()
    }

    /// Volume of every integration point of element `le` (one-point: V; full: w·det J).
    #[inline]
    fn point_volume(&self, le: usize, gp: usize) -> f64 {
        match &self.geometry {
            GroupGeometry::Uniform(g) => g[le].volume,
            GroupGeometry::Full(g) => g[le].wdet[gp],
        }
    }

    /// Element averages (volume-weighted over the points) of the damage variables:
    /// per element [D, D_t, D_c, κ_t, κ_c, εᵖ (6)], or `None` without a damage model.
    pub fn element_damage_fields(&self) -> Option<Vec<[f64; 11]>> {
        if !self.material.has_damage() {
            return None;
        }
        let stride = self.states.stride();
        let np = self.integration.points();
        let state = self.states.current();
        Some(
            (0..self.len())
                .map(|le| {
                    let mut acc = [0.0; 11];
                    for gp in 0..np {
                        let p = le * np + gp;
                        let w = self.point_volume(le, gp) / self.volume[le];
                        let d = self
                            .material
                            .damage_state(&state[p * stride..(p + 1) * stride])
                            .unwrap_or_default();
                        let vals = [d.d, d.dt, d.dc, d.kappa_t, d.kappa_c];
                        for k in 0..5 {
                            acc[k] += w * vals[k];
                        }
                        for k in 0..6 {
                            acc[5 + k] += w * d.plastic_strain[k];
                        }
                    }
                    acc
                })
                .collect(),
        )
    }

    /// Damaged volume of eq. (27), [tension, compression, either]: with `per_element`
    /// false, the summed volume of the integration points whose D_t (resp. D_c, either) is
    /// at least `threshold`; with `per_element` true, the summed volume of the elements
    /// whose volume-averaged D_t (resp. D_c, either) is at least `threshold`
    /// (docs/plastic_damage.md §5).
    ///
    /// Elements in parallel, in fixed chunks whose partial sums are added in chunk order:
    /// the same bits on any number of threads.
    pub fn damaged_volume(&self, threshold: f64, per_element: bool) -> [f64; 3] {
        if threshold > 0.0 {
            // Only the marked elements can reach a threshold above zero.
            self.damaged_volume_of(threshold, per_element, true, |le| {
                self.damage_marks.is_marked(le)
            })
        } else {
            self.damaged_volume_of(threshold, per_element, true, |_| true)
        }
    }

    /// [`ElementGroup::damaged_volume`] reading every element's states, without the
    /// marks or the kept answers of [`DamageScan`] (and leaving them as they are): the
    /// reference the scan is tested against. Allocates.
    pub fn damaged_volume_scanning_all(&self, threshold: f64, per_element: bool) -> [f64; 3] {
        self.damaged_volume_of(threshold, per_element, false, |_| true)
    }

    /// Number of elements marked as possibly damaged ([`DamageMarks`]).
    pub fn marked_elements(&self) -> usize {
        self.damage_marks.count()
    }

    /// The damaged volume over the elements with `visit(le)`, in chunks of
    /// [`DAMAGE_CHUNK`] elements summed in order (the same sums on any thread count); with
    /// `keep_answers`, through [`DamageScan`] (the states of an element whose hardening
    /// has not moved since its last reading are not read again).
    fn damaged_volume_of(
        &self,
        threshold: f64,
        per_element: bool,
        keep_answers: bool,
        visit: impl Fn(usize) -> bool + Sync,
    ) -> [f64; 3] {
        if !self.material.has_damage() {
            return [0.0; 3];
        }
        let stride = self.states.stride();
        let np = self.integration.points();
        let state = self.states.current();
        let add = |v: &mut [f64; 3], t: bool, c: bool, vol: f64| {
            if t {
                v[0] += vol;
            }
            if c {
                v[1] += vol;
            }
            if t || c {
                v[2] += vol;
            }
        };
        let damage = |p: usize| {
            self.material
                .tensile_and_compressive_damage(&state[p * stride..(p + 1) * stride])
        };
        // Element `le`'s volumes added to `v`: from its kept answers `bits` when `kept`,
        // else from its states, the answers stored in `bits`.
        let element = |le: usize, v: &mut [f64; 3], bits: &mut u16, kept: bool| {
            if per_element {
                if !kept {
                    let (mut et, mut ec) = (0.0, 0.0);
                    for gp in 0..np {
                        if let Some((dt, dc)) = damage(le * np + gp) {
                            let pv = self.point_volume(le, gp);
                            et += dt * pv / self.volume[le];
                            ec += dc * pv / self.volume[le];
                        }
                    }
                    *bits = answers(et >= threshold, ec >= threshold);
                }
                add(v, *bits & 1 != 0, *bits & 2 != 0, self.volume[le]);
                return;
            }
            if !kept {
                *bits = 0;
            }
            for gp in 0..np {
                let (t, c) = if kept {
                    let b = *bits >> (2 * gp);
                    (b & 1 != 0, b & 2 != 0)
                } else {
                    let (t, c) = match damage(le * np + gp) {
                        Some((dt, dc)) => (dt >= threshold, dc >= threshold),
                        None => (false, false),
                    };
                    if gp < KNOWN_POINTS {
                        *bits |= answers(t, c) << (2 * gp);
                    }
                    (t, c)
                };
                add(v, t, c, self.point_volume(le, gp));
            }
        };
        let chunk_elements = |c: usize| c * DAMAGE_CHUNK..((c + 1) * DAMAGE_CHUNK).min(self.len());
        if !keep_answers {
            // Every state read, nothing kept or changed.
            let partial: Vec<[f64; 3]> = (0..self.len().div_ceil(DAMAGE_CHUNK))
                .into_par_iter()
                .map(|c| {
                    let mut v = [0.0; 3];
                    for le in chunk_elements(c).filter(|&le| visit(le)) {
                        element(le, &mut v, &mut 0, false);
                    }
                    v
                })
                .collect();
            return add_in_order(&partial);
        }
        // Kept answers only while passes commit in place (module docs of DamageScan).
        let reuse = self.states.is_in_place() && np <= KNOWN_POINTS;
        let scan = &self.damage_scan;
        scan.sum_in_order(DAMAGE_CHUNK, threshold, per_element, |c, known| {
            let mut v = [0.0; 3];
            for (le, bits) in chunk_elements(c).zip(known.iter_mut()) {
                if visit(le) {
                    // (`unchanged` clears the element's mark: `element` stores answers)
                    let kept = scan.unchanged(le) && reuse;
                    element(le, &mut v, bits, kept);
                }
            }
            v
        })
    }

    /// Elastic strain energy ½ ∫ ε : E0 : ε dV (+ hourglass energy ½ κ q²) of the group for
    /// displacements `u` — exact for linear elastic groups, used to check conservation.
    pub fn elastic_strain_energy(&self, u: &[[f64; 3]]) -> f64 {
        let el = *self.material.elastic();
        let parts: Vec<f64> = (0..self.len())
            .into_par_iter()
            .with_min_len(1024)
            .map(|le| {
                let ue = self.element_displacements(le, u);
                match &self.geometry {
                    GroupGeometry::Uniform(g) => {
                        let g = &g[le];
                        let e = self.with_initial_strain(le, 0, &g.strain(&ue));
                        let s = el.stress(&e);
                        let q = g.hourglass_modes(&ue);
                        let hq: f64 = q.iter().flatten().map(|x| x * x).sum();
                        0.5 * g.volume * dot6(&s, &e) + 0.5 * g.kappa * hq
                    }
                    GroupGeometry::Full(g) => (0..8)
                        .map(|gp| {
                            let e = self.with_initial_strain(le, gp, &g[le].strain(gp, &ue));
                            0.5 * g[le].wdet[gp] * dot6(&el.stress(&e), &e)
                        })
                        .sum(),
                }
            })
            .collect();
        parts.iter().sum()
    }
}

/// The static stage's editing of groups: subsets of the elements (excavation,
/// activation), carrying the point data of surviving elements over, initial strains,
/// reference displacements and element stiffness matrices. None of it runs in the step loop.
impl ElementGroup {
    /// Displacements of element `le`'s nodes, relative to its reference if it has one.
    #[inline]
    pub fn element_displacements(&self, le: usize, u: &[[f64; 3]]) -> [[f64; 3]; 8] {
        let nodes = &self.conn[le];
        let mut ue: [[f64; 3]; 8] = std::array::from_fn(|a| u[nodes[a] as usize]);
        if let Some(r) = &self.reference {
            subtract_reference(&mut ue, &r[le]);
        }
        ue
    }

    /// `eps` plus the initial strain of point `gp` of element `le` (if any).
    #[inline]
    pub fn with_initial_strain(&self, le: usize, gp: usize, eps: &Voigt) -> Voigt {
        match &self.initial_strain {
            None => *eps,
            Some(e0) => {
                let e0 = &e0[le * self.integration.points() + gp];
                std::array::from_fn(|i| eps[i] + e0[i])
            }
        }
    }

    /// A new group holding only the elements for which `keep(global id)` is true, in the
    /// same order (so the colouring and its blocks stay valid), with their geometry,
    /// point states, initial strains and references.
    pub fn retain_elements(&self, keep: impl Fn(u32) -> bool) -> ElementGroup {
        let np = self.integration.points();
        let stride = self.states.stride();
        let kept: Vec<usize> = (0..self.len())
            .filter(|&le| keep(self.elements[le]))
            .collect();
        let elements: Vec<u32> = kept.iter().map(|&le| self.elements[le]).collect();
        let mut colour_ranges = Vec::with_capacity(self.colour_ranges.len());
        let mut start = 0;
        for range in &self.colour_ranges {
            let n = kept.iter().filter(|&&le| range.contains(&le)).count();
            colour_ranges.push(start..start + n);
            start += n;
        }
        let (blocks, colour_blocks) = colouring_blocks(&elements, &colour_ranges);
        let geometry = match &self.geometry {
            GroupGeometry::Uniform(g) => GroupGeometry::Uniform(g.subset(&kept)),
            GroupGeometry::Full(g) => GroupGeometry::Full(kept.iter().map(|&le| g[le]).collect()),
        };
        let current = self.states.current();
        let states = PointStates::new(stride, kept.len() * np, |p, s| {
            let (k, gp) = (p / np, p % np);
            let q = kept[k] * np + gp;
            s.copy_from_slice(&current[q * stride..(q + 1) * stride]);
        });
        let damage_marks = marks_of(&self.material, &states, np, kept.len());
        ElementGroup {
            region: self.region,
            name: self.name.clone(),
            material: self.material.clone(),
            integration: self.integration,
            conn: kept.iter().map(|&le| self.conn[le]).collect(),
            geometry,
            char_length: kept.iter().map(|&le| self.char_length[le]).collect(),
            volume: kept.iter().map(|&le| self.volume[le]).collect(),
            colour_ranges,
            blocks,
            colour_blocks,
            states,
            damage_marks,
            damage_scan: DamageScan::new(kept.len()),
            initial_strain: self.initial_strain.as_ref().map(|e0| {
                kept.iter()
                    .flat_map(|&le| e0[le * np..(le + 1) * np].iter().copied())
                    .collect()
            }),
            reference: self
                .reference
                .as_ref()
                .map(|r| kept.iter().map(|&le| r[le]).collect()),
            lanes: self.lanes,
            element_forces: self
                .element_forces
                .as_ref()
                .map(|_| ElementForces::new(kept.len())),
            matrices: self.matrices.as_ref().map(|m| m.subset(&kept)),
            elements,
        }
    }

    /// Copy the committed point states, initial strains and references of the elements
    /// that `old` also holds (matched by global element id); the other elements keep
    /// theirs. `old` must be a group of the same region.
    pub fn carry_point_data_from(&mut self, old: &ElementGroup) {
        let np = self.integration.points();
        let stride = self.states.stride();
        let mut index: Vec<(u32, usize)> = old
            .elements
            .iter()
            .enumerate()
            .map(|(le, &e)| (e, le))
            .collect();
        index.sort_unstable();
        let find = |e: u32| {
            index
                .binary_search_by_key(&e, |x| x.0)
                .ok()
                .map(|k| index[k].1)
        };
        let mut values = self.states.current().to_vec();
        let old_states = old.states.current();
        let mut any_initial = false;
        let mut any_reference = false;
        let matches: Vec<(usize, usize)> = (0..self.len())
            .filter_map(|le| find(self.elements[le]).map(|lo| (le, lo)))
            .collect();
        for &(le, lo) in &matches {
            values[le * np * stride..(le + 1) * np * stride]
                .copy_from_slice(&old_states[lo * np * stride..(lo + 1) * np * stride]);
            any_initial |= old.initial_strain.is_some();
            any_reference |= old.reference.is_some();
        }
        self.restore_states(&values);
        if any_initial {
            let n = self.len() * np;
            let e0 = self.initial_strain.get_or_insert_with(|| vec![[0.0; 6]; n]);
            let src = old.initial_strain.as_ref().expect("checked");
            for &(le, lo) in &matches {
                e0[le * np..(le + 1) * np].copy_from_slice(&src[lo * np..(lo + 1) * np]);
            }
        }
        if any_reference {
            let n = self.len();
            let r = self.reference.get_or_insert_with(|| vec![[[0.0; 3]; 8]; n]);
            let src = old.reference.as_ref().expect("checked");
            for &(le, lo) in &matches {
                r[le] = src[lo];
            }
        }
    }

    /// Make element `le` stress-free at the nodal displacements `ue` (its reference).
    pub fn set_reference(&mut self, le: usize, ue: [[f64; 3]; 8]) {
        let n = self.len();
        self.reference.get_or_insert_with(|| vec![[[0.0; 3]; 8]; n])[le] = ue;
    }

    /// Physical coordinates of the integration points of element `le` (one-point: the
    /// volume centroid; full: the 2×2×2 Gauss points), `x` its nodal coordinates.
    pub fn point_coordinates(&self, x: &[[f64; 3]; 8]) -> Vec<[f64; 3]> {
        use crate::element::hex8_shape::{gauss_points, jacobian, shape, shape_derivatives};
        let gp = gauss_points();
        let at = |p: &[f64; 3]| -> [f64; 3] {
            let n = shape(p);
            std::array::from_fn(|d| (0..8).map(|a| n[a] * x[a][d]).sum())
        };
        match self.integration {
            Integration::OnePoint => {
                let mut c = [0.0; 3];
                let mut v = 0.0;
                for p in &gp {
                    let (_, det) = jacobian(x, &shape_derivatives(p));
                    let q = at(p);
                    for d in 0..3 {
                        c[d] += det * q[d];
                    }
                    v += det;
                }
                vec![c.map(|q| q / v)]
            }
            Integration::Full => gp.iter().map(at).collect(),
        }
    }

    /// Set the initial stress of every integration point to `stress(point coordinates)`
    /// (Pa, tension positive): stored as the initial strain ε₀ = E₀⁻¹ : σ₀, with the
    /// material state primed at that strain. `mesh` gives the coordinates.
    pub fn set_initial_stress(&mut self, mesh: &Mesh, stress: impl Fn(&[f64; 3]) -> Voigt) {
        let np = self.integration.points();
        let stride = self.states.stride();
        let el = *self.material.elastic();
        let mut e0 = vec![[0.0; 6]; self.len() * np];
        for le in 0..self.len() {
            let x = mesh.element_coords(self.elements[le] as usize);
            for (gp, p) in self.point_coordinates(&x).iter().enumerate() {
                e0[le * np + gp] = el.strain(&stress(p));
            }
        }
        if stride > 0 {
            let mut values = self.states.current().to_vec();
            for (p, s) in values.chunks_exact_mut(stride).enumerate() {
                self.material.prime_strain(s, &e0[p]);
            }
            self.restore_states(&values);
        }
        self.initial_strain = Some(e0);
    }

    /// Stiffness of element `le` with the initial elastic moduli (the exact Jacobian of its
    /// kernel for an elastic material; `element::stiffness`).
    pub fn element_stiffness(&self, le: usize) -> crate::element::stiffness::ElementStiffness {
        use crate::element::stiffness::{full_stiffness, uniform_stiffness};
        match &self.geometry {
            GroupGeometry::Uniform(g) => uniform_stiffness(&g[le], self.material.elastic()),
            GroupGeometry::Full(g) => full_stiffness(&g[le], self.material.elastic()),
        }
    }

    /// The stiffness matrices of the group's elastic, fully integrated elements whose
    /// geometry repeats ([`ElasticMatrices`]), if any.
    pub fn elastic_matrices(&self) -> Option<&ElasticMatrices> {
        self.matrices.as_ref()
    }

    /// The integration-point states.
    pub fn states(&self) -> &PointStates {
        &self.states
    }

    /// End of step: the last pass's states become the committed ones
    /// ([`PointStates::commit`]).
    pub fn commit_states(&mut self) {
        self.states.commit();
    }

    /// Replace the committed states by `values` (a checkpoint's; the same length).
    pub fn restore_states(&mut self, values: &[f64]) {
        self.states.restore(values);
        self.refresh_damage_marks();
    }

    /// Replace the state buffers by `states` (saved from this group, e.g. before a trial).
    pub fn replace_states(&mut self, states: PointStates) {
        assert_eq!(states.current().len(), self.states.current().len());
        self.states = states;
        self.refresh_damage_marks();
    }

    /// Recompute [`ElementGroup::damage_marks`] from the committed states.
    fn refresh_damage_marks(&mut self) {
        self.damage_scan.forget();
        self.damage_marks = marks_of(
            &self.material,
            &self.states,
            self.integration.points(),
            self.len(),
        );
    }

    /// Run the force passes of the group in place or buffered
    /// ([`PointStates::set_in_place`]).
    pub fn set_states_in_place(&mut self, in_place: bool) {
        let per = self.state_values_per_element();
        self.states.set_in_place(in_place, per);
        self.damage_scan.forget();
    }

    /// Material state values of one element (all its integration points).
    fn state_values_per_element(&self) -> usize {
        self.states.stride() * self.integration.points()
    }

    /// Volume of integration point `gp` of element `le` (one-point: V; full: w det J).
    pub fn integration_point_volume(&self, le: usize, gp: usize) -> f64 {
        self.point_volume(le, gp)
    }
}

/// One group's element kernel for one force pass: its data, the displacements and
/// velocities, and the state buffers (the committed states read, each element writing
/// only its own slice of the pending ones).
struct Kernel<'k> {
    material: &'k Material,
    conn: &'k [[u32; 8]],
    lengths: &'k [f64],
    geometry: &'k GroupGeometry,
    initial: Option<&'k [Voigt]>,
    reference: Option<&'k [[[f64; 3]; 8]]>,
    /// The group's state buffers (each element reads and writes its own slice).
    states: StateAccess,
    /// State values per element.
    stride: usize,
    /// State values per integration point.
    point_stride: usize,
    /// Marked here when an element's new state has a yielded point.
    marks: &'k DamageMarks,
    /// Marked here when an element's hardening variables moved ([`DamageScan`]).
    changes: &'k DamageMarks,
    beta: f64,
    /// Kernels in lanes ([`ElementGroup::lanes`]).
    lanes: bool,
    /// The group's elastic matrices, when its forces may use them.
    matrices: Option<&'k ElasticMatrices>,
    u: &'k [[f64; 3]],
    v: &'k [[f64; 3]],
}

impl<'k> Kernel<'k> {
    /// Nodal displacements of element `le` (less its reference displacements).
    #[inline(always)]
    fn displacements(&self, le: usize) -> [[f64; 3]; 8] {
        let nodes = &self.conn[le];
        let mut ue: [[f64; 3]; 8] = std::array::from_fn(|a| self.u[nodes[a] as usize]);
        if let Some(r) = self.reference {
            subtract_reference(&mut ue, &r[le]);
        }
        ue
    }

    /// Damping force β K0 v of a fully integrated element `le` into `fd` (zero when
    /// β = 0; the one-point elements' damping is computed in [`Kernel::forces`]).
    #[inline(always)]
    fn damping<S: Simd>(&self, simd: S, le: usize, fd: &mut [[f64; 3]; 8]) {
        *fd = [[0.0; 3]; 8];
        if self.beta > 0.0 {
            if let GroupGeometry::Full(g) = self.geometry {
                let nodes = &self.conn[le];
                let ve: [[f64; 3]; 8] = std::array::from_fn(|a| self.v[nodes[a] as usize]);
                if self.lanes {
                    let el = self.material.elastic();
                    *fd = hex8_full_lanes::damping_force(
                        simd, &g[le], el.lambda, el.mu, &ve, self.beta,
                    );
                } else {
                    damping_force_full(&g[le], self.material, &ve, self.beta, fd);
                }
            }
        }
    }

    /// The forces of the elements `first..first + out.len()` into `out`, and their damping
    /// forces into `damping` (indexed by element) when β > 0; elements not due are
    /// skipped. An `#[inline(always)]` body, so that it is compiled for the instruction
    /// set of the [`lanes::run_lane_work`] that calls it.
    #[inline(always)]
    fn chunk_forces<S: Simd>(
        &self,
        simd: S,
        settings: &ForceSettings<'_>,
        first: usize,
        out: &mut [[[f64; 3]; 8]],
        damping: SharedMut<[[f64; 3]; 8]>,
    ) {
        let mut i = 0;
        while i < out.len() {
            let le = first + i;
            if let Some((block, dts)) = self.lane_block(settings, le, out.len() - i) {
                let fe: &mut [[[f64; 3]; 8]; LANES] = (&mut out[i..i + LANES])
                    .try_into()
                    .expect("a lane block of elements");
                self.uniform_lane_forces(block, le, &dts, fe);
                if self.beta > 0.0 {
                    for l in 0..LANES {
                        let mut fd = [[0.0; 3]; 8];
                        self.damping_uniform_of(le + l, &mut fd);
                        // SAFETY: element le + l's entry, written by this call alone.
                        unsafe { *damping.at(le + l) = fd };
                    }
                }
                i += LANES;
                continue;
            }
            i += 1;
            let Some(dt) = settings.element_dt(le) else {
                continue;
            };
            let fe = &mut out[le - first];
            let mut fd = [[0.0; 3]; 8];
            self.forces(simd, le, dt, fe, &mut fd);
            if self.beta > 0.0 {
                // SAFETY: element le's entry, written by this call alone.
                unsafe { *damping.at(le) = fd };
            }
        }
    }

    /// Compute the forces of the due elements of one colouring run in order and hand each
    /// to `add` (its nodes, internal and damping forces). `#[inline(always)]` like
    /// [`Kernel::chunk_forces`].
    #[inline(always)]
    fn run_forces<S: Simd>(
        &self,
        simd: S,
        settings: &ForceSettings<'_>,
        run: std::ops::Range<usize>,
        add: &impl Fn(&[u32; 8], &[[f64; 3]; 8], &[[f64; 3]; 8]),
    ) {
        let mut le = run.start;
        while le < run.end {
            if let Some((block, dts)) = self.lane_block(settings, le, run.end - le) {
                let mut fe = [[[0.0; 3]; 8]; LANES];
                self.uniform_lane_forces(block, le, &dts, &mut fe);
                for (l, fe) in fe.iter().enumerate() {
                    let mut fd = [[0.0; 3]; 8];
                    self.damping_uniform_of(le + l, &mut fd);
                    add(&self.conn[le + l], fe, &fd);
                }
                le += LANES;
                continue;
            }
            if let Some(dt) = settings.element_dt(le) {
                let mut fe = [[0.0; 3]; 8];
                let mut fd = [[0.0; 3]; 8];
                self.forces(simd, le, dt, &mut fe, &mut fd);
                add(&self.conn[le], &fe, &fd);
            }
            le += 1;
        }
    }

    /// The lane block of one-point elements that starts at element `le`, with the steps
    /// of its elements, when the pass runs them in lanes: lanes on, a linear elastic
    /// material, states in place, `le` the first element of a block of
    /// [`UniformSet::block`], the whole block among the `remaining` elements of the
    /// caller's range, and every element of it due.
    ///
    /// Plastic-damage one-point elements stay scalar. In lanes (tested bit for bit, the
    /// kernel alone 2.5× faster per element in L1) they are faster only while the group
    /// stays in cache: the 20³ cube's elastic regime 1.05–1.16e7 against 7.2–8.0e6
    /// element-updates/s on one thread, but its localised regime 7.9–9.0e6 against
    /// 9.0–9.3e6, the 30³ and 40³ cubes and the Yingxiuwan rock (171k elements) at parity
    /// or slower, and still at parity on the 40³ cube with the geometry shared
    /// ([`UniformSet`]) and with the states' write-back trimmed: out of cache what the
    /// lanes save is not what bounds the pass (docs/benchmarks.md, 2026-11-28).
    #[inline(always)]
    fn lane_block(
        &self,
        settings: &ForceSettings<'_>,
        le: usize,
        remaining: usize,
    ) -> Option<(&'k UniformBlock, [f64; LANES])> {
        let GroupGeometry::Uniform(g) = self.geometry else {
            return None;
        };
        if !self.lanes
            || !matches!(self.material, Material::Elastic(_))
            || !self.states.in_place
            || !le.is_multiple_of(LANES)
            || remaining < LANES
        {
            return None;
        }
        let block = g.block(le / LANES)?;
        let mut dts = [0.0; LANES];
        for (l, dt) in dts.iter_mut().enumerate() {
            *dt = settings.element_dt(le + l)?;
        }
        Some((block, dts))
    }

    /// Internal forces `fe` of the eight one-point elements `first..first + 8` (lane block
    /// `block`, steps `dts`) in lanes, their states updated in place and their damage
    /// marked: [`Kernel::forces`] of each, bit for bit ([`hex8_uniform_lanes`]).
    #[inline(always)]
    fn uniform_lane_forces(
        &self,
        block: &UniformBlock,
        first: usize,
        dts: &[f64; LANES],
        fe: &mut [[[f64; 3]; 8]; LANES],
    ) {
        let conn: &[[u32; 8]; LANES] = self.conn[first..first + LANES]
            .try_into()
            .expect("a lane block of elements");
        let reference = self.reference.map(|r| {
            <&[[[f64; 3]; 8]; LANES]>::try_from(&r[first..first + LANES])
                .expect("a lane block of elements")
        });
        let mut u = hex8_uniform_lanes::gather_relative(self.u, conn, reference);
        // An optimisation barrier: the gathered vectors are stored whole and read back as
        // vectors. Without it the compiler carried them as 8 × 24 scalars and vectorised
        // the kernel's arithmetic only partly (2.5× slower than with vectors, measured).
        std::hint::black_box(&mut u);
        let eps0 = self.initial.map(|e0| {
            hex8_uniform_lanes::voigt_lanes(
                e0[first..first + LANES]
                    .try_into()
                    .expect("a lane block of elements"),
            )
        });
        let ctx: [PointContext; LANES] = std::array::from_fn(|l| PointContext {
            char_length: self.lengths[first + l],
            dt: dts[l],
            reads_damage: true,
        });
        let stride = self.stride;
        assert!(
            (first + LANES) * stride <= self.states.len,
            "state slices of elements {first}.. out of bounds"
        );
        // SAFETY: each element owns the state slice of its index, and every pass evaluates
        // an element at most once.
        let mut states: [&mut [f64]; LANES] = std::array::from_fn(|l| unsafe {
            std::slice::from_raw_parts_mut(self.states.new.add((first + l) * stride), stride)
        });
        // Dispatched on its own, not `.run(simd)` with the pass's token: inlined into the
        // dispatched pass the one-point elastic cube ran 2× slower (40³, one thread:
        // 4.09e6 against 7.4–8.4e6 element-updates/s alternated; docs/benchmarks.md,
        // stop 62; the code generation behind it was not traced).
        let (f, moved) = lanes::run_lane_work(hex8_uniform_lanes::LaneKernel {
            block,
            material: self.material,
            u: &u,
            eps0: eps0.as_ref(),
            states: &mut states,
            ctx: &ctx,
        });
        seq_macro::seq!(L in 0..8 {
            hex8_uniform_lanes::write_lane(&f, L, &mut fe[L]);
        });
        for (l, state) in states.iter().enumerate() {
            self.mark_damage(first + l, state, || moved[l]);
        }
    }

    /// [`Kernel::damping_uniform`] of one-point element `le` (`fd` left as it is when
    /// β = 0 or the group is not one-point).
    #[inline(always)]
    fn damping_uniform_of(&self, le: usize, fd: &mut [[f64; 3]; 8]) {
        if let GroupGeometry::Uniform(g) = self.geometry {
            self.damping_uniform(le, &g[le], fd);
        }
    }

    /// Internal force `fe` and damping force `fd` (zero when β = 0) of element `le` over
    /// a step `dt`, its material states written to the pending buffer (or in place).
    #[inline(always)]
    fn forces<S: Simd>(
        &self,
        simd: S,
        le: usize,
        dt: f64,
        fe: &mut [[f64; 3]; 8],
        fd: &mut [[f64; 3]; 8],
    ) {
        let ue = self.displacements(le);
        if let Some(k) = self.matrices.and_then(|m| m.matrix_of(le)) {
            // Linear elastic: no state to update, no damage to mark.
            *fe = k.apply(&ue);
            *fd = [[0.0; 3]; 8];
            if self.beta > 0.0 {
                let nodes = &self.conn[le];
                let ve: [[f64; 3]; 8] = std::array::from_fn(|a| self.v[nodes[a] as usize]);
                let beta = self.beta;
                *fd = k.apply(&ve).map(|fa| fa.map(|x| beta * x));
            }
            return;
        }
        let ctx = PointContext {
            char_length: self.lengths[le],
            dt,
            reads_damage: matches!(self.geometry, GroupGeometry::Uniform(_)),
        };
        let stride = self.stride;
        let range = le * stride..(le + 1) * stride;
        assert!(
            range.end <= self.states.len,
            "state slice of element {le} out of bounds"
        );
        // SAFETY: each element owns the state slice `range` of both buffers, and every
        // pass evaluates an element at most once; the in-place pass reads a copy (or, in
        // lanes, updates the states where they are, copying only what it must).
        let new_s =
            unsafe { std::slice::from_raw_parts_mut(self.states.new.add(range.start), stride) };
        let material = self.material;
        *fe = [[0.0; 3]; 8];
        *fd = [[0.0; 3]; 8];
        if self.states.in_place {
            // The one-point kernel and the 8-point one in lanes update the states where
            // they are.
            let moved = match self.geometry {
                GroupGeometry::Uniform(g) => {
                    let e0 = self.initial.map(|e0| &e0[le]);
                    let (_, moved) = hex8_uniform::internal_force_in_place(
                        &g[le], material, &ue, e0, new_s, &ctx, fe,
                    );
                    self.damping_uniform(le, &g[le], fd);
                    Some(moved)
                }
                GroupGeometry::Full(g) if self.lanes => {
                    let e0 = self.initial.map(|e0| &e0[8 * le..8 * le + 8]);
                    let moved = hex8_full_lanes::internal_force_in_place(
                        simd, &g[le], material, &ue, e0, new_s, &ctx, fe,
                    );
                    self.damping(simd, le, fd);
                    Some(moved)
                }
                GroupGeometry::Full(_) => None,
            };
            if let Some(moved) = moved {
                self.mark_damage(le, new_s, || moved);
                return;
            }
        }
        let mut copy = std::mem::MaybeUninit::<[f64; MAX_ELEMENT_STATE]>::uninit();
        let old_s: &[f64] = if self.states.in_place {
            // The committed state of the element, read once into the copy (which
            // `ElementGroup::set_states_in_place` checked it fits).
            assert!(stride <= MAX_ELEMENT_STATE);
            let p = copy.as_mut_ptr() as *mut f64;
            // SAFETY: `stride` values copied into the copy, then only those read.
            unsafe {
                std::ptr::copy_nonoverlapping(new_s.as_ptr(), p, stride);
                std::slice::from_raw_parts(p, stride)
            }
        } else {
            unsafe { std::slice::from_raw_parts(self.states.old.add(range.start), stride) }
        };
        match self.geometry {
            GroupGeometry::Uniform(g) => {
                match self.initial {
                    None => {
                        hex8_uniform::internal_force(&g[le], material, &ue, old_s, new_s, &ctx, fe)
                    }
                    Some(e0) => hex8_uniform::internal_force_with_initial_strain(
                        &g[le],
                        material,
                        &ue,
                        Some(&e0[le]),
                        old_s,
                        new_s,
                        &ctx,
                        fe,
                    ),
                };
                self.damping_uniform(le, &g[le], fd);
            }
            GroupGeometry::Full(g) => {
                let e0 = self.initial.map(|e0| &e0[8 * le..8 * le + 8]);
                if self.lanes {
                    hex8_full_lanes::internal_force(
                        simd, &g[le], material, &ue, e0, old_s, new_s, &ctx, fe,
                    );
                } else {
                    hex8_full::internal_force_with_initial_strain(
                        &g[le], material, &ue, e0, old_s, new_s, &ctx, fe,
                    );
                }
                self.damping(simd, le, fd);
            }
        }
        self.mark_damage(le, new_s, || {
            old_s
                .chunks_exact(self.point_stride)
                .zip(new_s.chunks_exact(self.point_stride))
                .any(|(o, n)| material.hardening_moved(o, n))
        });
    }

    /// Stiffness-proportional damping force `fd` of one-point element `le` (geometry
    /// `g`), left as it is when β = 0.
    #[inline(always)]
    fn damping_uniform(&self, le: usize, g: &UniformGeometry, fd: &mut [[f64; 3]; 8]) {
        if self.beta > 0.0 {
            let nodes = &self.conn[le];
            let ve: [[f64; 3]; 8] = std::array::from_fn(|a| self.v[nodes[a] as usize]);
            damping_force_uniform(g, self.material, &ve, self.beta, fd);
        }
    }

    /// Mark element `le`, whose new states are `new_s`, as one that may hold damage when a
    /// point of it may, and then as one whose damage changed when `moved()` (the hardening
    /// of some point moved in this pass).
    #[inline(always)]
    fn mark_damage(&self, le: usize, new_s: &[f64], moved: impl FnOnce() -> bool) {
        let material = self.material;
        if material.has_damage()
            && new_s
                .chunks_exact(self.point_stride)
                .any(|p| material.may_hold_damage(p))
        {
            self.marks.mark(le);
            if moved() {
                self.changes.mark(le);
            }
        }
    }
}

/// [`Kernel::chunk_forces`] as a [`LaneWork`].
struct ChunkForces<'w, 'k> {
    kernel: &'w Kernel<'k>,
    settings: &'w ForceSettings<'w>,
    first: usize,
    out: &'w mut [[[f64; 3]; 8]],
    damping: SharedMut<[[f64; 3]; 8]>,
}

impl LaneWork for ChunkForces<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn run<S: Simd>(self, simd: S) {
        self.kernel
            .chunk_forces(simd, self.settings, self.first, self.out, self.damping)
    }
}

/// [`Kernel::run_forces`] as a [`LaneWork`].
struct RunForces<'w, 'k, A> {
    kernel: &'w Kernel<'k>,
    settings: &'w ForceSettings<'w>,
    run: std::ops::Range<usize>,
    add: &'w A,
}

impl<A: Fn(&[u32; 8], &[[f64; 3]; 8], &[[f64; 3]; 8])> LaneWork for RunForces<'_, '_, A> {
    type Output = ();
    #[inline(always)]
    fn run<S: Simd>(self, simd: S) {
        self.kernel
            .run_forces(simd, self.settings, self.run, self.add)
    }
}

/// u − u_ref for the eight nodes of an element.
#[inline(always)]
fn subtract_reference(ue: &mut [[f64; 3]; 8], r: &[[f64; 3]; 8]) {
    for a in 0..8 {
        for d in 0..3 {
            ue[a][d] -= r[a][d];
        }
    }
}

/// Runs of one colour and one colouring block (`BLOCK` consecutive global elements), in
/// the group's order, and the range of runs of each colour.
fn colouring_blocks(
    elements: &[u32],
    colour_ranges: &[std::ops::Range<usize>],
) -> (Vec<std::ops::Range<usize>>, Vec<std::ops::Range<usize>>) {
    let mut blocks = Vec::new();
    let mut colour_blocks = Vec::with_capacity(colour_ranges.len());
    for range in colour_ranges {
        let first = blocks.len();
        let mut start = range.start;
        for le in range.clone() {
            if le + 1 == range.end
                || elements[le + 1] as usize / BLOCK != elements[start] as usize / BLOCK
            {
                blocks.push(start..le + 1);
                start = le + 1;
            }
        }
        colour_blocks.push(first..blocks.len());
    }
    (blocks, colour_blocks)
}

#[inline(always)]
fn dot6(a: &Voigt, b: &Voigt) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Stiffness-proportional damping force β K0 v of a one-point element (initial stiffness,
/// hourglass included).
#[inline(always)]
fn damping_force_uniform(
    g: &UniformGeometry,
    material: &Material,
    v: &[[f64; 3]; 8],
    beta: f64,
    f: &mut [[f64; 3]; 8],
) {
    g.damping_forces(material.elastic(), v, beta, f);
}

/// Stiffness-proportional damping force β K0 v of a fully integrated element.
#[inline(always)]
fn damping_force_full(
    g: &FullGeometry,
    material: &Material,
    v: &[[f64; 3]; 8],
    beta: f64,
    f: &mut [[f64; 3]; 8],
) {
    for gp in 0..8 {
        let s = material
            .elastic()
            .stress(&g.strain(gp, v))
            .map(|x| beta * x);
        g.add_forces(gp, &s, f);
    }
}

/// The two answers (D_t, D_c at or above the threshold) as bits 0 and 1 ([`DamageScan`]).
#[inline]
fn answers(t: bool, c: bool) -> u16 {
    u16::from(t) | (u16::from(c) << 1)
}
