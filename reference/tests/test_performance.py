"""The performance table: the same explicit steps on the same 40³ mesh in dcfm, in a scipy
sparse leapfrog and in OpenSeesPy, on the same machine in the same run — and a check that
the three integrate the same discrete system.

Model (that of benchmarks/src/cube.rs): a 10 m rock cube (E 20 GPa, ν 0.25,
ρ 2700 kg/m³), 40 × 40 × 40 hex8, base face fixed, every other node started at
v = (0.1, 0.05, −0.02) m/s, Δt = 0.9 × dcfm's critical step, STEPS steps (OPS_STEPS for
OpenSees, which takes seconds per step here; the table compares element updates per
second).

- dcfm: full 2×2×2 integration (the element of the other two codes) and one-point with
  hourglass control (dcfm's production element), 1 and 2 threads;
- scipy: K assembled by scikit-fem from the same hex8 (ElementHex1, intorder 2), lumped
  mass, CSR sparse matrix–vector product per step (``dcfm_reference.leapfrog``), one
  thread of numpy/scipy;
- OpenSees: stdBrick (2×2×2) with the lumped mass on the nodes, ``ExplicitDifference``
  (central difference in velocity form; ``CentralDifference`` ignores initial
  velocities) with a diagonal system, serial.

Agreement: full-integration dcfm and scipy after STEPS steps, dcfm and OpenSees after
OPS_STEPS steps, agree to 1e-9 of the largest displacement (same element, mass, scheme;
round-off only).
Element updates per second are element count × steps / wall time of the step loop alone.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

import dcfm
from dcfm_reference import hex8, record
from dcfm_reference.leapfrog import leapfrog
from dcfm_reference.opensees import add_bricks, opensees

N = 40
STEPS = 40
OPS_STEPS = 4  # OpenSees takes seconds per step on this mesh: fewer steps, same per-step measure
E, NU, RHO = 20e9, 0.25, 2700.0
V0 = [0.1, 0.05, -0.02]
CASE = "40³ cube: the same steps in dcfm, scipy and OpenSees"
SRC = "same mesh, element (hex8, 2×2×2), lumped mass and central difference"


def cube_case(integration: str) -> dcfm.Case:
    return dcfm.Case.from_dict(
        {
            "title": f"cube{N} {integration}",
            "time": {"end": 1.0},
            "mesh": {"blocks": [{"name": "rock", "origin": [0.0, 0.0, 0.0], "size": [10.0, 10.0, 10.0], "divisions": [N, N, N]}]},
            "materials": {"rock": {"model": "elastic", "young": E, "poisson": NU, "density": RHO}},
            "regions": [{"name": "rock", "material": "rock", "integration": integration}],
            "boundary": {"fixed": [{"set": "rock.zmin", "dofs": "xyz"}]},
            "initial": {"velocity": [{"set": "rock", "value": V0}]},
        },
        label=f"cube{N}_{integration}",
    )


def timed_dcfm(case: dcfm.Case, dt: float, threads: int, steps: int = STEPS) -> tuple[np.ndarray, float]:
    sim = case.start(dt=dt)
    t0 = time.perf_counter()
    sim.step(steps, threads=threads)
    return sim.displacement, time.perf_counter() - t0


def entry(code: str, variant: str, n_el: int, wall: float, threads: int, steps: int = STEPS) -> dict:
    return {
        "label": f"cube{N} {code} {variant} {threads}t",
        "problem": f"cube {N}³ hex8, {STEPS} steps",
        "code": code,
        "variant": variant,
        "elements": n_el,
        "steps": steps,
        "threads": threads,
        "wall_s": wall,
        "element_updates_per_s": n_el * steps / wall,
    }


def test_cube40_three_codes():
    full = cube_case("full")
    one = cube_case("one_point")
    dt = full.dt
    n_el = full.n_elements
    u_full = None
    for threads in (1, 2):
        u, wall = timed_dcfm(full, dt, threads)
        u_full = u if u_full is None else u_full
        if threads == 2:
            # Results do not depend on the thread count (bit-identical).
            assert np.array_equal(u, u_full)
        record.performance(entry("dcfm", "full", n_el, wall, threads))
        _, wall = timed_dcfm(one, one.dt, threads)  # its own (marginally smaller) step
        record.performance(entry("dcfm", "one_point", n_el, wall, threads))

    # scipy leapfrog on the scikit-fem assembly of the same mesh.
    coords, elements = full.coords, full.elements
    n = full.n_nodes
    basis = hex8.vector_basis(hex8.skfem_mesh(coords, elements))
    k = hex8.stiffness(basis, E, NU)
    m = hex8.lumped_mass(basis, RHO)
    dofs = hex8.dof_index(basis, n)
    fixed = dofs[full.nodes_of("rock.zmin")].ravel()
    v0 = np.zeros(3 * n)
    for d in range(3):
        v0[dofs[:, d]] = V0[d]
    u_sp, _, wall = leapfrog(k, m, np.zeros(3 * n), v0, dt, STEPS, fixed)
    record.performance(entry("scipy", "CSR leapfrog", n_el, wall, 1))
    u_sp_nodes = u_sp[dofs]

    # OpenSees.
    ops = opensees()
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 3)
    add_bricks(ops, coords, elements, E, NU, RHO)
    base = set(full.nodes_of("rock.zmin").tolist())
    for i in range(n):
        if i in base:
            ops.fix(i + 1, 1, 1, 1)
        else:
            for d in range(3):
                ops.setNodeVel(i + 1, d + 1, V0[d], "-commit")
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("Diagonal")
    ops.algorithm("Linear")
    ops.integrator("ExplicitDifference")
    ops.analysis("Transient")
    t0 = time.perf_counter()
    assert ops.analyze(OPS_STEPS, dt) == 0
    wall = time.perf_counter() - t0
    record.performance(entry("OpenSees", "stdBrick ExplicitDifference", n_el, wall, 1, OPS_STEPS))
    u_ops = np.array([ops.nodeDisp(i + 1) for i in range(n)])
    u_short, _ = timed_dcfm(full, dt, 1, OPS_STEPS)

    scale = np.abs(u_full).max()
    rows = [
        record.check(CASE, f"max |u_scipy − u_dcfm| / max |u| after {STEPS} steps", 0.0, np.abs(u_sp_nodes - u_full).max() / scale, 1e-9, SRC, "scipy 1.17.1 + scikit-fem 12.0.2", absolute=True),
        record.check(CASE, f"max |u_OpenSees − u_dcfm| / max |u| after {OPS_STEPS} steps", 0.0, np.abs(u_ops - u_short).max() / np.abs(u_short).max(), 1e-9, SRC, "OpenSeesPy 3.7.1", absolute=True),
    ]
    assert not record.failures(rows), record.failures(rows)
