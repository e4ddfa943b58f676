//! One explicit step (`Simulation::step`) of the 20³ one-point elastic cube of the
//! throughput runner (8 000 elements, 9 261 nodes), on rayon's global pool: element forces
//! colour by colour, the node pass (predictor, energies, instability check) and the commit.
//!
//! `internal_forces/cube20_full_{lanes,scalar}`: the element-force phase alone
//! (`Simulation::internal_forces`) of the fully integrated elastic 20³ cube, with the
//! Gauss points in SIMD lanes (`hex8_full_lanes`, `ElementGroup::lanes = true`, the
//! default) and with the scalar kernel; both give the same forces bit for bit.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use dcfm::element::Integration;
use dcfm_benchmarks::cube::CubeSpec;

fn step_20_one_point(c: &mut Criterion) {
    let spec = CubeSpec::new(20, Integration::OnePoint);
    let mut sim = spec.simulation().expect("the benchmark cube builds");
    // Let the waves from the fixed base cross the cube so every element strains.
    sim.run_steps(spec.divisions as u64 + 5)
        .expect("stable warm-up");
    let mut group = c.benchmark_group("full_step");
    group.throughput(Throughput::Elements(spec.elements() as u64));
    group.bench_function("cube20_one_point", |b| {
        b.iter(|| sim.step().expect("stable step"))
    });
    group.finish();
}

fn forces_20_full(c: &mut Criterion) {
    let spec = CubeSpec::new(20, Integration::Full);
    let mut sim = spec.simulation().expect("the benchmark cube builds");
    sim.run_steps(spec.divisions as u64 + 5)
        .expect("stable warm-up");
    let mut group = c.benchmark_group("internal_forces");
    group.throughput(Throughput::Elements(spec.elements() as u64));
    for (name, lanes) in [("cube20_full_lanes", true), ("cube20_full_scalar", false)] {
        for g in &mut sim.model.groups {
            g.lanes = lanes;
        }
        group.bench_function(name, |b| b.iter(|| sim.internal_forces()));
    }
    group.finish();
}

criterion_group!(benches, step_20_one_point, forces_20_full);
criterion_main!(benches);
