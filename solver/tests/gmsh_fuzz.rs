//! Fuzz target of the Gmsh reader (issue 13): random truncations, byte mutations,
//! insertions and random bodies of valid ASCII and binary MSH 4.1 files never make it
//! panic or allocate without bound; every error names the file.

use std::path::Path;

use proptest::prelude::*;

use dcfm::mesh::gmsh::parse_gmsh;

fn fixture(name: &str) -> Vec<u8> {
    std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/fixtures")
            .join(name),
    )
    .expect("fixture")
}

fn fixtures() -> Vec<Vec<u8>> {
    [
        "cube_2x2x2.msh",
        "cube_2x2x2_binary.msh",
        "gmsh_stack.msh",
        "gmsh_stack_binary.msh",
    ]
    .iter()
    .map(|f| fixture(f))
    .collect()
}

/// Parse and check the error (if any) names the file.
fn parse_named(bytes: &[u8]) -> Result<(), TestCaseError> {
    if let Err(e) = parse_gmsh(bytes, "fuzz.msh") {
        let msg = e.to_string();
        prop_assert!(
            msg.contains("fuzz.msh") || msg.starts_with("element") || msg.starts_with("mesh"),
            "{}",
            msg
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Cut anywhere.
    #[test]
    fn truncated_files_never_panic(which in 0usize..4, cut in 0.0f64..1.0) {
        let f = &fixtures()[which];
        let at = ((f.len() as f64) * cut) as usize;
        parse_named(&f[..at])?;
    }

    /// Overwrite a few bytes with random values (in binary files these hit counts, tags,
    /// coordinates and element types).
    #[test]
    fn mutated_bytes_never_panic(which in 0usize..4,
                                 edits in prop::collection::vec((0.0f64..1.0, any::<u8>()), 1..8)) {
        let mut f = fixtures()[which].clone();
        for (at, b) in edits {
            let i = ((f.len() as f64) * at) as usize % f.len();
            f[i] = b;
        }
        parse_named(&f)?;
    }

    /// Insert or delete a run of bytes somewhere.
    #[test]
    fn inserted_and_deleted_runs_never_panic(which in 0usize..4, at in 0.0f64..1.0,
                                             delete in 0usize..64,
                                             insert in prop::collection::vec(any::<u8>(), 0..32)) {
        let mut f = fixtures()[which].clone();
        let i = ((f.len() as f64) * at) as usize;
        let end = (i + delete).min(f.len());
        f.splice(i..end, insert);
        parse_named(&f)?;
    }

    /// Text edits of the ASCII files: digits replaced by other digits, signs or huge numbers.
    #[test]
    fn edited_numbers_never_panic(which in prop::sample::select(vec![0usize, 2]), at in 0.0f64..1.0,
                                  text in prop::sample::select(vec!["0", "-1", "18446744073709551615",
                                      "99999999999999999999", "1e308", "nan", "2147483648", "5", "15", "3"])) {
        let f = String::from_utf8(fixtures()[which].clone()).unwrap();
        let tokens: Vec<&str> = f.split(' ').collect();
        let i = ((tokens.len() as f64) * at) as usize % tokens.len();
        let mut edited: Vec<String> = tokens.iter().map(|t| t.to_string()).collect();
        let tail: String = edited[i].chars().skip_while(|c| !c.is_whitespace()).collect();
        edited[i] = format!("{text}{tail}");
        parse_named(edited.join(" ").as_bytes())?;
    }

    /// Random bodies after a valid header.
    #[test]
    fn random_bodies_never_panic(binary in any::<bool>(),
                                 body in prop::collection::vec(any::<u8>(), 0..400)) {
        let mut f = if binary {
            b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n$Nodes\n".to_vec()
        } else {
            b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n".to_vec()
        };
        f.extend(body);
        parse_named(&f)?;
    }
}
