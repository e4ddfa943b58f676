//! The Yingxiuwan underground powerhouse (paper §4, Fig. 6, Table 1) as a preset of the
//! parametric cavern: the dimensions the paper gives, the ones it does not (chosen and
//! justified in docs/yingxiuwan.md), two mesh variants, and the case file that goes with
//! the mesh (mesh, regions, materials, interfaces; the static stage and the seismic input
//! are later sections of that file).

use super::cavern::{CavernGeometry, Density};

/// Mesh variants: `Full` near the paper's 171,432 hex8 / 189,187 nodes, `Ci` ≈ 10⁴
/// elements for runs in continuous integration (same geometry, coarser cells).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variant {
    Full,
    Ci,
}

impl Variant {
    pub fn name(self) -> &'static str {
        match self {
            Variant::Full => "full",
            Variant::Ci => "ci",
        }
    }

    /// Parse "full" or "ci".
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "full" => Some(Variant::Full),
            "ci" => Some(Variant::Ci),
            _ => None,
        }
    }

    /// Cell sizes: the paper's largest element, 7.0 m, is the cap of both.
    pub fn density(self) -> Density {
        match self {
            Variant::Full => Density {
                h_core: 1.17,
                growth: 1.25,
                h_max: 7.0,
            },
            Variant::Ci => Density {
                h_core: 6.0,
                growth: 1.6,
                h_max: 7.0,
            },
        }
    }
}

/// The preset geometry (m). Paper: model 96.0 × 88.2 × 147.7 m, powerhouse 52.8 m long,
/// 17.0 m wide, 37.2 m high (§4.2); three units (§4.1). Everything else: docs/yingxiuwan.md.
pub fn geometry() -> CavernGeometry {
    CavernGeometry {
        model: [96.0, 88.2, 147.7],
        origin: [48.0, 17.7, 55.0],
        width: 17.0,
        length: 52.8,
        height: 37.2,
        arch_rise: 4.0,
        lining: 1.0,
        erection_bay: 10.8,
        units: 3,
        unit_spacing: 14.0,
        turbine_floor_bottom: 9.0,
        turbine_floor: 1.0,
        generator_floor_bottom: 16.0,
        generator_floor: 1.0,
        end_wall: 1.0,
        pedestal: 10.0,
        pit: 6.0,
        column_y: 2.0,
        corbel_bottom: 25.5,
        corbel_height: 2.0,
        corbel_depth: 2.5,
        tunnel_width: 4.0,
        tunnel_height: 5.0,
        tunnel_lining: 1.0,
        tunnel_length: 12.0,
    }
}

/// Lower levels of the excavation benches from the crown down (cavern frame): the top
/// heading to the corbel top, the bench to the generator floor bottom, the turbine layer,
/// the pits and the bottom.
pub fn benches() -> Vec<f64> {
    vec![27.5, 16.0, 9.0, f64::NEG_INFINITY]
}

/// The case file of a variant whose mesh is `mesh_file` (relative to the case file).
pub fn case_toml(variant: Variant, mesh_file: &str) -> String {
    format!(
        r#"# Yingxiuwan underground powerhouse, {variant} variant — written by `dcfm mesh yingxiuwan`.
# Paper: Yang, Chen & Xiao (2014) §4; dimensions and choices: docs/yingxiuwan.md.
title = "Yingxiuwan underground powerhouse ({variant} mesh)"

# ---- Time: a placeholder so that `dcfm check` runs; the seismic stage sets it. ----------
[time]
end = 0.01

[output]
damage_threshold = 0.1          # docs/plastic_damage.md §5
damaged_volume = "point"

# ---- Mesh: regions rock / lining / inner; the interfaces' nodes are already duplicated
# (face sets lining-rock, rock-lining, inner-rock, rock-inner, lining-inner, inner-lining),
# so no `split` here. Outer faces xmin … zmax; excavated rock surface `excavation` and per
# bench `excavation_1` (crown) … `excavation_4` (bottom); survey element sets arch,
# upper_sidewalls, generator_floor, turbine_floor, pedestal_inner_wall,
# crane_beam_corbels, junctions (and pedestals, turbine_layer_columns, turbine_layer_walls,
# mass_concrete, tunnel_lining). -------------------------------------------------------
[mesh]
gmsh = "{mesh_file}"

# ---- Materials: Table 1 of the paper with the plastic-damage mapping of
# docs/plastic_damage.md §4; densities chosen in docs/yingxiuwan.md. ------------------
[materials.rock]
model = "plastic_damage"
young = 10.0e9
poisson = 0.25
density = 2700.0
[materials.rock.plastic_damage]
ft0 = 1.97e6
cohesion = 2.18e6
friction_angle_deg = 41.6

[materials.concrete]
model = "plastic_damage"
young = 25.0e9
poisson = 0.17
density = 2450.0
[materials.concrete.plastic_damage]
ft0 = 1.30e6
cohesion = 2.0e6
friction_angle_deg = 46.0

[[regions]]
name = "rock"
material = "rock"
integration = "one_point"

[[regions]]
name = "lining"
material = "concrete"
integration = "full"

[[regions]]
name = "inner"
material = "concrete"
integration = "full"

# ---- Interfaces (dynamic contact force method, paper §2): concrete on rock and the
# lining on the inner structure; friction and cohesion chosen in docs/yingxiuwan.md. ---
[[interfaces]]
name = "lining_rock"
surface_a = "lining-rock"
surface_b = "rock-lining"
mu_s = 1.0
mu_d = 0.7
cohesion = 0.9e6

[[interfaces]]
name = "inner_rock"
surface_a = "inner-rock"
surface_b = "rock-inner"
mu_s = 1.0
mu_d = 0.7
cohesion = 0.9e6

[[interfaces]]
name = "lining_inner"
surface_a = "lining-inner"
surface_b = "inner-lining"
mu_s = 1.0
mu_d = 0.75
cohesion = 1.0e6

# ---- Static stage (in-situ stress, excavation by benches `excavation_1..4`, lining and
# inner structure activated): to be added by the static stage. ------------------------

# ---- Seismic input, free-field sides, viscous-spring base: to be added. --------------

# ---- Anchor bars (docs/anchors.md), e.g. rock bolts from the excavated surface:
# [[anchors.patterns]]
# face_set = "rock-lining"
# length = 6.0
# spacing = 1.5
# diameter = 0.028
# young = 200e9
# yield_stress = 400e6
"#,
        variant = variant.name(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generators::cavern::generate;
    use crate::mesh::hex8_shape::check_jacobian;

    /// The CI variant: every element valid, all sets present, sizes within the paper's cap,
    /// the paper's outer dimensions, the three interfaces, the survey sets where they belong.
    #[test]
    fn ci_variant_is_valid_and_complete() {
        let geo = geometry();
        let model = generate(&geo, &Variant::Ci.density(), &benches()).unwrap();
        let m = &model.mesh;
        for e in 0..m.n_elements() {
            check_jacobian(&m.element_coords(e)).unwrap();
        }
        let q = &model.quality;
        assert!(q.max_edge <= 7.0 + 1e-9, "{q:?}");
        assert!(q.min_scaled_jacobian > 0.3, "{q:?}");
        for d in 0..3 {
            let lo = m.coords.iter().map(|x| x[d]).fold(f64::INFINITY, f64::min);
            let hi = m.coords.iter().map(|x| x[d]).fold(-f64::INFINITY, f64::max);
            assert!(
                lo.abs() < 1e-9 && (hi - geo.model[d]).abs() < 1e-9,
                "axis {d}: {lo}..{hi}"
            );
        }
        for name in [
            "xmin",
            "xmax",
            "ymin",
            "ymax",
            "zmin",
            "zmax",
            "excavation",
            "excavation_1",
            "excavation_2",
            "excavation_3",
            "excavation_4",
            "lining-rock",
            "rock-lining",
            "inner-rock",
            "rock-inner",
            "lining-inner",
            "inner-lining",
        ] {
            assert!(!m.face_sets[name].is_empty(), "{name}");
        }
        // The survey sets lie where the geometry puts them (cavern frame).
        let centre = |e: u32| {
            let x = m.element_coords(e as usize);
            let mut c = [0.0; 3];
            for p in x {
                for d in 0..3 {
                    c[d] += 0.125 * (p[d] - geo.origin[d]);
                }
            }
            c
        };
        for &e in &m.element_sets["arch"] {
            assert!(
                centre(e)[2] > geo.springline() - geo.lining,
                "arch element {e}"
            );
        }
        for &e in &m.element_sets["generator_floor"] {
            let z = centre(e)[2];
            assert!(z > 16.0 && z < 17.0, "generator floor element {e} at {z}");
        }
        for &e in &m.element_sets["junctions"] {
            assert!(
                centre(e)[0] > geo.half_width() - geo.lining - 1e-9,
                "junction element {e}"
            );
        }
        // The lining and the inner structure touch the rock only through the interfaces.
        let rock = m.nodes_of("rock").unwrap();
        for concrete in ["lining", "inner"] {
            let nodes = m.nodes_of(concrete).unwrap();
            assert!(
                nodes.iter().all(|n| rock.binary_search(n).is_err()),
                "{concrete}"
            );
        }
    }
}
