//! Nodes, hex8 connectivity, regions and named node / face / element sets.
//!
//! Hex8 node order is that of VTK and Gmsh: nodes 0–3 on the face ζ = −1 counter-clockwise
//! seen from +ζ, nodes 4–7 above them. Natural coordinates of node a are
//! [`hex8_shape::NODE_XI`]. The trilinear geometry of the hex8 ([`hex8_shape`]: shape
//! functions, Jacobian checks) is part of the mesh; the element kernels build on it.

pub mod box_generator;
pub mod generators;
pub mod gmsh;
pub mod hex8_shape;
mod model_mesh;
mod node_merge;

pub use box_generator::{BlockSpec, BoxMeshSpec};
pub use model_mesh::{Face, Mesh, HEX8_FACES};
pub use node_merge::merge_coincident_nodes;
