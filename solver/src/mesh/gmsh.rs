//! Gmsh 4.1 import (placeholder while written in its own branch).
