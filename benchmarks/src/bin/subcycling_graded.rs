//! Effective throughput of multi-time-step integration (issue 11 item 3) on a graded
//! mesh: a box whose element edges grow from 0.5 m in its core to 7 m at its sides
//! (tensor-product grading, the same sizes along x, y and z), elastic rock, base fixed,
//! an initial velocity everywhere else. Runs the same number of steps with single steps
//! and with `max_level` 3, on a pool of `--threads` threads, and prints for each the wall
//! time, the process CPU time and the effective element-updates/s per CPU second
//! (steps × elements / CPU s: the single-step work done, whatever subcycling skipped;
//! CPU time is steadier than wall time on a shared machine), plus the levels.
//! docs/benchmarks.md.

use std::time::Instant;

use clap::Parser;
use dcfm::element::Integration;
use dcfm::material::{Elastic, Material};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup};
use dcfm::stage::Simulation;
use dcfm_benchmarks::cputime::process_cpu_seconds;

#[derive(Parser)]
struct Args {
    /// Threads of the pool.
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Steps of each run (a multiple of 8 keeps the subcycled run synchronous at its end).
    #[arg(long, default_value_t = 400)]
    steps: u64,
}

/// Element edges along each axis (m): 7 m at the sides down to 0.5 m in the core.
const EDGES: [f64; 18] = [
    7.0, 7.0, 7.0, 7.0, 3.5, 1.75, 1.0, 0.5, 0.5, 0.5, 0.5, 1.0, 1.75, 3.5, 7.0, 7.0, 7.0, 7.0,
];

fn simulation() -> Simulation {
    let n = EDGES.len();
    let mut mesh = BoxMeshSpec::single("rock", [0.0; 3], [n as f64; 3], [n; 3])
        .build("graded box")
        .expect("box");
    let mut at = vec![0.0; n + 1];
    for k in 0..n {
        at[k + 1] = at[k] + EDGES[k];
    }
    for x in mesh.coords.iter_mut() {
        for c in x.iter_mut() {
            *c = at[c.round() as usize];
        }
    }
    let setup = RegionSetup {
        region: "rock".to_string(),
        material: Material::Elastic(Elastic::new("rock", 20e9, 0.25, 2700.0).expect("rock")),
        integration: Integration::Full,
        hourglass: 0.05,
    };
    let mut model = Model::new(mesh, &[setup], "graded box").expect("model");
    let base = model.mesh.node_sets["rock.zmin"].clone();
    model.constraints.fix(&base, 0b111);
    model.refresh_stable_step();
    let dt = model.time_step(None, 0.9).expect("dt");
    let mut sim = Simulation::new(model, dt, 0.9).expect("simulation");
    for (i, v) in sim.v.iter_mut().enumerate() {
        if !base.contains(&(i as u32)) {
            *v = [0.01, 0.0, -0.01];
        }
    }
    sim.restart_energy_account();
    sim
}

fn main() {
    let args = Args::parse();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()
        .expect("pool");
    pool.install(|| {
        for level in [None, Some(3u8)] {
            let mut sim = simulation();
            if let Some(l) = level {
                let s = sim.enable_subcycling(l, 0.9).expect("subcycling");
                println!("levels: {}", serde_json::to_string(s).expect("json"));
            }
            let n_elements = sim.model.n_elements() as f64;
            let t0 = Instant::now();
            let c0 = process_cpu_seconds().unwrap_or(f64::NAN);
            sim.run_steps(args.steps).expect("run");
            let wall = t0.elapsed().as_secs_f64();
            let cpu = process_cpu_seconds().unwrap_or(f64::NAN) - c0;
            println!(
                "{{\"subcycling\": {}, \"threads\": {}, \"elements\": {}, \"steps\": {}, \
                 \"wall_s\": {:.3}, \"cpu_s\": {:.3}, \
                 \"effective_element_updates_per_cpu_s\": {:.4e}, \
                 \"element_evaluations_per_cpu_s\": {:.4e}, \"energy_residual_relative\": {:.3e}}}",
                level.map_or("\"off\"".to_string(), |l| l.to_string()),
                args.threads,
                n_elements,
                args.steps,
                wall,
                cpu,
                args.steps as f64 * n_elements / cpu,
                args.steps as f64 * sim.element_updates_per_step() / cpu,
                sim.energies.relative_residual()
            );
        }
    });
}
