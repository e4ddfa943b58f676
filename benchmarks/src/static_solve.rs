//! The static-stage rows of the throughput runner (issue #7): the direct step of an elastic
//! n³ cube under its own weight (fully integrated elements, base fixed), solved with the
//! Cholesky factor — timed in its three phases, assembly of K, factorisation (orderings
//! included), forward/back solve — and with conjugate gradients (assembly, iterations),
//! with the sizes of K and L and the process's peak memory.

use serde::{Deserialize, Serialize};

use dcfm::element::Integration;
use dcfm::load::{Gravity, TimeFunction};
use dcfm::stage::static_stage::linear_solver::LinearSolverChoice;
use dcfm::stage::static_stage::{self, Convergence, InSitu, StaticPlan, StepSolver};

use crate::cube::CubeSpec;
use crate::error::BenchError;

/// Timings and sizes of one static direct solve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StaticSolveTiming {
    /// Equations (free DOFs).
    pub equations: usize,
    /// Stored nonzeros of K (upper triangle).
    pub stiffness_nonzeros: usize,
    /// Nonzeros of the Cholesky factor L.
    pub factor_nonzeros: usize,
    /// faer's supernodal factorisation (else simplicial).
    pub supernodal: bool,
    /// Conjugate-gradient iterations (the conjugate-gradient row).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cg_iterations: Option<usize>,
    /// Seconds in the assembly of K, the factorisation and the solve.
    pub assembly_s: f64,
    pub factorization_s: f64,
    pub solve_s: f64,
    /// Bytes of K (values and row indices) and of L (values).
    pub stiffness_bytes: u64,
    pub factor_bytes: u64,
    /// Peak resident memory (VmHWM, Linux) since the runner reset it before this case
    /// (the record's `peak_rss_reset`), bytes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_rss_bytes: Option<u64>,
}

/// The process's peak resident set size (Linux), bytes: [`crate::memory::peak_rss_bytes`].
pub fn peak_rss_bytes() -> Option<u64> {
    crate::memory::peak_rss_bytes()
}

/// The linear solvers the static rows time, in run order.
pub const SOLVERS: [LinearSolverChoice; 2] = [
    LinearSolverChoice::Cholesky,
    LinearSolverChoice::ConjugateGradients,
];

/// Case name of the static row of an n³ cube solved by `solver`.
pub fn case_name(n: usize, solver: LinearSolverChoice) -> String {
    match solver {
        LinearSolverChoice::ConjugateGradients => format!("static_cg_cube{n}"),
        _ => format!("static_cholesky_cube{n}"),
    }
}

/// Build the n³ cube, solve it statically under gravity in one direct step with `solver`
/// and return the timing (and the wall time of the whole static stage, model building
/// excluded).
pub fn time_static_solve(
    n: usize,
    solver: LinearSolverChoice,
) -> Result<(StaticSolveTiming, f64, usize), BenchError> {
    let spec = CubeSpec::new(n, Integration::Full);
    let mut model = spec.model()?;
    model.initial_velocity.clear();
    model.gravity = Some(Gravity {
        acceleration: [0.0, 0.0, -9.81],
        history: TimeFunction::Constant { value: 1.0 },
    });
    let nodes = model.mesh.n_nodes();
    let mut plan = StaticPlan::new(model.constraints.clone());
    plan.linear.choice = solver;
    plan.in_situ = InSitu::Gravity {
        solver: StepSolver::Direct,
        convergence: Convergence::default(),
    };
    let t0 = std::time::Instant::now();
    let (_, result) = static_stage::run(model, &plan)?;
    let wall = t0.elapsed().as_secs_f64();
    let s = &result.steps[0];
    Ok((
        StaticSolveTiming {
            equations: s.equations,
            stiffness_nonzeros: s.stiffness_nonzeros,
            factor_nonzeros: s.factor_nonzeros,
            supernodal: s.supernodal,
            cg_iterations: (solver == LinearSolverChoice::ConjugateGradients)
                .then_some(s.iterations),
            assembly_s: s.seconds[0],
            factorization_s: s.seconds[1],
            solve_s: s.seconds[2],
            stiffness_bytes: (s.stiffness_nonzeros * 16) as u64,
            factor_bytes: (s.factor_nonzeros * 8) as u64,
            peak_rss_bytes: peak_rss_bytes(),
        },
        wall,
        nodes,
    ))
}
