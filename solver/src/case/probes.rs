//! Output probes resolved against the model (`[output] nodes`, `elements`,
//! `[[output.probes]]`, `[[output.element_probes]]`): which nodes and elements feed which
//! columns of histories.csv, and how each probe was found (for `dcfm check` and the
//! summary). The case builder resolves them once ([`crate::case::Case::probes`]); the run
//! driver reads the values.

use serde::Serialize;

/// One group of columns of node quantities.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NodeProbe {
    /// Column prefix: `crest` gives `crest_ux` … `crest_az`.
    pub label: String,
    /// The node(s): one, or the set of a mean.
    pub nodes: Vec<u32>,
    /// Report the mass-free mean over `nodes` (else `nodes` has one node).
    pub mean: bool,
    /// How it was found, e.g. `node 313 at (1, 0, 50), 0.12 m from (1, 0.1, 50)`.
    pub found: String,
    /// The field that asked for it (`output.probes[2]`).
    pub field: String,
}

/// One group of columns of element quantities (volume-mean stress).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ElementProbe {
    /// Column prefix: `crown` gives `crown_sxx` … `crown_szx`.
    pub label: String,
    /// The element(s): one, or the set of a volume mean.
    pub elements: Vec<u32>,
    /// Report the volume mean over `elements`.
    pub mean: bool,
    /// How it was found.
    pub found: String,
    /// The field that asked for it.
    pub field: String,
}

/// Every probe of a case, in the order of their columns.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Probes {
    pub nodes: Vec<NodeProbe>,
    pub elements: Vec<ElementProbe>,
}

impl Probes {
    /// One line per probe, for `dcfm check`.
    pub fn describe(&self) -> Vec<String> {
        let mut out = Vec::new();
        for p in &self.nodes {
            out.push(format!(
                "probe     {:<16} {}  ({})",
                p.label, p.found, p.field
            ));
        }
        for p in &self.elements {
            out.push(format!(
                "probe     {:<16} {}  ({})",
                p.label, p.found, p.field
            ));
        }
        out
    }

    /// Every node whose motion a probe reads (node probes and the nodes of element
    /// probes), sorted and unique.
    pub fn touched_nodes(&self, mesh: &crate::mesh::Mesh) -> Vec<u32> {
        let mut n: Vec<u32> = self
            .nodes
            .iter()
            .flat_map(|p| p.nodes.iter().copied())
            .chain(
                self.elements
                    .iter()
                    .flat_map(|p| p.elements.iter())
                    .flat_map(|&e| mesh.elements[e as usize]),
            )
            .collect();
        n.sort_unstable();
        n.dedup();
        n
    }
}
