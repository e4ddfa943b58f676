//! No runaways and readable numbers (issue 13.4, 13.6): the step budget of `dcfm run`,
//! the wall-time estimate and the engineering notation of `dcfm check`, `--threads`
//! capped, `--resume` without a checkpoint, contradicting contact fields, and a progress
//! bar whose simulated time belongs to its step.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Arc, LazyLock, Mutex};

mod common;

use dcfm::case::parse_case;
use dcfm_app::run::RunOptions;

/// One 2 m block of 2×2×2 elements: Δt = 0.9 × 2.598e-4 s, so 9 steps to 0.002 s.
static SMALL: LazyLock<String> =
    LazyLock::new(|| common::elastic_block("small", "0.002", 2.0, common::GRAVITY));

fn dir(name: &str) -> PathBuf {
    common::created_dir("limits", name)
}

fn run(text: &str, out: &Path, allow_long: bool) -> dcfm::Result<dcfm_app::run::RunSummary> {
    common::run_text(
        "small.toml",
        text,
        &RunOptions {
            allow_long,
            ..common::options(out)
        },
    )
}

#[test]
fn an_end_time_of_1e30_is_refused_at_once_naming_the_budget() {
    let out = dir("1e30");
    let text = SMALL.replace("end = 0.002", "end = 1e30");
    let t0 = std::time::Instant::now();
    let e = run(&text, &out, false).unwrap_err().to_string();
    assert!(
        e.starts_with("small.toml: time.end = 1e30: 4.277e33 steps")
            && e.contains("time.max_steps = 100e6")
            && e.contains("--allow-long"),
        "{e}"
    );
    // Even when asked: more than 2^53 steps never end (t + Δt = t).
    let e = run(&text, &out, true).unwrap_err().to_string();
    assert!(e.contains("time.end") && e.contains("2^53"), "{e}");
    assert!(
        t0.elapsed().as_secs_f64() < 5.0,
        "refusals must not run steps"
    );
    assert!(!out.join("histories.csv").exists());
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn the_step_budget_is_settable_and_can_be_overridden() {
    let out = dir("budget");
    let text = SMALL.replace("end = 0.002", "end = 0.002\nmax_steps = 5");
    let e = run(&text, &out, false).unwrap_err().to_string();
    assert!(
        e.contains("time.end") && e.contains("time.max_steps = 5") && e.contains("9 steps"),
        "{e}"
    );
    let s = run(&text, &out, true).unwrap();
    assert_eq!(s.steps, 9);
    // Exactly at the budget runs.
    let s = run(
        &SMALL.replace("end = 0.002", "end = 0.002\nmax_steps = 9e0"),
        &out,
        false,
    )
    .unwrap();
    assert_eq!(s.steps, 9);
    for bad in ["0", "2.5", "-3", "1e300"] {
        let text = SMALL.replace("end = 0.002", &format!("end = 0.002\nmax_steps = {bad}"));
        let e = parse_case(&text, "small.toml", Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("small.toml: time.max_steps = ") && e.contains("whole number"),
            "{bad}: {e}"
        );
    }
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn slip_threshold_and_its_fraction_together_are_an_error() {
    let case = |extra: &str| {
        format!(
            r#"
[time]
end = 0.001
[mesh]
split = [["base", "block"]]
[[mesh.blocks]]
name = "base"
origin = [0.0, 0.0, 0.0]
size = [2.0, 2.0, 1.0]
divisions = [2, 2, 1]
[[mesh.blocks]]
name = "block"
origin = [0.0, 0.0, 1.0]
size = [2.0, 2.0, 1.0]
divisions = [2, 2, 1]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "base"
material = "rock"
[[regions]]
name = "block"
material = "rock"
[[interfaces]]
name = "j"
surface_a = "block-base"
surface_b = "base-block"
mu_s = 0.5
mu_d = 0.4
cohesion = 0.0
{extra}
"#
        )
    };
    let e = parse_case(
        &case("slip_threshold = 0.01\nslip_threshold_fraction = 0.5"),
        "j.toml",
        Path::new("."),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("j.toml: interfaces[0].slip_threshold_fraction = 0.5")
            && e.contains("interfaces[0].slip_threshold = 0.01")
            && e.contains("not both"),
        "{e}"
    );
    // Either alone, or neither, is fine — the default fraction included.
    for extra in ["slip_threshold = 0.01", "slip_threshold_fraction = 0.5", ""] {
        parse_case(&case(extra), "j.toml", Path::new("."))
            .unwrap_or_else(|e| panic!("{extra}: {e}"));
    }
}

fn dcfm(args: &[&str]) -> (bool, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_dcfm"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Longest run of digits in `s`.
fn longest_digit_run(s: &str) -> usize {
    s.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

#[test]
fn check_prints_huge_counts_readably_with_a_wall_time_and_the_budget_warning() {
    let d = dir("check");
    let case = d.join("huge.toml");
    std::fs::write(&case, SMALL.replace("end = 0.002", "end = 1e30")).unwrap();
    let (ok, out, err) = dcfm(&["check", case.to_str().unwrap()]);
    assert!(ok, "{err}");
    let time = out.lines().find(|l| l.starts_with("time ")).unwrap();
    // 1e30 s / 2.338e-4 s = 4.277e33 steps, in engineering notation.
    assert!(
        time.contains("end 1e30 s") && time.contains("e33 steps"),
        "{time}"
    );
    assert!(longest_digit_run(&out) < 12, "{out}");
    assert!(
        out.lines()
            .any(|l| l.starts_with("warning") && l.contains("dcfm run will refuse")),
        "{out}"
    );
    let est = out.lines().find(|l| l.starts_with("estimate")).unwrap();
    assert!(
        est.contains("years") && est.contains("element-updates/s"),
        "{est}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn check_estimates_the_wall_time_of_an_ordinary_case() {
    let d = dir("check-small");
    let case = d.join("small.toml");
    std::fs::write(&case, &*SMALL).unwrap();
    let (ok, out, err) = dcfm(&["check", case.to_str().unwrap()]);
    assert!(ok, "{err}");
    assert!(!out.contains("warning"), "{out}");
    let est = out.lines().find(|l| l.starts_with("estimate")).unwrap();
    assert!(
        est.contains("under a second") && est.contains("for 9 steps"),
        "{est}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn run_refuses_a_runaway_and_notes_capped_threads_and_a_missing_checkpoint() {
    let d = dir("cli");
    let huge = d.join("huge.toml");
    std::fs::write(&huge, SMALL.replace("end = 0.002", "end = 1e30")).unwrap();
    let out = d.join("out");
    let (ok, _, err) = dcfm(&[
        "run",
        huge.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        !ok && err.contains("time.max_steps") && err.contains("--allow-long"),
        "{err}"
    );

    let small = d.join("small.toml");
    std::fs::write(&small, &*SMALL).unwrap();
    let (ok, stdout, err) = dcfm(&[
        "run",
        small.to_str().unwrap(),
        "--quiet",
        "--resume",
        "--threads",
        "100000",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert!(
        err.contains("--threads 100000 is more than the") && err.contains("cores here; using"),
        "{err}"
    );
    assert!(
        err.contains("--resume: no checkpoint in") && err.contains("starting from scratch"),
        "{err}"
    );
    assert!(stdout.contains(": 9 steps"), "{stdout}");
    let _ = std::fs::remove_dir_all(&d);
}

/// A terminal that records every line the bar draws.
#[derive(Debug, Default, Clone)]
struct Recorder(Arc<Mutex<Vec<String>>>);

impl indicatif::TermLike for Recorder {
    fn width(&self) -> u16 {
        200
    }
    fn move_cursor_up(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn move_cursor_down(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn move_cursor_right(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn move_cursor_left(&self, _: usize) -> std::io::Result<()> {
        Ok(())
    }
    fn write_line(&self, s: &str) -> std::io::Result<()> {
        self.0.lock().unwrap().push(s.to_string());
        Ok(())
    }
    fn write_str(&self, s: &str) -> std::io::Result<()> {
        self.write_line(s)
    }
    fn clear_line(&self) -> std::io::Result<()> {
        Ok(())
    }
    fn flush(&self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn the_progress_bar_shows_the_time_of_its_own_step() {
    let rec = Recorder::default();
    let dt = 2.5e-4;
    let bar = dcfm_app::progress::run_bar(
        indicatif::ProgressDrawTarget::term_like(Box::new(rec.clone())),
        10_000,
        0,
        dt,
    );
    for k in 1..=6u64 {
        std::thread::sleep(std::time::Duration::from_millis(60));
        dcfm_app::progress::update(&bar, 64 * k, 1e6 * k as f64);
    }
    let lines = rec.0.lock().unwrap().clone();
    let mut checked = 0;
    for l in lines.iter().filter(|l| l.contains("step ")) {
        let step: f64 = l
            .split("step ")
            .nth(1)
            .unwrap()
            .split('/')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        let t: f64 = l
            .split("t = ")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!((t - step * dt).abs() <= 1e-3 * step * dt + 1e-12, "{l}");
        if step > 0.0 {
            checked += 1;
        }
    }
    assert!(checked >= 3, "too few redraws recorded: {lines:?}");
}
