//! Which linear solver a direct static step (and the relaxation's elastic predictor) uses
//! for K Δu = r: the sparse Cholesky factor ([`super::cholesky`], exact, memory growing as
//! n^{4/3} on 3D meshes) or preconditioned conjugate gradients
//! ([`super::conjugate_gradients`], memory proportional to K). `auto` analyses the
//! factor first — its size is known before any number of it is computed — and takes the
//! Cholesky factor when it fits `factor_memory_limit`, conjugate gradients otherwise.

use serde::{Deserialize, Serialize};

use super::assembly::Stiffness;
use super::cholesky::{Analysis, CholeskyKind, FactorError};
use super::conjugate_gradients::{self, CgError, CgSettings};

/// `[static] linear_solver`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LinearSolverChoice {
    /// Cholesky when its factor fits the memory limit, else conjugate gradients.
    #[default]
    Auto,
    Cholesky,
    ConjugateGradients,
}

/// The linear solver settings of the static stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearSettings {
    pub choice: LinearSolverChoice,
    /// Largest Cholesky factor `auto` accepts (bytes; 8 per nonzero of L).
    pub factor_memory_limit: f64,
    pub cg: CgSettings,
}

/// Default `factor_memory_limit` (GiB): half of the 8 GiB the full Yingxiuwan case is
/// allowed, the rest for the model and the explicit stage's state.
pub const DEFAULT_FACTOR_MEMORY_GIB: f64 = 4.0;

impl Default for LinearSettings {
    fn default() -> Self {
        Self {
            choice: LinearSolverChoice::Auto,
            factor_memory_limit: DEFAULT_FACTOR_MEMORY_GIB * GIB,
            cg: CgSettings::default(),
        }
    }
}

/// Bytes in a GiB.
pub const GIB: f64 = 1024.0 * 1024.0 * 1024.0;

/// The solver a solve used and what it cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LinearSolverUsed {
    Cholesky {
        /// Nonzeros of L.
        l_nnz: usize,
        supernodal: bool,
    },
    ConjugateGradients {
        iterations: usize,
        relative_residual: f64,
    },
}

/// Why a solve failed.
#[derive(Clone, Debug, PartialEq)]
pub enum LinearSolveError {
    Factor(FactorError),
    Iterative(CgError),
}

/// Solve K x = b in place (`b` becomes x). Returns the solver used and the seconds spent
/// preparing (ordering and factorisation, or the preconditioner and the iterations) and
/// in the solve proper.
pub fn solve_in_place(
    k: &Stiffness,
    b: &mut [f64],
    settings: &LinearSettings,
) -> Result<(LinearSolverUsed, [f64; 2]), LinearSolveError> {
    let t0 = std::time::Instant::now();
    let analysis = match settings.choice {
        LinearSolverChoice::ConjugateGradients => None,
        LinearSolverChoice::Cholesky | LinearSolverChoice::Auto => {
            Some(Analysis::new(k, CholeskyKind::Auto).map_err(LinearSolveError::Factor)?)
        }
    };
    // `auto` declines a factor over the limit (its analysis is dropped before iterating).
    let analysis = analysis.filter(|a| {
        settings.choice != LinearSolverChoice::Auto
            || a.l_nnz() as f64 * 8.0 <= settings.factor_memory_limit
    });
    match analysis {
        Some(a) => {
            let fact = a.factorize(k).map_err(LinearSolveError::Factor)?;
            let t1 = std::time::Instant::now();
            fact.solve_in_place(b);
            let used = LinearSolverUsed::Cholesky {
                l_nnz: fact.l_nnz,
                supernodal: fact.supernodal,
            };
            Ok((used, [(t1 - t0).as_secs_f64(), t1.elapsed().as_secs_f64()]))
        }
        None => {
            let out = conjugate_gradients::solve_in_place(k, b, settings.cg)
                .map_err(LinearSolveError::Iterative)?;
            let used = LinearSolverUsed::ConjugateGradients {
                iterations: out.iterations,
                relative_residual: out.relative_residual,
            };
            Ok((used, [t0.elapsed().as_secs_f64(), 0.0]))
        }
    }
}
