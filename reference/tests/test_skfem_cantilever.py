"""Cross-check: lowest natural frequencies of a cantilever block, scikit-fem eigen-solve
against dcfm's free vibration.

Set-up: an elastic block 1.0 × 0.6 × 4.0 m (rock of docs/verification_references.md:
E 20 GPa, ν 0.25, ρ 2700 kg/m³), 5 × 3 × 20 hex8 elements, clamped at z = 0 (every DOF of
the base nodes fixed), fully integrated (2×2×2 Gauss) in both codes.

scikit-fem: the same mesh (dcfm's coordinates and connectivity), ``ElementHex1`` with
intorder 2, stiffness K from ``linear_elasticity``, and the **row-sum lumped mass**
M_a = ∫ρ N_a dV — the mass dcfm integrates with. Both codes then hold the same discrete
system, so its eigenvalues are the frequencies dcfm must vibrate at; a consistent mass
would be a different discrete system (its frequencies lie 0.2–6 % higher here: printed,
not compared). Dense generalized eigen-solve K φ = ω² M φ on the free DOFs.

dcfm: a generic initial velocity field (bending in x and y, twist, axial stretch) and
free vibration for 2.5 s (≈ 40 periods of the lowest mode); the displacement history of
every node is projected on each scikit-fem mode (q_k = φ_kᵀ M u(t)), and the frequency of
q_k is measured from its zero crossings (linear interpolation, least-squares slope of
crossing time against crossing number = half a period).

Reference: the eigenfrequencies; tolerance ±1 % (issue 9). Central difference changes a
frequency by (ωΔt)²/24 ≈ 3e-5 here, so agreement should be far inside it.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

import dcfm
from dcfm_reference import hex8, record

CASE = "Cantilever block: lowest natural frequencies"
PEER = "scikit-fem 12.0.2 (eigen-solve, lumped mass)"
SOURCE = "generalized eigenproblem K φ = ω² M φ of the same hex8 mesh (scikit-fem)"
E, NU, RHO = 20e9, 0.25, 2700.0
SIZE = [1.0, 0.6, 4.0]
DIV = [5, 3, 20]
N_MODES = 4


def cantilever_case(end: float) -> dcfm.Case:
    return dcfm.Case.from_dict(
        {
            "title": "cantilever block, free vibration",
            "time": {"end": end},
            "mesh": {
                "blocks": [
                    {"name": "block", "origin": [0.0, 0.0, 0.0], "size": SIZE, "divisions": DIV}
                ]
            },
            "materials": {
                "rock": {"model": "elastic", "young": E, "poisson": NU, "density": RHO}
            },
            "regions": [{"name": "block", "material": "rock", "integration": "full"}],
            "boundary": {"fixed": [{"set": "block.zmin", "dofs": "xyz"}]},
        },
        label="cantilever",
    )


def zero_crossing_frequency(t: np.ndarray, q: np.ndarray) -> float:
    """Frequency of an oscillating signal from its zero crossings."""
    s = np.sign(q)
    idx = np.nonzero(s[:-1] * s[1:] < 0)[0]
    tc = t[idx] - q[idx] * (t[idx + 1] - t[idx]) / (q[idx + 1] - q[idx])
    n = np.arange(len(tc))
    half_period = np.polyfit(n, tc, 1)[0]
    return 1.0 / (2.0 * half_period)


def test_cantilever_frequencies():
    case = cantilever_case(end=2.5)
    coords, elements = case.coords, case.elements
    n = case.n_nodes
    mesh = hex8.skfem_mesh(coords, elements)
    basis = hex8.vector_basis(mesh)
    k = hex8.stiffness(basis, E, NU)
    m = hex8.lumped_mass(basis, RHO)
    dofs = hex8.dof_index(basis, n)
    # Same mesh, same lumping: the nodal masses agree with dcfm's.
    np.testing.assert_allclose(m[dofs[:, 0]], case.mass, rtol=1e-12)
    fixed_nodes = case.nodes_of("block.zmin")
    fixed = dofs[fixed_nodes].ravel()
    free = np.setdiff1d(np.arange(3 * n), fixed)
    kf = k[free][:, free].toarray()
    w2, phi_f = scipy.linalg.eigh(kf, np.diag(m[free]), subset_by_index=[0, N_MODES - 1])
    f_ref = np.sqrt(w2) / (2 * np.pi)
    mc = hex8.consistent_mass(basis, RHO)[free][:, free].toarray()
    w2c = scipy.linalg.eigh(kf, mc, eigvals_only=True, subset_by_index=[0, N_MODES - 1])
    print("lumped-mass frequencies (Hz):", f_ref)
    print("consistent-mass frequencies (Hz):", np.sqrt(w2c) / (2 * np.pi))

    # dcfm: free vibration from a generic initial velocity field.
    sim = case.start()
    x, y, z = coords[:, 0] - 0.5, coords[:, 1] - 0.3, coords[:, 2] / SIZE[2]
    v = np.stack(
        [0.02 * z**2 - 0.01 * z * y, 0.02 * z**1.5 + 0.01 * z * x, 0.002 * z], axis=1
    )
    sim.set_velocity(v)
    run = sim.run(end=2.5, record_every=10, nodes=list(range(n)), elements=[], threads=1)
    u = run.displacement.reshape(len(run.time), 3 * n)  # node-major: x, y, z per node
    # Map dcfm's (node, direction) order to scikit-fem's DOFs.
    order = dofs.ravel()
    u_sk = np.zeros((len(run.time), 3 * n))
    u_sk[:, order] = u
    phi = np.zeros((3 * n, N_MODES))
    phi[free] = phi_f
    q = u_sk @ (m[:, None] * phi)
    rows = []
    for j in range(N_MODES):
        f_dcfm = zero_crossing_frequency(run.time, q[:, j])
        rows.append(
            record.check(CASE, f"mode {j + 1}: frequency (Hz)", f_ref[j], f_dcfm, 0.01, SOURCE, PEER)
        )
    assert not record.failures(rows), record.failures(rows)
