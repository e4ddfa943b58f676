//! Warnings of a valid case: a value its field accepts but that lies far outside what the
//! field means for a physical model (a tensile strength of 1.3 Pa — MPa typed as Pa — or
//! a density of 2.7 kg/m³ — t/m³ typed as kg/m³). The case still builds and runs; `dcfm
//! check` and `dcfm run` print every warning on stderr and `summary.json` lists them
//! (docs/case_format.md, "Plausibility warnings"). The ranges and their physical
//! justification are in `case::build::plausibility`.

use serde::Serialize;

/// One warning: the file, the field path, the value and the range the field usually
/// holds, with why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CaseWarning {
    /// The case file.
    pub file: String,
    /// Dotted field path (`materials.rock.density`).
    pub field: String,
    /// The value as given.
    pub value: String,
    /// The usual range and why a value outside it is suspect.
    pub expected: String,
}

impl std::fmt::Display for CaseWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: {} = {}: {}",
            self.file, self.field, self.value, self.expected
        )
    }
}
