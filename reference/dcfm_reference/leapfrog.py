"""Central difference in leapfrog form with a lumped mass and a CSR stiffness (scipy):
the scheme of dcfm's elastic step without contact, for timing and for a like-for-like
comparison on the same mesh.

    V^{n+½} = V^{n−½} + Δt M⁻¹ (F − K Uⁿ),  U^{n+1} = Uⁿ + Δt V^{n+½}

Fixed DOFs keep zero displacement and velocity.
"""

from __future__ import annotations

import time

import numpy as np
import scipy.sparse as sp


def leapfrog(
    k: sp.csr_matrix,
    m_lumped: np.ndarray,
    u0: np.ndarray,
    v_half: np.ndarray,
    dt: float,
    steps: int,
    fixed: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, float]:
    """Run ``steps`` steps; returns (U, V^{n−½}, wall seconds of the step loop)."""
    u = u0.copy()
    v = v_half.copy()
    free = np.ones(u.shape[0], dtype=bool)
    free[fixed] = False
    w = np.where(free, dt / m_lumped, 0.0)
    v[~free] = 0.0
    t0 = time.perf_counter()
    for _ in range(steps):
        v -= w * (k @ u)
        u += dt * v
    wall = time.perf_counter() - t0
    return u, v, wall
