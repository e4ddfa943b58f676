"""The same hex8 mesh in scikit-fem, and its stiffness and mass matrices.

dcfm numbers the eight nodes of a hex8 as VTK/Gmsh do; scikit-fem's ``MeshHex`` orders
them by their reference coordinates (0,0,0), (0,0,1), (0,1,0), (1,0,0), (0,1,1), (1,0,1),
(1,1,0), (1,1,1). ``VTK_TO_SKFEM`` picks, for each scikit-fem local node, the VTK one.
Element: trilinear ``ElementHex1`` with 2×2×2 Gauss integration, the element of dcfm's
``integration = "full"`` regions.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import skfem
from skfem.helpers import dot
from skfem.models.elasticity import lame_parameters, linear_elasticity

VTK_TO_SKFEM = [0, 4, 3, 1, 7, 5, 2, 6]


def skfem_mesh(coords: np.ndarray, elements: np.ndarray) -> skfem.MeshHex:
    """The dcfm mesh (coords (n, 3), VTK-ordered elements (e, 8)) as a scikit-fem mesh
    with the same node numbers."""
    t = np.ascontiguousarray(np.asarray(elements)[:, VTK_TO_SKFEM].T)
    return skfem.MeshHex(np.ascontiguousarray(np.asarray(coords, dtype=float).T), t)


def vector_basis(mesh: skfem.MeshHex) -> skfem.Basis:
    """Trilinear vector basis with 2×2×2 Gauss points (intorder 2)."""
    return skfem.Basis(mesh, skfem.ElementVector(skfem.ElementHex1()), intorder=2)


def stiffness(basis: skfem.Basis, young: float, poisson: float) -> sp.csr_matrix:
    """Elastic stiffness K (isotropic, small strain)."""
    lam, mu = lame_parameters(young, poisson)
    return linear_elasticity(lam, mu).assemble(basis).tocsr()


def consistent_mass(basis: skfem.Basis, density: float) -> sp.csr_matrix:
    """Consistent mass ∫ρ N_a N_b dV (2×2×2 Gauss points)."""

    @skfem.BilinearForm
    def mass(u, v, w):
        return density * dot(u, v)

    return mass.assemble(basis).tocsr()


def lumped_mass(basis: skfem.Basis, density: float) -> np.ndarray:
    """Row-sum lumped mass per DOF (= ∫ρ N_a dV, the lumping dcfm uses)."""
    return np.asarray(consistent_mass(basis, density).sum(axis=1)).ravel()


def dof_index(basis: skfem.Basis, n_nodes: int) -> np.ndarray:
    """(n_nodes, 3) array: the global DOF of each node's x, y, z in ``basis``."""
    nd = basis.nodal_dofs  # (3, n_nodes)
    assert nd.shape == (3, n_nodes)
    return np.ascontiguousarray(nd.T)
