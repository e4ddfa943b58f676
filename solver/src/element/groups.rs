//! Element groups: the elements of one region with their material, integration rule,
//! precomputed geometry and integration-point state, sorted by colour so that every
//! colour is one contiguous range processed in parallel.

use rayon::prelude::*;

use crate::element::colouring::BLOCK;
use crate::element::hex8_full::{self, FullGeometry};
use crate::element::hex8_uniform::{self, UniformGeometry};
use crate::element::stable_step::characteristic_length;
use crate::element::Integration;
use crate::error::{DcfmError, Result};
use crate::material::{Material, PointContext, PointStates, Voigt};
use crate::mesh::Mesh;

/// Precomputed geometry of a group's elements.
#[derive(Clone, Debug)]
pub enum GroupGeometry {
    /// One-point elements.
    Uniform(Vec<UniformGeometry>),
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
    /// Integration-point state (`integration.points()` points per element).
    pub states: PointStates,
}

/// Raw pointer made shareable across threads; every use writes disjoint indices
/// (guaranteed by the colouring / by element ownership of its state slice).
#[derive(Clone, Copy)]
struct SharedMut<T>(*mut T);
unsafe impl<T> Send for SharedMut<T> {}
unsafe impl<T> Sync for SharedMut<T> {}

impl<T> SharedMut<T> {
    /// # Safety
    /// `i` must be in bounds and no other thread may access index `i` concurrently.
    #[inline(always)]
    unsafe fn at(self, i: usize) -> *mut T {
        self.0.add(i)
    }
}

/// Rayleigh stiffness-proportional damping coefficient and time step, passed to the kernels.
#[derive(Clone, Copy, Debug)]
pub struct ForceSettings {
    /// β of C = αM + βK (s).
    pub beta: f64,
    /// Time step (s).
    pub dt: f64,
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
        let mut blocks = Vec::new();
        let mut colour_blocks = Vec::with_capacity(n_colours);
        for range in &colour_ranges {
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
                GroupGeometry::Uniform(g)
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
        let stride = material.state_len();
        let n_points = elements.len() * integration.points();
        let states = PointStates::new(stride, n_points, |_, s| material.init_state(s));
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
            GroupGeometry::Uniform(_) => std::mem::size_of::<UniformGeometry>(),
            GroupGeometry::Full(_) => std::mem::size_of::<FullGeometry>(),
        };
        let fixed = geo + std::mem::size_of::<[u32; 8]>() + 4 + 2 * 8;
        fixed as f64 + self.states.bytes() as f64 / self.len() as f64
    }

    /// Add the internal forces of the elements of colour `c` into `f_int` (and the
    /// stiffness-proportional damping forces into `f_damp` when β > 0). Elements of one
    /// colour share no node, so the parallel adds never touch the same node; each run of
    /// one colouring block is added by one thread in the group's order.
    pub fn add_colour_forces(
        &mut self,
        c: usize,
        u: &[[f64; 3]],
        v: &[[f64; 3]],
        settings: ForceSettings,
        f_int: &mut [[f64; 3]],
        f_damp: &mut [[f64; 3]],
    ) {
        let Some(block_range) = self.colour_blocks.get(c).cloned() else {
            return;
        };
        if block_range.is_empty() {
            return;
        }
        let blocks = &self.blocks[block_range];
        let stride = self.states.stride() * self.integration.points();
        let (old, new) = self.states.split();
        let new_ptr = SharedMut(new.as_mut_ptr());
        let f_ptr = SharedMut(f_int.as_mut_ptr());
        let d_ptr = SharedMut(f_damp.as_mut_ptr());
        let n_nodes = f_int.len();
        debug_assert_eq!(f_damp.len(), n_nodes);
        let material = &self.material;
        let conn = &self.conn;
        let lengths = &self.char_length;
        let geometry = &self.geometry;
        let beta = settings.beta;
        let dt = settings.dt;
        let element = |le: usize| {
            let nodes = &conn[le];
            let ue: [[f64; 3]; 8] = std::array::from_fn(|a| u[nodes[a] as usize]);
            let ve: [[f64; 3]; 8] = if beta > 0.0 {
                std::array::from_fn(|a| v[nodes[a] as usize])
            } else {
                [[0.0; 3]; 8]
            };
            let ctx = PointContext {
                char_length: lengths[le],
                dt,
            };
            let old_s = &old[le * stride..(le + 1) * stride];
            // SAFETY: each element owns the state slice [le*stride, (le+1)*stride).
            let new_s = unsafe { std::slice::from_raw_parts_mut(new_ptr.at(le * stride), stride) };
            let mut fe = [[0.0; 3]; 8];
            let mut fd = [[0.0; 3]; 8];
            match geometry {
                GroupGeometry::Uniform(g) => {
                    hex8_uniform::internal_force(
                        &g[le], material, &ue, old_s, new_s, &ctx, &mut fe,
                    );
                    if beta > 0.0 {
                        damping_force_uniform(&g[le], material, &ve, beta, &mut fd);
                    }
                }
                GroupGeometry::Full(g) => {
                    hex8_full::internal_force(&g[le], material, &ue, old_s, new_s, &ctx, &mut fe);
                    if beta > 0.0 {
                        damping_force_full(&g[le], material, &ve, beta, &mut fd);
                    }
                }
            }
            for a in 0..8 {
                let n = nodes[a] as usize;
                debug_assert!(n < n_nodes);
                // SAFETY: no element of another run of this colour has node n (block
                // colouring), and the elements of this run are added serially by this thread.
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
        blocks
            .par_iter()
            .for_each(|run| run.clone().for_each(element));
    }

    /// Volume-averaged strain and stress of the group's element `le` from displacements
    /// `u` and the committed state (changes nothing).
    pub fn strain_stress_of(&self, le: usize, u: &[[f64; 3]]) -> (Voigt, Voigt) {
        let stride = self.states.stride();
        let state = self.states.current();
        let nodes = &self.conn[le];
        let ue: [[f64; 3]; 8] = std::array::from_fn(|a| u[nodes[a] as usize]);
        match &self.geometry {
            GroupGeometry::Uniform(g) => {
                let eps = g[le].strain(&ue);
                let s = &state[le * stride..(le + 1) * stride];
                (eps, self.material.stress_from_state(&eps, s))
            }
            GroupGeometry::Full(g) => {
                let mut em = [0.0; 6];
                let mut sm = [0.0; 6];
                let vol = g[le].volume();
                for gp in 0..8 {
                    let eps = g[le].strain(gp, &ue);
                    let p = le * 8 + gp;
                    let s = self
                        .material
                        .stress_from_state(&eps, &state[p * stride..(p + 1) * stride]);
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
    pub fn damaged_volume(&self, threshold: f64, per_element: bool) -> [f64; 3] {
        let mut v = [0.0; 3];
        if !self.material.has_damage() {
            return v;
        }
        let stride = self.states.stride();
        let np = self.integration.points();
        let state = self.states.current();
        let mut add = |dt: f64, dc: f64, vol: f64| {
            let (t, c) = (dt >= threshold, dc >= threshold);
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
        for le in 0..self.len() {
            let (mut et, mut ec) = (0.0, 0.0);
            for gp in 0..np {
                let p = le * np + gp;
                if let Some(d) = self
                    .material
                    .damage_state(&state[p * stride..(p + 1) * stride])
                {
                    let pv = self.point_volume(le, gp);
                    if per_element {
                        et += d.dt * pv / self.volume[le];
                        ec += d.dc * pv / self.volume[le];
                    } else {
                        add(d.dt, d.dc, pv);
                    }
                }
            }
            if per_element {
                add(et, ec, self.volume[le]);
            }
        }
        v
    }

    /// Elastic strain energy ½ ∫ ε : E0 : ε dV (+ hourglass energy ½ κ q²) of the group for
    /// displacements `u` — exact for linear elastic groups, used to check conservation.
    pub fn elastic_strain_energy(&self, u: &[[f64; 3]]) -> f64 {
        let el = *self.material.elastic();
        let parts: Vec<f64> = (0..self.len())
            .into_par_iter()
            .with_min_len(1024)
            .map(|le| {
                let nodes = &self.conn[le];
                let ue: [[f64; 3]; 8] = std::array::from_fn(|a| u[nodes[a] as usize]);
                match &self.geometry {
                    GroupGeometry::Uniform(g) => {
                        let g = &g[le];
                        let e = g.strain(&ue);
                        let s = el.stress(&e);
                        let q = g.hourglass_modes(&ue);
                        let hq: f64 = q.iter().flatten().map(|x| x * x).sum();
                        0.5 * g.volume * dot6(&s, &e) + 0.5 * g.kappa * hq
                    }
                    GroupGeometry::Full(g) => (0..8)
                        .map(|gp| {
                            let e = g[le].strain(gp, &ue);
                            0.5 * g[le].wdet[gp] * dot6(&el.stress(&e), &e)
                        })
                        .sum(),
                }
            })
            .collect();
        parts.iter().sum()
    }
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
