"""Cross-check: the layered shear column of docs/verification_references.md §W3, as a
finite-volume wave system in FiPy against dcfm's 1D hex8 column, both against the
closed-form transfer function.

Set-up (W3 layering): a soil layer H = 30 m, V_s = 300 m/s, ρ = 2000 kg/m³ over a rock
layer 30 m, V_s = 1500 m/s, ρ = 2500 kg/m³, on a rigid base whose horizontal motion is
prescribed (``test_transfer_function_peaks``) and on the elastic rock half-space of W3
(``test_half_space_transfer_function``: FiPy with the half-space's impedance at the base,
dcfm's reference free-field column and its 3D model with free-field sides and the
viscous-spring base under an incident pulse). Vertically propagating SH waves. Rayleigh damping C = αM + βK with
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

    ``base = "rigid"``: U = 1 on the base face, H = U(top). ``base = "half_space"``: the
    rock half-space below the base (ρ_r, c_r of the deepest layer) through its impedance,
    τ_0 = Z (U_0 − 2 U_I) with Z = iωρ_r c_r and U_I = 1 the upgoing wave (the exact 1D
    transmitting condition); the face value is extrapolated from the first cell,
    U_0 = (U_1 + h β U_I)/(1 + hβ/2) with β = Z/G*_1 (second order), and the face flux
    −Z(U_0 − 2U_I) = −γU_1 + 2γU_I, γ = Z/(1 + hβ/2), is added to the first cell's row;
    H = U(top)/(2 U_I), the surface over the half-space's outcrop motion.

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

    def __init__(self, base: str = "rigid"):
        import fipy

        self.base = base
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
        if base == "rigid":
            self.a.constrain(1.0, self.mesh.facesLeft)
            self.b.constrain(0.0, self.mesh.facesLeft)
        self.h0, self.g0 = dx[0], g[0]
        self.top = np.asarray(self.mesh.facesRight.value)
        self.mat0, self.rhs0 = self.assemble(0.0)
        mat1, rhs1 = self.assemble(1.0)
        self.mat1, self.rhs1 = mat1 - self.mat0, rhs1 - self.rhs0

    def assemble(self, w: float):
        """FiPy's matrix and right-hand side of the two coupled diffusion equations at
        angular frequency `w` (assembled only: FiPy's own solve of the diffusion terms
        alone would be singular on the half-space, whose base has no constraint)."""
        fp = self.fp
        a, b = self.a, self.b
        eq_a = fp.DiffusionTerm(coeff=self.g, var=a) - fp.DiffusionTerm(coeff=self.g * (w * BETA), var=b) == 0
        eq_b = fp.DiffusionTerm(coeff=self.g, var=b) + fp.DiffusionTerm(coeff=self.g * (w * BETA), var=a) == 0
        eq = eq_a & eq_b
        eq.cacheMatrix()
        eq.cacheRHSvector()
        eq._prepareLinearSystem(var=None, solver=None, boundaryConditions=(), dt=None)
        return eq.matrix.matrix.tocsr(), np.asarray(eq.RHSvector, dtype=float)

    def __call__(self, f: float) -> float:
        import scipy.sparse as sp
        import scipy.sparse.linalg as sla

        w = 2 * np.pi * f
        a, b = self.a, self.b
        # The coefficients are G and Gωβ, so FiPy's matrix and right-hand side are affine
        # in ω: assembled at ω = 0 and 1 once (in the constructor) and combined here.
        mat = self.mat0 + w * self.mat1
        rhs = self.rhs0 + w * self.rhs1
        inertia = self.rho * w**2 * self.volume
        mass_damping = self.rho * w * ALPHA * self.volume
        sources = sp.bmat([[sp.diags(inertia), sp.diags(mass_damping)], [sp.diags(-mass_damping), sp.diags(inertia)]])
        n = len(self.rho)
        system = (mat + sources).tolil()
        scale = 1.0
        if self.base == "half_space":
            _, vs, rho, _ = LAYERS[0]
            z = 1j * w * rho * vs
            beta = z / (self.g0 * (1 + 1j * w * BETA))
            gam = z / (1 + self.h0 * beta / 2)
            # Rows 0 (real part) and n (imaginary part) of the first cell: −γ U_1 + 2γ U_I.
            system[0, 0] -= gam.real
            system[0, n] += gam.imag
            system[n, 0] -= gam.imag
            system[n, n] -= gam.real
            rhs = rhs.copy()
            rhs[0] -= 2 * gam.real
            rhs[n] -= 2 * gam.imag
            scale = 0.5
        x = sla.spsolve(system.tocsc(), rhs)
        a.setValue(x[:n])
        b.setValue(x[n:])
        return scale * float(abs(a.faceValue.value[self.top][0] + 1j * b.faceValue.value[self.top][0]))


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
    record.describe(CASE, "The W3 layering on a rigid base with Rayleigh damping: FiPy finite volumes (frequency "
                    "domain) and dcfm's hex8 column (time domain, prescribed base) against the layer-matrix closed form. "
                    "Resonances ±2 %, peaks ±5 %.")
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


# ------------------------------------------------------------- elastic half-space (W3)

CASE_HS = "Layered shear column on an elastic half-space (W3 layering): free-field column and 3D model"
SRC_HS = "docs/verification_references.md §W3 (layer matrices on the half-space, Rayleigh damping)"


def test_half_space_transfer_function():
    """The same layering on the rock half-space: FiPy (impedance condition at the base),
    dcfm's reference free-field column and the 3D model with free-field sides and the
    viscous-spring base (W3 set-up, Rayleigh damping α, β in both layers), against the
    closed form H = U_s/(2 U_I). dcfm: an incident half-sine velocity pulse (0.02 s), 6 s
    of response; H = S(f) / (2 I(f)) with I the incident velocity at the same instants
    (the column's full-step velocity at tⁿ, the 3D nodes' V^{n−½} at tⁿ − Δt/2)."""
    from dcfm_reference import site

    record.describe(CASE_HS, "The W3 layering with Rayleigh damping (α 1.309 1/s, β 1.061e-3 s) in both layers on the "
                    "elastic rock half-space: FiPy finite volumes (frequency domain, impedance condition τ = iωρc(U − 2U_I) "
                    "at the base), dcfm's reference free-field column (transmitting base) and its 3D model (free-field "
                    "sides, viscous-spring base, incident SH pulse), against the layer-matrix closed form H = U_s/(2U_I). "
                    "Resonances ±2 %, peaks ±5 % (W3).")
    pulse = {"type": "half_sine", "amplitude": 0.01, "period": 0.02}
    case = dcfm.Case.from_dict(
        site.site_case({"definition": "incident", "quantity": "velocity", "x": pulse}, end=6.0, damping=(ALPHA, BETA), title="W3 layering, damped, pulse"),
        label="w3_half_space",
    )
    centre = int(case.nodes_of("centre")[0])
    corner = int(case.nodes_of("corner")[0])
    run = case.run(nodes=[centre, corner], elements=[], free_field=True, threads=1)
    dt = case.dt

    def incident(t):
        return np.where((t >= 0) & (t <= 0.02), 0.01 * np.sin(np.pi * np.clip(t, 0, 0.02) / 0.02), 0.0)

    ff = run.free_field
    histories = {
        "dcfm column": (ff["time"], ff["velocity"][:, -1, 0]),
        "dcfm 3D centre": (run.time - 0.5 * dt, run.velocity[:, 0, 0]),
        "dcfm 3D corner": (run.time - 0.5 * dt, run.velocity[:, 1, 0]),
    }

    def transfer(name):
        t, v = histories[name]
        inc = incident(t)
        return lambda f: abs(site.dtft(v, dt, f) / (2 * site.dtft(inc, dt, f)))

    def closed(f):
        return abs(site.layer_on_half_space(f, ALPHA, BETA)[0])

    f_grid = np.arange(0.5, 16.0, 0.1)
    ref = site.peaks(closed, f_grid, N_PEAKS)
    fv = FipyColumn(base="half_space")
    codes = {"FiPy": site.peaks(fv, f_grid, N_PEAKS)}
    for name in histories:
        codes[name] = site.peaks(transfer(name), f_grid, N_PEAKS)
    print("closed form", ref)
    for k, v in codes.items():
        print(k, v)
    rows = []
    for name, pk in codes.items():
        assert len(pk) == N_PEAKS, (name, pk)
        for j in range(N_PEAKS):
            rows.append(record.check(CASE_HS, f"{name}: resonance {j + 1} frequency (Hz)", ref[j][0], pk[j][0], 0.02, SRC_HS, FIPY))
            rows.append(record.check(CASE_HS, f"{name}: resonance {j + 1} peak |H|", ref[j][1], pk[j][1], 0.05, SRC_HS, FIPY))
    # dcfm against FiPy directly (same peaks, the two independent discretisations).
    for j in range(N_PEAKS):
        rows.append(record.check(CASE_HS, f"dcfm column vs FiPy: resonance {j + 1} peak |H|", codes["FiPy"][j][1], codes["dcfm column"][j][1], 0.05, "FiPy finite volumes (this test)", FIPY))
    f_plot = np.linspace(0.2, 16.0, 160)
    record.series(
        CASE_HS,
        "|H(f)| = surface / outcrop of the half-space",
        "frequency (Hz)",
        "|H|",
        f_plot,
        {
            "closed form": np.abs(site.layer_on_half_space(f_plot, ALPHA, BETA)),
            "FiPy": [fv(f) for f in f_plot],
            "dcfm column": [transfer("dcfm column")(f) for f in f_plot],
            "dcfm 3D centre": [transfer("dcfm 3D centre")(f) for f in f_plot],
        },
    )
    assert not record.failures(rows), record.failures(rows)
