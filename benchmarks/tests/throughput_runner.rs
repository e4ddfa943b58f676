//! The throughput runner in quick mode on a tiny cube: every record carries every key of the
//! history contract with sane values, the history file gets one line per record and reads
//! back unchanged, and a filter that matches nothing is an error. Correctness only: no
//! assertion on how fast anything is.

use std::path::PathBuf;

use dcfm::element::Integration;
use dcfm_benchmarks::record::REQUIRED_KEYS;
use dcfm_benchmarks::{history, run, speedup, targets, RunConfig, ScipyBaseline};

fn scratch_history(tag: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join(format!("history-{tag}-{}.jsonl", std::process::id()));
    let _ = std::fs::remove_file(&path);
    path
}

fn tiny(history: Option<PathBuf>) -> RunConfig {
    RunConfig {
        sizes: vec![3],
        threads: vec![1, 2],
        min_wall_s: 0.0,
        min_steps: 4,
        max_steps: 8,
        history,
        plastic_damage: Vec::new(),
        plastic_damage_integrations: vec![Integration::Full],
        large_one_point_sizes: Vec::new(),
        boundaries: false,
        interface_sizes: Vec::new(),
        static_sizes: Vec::new(),
        // The scipy rows have their own test (scipy_csr_row.rs).
        scipy: ScipyBaseline::Off,
        ..RunConfig::quick()
    }
}

#[test]
fn plastic_damage_cubes_run_in_both_regimes() {
    use dcfm_benchmarks::cube::CubeMaterial;
    let config = RunConfig {
        integrations: Vec::new(),
        plastic_damage: vec![
            CubeMaterial::PlasticDamageElastic,
            CubeMaterial::PlasticDamageDamaging,
        ],
        threads: vec![1],
        ..tiny(None)
    };
    let records = run(&config, |_| {}).expect("plastic-damage run");
    let names: Vec<&str> = records.iter().map(|r| r.case.as_str()).collect();
    assert_eq!(names, ["cube3_full_pd_elastic", "cube3_full_pd_damaging"]);
    for r in &records {
        assert_eq!(r.integration, "full");
        // 8 points × (17 state values) × (old + new) × 8 bytes on top of the geometry.
        assert!(
            r.bytes_per_element > 8.0 * 17.0 * 2.0 * 8.0,
            "{}",
            r.bytes_per_element
        );
        assert!(r.element_updates_per_s > 0.0);
    }
}

/// Issue #11 rows: one-point plastic-damage cubes in both regimes and the large one-point
/// cube, with their peak memory; the standard and quick runs list them.
#[test]
fn one_point_plastic_damage_and_large_cube_rows() {
    use dcfm_benchmarks::cube::CubeMaterial;
    let config = RunConfig {
        integrations: Vec::new(),
        plastic_damage: vec![
            CubeMaterial::PlasticDamageElastic,
            CubeMaterial::PlasticDamageDamaging,
        ],
        plastic_damage_integrations: vec![Integration::OnePoint],
        large_one_point_sizes: vec![6],
        ..tiny(None)
    };
    let records = run(&config, |_| {}).expect("one-point plastic-damage run");
    let names: Vec<(&str, usize)> = records
        .iter()
        .map(|r| (r.case.as_str(), r.threads))
        .collect();
    assert_eq!(
        names,
        [
            ("cube3_one_point_pd_elastic", 1),
            ("cube3_one_point_pd_elastic", 2),
            ("cube3_one_point_pd_damaging", 1),
            ("cube3_one_point_pd_damaging", 2),
            ("cube6_one_point", 1),
            ("cube6_one_point", 2),
        ]
    );
    for r in &records {
        assert_eq!(r.integration, "one_point");
        assert!(r.element_updates_per_s > 0.0);
        if r.case.contains("_pd_") {
            // One point × 17 state values × (old + new) × 8 bytes on top of the geometry.
            assert!(
                r.bytes_per_element > 17.0 * 2.0 * 8.0,
                "{}",
                r.bytes_per_element
            );
        }
        if cfg!(target_os = "linux") {
            let peak = r.peak_rss_bytes.expect("VmHWM on Linux");
            assert!(peak > 1 << 20, "{}: peak {peak} bytes", r.case);
            assert!(r.peak_rss_reset.is_some());
        }
    }
    let standard: Vec<String> = RunConfig::standard()
        .cases()
        .iter()
        .map(|c| c.name())
        .collect();
    for case in [
        "cube40_one_point_pd_elastic",
        "cube40_one_point_pd_damaging",
        "cube40_full_pd_elastic",
        "cube40_full_pd_localised",
        "cube40_one_point_pd_localised",
        "cube100_one_point",
    ] {
        assert!(
            standard.iter().any(|c| c == case),
            "standard run lacks {case}"
        );
    }
    let quick: Vec<String> = RunConfig::quick()
        .cases()
        .iter()
        .map(|c| c.name())
        .collect();
    for case in ["cube8_one_point_pd_damaging", "cube12_one_point"] {
        assert!(quick.iter().any(|c| c == case), "quick run lacks {case}");
    }
}

#[test]
fn quick_run_records_every_key_with_sane_values() {
    let path = scratch_history("keys");
    let mut printed = Vec::new();
    let records = run(&tiny(Some(path.clone())), |r| {
        printed.push(r.to_json_line())
    })
    .expect("quick run");
    assert_eq!(records.len(), 4, "2 integrations x 2 thread counts");
    assert_eq!(printed.len(), records.len());
    // Both thread counts time the same steps of the same motion.
    for pair in records.chunks(2) {
        assert_eq!(pair[0].case, pair[1].case);
        assert_eq!(pair[0].steps, pair[1].steps, "{}", pair[0].case);
    }

    for (r, line) in records.iter().zip(&printed) {
        let v: serde_json::Value = serde_json::from_str(line).expect("each printed line is JSON");
        let obj = v.as_object().expect("a JSON object");
        for key in REQUIRED_KEYS {
            assert!(obj.contains_key(key), "missing key {key} in {line}");
        }
        assert!(r.case.starts_with("cube3_"), "{}", r.case);
        assert_eq!(r.elements, 27);
        assert_eq!(r.nodes, 64);
        assert!(r.integration == "one_point" || r.integration == "full");
        assert!(r.case.ends_with(&r.integration));
        assert!(r.threads == 1 || r.threads == 2);
        assert!((4..=8).contains(&r.steps), "steps {}", r.steps);
        assert!(r.wall_s > 0.0 && r.wall_s.is_finite());
        assert!((r.steps_per_s * r.wall_s - r.steps as f64).abs() < 1e-6 * r.steps as f64);
        let rate = r.steps_per_s * r.elements as f64;
        assert!((r.element_updates_per_s - rate).abs() <= 1e-9 * rate);
        assert!(r.bytes_per_element > 0.0 && r.bytes_per_element < 2048.0);
        assert!(r.dt_s > 0.0);
        assert!(!r.commit.is_empty());
        assert!(r.commit == "unknown" || r.commit.chars().next().unwrap().is_ascii_hexdigit());
        let ts = &r.timestamp;
        assert!(
            ts.len() == 20 && ts.ends_with('Z') && &ts[10..11] == "T",
            "timestamp {ts}"
        );
        assert_eq!(r.mode, "quick");
        assert!(r.cpus >= 1);
    }
    // One-point elements hold less than fully integrated ones.
    let bpe = |i: &str| {
        records
            .iter()
            .find(|r| r.integration == i)
            .unwrap()
            .bytes_per_element
    };
    assert!(bpe("one_point") < bpe("full"));

    // The history file holds exactly these records, one per line; a second run appends.
    // (serde_json parses floats to within an ulp, not always bit-exactly.)
    let back = history::read(&path).expect("history reads back");
    assert_eq!(back.len(), records.len());
    for (b, r) in back.iter().zip(&records) {
        assert_eq!(
            (&b.case, b.threads, b.steps, &b.commit, &b.timestamp),
            (&r.case, r.threads, r.steps, &r.commit, &r.timestamp)
        );
        assert!(
            (b.element_updates_per_s - r.element_updates_per_s).abs()
                <= 1e-12 * r.element_updates_per_s
        );
        // (fractional since one-point geometry is shared: `UniformSet::bytes` per element)
        assert!((b.bytes_per_element - r.bytes_per_element).abs() <= 1e-12 * r.bytes_per_element);
    }
    run(&tiny(Some(path.clone())), |_| {}).expect("second quick run");
    assert_eq!(history::read(&path).unwrap().len(), 8);
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.lines().count(), 8);
    assert!(text.ends_with('\n'));
    std::fs::remove_file(&path).ok();

    // Speed-ups pair each case's 2-thread run with its 1-thread run.
    let s = speedup::speedups(&records);
    assert_eq!(s.len(), 2);
    assert!(s
        .iter()
        .all(|s| s.threads == 2 && s.base_threads == 1 && s.factor() > 0.0));
    // Bytes/element targets are checked for every case; 40³ rate targets are skipped.
    let checks = targets::check(&records);
    assert!(checks
        .iter()
        .any(|c| c.target.contains("bytes/element") && c.met));
    assert!(!checks.iter().any(|c| c.target.contains("cube40")));
}

#[test]
fn filter_and_no_record() {
    let config = RunConfig {
        filter: Some("full".into()),
        threads: vec![1],
        ..tiny(None)
    };
    assert_eq!(config.cases().len(), 1);
    assert_eq!(config.cases()[0].integration, Integration::Full);
    let records = run(&config, |_| {}).expect("filtered run");
    assert_eq!(records.len(), 1);
    assert_eq!(records[0].case, "cube3_full");

    let none = RunConfig {
        filter: Some("no-such-case".into()),
        ..tiny(None)
    };
    assert!(run(&none, |_| {}).is_err());
    let zero_threads = RunConfig {
        threads: vec![0],
        ..tiny(None)
    };
    assert!(run(&zero_threads, |_| {}).is_err());
}

#[test]
fn interface_slab_reports_the_contact_share() {
    let config = RunConfig {
        integrations: Vec::new(),
        interface_sizes: vec![4],
        threads: vec![1],
        ..tiny(None)
    };
    let records = run(&config, |_| {}).expect("interface slab run");
    assert_eq!(records.len(), 1);
    let r = &records[0];
    assert_eq!(r.case, "slab4_interface_one_point");
    assert_eq!(r.elements, 64);
    let share = r.contact_share.expect("contact share recorded");
    assert!(share > 0.0 && share < 1.0, "{share}");
    assert!(targets::check(&records)
        .iter()
        .any(|c| c.target.contains("contact phase")));
}

#[test]
fn static_row_reports_the_three_phases_and_the_sizes() {
    let config = RunConfig {
        integrations: Vec::new(),
        static_sizes: vec![4],
        ..tiny(None)
    };
    let records = run(&config, |_| {}).expect("static run");
    let r = records
        .iter()
        .find(|r| r.case == "static_cholesky_cube4")
        .expect("static row");
    let names: Vec<&str> = records.iter().map(|r| r.case.as_str()).collect();
    assert_eq!(
        names,
        ["static_cholesky_cube4", "static_cg_cube4"],
        "one thread count for each static row"
    );
    let s = r.static_solve.as_ref().expect("static timing");
    // 5³ nodes, the base's 25 fixed: 100 free nodes, 300 equations.
    assert_eq!(s.equations, 300);
    assert!(s.factor_nonzeros >= s.stiffness_nonzeros);
    assert_eq!(s.cg_iterations, None);
    // The conjugate-gradient row: the same equations, no factor, its iterations (at most
    // one per equation in exact arithmetic; the tolerance is reached well before).
    let cg = records[1].static_solve.as_ref().expect("cg timing");
    assert_eq!(cg.equations, 300);
    assert_eq!(cg.factor_nonzeros, 0);
    let iterations = cg.cg_iterations.expect("cg iterations");
    assert!(iterations > 1 && iterations < 300, "{iterations}");
    assert!(s.assembly_s >= 0.0 && s.factorization_s >= 0.0 && s.solve_s >= 0.0);
    assert!(s.assembly_s + s.factorization_s + s.solve_s <= r.wall_s);
    let line = r.to_json_line();
    for key in REQUIRED_KEYS {
        assert!(
            line.contains(&format!("\"{key}\"")),
            "{key} missing in {line}"
        );
    }
}

#[test]
fn boundary_row_follows_the_fixed_base_cube_and_gives_the_overhead() {
    let config = RunConfig {
        integrations: vec![Integration::Full],
        boundaries: true,
        threads: vec![1],
        ..tiny(None)
    };
    let records = run(&config, |_| {}).expect("boundary run");
    let names: Vec<&str> = records.iter().map(|r| r.case.as_str()).collect();
    assert_eq!(names, ["cube3_full", "cube3_full_boundaries"]);
    // The springs of the base shorten the critical step a little, never lengthen it.
    assert!(records[1].dt_s <= records[0].dt_s && records[1].dt_s > 0.5 * records[0].dt_s);
    let o = targets::boundary_overheads(&records);
    assert_eq!(o.len(), 1);
    assert_eq!(o[0].case, "cube3_full_boundaries");
    assert!(o[0].overhead.is_finite() && o[0].overhead > -1.0);
    // The target names the 40³ cube only.
    assert!(!targets::check(&records)
        .iter()
        .any(|c| c.target.contains("boundaries add")));
}
