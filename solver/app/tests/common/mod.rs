//! What the app's integration tests share: the small cases most of them start from, a fresh
//! output folder, running a case text, reading its histories.csv and its base64 VTU
//! fields back.
//!
//! Each test binary includes this module (`mod common;`) and uses a part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use dcfm::case::parse_case;
use dcfm_app::run::{run_case, RunOptions, RunSummary};

/// One block `b` of rock (E 20 GPa, ν 0.25, 2700 kg/m³), 2 × 2 × 2 hex8 with edge `size`
/// (m), fixed at `b.zmin`, run to `end` (written as given, so that tests can replace
/// `end = {end}`); `extra` (loads, output, damping tables) is appended.
pub fn elastic_block(title: &str, end: &str, size: f64, extra: &str) -> String {
    format!(
        r#"title = "{title}"
[time]
end = {end}
[mesh]
[[mesh.blocks]]
name = "b"
origin = [0.0, 0.0, 0.0]
size = [{size:?}, {size:?}, {size:?}]
divisions = [2, 2, 2]
{rock}{extra}"#,
        rock = rock(&["b"], "b.zmin"),
    )
}

/// The rock of these cases (elastic: E 20 GPa, ν 0.25, 2700 kg/m³) as `[materials.rock]`,
/// a region of it for each of `regions`, and the node set `fixed` held in x, y and z.
pub fn rock(regions: &[&str], fixed: &str) -> String {
    let regions: String = regions
        .iter()
        .map(|r| format!("[[regions]]\nname = \"{r}\"\nmaterial = \"rock\"\n"))
        .collect();
    format!(
        r#"[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
{regions}[[boundary.fixed]]
set = "{fixed}"
dofs = "xyz"
"#
    )
}

/// Gravity on the whole model (appended to [`elastic_block`]).
pub const GRAVITY: &str = "[loads.gravity]\nacceleration = [0.0, 0.0, -9.81]\n";

/// A ramped force on the top face of [`elastic_block`]'s block (100 kN/ms in x and −z).
pub const TOP_RAMP: &str = "[[loads.nodal]]\nset = \"b.zmax\"\nforce = [1e5, 0.0, -1e5]\n\
                            history = { type = \"ramp\", rate = 1000.0 }\n";

/// A 1 × 2 × 1 m block pushed by 8 kN along a fixed 4 × 2 × 1 m base under gravity,
/// through a Coulomb interface (μs 0.5, μd 0.4, cohesion 1 kPa): it sticks, then slides.
/// Histories every 2 steps, a checkpoint every 10, run to `end`.
pub fn sliding_block(end: &str) -> String {
    format!(
        r#"title = "block sliding on a base"
[time]
end = {end}
[output]
history_every = 2
checkpoint_every = 10
[mesh]
split = [["base", "block"]]
[[mesh.blocks]]
name = "base"
origin = [0.0, 0.0, 0.0]
size = [4.0, 2.0, 1.0]
divisions = [4, 2, 1]
[[mesh.blocks]]
name = "block"
origin = [1.0, 0.0, 1.0]
size = [1.0, 2.0, 1.0]
divisions = [1, 2, 1]
{rock}[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[[loads.nodal]]
set = "block"
force = [8000.0, 0.0, 0.0]
[[interfaces]]
name = "slip"
surface_a = "block-base"
surface_b = "base-block"
mu_s = 0.5
mu_d = 0.4
cohesion = 1e3
b_may_extend = true
"#,
        rock = rock(&["base", "block"], "base"),
    )
}

/// An empty folder `dcfm-{tag}-{pid}-{name}` in the temporary directory (removed first if
/// an earlier run left it; not created: `dcfm run` creates its output folder).
pub fn fresh_dir(tag: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("dcfm-{tag}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// [`fresh_dir`], created.
pub fn created_dir(tag: &str, name: &str) -> PathBuf {
    let d = fresh_dir(tag, name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Run options writing to `out`, without a progress bar, everything else default.
pub fn options(out: &Path) -> RunOptions {
    RunOptions {
        out: out.to_path_buf(),
        progress: false,
        ..Default::default()
    }
}

/// Parse `text` as the case file `file` (relative paths from the working directory) and
/// run it with `opts`.
pub fn run_text(file: &str, text: &str, opts: &RunOptions) -> dcfm::Result<RunSummary> {
    run_case(parse_case(text, file, Path::new("."))?, opts)
}

/// histories.csv of a run: its header and its rows.
pub struct Histories {
    pub header: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl Histories {
    /// Read `out/histories.csv`.
    pub fn read(out: &Path) -> Histories {
        let csv = std::fs::read_to_string(out.join("histories.csv")).unwrap();
        let mut lines = csv.lines();
        let header = lines
            .next()
            .unwrap()
            .split(',')
            .map(str::to_string)
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
            .collect();
        Histories { header, rows }
    }

    /// Index of the column `name` (panics naming the columns there are).
    pub fn index(&self, name: &str) -> usize {
        self.header
            .iter()
            .position(|c| c == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.header))
    }

    /// The values of the column `name`, row by row.
    pub fn column(&self, name: &str) -> Vec<f64> {
        let k = self.index(name);
        self.rows.iter().map(|r| r[k]).collect()
    }
}

/// Field `name` of a base64 VTU read with vtkio — a point field, or a cell field where
/// `cells` (a name that is both, `active`, is taken from the side asked for).
pub fn vtu_field(path: &Path, name: &str, cells: bool) -> Vec<f64> {
    use vtkio::model::{Attribute, DataSet, Piece};
    let vtk = vtkio::Vtk::import(path).expect("vtkio reads the file");
    let DataSet::UnstructuredGrid { mut pieces, .. } = vtk.data else {
        panic!("not an unstructured grid");
    };
    let Piece::Inline(p) = pieces.remove(0) else {
        panic!("not an inline piece");
    };
    let side = if cells { &p.data.cell } else { &p.data.point };
    side.iter()
        .find_map(|a| match a {
            Attribute::DataArray(d) if d.name == name => {
                Some(d.data.clone().cast_into::<f64>().unwrap())
            }
            _ => None,
        })
        .unwrap_or_else(|| panic!("no field {name} in {}", path.display()))
}
