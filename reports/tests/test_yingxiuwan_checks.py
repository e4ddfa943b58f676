"""The Yingxiuwan physics checks read dcfm's two VTU layouts and fail when the physics is
broken: a penetrating contact node, a damage variable that decreases, a damaged volume
that drops, an anchor above its yield force, an interface whose state areas do not add up."""

from __future__ import annotations

import base64
import json
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest

REPORTS = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPORTS))

import yingxiuwan_checks as yc  # noqa: E402

CASE = """
[[interfaces]]
name = "lr"

[[anchors.patterns]]
name = "bolts"
diameter = 0.025
yield_stress = 335e6
"""
YIELD = 335e6 * np.pi * 0.025**2 / 4


def write_vtu(path: Path, arrays: dict[str, np.ndarray], compressed: bool = False) -> None:
    """A VTU in the layout dcfm writes: base64 streams (header + data per array), or raw
    zlib blocks (VTK's compressed appended layout)."""
    decls, blobs, offset = [], [], 0
    for name, a in arrays.items():
        data = a.astype("<f8").tobytes()
        if compressed:
            block = zlib.compress(data)
            blob = np.array([1, len(data), 0, len(block)], "<u8").tobytes() + block
        else:
            blob = base64.b64encode(np.array([len(data)], "<u8").tobytes() + data)
        decls.append(f'<DataArray type="Float64" Name="{name}" NumberOfComponents="1" format="appended" offset="{offset}"/>')
        blobs.append(blob)
        offset += len(blob)
    compressor = ' compressor="vtkZLibDataCompressor"' if compressed else ""
    head = (
        f'<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64"{compressor}>\n'
        f'<UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="2"><PointData>{"".join(decls)}</PointData></Piece></UnstructuredGrid>\n'
        f'<AppendedData encoding="{"raw" if compressed else "base64"}">\n_'
    )
    path.write_bytes(head.encode() + b"".join(blobs) + b"\n</AppendedData>\n</VTKFile>\n")


def make_run(tmp: Path, *, gap: float = 0.0, dt_drop: float = 0.0, dv_drop: float = 0.0,
             anchor: float = 0.5, area_drift: float = 0.0, compressed: bool = False) -> tuple[Path, Path]:
    run = tmp / "run"
    run.mkdir()
    case = tmp / "case.toml"
    case.write_text(CASE, encoding="utf-8")
    frames = []
    for k, t in enumerate([0.0, 1.0]):
        state = np.array([0.0, 2.0, 3.0, -1.0])
        gaps = np.array([0.0, gap if k == 1 else 0.0, 1e-4, 0.0])
        d_t = np.array([0.1, 0.2 - (dt_drop if k == 1 else 0.0), 0.0, 0.0]) + 0.1 * k
        d_c = np.array([0.0, 0.0, 0.0, 0.0])
        write_vtu(run / f"f{k}.vtu", {"contact_state": state, "contact_gap": gaps, "damage": d_t,
                                       "damage_tension": d_t, "damage_compression": d_c}, compressed)
        frames.append(f'<DataSet timestep="{t}" file="f{k}.vtu"/>')
    (run / "case.pvd").write_text(f'<VTKFile type="Collection"><Collection>{"".join(frames)}</Collection></VTKFile>', encoding="utf-8")
    header = ["time", "kinetic", "internal", "residual", "damaged_volume_total_lining", "anchor_bolts_max_force",
              "area_bonded_lr", "area_stick_lr", "area_slide_lr", "area_separated_lr", "area_surface_lr"]
    rows = [[0.0, 0.0, 10.0, 0.0, 5.0, 0.0, 4.0, 0.0, 0.0, 0.0, 0.0],
            [1.0, 1.0, 9.0, 1e-3, 5.0 - dv_drop, anchor * YIELD, 3.0, 0.5, 0.5 + area_drift, 0.0, 0.0]]
    (run / "histories.csv").write_text(",".join(header) + "\n" + "\n".join(",".join(map(str, r)) for r in rows) + "\n", encoding="utf-8")
    (run / "summary.json").write_text(json.dumps({"steps": 10, "contact_unsettled_steps": [0, 0.0]}), encoding="utf-8")
    return run, case


def failed(run: Path, case: Path) -> set[str]:
    return {c["name"] for c in yc.run_checks(run, case) if not c["passed"]}


@pytest.mark.parametrize("compressed", [False, True])
def test_a_sound_run_passes_in_both_layouts(tmp_path, compressed):
    run, case = make_run(tmp_path, compressed=compressed)
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
    ],
)
def test_broken_physics_fails_its_check(tmp_path, broken, name):
    run, case = make_run(tmp_path, **broken)
    assert failed(run, case) == {name}
    assert yc.main([str(run), "--case", str(case)]) == 1


def test_an_unreadable_frame_is_named(tmp_path):
    run, case = make_run(tmp_path)
    (run / "f1.vtu").write_text("<VTKFile/>", encoding="utf-8")
    with pytest.raises(yc.CheckError, match="f1.vtu"):
        yc.run_checks(run, case)
