//! Reinforcement mats: bars parallel to a face set, at a cover depth below it, in both
//! directions of every face — the steel bars embedded in concrete of the paper's §3
//! ("the stiffness of the steel bars can be superimposed onto the stiffness of rock or
//! concrete element", its ref. [39]), laid out as a designer places a two-way mat under a
//! surface.
//!
//! Every face of the set is a bilinear quad x(s, t), s, t ∈ [0, 1], with outward normal
//! n = x,s × x,t / |x,s × x,t| (the face's corners counter-clockwise seen from outside).
//! Its bars along s lie at t_k = (k + ½)/n_t, k = 0 … n_t − 1, n_t = max(1, round(L_t /
//! spacing)) with L_t the mean length of the face's two edges along t (and the same with s
//! and t swapped): each runs from the face's edge s = 0 to s = 1, its ends at depth `cover`
//! along the inward normal there, x(s, t_k) − cover · n(s, t_k). The bars of neighbouring
//! faces meet at the shared edge where the surface is flat; on a curved one their ends lie
//! 2 cover sin(θ/2) apart (θ the angle between the faces' normals). With perfect bond each bar's
//! segments act between host points (docs/anchors.md), so a mat of one bar per face and
//! direction is the continuous mat up to those gaps.

use serde::Deserialize;

use crate::element::anchor_bar::SteelSpec;
use crate::mesh::face_geometry::{cross, face_point, norm, sub};
use crate::mesh::{Face, Mesh};

/// `[[anchors.mats]]`: a two-way mat of bars under every face of a face set.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MatSpec {
    /// Name (histories); default `mat<i>`.
    #[serde(default)]
    pub name: Option<String>,
    /// The face set the mat lies under (inside the faces' own elements).
    pub face_set: String,
    /// Depth of the bars' axes below the faces (m), along the inward normal.
    pub cover: f64,
    /// Distance between neighbouring bars of one direction (m).
    pub spacing: f64,
    #[serde(flatten)]
    pub steel: SteelSpec,
}

/// Bilinear point and outward unit normal at (s, t) ∈ [0, 1]² of the quad `q` (corners
/// counter-clockwise seen from outside): the face of [`face_point`] at ξ, η = 2s − 1,
/// 2t − 1, its normal ∂x/∂ξ × ∂x/∂η normalised; `None` where the face is degenerate.
pub(crate) fn point_and_normal(q: &[[f64; 3]; 4], s: f64, t: f64) -> Option<([f64; 3], [f64; 3])> {
    let (p, dxi, deta) = face_point(q, 2.0 * s - 1.0, 2.0 * t - 1.0);
    let n = cross(dxi, deta);
    let len = norm(n);
    (len > 0.0 && len.is_finite()).then(|| (p, n.map(|v| v / len)))
}

fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    norm(sub(*a, *b))
}

/// The bars (start, end) of a mat under `faces`, face by face in set order, first those
/// along s then those along t; `Err` names a degenerate face.
pub fn mat_bars(
    mesh: &Mesh,
    faces: &[Face],
    cover: f64,
    spacing: f64,
) -> Result<Vec<[[f64; 3]; 2]>, String> {
    let mut bars = Vec::new();
    for f in faces {
        let q = mesh.face_nodes(*f).map(|n| mesh.coords[n as usize]);
        // Mean edge lengths along s (edges 0–1, 3–2) and along t (0–3, 1–2).
        let len_s = 0.5 * (distance(&q[0], &q[1]) + distance(&q[3], &q[2]));
        let len_t = 0.5 * (distance(&q[0], &q[3]) + distance(&q[1], &q[2]));
        let under = |s: f64, t: f64| {
            point_and_normal(&q, s, t)
                .map(|(p, n)| std::array::from_fn(|d| p[d] - cover * n[d]))
                .ok_or_else(|| {
                    format!(
                        "face {} of element {} is degenerate (no normal at s = {s}, t = {t})",
                        f.local, f.element
                    )
                })
        };
        let count = |across: f64| ((across / spacing).round() as usize).max(1);
        let (n_t, n_s) = (count(len_t), count(len_s));
        for k in 0..n_t {
            let t = (k as f64 + 0.5) / n_t as f64;
            bars.push([under(0.0, t)?, under(1.0, t)?]);
        }
        for k in 0..n_s {
            let s = (k as f64 + 0.5) / n_s as f64;
            bars.push([under(s, 0.0)?, under(s, 1.0)?]);
        }
    }
    Ok(bars)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::anchor_bar::{AnchorBars, BarNames};
    use crate::element::host_locate::HostLocator;
    use crate::mesh::box_generator::BoxMeshSpec;

    fn steel() -> SteelSpec {
        SteelSpec {
            diameter: 0.02,
            young: 200e9,
            yield_stress: 400e6,
            density: 7850.0,
            pretension: 0.0,
            bond_stiffness: None,
            segment_length: None,
        }
    }

    /// A 4 m × 2 m × 1 m slab of 1 m cubes, the mat under its top at 0.05 m, bars 0.25 m
    /// apart: per 1 m face 4 bars each way, all at z = 0.95 m, inside the slab. Stretched by
    /// u = ε x, the bars along x carry EA ε and those along y nothing, and the forces on the
    /// nodes of the far end x = 4 add up to (number of bar lines along x) × EA ε — 8 lines
    /// across the 2 m width — while all host forces sum to zero.
    #[test]
    fn a_mat_under_a_slab_carries_ea_strain_along_its_bars() {
        let mesh = BoxMeshSpec::single("s", [0.0; 3], [4.0, 2.0, 1.0], [4, 2, 1])
            .build("test")
            .unwrap();
        let faces = &mesh.face_sets["s.zmax"];
        let bars = mat_bars(&mesh, faces, 0.05, 0.25).unwrap();
        assert_eq!(bars.len(), 8 * 8);
        for [a, b] in &bars {
            assert!((a[2] - 0.95).abs() < 1e-12 && (b[2] - 0.95).abs() < 1e-12);
            assert!((distance(a, b) - 1.0).abs() < 1e-12);
            // Along x: ends on the cube edges x = 0 … 4, at y = 0.125, 0.375, …; along y
            // the same with x and y swapped.
            let (along, across) = if (a[1] - b[1]).abs() < 1e-12 {
                (0, 1)
            } else {
                (1, 0)
            };
            let quarter = |v: f64| ((v - 0.125) / 0.25 - ((v - 0.125) / 0.25).round()).abs() < 1e-9;
            for p in [a, b] {
                assert!(
                    (p[along] - p[along].round()).abs() < 1e-12,
                    "bar end at {p:?}"
                );
                assert!(quarter(p[across]), "bar end at {p:?}");
            }
        }
        let locator = HostLocator::new(&mesh, |_| true);
        let mut anchors = AnchorBars::default();
        for (i, bar) in bars.iter().enumerate() {
            let names = BarNames {
                name: format!("m.{i}"),
                group: "m".into(),
            };
            anchors
                .add_bar(&mesh, &locator, names, *bar, &steel())
                .unwrap();
        }
        anchors.finish();
        let eps = 1e-4;
        let u: Vec<[f64; 3]> = mesh.coords.iter().map(|x| [eps * x[0], 0.0, 0.0]).collect();
        let mut f = vec![[0.0; 3]; mesh.coords.len()];
        anchors.add_internal_forces(&mesh, &u, &mut f);
        let ea = 200e9 * 0.25 * std::f64::consts::PI * 0.02 * 0.02;
        let end: f64 = mesh
            .coords
            .iter()
            .zip(&f)
            .filter(|(x, _)| (x[0] - 4.0).abs() < 1e-12)
            .map(|(_, f)| f[0])
            .sum();
        assert!(
            (end - 8.0 * ea * eps).abs() < 1e-9 * ea * eps,
            "{end} N at the far end, expected {}",
            8.0 * ea * eps
        );
        // Beyond yield (ε = 3e-3 > f_y/E = 2e-3): the bars along x carry f_y A with the
        // excess as plastic strain, which the VTU lines report per segment; those across
        // stay at zero.
        let u_far: Vec<[f64; 3]> = mesh
            .coords
            .iter()
            .map(|x| [3e-3 * x[0], 0.0, 0.0])
            .collect();
        anchors.add_internal_forces(&mesh, &u_far, &mut vec![[0.0; 3]; mesh.coords.len()]);
        anchors.commit(0.0, 1e-4, 0.0);
        let lines = anchors.lines();
        assert_eq!(lines.plastic_strain.len(), lines.lines.len());
        for (k, [a, b]) in lines.lines.iter().enumerate() {
            let along_x =
                (lines.points[*a as usize][1] - lines.points[*b as usize][1]).abs() < 1e-12;
            let (ep, n) = (lines.plastic_strain[k], lines.force[k]);
            if along_x {
                assert!(
                    (ep - 1e-3).abs() < 1e-12 && (n - ea * 2e-3).abs() < 1e-6 * ea * 2e-3,
                    "line {k}: εᵖ {ep}, N {n}"
                );
            } else {
                assert!(ep == 0.0 && n.abs() < 1e-6, "line {k}: εᵖ {ep}, N {n}");
            }
        }
        for d in 0..3 {
            let total: f64 = f.iter().map(|v| v[d]).sum();
            assert!(
                total.abs() < 1e-9 * ea * eps,
                "net force {total} N along {d}"
            );
        }
    }

    /// On a curved surface (a quarter cylinder of radius 2 m meshed by 6 faces), the bars
    /// lie at the cover depth below every face, and the hoop bars of neighbouring faces end
    /// 2 cover sin(θ/2) apart at their shared edge (θ = 15°, cover 0.1 m: 0.026 m).
    #[test]
    fn on_a_curved_surface_the_bars_follow_each_face() {
        let mut mesh = BoxMeshSpec::single("c", [0.0; 3], [1.0, 6.0, 1.0], [1, 6, 1])
            .build("test")
            .unwrap();
        // Map (x, y, z) of the box to the annulus: radius 2 − z (outer surface z = 0 at
        // r = 2), angle y · 15°, axis along x.
        for p in mesh.coords.iter_mut() {
            let (r, a) = (2.0 - p[2], p[1] * 15f64.to_radians());
            *p = [p[0], r * a.cos(), r * a.sin()];
        }
        let faces = &mesh.face_sets["c.zmin"];
        let cover = 0.1;
        let bars = mat_bars(&mesh, faces, cover, 0.5).unwrap();
        // Per face: the hoop bars lie across the 1 m along x (2 at 0.5 m), the bars along x
        // across the hoop chord 2·2·sin(7.5°) = 0.522 m (1).
        let chord = 4.0 * 7.5f64.to_radians().sin();
        let (n_hoop, n_axial) = (2, ((chord / 0.5).round() as usize).max(1));
        let per_face = n_hoop + n_axial;
        assert_eq!(bars.len(), 6 * per_face);
        let inward_depth = |p: &[f64; 3], face: usize| {
            // Distance from the face's plane (chord plane at r = 2 cos 7.5°, angle of the
            // face's middle) towards the axis.
            let mid = (face as f64 + 0.5) * 15f64.to_radians();
            2.0 * 7.5f64.to_radians().cos() - (p[1] * mid.cos() + p[2] * mid.sin())
        };
        for (k, [a, b]) in bars.iter().enumerate() {
            let face = k / per_face;
            for p in [a, b] {
                assert!(
                    (inward_depth(p, face) - cover).abs() < 1e-12,
                    "bar {k}: {p:?}"
                );
            }
        }
        let hoop_ends: Vec<[[f64; 3]; 2]> = bars
            .iter()
            .filter(|[a, b]| (a[0] - b[0]).abs() < 1e-12)
            .copied()
            .collect();
        assert_eq!(hoop_ends.len(), 6 * n_hoop);
        let theta = 15f64.to_radians();
        let mut gaps = Vec::new();
        for a in &hoop_ends {
            for b in &hoop_ends {
                let g = distance(&a[1], &b[0]);
                if g < 0.1 && (a[0][0] - b[0][0]).abs() < 1e-12 {
                    gaps.push(g);
                }
            }
        }
        assert_eq!(gaps.len(), 5 * n_hoop, "{gaps:?}");
        for g in gaps {
            assert!((g - 2.0 * cover * (theta / 2.0).sin()).abs() < 1e-9, "{g}");
        }
    }
}
