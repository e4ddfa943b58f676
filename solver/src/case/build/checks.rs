//! Small validators shared by the section builders: every failure names the file, the
//! field path, the value and what was expected.

use crate::error::{DcfmError, Result};
use crate::mesh::Mesh;

/// `v` must be finite and > 0.
pub(super) fn finite_positive(label: &str, field: &str, v: f64, what: &str) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(DcfmError::invalid(
            label,
            field,
            v,
            format!("must be finite and > 0 ({what})"),
        ))
    }
}

/// Every component of `v` must be finite.
pub(super) fn finite_components(label: &str, field: &str, v: &[f64; 3], unit: &str) -> Result<()> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(DcfmError::invalid(
            label,
            field,
            format!("{v:?}"),
            format!("finite components ({unit})"),
        ))
    }
}

/// DOF letters ("x", "yz", "xyz") as a bit mask x = 1, y = 2, z = 4.
pub(super) fn dof_mask(label: &str, field: &str, dofs: &str) -> Result<u8> {
    let mut mask = 0u8;
    if dofs.is_empty() {
        return Err(DcfmError::invalid(
            label,
            field,
            "\"\"",
            "one or more of x, y, z (e.g. \"xyz\")",
        ));
    }
    for ch in dofs.chars() {
        mask |= match ch {
            'x' => 1,
            'y' => 2,
            'z' => 4,
            _ => {
                return Err(DcfmError::invalid(
                    label,
                    field,
                    format!("\"{dofs}\""),
                    "only the letters x, y, z",
                ))
            }
        };
    }
    Ok(mask)
}

/// The nodes of a node, face or element set or a region; at least one.
pub(super) fn nodes_of(mesh: &Mesh, label: &str, field: &str, set: &str) -> Result<Vec<u32>> {
    match mesh.nodes_of(set) {
        Some(n) if !n.is_empty() => Ok(n),
        Some(_) => Err(DcfmError::invalid(
            label,
            field,
            format!("\"{set}\""),
            "a set with at least one node",
        )),
        None => Err(DcfmError::invalid(
            label,
            field,
            format!("\"{set}\""),
            format!(
                "a node, face or element set or a region{}",
                near_names(set, &mesh.set_names())
            ),
        )),
    }
}

/// "; did you mean 'x'?" for the known name nearest to `name` (edit distance at most a
/// third of its length, at least 1), then the list of known names; for messages about a
/// name that matches nothing.
pub(crate) fn near_names(name: &str, known: &[String]) -> String {
    let near = known
        .iter()
        .map(|k| (edit_distance(&name.to_lowercase(), &k.to_lowercase()), k))
        .filter(|(d, k)| *d <= (k.chars().count() / 3).max(1))
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| format!("; did you mean '{k}'?"))
        .unwrap_or_default();
    format!("{near} (known: {})", known.join(", "))
}

/// Levenshtein distance (insertions, deletions, substitutions) between two short names.
pub(crate) fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for (i, ca) in a.chars().enumerate() {
        cur[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_single_edits() {
        assert_eq!(edit_distance("lining", "lining"), 0);
        assert_eq!(edit_distance("linning", "lining"), 1);
        assert_eq!(edit_distance("rock", "rokc"), 2);
        assert_eq!(edit_distance("", "abc"), 3);
    }

    #[test]
    fn near_names_suggests_the_closest_only_when_close() {
        let known = vec!["rock".to_string(), "lining".to_string()];
        assert!(near_names("linning", &known).contains("did you mean 'lining'"));
        assert!(near_names("Rock", &known).contains("did you mean 'rock'"));
        let far = near_names("concrete", &known);
        assert!(
            !far.contains("did you mean") && far.contains("rock, lining"),
            "{far}"
        );
    }
}
