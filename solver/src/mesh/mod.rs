//! Nodes, hex8 connectivity, regions and named node / face / element sets.
//!
//! Hex8 node order is that of VTK and Gmsh: nodes 0–3 on the face ζ = −1 counter-clockwise
//! seen from +ζ, nodes 4–7 above them. Natural coordinates of node a are
//! [`element::hex8_shape::NODE_XI`](crate::element::hex8_shape::NODE_XI).

pub mod box_generator;
pub mod gmsh;
mod model_mesh;
mod node_merge;

pub use box_generator::{BlockSpec, BoxMeshSpec};
pub use model_mesh::{Face, Mesh, HEX8_FACES};
pub use node_merge::merge_coincident_nodes;
