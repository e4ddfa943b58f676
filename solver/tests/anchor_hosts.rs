//! Which element hosts a bar point (docs/anchors.md, "Host elements"): among the elements
//! holding it, the lowest-numbered one that is active when the bars are installed — at
//! the start of the seismic stage, after the static stage's excavation and placements.
//! An excavated element overlapped by the concrete placed in its volume must not host a
//! bar even when its number is lower (its stiffness would act on the nodes of a removed
//! element); a bar point held by removed elements only is bad input, named.

use std::path::Path;

use dcfm::case::parse_case;

/// A rock box with a gallery excavated by the first static step and a lining placed by
/// the second (gallery element 4, numbered below everything placed later).
const CASE: &str = include_str!("fixtures/gallery_lining.toml");

/// A concrete plug in the gallery's volume, numbered after the gallery (the last block),
/// with its own nodes (split from the gallery's, as the Yingxiuwan concrete overlapping the
/// excavated rock), placed with the lining.
fn with_plug(text: &str) -> String {
    text.replace("[mesh]\n", "[mesh]\nsplit = [[\"gallery\", \"plug\"], [\"plug\", \"rock\"]]\n")
        .replace(
        "[node_sets.all]",
        "[[mesh.blocks]]\nname = \"plug\"\nregion = \"plug\"\norigin = [10.0, 0.0, 10.0]\n\
         size = [10.0, 10.0, 10.0]\ndivisions = [1, 1, 1]\n[node_sets.all]",
    )
    .replace(
        "[loads.gravity]",
        "[[regions]]\nname = \"plug\"\nmaterial = \"rock\"\nintegration = \"full\"\n[loads.gravity]",
    )
    .replace("activate = [\"lining\"]", "activate = [\"lining\", \"plug\"]")
}

fn bar(start: [f64; 3], end: [f64; 3]) -> String {
    format!(
        "[[anchors.bars]]\nname = \"b\"\nstart = {start:?}\nend = {end:?}\ndiameter = 0.02\n\
         yield_stress = 400e6\n"
    )
}

fn region_elements(case: &dcfm::case::Case, name: &str) -> Vec<u32> {
    let mesh = &case.model.mesh;
    let r = mesh.region_index(name).unwrap();
    (0..mesh.n_elements() as u32)
        .filter(|&e| mesh.element_region[e as usize] as usize == r)
        .collect()
}

/// A bar inside the gallery's volume and into the rock above it: the part in the gallery's
/// volume is hosted by the plug (placed), not by the lower-numbered gallery (excavated).
#[test]
fn a_bar_in_placed_concrete_is_hosted_by_it_not_by_the_excavated_element_below_its_number() {
    let text = with_plug(CASE) + &bar([15.0, 5.0, 12.0], [15.0, 5.0, 25.0]);
    let case = parse_case(&text, "case.toml", Path::new(".")).unwrap();
    let (gallery, plug) = (
        region_elements(&case, "gallery"),
        region_elements(&case, "plug"),
    );
    assert_eq!((gallery.len(), plug.len()), (1, 1));
    assert!(
        gallery[0] < plug[0],
        "the test needs the excavated element numbered first"
    );
    let hosts: Vec<u32> = case
        .model
        .anchors
        .as_ref()
        .expect("bars")
        .host_elements()
        .collect();
    assert!(hosts.contains(&plug[0]), "hosts {hosts:?}, plug {plug:?}");
    assert!(
        !hosts.contains(&gallery[0]),
        "hosts {hosts:?}: the excavated gallery hosts a bar"
    );
}

/// Without the plug the gallery's volume is empty at installation: a bar running into it
/// is rejected, naming the bar, the point and why.
#[test]
fn a_bar_point_held_only_by_removed_elements_is_named() {
    let text = CASE.to_string() + &bar([15.0, 5.0, 25.0], [15.0, 5.0, 15.0]);
    let e = match parse_case(&text, "case.toml", Path::new(".")) {
        Ok(_) => panic!("a bar into the excavated gallery was accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        e.contains("case.toml: anchors.bars[0]")
            && e.contains("not active when the bars are installed")
            && e.contains("element 4"),
        "{e}"
    );
    // The point named is on the bar, in the gallery's volume (z 10–20 m).
    let at = e.split(" at [").nth(1).expect("a point in the message");
    let z: f64 = at
        .split(']')
        .next()
        .unwrap()
        .split(", ")
        .nth(2)
        .unwrap()
        .parse()
        .unwrap();
    assert!((10.0..=20.0).contains(&z), "{e}");
}
