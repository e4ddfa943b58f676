//! The static stage of `cases/static_k0_excavation_lining.toml` — K0 in-situ stress, an
//! excavation, a lining placed on the rock; direct steps and relaxation steps with the
//! direct predictor — solved with the Cholesky
//! factor and with conjugate gradients (`[static] linear_solver`), and with `auto` under a
//! factor-memory limit too small for the factor: the same displacements, each step
//! reporting the solver it used.

use std::path::Path;

use dcfm::case::parse_case;
use dcfm::stage::static_stage::linear_solver::LinearSolverChoice;
use dcfm::stage::static_stage::{self, StaticResult, StepSolver};

fn solve(extra: &str) -> StaticResult {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases");
    let text = std::fs::read_to_string(dir.join("static_k0_excavation_lining.toml")).unwrap();
    let text = text.replacen("[static]\n", &format!("[static]\n{extra}\n"), 1);
    let case = parse_case(&text, "linear solvers", &dir).unwrap();
    let plan = case.static_plan.clone().expect("a static stage");
    static_stage::run(case.model, &plan).unwrap().1
}

#[test]
fn cholesky_and_conjugate_gradients_give_the_same_static_state() {
    let chol = solve("linear_solver = \"cholesky\"");
    let cg = solve("linear_solver = \"conjugate_gradients\"\ncg_tolerance = 1e-12");
    let auto = solve("factor_memory_limit = 1e-6");
    let direct = |r: &StaticResult| {
        r.steps
            .iter()
            .filter(|s| s.solver == StepSolver::Direct)
            .cloned()
            .collect::<Vec<_>>()
    };
    assert!(direct(&chol).len() >= 2);
    for s in &direct(&chol) {
        assert_eq!(
            s.linear_solver,
            Some(LinearSolverChoice::Cholesky),
            "{}",
            s.name
        );
        assert!(s.factor_nonzeros > 0);
    }
    for s in direct(&cg).iter().chain(&direct(&auto)) {
        assert_eq!(
            s.linear_solver,
            Some(LinearSolverChoice::ConjugateGradients),
            "{}",
            s.name
        );
        assert!(s.iterations > 1, "{}: {} iterations", s.name, s.iterations);
        assert!(s.out_of_balance.ratio < 1e-6, "{}", s.name);
    }
    let umax = chol.u.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(umax > 0.0);
    for other in [&cg, &auto] {
        let err = chol
            .u
            .iter()
            .flatten()
            .zip(other.u.iter().flatten())
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err <= 1e-8 * umax, "{err:e} of {umax:e}");
    }
}
