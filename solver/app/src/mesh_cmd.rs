//! `dcfm mesh yingxiuwan [--variant full|ci] [--measure LIST] [--end T] [--stable-step B] [--out DIR]`:
//! generate the powerhouse mesh (Gmsh MSH 4.1, to inspect and edit in Gmsh) and the whole
//! case file that reads it, and print the element counts, the quality figures, the time
//! step and the time taken. The case is written twice: once to build the model and find
//! its stable step (contact, anchors and boundaries included), then with the step that
//! puts the field outputs exactly every 0.1 s.

use std::path::Path;
use std::time::Instant;

use dcfm::error::{DcfmError, Result};
use dcfm::mesh::generators::cavern::extrude::ELEMENT_SETS;
use dcfm::mesh::generators::cavern::{generate, QualityReport};
use dcfm::mesh::generators::yingxiuwan::{
    benches, case_toml, geometry, CaseSpec, Measures, Timing, Variant, DURATION,
};
use dcfm::mesh::gmsh_write::prepare_gmsh_export;
use dcfm::model::StepBound;

use crate::output::{write_atomic, write_atomic_with};

/// What the command produced.
#[derive(Debug)]
pub struct MeshOutput {
    pub case_file: std::path::PathBuf,
    pub mesh_file: std::path::PathBuf,
    pub quality: QualityReport,
    pub generate_s: f64,
    pub write_s: f64,
    pub regions: Vec<(String, usize)>,
    /// Time step written into the case (s) and the number of steps.
    pub dt: f64,
    pub steps: u64,
}

/// What to generate.
#[derive(Clone, Debug)]
pub struct MeshRequest<'a> {
    pub variant: &'a str,
    /// Comma-separated anti-seismic measures ("none", "all", or names).
    pub measure: &'a str,
    /// End time of the seismic stage (s); default 60.
    pub end: Option<f64>,
    /// How the written case bounds its critical step (`time.stable_step`): "element" or
    /// "shared_mass"; `None`: the variant's default ([`default_step_bound`]).
    pub stable_step: Option<&'a str>,
    pub out: &'a Path,
}

/// The critical-step bound a variant's case is written with when `--stable-step` is not
/// given. Full: the nodal masses shared among the elements (still a bound, 1.092× the
/// elements' own on this mesh: 286,200 steps for 60 s instead of 312,600; docs/yingxiuwan.md).
/// CI: the elements' own bound, so that the CI case's figures, tracked over commits since
/// before the shared bound existed, stay comparable.
pub fn default_step_bound(variant: Variant) -> StepBound {
    match variant {
        Variant::Full => StepBound::SharedMass,
        Variant::Ci => StepBound::Element,
    }
}

/// Generate the Yingxiuwan model of `req.variant` with `req.measure` into `req.out`.
pub fn mesh_yingxiuwan(req: &MeshRequest) -> Result<MeshOutput> {
    let out = req.out;
    let variant = Variant::parse(req.variant).ok_or_else(|| {
        DcfmError::invalid(
            "command line",
            "--variant",
            req.variant,
            "\"full\" or \"ci\"",
        )
    })?;
    let measures = Measures::parse(req.measure).ok_or_else(|| {
        DcfmError::invalid(
            "command line",
            "--measure",
            req.measure,
            format!(
                "\"none\", \"all\" or a comma-separated list of {:?}",
                Measures::NAMES
            ),
        )
    })?;
    let stable_step = match req.stable_step {
        None => default_step_bound(variant),
        Some(name) => StepBound::parse(name).ok_or_else(|| {
            DcfmError::invalid("command line", "--stable-step", name, StepBound::CHOICES)
        })?,
    };
    let end = req.end.unwrap_or(DURATION);
    if !(end.is_finite() && end > 0.0) {
        return Err(DcfmError::invalid(
            "command line",
            "--end",
            end,
            "a positive time (s)",
        ));
    }
    std::fs::create_dir_all(out).map_err(|e| DcfmError::io(out.display().to_string(), e))?;
    let t0 = Instant::now();
    let model = generate(
        &geometry(),
        &variant.density(),
        &benches(),
        &measures.zones(),
    )?;
    let generate_s = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let stem = format!("yingxiuwan_{}{}", variant.name(), measures.suffix());
    let mesh_file = out.join(format!("{stem}.msh"));
    let case_file = out.join(format!("{stem}.toml"));
    let export = prepare_gmsh_export(&model.mesh)?;
    write_atomic_with(&mesh_file, |w| export.write(w))?;
    // The element sets of the survey table for the post-processing (reports/yingxiuwan_post.py).
    let sets: std::collections::BTreeMap<&str, &Vec<u32>> = ELEMENT_SETS
        .iter()
        .chain(&["lining", "inner"])
        .map(|&n| (n, &model.mesh.element_sets[n]))
        .collect();
    let sets_json = serde_json::to_vec(&serde_json::json!({
        "element_sets": sets,
        "regions": model.mesh.region_names,
    }))
    .map_err(|e| DcfmError::invalid("sets", "json", e, "serialisable"))?;
    write_atomic(&out.join(format!("{stem}_sets.json")), &sets_json)?;
    let mut spec = CaseSpec {
        variant,
        measures,
        mesh_file: format!("{stem}.msh"),
        timing: Timing {
            dt: None,
            vtu_every: 0,
            checkpoint_every: 0,
        },
        end,
        stable_step,
    };
    write_atomic(&case_file, case_toml(&spec).as_bytes())?;
    // The model's stable step (safety factor and damping included), then the step that
    // divides the frame interval.
    let stable_dt = dcfm::case::load_case(&case_file)?.dt;
    spec.timing = Timing::from_stable_step(stable_dt);
    write_atomic(&case_file, case_toml(&spec).as_bytes())?;
    let dt = spec.timing.dt.unwrap_or(stable_dt);
    let write_s = t1.elapsed().as_secs_f64();
    let m = &model.mesh;
    let regions = m
        .region_names
        .iter()
        .enumerate()
        .map(|(r, n)| {
            (
                n.clone(),
                m.element_region
                    .iter()
                    .filter(|&&x| x as usize == r)
                    .count(),
            )
        })
        .collect();
    Ok(MeshOutput {
        case_file,
        mesh_file,
        quality: model.quality,
        generate_s,
        write_s,
        regions,
        dt,
        steps: (end / dt).round() as u64,
    })
}

/// The `dcfm mesh` subcommand: generate, print the summary, exit code 0 / 2.
pub fn run_mesh_command(model: &str, req: &MeshRequest) -> std::process::ExitCode {
    use std::io::Write;
    if model != "yingxiuwan" {
        let _ = writeln!(
            std::io::stderr(),
            "error: unknown model '{model}': expected \"yingxiuwan\""
        );
        return std::process::ExitCode::from(2);
    }
    match mesh_yingxiuwan(req) {
        Ok(r) => {
            let q = &r.quality;
            let mut o = std::io::stdout();
            let _ = writeln!(
                o,
                "mesh      {} ({} hex8, {} nodes)",
                r.mesh_file.display(),
                q.elements,
                q.nodes
            );
            for (name, n) in &r.regions {
                let _ = writeln!(o, "region    {name:<8} {n:>8} elements");
            }
            let _ = writeln!(
                o,
                "quality   min scaled Jacobian {:.3} (element {}), max aspect ratio {:.2} (element {}), edges {:.3}–{:.3} m; {} elements below 0.5, {} above aspect 10",
                q.min_scaled_jacobian,
                q.min_scaled_jacobian_element,
                q.max_aspect_ratio,
                q.max_aspect_ratio_element,
                q.min_edge,
                q.max_edge,
                q.below_half_scaled_jacobian,
                q.above_ten_aspect_ratio
            );
            let _ = writeln!(o, "case      {}", r.case_file.display());
            let _ = writeln!(
                o,
                "time      Δt = {:.4e} s, {} steps (fields every 0.1 s)",
                r.dt, r.steps
            );
            let _ = writeln!(
                o,
                "cost      generated in {:.2} s, written and checked in {:.2} s",
                r.generate_s, r.write_s
            );
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            let _ = writeln!(std::io::stderr(), "error: {e}");
            std::process::ExitCode::from(2)
        }
    }
}
