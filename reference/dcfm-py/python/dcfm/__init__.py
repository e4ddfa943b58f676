"""dcfm from Python: load and run cases, drive material points and contact pairs, read and
process ground motions.

The functions and classes come from the compiled extension ``dcfm._dcfm`` (Rust, pyo3);
their typed signatures are in ``__init__.pyi``. See ``reference/README.md``.
"""

from ._dcfm import (
    Case,
    DcfmError,
    Mesh,
    Motion,
    RunResult,
    Simulation,
    __version__,
    box_mesh,
    contact_pair_step,
    material_point,
    read_motion,
    response_spectrum,
    synthetic_motion,
    to_toml,
)

__all__ = [
    "Case",
    "DcfmError",
    "Mesh",
    "Motion",
    "RunResult",
    "Simulation",
    "__version__",
    "box_mesh",
    "contact_pair_step",
    "material_point",
    "read_motion",
    "response_spectrum",
    "synthetic_motion",
    "to_toml",
]
