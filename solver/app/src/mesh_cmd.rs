//! `dcfm mesh yingxiuwan [--variant full|ci] [--out DIR]`: generate the powerhouse mesh
//! (Gmsh MSH 4.1, to inspect and edit in Gmsh) and the case file that reads it, and print
//! the element counts, the quality figures and the time taken.

use std::path::Path;
use std::time::Instant;

use dcfm::error::{DcfmError, Result};
use dcfm::mesh::generators::cavern::{generate, QualityReport};
use dcfm::mesh::generators::yingxiuwan::{benches, case_toml, geometry, Variant};
use dcfm::mesh::gmsh_write::prepare_gmsh_export;

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
}

/// Generate the Yingxiuwan model of `variant` into `out`.
pub fn mesh_yingxiuwan(variant: &str, out: &Path) -> Result<MeshOutput> {
    let variant = Variant::parse(variant).ok_or_else(|| {
        DcfmError::invalid("command line", "--variant", variant, "\"full\" or \"ci\"")
    })?;
    std::fs::create_dir_all(out).map_err(|e| DcfmError::io(out.display().to_string(), e))?;
    let t0 = Instant::now();
    let model = generate(&geometry(), &variant.density(), &benches())?;
    let generate_s = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let stem = format!("yingxiuwan_{}", variant.name());
    let mesh_file = out.join(format!("{stem}.msh"));
    let case_file = out.join(format!("{stem}.toml"));
    let export = prepare_gmsh_export(&model.mesh)?;
    write_atomic_with(&mesh_file, |w| export.write(w))?;
    write_atomic(
        &case_file,
        case_toml(variant, &format!("{stem}.msh")).as_bytes(),
    )?;
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
    })
}

/// The `dcfm mesh` subcommand: generate, print the summary, exit code 0 / 2.
pub fn run_mesh_command(model: &str, variant: &str, out: &Path) -> std::process::ExitCode {
    use std::io::Write;
    if model != "yingxiuwan" {
        let _ = writeln!(
            std::io::stderr(),
            "error: unknown model '{model}': expected \"yingxiuwan\""
        );
        return std::process::ExitCode::from(2);
    }
    match mesh_yingxiuwan(variant, out) {
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
                "time      generated in {:.2} s, written in {:.2} s",
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
