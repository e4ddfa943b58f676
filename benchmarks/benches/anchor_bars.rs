//! The anchor-bar force pass (`AnchorBars::add_internal_forces`) of a model reinforced like
//! the Yingxiuwan CI case: a 24³ box of 1 m rock elements (13 824 elements, close to the CI
//! mesh's 13 612) with two-way mats (φ25 at 0.2 m, 0.1 m cover) under all six faces and
//! 6 m rock bolts (φ25 at 1.5 m) from the top and one side — about 36 000 perfect-bond
//! segments, the order of the CI case's bars. Measured on a one- and a two-thread rayon
//! pool (`anchor_bars/add_internal_forces_threads{1,2}`); the forces are the same bit for
//! bit on both.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use dcfm::element::anchor_bar::{AnchorBars, BarNames, SteelSpec};
use dcfm::element::anchor_mat::mat_bars;
use dcfm::element::anchor_pattern::pattern_points;
use dcfm::element::host_locate::HostLocator;
use dcfm::mesh::{BoxMeshSpec, Mesh};

fn steel() -> SteelSpec {
    SteelSpec {
        diameter: 0.025,
        young: 200e9,
        yield_stress: 335e6,
        density: 7850.0,
        pretension: 0.0,
        bond_stiffness: None,
        segment_length: None,
    }
}

/// The reinforced box and its bars.
fn reinforced_box() -> (Mesh, AnchorBars) {
    let mesh = BoxMeshSpec::single("rock", [0.0; 3], [24.0; 3], [24; 3])
        .build("bench")
        .expect("the benchmark box builds");
    let locator = HostLocator::new(&mesh, |_| true);
    let mut anchors = AnchorBars::default();
    let mut add = |group: &str, k: usize, ends: [[f64; 3]; 2]| {
        let names = BarNames {
            name: format!("{group}.{k}"),
            group: group.into(),
        };
        anchors
            .add_bar(&mesh, &locator, names, ends, &steel())
            .expect("the bar lies in the box");
    };
    for side in ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"] {
        let faces = &mesh.face_sets[&format!("rock.{side}")];
        let bars = mat_bars(&mesh, faces, 0.1, 0.2).expect("flat faces");
        for (k, ends) in bars.into_iter().enumerate() {
            add(side, k, ends);
        }
    }
    for side in ["zmax", "xmin"] {
        let faces = &mesh.face_sets[&format!("rock.{side}")];
        for (k, (p, n)) in pattern_points(&mesh, faces, 1.5).into_iter().enumerate() {
            add("bolts", k, [p, std::array::from_fn(|d| p[d] + 6.0 * n[d])]);
        }
    }
    anchors.finish();
    (mesh, anchors)
}

fn add_internal_forces(c: &mut Criterion) {
    let (mesh, mut anchors) = reinforced_box();
    // A strain field below yield: stretch along x, shear in y–z.
    let u: Vec<[f64; 3]> = mesh
        .coords
        .iter()
        .map(|x| [1e-4 * x[0], 5e-5 * x[2], -3e-5 * x[1]])
        .collect();
    let mut f = vec![[0.0; 3]; mesh.n_nodes()];
    let mut group = c.benchmark_group("anchor_bars");
    group.throughput(Throughput::Elements(anchors.segments.len() as u64));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a rayon pool");
        group.bench_function(format!("add_internal_forces_threads{threads}"), |b| {
            pool.install(|| b.iter(|| anchors.add_internal_forces(&mesh, &u, black_box(&mut f))))
        });
    }
    group.finish();
}

criterion_group!(benches, add_internal_forces);
criterion_main!(benches);
