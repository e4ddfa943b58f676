"""Cross-checks against OpenSeesPy 3.7 (stdBrick, explicit central difference; zeroLength
elastic–perfectly-plastic friction): the same 3D elastic wave problem and a sliding-block
problem, each code against the closed form, and the wall-time ratio.

1. **P pulse up a hex8 column** — ``cases/w01_p_pulse.toml`` (docs/
   verification_references.md §W1): 1 × 1 × 200 m, 200 fully integrated hex8, lateral
   rollers, base velocity 0.1 sin(πt/0.02) m/s, free top. OpenSees: the same nodes and
   connectivity as ``stdBrick`` elements (2×2×2 Gauss) with the row-sum lumped mass
   ρV/8 per element corner on the nodes (``dcfm_reference.opensees.add_bricks``),
   ``ExplicitDifference`` (central difference in velocity form) with a diagonal system,
   the base displacement ∫v dt imposed through ``sp`` on a ``Path`` series sampled at the
   step, the same Δt.
   Closed form (d'Alembert): incident stress ρ c_p v0 at mid-height, net displacement
   2v0T/π, free-end velocity 2v0. Tolerances of W1: ±3 %, ±1 %, 2.00 ± 0.06.
2. **Newmark sliding block, rectangular pulse** (§W7): base acceleration 0.5 g for
   0.2 s, friction coefficient 0.2. dcfm: the W7 model as a case (an elastic plate on a
   base, point-to-point contact, Coulomb friction). OpenSees: a mass on a zeroLength
   element with an elastic–perfectly-plastic material whose yield force is μ m g, under
   ``UniformExcitation`` (relative motion), Newmark average acceleration. Closed form:
   slip V²/(2Ng)(1 − N/A) = 0.14715 m, ending A t0/N = 0.5 s after the pulse start;
   tolerance ±3 % (W7).

Wall times: both codes run the same number of steps of the wave problem without
recording (one thread for dcfm, OpenSees is serial); the ratio goes to the performance
table. (The sliding-block models differ in size — a meshed plate with contact against
one spring — so their times are not compared.)
"""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

import dcfm
from dcfm_reference import record
from dcfm_reference.opensees import add_bricks, opensees
from dcfm_reference.paths import CASES

OPS_VERSION = "OpenSeesPy 3.7.1"
WAVE = "3D hex column, P pulse (dcfm and OpenSees)"
BLOCK = "Newmark sliding block (dcfm and OpenSees)"
SRC_W1 = "docs/verification_references.md §W1 (d'Alembert)"
SRC_W7 = "docs/verification_references.md §W7 (Newmark 1965)"
V0, T = 0.1, 0.02
E, NU, RHO = 20e9, 0.25, 2700.0
G = 9.81


@pytest.fixture(scope="module")
def ops():
    return opensees()


def p_wave_speed() -> float:
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    return math.sqrt((lam + 2 * mu) / RHO)


def base_displacement(t: np.ndarray) -> np.ndarray:
    """∫ v0 sin(πt/T) dt: v0 T/π (1 − cos(πt/T)) during the pulse, 2 v0 T/π after."""
    tt = np.minimum(t, T)
    return V0 * T / math.pi * (1.0 - np.cos(math.pi * tt / T))


def build_opensees_column(ops, case: dcfm.Case) -> None:
    """The case's mesh as stdBrick elements with lateral rollers."""
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 3)
    add_bricks(ops, case.coords, case.elements, E, NU, RHO)
    for i in range(case.n_nodes):
        ops.fix(i + 1, 1, 1, 0)  # lateral rollers; the base z comes from sp below


def opensees_column_run(ops, case: dcfm.Case, record_every_step: bool):
    dt = case.dt
    n_steps = case.n_steps
    build_opensees_column(ops, case)
    base = case.nodes_of("col.zmin").tolist()
    # Imposed base displacement: remove the z fixity and impose it through sp.
    t = np.arange(n_steps + 2) * dt
    ops.timeSeries("Path", 1, "-dt", dt, "-values", *base_displacement(t).tolist())
    ops.pattern("Plain", 1, 1)
    for i in base:
        ops.sp(i + 1, 3, 1.0)
    ops.constraints("Transformation")
    ops.numberer("Plain")
    ops.system("Diagonal")
    ops.algorithm("Linear")
    ops.integrator("ExplicitDifference")
    ops.analysis("Transient")
    if not record_every_step:
        t0 = time.perf_counter()
        ok = ops.analyze(n_steps, dt)
        wall = time.perf_counter() - t0
        assert ok == 0
        return wall
    mid_e, top_n, mid_n = 101, 801, 401  # element 100, node 800 (top), node 400 (mid)
    times, s_mid, v_top, u_mid = [], [], [], []
    for _ in range(n_steps):
        assert ops.analyze(1, dt) == 0
        times.append(ops.getTime())
        s = np.asarray(ops.eleResponse(mid_e, "stresses")).reshape(8, 6)
        s_mid.append(s[:, 2].mean())
        v_top.append(ops.nodeVel(top_n, 3))
        u_mid.append(ops.nodeDisp(mid_n, 3))
    return np.array(times), np.array(s_mid), np.array(v_top), np.array(u_mid)


def test_p_pulse_column(ops):
    case = dcfm.Case.from_file(CASES / "w01_p_pulse.toml")
    c = p_wave_speed()
    h = 200.0
    run = case.run(nodes=[400, 800], elements=[100], threads=1)
    t = run.time
    s_mid = -run.stress[:, 0, 2]  # compression pulse: −σ_zz
    u_mid = run.displacement[:, 0, 2]
    v_top = run.velocity[:, 1, 2]
    ot, os_mid, ov_top, ou_mid = opensees_column_run(ops, case, record_every_step=True)
    os_mid = -os_mid
    incident = RHO * c * V0
    net = 2 * V0 * T / math.pi
    window = t <= 1.2 * h / 2 / c + T  # before the top reflection returns to mid-height
    owindow = ot <= 1.2 * h / 2 / c + T
    u_after = t <= h / c  # after the pulse passed mid-height, before the reflection
    ou_after = ot <= h / c
    rows = []
    for code, peak, net_u, vtop in [
        ("dcfm", s_mid[window].max(), u_mid[u_after][-1], np.abs(v_top).max()),
        ("OpenSees", os_mid[owindow].max(), ou_mid[ou_after][-1], np.abs(ov_top).max()),
    ]:
        rows.append(record.check(WAVE, f"{code}: incident stress ρ c_p v0 (Pa)", incident, peak, 0.03, SRC_W1, OPS_VERSION))
        rows.append(record.check(WAVE, f"{code}: net displacement 2v0T/π (m)", net, net_u, 0.01, SRC_W1, OPS_VERSION))
        rows.append(record.check(WAVE, f"{code}: free-end velocity / v0", 2.0, vtop / V0, 0.06, SRC_W1, OPS_VERSION, absolute=True))
    # The two codes integrate the same discrete system: their mid-height displacement
    # histories agree far inside the tolerances above.
    n = min(len(u_mid) - 1, len(ou_mid))
    diff = np.abs(u_mid[1 : n + 1] - ou_mid[:n]).max() / net
    rows.append(record.check(WAVE, "max |u_dcfm − u_OpenSees| at mid-height / net displacement", 0.0, diff, 1e-6, "same mesh, element, mass and scheme", OPS_VERSION, absolute=True))
    record.series(
        WAVE,
        "displacement at z = 100 m",
        "time (s)",
        "displacement (m)",
        t[1 : n + 1],
        {
            "dcfm": u_mid[1 : n + 1],
            "OpenSees": ou_mid[:n],
            "d'Alembert": base_displacement(np.maximum(t[1 : n + 1] - 100.0 / c, 0.0)),
        },
    )
    # Wall time of the same steps without recording.
    sim = case.start()
    t0 = time.perf_counter()
    sim.step(case.n_steps, threads=1)
    dcfm_wall = time.perf_counter() - t0
    ops_wall = opensees_column_run(ops, case, record_every_step=False)
    for code, wall, threads in [("dcfm", dcfm_wall, 1), ("OpenSees", ops_wall, 1)]:
        record.performance(
            {
                "label": f"column200 {code}",
                "problem": "W1 P column, 200 hex8 (full integration)",
                "code": code,
                "elements": case.n_elements,
                "steps": case.n_steps,
                "threads": threads,
                "wall_s": wall,
                "element_updates_per_s": case.n_elements * case.n_steps / wall,
            }
        )
    print(f"column: dcfm {dcfm_wall:.3f} s, OpenSees {ops_wall:.3f} s, ratio {ops_wall / dcfm_wall:.1f}")
    assert not record.failures(rows), record.failures(rows)


def newmark_case() -> dcfm.Case:
    """W7's rectangular-pulse model as a case (see verification/src/cases/w07_newmark_block.rs)."""
    plate = 0.02
    return dcfm.Case.from_dict(
        {
            "title": "W7 Newmark block, rectangular pulse",
            "time": {"end": 0.85},
            "mesh": {
                "blocks": [
                    {"name": "base", "origin": [0.0, 0.0, 0.0], "size": [2.0, 2.0, 1.0], "divisions": [2, 2, 1]},
                    {"name": "top", "origin": [0.0, 0.0, 1.0], "size": [2.0, 2.0, plate], "divisions": [2, 2, 1]},
                ],
                "split": [["base", "top"]],
            },
            "materials": {
                "base": {"model": "elastic", "young": 1e6, "poisson": 0.25, "density": 1000.0},
                "plate": {"model": "elastic", "young": 1e8, "poisson": 0.0, "density": 1000.0 / (4 * plate)},
            },
            "regions": [
                {"name": "base", "material": "base", "integration": "full"},
                {"name": "top", "material": "plate", "integration": "full"},
            ],
            "boundary": {
                "fixed": [{"set": "base", "dofs": "yz"}],
                "prescribed": [
                    {
                        "set": "base",
                        "dof": "x",
                        "kind": "acceleration",
                        "history": {"type": "pulse", "amplitude": 0.5 * G, "duration": 0.2, "start": 0.05},
                    }
                ],
            },
            "loads": {
                "gravity": {
                    "acceleration": [0.0, 0.0, -G],
                    "history": {"type": "table", "times": [0.0, 0.01], "values": [0.0, 1.0]},
                }
            },
            "damping": {"beta": 4.1e-4},
            "interfaces": [
                {
                    "name": "newmark",
                    "surface_a": "top-base",
                    "surface_b": "base-top",
                    "mu_s": 0.2,
                    "mu_d": 0.2,
                    "cohesion": 0.0,
                    "slip_threshold": 100.0,
                }
            ],
        },
        label="newmark_block",
    )


def opensees_newmark(ops, a: float, t0: float, n: float, ts: float, dt: float, t_end: float):
    """Rigid block on an elastic–perfectly-plastic friction spring under a base pulse:
    returns (times, slip)."""
    m = 1000.0
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(1, 0.0)
    ops.node(2, 0.0)
    ops.fix(1, 1)
    ops.mass(2, m)
    k = 1e12  # stiff: the elastic part of the spring is ~1e-9 m
    ops.uniaxialMaterial("ElasticPP", 1, k, n * m * G / k)
    ops.element("zeroLength", 1, 1, 2, "-mat", 1, "-dir", 1)
    steps = int(round(t_end / dt))
    tt = np.arange(steps + 2) * dt
    ag = np.where((tt >= ts) & (tt < ts + t0), a * G, 0.0)
    ops.timeSeries("Path", 1, "-dt", dt, "-values", *ag.tolist())
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    times, slip = [], []
    for _ in range(steps):
        assert ops.analyze(1, dt) == 0
        times.append(ops.getTime())
        slip.append(ops.nodeDisp(2, 1))
    return np.array(times), np.abs(np.array(slip))


def newmark_slip(a: float, t0: float, n: float, tau: np.ndarray) -> np.ndarray:
    """Newmark's rigid-plastic slip τ after the pulse start (docs/verification_references.md §W7)."""
    tau = np.asarray(tau, dtype=float)
    rise = 0.5 * (a - n) * G * np.minimum(np.maximum(tau, 0.0), t0) ** 2
    s = np.clip(tau, t0, a * t0 / n) - t0
    return np.where(tau <= t0, rise, 0.5 * (a - n) * G * t0**2 + (a - n) * G * t0 * s - 0.5 * n * G * s**2)


def slip_end(t: np.ndarray, slip: np.ndarray) -> float:
    """When the slip settles: the first time from which it stays within 1e-6 of its final
    value (the elastic parts of both models ring at amplitudes far below that; the slip
    approaches its end parabolically, so the 1e-6 band costs ≈ 0.4 ms here)."""
    away = np.nonzero(np.abs(slip - slip[-1]) > 1e-6 * abs(slip[-1]))[0]
    return float(t[away[-1] + 1])


def test_newmark_block(ops):
    a, t0, n, ts = 0.5, 0.2, 0.2, 0.05
    slip_ref = (a * G * t0) ** 2 / (2 * n * G) * (1 - n / a)
    assert abs(slip_ref - 0.14715) < 5e-5
    end_ref = a * t0 / n
    case = newmark_case()
    top = case.nodes_of("top").tolist()
    base0 = int(case.nodes_of("base")[0])
    mass = case.mass
    run = case.run(nodes=top + [base0], elements=[], threads=1)
    mt = mass[top]
    x_plate = (run.displacement[:, : len(top), 0] * mt).sum(axis=1) / mt.sum()
    slip = np.abs(x_plate - run.displacement[:, -1, 0])
    t = run.time
    d_end = slip_end(t, slip) - ts
    ot, oslip = opensees_newmark(ops, a, t0, n, ts, 1e-4, 0.85)
    o_end = slip_end(ot, oslip) - ts
    rows = []
    for code, s_final, s_end in [("dcfm", slip[-1], d_end), ("OpenSees", oslip[-1], o_end)]:
        rows.append(record.check(BLOCK, f"{code}: slip V²/(2Ng)(1 − N/A) (m)", slip_ref, s_final, 0.03, SRC_W7, OPS_VERSION))
        rows.append(record.check(BLOCK, f"{code}: slip ends A t0/N after the pulse start (s)", end_ref, s_end, 0.03, SRC_W7, OPS_VERSION))
    record.series(
        BLOCK,
        "slip of the block on the base",
        "time (s)",
        "|slip| (m)",
        ot[::20],
        {
            "dcfm": np.interp(ot[::20], t, slip),
            "OpenSees": oslip[::20],
            "Newmark (closed form)": newmark_slip(a, t0, n, ot[::20] - ts),
        },
    )
    assert not record.failures(rows), record.failures(rows)
