"""The scipy CSR leapfrog baseline of the throughput runner (``benchmarks/python/
csr_leapfrog.py``, issue 11) on tiny cubes: its JSON record, its sanity checks (they must
refuse a broken K and an unstable step), and the leapfrog against closed forms —

- a free cube started at a uniform velocity translates rigidly: Uⁿ = n Δt V₀ at every DOF,
  V stays V₀ (K annihilates translations);
- with the base fixed, the discrete energy of the central difference,
  E^{n+½} = ½ V^{n+½}ᵀ M V^{n+½} + ½ Uⁿᵀ K U^{n+1}, is conserved exactly (K symmetric):
  E^{n+½} − E^{n−½} = ½ (V^{n+½} + V^{n−½})ᵀ M (V^{n+½} − V^{n−½}) + ½ Uⁿᵀ K (U^{n+1} − U^{n−1})
  = −½ (U^{n+1} − U^{n−1})ᵀ K Uⁿ + ½ Uⁿᵀ K (U^{n+1} − U^{n−1}) = 0; an explicit Euler
  step breaks it (shown, so that the check can fail);
- and it is dcfm's cube: the script's mesh is dcfm's box mesh node for node, and after the
  same steps at dcfm's Δt its displacements are dcfm's fully integrated ones to round-off.
"""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys

import numpy as np
import pytest
import scipy
import skfem

import dcfm
from dcfm_reference.leapfrog import leapfrog
from dcfm_reference.paths import ROOT

SCRIPT = ROOT / "benchmarks" / "python" / "csr_leapfrog.py"


def load_script():
    spec = importlib.util.spec_from_file_location("csr_leapfrog", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # dataclasses look their module up
    spec.loader.exec_module(mod)
    return mod


csr = load_script()
NONE = np.array([], dtype=np.int64)
# The cube of benchmarks/src/cube.rs (CubeSpec::new, CubeSpec::model), written out here
# rather than taken from the script, so that a script that drifts from it fails.
EDGE, YOUNG, POISSON, DENSITY = 10.0, 20e9, 0.25, 2700.0
VELOCITY = [0.1, 0.05, -0.02]


def run_script(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, str(SCRIPT), *args], capture_output=True, text=True, timeout=120
    )


def dcfm_cube(n: int) -> dcfm.Case:
    return dcfm.Case.from_dict(
        {
            "title": f"cube{n} full",
            "time": {"end": 1.0},
            "mesh": {"blocks": [{"name": "rock", "origin": [0.0, 0.0, 0.0], "size": [EDGE] * 3, "divisions": [n, n, n]}]},
            "materials": {"rock": {"model": "elastic", "young": YOUNG, "poisson": POISSON, "density": DENSITY}},
            "regions": [{"name": "rock", "material": "rock", "integration": "full"}],
            "boundary": {"fixed": [{"set": "rock.zmin", "dofs": "xyz"}]},
            "initial": {"velocity": [{"set": "rock", "value": VELOCITY}]},
        },
        label=f"cube{n}_full",
    )


def test_record_of_a_tiny_cube():
    out = run_script("--divisions", "3", "--warmup", "3", "--min-wall", "0", "--min-steps", "5", "--max-steps", "5")
    assert out.returncode == 0, out.stderr
    lines = [l for l in out.stdout.splitlines() if l.strip()]
    assert len(lines) == 1, out.stdout
    r = json.loads(lines[0])
    assert r["case"] == "cube3_scipy_csr"
    assert (r["elements"], r["nodes"]) == (27, 64)
    # 4 × 4 nodes of the base fixed: 48 free nodes.
    assert (r["dofs"], r["dofs_total"]) == (144, 192)
    assert r["nnz"] < r["nnz_full"] <= 81 * 192
    assert (r["warmup_steps"], r["steps"], r["threads"]) == (3, 5, 1)
    assert r["element_updates_per_s"] == pytest.approx(27 * 5 / r["seconds"], rel=1e-12)
    assert r["steps_per_s"] == pytest.approx(5 / r["seconds"], rel=1e-12)
    assert r["dt_s"] > 0 and r["assembly_s"] > 0 and r["peak_rss_bytes"] > 1 << 20
    assert r["checks"]["symmetry"] <= csr.SYMMETRY_TOL
    assert r["checks"]["rigid"] <= csr.RIGID_TOL
    assert r["checks"]["mass"] <= csr.MASS_TOL
    assert (r["numpy"], r["scipy"], r["skfem"]) == (np.__version__, scipy.__version__, skfem.__version__)


def test_mesh_is_dcfms_box_mesh():
    case = dcfm_cube(3)
    coords, elements = csr.cube_mesh(3)
    assert np.array_equal(coords, np.asarray(case.coords))
    assert np.array_equal(elements, np.asarray(case.elements))


def test_same_displacements_as_dcfm():
    """The script's system stepped at dcfm's Δt gives dcfm's displacements (full
    integration, base fixed): the same cube, material, load and start."""
    n, steps = 3, 12
    case = dcfm_cube(n)
    sim = case.start(dt=case.dt)
    sim.step(steps, threads=1)
    u_dcfm = np.asarray(sim.displacement)
    s = csr.assemble(n)
    u, _, _ = leapfrog(s.k, s.m, np.zeros(s.k.shape[0]), s.v0, case.dt, steps, NONE)
    full = np.zeros(s.k_full.shape[0])
    full[s.free] = u
    u_sp = full[s.dofs]
    scale = np.abs(u_dcfm).max()
    assert scale > 0
    assert np.abs(u_sp - u_dcfm).max() <= 1e-9 * scale


def test_free_cube_translates_rigidly():
    s = csr.assemble(3, fix_base=False)
    assert s.k.shape == s.k_full.shape
    dt, steps = 0.9 * csr.stable_dt(s.k, s.m), 50
    u, v, _ = leapfrog(s.k, s.m, np.zeros(s.k.shape[0]), s.v0, dt, steps, NONE)
    exact = steps * dt * s.v0
    assert np.abs(u - exact).max() <= 1e-10 * np.abs(exact).max()
    assert np.abs(v - s.v0).max() <= 1e-10 * np.abs(s.v0).max()


def energy_drift(s, dt: float, steps: int, explicit_euler: bool = False) -> float:
    """max |E^{n+½} − E^{½}| / E^{½} over the steps."""
    u = np.zeros(s.k.shape[0])
    v = s.v0.copy()
    e0 = None
    drift = 0.0
    for _ in range(steps):
        if explicit_euler:
            u_next = u + dt * v
            v = v - dt * (s.k @ u) / s.m
        else:
            u_next, v, _ = leapfrog(s.k, s.m, u, v, dt, 1, NONE)
        e = 0.5 * np.dot(s.m * v, v) + 0.5 * np.dot(u, s.k @ u_next)
        u = u_next
        e0 = e if e0 is None else e0
        drift = max(drift, abs(e - e0) / e0)
    return drift


def test_discrete_energy_is_conserved():
    s = csr.assemble(3)
    dt = 0.9 * csr.stable_dt(s.k, s.m)
    assert energy_drift(s, dt, 300) <= 1e-10
    # The check sees a wrong scheme.
    assert energy_drift(s, dt, 300, explicit_euler=True) > 1e-2


def test_sanity_checks_refuse_a_broken_system():
    s = csr.assemble(2)
    assert csr.sanity_checks(s, 2)["rigid"] <= csr.RIGID_TOL
    k = s.k_full.tolil()
    k[0, 1] += 1e-6 * abs(s.k_full).max()
    s.k_full = k.tocsr()
    with pytest.raises(csr.SanityError, match="not symmetric"):
        csr.sanity_checks(s, 2)
    s = csr.assemble(2)
    k = s.k_full.tolil()
    k[0, 0] *= 1.0 + 1e-6
    s.k_full = k.tocsr()
    with pytest.raises(csr.SanityError, match="rigid translation x"):
        csr.sanity_checks(s, 2)
    s = csr.assemble(2)
    s.m_full = 1.01 * s.m_full
    with pytest.raises(csr.SanityError, match="lumped mass"):
        csr.sanity_checks(s, 2)
    with pytest.raises(csr.SanityError, match="expected 3³"):
        csr.sanity_checks(csr.assemble(2), 3)


def test_unstable_step_fails_loudly():
    s = csr.assemble(2)
    dt = 3.0 * csr.stable_dt(s.k, s.m)
    out = run_script("--divisions", "2", "--dt", repr(dt), "--warmup", "40", "--min-wall", "0", "--min-steps", "40", "--max-steps", "40")
    assert out.returncode == 2
    assert "unstable" in out.stderr and out.stdout == ""
