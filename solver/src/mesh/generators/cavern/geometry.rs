//! The parametric powerhouse: its dimensions and what sits at a point.
//!
//! Coordinates are relative to the cavern: x across the cavern from its axis (the
//! downstream side x > 0), y along the axis from the cavern's end wall at the erection bay,
//! z up from the excavation bottom of the unit bays. [`CavernGeometry::origin`] places this
//! frame in the model box, whose corner is the origin of the mesh coordinates.

use serde::{Deserialize, Serialize};

/// Every dimension of the parametric powerhouse (m). docs/yingxiuwan.md gives the values
/// of the preset and where each comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CavernGeometry {
    /// Model box (x, y, z).
    pub model: [f64; 3],
    /// Position of the cavern frame (axis, erection-bay end wall, excavation bottom) in the
    /// model box.
    pub origin: [f64; 3],
    /// Excavated width (rock face to rock face, x).
    pub width: f64,
    /// Excavated length (y).
    pub length: f64,
    /// Excavated height, bottom to crown (z).
    pub height: f64,
    /// Rise of the crown arch above the springline (circular arch).
    pub arch_rise: f64,
    /// Concrete thickness of the sidewall lining and of the arch lining at the crown.
    pub lining: f64,
    /// Erection bay length at the y = 0 end; its floor is the generator floor on rock.
    pub erection_bay: f64,
    /// Number of generating units and their spacing along y (from the erection bay on).
    pub units: usize,
    pub unit_spacing: f64,
    /// Top of the mass concrete (spiral case and draft tube embedded) = turbine floor slab
    /// bottom; turbine floor thickness.
    pub turbine_floor_bottom: f64,
    pub turbine_floor: f64,
    /// Generator floor slab bottom and thickness.
    pub generator_floor_bottom: f64,
    pub generator_floor: f64,
    /// End walls of the turbine layer (y), thickness.
    pub end_wall: f64,
    /// Generator pedestal: square outer side and square pit side (pit through the
    /// turbine layer and the generator floor).
    pub pedestal: f64,
    pub pit: f64,
    /// Turbine-layer columns between the pedestals: side along x (at the pedestal walls)
    /// and along y (centred in the gap).
    pub column_y: f64,
    /// Crane-beam corbels (with the beam): bottom, height, protrusion from the lining face.
    pub corbel_bottom: f64,
    pub corbel_height: f64,
    pub corbel_depth: f64,
    /// Busbar tunnels (one per unit, downstream wall, floor at the generator floor top):
    /// clear width, clear height, lining thickness, length of the modelled stub.
    pub tunnel_width: f64,
    pub tunnel_height: f64,
    pub tunnel_lining: f64,
    pub tunnel_length: f64,
}

/// What occupies a point (or a cell of the mesh).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Part {
    /// Not meshed: the air of the cavern, the pits, the turbine-layer rooms, the tunnels.
    Void,
    Rock,
    /// Arch lining (above the sidewall lining's top layer of cells).
    ArchLining,
    /// Sidewall lining above the generator floor.
    WallLining,
    CraneCorbel,
    TunnelLining,
    MassConcrete,
    TurbineFloor,
    /// Walls of the turbine layer (along the sidewalls and at the ends).
    TurbineLayerWall,
    Pedestal,
    Column,
    GeneratorFloor,
}

impl Part {
    /// Region (material and contact body) of a meshed part.
    pub fn region(self) -> Option<&'static str> {
        match self {
            Part::Void => None,
            Part::Rock => Some("rock"),
            Part::ArchLining | Part::WallLining | Part::CraneCorbel | Part::TunnelLining => {
                Some("lining")
            }
            _ => Some("inner"),
        }
    }
}

/// Where a cell sits relative to the arch band of the mesh lines (the lines that bend to
/// follow the arch): the classification of those cells is topological, not by centroid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArchBand {
    /// Below the bending lines or away from the cavern: classify by centroid.
    None,
    /// Between the lining's inner and outer arch lines.
    Lining,
    /// Above the outer arch line.
    Above,
}

impl CavernGeometry {
    pub fn half_width(&self) -> f64 {
        0.5 * self.width
    }

    /// Springline height.
    pub fn springline(&self) -> f64 {
        self.height - self.arch_rise
    }

    /// Radius and centre height of a circular arch of half-span `c` rising `f` above the
    /// springline.
    fn circle(&self, c: f64, f: f64) -> (f64, f64) {
        let r = (c * c + f * f) / (2.0 * f);
        (r, self.springline() + f - r)
    }

    /// The excavated rock surface of the crown at |x| ≤ half width.
    pub fn outer_arch(&self, x: f64) -> f64 {
        let (r, zc) = self.circle(self.half_width(), self.arch_rise);
        zc + (r * r - x * x).max(0.0).sqrt()
    }

    /// The lining's inner surface of the crown at |x| ≤ half width − lining: the circle
    /// concentric with the excavated arch, `lining` inside it, so that the arch lining is
    /// `lining` thick normal to its surfaces everywhere (at the crown as at the haunches).
    /// It meets the sidewall lining's face at [`CavernGeometry::inner_springing`], below
    /// the springline.
    pub fn inner_arch(&self, x: f64) -> f64 {
        let (r, zc) = self.circle(self.half_width(), self.arch_rise);
        let ri = r - self.lining;
        zc + (ri * ri - x * x).max(0.0).sqrt()
    }

    /// Height at which the lining's inner arch meets the face of the sidewall lining
    /// (|x| = half width − lining): the top of that face.
    pub fn inner_springing(&self) -> f64 {
        self.inner_arch(self.half_width() - self.lining)
    }

    /// Centre (y) of unit `u`.
    pub fn unit_centre(&self, u: usize) -> f64 {
        self.erection_bay + (u as f64 + 0.5) * self.unit_spacing
    }

    /// End of the unit bays (y).
    pub fn units_end(&self) -> f64 {
        self.erection_bay + self.units as f64 * self.unit_spacing
    }

    /// Nearest unit centre and |y − centre|.
    fn nearest_unit(&self, y: f64) -> (usize, f64) {
        (0..self.units)
            .map(|u| (u, (y - self.unit_centre(u)).abs()))
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a })
    }

    /// Within a busbar tunnel's excavated box (its lining included).
    fn in_tunnel_box(&self, x: f64, y: f64, z: f64) -> bool {
        let a = self.half_width();
        let (_, dy) = self.nearest_unit(y);
        let zf = self.generator_floor_bottom;
        x > a
            && x < a + self.tunnel_length
            && dy < 0.5 * self.tunnel_width + self.tunnel_lining
            && z > zf
            && z < zf + self.generator_floor + self.tunnel_height + self.tunnel_lining
    }

    /// Within a busbar tunnel's clear opening (extended through the sidewall lining).
    fn in_tunnel_opening(&self, x: f64, y: f64, z: f64) -> bool {
        let a = self.half_width();
        let (_, dy) = self.nearest_unit(y);
        let z0 = self.generator_floor_bottom + self.generator_floor;
        x > a - self.lining
            && x < a + self.tunnel_length
            && dy < 0.5 * self.tunnel_width
            && z > z0
            && z < z0 + self.tunnel_height
            && y > self.erection_bay
            && y < self.units_end()
    }

    /// What is at a cell centroid (x, y, z), given the cell's place in the arch band.
    pub fn part_at(&self, x: f64, y: f64, z: f64, band: ArchBand) -> Part {
        let a = self.half_width();
        let ax = x.abs();
        let in_length = y > 0.0 && y < self.length;
        let units = y > self.erection_bay && y < self.units_end();
        match band {
            ArchBand::Above => return Part::Rock,
            ArchBand::Lining => {
                return if in_length && ax < a {
                    Part::ArchLining
                } else {
                    Part::Rock
                };
            }
            ArchBand::None => {}
        }
        // Busbar tunnels (downstream, beyond the sidewall).
        if x > a {
            if self.in_tunnel_opening(x, y, z) {
                return Part::Void;
            }
            if self.in_tunnel_box(x, y, z) && units {
                return Part::TunnelLining;
            }
            return Part::Rock;
        }
        if ax > a || !in_length {
            return Part::Rock;
        }
        // Above the excavated crown (cells over the arch band, whose lines are flat): rock,
        // the sidewall lining's column included.
        if z > self.springline() && z > self.outer_arch(x) {
            return Part::Rock;
        }
        let floor_top = self.generator_floor_bottom + self.generator_floor;
        let wall = ax > a - self.lining;
        if z > floor_top {
            // Above the generator floor: sidewall lining, corbels, air.
            if wall {
                return if self.in_tunnel_opening(x, y, z) {
                    Part::Void
                } else {
                    Part::WallLining
                };
            }
            let corbel_face = a - self.lining - self.corbel_depth;
            if ax > corbel_face
                && z > self.corbel_bottom
                && z < self.corbel_bottom + self.corbel_height
            {
                return Part::CraneCorbel;
            }
            return Part::Void;
        }
        if !units {
            // Erection bay: its floor slab on the rock.
            return if z > self.generator_floor_bottom {
                Part::GeneratorFloor
            } else {
                Part::Rock
            };
        }
        if z < 0.0 {
            return Part::Rock;
        }
        let (_, dy) = self.nearest_unit(y);
        let in_pit = ax < 0.5 * self.pit && dy < 0.5 * self.pit;
        if z > self.generator_floor_bottom {
            return if in_pit {
                Part::Void
            } else {
                Part::GeneratorFloor
            };
        }
        let turbine_top = self.turbine_floor_bottom + self.turbine_floor;
        if z > turbine_top {
            // Turbine layer.
            let end_wall =
                y < self.erection_bay + self.end_wall || y > self.units_end() - self.end_wall;
            if wall || end_wall {
                return Part::TurbineLayerWall;
            }
            let in_pedestal = ax < 0.5 * self.pedestal && dy < 0.5 * self.pedestal;
            if in_pedestal {
                return if in_pit { Part::Void } else { Part::Pedestal };
            }
            // Columns centred between two neighbouring pedestals, at the pedestal walls' x.
            let in_column = (1..self.units).any(|g| {
                let centre = self.erection_bay + g as f64 * self.unit_spacing;
                (y - centre).abs() < 0.5 * self.column_y
            });
            if in_column && ax > 0.5 * self.pit && ax < 0.5 * self.pedestal {
                return Part::Column;
            }
            return Part::Void;
        }
        if z > self.turbine_floor_bottom {
            return Part::TurbineFloor;
        }
        Part::MassConcrete
    }

    /// The pedestal's inner wall: the half of the pedestal wall nearest the pit.
    pub fn is_pedestal_inner_wall(&self, x: f64, y: f64) -> bool {
        let (_, dy) = self.nearest_unit(y);
        let d = (x.abs().max(dy)) - 0.5 * self.pit;
        d <= 0.25 * (self.pedestal - self.pit) + 1e-9
    }

    /// A cavern junction: the tunnel lining within `reach` of the sidewall, and the
    /// sidewall lining within `reach` of a tunnel opening.
    pub fn is_junction(&self, x: f64, y: f64, z: f64, reach: f64) -> bool {
        let a = self.half_width();
        let (_, dy) = self.nearest_unit(y);
        let z0 = self.generator_floor_bottom + self.generator_floor;
        x > a - self.lining
            && x < a + reach
            && dy < 0.5 * self.tunnel_width + reach
            && z < z0 + self.tunnel_height + reach
            && z > self.generator_floor_bottom
    }
}

impl CavernGeometry {
    /// Reach of the junction survey region from the tunnel opening (m): one tunnel lining
    /// thickness plus half a tunnel width.
    pub fn junction_reach(&self) -> f64 {
        self.tunnel_lining + 0.5 * self.tunnel_width
    }
}

impl CavernGeometry {
    /// Distance (m) from a point to the excavated volume, taken as the cavern's bounding
    /// box (crown included) and the busbar tunnels' boxes (their linings included): 0
    /// inside. Used for zones of the rock around the excavation.
    pub fn distance_to_excavation(&self, x: f64, y: f64, z: f64) -> f64 {
        let a = self.half_width();
        let outside = |v: f64, lo: f64, hi: f64| (lo - v).max(v - hi).max(0.0);
        let cavern = (outside(x, -a, a).powi(2)
            + outside(y, 0.0, self.length).powi(2)
            + outside(z, 0.0, self.height).powi(2))
        .sqrt();
        let zf = self.generator_floor_bottom;
        let ztop = zf + self.generator_floor + self.tunnel_height + self.tunnel_lining;
        let half = 0.5 * self.tunnel_width + self.tunnel_lining;
        (0..self.units)
            .map(|u| {
                let c = self.unit_centre(u);
                (outside(x, a, a + self.tunnel_length).powi(2)
                    + outside(y, c - half, c + half).powi(2)
                    + outside(z, zf, ztop).powi(2))
                .sqrt()
            })
            .fold(cavern, f64::min)
    }
}
