//! The mesh: coordinates, hex8 connectivity, regions and named sets.

use std::collections::BTreeMap;

use crate::error::{DcfmError, Result};

/// Local node numbers of the six hex8 faces, ordered counter-clockwise seen from outside
/// (so the right-hand normal points out of the element): ζ−, ζ+, η−, ξ+, η+, ξ−.
pub const HEX8_FACES: [[usize; 4]; 6] = [
    [0, 3, 2, 1],
    [4, 5, 6, 7],
    [0, 1, 5, 4],
    [1, 2, 6, 5],
    [2, 3, 7, 6],
    [0, 4, 7, 3],
];

/// One face of one element: `element` and its local face number (index into [`HEX8_FACES`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Face {
    pub element: u32,
    pub local: u8,
}

/// A hex8 mesh with named regions and sets.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Node coordinates (m).
    pub coords: Vec<[f64; 3]>,
    /// Element connectivity (node indices).
    pub elements: Vec<[u32; 8]>,
    /// Region index of every element.
    pub element_region: Vec<u16>,
    /// Region names, indexed by the values of `element_region`.
    pub region_names: Vec<String>,
    /// Named node sets (sorted, unique node indices).
    pub node_sets: BTreeMap<String, Vec<u32>>,
    /// Named face sets.
    pub face_sets: BTreeMap<String, Vec<Face>>,
    /// Named element sets (sorted, unique element indices).
    pub element_sets: BTreeMap<String, Vec<u32>>,
}

impl Mesh {
    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.coords.len()
    }

    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.elements.len()
    }

    /// Coordinates of the eight nodes of element `e`.
    #[inline]
    pub fn element_coords(&self, e: usize) -> [[f64; 3]; 8] {
        let conn = &self.elements[e];
        std::array::from_fn(|a| self.coords[conn[a] as usize])
    }

    /// Global node numbers of a face, counter-clockwise seen from outside the element.
    #[inline]
    pub fn face_nodes(&self, f: Face) -> [u32; 4] {
        let conn = &self.elements[f.element as usize];
        HEX8_FACES[f.local as usize].map(|a| conn[a])
    }

    /// Index of region `name`.
    pub fn region_index(&self, name: &str) -> Option<usize> {
        self.region_names.iter().position(|r| r == name)
    }

    /// Nodes of a face set (sorted, unique).
    pub fn face_set_nodes(&self, faces: &[Face]) -> Vec<u32> {
        let mut nodes: Vec<u32> = faces.iter().flat_map(|f| self.face_nodes(*f)).collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// Resolve a set name to nodes: a node set, else the nodes of a face set, else the nodes
    /// of an element set, else the nodes of a region.
    pub fn nodes_of(&self, name: &str) -> Option<Vec<u32>> {
        if let Some(n) = self.node_sets.get(name) {
            return Some(n.clone());
        }
        if let Some(f) = self.face_sets.get(name) {
            return Some(self.face_set_nodes(f));
        }
        let elements: Vec<u32> = if let Some(e) = self.element_sets.get(name) {
            e.clone()
        } else {
            let r = self.region_index(name)? as u16;
            (0..self.n_elements() as u32)
                .filter(|&e| self.element_region[e as usize] == r)
                .collect()
        };
        let mut nodes: Vec<u32> = elements
            .iter()
            .flat_map(|&e| self.elements[e as usize])
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        Some(nodes)
    }

    /// Names of every set and region, for error messages.
    pub fn set_names(&self) -> Vec<String> {
        let mut names: Vec<String> = self
            .node_sets
            .keys()
            .chain(self.face_sets.keys())
            .chain(self.element_sets.keys())
            .chain(self.region_names.iter())
            .cloned()
            .collect();
        names.sort();
        names.dedup();
        names
    }

    /// Check connectivity ranges and that every element has a positive Jacobian at all
    /// eight Gauss points and at its centre; inverted or degenerate elements are named.
    pub fn validate(&self) -> Result<()> {
        let n = self.n_nodes() as u32;
        if self.element_region.len() != self.elements.len() {
            return Err(DcfmError::Mesh(format!(
                "{} elements but {} region tags",
                self.elements.len(),
                self.element_region.len()
            )));
        }
        for (e, conn) in self.elements.iter().enumerate() {
            if let Some(bad) = conn.iter().find(|&&a| a >= n) {
                return Err(DcfmError::BadElement {
                    element: e,
                    reason: format!("node {bad} does not exist (mesh has {n} nodes)"),
                });
            }
            let mut sorted = *conn;
            sorted.sort_unstable();
            if sorted.windows(2).any(|w| w[0] == w[1]) {
                return Err(DcfmError::BadElement {
                    element: e,
                    reason: format!("repeated node in connectivity {conn:?} (degenerate hex8)"),
                });
            }
            crate::mesh::hex8_shape::check_jacobian(&self.element_coords(e))
                .map_err(|reason| DcfmError::BadElement { element: e, reason })?;
        }
        for (name, nodes) in &self.node_sets {
            if let Some(bad) = nodes.iter().find(|&&a| a >= n) {
                return Err(DcfmError::Mesh(format!(
                    "node set '{name}' refers to node {bad}, mesh has {n} nodes"
                )));
            }
        }
        Ok(())
    }
}
