//! A parametric underground powerhouse in its rock: the cavern with its crown arch, the
//! concrete lining of the arch and the sidewalls, the crane-beam corbels, the inner
//! structure below the generator floor (mass concrete, turbine floor, turbine-layer walls,
//! generator pedestals with their pits, turbine-layer columns, generator floor) and the
//! busbar tunnels that join the downstream wall, meshed with hex8 graded away from the
//! cavern, the concrete–rock and lining–inner-structure interfaces with duplicated nodes.
//!
//! One concept per file: [`geometry`] (the dimensions and what sits at a point),
//! [`section`] (the mesh lines and the arch), [`extrude`] (cells, sets, interfaces),
//! [`quality`] (element quality). The Yingxiuwan preset is
//! [`super::yingxiuwan`]; docs/yingxiuwan.md documents every dimension.

pub mod extrude;
pub mod geometry;
pub mod quality;
pub mod section;

use crate::error::Result;
use crate::mesh::Mesh;

pub use extrude::RockZones;
pub use geometry::{CavernGeometry, Part};
pub use quality::QualityReport;
pub use section::Density;

/// A generated cavern model: the mesh and its quality.
pub struct CavernModel {
    pub mesh: Mesh,
    pub quality: QualityReport,
    /// Excavation bench levels (cavern frame, from the crown down).
    pub benches: Vec<f64>,
}

/// Generate the mesh of `geo` at `density`; `benches` are the lower levels of the
/// excavation benches from the crown down (cavern frame; the last is the bottom bench);
/// `zones` the optional rock zones of the anti-seismic measures.
pub fn generate(
    geo: &CavernGeometry,
    density: &Density,
    benches: &[f64],
    zones: &RockZones,
) -> Result<CavernModel> {
    let lines = section::SectionLines::new(geo, density);
    let mesh = extrude::build_mesh(geo, &lines, benches, zones)?;
    let quality = quality::quality(&mesh);
    Ok(CavernModel {
        mesh,
        quality,
        benches: benches.to_vec(),
    })
}
