//! A plane free-field wall: the free field beside one vertical side of the model, a
//! two-dimensional grid in the side's plane whose elements are the side's faces (one to
//! one, so every main-grid side node has its free-field partner), extended up through the
//! overburden when the model's top lies below the ground surface. Its motion varies in
//! the plane (s along the side, z up) but not across it: every node has the three
//! displacement components, the strains are those of u(s, z) with ∂/∂n = 0 (generalised
//! plane strain), per unit thickness. This is FLAC3D's plane free-field grid.
//!
//! Bilinear quadrilaterals with 2×2 Gauss points, lumped (row-sum) masses, the elastic
//! constants of the main-grid element behind each face (the free field is linear; with a
//! static stage its initial stress is superposed, docs/boundaries.md §5). Rayleigh
//! damping as in the main grid. Its base takes the seismic input like the main grid's
//! base (springs, dashpots and the reference column's free field); its two vertical ends
//! are coupled to the 1D columns at the model's vertical edges through dashpots on the
//! relative velocity plus the columns' tractions (the columns are the free field of the
//! walls, as the walls are that of the main grid); its top is the ground surface.

use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;

use crate::boundary::centred_dashpot::CentredDashpotNode;
use crate::boundary::free_field::column::Column;
use crate::boundary::per_slot::PerSlot;
use crate::material::{Elastic, Voigt};

/// Smallest number of wall elements one parallel task takes (below it the split costs
/// more than it saves).
const ELEMENTS_PER_TASK: usize = 256;

/// Wall nodes per parallel task of the node passes.
const NODES_PER_TASK: usize = 512;

/// One Gauss point of a wall element.
#[derive(Clone, Copy, Debug)]
pub struct WallPoint {
    /// Shape functions N_a.
    pub shape: [f64; 4],
    /// ∇N_a in global coordinates (in the wall's plane).
    pub grad: [[f64; 3]; 4],
    /// Gauss weight × det J (m² per unit thickness).
    pub weight: f64,
}

/// Coupling of a wall node to a column at one level.
#[derive(Clone, Copy, Debug)]
pub struct ColumnLink {
    /// Wall node.
    pub node: u32,
    /// Column index (into the free field's columns) and level.
    pub column: u32,
    pub level: u32,
    /// Dashpot matrix (per unit thickness).
    pub dashpot: Matrix3<f64>,
    /// Spring matrix (per unit thickness; viscous-spring base only).
    pub spring: Matrix3<f64>,
    /// How the traction enters: for a lateral end, ½ h n of the column elements below and
    /// above the level; for the base, the ground below the level (length).
    pub traction: LinkTraction,
}

/// The traction a link takes from its column.
#[derive(Clone, Copy, Debug)]
pub enum LinkTraction {
    /// Lateral end with outward normal n: ½ h_below σ_below·n + ½ h_above σ_above·n,
    /// given as (½ h_below n, ½ h_above n).
    Lateral { below: [f64; 3], above: [f64; 3] },
    /// Base: the ground's traction on the column's base, times this length.
    Base { length: f64 },
}

/// A plane free-field wall.
#[derive(Clone, Debug)]
pub struct Wall {
    /// Name of the side (its face set(s)), for messages.
    pub name: String,
    /// Outward unit normal of the main grid's side.
    pub normal: [f64; 3],
    /// Main-grid node of each wall node (u32::MAX for nodes above the model's top).
    pub main_node: Vec<u32>,
    /// Wall elements (wall node indices, counter-clockwise in the (s, z) plane).
    pub elements: Vec<[u32; 4]>,
    /// Gauss points of each element.
    pub points: Vec<[WallPoint; 4]>,
    /// Material of each element.
    pub materials: Vec<Elastic>,
    /// Rayleigh (α, β) of each element.
    pub damping: Vec<(f64, f64)>,
    /// Lumped mass per unit thickness of each wall node.
    pub mass: Vec<f64>,
    /// Links to the columns (ends and base).
    pub links: Vec<ColumnLink>,
    /// Wall nodes with links, sorted, and their total dashpot / spring.
    link_nodes: Vec<u32>,
    link_dashpot: Vec<Matrix3<f64>>,
    link_spring: Vec<Matrix3<f64>>,
    updates: Vec<CentredDashpotNode>,
    /// Slot in `link_nodes` of each wall node (u32::MAX: none).
    link_slot: Vec<u32>,
    /// Mass-proportional α of each node (mass-weighted over its elements).
    alpha: Vec<f64>,
    /// State: Uⁿ (becomes U^{n+1}), V (half steps), previous values.
    u: Vec<[f64; 3]>,
    v: Vec<[f64; 3]>,
    u_prev: Vec<[f64; 3]>,
    v_prev: Vec<[f64; 3]>,
    /// Stress at each Gauss point at tⁿ.
    stress: Vec<[Voigt; 4]>,
    source: Vec<[f64; 3]>,
    /// Per-element internal and (β-scaled) damping forces of the step, computed in
    /// parallel and then added to the nodes in element order (thread-count independent).
    element_force: Vec<[[f64; 3]; 4]>,
    element_damping: Vec<[[f64; 3]; 4]>,
    /// The (element, corner) pairs `4 e + k` of each node, in element order.
    node_corners: PerSlot,
}

/// Strain (Voigt, engineering shear) from displacement gradients ∂u_i/∂x_j.
#[inline]
fn strain(g: &[[f64; 3]; 3]) -> Voigt {
    [
        g[0][0],
        g[1][1],
        g[2][2],
        g[0][1] + g[1][0],
        g[1][2] + g[2][1],
        g[2][0] + g[0][2],
    ]
}

/// σ·a for a Voigt stress and a vector.
#[inline]
pub fn stress_dot(s: &Voigt, a: &[f64; 3]) -> [f64; 3] {
    [
        s[0] * a[0] + s[3] * a[1] + s[5] * a[2],
        s[3] * a[0] + s[1] * a[1] + s[4] * a[2],
        s[5] * a[0] + s[4] * a[1] + s[2] * a[2],
    ]
}

impl WallPoint {
    /// Gauss points of a plane quadrilateral with corners `x` (3D, in a vertical plane
    /// with in-plane unit vectors `es` (horizontal) and e_z), counter-clockwise in (s, z).
    pub fn of_quad(x: &[[f64; 3]; 4], es: [f64; 3]) -> Option<[WallPoint; 4]> {
        let g = 1.0 / 3f64.sqrt();
        let xi = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
        let sz: [[f64; 2]; 4] = x.map(|p| [p[0] * es[0] + p[1] * es[1] + p[2] * es[2], p[2]]);
        let mut out = [WallPoint {
            shape: [0.0; 4],
            grad: [[0.0; 3]; 4],
            weight: 0.0,
        }; 4];
        for (q, (a, b)) in [(-g, -g), (g, -g), (g, g), (-g, g)].into_iter().enumerate() {
            let shape: [f64; 4] =
                std::array::from_fn(|k| 0.25 * (1.0 + xi[k][0] * a) * (1.0 + xi[k][1] * b));
            let dxi: [[f64; 2]; 4] = std::array::from_fn(|k| {
                [
                    0.25 * xi[k][0] * (1.0 + xi[k][1] * b),
                    0.25 * xi[k][1] * (1.0 + xi[k][0] * a),
                ]
            });
            let mut j = [[0.0; 2]; 2];
            for k in 0..4 {
                for r in 0..2 {
                    for c in 0..2 {
                        j[r][c] += sz[k][r] * dxi[k][c];
                    }
                }
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            if !(det > 0.0 && det.is_finite()) {
                return None;
            }
            let inv = [
                [j[1][1] / det, -j[0][1] / det],
                [-j[1][0] / det, j[0][0] / det],
            ];
            let mut grad = [[0.0; 3]; 4];
            for k in 0..4 {
                // ∂N/∂s, ∂N/∂z = Σ_c ∂N/∂ξ_c (J⁻¹)_{c, ·}.
                let ds = dxi[k][0] * inv[0][0] + dxi[k][1] * inv[1][0];
                let dz = dxi[k][0] * inv[0][1] + dxi[k][1] * inv[1][1];
                grad[k] = [ds * es[0], ds * es[1], ds * es[2] + dz];
            }
            out[q] = WallPoint {
                shape,
                grad,
                weight: det,
            };
        }
        Some(out)
    }
}

impl Wall {
    /// A wall from its nodes (main-grid ids, `u32::MAX` above the model), elements and
    /// their geometry and materials; links are added with [`Wall::set_links`].
    pub fn new(
        name: String,
        normal: [f64; 3],
        main_node: Vec<u32>,
        elements: Vec<[u32; 4]>,
        points: Vec<[WallPoint; 4]>,
        materials: Vec<Elastic>,
        damping: Vec<(f64, f64)>,
    ) -> Self {
        let n = main_node.len();
        let mut mass = vec![0.0; n];
        let mut alpha = vec![0.0; n];
        for (((conn, pts), m), d) in elements.iter().zip(&points).zip(&materials).zip(&damping) {
            for p in pts {
                for k in 0..4 {
                    let dm = m.density * p.shape[k] * p.weight;
                    mass[conn[k] as usize] += dm;
                    alpha[conn[k] as usize] += d.0 * dm;
                }
            }
        }
        for (a, m) in alpha.iter_mut().zip(&mass) {
            *a /= m;
        }
        let ne = elements.len();
        let node_corners = PerSlot::new(n, elements.iter().flat_map(|c| c.iter().copied()));
        Self {
            name,
            normal,
            main_node,
            elements,
            points,
            materials,
            damping,
            mass,
            links: Vec::new(),
            link_nodes: Vec::new(),
            link_dashpot: Vec::new(),
            link_spring: Vec::new(),
            updates: Vec::new(),
            link_slot: vec![u32::MAX; n],
            alpha,
            u: vec![[0.0; 3]; n],
            v: vec![[0.0; 3]; n],
            u_prev: vec![[0.0; 3]; n],
            v_prev: vec![[0.0; 3]; n],
            stress: vec![[[0.0; 6]; 4]; ne],
            source: vec![[0.0; 3]; n],
            element_force: vec![[[0.0; 3]; 4]; ne],
            element_damping: vec![[[0.0; 3]; 4]; ne],
            node_corners,
        }
    }

    /// Number of wall nodes.
    pub fn n_nodes(&self) -> usize {
        self.main_node.len()
    }

    /// Set the links to the columns.
    pub fn set_links(&mut self, links: Vec<ColumnLink>) {
        let mut nodes: Vec<u32> = links.iter().map(|l| l.node).collect();
        nodes.sort_unstable();
        nodes.dedup();
        self.link_dashpot = vec![Matrix3::zeros(); nodes.len()];
        self.link_spring = vec![Matrix3::zeros(); nodes.len()];
        for (slot, &n) in nodes.iter().enumerate() {
            self.link_slot[n as usize] = slot as u32;
        }
        for l in &links {
            let s = self.link_slot[l.node as usize] as usize;
            self.link_dashpot[s] += l.dashpot;
            self.link_spring[s] += l.spring;
        }
        self.link_nodes = nodes;
        self.links = links;
    }

    /// Precompute the node updates for Δt.
    pub fn prepare(&mut self, dt: f64) {
        self.updates = self
            .link_nodes
            .iter()
            .zip(&self.link_dashpot)
            .map(|(&n, c)| CentredDashpotNode::new(self.mass[n as usize], *c, 0, dt))
            .collect();
    }

    /// Largest ω² of the wall: per element, by power iteration on its own kernel with the
    /// lumped masses of the free element (Irons–Treharne), plus the springs' K/M.
    pub fn max_omega_squared(&self) -> f64 {
        let mut w2 = 0.0f64;
        for (e, pts) in self.points.iter().enumerate() {
            let m = &self.materials[e];
            let mut mass = [0.0; 4];
            for p in pts {
                for k in 0..4 {
                    mass[k] += m.density * p.shape[k] * p.weight;
                }
            }
            // Power iteration on M⁻¹K.
            let mut x = [[0.0; 3]; 4];
            for k in 0..4 {
                x[k] = [
                    1.0 + 0.1 * k as f64,
                    -0.7 + 0.3 * k as f64,
                    0.5 - 0.2 * k as f64,
                ];
            }
            let mut lambda = 0.0;
            for _ in 0..200 {
                let f = element_forces(pts, m, &x);
                let y: [[f64; 3]; 4] =
                    std::array::from_fn(|k| std::array::from_fn(|d| f[k][d] / mass[k]));
                let num: f64 = (0..4)
                    .map(|k| (0..3).map(|d| mass[k] * x[k][d] * y[k][d]).sum::<f64>())
                    .sum();
                let den: f64 = (0..4)
                    .map(|k| (0..3).map(|d| mass[k] * x[k][d] * x[k][d]).sum::<f64>())
                    .sum();
                lambda = num / den;
                let norm = (0..4)
                    .map(|k| (0..3).map(|d| mass[k] * y[k][d] * y[k][d]).sum::<f64>())
                    .sum::<f64>()
                    .sqrt();
                if norm == 0.0 {
                    break;
                }
                x = std::array::from_fn(|k| std::array::from_fn(|d| y[k][d] / norm));
            }
            // The Rayleigh quotient approaches λ_max from below: 1 % margin.
            w2 = w2.max(1.01 * lambda);
        }
        let springs = self
            .link_nodes
            .iter()
            .zip(&self.link_spring)
            .map(|(&n, k)| k.symmetric_eigenvalues().max() / self.mass[n as usize])
            .fold(0.0, f64::max);
        w2 + springs
    }

    /// One step tⁿ → tⁿ⁺¹; `columns` hold the columns' state at tⁿ (already stepped).
    pub fn step(&mut self, columns: &[Column], dt: f64) {
        for f in self.source.iter_mut() {
            *f = [0.0; 3];
        }
        // Element forces in parallel (each element writes only its own slots) …
        let (u, v) = (&self.u, &self.v);
        self.element_force
            .par_iter_mut()
            .zip(self.element_damping.par_iter_mut())
            .zip(self.stress.par_iter_mut())
            .zip(self.elements.par_iter())
            .zip(self.points.par_iter())
            .zip(self.materials.par_iter())
            .zip(self.damping.par_iter())
            .with_min_len(ELEMENTS_PER_TASK)
            .for_each(|((((((fe, fd), s), conn), pts), m), &(_, beta))| {
                let ue: [[f64; 3]; 4] = std::array::from_fn(|k| u[conn[k] as usize]);
                *fe = element_forces_with_stress(pts, m, &ue, s);
                if beta > 0.0 {
                    let ve: [[f64; 3]; 4] = std::array::from_fn(|k| v[conn[k] as usize]);
                    let f = element_forces(pts, m, &ve);
                    *fd = f.map(|fk| fk.map(|x| beta * x));
                }
            });
        // Column-driven forces on the linked nodes.
        for l in &self.links {
            let col = &columns[l.column as usize];
            let lev = l.level as usize;
            let u = Vector3::from(col.displacement(lev));
            let v = Vector3::from(col.velocity(lev));
            let f = l.spring * u + l.dashpot * v;
            let t = match l.traction {
                LinkTraction::Lateral { below, above } => {
                    let mut t = [0.0; 3];
                    if lev > 0 {
                        let s = stress_dot(&col.stress(lev - 1), &below);
                        t = std::array::from_fn(|d| t[d] + s[d]);
                    }
                    if lev + 1 < col.n_levels() {
                        let s = stress_dot(&col.stress(lev), &above);
                        t = std::array::from_fn(|d| t[d] + s[d]);
                    }
                    t
                }
                LinkTraction::Base { length } => col.base_traction().map(|x| x * length),
            };
            let s = &mut self.source[l.node as usize];
            for d in 0..3 {
                s[d] += f[d] + t[d];
            }
        }
        self.u_prev.copy_from_slice(&self.u);
        self.v_prev.copy_from_slice(&self.v);
        // Each node on its own, in parallel: its element forces added in element order (the
        // same sums on any thread count), then its update.
        let (ef, ed, damping) = (&self.element_force, &self.element_damping, &self.damping);
        let corners = &self.node_corners;
        let (mass, link_slot, alpha, source) =
            (&self.mass, &self.link_slot, &self.alpha, &self.source);
        let (u_prev, v_prev) = (&self.u_prev, &self.v_prev);
        let (link_spring, updates) = (&self.link_spring, &self.updates);
        self.u
            .par_chunks_mut(NODES_PER_TASK)
            .zip(self.v.par_chunks_mut(NODES_PER_TASK))
            .enumerate()
            .for_each(|(c, (us, vs))| {
                for (k, (u, v)) in us.iter_mut().zip(vs).enumerate() {
                    let i = c * NODES_PER_TASK + k;
                    let (mut fi, mut fd) = ([0.0; 3], [0.0; 3]);
                    for &ek in corners.of(i) {
                        let (e, a) = (ek as usize / 4, ek as usize % 4);
                        for d in 0..3 {
                            fi[d] += ef[e][a][d];
                        }
                        if damping[e].1 > 0.0 {
                            for d in 0..3 {
                                fd[d] += ed[e][a][d];
                            }
                        }
                    }
                    let m = mass[i];
                    let slot = link_slot[i];
                    let mut force: [f64; 3] = std::array::from_fn(|d| {
                        source[i][d] - fi[d] - fd[d] - alpha[i] * m * v_prev[i][d]
                    });
                    let vn = if slot == u32::MAX {
                        std::array::from_fn(|d| v_prev[i][d] + dt * force[d] / m)
                    } else {
                        let s = slot as usize;
                        let ku = link_spring[s] * Vector3::from(u_prev[i]);
                        for d in 0..3 {
                            force[d] -= ku[d];
                        }
                        updates[s].half_step_velocity(v_prev[i], force, [0.0; 3], dt)
                    };
                    *v = vn;
                    for d in 0..3 {
                        u[d] += dt * vn[d];
                    }
                }
            });
    }

    /// Displacement of wall node `i` at tⁿ of the last step.
    #[inline]
    pub fn displacement(&self, i: usize) -> [f64; 3] {
        self.u_prev[i]
    }

    /// Full-step velocity of wall node `i` at tⁿ of the last step.
    #[inline]
    pub fn velocity(&self, i: usize) -> [f64; 3] {
        std::array::from_fn(|d| 0.5 * (self.v_prev[i][d] + self.v[i][d]))
    }

    /// Stress at Gauss point `q` of element `e` at tⁿ of the last step.
    #[inline]
    pub fn stress(&self, e: usize, q: usize) -> Voigt {
        self.stress[e][q]
    }

    /// State for checkpoints.
    pub fn state_values(&self, out: &mut Vec<f64>) {
        for f in [&self.u, &self.v, &self.u_prev, &self.v_prev] {
            out.extend(f.iter().flatten());
        }
        out.extend(self.stress.iter().flatten().flatten());
    }

    /// Restore what [`Wall::state_values`] wrote; returns the values consumed.
    pub fn restore_state(&mut self, values: &[f64]) -> Result<usize, String> {
        let need = 12 * self.n_nodes() + 24 * self.elements.len();
        if values.len() < need {
            return Err(format!(
                "free-field wall '{}' state too short ({} values, {need} needed)",
                self.name,
                values.len()
            ));
        }
        let mut it = values.iter().copied();
        for f in [&mut self.u, &mut self.v, &mut self.u_prev, &mut self.v_prev] {
            for x in f.iter_mut().flatten() {
                *x = it.next().unwrap_or_default();
            }
        }
        for x in self.stress.iter_mut().flatten().flatten() {
            *x = it.next().unwrap_or_default();
        }
        Ok(need)
    }
}

/// Internal forces ∫ σ·∇N_a dA of a wall element (per unit thickness).
fn element_forces(pts: &[WallPoint; 4], m: &Elastic, u: &[[f64; 3]; 4]) -> [[f64; 3]; 4] {
    let mut s = [[0.0; 6]; 4];
    element_forces_with_stress(pts, m, u, &mut s)
}

/// [`element_forces`], also returning the stress at the Gauss points.
fn element_forces_with_stress(
    pts: &[WallPoint; 4],
    m: &Elastic,
    u: &[[f64; 3]; 4],
    stress: &mut [Voigt; 4],
) -> [[f64; 3]; 4] {
    let mut f = [[0.0; 3]; 4];
    for (q, p) in pts.iter().enumerate() {
        let mut g = [[0.0; 3]; 3];
        for k in 0..4 {
            for i in 0..3 {
                for j in 0..3 {
                    g[i][j] += u[k][i] * p.grad[k][j];
                }
            }
        }
        let s = m.stress(&strain(&g));
        stress[q] = s;
        for k in 0..4 {
            let t = stress_dot(&s, &p.grad[k]);
            for d in 0..3 {
                f[k][d] += t[d] * p.weight;
            }
        }
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad_in_a_tilted_vertical_plane_has_the_right_area_and_gradients() {
        // A 2 × 3 rectangle in the vertical plane through the origin with normal
        // n = (cos 30°, sin 30°, 0); e_s = e_z × n = (−sin 30°, cos 30°, 0).
        let (s30, c30) = (0.5f64, 3f64.sqrt() / 2.0);
        let es = [-s30, c30, 0.0];
        let at = |s: f64, z: f64| [s * es[0], s * es[1], z];
        let x = [at(0.0, 0.0), at(2.0, 0.0), at(2.0, 3.0), at(0.0, 3.0)];
        let pts = WallPoint::of_quad(&x, es).unwrap();
        let area: f64 = pts.iter().map(|p| p.weight).sum();
        assert!((area - 6.0).abs() < 1e-12);
        // A linear field u = x reproduces ∇u exactly: Σ_a x_a ⊗ ∇N_a = P (projector on
        // the plane).
        for p in &pts {
            for i in 0..3 {
                for j in 0..3 {
                    let g: f64 = (0..4).map(|k| x[k][i] * p.grad[k][j]).sum();
                    let proj = es[i] * es[j] + if i == 2 && j == 2 { 1.0 } else { 0.0 };
                    assert!((g - proj).abs() < 1e-12, "{i}{j}: {g} vs {proj}");
                }
            }
        }
    }

    #[test]
    fn rigid_motion_gives_no_force() {
        let es = [1.0, 0.0, 0.0];
        let x = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.2, 0.0, 1.0],
            [0.1, 0.0, 1.1],
        ];
        let pts = WallPoint::of_quad(&x, es).unwrap();
        let m = Elastic::new("r", 20e9, 0.25, 2700.0).unwrap();
        let f = element_forces(&pts, &m, &[[0.3, -0.2, 0.1]; 4]);
        assert!(f.iter().flatten().all(|v| v.abs() < 1e-3));
    }
}
