"""Cross-check: the layered shear column of docs/verification_references.md §W3, as a
finite-volume wave system in FiPy against dcfm's 1D hex8 column, both against the
closed-form transfer function.

Set-up (W3 layering): a soil layer H = 30 m, V_s = 300 m/s, ρ = 2000 kg/m³ over a rock
layer 30 m, V_s = 1500 m/s, ρ = 2500 kg/m³, on a rigid base whose horizontal motion is
prescribed (the elastic half-space of W3 needs the absorbing base of the seismic
boundaries: pending). Vertically propagating SH waves. Rayleigh damping C = αM + βK with
α = 1.309 1/s, β = 1.061e-3 s (ξ = 5 % at 2.5 and 12.5 Hz); in the continuum
ρ(ü + α u̇) = ∂z(G(u + β u̇)_z).

Closed form: in each layer U'' + k²U = 0 with k² = ρ(ω² − iωα)/(G(1 + iωβ)); the
layer matrices [[cos kd, sin kd/(G*k)], [−G*k sin kd, cos kd]] carry (U, τ) from the base
(U = 1) to the free surface (τ = 0); H(f) = U(surface)/U(base) (Kramer 1996, §7.2, with
Rayleigh instead of hysteretic damping).

FiPy: the same equation in the frequency domain (the Helmholtz form of the wave system),
real and imaginary parts as two coupled cell variables, 0.5 m cells in the soil and 1 m
in the rock, U = 1 at the base, zero flux at the top; |H| is swept and each peak refined
with a bounded scalar search (see ``FipyColumn`` for how the ω² term enters).

dcfm: a column of hex8 (1 × 1 m in plan; 1 m elements in the soil, 2 m in the rock), y
and z fixed everywhere, a Hann velocity pulse (0.04 s) prescribed at the base, 12 s of
response; H = DTFT(v_surface)/DTFT(v_base), its peaks refined the same way.

Tolerances (W3): resonance frequencies ±2 %, damped peak amplitudes ±5 %.
"""

from __future__ import annotations

import os

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

os.environ.setdefault("FIPY_SOLVERS", "scipy")

import dcfm  # noqa: E402
from dcfm_reference import record  # noqa: E402

CASE = "Layered shear column transfer function (W3 layering, rigid base)"
SRC = "docs/verification_references.md §W3 (layer matrices, Rayleigh damping)"
FIPY = "FiPy 4.0.3 (finite volumes, frequency domain)"
LAYERS = [  # bottom to top: thickness (m), V_s (m/s), ρ (kg/m³), element size in dcfm (m)
    (30.0, 1500.0, 2500.0, 2.0),
    (30.0, 300.0, 2000.0, 1.0),
]
ALPHA, BETA = 1.309, 1.061e-3
N_PEAKS = 3


def closed_form(f: np.ndarray) -> np.ndarray:
    """H(f) = U(surface)/U(base) of the damped layered column on a rigid base."""
    w = 2 * np.pi * np.atleast_1d(np.asarray(f, dtype=float))
    out = np.empty(w.shape, dtype=complex)
    for i, om in enumerate(w):
        m = np.eye(2, dtype=complex)
        for d, vs, rho, _ in LAYERS:
            gstar = rho * vs**2 * (1 + 1j * om * BETA)
            k = np.sqrt(rho * (om**2 - 1j * om * ALPHA) / gstar)
            layer = np.array(
                [[np.cos(k * d), np.sin(k * d) / (gstar * k)], [-gstar * k * np.sin(k * d), np.cos(k * d)]]
            )
            m = layer @ m
        # [U_s, τ_s] = m [1, τ_b], τ_s = 0 → τ_b = −m10/m11.
        tau_b = -m[1, 0] / m[1, 1]
        out[i] = m[0, 0] + m[0, 1] * tau_b
    return out


class FipyColumn:
    """|H(f)| of the column by finite volumes (FiPy), one solve per frequency.

    FiPy discretises the flux terms: for each frequency the coupled diffusion operators
    of the real part a and the imaginary part b (coefficient G on the diagonal blocks,
    ∓Gωβ on the off-diagonal ones, harmonic face averages of G between the layers, a = 1
    and b = 0 on the base face, no flux at the top) are assembled by FiPy. The inertia and
    mass-damping terms ρω²(a, b) and ρωα(b, −a) are added to that matrix as cell sources
    (coefficient × cell volume, FiPy's sign convention), then the system is solved with
    scipy. They are not given to FiPy as ``ImplicitSourceTerm``s because FiPy deliberately
    moves a source that weakens diagonal dominance — a positive ρω², which is what makes a
    wave equation a wave equation — to the right-hand side, evaluated at the previous
    iterate, which would need sweeps that diverge above the first resonance.
    """

    def __init__(self):
        import fipy

        self.fp = fipy
        dx, rho, g = [], [], []
        for d, vs, r, _ in LAYERS:
            h = 0.5 if vs < 1000 else 1.0
            n = int(round(d / h))
            dx += [d / n] * n
            rho += [r] * n
            g += [r * vs**2] * n
        self.mesh = fipy.Grid1D(dx=np.array(dx))
        self.rho = np.array(rho)
        self.volume = np.asarray(self.mesh.cellVolumes)
        self.g = fipy.CellVariable(mesh=self.mesh, value=np.array(g)).harmonicFaceValue
        self.a = fipy.CellVariable(mesh=self.mesh, value=0.0)
        self.b = fipy.CellVariable(mesh=self.mesh, value=0.0)
        self.a.constrain(1.0, self.mesh.facesLeft)
        self.b.constrain(0.0, self.mesh.facesLeft)
        self.top = np.asarray(self.mesh.facesRight.value)

    def __call__(self, f: float) -> float:
        import scipy.sparse as sp
        import scipy.sparse.linalg as sla

        fp = self.fp
        w = 2 * np.pi * f
        a, b = self.a, self.b
        eq_a = fp.DiffusionTerm(coeff=self.g, var=a) - fp.DiffusionTerm(coeff=self.g * (w * BETA), var=b) == 0
        eq_b = fp.DiffusionTerm(coeff=self.g, var=b) + fp.DiffusionTerm(coeff=self.g * (w * BETA), var=a) == 0
        eq = eq_a & eq_b
        eq.cacheMatrix()
        eq.cacheRHSvector()
        eq.solve()  # assembles the matrix and right-hand side (the solution is replaced below)
        mat = eq.matrix.matrix.tocsr()
        rhs = np.asarray(eq.RHSvector, dtype=float)
        inertia = self.rho * w**2 * self.volume
        mass_damping = self.rho * w * ALPHA * self.volume
        sources = sp.bmat([[sp.diags(inertia), sp.diags(mass_damping)], [sp.diags(-mass_damping), sp.diags(inertia)]])
        x = sla.spsolve((mat + sources).tocsc(), rhs)
        n = len(self.rho)
        a.setValue(x[:n])
        b.setValue(x[n:])
        return float(abs(a.faceValue.value[self.top][0] + 1j * b.faceValue.value[self.top][0]))


def peaks(func, f_grid: np.ndarray, n: int) -> list[tuple[float, float]]:
    """The first ``n`` local maxima of ``func`` on the grid, refined by a bounded search."""
    vals = np.array([func(f) for f in f_grid])
    idx = [i for i in range(1, len(vals) - 1) if vals[i] > vals[i - 1] and vals[i] >= vals[i + 1]][:n]
    out = []
    for i in idx:
        res = minimize_scalar(lambda f: -func(f), bounds=(f_grid[i - 1], f_grid[i + 1]), method="bounded", options={"xatol": 1e-5})
        out.append((float(res.x), float(-res.fun)))
    return out


def column_case() -> dcfm.Case:
    blocks, materials, regions = [], {}, []
    z = 0.0
    for i, (d, vs, rho, h) in enumerate(LAYERS):
        name = f"layer{i}"
        blocks.append({"name": name, "origin": [0.0, 0.0, z], "size": [1.0, 1.0, d], "divisions": [1, 1, int(round(d / h))]})
        materials[name] = {"model": "elastic", "young": 2 * rho * vs**2 * 1.25, "poisson": 0.25, "density": rho}
        regions.append({"name": name, "material": name, "integration": "full"})
        z += d
    fixed = [{"set": f"layer{i}", "dofs": "yz"} for i in range(len(LAYERS))]
    return dcfm.Case.from_dict(
        {
            "title": "layered shear column",
            "time": {"end": 12.0},
            "mesh": {"blocks": blocks},
            "materials": materials,
            "regions": regions,
            "damping": {"alpha": ALPHA, "beta": BETA},
            "boundary": {
                "fixed": fixed,
                "prescribed": [
                    {
                        "set": "layer0.zmin",
                        "dof": "x",
                        "kind": "velocity",
                        "history": {"type": "sine_squared", "amplitude": 0.1, "period": 0.04},
                    }
                ],
            },
        },
        label="layered_column",
    )


@pytest.fixture(scope="module")
def dcfm_transfer():
    case = column_case()
    top = int(case.nodes_of("layer1.zmax")[0])
    base = int(case.nodes_of("layer0.zmin")[0])
    run = case.run(nodes=[base, top], elements=[], threads=1)
    v = run.velocity[:, :, 0]
    t = run.time - 0.5 * case.dt  # half-step velocities

    def h(f: float) -> complex:
        e = np.exp(-2j * np.pi * f * t)
        return complex(e @ v[:, 1] / (e @ v[:, 0]))

    return h


def test_transfer_function_peaks(dcfm_transfer):
    f_grid = np.arange(0.5, 20.0, 0.1)
    ref = peaks(lambda f: abs(closed_form(f)[0]), f_grid, N_PEAKS)
    fv = FipyColumn()
    fip = peaks(fv, f_grid, N_PEAKS)
    dc = peaks(lambda f: abs(dcfm_transfer(f)), f_grid, N_PEAKS)
    print("closed form", ref, "\nFiPy", fip, "\ndcfm", dc)
    assert len(ref) == len(fip) == len(dc) == N_PEAKS
    rows = []
    for j in range(N_PEAKS):
        for code, (f, amp) in [("FiPy", fip[j]), ("dcfm", dc[j])]:
            rows.append(record.check(CASE, f"{code}: resonance {j + 1} frequency (Hz)", ref[j][0], f, 0.02, SRC, FIPY))
            rows.append(record.check(CASE, f"{code}: resonance {j + 1} peak |H|", ref[j][1], amp, 0.05, SRC, FIPY))
    f_plot = np.linspace(0.2, 20.0, 200)
    record.series(
        CASE,
        "|H(f)| = surface / base motion",
        "frequency (Hz)",
        "|H|",
        f_plot,
        {
            "closed form": np.abs(closed_form(f_plot)),
            "FiPy": [fv(f) for f in f_plot],
            "dcfm": [abs(dcfm_transfer(f)) for f in f_plot],
        },
    )
    assert not record.failures(rows), record.failures(rows)
