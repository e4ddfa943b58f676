//! Internal-force kernels of one hex8 element, elastic material:
//! - `one_point`: uniform-strain gradient + Flanagan–Belytschko hourglass forces
//!   (`hex8_uniform::internal_force`, dispatched like the step so that its fused
//!   multiply-adds are FMA instructions);
//! - `full`: 2×2×2 Gauss points (`hex8_full::internal_force`);
//! - `full_lanes`: the same with the eight Gauss points in SIMD lanes
//!   (`hex8_full_lanes::internal_force` through `InternalForce`, dispatched like the step);
//! - `hex8_full/single_matrix`, `hex8_full/stream_64000_matrix`: the same elastic force as
//!   K u through the element's stiffness matrix (`elastic_matrices::ElementMatrix`, the
//!   step's path for elastic elements whose geometry repeats), dispatched like the step;
//!   the sweep with one matrix shared by the 64 000 elements, as a box's repeated cells
//!   share it;
//! - `hex8_full_plastic_damage/{scalar,lanes}`: both with the plastic-damage model below
//!   first yield (the never-yielded shortcut, checked in lanes by the lane kernel);
//!   `.../{scalar,lanes}_cracked`: the same element cracked under the consistent recovery
//!   and unloaded a little, its eight points damaged (D_t > 0) and inside their surfaces
//!   (the yielded-elastic branch, `PlasticDamage::yielded_lanes` in lanes: the late
//!   Yingxiuwan step's concrete). One element evaluated over and over: its branches are
//!   the same at every iteration, so the row favours branchy code over masked lanes;
//! - `hex8_one_point_plastic_damage/in_place`: the one-point kernel with the plastic-damage
//!   model below first yield, its state updated in place, dispatched like the step (the
//!   Yingxiuwan rock's kernel); `.../lanes_of_8`: eight such elements at once in SIMD lanes
//!   (`hex8_uniform_lanes::LaneKernel`, dispatched as the force pass does, geometry in a
//!   lane block), counted
//!   as eight elements.
//!
//! `*/single` runs one element whose data stays in L1 (pure arithmetic cost);
//! `*/stream_64000` sweeps the geometry of 64 000 distinct elements (the 40³ cube's working
//! set), gathering displacements and scattering forces through a 40³ connectivity like the
//! solver does (serially, in mesh order, no colouring), so the gap between the two is the
//! memory cost per element.
//!
//! The kernels are the split Flanagan–Belytschko one-point form (304 B of geometry) and
//! the J⁻¹-per-Gauss-point full form (640 B), see docs/benchmarks.md for their history.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use dcfm::element::elastic_matrices::ElementMatrix;
use dcfm::element::hex8_full::{self, FullGeometry};
use dcfm::element::hex8_full_lanes::InternalForce;
use dcfm::element::hex8_uniform::{self, UniformGeometry};
use dcfm::element::hex8_uniform_lanes::{LaneKernel, UniformBlock};
use dcfm::element::lanes::{run_lane_work, F64s, LaneWork, NodalLanes, Simd, LANES};
use dcfm::material::plastic_damage::{PlasticDamageParams, Recovery};
use dcfm::material::{Elastic, Material, PlasticDamage, PointContext};

/// A distorted 0.25 m hexahedron (node order of `hex8_shape::NODE_XI`), shifted by `s`.
fn coords(s: f64) -> [[f64; 3]; 8] {
    let h = 0.25;
    let x = [
        [0.0, 0.0, 0.0],
        [h, 0.01, -0.005],
        [1.05 * h, 0.98 * h, 0.0],
        [0.02, h, 0.01],
        [0.0, 0.01, h],
        [0.97 * h, 0.0, 1.02 * h],
        [h, h, h],
        [-0.01, 1.03 * h, 0.99 * h],
    ];
    x.map(|p| [p[0] + s, p[1], p[2]])
}

/// A smooth, non-trivial displacement of the element's nodes.
fn displacements(x: &[[f64; 3]; 8]) -> [[f64; 3]; 8] {
    x.map(|p| {
        [
            1e-4 * p[1] + 2e-5 * p[0] * p[2],
            -3e-5 * p[0] + 1e-5 * p[2],
            5e-5 * p[2] + 1e-5 * p[0] * p[1],
        ]
    })
}

fn material() -> Material {
    Material::Elastic(Elastic::new("rock", 20e9, 0.25, 2700.0).expect("valid elastic constants"))
}

/// [`material`]'s elastic constants with plastic damage (f_t0 2.9 MPa, f_c0 13 MPa,
/// f_cu 24.1 MPa, G_t 100 J/m², G_c 10 kJ/m²).
fn plastic_damage() -> Material {
    Material::PlasticDamage(Box::new(
        PlasticDamage::new(
            "concrete",
            *material().elastic(),
            &PlasticDamageParams::from_strengths(2.9e6, 13e6, 24.1e6, 100.0, 10e3),
        )
        .expect("valid plastic-damage parameters"),
    ))
}

/// The update context of the 0.25 m elements.
fn context() -> PointContext {
    PointContext {
        char_length: 0.25,
        dt: 1e-5,
        reads_damage: false,
    }
}

const STREAM: usize = 64_000;

/// Connectivity of `STREAM` elements over a pool of displacement "nodes", each element
/// reading 8 nodes spread through the array like a structured mesh does.
fn stream_setup() -> (Vec<[u32; 8]>, Vec<[f64; 3]>) {
    let n = 40usize;
    let np = n + 1;
    let node = |i: usize, j: usize, k: usize| (i + np * (j + np * k)) as u32;
    let mut conn = Vec::with_capacity(STREAM);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                conn.push([
                    node(i, j, k),
                    node(i + 1, j, k),
                    node(i + 1, j + 1, k),
                    node(i, j + 1, k),
                    node(i, j, k + 1),
                    node(i + 1, j, k + 1),
                    node(i + 1, j + 1, k + 1),
                    node(i, j + 1, k + 1),
                ]);
            }
        }
    }
    let u = (0..np * np * np)
        .map(|i| {
            let t = i as f64 * 1e-3;
            [1e-5 * t.sin(), 1e-5 * t.cos(), 1e-6 * t]
        })
        .collect();
    (conn, u)
}

/// One elastic one-point element (`hex8_uniform::internal_force`), inside pulp's dispatch
/// as the step runs its kernels (so that its fused multiply-adds are FMA instructions).
struct OnePointForce<'a> {
    geo: &'a UniformGeometry,
    material: &'a Material,
    u: &'a [[f64; 3]; 8],
    ctx: &'a PointContext,
    f: &'a mut [[f64; 3]; 8],
}

impl LaneWork for OnePointForce<'_> {
    type Output = [f64; 6];
    #[inline(always)]
    fn run<S: Simd>(self, _simd: S) -> [f64; 6] {
        hex8_uniform::internal_force(
            self.geo,
            self.material,
            self.u,
            &[],
            &mut [],
            self.ctx,
            self.f,
        )
    }
}

/// The sweep of `hex8_one_point/stream_64000`: every element's displacements gathered,
/// its force computed and scattered, in mesh order, inside one dispatch.
struct OnePointSweep<'a> {
    geos: &'a [UniformGeometry],
    conn: &'a [[u32; 8]],
    u: &'a [[f64; 3]],
    material: &'a Material,
    ctx: &'a PointContext,
    f_int: &'a mut [[f64; 3]],
}

impl LaneWork for OnePointSweep<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: Simd>(self, _simd: S) {
        for (g, nodes) in self.geos.iter().zip(self.conn) {
            let ue: [[f64; 3]; 8] = std::array::from_fn(|a| self.u[nodes[a] as usize]);
            let mut f = [[0.0; 3]; 8];
            hex8_uniform::internal_force(g, self.material, &ue, &[], &mut [], self.ctx, &mut f);
            for (a, fa) in f.iter().enumerate() {
                let p = &mut self.f_int[nodes[a] as usize];
                p[0] += fa[0];
                p[1] += fa[1];
                p[2] += fa[2];
            }
        }
    }
}

fn one_point(c: &mut Criterion) {
    let mat = material();
    let ctx = context();
    let x = coords(0.0);
    let geo = UniformGeometry::new(&x, mat.elastic(), 0.05).expect("valid element");
    let u = displacements(&x);
    let mut group = c.benchmark_group("hex8_one_point");
    group.throughput(Throughput::Elements(1));
    group.bench_function("single", |b| {
        let mut f = [[0.0; 3]; 8];
        b.iter(|| {
            let s = run_lane_work(OnePointForce {
                geo: black_box(&geo),
                material: &mat,
                u: black_box(&u),
                ctx: &ctx,
                f: &mut f,
            });
            black_box((&f, s));
        })
    });
    let (conn, us) = stream_setup();
    let geos: Vec<UniformGeometry> = (0..STREAM)
        .map(|e| {
            UniformGeometry::new(&coords(e as f64), mat.elastic(), 0.05).expect("valid element")
        })
        .collect();
    group.throughput(Throughput::Elements(STREAM as u64));
    group.sample_size(20);
    group.bench_function("stream_64000", |b| {
        let mut f_int = vec![[0.0; 3]; us.len()];
        b.iter(|| {
            run_lane_work(OnePointSweep {
                geos: &geos,
                conn: &conn,
                u: &us,
                material: &mat,
                ctx: &ctx,
                f_int: &mut f_int,
            });
            black_box(&mut f_int);
        })
    });
    group.finish();
}

fn full(c: &mut Criterion) {
    let mat = material();
    let ctx = context();
    let x = coords(0.0);
    let geo = FullGeometry::new(&x).expect("valid element");
    let u = displacements(&x);
    let mut group = c.benchmark_group("hex8_full");
    group.throughput(Throughput::Elements(1));
    group.bench_function("single", |b| {
        let mut f = [[0.0; 3]; 8];
        b.iter(|| {
            let s = hex8_full::internal_force(
                black_box(&geo),
                &mat,
                black_box(&u),
                &[],
                &mut [],
                &ctx,
                &mut f,
            );
            black_box((&f, s));
        })
    });
    let (conn, us) = stream_setup();
    let geos: Vec<FullGeometry> = (0..STREAM)
        .map(|e| FullGeometry::new(&coords(e as f64)).expect("valid element"))
        .collect();
    group.throughput(Throughput::Elements(STREAM as u64));
    group.sample_size(10);
    group.bench_function("stream_64000", |b| {
        let mut f_int = vec![[0.0; 3]; us.len()];
        b.iter(|| {
            for (g, nodes) in geos.iter().zip(&conn) {
                let ue: [[f64; 3]; 8] = std::array::from_fn(|a| us[nodes[a] as usize]);
                let mut f = [[0.0; 3]; 8];
                hex8_full::internal_force(g, &mat, &ue, &[], &mut [], &ctx, &mut f);
                for (a, fa) in f.iter().enumerate() {
                    let p = &mut f_int[nodes[a] as usize];
                    p[0] += fa[0];
                    p[1] += fa[1];
                    p[2] += fa[2];
                }
            }
            black_box(&mut f_int);
        })
    });
    group.finish();
}

/// One element's forces with its Gauss points in lanes, dispatched like the step, the
/// geometry and displacements behind `black_box`.
fn lanes_force(
    geo: &FullGeometry,
    material: &Material,
    u: &[[f64; 3]; 8],
    old: &[f64],
    new: &mut [f64],
    ctx: &PointContext,
    f: &mut [[f64; 3]; 8],
) {
    run_lane_work(InternalForce {
        geo: black_box(geo),
        material,
        u: black_box(u),
        eps0: None,
        old,
        new,
        ctx,
        f,
    });
    black_box(f);
}

fn full_lanes(c: &mut Criterion) {
    let ctx = context();
    let x = coords(0.0);
    let geo = FullGeometry::new(&x).expect("valid element");
    let u = displacements(&x);
    let elastic = material();
    let plastic = plastic_damage();
    for (name, mat) in [
        ("hex8_full", &elastic),
        ("hex8_full_plastic_damage", &plastic),
    ] {
        let stride = mat.state_len();
        let old = {
            let mut s = vec![0.0; 8 * stride];
            for p in s.chunks_exact_mut(stride.max(1)) {
                mat.init_state(p);
            }
            s
        };
        let mut new = old.clone();
        let mut group = c.benchmark_group(name);
        group.throughput(Throughput::Elements(1));
        if stride > 0 {
            group.bench_function("scalar", |b| {
                let mut f = [[0.0; 3]; 8];
                b.iter(|| {
                    hex8_full::internal_force(
                        black_box(&geo),
                        mat,
                        black_box(&u),
                        &old,
                        &mut new,
                        &ctx,
                        &mut f,
                    );
                    black_box(&f);
                })
            });
        }
        group.bench_function(if stride > 0 { "lanes" } else { "single_lanes" }, |b| {
            let mut f = [[0.0; 3]; 8];
            b.iter(|| {
                lanes_force(&geo, mat, &u, &old, &mut new, &ctx, &mut f);
            })
        });
        group.finish();
    }
}

/// `hex8_full_plastic_damage/{scalar,lanes}_cracked` (module docs): the element stretched
/// in three steps to 30 × [`displacements`] (strains of order 3e-3, twenty times the
/// cracking strain) under the consistent recovery, then evaluated from that state at the
/// least unloading, from 30 × down in steps of 0.1, that leaves every point cracked and
/// inside its surface (the factor is printed).
fn full_lanes_cracked(c: &mut Criterion) {
    let ctx = context();
    let x = coords(0.0);
    let geo = FullGeometry::new(&x).expect("valid element");
    let u = displacements(&x);
    let scaled = |s: f64| u.map(|n| n.map(|v| s * v));
    let mat = Material::PlasticDamage(Box::new(
        PlasticDamage::new(
            "concrete",
            *material().elastic(),
            &PlasticDamageParams {
                recovery: Recovery::Consistent,
                ..PlasticDamageParams::from_strengths(2.9e6, 13e6, 24.1e6, 100.0, 10e3)
            },
        )
        .expect("valid plastic-damage parameters"),
    ));
    let stride = mat.state_len();
    let mut fresh = vec![0.0; 8 * stride];
    for p in fresh.chunks_exact_mut(stride) {
        mat.init_state(p);
    }
    let pd = match &mat {
        Material::PlasticDamage(pd) => pd,
        _ => unreachable!("built as plastic damage"),
    };
    // The element cracked along `field`, and the least unloading (from 30 × down) that
    // leaves all eight points cracked inside their surfaces: (state, displacements, factor).
    let crack = |field: &dyn Fn(f64) -> [[f64; 3]; 8]| {
        let mut f = [[0.0; 3]; 8];
        let mut old = fresh.clone();
        let mut new = fresh.clone();
        for s in [10.0, 20.0, 30.0] {
            hex8_full::internal_force(&geo, &mat, &field(s), &old, &mut new, &ctx, &mut f);
            old.copy_from_slice(&new);
        }
        (1..=290).map(|k| 30.0 - 0.1 * k as f64).find_map(|s| {
            hex8_full::internal_force(&geo, &mat, &field(s), &old, &mut new, &ctx, &mut f);
            (0..8)
                .all(|g| {
                    let (o, n) = (&old[g * stride..][..stride], &new[g * stride..][..stride]);
                    !mat.hardening_moved(o, n) && pd.tensile_damage(o) > 0.0
                })
                .then(|| (old.clone(), field(s), s))
        })
    };
    let (old, unloaded, factor) =
        crack(&scaled).expect("an unloading that stays inside every surface");
    eprintln!("hex8_full_plastic_damage/*_cracked: unloaded to {factor:.1} × the displacements");
    // Elements cracked along 64 fields: the bench's field plus a random uniform gradient
    // of the same size per element (LCG), those that find such an unloading.
    let mut seed = 0x5eed_c0de_u64;
    let mut rand = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let varied: Vec<(Vec<f64>, [[f64; 3]; 8])> = (0..64)
        .filter_map(|_| {
            let g: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| 2e-4 * rand()));
            let field = |s: f64| {
                std::array::from_fn(|a| {
                    std::array::from_fn(|i| {
                        s * (u[a][i] + g[i][0] * x[a][0] + g[i][1] * x[a][1] + g[i][2] * x[a][2])
                    })
                })
            };
            crack(&field).map(|(state, u, _)| (state, u))
        })
        .collect();
    eprintln!(
        "hex8_full_plastic_damage/lanes_cracked_varied: {} elements",
        varied.len()
    );
    let mut new = old.clone();
    let mut f = [[0.0; 3]; 8];
    let mut group = c.benchmark_group("hex8_full_plastic_damage");
    group.throughput(Throughput::Elements(1));
    group.bench_function("scalar_cracked", |b| {
        b.iter(|| {
            hex8_full::internal_force(
                black_box(&geo),
                &mat,
                black_box(&unloaded),
                &old,
                &mut new,
                &ctx,
                &mut f,
            );
            black_box(&f);
        })
    });
    group.bench_function("lanes_cracked", |b| {
        b.iter(|| {
            lanes_force(&geo, &mat, &unloaded, &old, &mut new, &ctx, &mut f);
        })
    });
    group.throughput(Throughput::Elements(varied.len() as u64));
    group.bench_function("lanes_cracked_varied", |b| {
        b.iter(|| {
            for (state, u) in &varied {
                lanes_force(&geo, &mat, u, state, &mut new, &ctx, &mut f);
            }
        })
    });
    group.finish();
}

/// K u of one element through its stiffness matrix, inside pulp's dispatch as in the step.
struct MatrixForce<'a> {
    k: &'a ElementMatrix,
    u: &'a [[f64; 3]; 8],
}

impl LaneWork for MatrixForce<'_> {
    type Output = [[f64; 3]; 8];
    #[inline(always)]
    fn run<S: Simd>(self, _simd: S) -> [[f64; 3]; 8] {
        self.k.apply(self.u)
    }
}

/// The 40³ sweep of `stream_64000` with every element's force K u from one shared matrix.
struct MatrixStream<'a> {
    k: &'a ElementMatrix,
    conn: &'a [[u32; 8]],
    us: &'a [[f64; 3]],
    f_int: &'a mut [[f64; 3]],
}

impl LaneWork for MatrixStream<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: Simd>(self, _simd: S) {
        for nodes in self.conn {
            let ue: [[f64; 3]; 8] = std::array::from_fn(|a| self.us[nodes[a] as usize]);
            let f = self.k.apply(&ue);
            for (a, fa) in f.iter().enumerate() {
                let p = &mut self.f_int[nodes[a] as usize];
                p[0] += fa[0];
                p[1] += fa[1];
                p[2] += fa[2];
            }
        }
    }
}

/// `hex8_full/{single,stream_64000}_matrix` (module docs).
fn full_matrix(c: &mut Criterion) {
    let x = coords(0.0);
    let geo = FullGeometry::new(&x).expect("valid element");
    let k = ElementMatrix::new(&geo, material().elastic());
    let u = displacements(&x);
    let mut group = c.benchmark_group("hex8_full");
    group.throughput(Throughput::Elements(1));
    group.bench_function("single_matrix", |b| {
        b.iter(|| {
            black_box(run_lane_work(MatrixForce {
                k: black_box(&k),
                u: black_box(&u),
            }));
        })
    });
    let (conn, us) = stream_setup();
    group.throughput(Throughput::Elements(STREAM as u64));
    group.sample_size(10);
    group.bench_function("stream_64000_matrix", |b| {
        let mut f_int = vec![[0.0; 3]; us.len()];
        b.iter(|| {
            run_lane_work(MatrixStream {
                k: &k,
                conn: &conn,
                us: &us,
                f_int: &mut f_int,
            });
            black_box(&mut f_int);
        })
    });
    group.finish();
}

/// One one-point plastic-damage element below first yield, its state updated in place
/// (`hex8_uniform::internal_force_in_place`), as the step runs it: inside pulp's dispatch.
struct OnePointInPlace<'a> {
    geo: &'a UniformGeometry,
    material: &'a Material,
    u: &'a [[f64; 3]; 8],
    state: &'a mut [f64],
    ctx: &'a PointContext,
    f: &'a mut [[f64; 3]; 8],
}

impl LaneWork for OnePointInPlace<'_> {
    type Output = bool;
    #[inline(always)]
    fn run<S: Simd>(self, _simd: S) -> bool {
        hex8_uniform::internal_force_in_place(
            self.geo,
            self.material,
            self.u,
            None,
            self.state,
            self.ctx,
            self.f,
        )
        .1
    }
}

/// `hex8_one_point_plastic_damage/in_place`: the rock's kernel on the Yingxiuwan mesh (a
/// one-point plastic-damage element that has never yielded, the never-yielded shortcut),
/// one element whose data stays in L1.
fn one_point_plastic_damage(c: &mut Criterion) {
    let ctx = PointContext {
        reads_damage: true,
        ..context()
    };
    let x = coords(0.0);
    let u = displacements(&x);
    let mat = plastic_damage();
    let geo = UniformGeometry::new(&x, mat.elastic(), 0.05).expect("valid element");
    let mut state = vec![0.0; mat.state_len()];
    mat.init_state(&mut state);
    let mut group = c.benchmark_group("hex8_one_point_plastic_damage");
    group.throughput(Throughput::Elements(1));
    group.bench_function("in_place", |b| {
        let mut f = [[0.0; 3]; 8];
        b.iter(|| {
            let moved = run_lane_work(OnePointInPlace {
                geo: black_box(&geo),
                material: &mat,
                u: black_box(&u),
                state: &mut state,
                ctx: &ctx,
                f: &mut f,
            });
            black_box((&f, moved));
        })
    });
    let geos: [UniformGeometry; LANES] = std::array::from_fn(|l| {
        UniformGeometry::new(&coords(0.3 * l as f64), mat.elastic(), 0.05).expect("valid element")
    });
    let block = UniformBlock::new(&geos);
    let u_lanes: NodalLanes = std::array::from_fn(|a| {
        std::array::from_fn(|i| {
            F64s(std::array::from_fn(|l| {
                displacements(&coords(0.3 * l as f64))[a][i]
            }))
        })
    });
    let ctxs = [ctx; LANES];
    let mut states: [Vec<f64>; LANES] = std::array::from_fn(|_| state.clone());
    group.throughput(Throughput::Elements(LANES as u64));
    group.bench_function("lanes_of_8", |b| {
        b.iter(|| {
            let mut slices = states.each_mut().map(|v| v.as_mut_slice());
            let out = run_lane_work(LaneKernel {
                block: black_box(&block),
                material: &mat,
                u: black_box(&u_lanes),
                eps0: None,
                states: &mut slices,
                ctx: &ctxs,
            });
            black_box(out);
        })
    });
    group.finish();
}

criterion_group!(
    benches,
    one_point,
    full,
    full_lanes,
    full_lanes_cracked,
    full_matrix,
    one_point_plastic_damage
);
criterion_main!(benches);
