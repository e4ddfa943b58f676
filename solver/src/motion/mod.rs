//! Ground motions: records in their formats, processing, intensity measures, a seeded
//! synthetic generator, and the [`GroundMotion`] the solver consumes.
//!
//! ```text
//! file(s) ──readers──▶ Record (m/s²) ──processing──▶ GroundMotion {x, y, z: a, v, u}
//! synthetic spec ──generator──▶ Record ──┘                 │
//!                                                           ├─▶ TimeFunction::Motion (case)
//!                                                           └─▶ seismic-input boundaries
//! ```
//!
//! - [`readers`]: text/CSV, PEER AT2, K-NET/KiK-net, COSMOS V1/V2, USGS SMC;
//! - [`processing`]: window, baseline, taper, Butterworth band-pass, resampling, end
//!   correction, scaling, integration (order and defaults in its doc);
//! - [`measures`]: PGA/PGV/PGD, response spectrum (Nigam–Jennings), Arias intensity,
//!   Husid curve, D5–95, Fourier amplitude spectrum;
//! - [`synthetic`]: filtered-noise generator and the Wolong-like preset;
//! - [`spec`]: the `[motions.NAME]` case item.
//!
//! The solver's seismic input takes a motion by name from [`Motions`] (the case builder
//! fills it from `[motions.*]`) with [`motion_by_name`], and evaluates
//! [`GroundMotion::at`]`(axis, t)` → (a, v, u), O(1) and allocation-free.

pub mod ground_motion;
pub mod measures;
pub mod processing;
pub mod readers;
pub mod record;
pub mod spec;
pub mod summary;
pub mod synthetic;
pub mod units;

use std::collections::BTreeMap;
use std::sync::Arc;

pub use ground_motion::{GroundMotion, Kinematics, MotionComponent};
pub use processing::{process, ProcessingOptions};
pub use readers::{read_bytes, read_file, read_str, Format, ReadOptions};
pub use record::{Axis, Record, RecordComponent};
pub use spec::MotionSpec;
pub use synthetic::SyntheticSpec;
pub use units::AccelUnits;

use crate::error::{DcfmError, Result};

/// The motions of a case by name (`[motions.NAME]`), shared with every time function and
/// boundary that uses them.
pub type Motions = BTreeMap<String, Arc<GroundMotion>>;

/// The motion `name` of `motions`; `file`/`field` name the reference in the error, which
/// lists the motions the case defines.
pub fn motion_by_name(
    motions: &Motions,
    name: &str,
    file: &str,
    field: &str,
) -> Result<Arc<GroundMotion>> {
    motions.get(name).cloned().ok_or_else(|| {
        let known: Vec<&str> = motions.keys().map(String::as_str).collect();
        DcfmError::invalid(
            file,
            field,
            format!("\"{name}\""),
            if known.is_empty() {
                "a motion defined in [motions.NAME] (the case defines none)".to_string()
            } else {
                format!("a motion defined in [motions.NAME]: {}", known.join(", "))
            },
        )
    })
}

/// Load every `[motions.NAME]` of a case (`file` names it in errors, `dir` resolves paths).
pub fn load_motions(
    specs: &BTreeMap<String, MotionSpec>,
    file: &str,
    dir: &std::path::Path,
) -> Result<Motions> {
    let mut out = Motions::new();
    for (name, spec) in specs {
        out.insert(name.clone(), Arc::new(spec.load(name, file, dir)?));
    }
    Ok(out)
}
