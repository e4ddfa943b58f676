//! A block reinforced with thousands of anchor segments (two-way mats under its top and one side, rock
//! bolts with pretension from the top, one bond–slip bar), loaded on the top and stepped:
//! displacements, internal forces and bar forces are the same bit for bit on 1 and 2
//! threads — the perfect-bond pass runs in parallel (segments, hosts, then host nodes) with
//! every host's sum taken in segment order and every node's in host order (anchor_bar.rs,
//! `AnchorBars::add_internal_forces`).

use std::path::Path;

use dcfm::case::parse_case;
use dcfm::stage::Simulation;

const CASE: &str = r#"
title = "anchor threads"
[time]
end = 1.0
[mesh]
[[mesh.blocks]]
name = "b"
origin = [0.0, 0.0, 0.0]
size = [12.0, 12.0, 6.0]
divisions = [12, 12, 6]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "b"
material = "rock"
[[boundary.fixed]]
set = "b.zmin"
dofs = "xyz"
[[loads.nodal]]
set = "b.zmax"
force = [2e6, 1e6, 5e6]
history = { type = "ramp", rate = 1000.0 }
[[anchors.mats]]
name = "mat"
face_set = "b.zmax"
cover = 0.05
spacing = 0.1
diameter = 0.025
yield_stress = 335e6
[[anchors.mats]]
name = "side_mat"
face_set = "b.ymin"
cover = 0.05
spacing = 0.1
diameter = 0.02
yield_stress = 335e6
[[anchors.patterns]]
name = "bolts"
face_set = "b.zmax"
length = 4.0
spacing = 0.75
diameter = 0.025
yield_stress = 335e6
pretension = 5e4
[[anchors.bars]]
name = "slip"
start = [6.1, 6.1, 6.0]
end = [6.1, 6.1, 1.0]
diameter = 0.028
yield_stress = 400e6
bond_stiffness = 2e8
pretension = 1e4
"#;

struct State {
    u: Vec<[f64; 3]>,
    f_int: Vec<[f64; 3]>,
    bar_force: Vec<f64>,
    segments: usize,
}

fn run(threads: usize) -> State {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let case = parse_case(CASE, "anchor threads", Path::new(".")).unwrap();
        let mut sim = Simulation::new(case.model, case.dt, case.safety).unwrap();
        sim.run_steps(40).unwrap();
        let anchors = sim.model.anchors.as_ref().unwrap();
        State {
            u: sim.u.clone(),
            f_int: sim.internal_force().to_vec(),
            bar_force: anchors.force.clone(),
            segments: anchors.segments.len(),
        }
    })
}

#[test]
fn reinforced_block_steps_alike_on_one_and_two_threads() {
    let one = run(1);
    let two = run(2);
    // Enough segments and host nodes for the parallel phases to split (1024 segments,
    // 512 nodes per task).
    assert!(one.segments > 4096, "{} segments", one.segments);
    let moved = one.u.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(moved > 0.0, "the load must move the block");
    assert!(
        one.bar_force.iter().any(|&n| n.abs() > 1e3),
        "the bars must carry force"
    );
    assert!(
        one.u == two.u,
        "displacements differ between 1 and 2 threads"
    );
    assert!(
        one.f_int == two.f_int,
        "internal forces differ between 1 and 2 threads"
    );
    assert!(
        one.bar_force == two.bar_force,
        "bar forces differ between 1 and 2 threads"
    );
}
