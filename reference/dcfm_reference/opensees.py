"""Import OpenSeesPy on a machine without a system BLAS.

The openseespylinux 3.7.x wheel ships libblas.so.3, liblapack.so.3 and their Fortran
runtime in ``openseespylinux/lib`` but its extension does not find them (no rpath), so
``import openseespy.opensees`` fails unless Debian's libblas3/liblapack3 are installed.
Loading the bundled libraries first with ``RTLD_GLOBAL`` (dependencies before the
libraries that need them) makes the import work anywhere.
"""

from __future__ import annotations

import ctypes
import importlib.util
from pathlib import Path
from types import ModuleType

# Load order: the Fortran runtime, then BLAS, then LAPACK (which needs BLAS).
_BUNDLED = ["libquadmath.so.0", "libgfortran.so.4", "libgomp.so.1", "libblas.so.3", "liblapack.so.3"]


def opensees() -> ModuleType:
    """The ``openseespy.opensees`` module, with the wheel's BLAS preloaded."""
    spec = importlib.util.find_spec("openseespylinux")
    if spec is not None and spec.origin is not None:
        lib = Path(spec.origin).parent / "lib"
        for name in _BUNDLED:
            path = lib / name
            if path.exists():
                ctypes.CDLL(str(path), mode=ctypes.RTLD_GLOBAL)
    import openseespy.opensees as ops  # noqa: PLC0415 (after the preload, on purpose)

    return ops


def add_bricks(ops, coords, elements, young: float, poisson: float, density: float) -> None:
    """Nodes and ``stdBrick`` elements (2×2×2 Gauss) of a hex8 mesh of axis-aligned
    boxes, with the row-sum lumped mass ρV/8 per element corner assigned to the nodes.

    stdBrick's own mass (from the material's density) is not this lumped mass: with it
    the explicit schemes go unstable at the step of the lumped-mass element (a mass with a
    smaller diagonal, hence a higher largest frequency). So the material gets ρ = 0 and
    the nodes get ∫ρ N_a dV, which for a box is ρV/8 at each corner.
    """
    import numpy as np

    coords = np.asarray(coords, dtype=float)
    elements = np.asarray(elements)
    for i, x in enumerate(coords):
        ops.node(i + 1, *map(float, x))
    ops.nDMaterial("ElasticIsotropic", 1, young, poisson, 0.0)
    mass = np.zeros(len(coords))
    for e, conn in enumerate(elements):
        ops.element("stdBrick", e + 1, *[int(c) + 1 for c in conn], 1)
        x = coords[conn]
        volume = float(np.prod(x.max(axis=0) - x.min(axis=0)))
        mass[conn] += density * volume / 8.0
    for i, m in enumerate(mass):
        ops.mass(i + 1, m, m, m)
