//! Ground-motion readers: round trips of every format, typed errors naming the file, the
//! line and the value, and no panic on random bytes or truncated files (proptest).

use std::path::{Path, PathBuf};

use proptest::prelude::*;

use dcfm::motion::processing::ProcessingOptions;
use dcfm::motion::{process, read_bytes, read_str, AccelUnits, Axis, Format, ReadOptions};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../verification/fixtures/motions")
}

fn with(format: Format) -> ReadOptions {
    ReadOptions {
        format: Some(format),
        ..ReadOptions::default()
    }
}

/// A known series: values with 5 significant digits so every format prints them exactly.
fn series(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| ((i as f64 * 0.37).sin() * 1234.5).round() / 1000.0)
        .collect()
}

fn assert_same(read: &[f64], expected: &[f64], factor: f64) {
    assert_eq!(read.len(), expected.len());
    for (i, (r, e)) in read.iter().zip(expected).enumerate() {
        assert!(
            (r - e * factor).abs() <= 1e-12 * (1.0 + (e * factor).abs()),
            "sample {i}: {r} vs {}",
            e * factor
        );
    }
}

#[test]
fn text_round_trips_one_two_and_three_columns() {
    let a = series(50);
    let one: String = a.iter().map(|v| format!("{v}\n")).collect();
    let opts = ReadOptions {
        format: None,
        units: Some(AccelUnits::G),
        dt: Some(0.02),
    };
    let r = read_str(&one, "one.txt", &opts).unwrap();
    assert_eq!(
        (r.format, r.dt, r.components.len()),
        (Format::Text, 0.02, 1)
    );
    assert_same(&r.components[0].acceleration, &a, 9.80665);

    let two: String = a
        .iter()
        .enumerate()
        .map(|(i, v)| format!("{:.3} {v}\n", i as f64 * 0.02))
        .collect();
    let opts = ReadOptions {
        format: None,
        units: Some(AccelUnits::Gal),
        dt: None,
    };
    let r = read_str(&two, "two.txt", &opts).unwrap();
    assert!((r.dt - 0.02).abs() < 1e-15);
    assert_same(&r.components[0].acceleration, &a, 0.01);

    let csv: String = std::iter::once("time,EW,NS,UD\n".to_string())
        .chain(
            a.iter()
                .enumerate()
                .map(|(i, v)| format!("{:.3},{v},{},{}\n", i as f64 * 0.02, -v, 2.0 * v)),
        )
        .collect();
    let opts = ReadOptions {
        format: None,
        units: Some(AccelUnits::MetrePerSecond2),
        dt: None,
    };
    let r = read_str(&csv, "three.csv", &opts).unwrap();
    assert_eq!(r.format, Format::Csv);
    let axes: Vec<_> = r.components.iter().map(|c| c.axis).collect();
    assert_eq!(axes, vec![Some(Axis::X), Some(Axis::Y), Some(Axis::Z)]);
    assert_same(
        &r.components[1].acceleration,
        &a.iter().map(|v| -v).collect::<Vec<_>>(),
        1.0,
    );

    // Units and dt stated in comments.
    let commented = format!("# units = gal\n# dt = 0.02\n{one}");
    let r = read_str(&commented, "c.txt", &ReadOptions::default()).unwrap();
    assert_eq!((r.units, r.dt), (AccelUnits::Gal, 0.02));
}

#[test]
fn g_gal_and_si_give_the_same_motion() {
    let a = [0.1, -0.2, 0.05];
    let text = |f: f64| a.iter().map(|v| format!("{}\n", v * f)).collect::<String>();
    let read = |t: String, u| {
        read_str(
            &t,
            "u.txt",
            &ReadOptions {
                format: None,
                units: Some(u),
                dt: Some(0.01),
            },
        )
        .unwrap()
    };
    let g = read(text(1.0), AccelUnits::G);
    let gal = read(text(980.665), AccelUnits::Gal);
    let si = read(text(9.80665), AccelUnits::MetrePerSecond2);
    for k in 0..3 {
        let x = g.components[0].acceleration[k];
        assert!((x - gal.components[0].acceleration[k]).abs() < 1e-12);
        assert!((x - si.components[0].acceleration[k]).abs() < 1e-12);
    }
}

fn at2(values: &[f64], new_header: bool) -> String {
    let mut s = String::from("PEER NGA STRONG MOTION DATABASE RECORD\nTEST 01/01/00, SOMEWHERE, 270\nACCELERATION TIME SERIES IN UNITS OF G\n");
    if new_header {
        s.push_str(&format!("NPTS= {:6}, DT= .0050 SEC\n", values.len()));
    } else {
        s.push_str(&format!("{}    0.0050    NPTS, DT\n", values.len()));
    }
    for chunk in values.chunks(5) {
        s.push_str(
            &chunk
                .iter()
                .map(|v| format!("{v:15.7E}"))
                .collect::<String>(),
        );
        s.push('\n');
    }
    s
}

#[test]
fn at2_round_trips_old_and_new_headers() {
    let a = series(23);
    for new_header in [false, true] {
        let r = read_str(&at2(&a, new_header), "x.AT2", &ReadOptions::default()).unwrap();
        assert_eq!(
            (r.format, r.npts(), r.dt, r.units),
            (Format::PeerAt2, 23, 0.005, AccelUnits::G)
        );
        assert_eq!(
            (r.station.as_str(), r.components[0].name.as_str()),
            ("SOMEWHERE", "270")
        );
        assert_eq!(r.components[0].axis, Some(Axis::X));
        assert_same(&r.components[0].acceleration, &a, 9.80665);
    }
}

#[test]
fn knet_round_trips() {
    let counts: Vec<i64> = (0..20).map(|i| (i * 37 % 11) - 5).collect();
    let mut s = String::from("Origin Time       2000/01/01 00:00:00\nStation Code      TST001\nSampling Freq(Hz) 200Hz\nDuration Time(s)  1\nDir.              4\nScale Factor      3920(gal)/6182761\nMax. Acc. (gal)   0.004\nMemo.\n");
    for chunk in counts.chunks(8) {
        s.push_str(&chunk.iter().map(|c| format!("{c:8}")).collect::<String>());
        s.push('\n');
    }
    let r = read_str(&s, "x.NS2", &ReadOptions::default()).unwrap();
    assert_eq!(
        (r.format, r.npts(), r.dt, r.station.as_str()),
        (Format::Knet, 20, 0.005, "TST001")
    );
    // KiK-net direction 4 is the surface N-S.
    assert_eq!(
        (r.components[0].name.as_str(), r.components[0].axis),
        ("NS2", Some(Axis::Y))
    );
    let expected: Vec<f64> = counts
        .iter()
        .map(|&c| c as f64 * 3920.0 / 6182761.0)
        .collect();
    assert_same(&r.components[0].acceleration, &expected, 0.01);
}

fn smc(values: &[f64]) -> String {
    let mut s = String::from("2 CORRECTED ACCELEROGRAM\n*\nTEST\n 2000 TEST EVENT\nMag\nstation = TEST SITE   component= 090\nepicentral dist = 1 pk acc = 1.0E+0\n*\n*\n*\n*\n");
    let mut ints = [-32768i64; 48];
    ints[15] = 1;
    ints[16] = values.len() as i64;
    for chunk in ints.chunks(8) {
        s.push_str(&chunk.iter().map(|v| format!("{v:10}")).collect::<String>());
        s.push('\n');
    }
    let mut reals = [1.7e38f64; 50];
    reals[1] = 100.0;
    for chunk in reals.chunks(5) {
        s.push_str(
            &chunk
                .iter()
                .map(|v| format!("{v:15.7E}"))
                .collect::<String>(),
        );
        s.push('\n');
    }
    s.push_str("| a comment\n");
    for chunk in values.chunks(8) {
        // Fields of exactly 10 characters that run into each other, as in real SMC files.
        s.push_str(
            &chunk
                .iter()
                .map(|v| format!("{:>10}", format!("{v:.4E}")))
                .collect::<String>(),
        );
        s.push('\n');
    }
    s
}

#[test]
fn smc_round_trips() {
    let a: Vec<f64> = series(19).iter().map(|v| v * -1.0).collect();
    let r = read_str(&smc(&a), "x.smc", &ReadOptions::default()).unwrap();
    assert_eq!(
        (r.format, r.npts(), r.dt, r.units),
        (Format::Smc, 19, 0.01, AccelUnits::Gal)
    );
    assert_eq!(r.components[0].axis, Some(Axis::X));
    assert_same(&r.components[0].acceleration, &a, 0.01);
}

#[test]
fn cosmos_reads_its_fixture_and_two_channels_in_one_file() {
    let one = std::fs::read_to_string(fixtures().join("hand_made.v2")).unwrap();
    let r = read_str(&one, "hand_made.v2", &ReadOptions::default()).unwrap();
    assert_eq!(
        (r.format, r.npts(), r.dt, r.station.as_str()),
        (Format::Cosmos, 400, 0.01, "DCFM01")
    );
    // The same block twice with another orientation (0° → y): one record of two components.
    let second = one.replacen(
        "     -999    -999    -999    -999    -999    -999    -999    -999    -999    -999",
        "",
        0,
    );
    let mut lines: Vec<String> = second.lines().map(str::to_string).collect();
    let int_row = 14 + 5; // integer header row holding #51-#60
    let row: Vec<String> = lines[int_row]
        .as_bytes()
        .chunks(8)
        .map(|c| String::from_utf8_lossy(c).to_string())
        .collect();
    let mut row = row;
    row[3] = format!("{:8}", 0);
    lines[int_row] = row.concat();
    let both = format!("{one}{}\n", lines.join("\n"));
    let r = read_str(&both, "two.v2", &ReadOptions::default()).unwrap();
    let axes: Vec<_> = r.components.iter().map(|c| c.axis).collect();
    assert_eq!(axes, vec![Some(Axis::X), Some(Axis::Y)]);
}

fn error_of(text: &str, label: &str, opts: &ReadOptions) -> String {
    read_str(text, label, opts).unwrap_err().to_string()
}

#[test]
fn errors_name_the_file_the_line_and_the_value() {
    let a = series(10);
    // A header that does not parse.
    let bad = at2(&a, false)
        .replace("4096", "x")
        .replace("10    0.0050", "ten    0.0050");
    let e = error_of(&bad, "bad.AT2", &ReadOptions::default());
    assert!(
        e.starts_with("bad.AT2: line 4 = ") && e.contains("NPTS"),
        "{e}"
    );
    // npts disagreeing with the data (too few and too many).
    let short = at2(&a, false).replace("10    0.0050", "12    0.0050");
    let e = error_of(&short, "short.AT2", &ReadOptions::default());
    assert!(
        e.contains("short.AT2: line") && e.contains("12 acceleration values"),
        "{e}"
    );
    let long = at2(&a, false).replace("10    0.0050", "8    0.0050");
    let e = error_of(&long, "long.AT2", &ReadOptions::default());
    assert!(
        e.contains("long.AT2: line 6") && e.contains("disagrees"),
        "{e}"
    );
    // Non-numeric and non-finite values.
    let opts = ReadOptions {
        format: None,
        units: Some(AccelUnits::G),
        dt: Some(0.01),
    };
    let e = error_of("0.1\n0.2\n0.3x\n", "v.txt", &opts);
    assert_eq!(e, "v.txt: line 3 = \"0.3x\": a finite number");
    let e = error_of("0.1\nNaN\n", "n.txt", &opts);
    assert!(
        e.starts_with("n.txt: line 2 = \"NaN\" (not a finite number)"),
        "{e}"
    );
    let e = error_of("0.1\n1e999\n", "i.txt", &opts);
    assert!(e.starts_with("i.txt: line 2 = \"1e999\""), "{e}");
    // Missing dt, missing units.
    let e = error_of(
        "0.1\n0.2\n",
        "m.txt",
        &ReadOptions {
            format: None,
            units: Some(AccelUnits::G),
            dt: None,
        },
    );
    assert!(e.starts_with("m.txt: dt = none: a sampling step"), "{e}");
    let e = error_of(
        "0.1\n0.2\n",
        "m.txt",
        &ReadOptions {
            format: None,
            units: None,
            dt: Some(0.01),
        },
    );
    assert!(
        e.starts_with("m.txt: units = none: units for this text file"),
        "{e}"
    );
    // Unknown format, with the list of known ones.
    let e = Format::parse("sac").unwrap_err();
    assert!(
        e.contains("\"sac\"")
            && e.contains("at2")
            && e.contains("knet")
            && e.contains("cosmos")
            && e.contains("smc"),
        "{e}"
    );
    // A non-uniform time column.
    let e = error_of(
        "0 1\n0.01 2\n0.03 3\n",
        "t.txt",
        &ReadOptions {
            format: None,
            units: Some(AccelUnits::G),
            dt: None,
        },
    );
    assert!(
        e.starts_with("t.txt: line 3 = 0.03: uniform sampling"),
        "{e}"
    );
}

#[test]
fn band_pass_above_nyquist_is_an_error_naming_the_field() {
    let opts = ReadOptions {
        format: None,
        units: Some(AccelUnits::G),
        dt: Some(0.01),
    };
    let r = read_str("0.1\n0.2\n0.1\n0.0\n", "r.txt", &opts).unwrap();
    let p = ProcessingOptions {
        lowpass: Some(60.0),
        ..ProcessingOptions::default()
    };
    let e = process(&r, "r", &p, "case.toml", "motions.r.processing")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("case.toml: motions.r.processing.lowpass = 60: a corner below the Nyquist frequency 50 Hz"),
        "{e}"
    );
}

#[test]
fn real_fixtures_are_detected_by_content() {
    for (file, format) in [
        ("NIS090.AT2", Format::PeerAt2),
        ("2516b_a.smc", Format::Smc),
        ("test.knet", Format::Knet),
        ("hand_made.v2", Format::Cosmos),
    ] {
        let text = std::fs::read_to_string(fixtures().join(file)).unwrap();
        // A neutral name: the content alone decides (except SMC, which names itself by its
        // first line "2 CORRECTED ACCELEROGRAM").
        assert_eq!(Format::detect("record", &text), format, "{file}");
    }
}

fn fixture_texts() -> Vec<(String, Vec<u8>)> {
    ["NIS090.AT2", "2516b_a.smc", "test.knet", "hand_made.v2"]
        .iter()
        .map(|f| (f.to_string(), std::fs::read(fixtures().join(f)).unwrap()))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Random bytes, read as every format: an error or a record, never a panic.
    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..2000), which in 0usize..6) {
        let format = [Format::Text, Format::Csv, Format::PeerAt2, Format::Knet, Format::Cosmos, Format::Smc][which];
        let _ = read_bytes(&bytes, "random", &with(format));
        let _ = read_bytes(&bytes, "random.txt", &ReadOptions { format: None, units: Some(AccelUnits::G), dt: Some(0.01) });
    }

    /// Every real file cut at a random place, or with a random byte changed: never a panic.
    #[test]
    fn truncated_or_damaged_files_never_panic(which in 0usize..4, cut in 0.0f64..1.0, pos in 0.0f64..1.0, byte in any::<u8>()) {
        let files = fixture_texts();
        let (name, bytes) = &files[which];
        let n = (cut * bytes.len() as f64) as usize;
        let _ = read_bytes(&bytes[..n], name, &ReadOptions::default());
        let mut damaged = bytes.clone();
        let k = ((pos * damaged.len() as f64) as usize).min(damaged.len() - 1);
        damaged[k] = byte;
        let _ = read_bytes(&damaged, name, &ReadOptions::default());
    }

    /// Header lines of every format with random text in them: never a panic.
    #[test]
    fn random_header_lines_never_panic(which in 0usize..4, line in 0usize..40, text in "\\PC{0,90}") {
        let files = fixture_texts();
        let (name, bytes) = &files[which];
        let s = String::from_utf8_lossy(bytes);
        let mut lines: Vec<&str> = s.lines().collect();
        if line < lines.len() {
            lines[line] = &text;
        }
        let _ = read_str(&lines.join("\n"), name, &ReadOptions::default());
    }
}
