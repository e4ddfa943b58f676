//! A plate (slab) with a circular hole, meshed as an O-grid and extruded through its
//! thickness: the hole is meshed too (its own region, to be excavated by the static stage),
//! the plate around it with radial lines from the hole to the square outer boundary.
//!
//! ```text
//!   ┌──────────────┐   in-plane axes (s1, s2), thickness along s3 = `axis`:
//!   │ \    |     / │     axis z: (s1, s2, s3) = (x, y, z)
//!   │  \ __|__  /  │     axis x: (y, z, x);  axis y: (z, x, y)  (right-handed)
//!   │   /┌───┐\   │   core: m × m square of half-width 0.4a (hole region)
//!   │──|─│   │─|──│   transition: core boundary → circle r = a (hole region)
//!   │   \└───┘/   │   plate: circle → square of half-width b along the rays of the
//!   │  /  ‾‾‾  \  │          circle nodes (radial grading), 4m elements round the hole
//!   └──────────────┘
//! ```
//!
//! The circle nodes are equally spaced in angle (θ_j = −π/4 + jπ/(2m)); the outer node of
//! ray j lies on the square at the same angle. Sets: regions `hole_region` and
//! `plate_region` (element sets of the same names); face sets (and node sets) of the plate
//! `P.s1min`, `P.s1max`, `P.s2min`, `P.s2max` named by the axis letters (e.g. `plate.xmin`),
//! the thickness faces `P.s3min`, `P.s3max`, and `P.wall`, the plate's faces on the hole.

use serde::Deserialize;

use crate::error::{DcfmError, Result};
use crate::mesh::{Face, Mesh};

/// `[mesh.plate_with_hole]`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PlateWithHoleSpec {
    /// Hole radius a (m).
    pub radius: f64,
    /// Half-width b of the square plate (m), > a.
    pub half_width: f64,
    /// Thickness along `axis` (m).
    pub thickness: f64,
    /// Axis of the hole: "x", "y" or "z" (default "z").
    #[serde(default = "default_axis")]
    pub axis: String,
    /// Centre of the hole on the plate's lower thickness face (m).
    #[serde(default)]
    pub centre: [f64; 3],
    /// Elements round the hole (a multiple of 4, ≥ 8).
    #[serde(default = "default_around")]
    pub divisions_around: usize,
    /// Elements from the hole to the outer boundary.
    pub divisions_radial: usize,
    /// Ratio of the last to the first radial element length (1 = uniform).
    #[serde(default = "one")]
    pub grading: f64,
    /// Elements through the thickness.
    #[serde(default = "one_usize")]
    pub divisions_thickness: usize,
    /// Region of the elements inside the hole.
    #[serde(default = "default_hole")]
    pub hole_region: String,
    /// Region of the plate.
    #[serde(default = "default_plate")]
    pub plate_region: String,
}

fn default_axis() -> String {
    "z".into()
}
fn default_around() -> usize {
    64
}
fn one() -> f64 {
    1.0
}
fn one_usize() -> usize {
    1
}
fn default_hole() -> String {
    "hole".into()
}
fn default_plate() -> String {
    "plate".into()
}

/// Core half-width as a fraction of the radius.
const CORE: f64 = 0.4;

impl PlateWithHoleSpec {
    /// The defaults with the given radius, half-width, thickness and radial divisions.
    pub fn new(radius: f64, half_width: f64, thickness: f64, divisions_radial: usize) -> Self {
        Self {
            radius,
            half_width,
            thickness,
            axis: default_axis(),
            centre: [0.0; 3],
            divisions_around: default_around(),
            divisions_radial,
            grading: 1.0,
            divisions_thickness: 1,
            hole_region: default_hole(),
            plate_region: default_plate(),
        }
    }

    fn validate(&self, file: &str) -> Result<usize> {
        let f = |name: &str| format!("mesh.plate_with_hole.{name}");
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(DcfmError::invalid(
                    file,
                    f(name),
                    v,
                    "must be finite and > 0",
                ))
            }
        };
        positive("radius", self.radius)?;
        positive("thickness", self.thickness)?;
        positive("grading", self.grading)?;
        if !(self.half_width.is_finite() && self.half_width > self.radius) {
            return Err(DcfmError::invalid(
                file,
                f("half_width"),
                self.half_width,
                format!("must be finite and > radius = {}", self.radius),
            ));
        }
        if self.divisions_around < 8
            || self.divisions_around & 3 != 0
            || self.divisions_around > 4096
        {
            return Err(DcfmError::invalid(
                file,
                f("divisions_around"),
                self.divisions_around,
                "a multiple of 4 between 8 and 4096",
            ));
        }
        for (name, v) in [
            ("divisions_radial", self.divisions_radial),
            ("divisions_thickness", self.divisions_thickness),
        ] {
            if v == 0 || v > 10_000 {
                return Err(DcfmError::invalid(file, f(name), v, "between 1 and 10000"));
            }
        }
        if !self.centre.iter().all(|c| c.is_finite()) {
            return Err(DcfmError::invalid(
                file,
                f("centre"),
                format!("{:?}", self.centre),
                "finite coordinates",
            ));
        }
        if self.hole_region == self.plate_region {
            return Err(DcfmError::invalid(
                file,
                f("hole_region"),
                &self.hole_region,
                "must differ from plate_region",
            ));
        }
        match self.axis.as_str() {
            "x" => Ok(0),
            "y" => Ok(1),
            "z" => Ok(2),
            other => Err(DcfmError::invalid(
                file,
                f("axis"),
                format!("\"{other}\""),
                "one of \"x\", \"y\", \"z\"",
            )),
        }
    }

    /// Build the mesh; `file` names the case in errors.
    pub fn build(&self, file: &str) -> Result<Mesh> {
        let axis = self.validate(file)?;
        // Global axis of each local axis (s1, s2, s3), right-handed.
        let map: [usize; 3] = [(axis + 1) % 3, (axis + 2) % 3, axis];
        let letters = ["x", "y", "z"];
        let m = self.divisions_around / 4;
        let n_loop = 4 * m;
        let (a, b) = (self.radius, self.half_width);
        let c = CORE * a;
        let n_in = (m / 2).max(1);
        let n_out = self.divisions_radial;
        let nt = self.divisions_thickness;
        // 2D nodes: core grid, then the loops of levels 1..=n_in + n_out (level 0 is the
        // core boundary).
        let mut xy: Vec<[f64; 2]> = Vec::new();
        let core = |i1: usize, i2: usize| (i1 + (m + 1) * i2) as u32;
        for i2 in 0..=m {
            for i1 in 0..=m {
                xy.push([
                    -c + 2.0 * c * i1 as f64 / m as f64,
                    -c + 2.0 * c * i2 as f64 / m as f64,
                ]);
            }
        }
        let core_loop = |j: usize| -> u32 {
            let (s, t) = (j / m, j % m);
            match s {
                0 => core(m, t),
                1 => core(m - t, m),
                2 => core(0, m - t),
                _ => core(t, 0),
            }
        };
        // Point of loop j on a square of half-width h, and on the circle.
        let on_square = |j: usize, h: f64| -> [f64; 2] {
            let (s, t) = (j / m, (j % m) as f64 / m as f64);
            let tau = -1.0 + 2.0 * t;
            match s {
                0 => [h, h * tau],
                1 => [-h * tau, h],
                2 => [-h, -h * tau],
                _ => [h * tau, -h],
            }
        };
        let theta = |j: usize| {
            -std::f64::consts::FRAC_PI_4 + j as f64 * std::f64::consts::FRAC_PI_2 / m as f64
        };
        let on_circle = |j: usize| -> [f64; 2] { [a * theta(j).cos(), a * theta(j).sin()] };
        // Outer square point on the ray of angle θ_j.
        let on_outer = |j: usize| -> [f64; 2] {
            let (s, t) = (j / m, (j % m) as f64 / m as f64);
            let tau = ((-1.0 + 2.0 * t) * std::f64::consts::FRAC_PI_4).tan();
            match s {
                0 => [b, b * tau],
                1 => [-b * tau, b],
                2 => [-b, -b * tau],
                _ => [b * tau, -b],
            }
        };
        // Radial fractions of the plate's levels (geometric grading).
        let mut mu = vec![0.0; n_out + 1];
        if (self.grading - 1.0).abs() < 1e-12 || n_out == 1 {
            for (k, v) in mu.iter_mut().enumerate() {
                *v = k as f64 / n_out as f64;
            }
        } else {
            let r = self.grading.powf(1.0 / (n_out as f64 - 1.0));
            let first = (r - 1.0) / (r.powi(n_out as i32) - 1.0);
            let mut h = first;
            for k in 1..=n_out {
                mu[k] = mu[k - 1] + h;
                h *= r;
            }
            mu[n_out] = 1.0;
        }
        let levels = n_in + n_out;
        let mut loops: Vec<Vec<u32>> = vec![(0..n_loop).map(core_loop).collect()];
        for k in 1..=levels {
            let mut ids = Vec::with_capacity(n_loop);
            for j in 0..n_loop {
                let p = if k <= n_in {
                    let l = k as f64 / n_in as f64;
                    let (s, q) = (on_square(j, c), on_circle(j));
                    [(1.0 - l) * s[0] + l * q[0], (1.0 - l) * s[1] + l * q[1]]
                } else {
                    let w = mu[k - n_in];
                    let (q, o) = (on_circle(j), on_outer(j));
                    [q[0] + w * (o[0] - q[0]), q[1] + w * (o[1] - q[1])]
                };
                ids.push(xy.len() as u32);
                xy.push(p);
            }
            loops.push(ids);
        }
        // 2D quads (counter-clockwise in s1, s2) with their level (0: core).
        let mut quads: Vec<([u32; 4], usize, usize)> = Vec::new();
        for i2 in 0..m {
            for i1 in 0..m {
                quads.push((
                    [
                        core(i1, i2),
                        core(i1 + 1, i2),
                        core(i1 + 1, i2 + 1),
                        core(i1, i2 + 1),
                    ],
                    0,
                    0,
                ));
            }
        }
        for k in 0..levels {
            for j in 0..n_loop {
                let jn = (j + 1) % n_loop;
                quads.push((
                    [loops[k][j], loops[k + 1][j], loops[k + 1][jn], loops[k][jn]],
                    k + 1,
                    j,
                ));
            }
        }
        // Extrude.
        let n2 = xy.len();
        let mut mesh = Mesh {
            region_names: vec![self.hole_region.clone(), self.plate_region.clone()],
            ..Default::default()
        };
        for l in 0..=nt {
            let s3 = self.thickness * l as f64 / nt as f64;
            for p in &xy {
                let local = [p[0], p[1], s3];
                let mut x = [0.0; 3];
                for d in 0..3 {
                    x[map[d]] = self.centre[map[d]] + local[d];
                }
                mesh.coords.push(x);
            }
        }
        let id = |n: u32, l: usize| n + (l * n2) as u32;
        let pname = &self.plate_region;
        let mut faces: std::collections::BTreeMap<String, Vec<Face>> = Default::default();
        let side_name = |s: usize| -> String {
            match s {
                0 => format!("{pname}.{}max", letters[map[0]]),
                1 => format!("{pname}.{}max", letters[map[1]]),
                2 => format!("{pname}.{}min", letters[map[0]]),
                _ => format!("{pname}.{}min", letters[map[1]]),
            }
        };
        for l in 0..nt {
            for &(q, level, j) in &quads {
                let e = mesh.elements.len() as u32;
                mesh.elements.push([
                    id(q[0], l),
                    id(q[1], l),
                    id(q[2], l),
                    id(q[3], l),
                    id(q[0], l + 1),
                    id(q[1], l + 1),
                    id(q[2], l + 1),
                    id(q[3], l + 1),
                ]);
                let plate = level > n_in;
                mesh.element_region.push(u16::from(plate));
                if !plate {
                    continue;
                }
                if level == n_in + 1 {
                    faces
                        .entry(format!("{pname}.wall"))
                        .or_default()
                        .push(Face {
                            element: e,
                            local: 5,
                        });
                }
                if level == levels {
                    faces.entry(side_name(j / m)).or_default().push(Face {
                        element: e,
                        local: 3,
                    });
                }
                if l == 0 {
                    faces
                        .entry(format!("{pname}.{}min", letters[map[2]]))
                        .or_default()
                        .push(Face {
                            element: e,
                            local: 0,
                        });
                }
                if l + 1 == nt {
                    faces
                        .entry(format!("{pname}.{}max", letters[map[2]]))
                        .or_default()
                        .push(Face {
                            element: e,
                            local: 1,
                        });
                }
            }
        }
        for (r, name) in mesh.region_names.clone().iter().enumerate() {
            let list: Vec<u32> = (0..mesh.n_elements() as u32)
                .filter(|&e| mesh.element_region[e as usize] as usize == r)
                .collect();
            mesh.element_sets.insert(name.clone(), list);
        }
        for (name, f) in faces {
            let nodes = mesh.face_set_nodes(&f);
            mesh.node_sets.insert(name.clone(), nodes);
            mesh.face_sets.insert(name, f);
        }
        mesh.validate()?;
        Ok(mesh)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_sets_and_volume() {
        let mut spec = PlateWithHoleSpec::new(10.0, 100.0, 2.0, 12);
        spec.divisions_around = 48;
        spec.grading = 8.0;
        spec.axis = "y".into();
        let mesh = spec.build("t").unwrap();
        let m = 12;
        let n_in = 6;
        let per_layer = m * m + 48 * (n_in + 12);
        assert_eq!(mesh.n_elements(), per_layer);
        assert_eq!(mesh.face_sets["plate.wall"].len(), 48);
        // Axis y: s1 = z, s2 = x.
        for name in ["plate.zmax", "plate.zmin", "plate.xmax", "plate.xmin"] {
            assert_eq!(mesh.face_sets[name].len(), 12, "{name}");
        }
        assert_eq!(mesh.face_sets["plate.ymin"].len(), 48 * 12);
        // Volumes: the plate is (2b)² t − π a² t up to the polygonal hole (48 chords).
        let vol = |region: usize| -> f64 {
            (0..mesh.n_elements())
                .filter(|&e| mesh.element_region[e] as usize == region)
                .map(|e| crate::mesh::hex8_shape::volume(&mesh.element_coords(e)))
                .sum()
        };
        let polygon = 0.5 * 48.0 * 100.0 * (2.0 * std::f64::consts::PI / 48.0).sin();
        assert!((vol(0) - polygon * 2.0).abs() < 1e-9 * vol(0));
        assert!((vol(1) - (200.0 * 200.0 - polygon) * 2.0).abs() < 1e-9 * vol(1));
        // Wall nodes on the circle.
        for &n in &mesh.node_sets["plate.wall"] {
            let x = mesh.coords[n as usize];
            assert!(((x[2] * x[2] + x[0] * x[0]).sqrt() - 10.0).abs() < 1e-12);
        }
    }

    #[test]
    fn bad_inputs_are_named() {
        let mut spec = PlateWithHoleSpec::new(10.0, 5.0, 1.0, 4);
        let e = spec.build("c.toml").unwrap_err().to_string();
        assert!(
            e.contains("c.toml: mesh.plate_with_hole.half_width = 5"),
            "{e}"
        );
        spec.half_width = 50.0;
        spec.divisions_around = 30;
        let e = spec.build("c.toml").unwrap_err().to_string();
        assert!(e.contains("divisions_around = 30"), "{e}");
        spec.divisions_around = 32;
        spec.axis = "w".into();
        let e = spec.build("c.toml").unwrap_err().to_string();
        assert!(e.contains("axis"), "{e}");
    }
}
