//! Bad boundary input gets a clear error naming the file, the field and the value — an
//! absorbing boundary or free field on a face set that is not on the outside, a free-field
//! side that is not plane and vertical or not a rectangle, input faces that are not the
//! horizontal base, a buried top without overburden, a seismic section without an input
//! boundary and the reverse, unknown sets and materials, bad spring parameters.

use std::path::Path;

use dcfm::case::parse_case;

/// Two stacked blocks split apart (an interface between them), rock below, concrete above.
const BASE: &str = r#"
[time]
end = 0.01
[mesh]
split = [["lower", "upper"]]
[[mesh.blocks]]
name = "lower"
origin = [0.0, 0.0, 0.0]
size = [4.0, 4.0, 4.0]
divisions = [2, 2, 2]
[[mesh.blocks]]
name = "upper"
origin = [0.0, 0.0, 4.0]
size = [4.0, 4.0, 2.0]
divisions = [2, 2, 1]
[materials.rock]
model = "elastic"
young = 10e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "lower"
material = "rock"
[[regions]]
name = "upper"
material = "rock"
[[interfaces]]
name = "joint"
surface_a = "upper-lower"
surface_b = "lower-upper"
mu_s = 0.6
mu_d = 0.5
cohesion = 1e5
"#;

const SEISMIC: &str = r#"
[seismic]
definition = "incident"
x = { type = "sine", amplitude = 1.0, frequency = 2.0 }
"#;

fn err(extra: &str) -> String {
    let text = format!("{BASE}{extra}");
    match parse_case(&text, "case.toml", Path::new(".")) {
        Ok(_) => panic!("accepted:\n{extra}"),
        Err(e) => e.to_string(),
    }
}

fn has(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "{msg:?} lacks {p:?}");
    }
}

#[test]
fn absorbing_boundary_on_an_interface_or_inner_faces_is_refused() {
    let m = err("[[boundary.absorbing]]\nset = \"lower-upper\"\nkind = \"dashpot\"\n");
    has(
        &m,
        &[
            "case.toml",
            "boundary.absorbing[0].set",
            "lower-upper",
            "outside",
        ],
    );
    let m = err("[[boundary.absorbing]]\nset = \"nowhere\"\nkind = \"dashpot\"\n");
    has(&m, &["boundary.absorbing[0].set", "nowhere", "face set"]);
}

#[test]
fn bad_spring_parameters_are_refused_at_their_field() {
    let m = err(
        "[[boundary.absorbing]]\nset = \"outer.zmin\"\nkind = \"viscous_spring\"\nalpha_n = -1.0\n",
    );
    has(&m, &["boundary.absorbing[0].alpha_n", "-1"]);
    let m = err("[[boundary.absorbing]]\nset = \"outer.zmin\"\nkind = \"viscous_spring\"\ndistance = 10.0\nsource = [0.0, 0.0, 0.0]\n");
    has(&m, &["boundary.absorbing[0].distance", "not both"]);
    let m = err("[[boundary.absorbing]]\nset = \"outer.zmin\"\nkind = \"dashpot\"\nmaterial = \"granite\"\n");
    has(&m, &["boundary.absorbing[0].material", "granite", "rock"]);
}

#[test]
fn input_and_seismic_need_each_other() {
    let m = err("[[boundary.absorbing]]\nset = \"outer.zmin\"\nkind = \"dashpot\"\ninput = true\n");
    has(&m, &["boundary.absorbing[0].input", "[seismic]"]);
    let m = err(SEISMIC);
    has(&m, &["seismic", "input = true"]);
}

#[test]
fn input_faces_must_be_the_horizontal_base() {
    let m = err(&format!(
        "[[boundary.absorbing]]\nset = \"outer.xmin\"\nkind = \"dashpot\"\ninput = true\n{SEISMIC}"
    ));
    has(
        &m,
        &["boundary.absorbing.input", "horizontal faces facing down"],
    );
}

#[test]
fn free_field_sides_must_be_plane_vertical_rectangles_on_the_outside() {
    let base = format!("[[boundary.absorbing]]\nset = \"outer.zmin\"\nkind = \"viscous_spring\"\ninput = true\n{SEISMIC}");
    // The base is not vertical.
    let m = err(&format!(
        "{base}[boundary.free_field]\nsides = [\"outer.zmax\"]\n"
    ));
    has(&m, &["boundary.free_field.sides[0]", "not vertical"]);
    // Two different planes in one side.
    let m = err(&format!(
        "{base}[boundary.free_field]\nsides = [[\"lower.xmin\", \"lower.ymin\"]]\n"
    ));
    has(
        &m,
        &["boundary.free_field.sides[0]", "not one vertical plane"],
    );
    // Only the lower block's face of a side: its top edge is not the model's top.
    let m = err(&format!(
        "{base}[boundary.free_field]\nsides = [\"lower.xmin\"]\n"
    ));
    has(&m, &["boundary.free_field.sides[0]", "rectangle"]);
}

#[test]
fn a_buried_top_needs_the_overburden_and_seismic_input() {
    let m = err("[boundary.free_field]\ntop = \"outer.zmax\"\n");
    has(&m, &["boundary.free_field", "[seismic]"]);
    let m = err(&format!(
        "[[boundary.absorbing]]\nset = \"outer.zmin\"\nkind = \"dashpot\"\ninput = true\n{SEISMIC}[boundary.free_field]\ntop = \"outer.zmax\"\n"
    ));
    has(&m, &["boundary.free_field.top", "overburden"]);
}

#[test]
fn overburden_and_motion_fields_are_checked() {
    let base = "[[boundary.absorbing]]\nset = \"outer.zmin\"\nkind = \"dashpot\"\ninput = true\n";
    let m = err(&format!(
        "{base}{SEISMIC}[[seismic.overburden]]\nthickness = -5.0\nmaterial = \"rock\"\n"
    ));
    has(&m, &["seismic.overburden[0].thickness", "-5"]);
    let m = err(&format!(
        "{base}{SEISMIC}[[seismic.overburden]]\nthickness = 5.0\nmaterial = \"soil\"\n"
    ));
    has(&m, &["seismic.overburden[0].material", "soil"]);
    let m = err(&format!("{base}[seismic]\ndefinition = \"incident\"\n"));
    has(&m, &["seismic", "at least one of x, y, z"]);
    let m = err(&format!(
        "{base}[seismic]\ndefinition = \"incident\"\nquantity = \"displacement\"\nx = {{ type = \"sine\", amplitude = 1.0, frequency = 1.0 }}\n"
    ));
    has(&m, &["seismic.quantity", "displacement"]);
}
