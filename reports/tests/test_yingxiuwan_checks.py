"""The Yingxiuwan physics checks read dcfm's two VTU layouts and fail when the physics is
broken: a penetrating contact node, a damage variable that decreases, a damaged volume
that drops, an anchor above its yield force, an interface whose state areas do not add up,
damage without plastic flow, an undamaged element beyond the yield surface, a damaged one
outside its current surface, a bolt in compression where the rock moved into the cavern,
concrete that comes apart."""

from __future__ import annotations

import base64
import json
import math
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest

REPORTS = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPORTS))
sys.path.insert(0, str(REPORTS / "tests"))

import lee_fenves as lf  # noqa: E402
import table1  # noqa: E402
import yingxiuwan_checks as yc  # noqa: E402

CASE = (
    """
[[regions]]
name = "rock"
material = "rock"
integration = "one_point"

[[regions]]
name = "lining"
material = "concrete"
integration = "full"

"""
    + table1.materials()
    + """
[[interfaces]]
name = "lr"

[[anchors.patterns]]
name = "bolts"
diameter = 0.025
yield_stress = 335e6
"""
)
YIELD = 335e6 * np.pi * 0.025**2 / 4
EA = 200e9 * np.pi * 0.025**2 / 4
FT_ROCK, FT_CONCRETE = 1.97e6, 1.30e6

# Two unit cubes in a row along x: element 0 rock (one-point), element 1 lining (full).
POINTS = np.array([[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0, 2.0)])
CONN = np.array([[0, 1, 4, 3, 6, 7, 10, 9], [1, 2, 5, 4, 7, 8, 11, 10]])
# A bolt from the face x = 0.1 (the cavern at x < 0) to x = 1.9, cut at the shared face.
BOLT = np.array([[0.1, 0.5, 0.5], [1.0, 0.5, 0.5], [1.0, 0.5, 0.5], [1.9, 0.5, 0.5]])
STRETCH = 1e-5  # u_x = STRETCH x: the face moves into the cavern relative to the deep end


def write_vtu(path: Path, points: dict[str, np.ndarray], cells: dict[str, np.ndarray],
              geometry: dict[str, np.ndarray], compressed: bool = False) -> None:
    """A VTU in the layout dcfm writes: base64 streams (header + data per array), or raw
    zlib blocks (VTK's compressed appended layout)."""
    blobs, offset = [], 0

    def decl(name: str, a: np.ndarray) -> str:
        nonlocal offset
        a = np.asarray(a)
        kind = "Int64" if a.dtype.kind == "i" else "Float64"
        data = a.astype("<i8" if kind == "Int64" else "<f8").tobytes()
        if compressed:
            block = zlib.compress(data)
            blob = np.array([1, len(data), 0, len(block)], "<u8").tobytes() + block
        else:
            blob = base64.b64encode(np.array([len(data)], "<u8").tobytes() + data)
        ncomp = a.shape[1] if a.ndim == 2 else 1
        text = f'<DataArray type="{kind}" Name="{name}" NumberOfComponents="{ncomp}" format="appended" offset="{offset}"/>'
        blobs.append(blob)
        offset += len(blob)
        return text

    if "types" not in geometry:  # dcfm writes the VTK type of every cell: hex8 12, line 3
        sizes = np.diff(np.concatenate([[0], np.asarray(geometry["offsets"]).ravel()]))
        geometry = {**geometry, "types": np.where(sizes == 8, 12, 3).astype(np.int64)}
    pd = "".join(decl(k, v) for k, v in points.items())
    cd = "".join(decl(k, v) for k, v in cells.items())
    pts = "".join(decl(k, v) for k, v in geometry.items() if k == "Points")
    cl = "".join(decl(k, v) for k, v in geometry.items() if k != "Points")
    compressor = ' compressor="vtkZLibDataCompressor"' if compressed else ""
    head = (
        f'<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64"{compressor}>\n'
        f'<UnstructuredGrid><Piece NumberOfPoints="{len(geometry["Points"])}" NumberOfCells="2"><PointData>{pd}</PointData>'
        f'<CellData>{cd}</CellData><Points>{pts}</Points><Cells>{cl}</Cells></Piece></UnstructuredGrid>\n'
        f'<AppendedData encoding="{"raw" if compressed else "base64"}">\n_'
    )
    path.write_bytes(head.encode() + b"".join(blobs) + b"\n</AppendedData>\n</VTKFile>\n")


def uniaxial(s: float) -> list[float]:
    return [s, 0.0, 0.0, 0.0, 0.0, 0.0]


def make_run(tmp: Path, *, gap: float = 0.0, dt_drop: float = 0.0, dv_drop: float = 0.0,
             anchor: float = 0.5, area_drift: float = 0.0, compressed: bool = False,
             no_flow: bool = False, undamaged_stress: float = 0.5, damaged_stress: float = 0.9,
             bolt_sign: float = 1.0, full_pvd: bool = False, fall: float = 0.0,
             bolt_plastic: float = 0.0, dt_gain: float = 0.1, kappa_still: bool = False) -> tuple[Path, Path]:
    """A run of two elements and one bolt over two frames (t = 0: the state at which the
    bolt is installed; t = 1 s). Element 0 (rock, one point) cracks in uniaxial tension,
    its stress at `damaged_stress` × f_t0 (effective), its plastic strain growing unless
    `no_flow`; element 1 (lining, full integration) stays undamaged in uniaxial tension,
    0.5 f_t0 at t = 0 and `undamaged_stress` × f_t0 at t = 1 s. The rock stretches by STRETCH along the bolt, whose force
    is `bolt_sign` × EA STRETCH, its plastic strain `bolt_plastic` at t = 1 s. The lining's far face (x = 2) moves down by `fall` at t = 1 s.
    The rock's d_t grows by `dt_gain` (κ_t = d_t, or κ_t left at its t = 0 value when
    `kappa_still`)."""
    run = tmp / "run"
    run.mkdir()
    case = tmp / "case.toml"
    case.write_text(CASE, encoding="utf-8")
    frames, bolts = [], []
    for k, t in enumerate([0.0, 1.0]):
        state = np.array([0.0, 2.0, 3.0] + [-1.0] * 9)
        gaps = np.array([0.0, gap if k == 1 else 0.0, 1e-4] + [0.0] * 9)
        u = np.zeros((12, 3))
        u[:, 0] = STRETCH * POINTS[:, 0] * k
        u[POINTS[:, 0] == 2.0, 2] -= fall * k
        d_t = np.array([0.1 + dt_gain * k - (dt_drop if k == 1 else 0.0), 0.0])
        kappa_t = np.array([0.1, 0.0]) if kappa_still else d_t
        d_c = np.zeros(2)
        # D of eq. (24) in uniaxial tension (r = 1, s = 1): d_t.
        stress = np.array([uniaxial((1.0 - d_t[0]) * damaged_stress * FT_ROCK),
                           uniaxial((undamaged_stress if k == 1 else 0.5) * FT_CONCRETE)])
        ep = np.zeros((2, 6))
        ep[0, 0] = 1e-5 * (1 if no_flow else 1 + k)
        write_vtu(run / f"f{k}.vtu",
                  {"displacement": u, "velocity": np.zeros((12, 3)), "contact_state": state, "contact_gap": gaps},
                  {"stress": stress, "damage": d_t, "damage_tension": d_t, "damage_compression": d_c,
                   "kappa_tension": kappa_t, "kappa_compression": d_c, "plastic_strain": ep,
                   "region": np.array([0.0, 1.0]), "active": np.array([1.0, 1.0])},
                  {"Points": POINTS, "connectivity": CONN.reshape(-1), "offsets": np.array([8, 16])}, compressed)
        frames.append(f'<DataSet timestep="{t}" file="f{k}.vtu"/>')
        force = np.full(2, bolt_sign * EA * STRETCH * k)
        write_vtu(run / f"a{k}.vtu", {}, {"axial_force": force, "plastic_strain": np.full(2, bolt_plastic * k),
                                          "bar": np.zeros(2)},
                  {"Points": BOLT, "connectivity": np.array([0, 1, 2, 3]), "offsets": np.array([2, 4])}, compressed)
        bolts.append(f'<DataSet timestep="{t}" file="a{k}.vtu"/>')
    collection = f'<VTKFile type="Collection"><Collection>{"".join(frames)}</Collection></VTKFile>'
    (run / ("full.pvd" if full_pvd else "case.pvd")).write_text(collection, encoding="utf-8")
    if full_pvd:  # compact frames in case.pvd: the checks must read full.pvd
        (run / "case.pvd").write_text('<VTKFile type="Collection"><Collection><DataSet timestep="0" file="compact.vtu"/>'
                                      '</Collection></VTKFile>', encoding="utf-8")
    (run / "anchors.pvd").write_text(f'<VTKFile type="Collection"><Collection>{"".join(bolts)}</Collection></VTKFile>',
                                     encoding="utf-8")
    header = ["time", "kinetic", "internal", "residual", "damaged_volume_total_lining", "anchor_bolts_max_force",
              "area_bonded_lr", "area_stick_lr", "area_slide_lr", "area_separated_lr", "area_surface_lr"]
    rows = [[0.0, 0.0, 10.0, 0.0, 5.0, 0.0, 4.0, 0.0, 0.0, 0.0, 0.0],
            [1.0, 1.0, 9.0, 1e-3, 5.0 - dv_drop, anchor * YIELD, 3.0, 0.5, 0.5 + area_drift, 0.0, 0.0]]
    (run / "histories.csv").write_text(",".join(header) + "\n" + "\n".join(",".join(map(str, r)) for r in rows) + "\n", encoding="utf-8")
    (run / "summary.json").write_text(json.dumps({"steps": 10, "dt": 1e-4, "end_time": 1.0, "last_dt": 1e-4,
                                                  "contact_unsettled_steps": [0, 0.0]}), encoding="utf-8")
    return run, case


def failed(run: Path, case: Path) -> set[str]:
    return {c["name"] for c in yc.run_checks(run, case) if not c["passed"]}


@pytest.mark.parametrize("compressed, full_pvd", [(False, False), (True, False), (False, True)])
def test_a_sound_run_passes_in_both_layouts(tmp_path, compressed, full_pvd):
    run, case = make_run(tmp_path, compressed=compressed, full_pvd=full_pvd)
    assert failed(run, case) == set()
    assert yc.main([str(run), "--case", str(case)]) == 0
    assert all(c["passed"] for c in json.loads((run / "checks.json").read_text()))


@pytest.mark.parametrize(
    "broken, name",
    [
        ({"gap": -2e-6}, "no penetration, pairs in contact"),
        ({"dt_drop": 0.15}, "damage never heals"),
        ({"dv_drop": 0.5}, "damaged volume never decreases"),
        ({"anchor": 1.01}, "anchors within yield"),
        ({"area_drift": 0.01}, "interface areas conserved"),
        ({"no_flow": True}, "damage only with plastic flow"),
        ({"undamaged_stress": 1.001}, "undamaged elements inside the initial yield surface"),
        ({"damaged_stress": 1.001}, "damaged elements on or inside the yield surface"),
        ({"fall": 0.5}, "concrete holds together"),
    ],
)
def test_broken_physics_fails_its_check(tmp_path, broken, name):
    run, case = make_run(tmp_path, **broken)
    assert failed(run, case) == {name}
    assert yc.main([str(run), "--case", str(case)]) == 1


def test_damage_growth_within_the_averages_roundoff_is_judged_on_plastic_flow(tmp_path):
    # d_t up by one ulp with κ_t on the same double (the rounding of an element average):
    # accepted when the plastic strain changed, counted in the detail.
    one_ulp = math.ulp(0.1)
    run, case = make_run(tmp_path, dt_gain=one_ulp, kappa_still=True)
    result = {c["name"]: c for c in yc.run_checks(run, case)}["damage only with plastic flow"]
    assert result["passed"] and "; 1 grew by at most" in result["what"], result


@pytest.mark.parametrize("gain, no_flow", [(8 * 2.0**-52 * 1.5, False), (math.ulp(0.1), True)])
def test_damage_growth_beyond_roundoff_or_without_flow_fails(tmp_path, gain, no_flow):
    # κ_t still: a growth of d_t beyond the round-off bound, or one within it without a
    # change of plastic strain, is damage without plastic flow.
    sub = tmp_path / f"g{gain}{no_flow}"
    sub.mkdir()
    run, case = make_run(sub, dt_gain=gain, kappa_still=True, no_flow=no_flow)
    assert "damage only with plastic flow" in failed(run, case)


def test_an_unreadable_frame_is_named(tmp_path):
    run, case = make_run(tmp_path)
    (run / "f1.vtu").write_text("<VTKFile/>", encoding="utf-8")
    with pytest.raises(yc.CheckError, match="f1.vtu"):
        yc.run_checks(run, case)


def test_a_bolt_in_compression_where_the_rock_moved_inward_fails(tmp_path):
    run, case = make_run(tmp_path, bolt_sign=-1.0)
    assert failed(run, case) == {"anchor forces follow the rock's elongation", "anchors in tension where the rock moves inward"}
    checks = {c["name"]: c for c in yc.run_checks(run, case)}
    assert checks["anchor forces follow the rock's elongation"]["value"] == 2  # both segments, frame t = 1
    assert checks["anchors in tension where the rock moves inward"]["value"] == 1  # the bolt at t = 1


def test_the_anchor_check_needs_per_bar_output(tmp_path):
    run, case = make_run(tmp_path)
    (run / "anchors.pvd").unlink()
    with pytest.raises(yc.CheckError, match="anchors.pvd"):
        yc.run_checks(run, case)


def test_bond_slip_bars_are_refused_by_name(tmp_path):
    run, case = make_run(tmp_path)
    case.write_text(CASE.replace("yield_stress = 335e6", "yield_stress = 335e6\nbond_stiffness = 1e8"), encoding="utf-8")
    with pytest.raises(yc.CheckError, match=r"anchors.patterns\[0\].bond_stiffness"):
        yc.run_checks(run, case)


def test_the_update_stress_is_one_elastic_increment_before_the_frame(tmp_path):
    """A frame's stress lies one elastic increment E₀:ε(Δt V) beyond the update's: an
    undamaged element at 0.999 f_t0 whose velocity stretches it by 0.2 % of f_t0 per step
    shows 1.001 f_t0 in the frame; the check reads it back to 0.999 f_t0 and passes. With
    the velocity reversed (the update's stress at 1.003 f_t0) it fails."""
    lam_mu = lf.material(__import__("tomllib").loads(CASE), "concrete", "case").lame()
    # Uniaxial stress increment 0.002 f_t0 from a strain increment along x only: σ_xx =
    # (λ + 2μ) Δε_xx (lateral stresses λ Δε_xx as well; F's margin absorbs them below).
    de = 0.002 * FT_CONCRETE / (lam_mu[0] + 2 * lam_mu[1])
    for sign, broken in ((1.0, False), (-1.0, True)):
        sub = tmp_path / ("up" if sign > 0 else "down")
        sub.mkdir()
        run, case = make_run(sub, undamaged_stress=1.001)
        # Velocities: v_x = sign × de/Δt × (x − 1) on the lining element (x in [1, 2]).
        v = np.zeros((12, 3))
        v[:, 0] = sign * de / 1e-4 * np.maximum(POINTS[:, 0] - 1.0, 0.0)
        frame = yc.read_vtu(run / "f1.vtu", ["displacement", "contact_state", "contact_gap", "stress", "damage",
                                              "damage_tension", "damage_compression", "kappa_tension",
                                              "kappa_compression", "plastic_strain", "region", "active",
                                              "Points", "connectivity", "offsets"])
        stress = frame["stress"].copy()
        # The frame's lateral stresses follow the same increment.
        stress[1, 1] = stress[1, 2] = sign * lam_mu[0] * de
        write_vtu(run / "f1.vtu",
                  {"displacement": frame["displacement"], "velocity": v, "contact_state": frame["contact_state"],
                   "contact_gap": frame["contact_gap"]},
                  {k: frame[k] for k in ("damage", "damage_tension", "damage_compression", "kappa_tension",
                                          "kappa_compression", "plastic_strain", "region", "active")} | {"stress": stress},
                  {"Points": frame["Points"], "connectivity": frame["connectivity"].reshape(-1), "offsets": frame["offsets"]})
        got = {c["name"]: c for c in yc.run_checks(run, case)}["undamaged elements inside the initial yield surface"]
        assert got["passed"] is (not broken), got


def test_consistent_recovery_of_the_full_integration_concrete_is_checked(tmp_path):
    """The undamaged-element check needs no recovery rule (σ̄ = σ where D = 0): a case whose
    concrete (full integration, never damaged here) uses `recovery = "consistent"` is
    checked and passes; the same run with an overstressed concrete element still fails."""
    run, case = make_run(tmp_path)
    case.write_text(CONSISTENT_CONCRETE, encoding="utf-8")
    assert failed(run, case) == set()
    (tmp_path / "over").mkdir()
    run2, case2 = make_run(tmp_path / "over", undamaged_stress=1.001)
    case2.write_text(CONSISTENT_CONCRETE, encoding="utf-8")
    assert failed(run2, case2) == {"undamaged elements inside the initial yield surface"}


def test_consistent_recovery_of_a_damaged_one_point_region_is_refused_by_name(tmp_path):
    run, case = make_run(tmp_path)
    case.write_text(CASE.replace("friction_angle_deg = 41.6\n", 'friction_angle_deg = 41.6\nrecovery = "consistent"\n', 1),
                    encoding="utf-8")
    with pytest.raises(yc.CheckError, match=r"region 'rock' \(one-point\) uses recovery = 'consistent'"):
        yc.run_checks(run, case)


CONSISTENT_CONCRETE = CASE.replace("[materials.concrete.plastic_damage]\n",
                                   '[materials.concrete.plastic_damage]\nrecovery = "consistent"\n', 1)


def test_a_name_that_is_a_point_and_a_cell_field_reads_as_the_cell_field(tmp_path):
    """dcfm writes `active` both per node and per element; the checks mean the element's."""
    path = tmp_path / "both.vtu"
    write_vtu(path, {"active": np.ones(12)}, {"active": np.array([1.0, 0.0])},
              {"Points": POINTS, "connectivity": CONN.reshape(-1), "offsets": np.array([8, 16])})
    got = yc.read_vtu(path, ["active", "connectivity"])
    assert got["active"][:, 0].tolist() == [1.0, 0.0]
    assert got["connectivity"].shape == (16, 1)


@pytest.mark.parametrize("share, fails", [(0.99, False), (1.01, True)])
def test_a_mat_above_its_yield_force_fails(tmp_path, share, fails):
    """Reinforcement mats (`[[anchors.mats]]`) are checked against their yield force like
    the bolts: a mat's largest force of 1.01 × f_y π d²/4 fails, 0.99 × passes."""
    run, case = make_run(tmp_path)
    case.write_text(case.read_text(encoding="utf-8") + '\n[[anchors.mats]]\nname = "m"\nface_set = "f"\n'
                    'cover = 0.05\nspacing = 0.2\ndiameter = 0.02\nyield_stress = 400e6\n', encoding="utf-8")
    hist = run / "histories.csv"
    lines = hist.read_text(encoding="utf-8").splitlines()
    force = share * 400e6 * np.pi * 0.02**2 / 4
    hist.write_text("\n".join([lines[0] + ",anchor_m_max_force", lines[1] + ",0.0", lines[2] + f",{force}"]) + "\n",
                    encoding="utf-8")
    assert failed(run, case) == ({"anchors within yield"} if fails else set())


def test_a_yielded_bolt_is_not_judged_for_its_sign():
    """Once a segment has yielded, N = EA(ε − εᵖ) may have the other sign than ε: a bolt in
    compression where the rock moved inward fails while elastic, and is counted as not
    judged once its plastic strain is non-zero."""
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        run, case = make_run(Path(d), bolt_sign=-1.0)
        assert {"anchor forces follow the rock's elongation", "anchors in tension where the rock moves inward"} <= failed(run, case)
    with tempfile.TemporaryDirectory() as d:
        run, case = make_run(Path(d), bolt_sign=-1.0, bolt_plastic=2e-5)
        checks = {c["name"]: c for c in yc.run_checks(run, case)}
        assert checks["anchor forces follow the rock's elongation"]["passed"]
        assert checks["anchors in tension where the rock moves inward"]["passed"]
        assert "2 segment-frames after their segment yielded not judged" in checks["anchor forces follow the rock's elongation"]["what"]
        assert "1 bar-frames of bars with a yielded segment not judged" in checks["anchors in tension where the rock moves inward"]["what"]


@pytest.mark.parametrize("bolt_sign, wrong", [(1.0, 0), (-1.0, 2)])
def test_sparser_anchor_frames_pair_with_whole_mesh_frames_by_time(tmp_path, bolt_sign, wrong):
    """`anchors_every` (docs/outputs.md) makes anchors.pvd sparser than the whole-mesh
    frames: here full.pvd has a frame at t = 0.5 s (the rock at rest, a copy of t = 0)
    that anchors.pvd lacks. The bolt frame of t = 1 s must be judged against the rock of
    t = 1 s (its 2 segments wrong when the force has the other sign), not against the
    second whole-mesh frame (at rest: nothing would be judged)."""
    run, case = make_run(tmp_path, full_pvd=True, bolt_sign=bolt_sign)
    (run / "full.pvd").write_text(
        '<VTKFile type="Collection"><Collection><DataSet timestep="0" file="f0.vtu"/>'
        '<DataSet timestep="0.5" file="f0.vtu"/><DataSet timestep="1" file="f1.vtu"/>'
        '</Collection></VTKFile>', encoding="utf-8")
    checks = {c["name"]: c for c in yc.run_checks(run, case)}
    sign = checks["anchor forces follow the rock's elongation"]
    assert sign["value"] == wrong, sign
    assert "× 2 frames" in sign["what"], sign
