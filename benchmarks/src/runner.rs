//! The whole-run throughput runner: for every cube size × integration rule × thread count,
//! build the model, warm up, time steps until a minimum wall time has passed, and emit one
//! [`ThroughputRecord`] (optionally appended to the history file).

use dcfm::stage::static_stage::linear_solver::LinearSolverChoice;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use dcfm::element::Integration;
use dcfm::stage::Simulation;

use crate::cube::{CubeMaterial, CubeSpec};
use crate::error::BenchError;
use crate::record::ThroughputRecord;
use crate::scipy_csr::{self, ScipyBaseline, ScipyCsrInfo, ScriptRun};
use crate::{cputime, git, history, memory, timestamp};

/// What to run and how long.
#[derive(Clone, Debug, PartialEq)]
pub struct RunConfig {
    /// Cube divisions n (n³ elements), one case per size and integration rule.
    pub sizes: Vec<usize>,
    /// Integration rules (elastic cubes).
    pub integrations: Vec<Integration>,
    /// Plastic-damage regimes, run at every size (issue #4) ...
    pub plastic_damage: Vec<CubeMaterial>,
    /// ... with each of these integration rules, in this order (issue #11: one-point
    /// plastic-damage, `cube{n}_one_point_pd_*`).
    pub plastic_damage_integrations: Vec<Integration>,
    /// Cube divisions of the one-point elastic cubes run after all the others, sizes
    /// whose data do not fit in the caches as real models' do not (issue #11: 100³).
    pub large_one_point_sizes: Vec<usize>,
    /// Time every size's fully integrated elastic cube also on seismic boundaries
    /// (`cube{n}_full_boundaries`: absorbing base with input, free-field sides), right
    /// after the fixed-base cube, for the boundaries' overhead per step (issue #7).
    pub boundaries: bool,
    /// Interface slabs (n² × 4 elements, (n+1)² DCFM pairs) whose contact phase is reported
    /// as a share of the step (issue #3); run after the cubes.
    pub interface_sizes: Vec<usize>,
    /// Static direct solves of n³ cubes (issue #7), run after the explicit cases on the
    /// largest thread count (the factorisation is sequential).
    pub static_sizes: Vec<usize>,
    /// Thread counts; each case is timed on each, in this order, on the same simulation.
    pub threads: Vec<usize>,
    /// Warm-up steps before each timing; `None`: n + 5, enough for the waves from the base
    /// to reach the top so that every element is straining.
    pub warmup_steps: Option<u64>,
    /// Keep stepping until this much wall time has passed (s) ...
    pub min_wall_s: f64,
    /// ... and at least this many steps ...
    pub min_steps: u64,
    /// ... but never more than this many.
    pub max_steps: u64,
    /// Run only the cases whose name contains this substring.
    pub filter: Option<String>,
    /// Append every record to this file (`None`: do not record).
    pub history: Option<PathBuf>,
    /// Recorded as the record's `mode`.
    pub mode: String,
    /// The scipy CSR leapfrog of `benchmarks/python/csr_leapfrog.py` on the same cube,
    /// timed right after every elastic `cube{n}_full` case (row `cube{n}_scipy_csr`, one
    /// thread) with that case's Δt, warm-up and minimum wall time (issue 11).
    pub scipy: ScipyBaseline,
}

impl RunConfig {
    /// The standard run: 20³ and 40³, one-point and full, 1 and 2 threads, ≥ 2 s each,
    /// recorded in `benchmarks/history.jsonl`.
    pub fn standard() -> Self {
        Self {
            sizes: vec![20, 40],
            integrations: vec![Integration::OnePoint, Integration::Full],
            boundaries: true,
            interface_sizes: vec![100],
            plastic_damage: vec![
                CubeMaterial::PlasticDamageElastic,
                CubeMaterial::PlasticDamageDamaging,
                CubeMaterial::PlasticDamageLocalised,
            ],
            plastic_damage_integrations: vec![Integration::Full, Integration::OnePoint],
            large_one_point_sizes: vec![100],
            static_sizes: vec![40],
            threads: vec![1, 2],
            warmup_steps: None,
            min_wall_s: 2.0,
            min_steps: 10,
            max_steps: 1_000_000,
            filter: None,
            history: Some(history::default_history_path()),
            mode: "standard".to_string(),
            scipy: ScipyBaseline::Auto,
        }
    }

    /// The CI smoke run: 4³ and 8³ (12³ for the large one-point cube), ≥ 0.1 s each
    /// (about a second in all).
    pub fn quick() -> Self {
        Self {
            sizes: vec![4, 8],
            large_one_point_sizes: vec![12],
            interface_sizes: vec![8],
            static_sizes: vec![8],
            min_wall_s: 0.1,
            min_steps: 5,
            max_steps: 200,
            mode: "quick".to_string(),
            ..Self::standard()
        }
    }

    /// The static cases to run (names `static_cholesky_cube{n}`, `static_cg_cube{n}`),
    /// filter applied.
    pub fn static_cases(&self) -> Vec<(usize, LinearSolverChoice)> {
        self.static_sizes
            .iter()
            .flat_map(|&n| crate::static_solve::SOLVERS.map(|s| (n, s)))
            .filter(|&(n, s)| {
                self.filter
                    .as_deref()
                    .is_none_or(|f| crate::static_solve::case_name(n, s).contains(f))
            })
            .collect()
    }

    /// The cases to run, filter applied, in run order.
    pub fn cases(&self) -> Vec<CubeSpec> {
        let mut out = Vec::new();
        for &n in &self.sizes {
            let boundaries = (self.boundaries && self.integrations.contains(&Integration::Full))
                .then(|| CubeSpec::new(n, Integration::Full).with_boundaries());
            let elastic = self
                .integrations
                .iter()
                .map(|&i| CubeSpec::new(n, i))
                .chain(boundaries);
            let damage = self.plastic_damage_integrations.iter().flat_map(|&i| {
                self.plastic_damage
                    .iter()
                    .map(move |&m| CubeSpec::new(n, i).with_material(m))
            });
            for spec in elastic.chain(damage) {
                if self
                    .filter
                    .as_deref()
                    .is_none_or(|f| spec.name().contains(f))
                {
                    out.push(spec);
                }
            }
        }
        for &n in &self.large_one_point_sizes {
            let spec = CubeSpec::new(n, Integration::OnePoint);
            if self
                .filter
                .as_deref()
                .is_none_or(|f| spec.name().contains(f))
            {
                out.push(spec);
            }
        }
        for &m in &self.interface_sizes {
            let spec = CubeSpec::interface_slab(m);
            if self
                .filter
                .as_deref()
                .is_none_or(|f| spec.name().contains(f))
            {
                out.push(spec);
            }
        }
        out
    }

    fn validate(&self) -> Result<(), BenchError> {
        if self.sizes.contains(&0)
            || self.static_sizes.contains(&0)
            || self.large_one_point_sizes.contains(&0)
        {
            return Err(BenchError::Config("cube sizes must be >= 1".into()));
        }
        if self.threads.is_empty() || self.threads.contains(&0) {
            return Err(BenchError::Config(
                "thread counts must be >= 1 (and at least one)".into(),
            ));
        }
        if !(self.min_wall_s.is_finite() && self.min_wall_s >= 0.0) {
            return Err(BenchError::Config(format!(
                "min wall time {} s must be >= 0",
                self.min_wall_s
            )));
        }
        if self.min_steps == 0 || self.max_steps < self.min_steps {
            return Err(BenchError::Config(format!(
                "need 1 <= min steps ({}) <= max steps ({})",
                self.min_steps, self.max_steps
            )));
        }
        Ok(())
    }
}

/// Steps and wall time of one timed run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    /// Timed steps.
    pub steps: u64,
    /// Their wall time.
    pub wall: Duration,
    /// CPU time the process used meanwhile (s), where it can be read.
    pub cpu_s: Option<f64>,
    /// Time the contact phase took during the timed steps (s), warm-up excluded.
    pub contact_s: f64,
}

/// Step `sim` `warmup` times untimed, then until `min_wall` has passed and at least
/// `min_steps` steps are done (at most `max_steps`).
pub fn time_steps(
    sim: &mut Simulation,
    warmup: u64,
    min_wall: Duration,
    min_steps: u64,
    max_steps: u64,
) -> dcfm::Result<Timing> {
    sim.run_steps(warmup)?;
    let contact0 = sim.contact_seconds;
    let cpu0 = cputime::process_cpu_seconds();
    let start = Instant::now();
    let mut steps = 0;
    while steps < min_steps || (steps < max_steps && start.elapsed() < min_wall) {
        sim.step()?;
        steps += 1;
    }
    let wall = start.elapsed();
    let cpu_s = cputime::process_cpu_seconds().zip(cpu0).map(|(b, a)| b - a);
    Ok(Timing {
        steps,
        wall,
        cpu_s,
        contact_s: sim.contact_seconds - contact0,
    })
}

/// Run every case of `config` on every thread count, calling `on_record` as each record is
/// made (after it has been appended to the history file, when recording). Returns all of
/// them in run order. An empty case list (filter matching nothing) is an error. Why a
/// scipy row was skipped goes to stderr (see [`run_with_notes`]).
pub fn run(
    config: &RunConfig,
    on_record: impl FnMut(&ThroughputRecord),
) -> Result<Vec<ThroughputRecord>, BenchError> {
    run_with_notes(config, on_record, |note| eprintln!("{note}"))
}

/// [`run`], with the lines that say why a scipy CSR row was skipped passed to `on_note`
/// (no Python, a failing script, output that is not its record, a different cube).
pub fn run_with_notes(
    config: &RunConfig,
    mut on_record: impl FnMut(&ThroughputRecord),
    mut on_note: impl FnMut(&str),
) -> Result<Vec<ThroughputRecord>, BenchError> {
    config.validate()?;
    let cases = config.cases();
    if cases.is_empty() && config.static_cases().is_empty() {
        return Err(BenchError::Config(format!(
            "no case matches the filter {:?}",
            config.filter.as_deref().unwrap_or("")
        )));
    }
    let root = history::workspace_root();
    let commit = git::commit_label(&root);
    let wants_scipy = |spec: &CubeSpec| {
        spec.integration == Integration::Full
            && spec.material == CubeMaterial::Elastic
            && !spec.boundaries
            && !spec.interface
    };
    let python = match scipy_csr::find_python(
        &config.scipy,
        std::env::var_os(scipy_csr::PYTHON_ENV),
        &root,
    ) {
        Ok(p) => Some(p),
        Err(why) => {
            if config.scipy != ScipyBaseline::Off && cases.iter().any(wants_scipy) {
                on_note(&format!("scipy CSR rows skipped: {why}; no ratio recorded"));
            }
            None
        }
    };
    let crate::machine::Host {
        cpus,
        machine_cpus,
        cpu_model,
        profile,
    } = crate::machine::Host::here();
    let mut records = Vec::new();
    for spec in cases {
        let reset = memory::reset_peak_rss();
        let mut first = Some(spec.simulation()?);
        let warmup = config.warmup_steps.unwrap_or(spec.divisions as u64 + 5);
        let (bytes_per_element, nodes) = first
            .as_ref()
            .map(|s| (s.model.bytes_per_element(), s.model.mesh.n_nodes()))
            .unwrap_or_default();
        // Every thread count times the same steps from the same state: a fresh copy of the
        // case, the same warm-up, then the number of steps the first thread count reached
        // in `min_wall_s`. Timing the thread counts one after the other on one simulation
        // compared different stretches of the motion, and in the damaging regime the cost
        // of a step grows as the damage spreads.
        let mut same_steps: Option<u64> = None;
        for &threads in &config.threads {
            let mut sim = match first.take() {
                Some(sim) => sim,
                None => spec.simulation()?,
            };
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()?;
            let (min_wall, min_steps, max_steps) = match same_steps {
                None => (
                    Duration::from_secs_f64(config.min_wall_s),
                    config.min_steps,
                    config.max_steps,
                ),
                Some(n) => (Duration::ZERO, n, n),
            };
            let timing =
                pool.install(|| time_steps(&mut sim, warmup, min_wall, min_steps, max_steps))?;
            same_steps.get_or_insert(timing.steps);
            let wall_s = timing.wall.as_secs_f64().max(1e-9);
            let contact_share = spec.interface.then(|| timing.contact_s / wall_s);
            let steps_per_s = timing.steps as f64 / wall_s;
            let record = ThroughputRecord {
                case: spec.name(),
                elements: spec.elements(),
                nodes,
                integration: spec.integration.name().to_string(),
                threads,
                steps: timing.steps,
                wall_s,
                steps_per_s,
                element_updates_per_s: steps_per_s * spec.elements() as f64,
                bytes_per_element,
                dt_s: sim.dt,
                commit: commit.clone(),
                timestamp: timestamp::utc_now(),
                cpus,
                machine_cpus,
                cpu_model: cpu_model.clone(),
                cpu_share: timing.cpu_s.map(|c| c / (wall_s * threads as f64)),
                mode: config.mode.clone(),
                contact_share,
                profile: profile.to_string(),
                peak_rss_bytes: memory::peak_rss_bytes(),
                peak_rss_reset: Some(reset),
                static_solve: None,
                scipy_csr: None,
            };
            if let Some(path) = &config.history {
                history::append(path, &record)?;
            }
            on_record(&record);
            records.push(record);
        }
        if let Some(python) = python.as_deref().filter(|_| wants_scipy(&spec)) {
            let dcfm: Vec<&ThroughputRecord> =
                records.iter().filter(|r| r.case == spec.name()).collect();
            let run = ScriptRun {
                divisions: spec.divisions,
                dt: dcfm.first().map_or(0.0, |r| r.dt_s),
                warmup,
                min_wall_s: config.min_wall_s,
                min_steps: config.min_steps,
                max_steps: config.max_steps,
            };
            let script = scipy_csr::script_path(&root);
            let name = scipy_csr::case_name(spec.divisions);
            match scipy_csr::measure(python, &script, &run).and_then(|out| {
                if out.elements != spec.elements() || out.nodes != nodes {
                    Err(format!(
                        "the script's cube has {} elements and {} nodes, dcfm's {} and {}",
                        out.elements,
                        out.nodes,
                        spec.elements(),
                        nodes
                    ))
                } else {
                    Ok(out)
                }
            }) {
                Err(why) => on_note(&format!("{name} skipped: {why}; no ratio recorded")),
                Ok(out) => {
                    let rate = out.element_updates_per_s;
                    let wall_s = out.seconds;
                    let record = ThroughputRecord {
                        case: name,
                        elements: out.elements,
                        nodes: out.nodes,
                        integration: spec.integration.name().to_string(),
                        threads: 1,
                        steps: out.steps,
                        wall_s,
                        steps_per_s: out.steps as f64 / wall_s,
                        element_updates_per_s: rate,
                        bytes_per_element: out.csr_bytes as f64 / out.elements as f64,
                        dt_s: out.dt_s,
                        commit: commit.clone(),
                        timestamp: timestamp::utc_now(),
                        cpus,
                        machine_cpus,
                        cpu_model: cpu_model.clone(),
                        cpu_share: Some(out.cpu_s / wall_s),
                        mode: config.mode.clone(),
                        contact_share: None,
                        profile: profile.to_string(),
                        peak_rss_bytes: Some(out.peak_rss_bytes),
                        peak_rss_reset: Some(true),
                        static_solve: None,
                        scipy_csr: Some(ScipyCsrInfo {
                            dofs: out.dofs,
                            dofs_total: out.dofs_total,
                            nnz: out.nnz,
                            assembly_s: out.assembly_s,
                            python: out.python,
                            numpy: out.numpy,
                            scipy: out.scipy,
                            skfem: out.skfem,
                            dcfm_over_scipy: dcfm
                                .iter()
                                .map(|r| (r.threads, r.element_updates_per_s / rate))
                                .collect(),
                        }),
                    };
                    if let Some(path) = &config.history {
                        history::append(path, &record)?;
                    }
                    on_record(&record);
                    records.push(record);
                }
            }
        }
    }
    let threads = config.threads.iter().copied().max().unwrap_or(1);
    for (n, solver) in config.static_cases() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()?;
        let reset = memory::reset_peak_rss();
        let cpu0 = cputime::process_cpu_seconds();
        let (timing, wall_s, nodes) =
            pool.install(|| crate::static_solve::time_static_solve(n, solver))?;
        let cpu_s = cputime::process_cpu_seconds().zip(cpu0).map(|(b, a)| b - a);
        let elements = n * n * n;
        let record = ThroughputRecord {
            case: crate::static_solve::case_name(n, solver),
            elements,
            nodes,
            integration: Integration::Full.name().to_string(),
            threads,
            steps: 1,
            wall_s,
            steps_per_s: 1.0 / wall_s.max(1e-9),
            element_updates_per_s: elements as f64 / wall_s.max(1e-9),
            bytes_per_element: (timing.stiffness_bytes + timing.factor_bytes) as f64
                / elements as f64,
            dt_s: 0.0,
            commit: commit.clone(),
            timestamp: timestamp::utc_now(),
            cpus,
            machine_cpus,
            cpu_model: cpu_model.clone(),
            cpu_share: cpu_s.map(|c| c / (wall_s.max(1e-9) * threads as f64)),
            mode: config.mode.clone(),
            contact_share: None,
            profile: profile.to_string(),
            peak_rss_bytes: memory::peak_rss_bytes(),
            peak_rss_reset: Some(reset),
            static_solve: Some(timing),
            scipy_csr: None,
        };
        if let Some(path) = &config.history {
            history::append(path, &record)?;
        }
        on_record(&record);
        records.push(record);
    }
    Ok(records)
}
