//! Contact kernels: the point-to-point pair update (per pair, kernel and through
//! `ContactSystem::compute` on a 100 × 100-face interface) and the point-to-surface solve
//! (per coupled group, and through `compute` on a block sliding over a larger base); the
//! setup of large interfaces (`ContactSystem::new`).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use dcfm::contact::geom::{face_shape, scale};
use dcfm::contact::surface::solve_group;
use dcfm::contact::{
    solve_pair, ContactMode, ContactStepInput, ContactSystem, InterfaceSpec, PairInput, PairParams,
    PairState,
};
use dcfm::mesh::{BlockSpec, BoxMeshSpec, Mesh};

fn block(name: &str, origin: [f64; 3], size: [f64; 3], div: [usize; 3]) -> BlockSpec {
    BlockSpec {
        name: name.into(),
        region: None,
        origin,
        size,
        divisions: div,
        grading: [1.0; 3],
    }
}

fn pair_kernel(c: &mut Criterion) {
    let p = PairParams {
        mu_s: 0.6,
        mu_d: 0.45,
        shear_capacity: 5e4,
        tensile_capacity: 5e4,
    };
    let inputs: Vec<PairInput> = (0..1024)
        .map(|k| {
            let f = k as f64 / 1024.0;
            PairInput {
                n: [0.0, 0.0, 1.0],
                w_sum: 1e-3,
                dt: 1e-4,
                rel_pred: [1e-6 * (f - 0.5), 2e-6 * f, -1e-6 * (f - 0.3)],
                rel_old: [0.0; 3],
            }
        })
        .collect();
    let mut g = c.benchmark_group("contact/pair_kernel");
    g.throughput(Throughput::Elements(inputs.len() as u64));
    g.bench_function("solve_pair x1024", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for inp in &inputs {
                acc += solve_pair(PairState::Bonded, &p, black_box(inp)).normal;
            }
            acc
        })
    });
    g.finish();
}

struct Model {
    mesh: Mesh,
    w: Vec<f64>,
    u_old: Vec<[f64; 3]>,
    u_pred: Vec<[f64; 3]>,
    v_pred: Vec<[f64; 3]>,
}

fn model(mesh: Mesh, load: [f64; 3], on: &[u32]) -> Model {
    let n = mesh.n_nodes();
    let dt: f64 = 1e-4;
    let w = vec![1e-3; n];
    let mut u_pred = vec![[0.0; 3]; n];
    let mut v_pred = vec![[0.0; 3]; n];
    for &k in on {
        v_pred[k as usize] = scale(dt * 1e-3, load);
        u_pred[k as usize] = scale(dt * dt * 1e-3, load);
    }
    Model {
        mesh,
        w,
        u_old: vec![[0.0; 3]; n],
        u_pred,
        v_pred,
    }
}

fn run_compute(c: &mut Criterion, name: &str, m: &Model, spec: &InterfaceSpec, per: u64) {
    let sys = ContactSystem::new(&m.mesh, std::slice::from_ref(spec), "bench").unwrap();
    let n = m.mesh.n_nodes();
    let mut g = c.benchmark_group("contact/compute");
    g.throughput(Throughput::Elements(per));
    g.bench_function(name, |b| {
        b.iter_batched_ref(
            || (sys.clone(), vec![[0.0; 3]; n]),
            |(sys, r)| {
                let inp = ContactStepInput {
                    step: 1,
                    time: 0.0,
                    dt: 1e-4,
                    inv_mass: &m.w,
                    coords: &m.mesh.coords,
                    u_old: &m.u_old,
                    u_pred: &m.u_pred,
                    v_pred: &m.v_pred,
                };
                sys.compute(&inp, r).unwrap();
            },
            BatchSize::LargeInput,
        )
    });
    g.finish();
}

fn point_to_point(c: &mut Criterion) {
    let mesh = BoxMeshSpec {
        blocks: vec![
            block("base", [0.0; 3], [100.0, 100.0, 1.0], [100, 100, 1]),
            block("top", [0.0, 0.0, 1.0], [100.0, 100.0, 1.0], [100, 100, 1]),
        ],
        split: vec![["base".into(), "top".into()]],
        merge_tolerance: 1e-6,
    }
    .build("bench")
    .unwrap();
    let spec = InterfaceSpec::new("pp", "base-top", "top-base", 0.6, 0.45, 2e3);
    let on = mesh.face_set_nodes(&mesh.face_sets["base-top"]);
    let pairs = on.len() as u64;
    let m = model(mesh, [300.0, 100.0, 1000.0], &on);
    run_compute(c, "point-to-point 10201 pairs", &m, &spec, pairs);
}

fn point_to_surface(c: &mut Criterion) {
    // Groups of 1, 4 and 9 slave nodes sharing face nodes (kernel: H system + faer + polish).
    let faces = [[0u32, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]];
    let mut g = c.benchmark_group("contact/surface_group");
    for m in [1usize, 4, 9] {
        let nodes: Vec<_> = (0..m)
            .map(|i| {
                let (xi, eta) = (-0.8 + 0.37 * (i % 3) as f64, -0.7 + 0.41 * (i / 3) as f64);
                let phi = face_shape(xi, eta);
                let f = faces[i % 4];
                let dbar = [1e-6 * (i as f64 - 4.0), 4e-7, 1e-5]; // closed: d·n < 0 with n = −z
                (1e-3, [1e-3; 4], phi, f, [0.0, 0.0, -1.0], dbar, [0.0; 3])
            })
            .collect();
        g.throughput(Throughput::Elements(1));
        g.bench_function(format!("solve_group {m} nodes"), |b| {
            b.iter(|| solve_group(1e-4, 0.6, 0.45, black_box(&nodes)).unwrap())
        });
    }
    g.finish();
    // Through compute(): a 20 × 20-face block on a 30 × 30-face base, nodes not coincident.
    let mesh = BoxMeshSpec {
        blocks: vec![
            block("base", [0.0; 3], [30.0, 30.0, 1.0], [30, 30, 1]),
            block("top", [5.3, 5.4, 1.0], [20.0, 20.0, 1.0], [20, 20, 1]),
        ],
        split: vec![],
        merge_tolerance: 1e-6,
    }
    .build("bench")
    .unwrap();
    let mut spec = InterfaceSpec::new("ps", "top.zmin", "base.zmax", 0.6, 0.45, 0.0);
    spec.mode = ContactMode::Surface;
    let on = mesh.face_set_nodes(&mesh.face_sets["top.zmin"]);
    let n_on = on.len() as u64;
    let m = model(mesh, [300.0, 100.0, -1000.0], &on);
    run_compute(c, "point-to-surface 441 nodes", &m, &spec, n_on);
}

/// Interface setup (`ContactSystem::new`: geometry, normals, pairing by grid, and in surface
/// mode the closest-face check of every node through sorted face bins) on large interfaces:
/// 101 × 101 coincident pairs, and a 100 × 100-face block on a 120 × 120-face base.
fn setup(c: &mut Criterion) {
    let mut g = c.benchmark_group("contact/setup");
    g.sample_size(10);
    let paired = BoxMeshSpec {
        blocks: vec![
            block("base", [0.0; 3], [100.0, 100.0, 1.0], [100, 100, 1]),
            block("top", [0.0, 0.0, 1.0], [100.0, 100.0, 1.0], [100, 100, 1]),
        ],
        split: vec![["base".into(), "top".into()]],
        merge_tolerance: 1e-6,
    }
    .build("bench")
    .unwrap();
    let spec = InterfaceSpec::new("pp", "base-top", "top-base", 0.6, 0.45, 2e3);
    g.throughput(Throughput::Elements(10201));
    g.bench_function("paired 10201 pairs", |b| {
        b.iter(|| ContactSystem::new(black_box(&paired), std::slice::from_ref(&spec), "bench"))
    });
    let surface = BoxMeshSpec {
        blocks: vec![
            block("base", [0.0; 3], [120.0, 120.0, 1.0], [120, 120, 1]),
            block("top", [10.3, 10.4, 1.0], [100.0, 100.0, 1.0], [100, 100, 1]),
        ],
        split: vec![],
        merge_tolerance: 1e-6,
    }
    .build("bench")
    .unwrap();
    let mut spec = InterfaceSpec::new("ps", "top.zmin", "base.zmax", 0.6, 0.45, 0.0);
    spec.mode = ContactMode::Surface;
    g.bench_function("surface 10201 nodes on 14400 faces", |b| {
        b.iter(|| ContactSystem::new(black_box(&surface), std::slice::from_ref(&spec), "bench"))
    });
    g.finish();
}

criterion_group!(
    benches,
    pair_kernel,
    point_to_point,
    point_to_surface,
    setup
);
criterion_main!(benches);
