//! Tests of the Gmsh reader: fixtures written by hand and by Gmsh, edits that must be
//! refused with the tag named.

use super::*;
use crate::mesh::box_generator::split_between_regions;

fn fixture(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

fn ascii_text() -> String {
    std::fs::read_to_string(fixture("cube_2x2x2.msh")).unwrap()
}

/// Replace the `n`-th line after the line equal to `header` with `f(line)`.
fn edit_after(text: &str, header: &str, n: usize, f: impl Fn(&str) -> String) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let at = lines
        .iter()
        .position(|l| *l == header)
        .expect("header line")
        + n;
    let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    out[at] = f(lines[at]);
    out.join("\n") + "\n"
}

/// The fixture: a 2 m cube of 2×2×2 hex8, "rock" below z = 1, "lining" above (both
/// also in "all"), quads "base" (z = 0, normal −z) and "interface" (z = 1, normal +z),
/// lines "edge" (y = z = 0) and an unnamed point group at the origin.
fn check_cube(m: &Mesh) {
    assert_eq!(m.n_nodes(), 27);
    assert_eq!(m.n_elements(), 8);
    // Nodes were written in grid order, so renumbering gives node i + 3j + 9k.
    for (n, c) in m.coords.iter().enumerate() {
        assert_eq!(*c, [(n % 3) as f64, ((n / 3) % 3) as f64, (n / 9) as f64]);
    }
    assert_eq!(m.elements[0], [0, 1, 4, 3, 9, 10, 13, 12]);
    assert_eq!(
        m.region_names,
        vec!["rock".to_string(), "lining".to_string()]
    );
    assert_eq!(m.element_region, vec![0, 0, 0, 0, 1, 1, 1, 1]);
    assert_eq!(m.element_sets["rock"], vec![0, 1, 2, 3]);
    assert_eq!(m.element_sets["lining"], vec![4, 5, 6, 7]);
    assert_eq!(m.element_sets["all"], (0..8).collect::<Vec<u32>>());
    // Base: the ζ− faces of the four rock elements.
    let base = &m.face_sets["base"];
    assert_eq!(base.len(), 4);
    assert!(
        base.iter().all(|f| f.local == 0 && f.element < 4),
        "{base:?}"
    );
    // Interface: both rock (ζ+) and lining (ζ−) faces match; the quad's +z normal
    // points out of the rock.
    let iface = &m.face_sets["interface"];
    assert_eq!(iface.len(), 4);
    assert!(
        iface.iter().all(|f| f.local == 1 && f.element < 4),
        "{iface:?}"
    );
    for f in base.iter().chain(iface) {
        let z = if f.local == 0 { 0.0 } else { 1.0 };
        assert!(m
            .face_nodes(*f)
            .iter()
            .all(|&n| m.coords[n as usize][2] == z));
    }
    assert_eq!(m.node_sets["base"], (0..9).collect::<Vec<u32>>());
    assert_eq!(m.node_sets["interface"], (9..18).collect::<Vec<u32>>());
    assert_eq!(m.node_sets["edge"], vec![0, 1, 2]);
    assert_eq!(m.node_sets["point_4"], vec![0]);
    assert!(!m.node_sets.contains_key("rock"));
}

#[test]
fn ascii_sparse_tags_counts_regions_and_sets() {
    let m = read_gmsh(&fixture("cube_2x2x2.msh")).unwrap();
    check_cube(&m);
}

#[test]
fn binary_dense_tags_same_mesh() {
    let b = read_gmsh(&fixture("cube_2x2x2_binary.msh")).unwrap();
    check_cube(&b);
    let a = read_gmsh(&fixture("cube_2x2x2.msh")).unwrap();
    assert_eq!(a.coords, b.coords);
    assert_eq!(a.elements, b.elements);
    assert_eq!(a.face_sets, b.face_sets);
    assert_eq!(a.node_sets, b.node_sets);
}

/// `gmsh_stack*.msh` were written by Gmsh 4.15 itself (OpenCASCADE boxes 3×3×2 "rock"
/// under 3×3×1 "lining", fragmented, transfinite with 3 points per curve, recombined;
/// physical surfaces "base" (z = 0) and "interface" (z = 2), an unnamed physical point
/// 31 at the origin), as ASCII and as binary MSH 4.1.
fn check_gmsh_stack(m: &Mesh) {
    assert_eq!(m.n_elements(), 16);
    assert_eq!(m.n_nodes(), 45);
    assert_eq!(
        m.region_names,
        vec!["rock".to_string(), "lining".to_string()]
    );
    let z = |n: u32| m.coords[n as usize][2];
    for (e, conn) in m.elements.iter().enumerate() {
        let zc: f64 = conn.iter().map(|&n| z(n)).sum::<f64>() / 8.0;
        let expect = if zc < 2.0 { 0 } else { 1 };
        assert_eq!(m.element_region[e], expect, "element {e} at z = {zc}");
    }
    assert_eq!(m.element_sets["rock"].len(), 8);
    assert_eq!(m.element_sets["lining"].len(), 8);
    for (name, level) in [("base", 0.0), ("interface", 2.0)] {
        let faces = &m.face_sets[name];
        assert_eq!(faces.len(), 4, "{name}");
        for f in faces {
            assert!(
                m.face_nodes(*f).iter().all(|&n| z(n) == level),
                "{name} {f:?}"
            );
        }
        assert_eq!(m.node_sets[name].len(), 9);
    }
    assert!(m.face_sets["base"]
        .iter()
        .all(|f| m.element_region[f.element as usize] == 0));
    let origin = &m.node_sets["point_31"];
    assert_eq!(origin.len(), 1);
    assert_eq!(m.coords[origin[0] as usize], [0.0; 3]);
}

#[test]
fn files_written_by_gmsh_itself() {
    let a = read_gmsh(&fixture("gmsh_stack.msh")).unwrap();
    check_gmsh_stack(&a);
    let b = read_gmsh(&fixture("gmsh_stack_binary.msh")).unwrap();
    check_gmsh_stack(&b);
    assert_eq!(a.coords, b.coords);
    assert_eq!(a.elements, b.elements);
    assert_eq!(a.face_sets, b.face_sets);
    let mut m = a;
    split_between_regions(&mut m, "rock", "lining").unwrap();
    m.validate().unwrap();
    assert_eq!(m.n_nodes(), 45 + 9);
    assert_eq!(m.face_sets["rock-lining"].len(), 4);
}

#[test]
fn unnamed_and_unassigned_volumes() {
    // Physical volume 2 ("lining") without a name: region and set `volume_2`.
    let text = ascii_text().replace("6\n3 1 \"rock\"\n3 2 \"lining\"\n", "5\n3 1 \"rock\"\n");
    let named = parse_gmsh(text.as_bytes(), "a.msh").unwrap();
    assert_eq!(
        named.region_names,
        vec!["rock".to_string(), "volume_2".to_string()]
    );
    assert_eq!(named.element_sets["volume_2"], vec![4, 5, 6, 7]);
    // Volume entity 2 in no physical group at all: region `unassigned_volume_2`.
    let text = text.replace("2.0 2.0 2.0 2 2 6 1 2", "2.0 2.0 2.0 0 1 2");
    let m = parse_gmsh(text.as_bytes(), "b.msh").unwrap();
    assert_eq!(
        m.region_names,
        vec!["rock".to_string(), "unassigned_volume_2".to_string()]
    );
    assert_eq!(m.element_region, vec![0, 0, 0, 0, 1, 1, 1, 1]);
    assert_eq!(m.element_sets["all"], vec![0, 1, 2, 3]);
    assert!(!m.element_sets.contains_key("volume_2"));
}

#[test]
fn physical_names_with_spaces() {
    let names = msh41::physical_names("2\n3  7   \"upper lining\"\n2 1 base\n").unwrap();
    assert_eq!(names[&(3, 7)], "upper lining");
    assert_eq!(names[&(2, 1)], "base");
    assert!(msh41::physical_names("1\n3 x \"a\"\n").is_err());
}

#[test]
fn split_between_imported_regions() {
    let mut m = read_gmsh(&fixture("cube_2x2x2.msh")).unwrap();
    split_between_regions(&mut m, "rock", "lining").unwrap();
    m.validate().unwrap();
    assert_eq!(m.n_nodes(), 27 + 9);
    assert_eq!(m.face_sets["rock-lining"].len(), 4);
    assert_eq!(m.face_sets["lining-rock"].len(), 4);
    let rock: Vec<u32> = m.nodes_of("rock").unwrap();
    let lining: Vec<u32> = m.nodes_of("lining").unwrap();
    assert!(
        lining.iter().all(|n| !rock.contains(n)),
        "no node shared after the split"
    );
    // The copies sit where the originals are.
    let a = &m.node_sets["rock-lining"];
    let b = &m.node_sets["lining-rock"];
    let za: Vec<f64> = a.iter().map(|&n| m.coords[n as usize][2]).collect();
    let zb: Vec<f64> = b.iter().map(|&n| m.coords[n as usize][2]).collect();
    assert!(za.iter().chain(&zb).all(|&z| z == 1.0));
    // The imported interface face set (rock faces) still names the rock side.
    assert_eq!(m.face_set_nodes(&m.face_sets["interface"]), *a);
}

#[test]
fn missing_file_and_garbage_name_the_file() {
    let msg = read_gmsh(Path::new("/no/such/mesh.msh"))
        .unwrap_err()
        .to_string();
    assert!(msg.contains("/no/such/mesh.msh"), "{msg}");
    let msg = parse_gmsh(b"hello", "junk.msh").unwrap_err().to_string();
    assert!(
        msg.starts_with("junk.msh: ") && msg.contains("$MeshFormat"),
        "{msg}"
    );
    let v2 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    let msg = parse_gmsh(v2.as_bytes(), "old.msh")
        .unwrap_err()
        .to_string();
    assert!(msg.contains("old.msh") && msg.contains("4.1"), "{msg}");
}

#[test]
fn truncated_file_names_file_and_line() {
    let text = ascii_text();
    let cut = &text[..text.find("$Elements").unwrap() + 40];
    let msg = parse_gmsh(cut.as_bytes(), "cut.msh")
        .unwrap_err()
        .to_string();
    assert!(
        msg.starts_with("cut.msh: ") && msg.contains("line"),
        "{msg}"
    );
    assert!(msg.len() < 600, "no hex dump: {msg}");
    let bin = std::fs::read(fixture("cube_2x2x2_binary.msh")).unwrap();
    let msg = parse_gmsh(&bin[..bin.len() - 100], "cut_bin.msh")
        .unwrap_err()
        .to_string();
    assert!(msg.starts_with("cut_bin.msh: "), "{msg}");
}

#[test]
fn inverted_element_is_named_by_its_gmsh_tag() {
    // First rock hex: swap its bottom and top node quadruples.
    let text = edit_after(&ascii_text(), "3 1 5 4", 1, |l| {
        let t: Vec<&str> = l.split_whitespace().collect();
        format!("{} {} {}", t[0], t[5..9].join(" "), t[1..5].join(" "))
    });
    let tag = text.lines().skip_while(|l| *l != "3 1 5 4").nth(1).unwrap();
    let tag = tag.split_whitespace().next().unwrap();
    let msg = parse_gmsh(text.as_bytes(), "inv.msh")
        .unwrap_err()
        .to_string();
    assert!(msg.starts_with("inv.msh: "), "{msg}");
    assert!(
        msg.contains(&format!("element {tag}")) && msg.contains("inverted"),
        "{msg}"
    );
}

#[test]
fn other_element_types_are_named() {
    // Turn the lining block into 4-node tetrahedra.
    let mut text = ascii_text().replace("\n3 2 5 4\n", "\n3 2 4 4\n");
    for i in 1..=4 {
        text = edit_after(&text, "3 2 4 4", i, |l| {
            l.split_whitespace().take(5).collect::<Vec<_>>().join(" ")
        });
    }
    let tag = text.lines().skip_while(|l| *l != "3 2 4 4").nth(1).unwrap();
    let tag = tag.split_whitespace().next().unwrap();
    let msg = parse_gmsh(text.as_bytes(), "tet.msh")
        .unwrap_err()
        .to_string();
    assert!(msg.starts_with("tet.msh: "), "{msg}");
    assert!(
        msg.contains("Tet4") && msg.contains(&format!("element {tag}")),
        "{msg}"
    );
}

#[test]
fn unknown_node_and_stray_quad_are_errors() {
    let text = edit_after(&ascii_text(), "3 2 5 4", 1, |l| {
        let mut t: Vec<String> = l.split_whitespace().map(String::from).collect();
        t[3] = "999999".into();
        t.join(" ")
    });
    let msg = parse_gmsh(text.as_bytes(), "n.msh")
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("n.msh") && msg.contains("node tag 999999"),
        "{msg}"
    );
    // A base quad whose nodes are not one hex face (two of them swapped with the top).
    let text = edit_after(&ascii_text(), "2 1 3 4", 1, |l| {
        let t: Vec<&str> = l.split_whitespace().collect();
        let hex = ascii_text();
        let top = hex
            .lines()
            .skip_while(|l| *l != "3 2 5 4")
            .nth(1)
            .unwrap()
            .to_string();
        let top: Vec<&str> = top.split_whitespace().collect();
        format!("{} {} {} {} {}", t[0], t[1], t[2], top[7], top[8])
    });
    let msg = parse_gmsh(text.as_bytes(), "q.msh")
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("q.msh") && msg.contains("'base'") && msg.contains("face"),
        "{msg}"
    );
}

#[test]
fn no_hex8_is_an_error() {
    let text = ascii_text()
        .replace("\n3 1 5 4\n", "\n3 1 4 0\n")
        .replace("\n3 2 5 4\n", "\n3 2 4 0\n");
    // Drop the eight hex lines that now follow empty blocks: simplest is to rebuild.
    let lines: Vec<&str> = text.lines().collect();
    let at = lines.iter().position(|l| *l == "3 1 4 0").unwrap();
    let mut kept: Vec<&str> = lines[..=at].to_vec();
    kept.push("3 2 4 0");
    kept.extend(&lines[at + 10..]);
    let text = kept.join("\n") + "\n";
    let text = text.replacen("6 19 1000 1054", "6 11 1000 1030", 1);
    let msg = parse_gmsh(text.as_bytes(), "empty.msh")
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("empty.msh: $Elements = no hex8 element"),
        "{msg}"
    );
}

/// A 2×1×1 block of unit hex8 written by hand: `blocks` lists the node blocks as (tag,
/// grid index i + 3j + 6k) pairs, `hex_tags` the two element tags; `coord` may replace the
/// coordinates of one grid node.
fn two_hex_msh(
    blocks: &[Vec<(u64, usize)>],
    hex_tags: [u64; 2],
    coord: Option<(usize, &str)>,
) -> String {
    let grid = |g: usize| [(g % 3) as f64, ((g / 3) % 2) as f64, (g / 6) as f64];
    let tag_of = |g: usize| {
        blocks
            .iter()
            .flatten()
            .find(|(_, gg)| *gg == g)
            .map(|(t, _)| *t)
            .expect("every grid node listed")
    };
    let n: usize = blocks.iter().map(Vec::len).sum();
    let all: Vec<u64> = blocks.iter().flatten().map(|(t, _)| *t).collect();
    let mut s = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    s += "$PhysicalNames\n1\n3 1 \"rock\"\n$EndPhysicalNames\n";
    s += "$Entities\n0 0 0 1\n1 0 0 0 2 1 1 1 1 0\n$EndEntities\n";
    s += &format!(
        "$Nodes\n{} {n} {} {}\n",
        blocks.len(),
        all.iter().min().unwrap(),
        all.iter().max().unwrap()
    );
    for b in blocks {
        s += &format!("3 1 0 {}\n", b.len());
        for (t, _) in b {
            s += &format!("{t}\n");
        }
        for (_, g) in b {
            match coord {
                Some((cg, text)) if cg == *g => s += &format!("{text}\n"),
                _ => {
                    let x = grid(*g);
                    s += &format!("{} {} {}\n", x[0], x[1], x[2]);
                }
            }
        }
    }
    s += "$EndNodes\n";
    s += &format!(
        "$Elements\n1 2 {} {}\n3 1 5 2\n",
        hex_tags.iter().min().unwrap(),
        hex_tags.iter().max().unwrap()
    );
    for (e, tag) in hex_tags.iter().enumerate() {
        let g = |i: usize, j: usize, k: usize| tag_of(e + i + 3 * j + 6 * k);
        s += &format!(
            "{tag} {} {} {} {} {} {} {} {}\n",
            g(0, 0, 0),
            g(1, 0, 0),
            g(1, 1, 0),
            g(0, 1, 0),
            g(0, 0, 1),
            g(1, 0, 1),
            g(1, 1, 1),
            g(0, 1, 1)
        );
    }
    s += "$EndElements\n";
    s
}

/// Element corner coordinates, the geometry the file means whatever the numbering.
fn element_geometry(m: &Mesh) -> Vec<[[f64; 3]; 8]> {
    (0..m.n_elements()).map(|e| m.element_coords(e)).collect()
}

fn reference_geometry() -> Vec<[[f64; 3]; 8]> {
    let one: Vec<(u64, usize)> = (0..12).map(|g| (g as u64 + 1, g)).collect();
    let m = parse_gmsh(two_hex_msh(&[one], [1, 2], None).as_bytes(), "ref.msh").unwrap();
    let geo = element_geometry(&m);
    assert_eq!(geo[1][0], [1.0, 0.0, 0.0]);
    geo
}

#[test]
fn node_blocks_in_reverse_order_keep_their_tags() {
    // Dense tags 1..12, but the block holding 7..12 comes first: numbering nodes in file
    // order (what a reader that drops dense tags does) would swap the two layers.
    let upper: Vec<(u64, usize)> = (6..12).map(|g| (g as u64 + 1, g)).collect();
    let lower: Vec<(u64, usize)> = (0..6).map(|g| (g as u64 + 1, g)).collect();
    let text = two_hex_msh(&[upper, lower], [1, 2], None);
    let m = parse_gmsh(text.as_bytes(), "reversed.msh").unwrap();
    assert_eq!(element_geometry(&m), reference_geometry());
    // Nodes are numbered in file order: the first node read is grid node 6, at z = 1.
    assert_eq!(m.coords[0], [0.0, 0.0, 1.0]);
}

#[test]
fn interleaved_and_shuffled_tags_keep_the_geometry() {
    // Odd tags in one block, even tags in the other, each listed in decreasing order.
    let tag = |g: usize| (12 - g) as u64 * 7 + 3;
    let a: Vec<(u64, usize)> = (0..12)
        .rev()
        .filter(|g| g % 2 == 0)
        .map(|g| (tag(g), g))
        .collect();
    let b: Vec<(u64, usize)> = (0..12)
        .rev()
        .filter(|g| g % 2 == 1)
        .map(|g| (tag(g), g))
        .collect();
    let text = two_hex_msh(&[b, a], [40, 9], None);
    let m = parse_gmsh(text.as_bytes(), "interleaved.msh").unwrap();
    assert_eq!(element_geometry(&m), reference_geometry());
}

#[test]
fn duplicate_node_tag_is_refused_with_the_tag() {
    let mut nodes: Vec<(u64, usize)> = (0..12).map(|g| (g as u64 + 1, g)).collect();
    let mut upper = nodes.split_off(6);
    upper[2].0 = 4; // tag 4 again (grid node 8)
    let text = two_hex_msh(&[nodes, upper], [1, 2], None);
    let msg = parse_gmsh(text.as_bytes(), "dup.msh")
        .unwrap_err()
        .to_string();
    assert!(
        msg.starts_with("dup.msh: ") && msg.contains("node tag 4 given twice"),
        "{msg}"
    );
}

#[test]
fn duplicate_element_tag_is_refused_with_the_tag() {
    let one: Vec<(u64, usize)> = (0..12).map(|g| (g as u64 + 1, g)).collect();
    let text = two_hex_msh(&[one], [5, 5], None);
    let msg = parse_gmsh(text.as_bytes(), "dupel.msh")
        .unwrap_err()
        .to_string();
    assert!(
        msg.starts_with("dupel.msh: ") && msg.contains("element tag 5 given twice"),
        "{msg}"
    );
}

#[test]
fn non_finite_coordinates_are_refused_with_the_tag() {
    let one: Vec<(u64, usize)> = (0..12).map(|g| (g as u64 + 101, g)).collect();
    for bad in ["nan 0 0", "1 inf 0", "1 0 -Infinity", "1 0 NaN"] {
        let text = two_hex_msh(std::slice::from_ref(&one), [1, 2], Some((4, bad)));
        let msg = parse_gmsh(text.as_bytes(), "nan.msh")
            .unwrap_err()
            .to_string();
        assert!(
            msg.starts_with("nan.msh: $Nodes: node 105 = ") && msg.contains("finite"),
            "{bad}: {msg}"
        );
    }
}

#[test]
fn node_tag_zero_and_wrong_counts_are_refused() {
    let mut one: Vec<(u64, usize)> = (0..12).map(|g| (g as u64 + 1, g)).collect();
    one[3].0 = 0;
    let text = two_hex_msh(&[one], [1, 2], None).replace("$Nodes\n1 12 0 12", "$Nodes\n1 12 1 12");
    let msg = parse_gmsh(text.as_bytes(), "zero.msh")
        .unwrap_err()
        .to_string();
    assert!(msg.contains("node tag 0"), "{msg}");
    let one: Vec<(u64, usize)> = (0..12).map(|g| (g as u64 + 1, g)).collect();
    let text = two_hex_msh(&[one], [1, 2], None).replace("$Nodes\n1 12 ", "$Nodes\n1 13 ");
    let msg = parse_gmsh(text.as_bytes(), "count.msh")
        .unwrap_err()
        .to_string();
    assert!(msg.contains("header says 13 nodes"), "{msg}");
    let one: Vec<(u64, usize)> = (0..12).map(|g| (g as u64 + 1, g)).collect();
    let text = two_hex_msh(&[one], [1, 2], None).replace("3 1 0 12", "3 1 0 99999999999");
    let msg = parse_gmsh(text.as_bytes(), "huge.msh")
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("more than the rest of the file can hold"),
        "{msg}"
    );
}
