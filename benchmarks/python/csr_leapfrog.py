"""The scipy CSR leapfrog on the throughput runner's elastic cube (issue 11, deliverable 5).

The baseline dcfm's fully integrated elastic cube is compared with: the same explicit scheme
written the way a numpy/scipy user would, one sparse matrix–vector product per step.

Model (that of ``benchmarks/src/cube.rs``, ``CubeSpec::new(n, Integration::Full)``): a 10 m
cube of n × n × n equal hex8 elements, nodes and elements numbered as
``solver/src/mesh/box_generator.rs`` numbers a single block (node i + (n+1)(j + (n+1)k),
elements x fastest, VTK node order), linear elastic rock E 20 GPa, ν 0.25, ρ 2700 kg/m³,
base face z = 0 fixed in x, y and z, every other node started at v = (0.1, 0.05, −0.02) m/s,
no external load (f = 0).

- K: scikit-fem's ``ElementVector(ElementHex1())`` with 2×2×2 Gauss points
  (``dcfm_reference.hex8``), an assembler independent of dcfm; the fixed DOFs are condensed
  out, so the matrix stepped is K_ff (the cheapest honest form for scipy);
- M: row-sum lumped mass ∫ρ N_a dV (what dcfm uses), assembled as a linear form;
- step (central difference in leapfrog form, ``dcfm_reference.leapfrog``):
  V^{n+½} = V^{n−½} + Δt M⁻¹ (F − K Uⁿ), U^{n+1} = Uⁿ + Δt V^{n+½}, F = 0,
  one CSR matvec and a few numpy vector operations per step, one thread (the thread
  variables of OpenMP, OpenBLAS, MKL are set to 1 before numpy is imported).

Timing: ``--warmup`` steps untimed (their time gives the step count), then at least
``--min-steps`` and enough steps for ``--min-wall`` seconds (at most ``--max-steps``),
timed around the step loop alone. Before timing, K is checked (symmetric, zero force for
the three rigid translations and rotations, total mass ρ V per direction) and after it the
state must be finite and bounded; a failed check exits with status 2 and says which.

Output: one JSON line on stdout (elements, nodes, dofs, nnz, steps, seconds,
element_updates_per_s, assembly_s, versions, ...). Run from anywhere::

    python benchmarks/python/csr_leapfrog.py --divisions 40 --dt 5.8e-5 --min-wall 2
"""

from __future__ import annotations

import os

for _var in (
    "OMP_NUM_THREADS",
    "OPENBLAS_NUM_THREADS",
    "MKL_NUM_THREADS",
    "NUMEXPR_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS",
):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import platform  # noqa: E402
import resource  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from dataclasses import dataclass  # noqa: E402
from pathlib import Path  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT / "reference") not in sys.path:
    sys.path.insert(0, str(ROOT / "reference"))

import numpy as np  # noqa: E402
import scipy  # noqa: E402
import scipy.sparse as sp  # noqa: E402
import skfem  # noqa: E402

from dcfm_reference import hex8  # noqa: E402
from dcfm_reference.leapfrog import leapfrog  # noqa: E402

EDGE = 10.0
YOUNG, POISSON, DENSITY = 20e9, 0.25, 2700.0
VELOCITY = (0.1, 0.05, -0.02)
# Relative tolerances of the sanity checks: round-off of sums of O(10²) terms of K.
SYMMETRY_TOL = 1e-12
RIGID_TOL = 1e-10
MASS_TOL = 1e-12
# After the run the kinetic energy ½ vᵀMv may not exceed this multiple of the initial one:
# the discrete energy ½ v_{n+½}ᵀ M v_{n+½} + ½ uₙᵀ K u_{n+1} is conserved, and its kinetic
# part stays within a small factor of it while Δt is stable; an unstable step grows
# exponentially past it.
ENERGY_GROWTH = 10.0


class SanityError(RuntimeError):
    """A check on the assembled system or on the run failed."""


def cube_mesh(n: int, edge: float = EDGE) -> tuple[np.ndarray, np.ndarray]:
    """Nodes ((n+1)³, 3) and VTK-ordered hex8 elements (n³, 8), numbered as dcfm's box
    generator numbers a single block."""
    x = edge * np.arange(n + 1) / n
    k, j, i = np.meshgrid(np.arange(n + 1), np.arange(n + 1), np.arange(n + 1), indexing="ij")
    coords = np.stack([x[i.ravel()], x[j.ravel()], x[k.ravel()]], axis=1)

    def nid(i, j, k):
        return i + (n + 1) * (j + (n + 1) * k)

    k, j, i = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()
    elements = np.stack(
        [
            nid(i, j, k),
            nid(i + 1, j, k),
            nid(i + 1, j + 1, k),
            nid(i, j + 1, k),
            nid(i, j, k + 1),
            nid(i + 1, j, k + 1),
            nid(i + 1, j + 1, k + 1),
            nid(i, j + 1, k + 1),
        ],
        axis=1,
    )
    return coords, elements


@dataclass
class CubeSystem:
    """The assembled cube: full K and lumped mass per DOF, the DOF numbering, and the
    condensed system that is stepped."""

    coords: np.ndarray
    elements: np.ndarray
    k_full: sp.csr_matrix
    m_full: np.ndarray
    dofs: np.ndarray  # (nodes, 3) global DOF of each node's x, y, z
    free: np.ndarray  # global DOFs not fixed, ascending
    k: sp.csr_matrix  # K_ff
    m: np.ndarray  # lumped mass of the free DOFs
    v0: np.ndarray  # initial velocity of the free DOFs
    assembly_s: float


def lumped_mass(basis: skfem.Basis) -> np.ndarray:
    """Row-sum lumped mass per DOF, ∫ρ N_a dV (2×2×2 Gauss): the row sums of
    ``hex8.consistent_mass`` as one linear form, without assembling the consistent matrix."""

    @skfem.LinearForm
    def form(v, _):
        return DENSITY * (v[0] + v[1] + v[2])

    return form.assemble(basis)


def assemble(n: int, fix_base: bool = True) -> CubeSystem:
    """Build and assemble the n³ cube (``fix_base=False``: a free-floating cube, for tests)."""
    coords, elements = cube_mesh(n)
    t0 = time.perf_counter()
    basis = hex8.vector_basis(hex8.skfem_mesh(coords, elements))
    k_full = hex8.stiffness(basis, YOUNG, POISSON)
    m_full = lumped_mass(basis)
    assembly_s = time.perf_counter() - t0
    dofs = hex8.dof_index(basis, coords.shape[0])
    fixed_mask = np.zeros(k_full.shape[0], dtype=bool)
    if fix_base:
        fixed_mask[dofs[coords[:, 2] == 0.0].ravel()] = True
    free = np.flatnonzero(~fixed_mask)
    k = k_full[free][:, free].tocsr()
    k.sort_indices()
    v_full = np.zeros(k_full.shape[0])
    for d in range(3):
        v_full[dofs[:, d]] = VELOCITY[d]
    return CubeSystem(
        coords, elements, k_full, m_full, dofs, free, k, m_full[free], v_full[free], assembly_s
    )


def rigid_modes(coords: np.ndarray, dofs: np.ndarray) -> list[tuple[str, np.ndarray]]:
    """The three translations and three infinitesimal rotations about the cube's centre as
    global DOF vectors (each of unit largest component)."""
    ndof = dofs.size
    c = coords - coords.mean(axis=0)
    modes = []
    for d, name in enumerate("xyz"):
        u = np.zeros(ndof)
        u[dofs[:, d]] = 1.0
        modes.append((f"translation {name}", u))
    for axis, name in enumerate("xyz"):
        w = np.zeros(3)
        w[axis] = 1.0
        disp = np.cross(w, c)  # ω × r
        u = np.zeros(ndof)
        for d in range(3):
            u[dofs[:, d]] = disp[:, d]
        modes.append((f"rotation about {name}", u / np.abs(u).max()))
    return modes


def sanity_checks(system: CubeSystem, n: int) -> dict[str, float]:
    """Check the assembled system; raises :class:`SanityError` naming the failed check.
    Returns the measured relative errors."""
    k = system.k_full
    scale = np.abs(k.data).max()
    asym = abs(k - k.T)
    symmetry = (asym.max() if asym.nnz else 0.0) / scale
    if not symmetry <= SYMMETRY_TOL:
        raise SanityError(f"K is not symmetric: max |K − Kᵀ| / max |K| = {symmetry:.3e} > {SYMMETRY_TOL}")
    rigid = 0.0
    for name, u in rigid_modes(system.coords, system.dofs):
        r = np.abs(k @ u).max() / (scale * np.abs(u).max())
        if not r <= RIGID_TOL:
            raise SanityError(f"K does not vanish on the rigid {name}: max |K u| / (max |K| max |u|) = {r:.3e} > {RIGID_TOL}")
        rigid = max(rigid, r)
    expected = DENSITY * EDGE**3
    mass = 0.0
    for d in range(3):
        total = system.m_full[system.dofs[:, d]].sum()
        err = abs(total - expected) / expected
        if not err <= MASS_TOL:
            raise SanityError(f"lumped mass along {'xyz'[d]} is {total:.6e} kg, expected ρ V = {expected:.6e} kg")
        mass = max(mass, err)
    if np.any(system.m_full <= 0.0):
        raise SanityError("a lumped mass is not positive")
    elements = system.elements.shape[0]
    if elements != n**3:
        raise SanityError(f"{elements} elements, expected {n}³ = {n**3}")
    return {"symmetry": symmetry, "rigid": rigid, "mass": mass}


def stable_dt(k: sp.csr_matrix, m: np.ndarray) -> float:
    """2/ω with ω² = max_i Σ_j |K_ij| / m_i, an upper bound (Gershgorin) of the largest
    eigenvalue of M⁻¹K: a step that is stable for certain."""
    row_abs = np.asarray(abs(k).sum(axis=1)).ravel()
    return 2.0 / math.sqrt((row_abs / m).max())


def kinetic(v: np.ndarray, m: np.ndarray) -> float:
    return 0.5 * float(np.dot(m * v, v))


def run(args: argparse.Namespace) -> dict:
    n = args.divisions
    system = assemble(n)
    checks = sanity_checks(system, n)
    dt = args.dt if args.dt is not None else 0.9 * stable_dt(system.k, system.m)
    if not (math.isfinite(dt) and dt > 0.0):
        raise SanityError(f"--dt {dt} must be a positive number")
    warmup = args.warmup if args.warmup is not None else n + 5
    none = np.array([], dtype=np.int64)
    u = np.zeros(system.k.shape[0])
    u, v, warm_s = leapfrog(system.k, system.m, u, system.v0, dt, warmup, none)
    per_step = warm_s / warmup if warmup > 0 else 0.0
    wanted = math.ceil(args.min_wall / per_step) if per_step > 0.0 else args.min_steps
    steps = max(args.min_steps, min(args.max_steps, wanted))
    cpu0 = time.process_time()
    u, v, seconds = leapfrog(system.k, system.m, u, v, dt, steps, none)
    cpu_s = time.process_time() - cpu0
    ke0 = kinetic(system.v0, system.m)
    ke = kinetic(v, system.m)
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v)) and ke <= ENERGY_GROWTH * ke0):
        raise SanityError(
            f"the run is unstable at dt = {dt:.4e} s: kinetic energy {ke:.3e} J against {ke0:.3e} J at the start"
        )
    elements = system.elements.shape[0]
    seconds = max(seconds, 1e-9)
    k = system.k
    return {
        "case": f"cube{n}_scipy_csr",
        "elements": elements,
        "nodes": system.coords.shape[0],
        "dofs": k.shape[0],
        "dofs_total": system.k_full.shape[0],
        "nnz": int(k.nnz),
        "nnz_full": int(system.k_full.nnz),
        "csr_bytes": int(k.data.nbytes + k.indices.nbytes + k.indptr.nbytes),
        "warmup_steps": warmup,
        "steps": steps,
        "seconds": seconds,
        "steps_per_s": steps / seconds,
        "element_updates_per_s": elements * steps / seconds,
        "cpu_s": cpu_s,
        "dt_s": dt,
        "assembly_s": system.assembly_s,
        "peak_rss_bytes": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
        "threads": 1,
        "checks": checks,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "skfem": skfem.__version__,
    }


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--divisions", type=int, required=True, help="elements along each edge (n³ in all)")
    p.add_argument("--dt", type=float, help="time step (s); default 0.9 × a Gershgorin-stable step")
    p.add_argument("--warmup", type=int, help="untimed steps first (default n + 5, as the runner)")
    p.add_argument("--min-wall", type=float, default=2.0, help="time at least this long (s)")
    p.add_argument("--min-steps", type=int, default=10)
    p.add_argument("--max-steps", type=int, default=1_000_000)
    args = p.parse_args(argv)
    if args.divisions < 1:
        p.error(f"--divisions {args.divisions}: must be >= 1")
    if args.warmup is not None and args.warmup < 1:
        p.error(f"--warmup {args.warmup}: must be >= 1")
    if not (args.min_wall >= 0.0 and math.isfinite(args.min_wall)):
        p.error(f"--min-wall {args.min_wall}: must be >= 0")
    if not 1 <= args.min_steps <= args.max_steps:
        p.error(f"need 1 <= --min-steps ({args.min_steps}) <= --max-steps ({args.max_steps})")
    return args


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    try:
        out = run(args)
    except SanityError as e:
        print(f"csr_leapfrog.py: sanity check failed: {e}", file=sys.stderr)
        return 2
    print(json.dumps(out), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
