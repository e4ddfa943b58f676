//! The mesh lines: graded coordinates along x, y and z through every dimension of the
//! geometry, and the z-lines that bend over the cavern to follow the crown arch.
//!
//! Along each axis the breakpoints (every face of the geometry) are joined by cells whose
//! size is `h_core` inside the cavern's box and grows by `growth − 1` per metre of distance
//! from it (a geometric progression of ratio ≈ `growth` from cell to cell), capped at
//! `h_max`: the cells grade away from the cavern and none exceeds `h_max`.
//!
//! Over the cavern (|x| ≤ half width) four z-lines bend: the inner arch line (the lining's
//! inner surface; flat at springline − lining beside the cavern), the outer arch line (the
//! excavated surface; flat at the springline beside it), and the lines between a flat line
//! below (`z_low`, the corbel top) and above (`z_high`) are spread proportionally. Cells
//! keep vertical sides; the arch is a polyline through the x-lines.

use super::geometry::CavernGeometry;

/// Cell sizes of a mesh variant (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Density {
    /// Cell size inside the cavern's box.
    pub h_core: f64,
    /// Growth ratio of the cell size away from the cavern.
    pub growth: f64,
    /// Largest cell size.
    pub h_max: f64,
}

/// Coordinates along one axis through `breaks` (sorted), sized as the module says, the
/// core being [core.0, core.1].
pub fn axis_lines(breaks: &[f64], core: (f64, f64), d: &Density) -> Vec<f64> {
    let size = |s: f64| {
        let dist = (core.0 - s).max(s - core.1).max(0.0);
        (d.h_core + (d.growth - 1.0) * dist).min(d.h_max)
    };
    let mut out = vec![breaks[0]];
    for w in breaks.windows(2) {
        let (a, b) = (w[0], w[1]);
        // ∫ ds/h by the midpoint rule on 200 slices; cells placed by equidistribution.
        const SLICES: usize = 200;
        let ds = (b - a) / SLICES as f64;
        let mut cum = vec![0.0; SLICES + 1];
        for i in 0..SLICES {
            cum[i + 1] = cum[i] + ds / size(a + (i as f64 + 0.5) * ds);
        }
        let total = cum[SLICES];
        let n = ((total - 1e-9).ceil() as usize).max(1);
        // The cap h_max must hold even where the integral rounds down.
        let n = n.max(((b - a) / d.h_max - 1e-9).ceil() as usize);
        for c in 1..n {
            let target = total * c as f64 / n as f64;
            let i = cum.partition_point(|&v| v < target).clamp(1, SLICES);
            let t = (target - cum[i - 1]) / (cum[i] - cum[i - 1]).max(f64::MIN_POSITIVE);
            out.push(a + ds * (i as f64 - 1.0 + t));
        }
        out.push(b);
    }
    out
}

/// Sorted breakpoints without near-duplicates.
pub fn sorted_breaks(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
    v
}

/// The lines of the mesh in the cavern's frame.
#[derive(Clone, Debug)]
pub struct SectionLines {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// z-lines where they are flat (beside the cavern).
    pub z: Vec<f64>,
    /// Indices of the bending lines: the flat line below, the inner arch, the outer arch,
    /// the flat line above.
    pub k_low: usize,
    pub k_inner: usize,
    pub k_outer: usize,
    pub k_high: usize,
}

impl SectionLines {
    pub fn new(geo: &CavernGeometry, d: &Density) -> Self {
        let g = geo;
        let a = g.half_width();
        let t = g.lining;
        let mut xb = vec![
            -g.origin[0],
            g.model[0] - g.origin[0],
            -a,
            a,
            -(a - t),
            a - t,
            -(a - t - g.corbel_depth),
            a - t - g.corbel_depth,
            -0.5 * g.pedestal,
            0.5 * g.pedestal,
            -0.5 * g.pit,
            0.5 * g.pit,
            0.0,
            a + g.tunnel_length,
        ];
        xb.retain(|v| v.is_finite());
        let mut yb = vec![
            -g.origin[1],
            g.model[1] - g.origin[1],
            0.0,
            g.length,
            g.erection_bay,
            g.erection_bay + g.end_wall,
            g.units_end() - g.end_wall,
            g.units_end(),
        ];
        for u in 0..g.units {
            let c = g.unit_centre(u);
            for h in [
                0.5 * g.pedestal,
                0.5 * g.pit,
                0.5 * g.tunnel_width,
                0.5 * g.tunnel_width + g.tunnel_lining,
            ] {
                yb.push(c - h);
                yb.push(c + h);
            }
        }
        for gap in 1..g.units {
            let c = g.erection_bay + gap as f64 * g.unit_spacing;
            yb.push(c - 0.5 * g.column_y);
            yb.push(c + 0.5 * g.column_y);
        }
        let floor_top = g.generator_floor_bottom + g.generator_floor;
        let z_low = g.corbel_bottom + g.corbel_height;
        let z_inner = g.springline() - t;
        let z_outer = g.springline();
        let z_high = g.height + g.arch_rise;
        // The lines between z_low and the inner arch bend up to the inner crown: enough
        // of them that no cell there exceeds h_max.
        let dome = ((g.height - t - z_low) / d.h_max).ceil().max(1.0) as usize;
        let mut zb = vec![
            -g.origin[2],
            g.model[2] - g.origin[2],
            0.0,
            g.turbine_floor_bottom,
            g.turbine_floor_bottom + g.turbine_floor,
            g.generator_floor_bottom,
            floor_top,
            floor_top + g.tunnel_height,
            floor_top + g.tunnel_height + g.tunnel_lining,
            g.corbel_bottom,
            z_low,
            z_inner,
            z_outer,
            z_high,
        ];
        zb.extend((1..dome).map(|i| z_low + (z_inner - z_low) * i as f64 / dome as f64));
        let core_x = (-a, a + g.tunnel_length);
        let core_y = (0.0, g.length);
        let core_z = (0.0, z_high);
        let x = axis_lines(&sorted_breaks(xb), core_x, d);
        let y = axis_lines(&sorted_breaks(yb), core_y, d);
        let z = axis_lines(&sorted_breaks(zb), core_z, d);
        let index = |v: f64| {
            z.iter()
                .position(|&s| (s - v).abs() < 1e-6)
                .expect("breakpoint is a line")
        };
        Self {
            k_low: index(z_low),
            k_inner: index(z_inner),
            k_outer: index(z_outer),
            k_high: index(z_high),
            x,
            y,
            z,
        }
    }

    /// Height of line `k` at x-line `i` (cavern frame).
    pub fn z_at(&self, geo: &CavernGeometry, i: usize, k: usize) -> f64 {
        let x = self.x[i];
        let zf = self.z[k];
        let a = geo.half_width();
        if x.abs() > a + 1e-9 || k <= self.k_low || k >= self.k_high {
            return zf;
        }
        let zi_flat = self.z[self.k_inner];
        let zo_flat = self.z[self.k_outer];
        // The two arch lines at this x.
        let inner_face = a - geo.lining;
        let z_inner = if x.abs() <= inner_face + 1e-9 {
            geo.inner_arch(x)
        } else {
            // Across the sidewall lining: from the top of its face down to the flat inner
            // line at the rock.
            let s = (x.abs() - inner_face) / geo.lining;
            let top = geo.inner_springing();
            top + s * (zi_flat - top)
        };
        let z_outer = geo.outer_arch(x);
        let z_low = self.z[self.k_low];
        let z_high = self.z[self.k_high];
        if k <= self.k_inner {
            z_low + (zf - z_low) / (zi_flat - z_low) * (z_inner - z_low)
        } else if k <= self.k_outer {
            z_inner + (zf - zi_flat) / (zo_flat - zi_flat) * (z_outer - z_inner)
        } else {
            z_high - (z_high - zf) / (z_high - zo_flat) * (z_high - z_outer)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_hit_breaks_grade_and_respect_the_cap() {
        let d = Density {
            h_core: 1.0,
            growth: 1.25,
            h_max: 7.0,
        };
        let x = axis_lines(&[-48.0, -8.5, 0.0, 8.5, 48.0], (-8.5, 8.5), &d);
        for b in [-48.0, -8.5, 0.0, 8.5, 48.0] {
            assert!(x.iter().any(|&v| (v - b).abs() < 1e-12), "{b}");
        }
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        assert!(h.iter().all(|&s| s > 0.0 && s <= 7.0 + 1e-9), "{h:?}");
        // Inside the core 1 m; cells grow outward.
        let inner: Vec<f64> = x
            .windows(2)
            .filter(|w| w[0] >= -8.5 && w[1] <= 8.5)
            .map(|w| w[1] - w[0])
            .collect();
        assert!(inner.iter().all(|&s| (s - 1.0).abs() < 0.1), "{inner:?}");
        let right: Vec<f64> = x
            .windows(2)
            .filter(|w| w[0] >= 8.5)
            .map(|w| w[1] - w[0])
            .collect();
        assert!(right.windows(2).all(|w| w[1] >= w[0] - 0.2), "{right:?}");
        assert!(*right.last().unwrap() > 4.0);
    }
}
