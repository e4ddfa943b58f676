//! Issue 13 leftovers: values valid but far outside what their field means are warned at
//! their field (and listed in summary.json); impossible values and a vanishing time step
//! are refused at their field; a failed run leaves summary.json with status "failed", the
//! error, and its failing state as the last frame of case.pvd.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::LazyLock;

mod common;

use dcfm::case::parse_case;
use dcfm_app::run::run_case;

/// A 1 m rock cube of 2 × 2 × 2 elements on a fixed base: c_p = 2981 m/s, stable step
/// ≈ 1.3e-4 s.
static CUBE: LazyLock<String> =
    LazyLock::new(|| common::elastic_block("cube", "0.002", 1.0, common::GRAVITY));

fn dir(name: &str) -> PathBuf {
    common::created_dir("honest", name)
}

fn warnings_of(text: &str) -> Vec<String> {
    parse_case(text, "c.toml", Path::new("."))
        .unwrap()
        .warnings
        .iter()
        .map(|w| w.to_string())
        .collect()
}

fn error_of(text: &str) -> String {
    parse_case(text, "c.toml", Path::new("."))
        .unwrap_err()
        .to_string()
}

fn has(warnings: &[String], needle: &str) -> bool {
    warnings.iter().any(|w| w.contains(needle))
}

#[test]
fn a_sound_case_has_no_warnings() {
    assert_eq!(warnings_of(&CUBE), Vec::<String>::new());
}

#[test]
fn units_slips_are_warned_at_their_field_with_the_usual_range() {
    // Density in t/m³, Young's modulus in GPa, gravity in mm/s².
    let w = warnings_of(
        &CUBE
            .replace("density = 2700.0", "density = 2.7")
            .replace("young = 20e9", "young = 20.0")
            .replace("-9.81]", "-9810.0]"),
    );
    assert_eq!(w.len(), 3, "{w:?}");
    assert!(
        has(
            &w,
            "c.toml: materials.rock.density = 2.7: outside the usual 100 to 23000 kg/m³"
        ),
        "{w:?}"
    );
    assert!(
        has(&w, "materials.rock.young = 20: outside the usual"),
        "{w:?}"
    );
    assert!(has(&w, "loads.gravity.acceleration = 9810"), "{w:?}");
}

#[test]
fn a_tensile_strength_in_pa_instead_of_mpa_is_warned() {
    let pd = CUBE.replace(
        "density = 2700.0\n",
        "density = 2700.0\n[materials.rock.plastic_damage]\nft0 = 1.3\nfc = 30e6\n",
    );
    let pd = pd.replace("model = \"elastic\"", "model = \"plastic_damage\"");
    // The same with MPa: no warning.
    assert_eq!(
        warnings_of(&pd.replace("ft0 = 1.3", "ft0 = 1.3e6")),
        Vec::<String>::new()
    );
    let w = warnings_of(&pd);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        has(
            &w,
            "materials.rock.plastic_damage.ft0 = 1.3: outside the usual 10000 to 100e6 Pa"
        ) && has(&w, "MPa typed as Pa"),
        "{w:?}"
    );
}

#[test]
fn a_friction_coefficient_above_two_is_warned() {
    let two = CUBE
        .replace(
            "divisions = [2, 2, 2]",
            "divisions = [2, 2, 1]\n[[mesh.blocks]]\nname = \"top\"\norigin = [0.0, 0.0, 1.0]\n\
             size = [1.0, 1.0, 1.0]\ndivisions = [2, 2, 1]",
        )
        .replace("[mesh]", "[mesh]\nsplit = [[\"b\", \"top\"]]")
        .replace(
            "[[boundary.fixed]]",
            "[[regions]]\nname = \"top\"\nmaterial = \"rock\"\n[[interfaces]]\nname = \"j\"\n\
             surface_a = \"top-b\"\nsurface_b = \"b-top\"\nmu_s = 30.0\nmu_d = 0.6\n\
             cohesion = 0.5\n[[boundary.fixed]]",
        );
    let w = warnings_of(&two);
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(
        has(&w, "interfaces[0].mu_s = 30: outside the usual 0 to 2"),
        "{w:?}"
    );
    assert!(has(&w, "interfaces[0].cohesion = 0.5"), "{w:?}");
    assert!(warnings_of(
        &two.replace("mu_s = 30.0", "mu_s = 0.7")
            .replace("cohesion = 0.5", "cohesion = 0.0")
    )
    .is_empty());
}

#[test]
fn a_time_step_far_below_the_stable_one_is_warned_and_a_vanishing_one_refused() {
    // 1e-8 s against ≈ 1.3e-4 s: valid, ten thousand times the steps needed.
    let w = warnings_of(&CUBE.replace("end = 0.002", "end = 0.002\ndt = 1e-8"));
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        has(&w, "c.toml: time.dt = 10e-9:") && has(&w, "of the stable step"),
        "{w:?}"
    );
    // 1e-300 s: an input error at time.dt, whatever the end time (a short end gives few
    // steps, a long one more than 2^53).
    for end in ["0.002", "1e-297"] {
        let e = error_of(&CUBE.replace("end = 0.002", &format!("end = {end}\ndt = 1e-300")));
        assert!(
            e.starts_with("c.toml: time.dt = 1e-300: a vanishing time step") && !e.contains("  "),
            "{e}"
        );
    }
    // Every element prescribed: no stable step, but 1e-300 s still overflows the steps.
    let e = error_of(
        &CUBE
            .replace("end = 0.002", "end = 0.002\ndt = 1e-300")
            .replace("set = \"b.zmin\"", "set = \"b\""),
    );
    assert!(e.contains("time.dt = 1e-300") && e.contains("2^53"), "{e}");
}

#[test]
fn impossible_values_are_refused_at_their_field() {
    let e = error_of(&CUBE.replace("young = 20e9", "young = 1e300"));
    assert!(
        e.starts_with("c.toml: materials.rock.young = 1e300: no solid has it"),
        "{e}"
    );
    let e = error_of(&CUBE.replace("young = 20e9", "young = 1e-300"));
    assert!(
        e.starts_with("c.toml: materials.rock.young = 1e-300:"),
        "{e}"
    );
    let e = error_of(&CUBE.replace("density = 2700.0", "density = 1e-300"));
    assert!(
        e.starts_with("c.toml: materials.rock.density = 1e-300:"),
        "{e}"
    );
    let e = error_of(&CUBE.replace(
        "divisions = [2, 2, 2]",
        "divisions = [3, 2, 2]\ngrading = [1e200, 1.0, 1.0]",
    ));
    assert!(
        e.starts_with("c.toml: mesh.blocks[0].grading[0] = 1e200: a finite ratio"),
        "{e}"
    );
    // A strong grading that any graded mesh may use is accepted, and warned beyond 100.
    let graded = |g: &str| {
        CUBE.replace(
            "divisions = [2, 2, 2]",
            &format!("divisions = [3, 2, 2]\ngrading = [{g}, 1.0, 1.0]"),
        )
    };
    assert!(warnings_of(&graded("20.0")).is_empty());
    assert!(has(
        &warnings_of(&graded("1000.0")),
        "mesh.blocks[0].grading[0] = 1000"
    ));
}

#[test]
fn summary_json_lists_the_warnings_and_a_completed_status() {
    let out = dir("warned");
    let text = CUBE.replace("-9.81]", "-9810.0]");
    let s = run_case(
        parse_case(&text, "c.toml", Path::new(".")).unwrap(),
        &common::options(&out),
    )
    .unwrap();
    assert_eq!((s.status, s.error.as_deref()), ("completed", None));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(v["status"], "completed");
    assert!(v["error"].is_null());
    assert_eq!(v["warnings"][0]["field"], "loads.gravity.acceleration");
    assert_eq!(v["warnings"][0]["value"], "9810");
    let _ = std::fs::remove_dir_all(&out);
}

/// An initial velocity of 2000 m/s, above half the P-wave speed: strains of order one at
/// the first step, an instability.
fn exploding() -> String {
    CUBE.replace(
        "[loads.gravity]",
        "[[initial.velocity]]\nset = \"b.zmax\"\nvalue = [0.0, 0.0, 2000.0]\n[output]\nvtu_every = 1\n[loads.gravity]",
    )
}

#[test]
fn a_failed_run_leaves_its_status_its_error_and_its_failing_state() {
    let out = dir("failed");
    let case = parse_case(&exploding(), "c.toml", Path::new(".")).unwrap();
    let e = run_case(case, &common::options(&out))
        .unwrap_err()
        .to_string();
    assert!(e.contains("unstable"), "{e}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(v["status"], "failed");
    assert_eq!(v["error"].as_str().unwrap(), e);
    let frame = v["failure_frame"].as_str().unwrap().to_string();
    assert_eq!(frame, "mesh_000001_failed.vtu");
    assert_eq!(v["steps"], 1);
    // The failing state is the last frame of the collection, after the initial one.
    let pvd = std::fs::read_to_string(out.join("case.pvd")).unwrap();
    let first = pvd.find("mesh_000000.vtu").expect("initial frame listed");
    let last = pvd.find(&frame).expect("failure frame listed");
    assert!(first < last, "{pvd}");
    assert_eq!(pvd.matches("<DataSet").count(), 2, "{pvd}");
    let vtu = std::fs::read(out.join(&frame)).unwrap();
    assert!(String::from_utf8_lossy(&vtu).contains("Name=\"velocity\""));
    // Written atomically: no temporary file left.
    for entry in std::fs::read_dir(&out).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.ends_with(".tmp"), "{name}");
    }
    // A sound run in the same folder replaces it: no failure frame left.
    run_case(
        parse_case(&CUBE, "c.toml", Path::new(".")).unwrap(),
        &common::options(&out),
    )
    .unwrap();
    assert!(!out.join(&frame).exists());
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn dcfm_check_and_run_print_the_warnings_on_stderr() {
    let d = dir("cli");
    let path = d.join("slip.toml");
    std::fs::write(&path, CUBE.replace("density = 2700.0", "density = 2.7")).unwrap();
    let check = Command::new(env!("CARGO_BIN_EXE_dcfm"))
        .arg("check")
        .arg(&path)
        .output()
        .unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&check.stdout),
        String::from_utf8_lossy(&check.stderr),
    );
    assert!(check.status.success(), "{stdout}{stderr}");
    assert!(
        stderr.contains("warning: ") && stderr.contains("materials.rock.density = 2.7"),
        "{stderr}"
    );
    assert!(!stdout.contains("materials.rock.density"), "{stdout}");
    let run = Command::new(env!("CARGO_BIN_EXE_dcfm"))
        .args(["run", "--quiet", "--out"])
        .arg(d.join("out"))
        .arg(&path)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(stderr.contains("materials.rock.density = 2.7"), "{stderr}");
    // An impossible value: refused by check, naming the field.
    std::fs::write(&path, CUBE.replace("young = 20e9", "young = 1e300")).unwrap();
    let check = Command::new(env!("CARGO_BIN_EXE_dcfm"))
        .arg("check")
        .arg(&path)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&check.stderr);
    assert_eq!(check.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("materials.rock.young = 1e300"), "{stderr}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_run_failing_on_another_error_keeps_its_last_state_as_the_failure_frame() {
    let out = dir("io");
    // A folder where the frame of step 1 must go: its write fails after step 1.
    std::fs::create_dir_all(out.join("mesh_000001.vtu").join("x")).unwrap();
    let text = CUBE.replace(
        "[loads.gravity]",
        "[output]\nvtu_every = 1\n[loads.gravity]",
    );
    let case = parse_case(&text, "c.toml", Path::new(".")).unwrap();
    let e = run_case(case, &common::options(&out))
        .unwrap_err()
        .to_string();
    assert!(e.contains("mesh_000001.vtu"), "{e}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(v["status"], "failed");
    assert_eq!(v["error"].as_str().unwrap(), e);
    // Not an instability: the last completed state, step 1.
    assert_eq!(v["steps"], 1);
    assert_eq!(v["failure_frame"], "mesh_000001_failed.vtu");
    let pvd = std::fs::read_to_string(out.join("case.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 2, "{pvd}");
    assert!(pvd.contains("file=\"mesh_000001_failed.vtu\""), "{pvd}");
    assert!(out.join("mesh_000001_failed.vtu").is_file());
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn absurd_lengths_damping_and_gravity_are_named_at_their_field() {
    // Block edges of 1e300 m and 1e-300 m read as "element 0: degenerate" before.
    for size in ["1e300", "1e-300"] {
        let e = error_of(&CUBE.replace(
            "size = [1.0, 1.0, 1.0]",
            &format!("size = [{size}, 1.0, 1.0]"),
        ));
        assert!(
            e.starts_with(&format!(
                "c.toml: mesh.blocks[0].size[0] = {size}: a length from"
            )),
            "{e}"
        );
    }
    // Rayleigh coefficients of 1e300 read as "time.dt = inf" before.
    for (key, field) in [("alpha", "damping.alpha"), ("beta", "damping.beta")] {
        let e = error_of(&format!("{}[damping]\n{key} = 1e300\n", *CUBE));
        assert!(
            e.starts_with(&format!("c.toml: {field} = 1e300: at most")),
            "{e}"
        );
    }
    // A region's own damping is named by its region.
    let e = error_of(&CUBE.replace(
        "material = \"rock\"\n",
        "material = \"rock\"\ndamping = { beta = 1e300 }\n",
    ));
    assert!(
        e.starts_with("c.toml: regions[0].damping.beta = 1e300"),
        "{e}"
    );
    // Gravity of 1e300 m/s²: its length does not overflow past the warning.
    let w = warnings_of(&CUBE.replace("-9.81]", "-1e300]"));
    assert!(has(&w, "loads.gravity.acceleration = 1e300"), "{w:?}");
}

#[test]
fn a_vanishing_safety_factor_is_refused_and_a_tiny_one_warned_at_time_safety() {
    let e = error_of(&CUBE.replace("end = 0.002", "end = 0.002\nsafety = 1e-300"));
    assert!(
        e.starts_with("c.toml: time.safety = 1e-300: a vanishing time step") && !e.contains("  "),
        "{e}"
    );
    let w = warnings_of(&CUBE.replace("end = 0.002", "end = 0.002\nsafety = 1e-4"));
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        has(&w, "c.toml: time.safety = 100e-6: below 0.001"),
        "{w:?}"
    );
    // Nearly incompressible: valid, warned.
    let w = warnings_of(&CUBE.replace("poisson = 0.25", "poisson = 0.4999"));
    assert!(
        has(
            &w,
            "materials.rock.poisson = 0.4999: outside the usual -0.5 to 0.495"
        ),
        "{w:?}"
    );
    assert!(warnings_of(&CUBE.replace("poisson = 0.25", "poisson = 0.49")).is_empty());
}
