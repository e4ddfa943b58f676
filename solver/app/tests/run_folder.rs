//! What a run leaves in its output folder when it is rerun or resumed: the peaks of the
//! whole run, exactly the VTU frames its collection lists, no temporary files of killed
//! writes.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

mod common;

use dcfm::case::parse_case;
use dcfm_app::output::PvdCollection;
use dcfm_app::run::{run_case, RunOptions, RunSummary};

/// A block fixed at its base whose top starts at 1 m/s and whose motion dies out under
/// mass-proportional damping: its peaks come early, before the checkpoints a run resumes
/// from.
fn decaying() -> String {
    common::elastic_block(
        "decaying",
        "0.004",
        2.0,
        "[output]\nvtu_every = 5\ncheckpoint_every = 4\n\
         [[initial.velocity]]\nset = \"b.zmax\"\nvalue = [1.0, 0.0, 0.0]\n\
         [damping]\nalpha = 1000.0\n",
    )
}

fn dir(name: &str) -> PathBuf {
    common::fresh_dir("folder", name)
}

fn run(text: &str, out: &Path, resume: bool) -> RunSummary {
    common::run_text(
        "decaying.toml",
        text,
        &RunOptions {
            resume,
            ..common::options(out)
        },
    )
    .unwrap()
}

/// Run to a shorter end, then resume to the full end. The short run ends at 0.0016 s with
/// a shortened 8th step (Δt = 2.19e-4 s): its last checkpoint is the state of step 7 (none
/// is written off the step grid), and its last frame is one that the full run's schedule
/// (every 5 steps) does not have.
fn interrupted(out: &Path) -> RunSummary {
    run(
        &decaying().replace("end = 0.004", "end = 0.0016"),
        out,
        false,
    );
    run(&decaying(), out, true)
}

/// (listed frames, mesh_*.vtu files in the folder).
fn frames(out: &Path) -> (Vec<String>, BTreeSet<String>) {
    let listed = PvdCollection::load(&out.join("case.pvd"))
        .unwrap()
        .entries()
        .iter()
        .map(|e| e.file.clone())
        .collect();
    let files = std::fs::read_dir(out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("mesh_") && n.ends_with(".vtu"))
        .collect();
    (listed, files)
}

#[test]
fn peaks_of_a_resumed_run_are_those_of_the_whole_run() {
    let root = dir("peaks");
    let full = run(&decaying(), &root.join("full"), false);
    let resumed = interrupted(&root.join("part"));
    let restart = resumed.resumed_from_step.expect("resumed") as f64 * resumed.dt;
    // The test means something only when the peaks come before the restart.
    assert!(full.peak_velocity.time < restart && full.peak_displacement.time < restart);
    for (a, b) in [
        (full.peak_velocity, resumed.peak_velocity),
        (full.peak_displacement, resumed.peak_displacement),
    ] {
        assert_eq!(a.value.to_bits(), b.value.to_bits(), "{a:?} against {b:?}");
        assert_eq!((a.node, a.time.to_bits()), (b.node, b.time.to_bits()));
    }
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_resumed_run_lists_exactly_the_frames_of_an_uninterrupted_run() {
    let root = dir("resume-frames");
    run(&decaying(), &root.join("full"), false);
    interrupted(&root.join("part"));
    let (full_listed, full_files) = frames(&root.join("full"));
    let (part_listed, part_files) = frames(&root.join("part"));
    assert!(!full_listed.contains(&"mesh_000008.vtu".to_string()));
    assert_eq!(full_listed, part_listed);
    assert_eq!(full_files, part_files);
    assert_eq!(full_files, full_listed.iter().cloned().collect());
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_rerun_in_a_used_folder_leaves_only_its_own_frames() {
    let root = dir("rerun");
    let out = root.join("out");
    // An earlier, longer run with frames at other steps, and a write killed midway.
    run(
        &decaying()
            .replace("end = 0.004", "end = 0.006")
            .replace("vtu_every = 5", "vtu_every = 3"),
        &out,
        false,
    );
    let killed = out.join(".case.pvd.4000000.7.tmp");
    std::fs::write(&killed, b"half").unwrap();
    run(&decaying(), &out, false);
    let (listed, files) = frames(&out);
    assert_eq!(files, listed.iter().cloned().collect(), "{files:?}");
    assert!(listed.contains(&"mesh_000005.vtu".to_string()));
    assert!(!listed.contains(&"mesh_000003.vtu".to_string()));
    assert!(!killed.exists(), "temporary file of a killed write kept");
    let _ = std::fs::remove_dir_all(&root);
}

/// The block pulled up at its top with a bar that yields at once (f_y A = 314 N) and a
/// bond–slip bar: a resumed run must carry the bars' plastic strains and bar-node motion.
const ANCHORED: &str = r#"
title = "anchored"
[time]
end = 0.002
[output]
vtu_every = 0
checkpoint_every = 4
[mesh]
[[mesh.blocks]]
name = "b"
origin = [0.0, 0.0, 0.0]
size = [2.0, 2.0, 2.0]
divisions = [2, 2, 2]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "b"
material = "rock"
[[boundary.fixed]]
set = "b.zmin"
dofs = "xyz"
[[loads.nodal]]
set = "b.zmax"
force = [2e5, 0.0, 1e6]
history = { type = "ramp", rate = 1000.0 }
[[anchors.bars]]
name = "soft"
start = [0.5, 0.5, 0.1]
end = [0.5, 0.5, 1.9]
diameter = 0.02
yield_stress = 1e6
[[anchors.bars]]
name = "slip"
start = [1.5, 1.5, 0.1]
end = [1.5, 1.5, 1.9]
diameter = 0.02
yield_stress = 1e6
bond_stiffness = 1e7
segment_length = 0.3
"#;

#[test]
fn a_resumed_run_with_yielding_anchors_matches_an_uninterrupted_run() {
    let root = dir("anchors");
    let full = run_anchored(ANCHORED, &root.join("full"), false);
    run_anchored(
        &ANCHORED.replace("end = 0.002", "end = 0.0011"),
        &root.join("part"),
        false,
    );
    let resumed = run_anchored(ANCHORED, &root.join("part"), true);
    assert!(resumed.resumed_from_step.is_some_and(|s| s > 0));
    let a = std::fs::read_to_string(root.join("full/histories.csv")).unwrap();
    let b = std::fs::read_to_string(root.join("part/histories.csv")).unwrap();
    let header: Vec<&str> = a.lines().next().unwrap().split(',').collect();
    let last: Vec<f64> = a
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    for g in ["soft", "slip"] {
        let k = header
            .iter()
            .position(|h| *h == format!("anchor_{g}_yielded_segments"))
            .unwrap_or_else(|| panic!("no anchor columns for {g}: {header:?}"));
        assert!(
            last[k] > 0.0,
            "bar {g} never yields: the test would prove nothing"
        );
    }
    assert_eq!(a, b, "histories differ after a resume with anchors");
    assert_eq!(
        full.energies.internal.to_bits(),
        resumed.energies.internal.to_bits()
    );
    let _ = std::fs::remove_dir_all(&root);
}

/// With `[output.frames]` the whole-mesh frames go to full.pvd; the first of them is written
/// before the run clears its folder of stale frames and was removed as one (full.pvd then
/// listed a missing mesh_000000.vtu, and the Yingxiuwan checks lost the state at which the
/// bolts are installed).
fn compact(text: &str) -> String {
    text.replace("vtu_every = 0", "vtu_every = 2")
        + "[output.frames]\nregions = [\"b\"]\nfull_every = 4\n"
}

/// Run `text` (the anchored block) into `out`.
fn run_anchored(text: &str, out: &Path, resume: bool) -> RunSummary {
    run_case(
        parse_case(text, "anchored.toml", Path::new(".")).unwrap(),
        &RunOptions {
            out: out.to_path_buf(),
            resume,
            progress: false,
            ..Default::default()
        },
    )
    .unwrap()
}

/// (file, time) of every entry of a collection.
fn listed(pvd: &Path) -> Vec<(String, u64)> {
    PvdCollection::load(pvd)
        .unwrap()
        .entries()
        .iter()
        .map(|e| (e.file.clone(), e.time.to_bits()))
        .collect()
}

fn vtu_files(out: &Path) -> BTreeSet<String> {
    std::fs::read_dir(out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".vtu"))
        .collect()
}

#[test]
fn compact_frames_keep_every_whole_mesh_frame_that_full_pvd_lists() {
    let root = dir("compact");
    let out = root.join("out");
    run_anchored(&compact(ANCHORED), &out, false);
    let full: Vec<String> = PvdCollection::load(&out.join("full.pvd"))
        .unwrap()
        .entries()
        .iter()
        .map(|e| e.file.clone())
        .collect();
    assert!(full.contains(&"mesh_000000.vtu".to_string()), "{full:?}");
    assert!(full.len() >= 3, "{full:?}");
    for f in full {
        assert!(
            out.join(&f).exists(),
            "full.pvd lists {f}, not in the folder"
        );
    }
    let anchors = PvdCollection::load(&out.join("anchors.pvd")).unwrap();
    for e in anchors.entries() {
        assert!(out.join(&e.file).exists(), "anchors.pvd lists {}", e.file);
    }
    let _ = std::fs::remove_dir_all(&root);
}

/// A run with compact frames, interrupted and resumed, lists in case.pvd, full.pvd and
/// anchors.pvd the frames of an uninterrupted run and leaves the same files (case.pvd lost
/// every compact frame on resume: its entries were filtered by the name `mesh_NNNNNN.vtu`).
#[test]
fn a_resumed_run_with_compact_frames_lists_the_frames_of_an_uninterrupted_run() {
    let root = dir("compact-resume");
    let text = compact(ANCHORED);
    run_anchored(&text, &root.join("full"), false);
    run_anchored(
        &text.replace("end = 0.002", "end = 0.0011"),
        &root.join("part"),
        false,
    );
    run_anchored(&text, &root.join("part"), true);
    for name in ["case.pvd", "full.pvd", "anchors.pvd"] {
        let (a, b) = (
            listed(&root.join("full").join(name)),
            listed(&root.join("part").join(name)),
        );
        assert!(a.len() >= 3, "{name}: {a:?}");
        assert_eq!(a, b, "{name}");
    }
    assert_eq!(vtu_files(&root.join("full")), vtu_files(&root.join("part")));
    let _ = std::fs::remove_dir_all(&root);
}

/// Steps of the frames a collection lists (`anchors_000006.vtu` → 6) with their times.
fn listed_steps(pvd: &Path) -> Vec<(u64, u64)> {
    PvdCollection::load(pvd)
        .unwrap()
        .entries()
        .iter()
        .map(|e| {
            let digits = e.file.rsplit('_').next().unwrap().trim_end_matches(".vtu");
            (digits.parse().unwrap(), e.time.to_bits())
        })
        .collect()
}

/// `anchors_every = 6` with compact frames every 2 steps: anchors.pvd lists the frames at
/// the multiples of 6, the first and the last step — each at the time of the compact frame
/// of its step (one time series with case.pvd) — and the folder holds exactly those.
#[test]
fn anchors_frames_come_every_anchors_every_steps_and_at_the_first_and_last() {
    let root = dir("anchors-every");
    let out = root.join("out");
    let s = run_anchored(&(compact(ANCHORED) + "anchors_every = 6\n"), &out, false);
    let n = s.steps;
    assert!(
        n > 12 && !n.is_multiple_of(6),
        "{n} steps: the test needs a last step off the 6s"
    );
    let case = listed_steps(&out.join("case.pvd"));
    let anchors = listed_steps(&out.join("anchors.pvd"));
    let expected: Vec<u64> = (0..=n).filter(|&k| k.is_multiple_of(6) || k == n).collect();
    let got: Vec<u64> = anchors.iter().map(|a| a.0).collect();
    assert_eq!(got, expected);
    for a in &anchors {
        assert!(
            case.contains(a),
            "anchors frame {a:?} at no compact frame's time"
        );
    }
    let files: BTreeSet<String> = vtu_files(&out)
        .into_iter()
        .filter(|f| f.starts_with("anchors_"))
        .collect();
    let wanted: BTreeSet<String> = expected
        .iter()
        .map(|k| format!("anchors_{k:06}.vtu"))
        .collect();
    assert_eq!(files, wanted);
    let _ = std::fs::remove_dir_all(&root);
}

/// Interrupted exactly at step 4 (a checkpoint and a compact frame, its last frame with an
/// anchors frame although 4 is not a multiple of `anchors_every` = 6) and resumed:
/// anchors.pvd and the folder are those of the uninterrupted run (the resumed collection
/// drops the interrupted run's last frame, off the schedule).
#[test]
fn a_resumed_run_keeps_anchors_pvd_on_the_anchors_every_schedule() {
    let root = dir("anchors-every-resume");
    let text = compact(ANCHORED) + "anchors_every = 6\n";
    let full = run_anchored(&text, &root.join("full"), false);
    let end4 = 4.0 * full.dt;
    run_anchored(
        &text.replace("end = 0.002", &format!("end = {end4:?}")),
        &root.join("part"),
        false,
    );
    let steps = |out: &Path| -> Vec<u64> {
        listed_steps(&out.join("anchors.pvd"))
            .iter()
            .map(|a| a.0)
            .collect()
    };
    assert_eq!(steps(&root.join("part")), [0, 4]);
    let resumed = run_anchored(&text, &root.join("part"), true);
    assert_eq!(resumed.resumed_from_step, Some(4));
    for name in ["case.pvd", "full.pvd", "anchors.pvd"] {
        assert_eq!(
            listed(&root.join("full").join(name)),
            listed(&root.join("part").join(name)),
            "{name}"
        );
    }
    assert_eq!(vtu_files(&root.join("full")), vtu_files(&root.join("part")));
    let _ = std::fs::remove_dir_all(&root);
}

/// Array `name` of a zlib-compressed raw appended VTU (VTK's `vtkZLibDataCompressor`
/// layout, docs/outputs.md) as Float64 values, decoded as a reader would.
fn zlib_array(file: &[u8], name: &str) -> Vec<f64> {
    use std::io::Read;
    let text = String::from_utf8_lossy(file);
    let tag = text
        .find(&format!("Name=\"{name}\""))
        .unwrap_or_else(|| panic!("no array {name}"));
    let head = &text[text[..tag].rfind('<').unwrap()..];
    assert!(
        head.starts_with("<DataArray type=\"Float64\""),
        "{head:.80}"
    );
    let o = head.find("offset=\"").unwrap() + 8;
    let offset: usize = head[o..o + head[o..].find('"').unwrap()].parse().unwrap();
    let marker = b"encoding=\"raw\">";
    let start = file
        .windows(marker.len())
        .position(|w| w == marker)
        .unwrap();
    let start = start + file[start..].iter().position(|&b| b == b'_').unwrap() + 1;
    let data = &file[start + offset..];
    let word = |i: usize| u64::from_le_bytes(data[8 * i..8 * i + 8].try_into().unwrap()) as usize;
    let blocks = word(0);
    let mut pos = 8 * (3 + blocks);
    let mut bytes = Vec::new();
    for b in 0..blocks {
        let len = word(3 + b);
        flate2::read::ZlibDecoder::new(&data[pos..pos + len])
            .read_to_end(&mut bytes)
            .unwrap();
        pos += len;
    }
    bytes
        .chunks(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

/// The whole-mesh frames of a run with compact frames are zlib-compressed Float64 by
/// default — the values of the base64 frames (`full_encoding = "base64"`) bit for bit, in
/// a smaller file — and an unknown encoding is an error that names the key.
#[test]
fn whole_mesh_frames_are_compressed_float64_unless_base64_is_asked() {
    let root = dir("full-encoding");
    let (zlib, plain) = (root.join("zlib"), root.join("base64"));
    let text = compact(ANCHORED);
    run_anchored(&text, &zlib, false);
    run_anchored(
        &format!("{text}full_encoding = \"base64\"\n"),
        &plain,
        false,
    );
    let files = listed(&zlib.join("full.pvd"));
    assert_eq!(files, listed(&plain.join("full.pvd")));
    assert!(files.len() >= 3, "{files:?}");
    for (f, _) in &files {
        let bytes = std::fs::read(zlib.join(f)).unwrap();
        let head = String::from_utf8_lossy(&bytes[..bytes.len().min(4000)]).into_owned();
        assert!(head.contains("compressor=\"vtkZLibDataCompressor\""), "{f}");
        assert!(
            !head.contains("Float32"),
            "{f}: whole-mesh frames are Float64"
        );
        let plain_file = plain.join(f);
        assert!(
            bytes.len() < std::fs::metadata(&plain_file).unwrap().len() as usize,
            "{f}: the compressed frame is not smaller"
        );
        for (name, cells) in [
            ("displacement", false),
            ("velocity", false),
            ("stress", true),
            ("strain", true),
            ("damage", true),
        ] {
            let a: Vec<u64> = zlib_array(&bytes, name)
                .iter()
                .map(|v| v.to_bits())
                .collect();
            let b: Vec<u64> = common::vtu_field(&plain_file, name, cells)
                .iter()
                .map(|v| v.to_bits())
                .collect();
            assert_eq!(a, b, "{f}: {name}");
        }
    }
    let bad = format!("{text}full_encoding = \"gzip\"\n");
    let e = parse_case(&bad, "anchored.toml", Path::new("."))
        .map(|_| ())
        .expect_err("an unknown encoding is an error")
        .to_string();
    assert!(e.contains("full_encoding") && e.contains("gzip"), "{e}");
    let _ = std::fs::remove_dir_all(&root);
}
