//! The scipy CSR leapfrog baseline (issue 11): `benchmarks/python/csr_leapfrog.py` run on
//! the same elastic fully integrated cube in the same run as `cube{n}_full`, as a row
//! `cube{n}_scipy_csr`, and the ratio of dcfm's element updates per second to it.
//!
//! The script assembles K of the same n³ cube with scikit-fem (2×2×2 Gauss hex8), condenses
//! the fixed base, lumps the mass and times the central-difference leapfrog
//! V^{n+½} = V^{n−½} + Δt M⁻¹(F − K Uⁿ), U^{n+1} = Uⁿ + Δt V^{n+½} (one CSR matvec per
//! step) on one thread; see its docstring.
//!
//! Python is looked for in this order: the runner's `--python`
//! ([`ScipyBaseline::Python`]), the environment variable [`PYTHON_ENV`], the project's
//! `.venv/bin/python` under the workspace root. No Python, a Python that cannot run the
//! script, or output that is not the expected JSON: the row is skipped with the reason,
//! and no ratio is recorded.

use std::collections::BTreeMap;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde::{Deserialize, Serialize};

/// Environment variable naming the Python interpreter to run the script with.
pub const PYTHON_ENV: &str = "DCFM_BENCH_PYTHON";

/// Whether and with which Python the baseline is measured.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ScipyBaseline {
    /// Not measured.
    Off,
    /// [`PYTHON_ENV`] if set, else `<workspace>/.venv/bin/python` if it exists, else
    /// skipped.
    Auto,
    /// This interpreter.
    Python(PathBuf),
}

/// The script, `<workspace root>/benchmarks/python/csr_leapfrog.py`.
pub fn script_path(root: &Path) -> PathBuf {
    root.join("benchmarks")
        .join("python")
        .join("csr_leapfrog.py")
}

/// The project venv's interpreter, `<root>/.venv/bin/python` (`Scripts\python.exe` on
/// Windows).
pub fn venv_python(root: &Path) -> PathBuf {
    if cfg!(windows) {
        root.join(".venv").join("Scripts").join("python.exe")
    } else {
        root.join(".venv").join("bin").join("python")
    }
}

/// The interpreter to use, or why there is none. `env` is the value of [`PYTHON_ENV`]
/// (passed in so that tests need not set the process environment).
pub fn find_python(
    choice: &ScipyBaseline,
    env: Option<OsString>,
    root: &Path,
) -> Result<PathBuf, String> {
    match choice {
        ScipyBaseline::Off => Err("switched off (--no-scipy)".to_string()),
        ScipyBaseline::Python(p) => Ok(p.clone()),
        ScipyBaseline::Auto => {
            if let Some(p) = env.filter(|p| !p.is_empty()) {
                return Ok(PathBuf::from(p));
            }
            let venv = venv_python(root);
            if venv.exists() {
                Ok(venv)
            } else {
                Err(format!(
                    "no Python found: {} does not exist and {PYTHON_ENV} is not set \
                     (run scripts/setup.sh, or pass --python)",
                    venv.display()
                ))
            }
        }
    }
}

/// What the script prints (one JSON line; keys it adds beyond these are ignored).
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct ScriptOutput {
    pub elements: usize,
    pub nodes: usize,
    /// DOFs of the stepped system (fixed base condensed out).
    pub dofs: usize,
    /// DOFs before condensing.
    pub dofs_total: usize,
    /// Nonzeros of the stepped CSR matrix.
    pub nnz: usize,
    /// Bytes of its data, indices and row pointers.
    pub csr_bytes: u64,
    pub steps: u64,
    /// Wall time of the timed step loop (s).
    pub seconds: f64,
    pub element_updates_per_s: f64,
    /// CPU time of the process during the timed loop (s).
    pub cpu_s: f64,
    pub dt_s: f64,
    /// Assembly of K and the lumped mass by scikit-fem (s), not timed in the rate.
    pub assembly_s: f64,
    pub peak_rss_bytes: u64,
    pub python: String,
    pub numpy: String,
    pub scipy: String,
    pub skfem: String,
}

/// The baseline's own data on its record (`scipy_csr` of a `cube{n}_scipy_csr` row).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScipyCsrInfo {
    /// DOFs of the stepped system (fixed base condensed out) and before condensing.
    pub dofs: usize,
    pub dofs_total: usize,
    /// Nonzeros of the stepped CSR matrix.
    pub nnz: usize,
    /// scikit-fem assembly of K and M (s).
    pub assembly_s: f64,
    /// Versions the row was measured with.
    pub python: String,
    pub numpy: String,
    pub scipy: String,
    pub skfem: String,
    /// dcfm's `cube{n}_full` element-updates/s in the same run over this row's, per thread
    /// count of dcfm (keys: threads).
    pub dcfm_over_scipy: BTreeMap<usize, f64>,
}

/// Parse the script's stdout: the last non-blank line must be the JSON object, every rate
/// and time finite and positive.
pub fn parse_output(stdout: &str) -> Result<ScriptOutput, String> {
    let line = stdout
        .lines()
        .rev()
        .find(|l| !l.trim().is_empty())
        .ok_or("the script printed nothing on stdout")?;
    let out: ScriptOutput = serde_json::from_str(line).map_err(|e| {
        format!(
            "the script's output {:?} is not its JSON record: {e}",
            clip(line)
        )
    })?;
    for (name, v) in [
        ("seconds", out.seconds),
        ("element_updates_per_s", out.element_updates_per_s),
        ("dt_s", out.dt_s),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(format!(
                "the script's {name} is {v}, expected a positive number"
            ));
        }
    }
    if out.elements == 0 || out.steps == 0 || out.nnz == 0 {
        return Err(format!(
            "the script reports {} elements, {} steps, {} nonzeros: expected at least one of each",
            out.elements, out.steps, out.nnz
        ));
    }
    Ok(out)
}

fn clip(s: &str) -> String {
    if s.chars().count() <= 200 {
        s.to_string()
    } else {
        s.chars().take(200).chain("...".chars()).collect()
    }
}

/// How the script is run for one cube.
#[derive(Clone, Debug, PartialEq)]
pub struct ScriptRun {
    pub divisions: usize,
    /// The time step of dcfm's case (the same discrete system is stepped).
    pub dt: f64,
    pub warmup: u64,
    pub min_wall_s: f64,
    pub min_steps: u64,
    pub max_steps: u64,
}

/// Run `script` with `python` for `run` (numpy/BLAS/OpenMP threads set to 1) and parse its
/// record; the error says why the row is skipped.
pub fn measure(python: &Path, script: &Path, run: &ScriptRun) -> Result<ScriptOutput, String> {
    if !script.exists() {
        return Err(format!("the script {} does not exist", script.display()));
    }
    let mut cmd = Command::new(python);
    cmd.arg(script)
        .arg("--divisions")
        .arg(run.divisions.to_string())
        .arg("--dt")
        .arg(format!("{:e}", run.dt))
        .arg("--warmup")
        .arg(run.warmup.max(1).to_string())
        .arg("--min-wall")
        .arg(run.min_wall_s.to_string())
        .arg("--min-steps")
        .arg(run.min_steps.to_string())
        .arg("--max-steps")
        .arg(run.max_steps.to_string());
    for var in [
        "OMP_NUM_THREADS",
        "OPENBLAS_NUM_THREADS",
        "MKL_NUM_THREADS",
        "NUMEXPR_NUM_THREADS",
        "VECLIB_MAXIMUM_THREADS",
    ] {
        cmd.env(var, "1");
    }
    let output = cmd
        .output()
        .map_err(|e| format!("could not start {}: {e}", python.display()))?;
    if !output.status.success() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        let tail: Vec<&str> = stderr.lines().rev().take(3).collect();
        let tail: Vec<&str> = tail.into_iter().rev().collect();
        return Err(format!(
            "{} {} failed ({}): {}",
            python.display(),
            script.display(),
            output.status,
            if tail.is_empty() {
                "no message".to_string()
            } else {
                tail.join(" | ")
            }
        ));
    }
    parse_output(&String::from_utf8_lossy(&output.stdout))
}

/// The row's case name, `cube{n}_scipy_csr`.
pub fn case_name(divisions: usize) -> String {
    format!("cube{divisions}_scipy_csr")
}

/// The dcfm case the row is compared with: `cube{n}_scipy_csr` → `cube{n}_full`.
pub fn dcfm_case(scipy_case: &str) -> Option<String> {
    scipy_case
        .strip_suffix("_scipy_csr")
        .map(|base| format!("{base}_full"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"{"case": "cube3_scipy_csr", "elements": 27, "nodes": 64, "dofs": 144, "dofs_total": 192, "nnz": 6170, "nnz_full": 8727, "csr_bytes": 74620, "warmup_steps": 8, "steps": 100, "seconds": 0.5, "steps_per_s": 200.0, "element_updates_per_s": 5400.0, "cpu_s": 0.5, "dt_s": 7.7e-4, "assembly_s": 0.13, "peak_rss_bytes": 67948544, "threads": 1, "checks": {"symmetry": 3e-17}, "python": "3.11.7", "numpy": "2.4.6", "scipy": "1.17.1", "skfem": "12.0.2"}"#;

    #[test]
    fn parses_the_last_line() {
        let out = parse_output(&format!("a warning\n{GOOD}\n\n")).unwrap();
        assert_eq!(
            (out.elements, out.nodes, out.dofs, out.nnz),
            (27, 64, 144, 6170)
        );
        assert_eq!(out.steps, 100);
        assert_eq!(out.scipy, "1.17.1");
    }

    #[test]
    fn refuses_bad_output() {
        assert!(parse_output("").unwrap_err().contains("nothing"));
        assert!(parse_output("hello").unwrap_err().contains("not its JSON"));
        let missing = GOOD.replace("\"nnz\": 6170, ", "");
        assert!(parse_output(&missing).unwrap_err().contains("nnz"));
        let zero = GOOD.replace("\"seconds\": 0.5", "\"seconds\": 0.0");
        assert!(parse_output(&zero).unwrap_err().contains("seconds is 0"));
        let no_steps = GOOD.replace("\"steps\": 100", "\"steps\": 0");
        assert!(parse_output(&no_steps).unwrap_err().contains("0 steps"));
    }

    #[test]
    fn python_search_order() {
        let root = Path::new("/nonexistent-root");
        let named = ScipyBaseline::Python("/x/python".into());
        assert_eq!(
            find_python(&named, Some("/y/python".into()), root),
            Ok(PathBuf::from("/x/python"))
        );
        assert_eq!(
            find_python(&ScipyBaseline::Auto, Some("/y/python".into()), root),
            Ok(PathBuf::from("/y/python"))
        );
        let none = find_python(&ScipyBaseline::Auto, Some("".into()), root).unwrap_err();
        assert!(
            none.contains("no Python found") && none.contains(PYTHON_ENV),
            "{none}"
        );
        assert!(
            find_python(&ScipyBaseline::Off, Some("/y/python".into()), root)
                .unwrap_err()
                .contains("--no-scipy")
        );
    }

    #[test]
    fn names() {
        assert_eq!(case_name(40), "cube40_scipy_csr");
        assert_eq!(
            dcfm_case("cube40_scipy_csr").as_deref(),
            Some("cube40_full")
        );
        assert_eq!(dcfm_case("cube40_full"), None);
    }
}
