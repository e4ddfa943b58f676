"""The Yingxiuwan post-processing (reports/yingxiuwan_post.py) on a small synthetic run
directory written here: five hex8 elements of known volume and damage in dcfm's VTU
layouts, a histories.csv and a case.pvd. Every expected number is worked out by hand in
the comments; a broken input stops it with a message naming the file."""

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

import yingxiuwan_post as yp  # noqa: E402

REGIONS = ["rock", "lining", "inner", "excavated"]
UNIT = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)


def elements() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points, hex8 cells (each element its own 8 nodes), regions. Volumes by hand:
    e0 unit cube 1; e1 box 2×1×1 = 2; e2 a parallelepiped on a 2×1 base, 3 high, its top
    shifted by 0.5 in x: base × height = 6; e3 (rock) a frustum of a square pyramid, base
    2 × 2, top 1 × 1, 1 high: h (A1 + A2 + √(A1 A2)) / 3 = 7/3 (det J not constant: a
    one-point rule would give 2.25); e4 an inactive lining unit cube (region −1), left out."""
    boxes = [
        UNIT + [0, 0, 0],
        UNIT * [2, 1, 1] + [1, 0, 0],
        UNIT * [2, 1, 3] + [0, 0, 2] + np.outer(UNIT[:, 2], [0.5, 0, 0]),
        np.column_stack([5 + np.where(UNIT[:, 2] == 0, 2 * UNIT[:, 0], 0.5 + UNIT[:, 0]),
                         5 + np.where(UNIT[:, 2] == 0, 2 * UNIT[:, 1], 0.5 + UNIT[:, 1]), 5 + UNIT[:, 2]]),
        UNIT + [9, 0, 0],
    ]
    points = np.vstack(boxes)
    cells = np.arange(40).reshape(5, 8)
    region = np.array([1, 1, 2, 0, -1], float)
    return points, cells, region


VOLUMES = [1.0, 2.0, 6.0, 7.0 / 3.0, 1.0]


def _blob(a: np.ndarray, dtype: str, compressed: bool) -> bytes:
    data = np.ascontiguousarray(a, dtype=dtype).tobytes()
    if compressed:
        block = zlib.compress(data)
        return np.array([1, len(data), len(data), len(block)], "<u8").tobytes() + block
    return base64.b64encode(np.array([len(data)], "<u8").tobytes() + data)


def write_vtu(path: Path, points: np.ndarray, cells: np.ndarray, point_data: dict, cell_data: dict,
              compressed: bool = False) -> None:
    """A VTU as dcfm writes it: appended base64 streams (a UInt64 byte count, then the
    values: mesh frames, solver/app/src/output/vtu.rs), or raw zlib blocks (compact frames,
    output/vtu_compressed.rs); the region names as field data."""
    blobs: list[bytes] = []
    offset = 0

    def decl(name: str, a: np.ndarray, vtype: str, dtype: str) -> str:
        nonlocal offset
        ncomp = 1 if a.ndim == 1 else a.shape[1]
        b = _blob(a, dtype, compressed)
        blobs.append(b)
        s = f'<DataArray type="{vtype}" Name="{name}" NumberOfComponents="{ncomp}" format="appended" offset="{offset}"/>'
        offset += len(b)
        return s

    fdt, vt = ("<f4", "Float32") if compressed else ("<f8", "Float64")
    pd = "".join(decl(k, v, vt, fdt) for k, v in point_data.items())
    cd = "".join(decl(k, v, vt, fdt) for k, v in cell_data.items())
    pts = decl("Points", points, vt, fdt)
    conn = decl("connectivity", cells.ravel(), "Int32", "<i4")
    offs = decl("offsets", 8 * np.arange(1, len(cells) + 1), "Int32", "<i4")
    types = decl("types", np.full(len(cells), 12), "UInt8", "u1")
    codes = " ".join(str(c) for c in b"".join(n.encode() + b"\0" for n in REGIONS))
    compressor = ' compressor="vtkZLibDataCompressor"' if compressed else ""
    head = (
        f'<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64"{compressor}>\n'
        f'<UnstructuredGrid><FieldData><Array type="String" Name="region_names" NumberOfTuples="{len(REGIONS)}" format="ascii">{codes}</Array></FieldData>\n'
        f'<Piece NumberOfPoints="{len(points)}" NumberOfCells="{len(cells)}"><PointData>{pd}</PointData><CellData>{cd}</CellData>'
        f"<Points>{pts}</Points><Cells>{conn}{offs}{types}</Cells></Piece></UnstructuredGrid>\n"
        f'<AppendedData encoding="{"raw" if compressed else "base64"}">\n_'
    )
    path.write_bytes(head.encode() + b"".join(blobs) + b"\n</AppendedData>\n</VTKFile>\n")


# Damage (d_t, d_c) per element at the first and the last frame.
DT0, DC0 = [0.05, 0.0, 0.0, 0.9, 0.5], [0.0, 0.02, 0.0, 0.0, 0.0]
DT1, DC1 = [0.3, 0.05, 0.1, 0.9, 0.9], [0.0, 0.08, 0.0, 0.0, 0.0]
SETS = {"arch": [0, 1, 4], "upper_sidewalls": [1], "generator_floor": [2], "junctions": [0],
        "crane_beam_corbels": [1], "lining": [0, 1, 4], "inner": [2]}


def contact_states(last: bool) -> np.ndarray:
    s = np.full(40, -1.0)
    if last:
        # e0's nodes: bonded, bonded, sliding, separated, off, off, separated in
        # point-to-surface contact (13), stick: 3 of 6 interface nodes sliding/separated.
        s[:8] = [0, 0, 2, 3, -1, -1, 13, 1]
    else:
        s[:4] = 0
    return s


def make_run(tmp: Path, compressed: bool = False) -> tuple[Path, Path]:
    run = tmp / "run"
    run.mkdir()
    points, cells, region = elements()
    for name, dt, dc, last in (("f0", DT0, DC0, False), ("f1", DT1, DC1, True)):
        cd = {"damage_tension": np.array(dt), "damage_compression": np.array(dc), "region": region}
        pts, cls = points, cells
        if compressed:
            # Compact frame: the concrete elements only (0, 1, 2, 4), with their numbers.
            keep = np.array([0, 1, 2, 4])
            cd = {k: v[keep] for k, v in cd.items()} | {"element_id": keep.astype(float)}
            cls = np.arange(len(keep) * 8).reshape(-1, 8)
            pts = points[cells[keep]].reshape(-1, 3)
            pdata = {"contact_state": contact_states(last)[cells[keep]].ravel()}
        else:
            pdata = {"contact_state": contact_states(last)}
        write_vtu(run / f"{name}.vtu", pts, cls, pdata, cd, compressed)
    (run / "case.pvd").write_text(
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n<Collection>\n'
        '<DataSet timestep="0.0" group="" part="0" file="f0.vtu"/>\n<DataSet timestep="3.0" group="" part="0" file="f1.vtu"/>\n'
        "</Collection>\n</VTKFile>\n")
    (run / "histories.csv").write_text(
        "time,kinetic,damaged_volume_total_rock,damaged_volume_total_lining,damaged_volume_total_inner,"
        "anchor_b_max_force,anchor_b_yielded_segments,area_bonded_lr,area_slide_lr,area_surface_lr\n"
        "0,0,99,10,0,0,0,5,0,0\n"
        "1,1,99,10.05,0,100,0,5,0,0\n"
        "2,1,99,10.05,0.2,250,1,4,1,0.5\n"
        "3,1,99,14,4,200,0,3,2,0.25\n")
    (run / "summary.json").write_text(json.dumps({"status": "completed", "nodes": 40, "elements": 5, "steps": 3, "wall_s": 1.5}))
    sets = tmp / "case_sets.json"
    sets.write_text(json.dumps({"element_sets": SETS, "regions": REGIONS}))
    return run, sets


def test_hex8_volumes_by_hand():
    points, cells, _ = elements()
    assert yp.hex8_volumes(points, cells) == pytest.approx(VOLUMES, rel=1e-12)


@pytest.mark.parametrize("compressed", [False, True])
def test_survey_table_and_damaged_volume(tmp_path, compressed):
    run, sets = make_run(tmp_path, compressed)
    r = yp.post(run, sets, tmp_path / "out", maps=False)
    assert json.loads((tmp_path / "out/post.json").read_text())["survey"] == r["survey"]
    s0, s1 = r["sets_0"], r["sets_end"]
    # arch = e0 (1 m³) + e1 (2 m³); e4 is inactive. At 0 s max(d) = 0.05, 0.02: none
    # damaged. At 3 s e0 0.3 ≥ 0.1 damaged, e1 max(0.05, 0.08) < 0.1: 1 of 3 m³.
    assert s0["arch"]["volume"] == pytest.approx(3.0)
    assert s0["arch"]["elements"] == 2
    assert s0["arch"]["damaged_volume"] == 0.0
    assert s1["arch"]["damaged_volume"] == pytest.approx(1.0)
    assert s1["arch"]["damaged_share"] == pytest.approx(1.0 / 3.0)
    assert s1["arch"]["max_damage"] == pytest.approx(0.3)
    # generator_floor = e2 (6 m³), d_t = 0.1 at 3 s: at the threshold counts as damaged.
    assert s1["generator_floor"]["volume"] == pytest.approx(6.0)
    assert s1["generator_floor"]["damaged_volume"] == pytest.approx(6.0)
    # Interface nodes of the arch at 3 s: e0's 6 nodes in a state, of which sliding (2),
    # separated (3) and point-to-surface separated (13): 3 / 6. At 0 s: 4 bonded, 0.
    assert s1["arch"]["interface_nodes"] == 6
    assert s1["arch"]["sliding_or_separated_share"] == pytest.approx(0.5)
    assert s0["arch"]["sliding_or_separated_share"] == 0.0
    rows = {row["set"]: row for row in r["survey"]}
    assert [row["location"] for row in r["survey"]] == [s[0] for s in yp.SURVEY]
    assert rows["arch"]["damaged_0"] is False and rows["arch"]["damaged"] is True
    assert rows["arch"]["damaged_share_0"] == 0.0
    assert rows["upper_sidewalls"]["damaged"] is False  # e1 only: 0.08 < 0.1
    assert rows["junctions"]["damaged_share_end"] == pytest.approx(1.0)
    assert rows["crane_beam_corbels"]["damaged_volume_end"] == 0.0
    # Damaged volume by level: the concrete is e0 (lining, 1 m³), e1 (lining, 2), e2
    # (inner, 6); e3 (rock) and e4 (inactive) left out. At 3 s d_t = 0.3, 0.05, 0.1 and
    # d_c = 0, 0.08, 0: d_t ≥ 0.1 e0 + e2 = 7 m³, ≥ 0.3 e0 = 1 m³, none above; d_c below
    # every level. At 0 s none (d ≤ 0.05).
    first, last = r["damage_levels"]
    assert last["levels"] == list(yp.DAMAGE_LEVELS)
    assert last["concrete_volume"] == pytest.approx(9.0)
    assert last["tension"] == pytest.approx([7.0, 1.0, 0.0, 0.0, 0.0, 0.0])
    assert last["either"] == pytest.approx([7.0, 1.0, 0.0, 0.0, 0.0, 0.0])
    assert last["compression"] == [0.0] * 6
    assert first["either"] == [0.0] * 6 and first["concrete_volume"] == pytest.approx(9.0)
    # Sets the run directory's sets file does not have are reported as missing.
    assert rows["turbine_floor"]["missing"] and rows["pedestal_inner_wall"]["missing"]
    # The histories: lining + inner = 10, 10.05, 10.25, 18 (rock left out). Onset: the
    # first row above 10 + 0.1 → t = 2. At 2.6 s: 10.25 + 0.6 × 7.75 = 14.9; growth
    # 0–2.6 s: 4.9, 2.6–3 s: 3.1 (rate 3.1 / 0.4 = 7.75 m³/s).
    dv = r["damaged_volume"]
    assert dv["before"] == pytest.approx(10.0)
    assert dv["end"] == pytest.approx(18.0)
    assert dv["onset"] == pytest.approx(2.0)
    assert [w["growth"] for w in dv["windows"]] == pytest.approx([4.9, 3.1])
    assert dv["windows"][1]["rate"] == pytest.approx(7.75)
    # Areas at the first and last row; the anchors' largest force 250 N at 2 s.
    assert r["interface_areas"]["lr"]["bonded"] == [5.0, 3.0]
    assert r["interface_areas"]["lr"]["sliding"] == [0.0, 2.0]
    assert r["anchors"]["b"] == {"max": 250.0, "time_of_max": 2.0, "end": 200.0, "yielded_segments_max": 1.0}
    assert r["cost"]["wall_s"] == 1.5


def test_damage_levels_by_hand(tmp_path):
    """Levels between the fixture's values: d_t 0.3, 0.05, 0.1 and d_c 0, 0.08, 0 on the
    concrete's 1, 2, 6 m³; the rock (d_t 0.9) and the inactive cell (0.9) left out."""
    run, _ = make_run(tmp_path)
    frame = yp.read_vtu(run / "f1.vtu")
    r = yp.damage_levels(frame, [1, 2], (0.05, 0.08, 0.95))
    assert r["tension"] == pytest.approx([9.0, 7.0, 0.0])
    assert r["compression"] == pytest.approx([2.0, 2.0, 0.0])
    assert r["either"] == pytest.approx([9.0, 9.0, 0.0])
    assert yp.damage_levels(frame, [0], (0.9,))["tension"] == pytest.approx([7.0 / 3.0])


def test_maps_written_and_deterministic(tmp_path):
    run, sets = make_run(tmp_path)
    a = yp.post(run, sets, tmp_path / "a")
    b = yp.post(run, sets, tmp_path / "b")
    assert sorted(a["maps"].values()) == ["contact_0s.png", "contact_3s.png", "damage_inner_0s.png",
                                          "damage_inner_3s.png", "damage_lining_0s.png", "damage_lining_3s.png"]
    for name in a["maps"].values():
        data = (tmp_path / "a" / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n"
        assert data == (tmp_path / "b" / name).read_bytes(), name


def test_boundary_faces_of_two_cubes_sharing_a_face():
    # Two unit cubes sharing the face x = 1: 12 faces less the 2 shared = 10, every
    # normal pointing away from its cube, whatever the node order (the second cube's
    # nodes listed top face first, which turns its faces' winding inside out).
    points = np.vstack([UNIT, UNIT + [1, 0, 0]])
    points = np.unique(points, axis=0)
    index = {tuple(p): i for i, p in enumerate(points)}
    cells = np.array([[index[tuple(p)] for p in UNIT + [0, 0, 0]],
                      [index[tuple(p)] for p in UNIT[[4, 5, 6, 7, 0, 1, 2, 3]] + [1, 0, 0]]])
    faces, owner, normals = yp.boundary_faces(cells, points)
    assert len(faces) == 10
    centres = points[faces].mean(axis=1) - points[cells[owner]].mean(axis=1)
    assert np.all(np.einsum("ij,ij->i", normals, centres) > 0)
    assert not np.any(np.all(np.isclose(points[faces][:, :, 0], 1.0), axis=1))


def _error(tmp_path, run, sets) -> str:
    with pytest.raises(yp.PostError) as e:
        yp.post(run, sets, tmp_path / "out", maps=False)
    return str(e.value)


def test_broken_histories_named(tmp_path):
    run, sets = make_run(tmp_path)
    with (run / "histories.csv").open("a") as f:
        f.write("4,1,99\n")
    msg = _error(tmp_path, run, sets)
    assert "histories.csv" in msg and "line 6" in msg


def test_missing_histories_named(tmp_path):
    run, sets = make_run(tmp_path)
    (run / "histories.csv").unlink()
    assert "histories.csv: missing" in _error(tmp_path, run, sets)


def test_broken_sets_named(tmp_path):
    run, sets = make_run(tmp_path)
    sets.write_text('{"element_sets": {"arch": [0, "x"]}, "regions": []}')
    msg = _error(tmp_path, run, sets)
    assert "case_sets.json" in msg and "arch" in msg
    sets.write_text("{not json")
    assert "case_sets.json: not JSON" in _error(tmp_path, run, sets)


def test_sets_of_another_mesh_named(tmp_path):
    run, sets = make_run(tmp_path)
    sets.write_text(json.dumps({"element_sets": {"arch": [0, 77]}, "regions": REGIONS}))
    msg = _error(tmp_path, run, sets)
    assert "case_sets.json" in msg and "77" in msg and "f0.vtu" in msg


def test_truncated_vtu_named(tmp_path):
    run, sets = make_run(tmp_path)
    data = (run / "f1.vtu").read_bytes()
    (run / "f1.vtu").write_bytes(data[: len(data) // 2])
    assert "f1.vtu" in _error(tmp_path, run, sets)


def test_vtu_without_damage_named(tmp_path):
    run, sets = make_run(tmp_path)
    points, cells, region = elements()
    write_vtu(run / "f0.vtu", points, cells, {}, {"region": region})
    msg = _error(tmp_path, run, sets)
    assert "f0.vtu" in msg and "damage_tension" in msg


def test_main_reports_error(tmp_path, capsys):
    run, sets = make_run(tmp_path)
    (run / "case.pvd").unlink()
    assert yp.main([str(run), "--sets", str(sets), "--out", str(tmp_path / "o"), "--no-maps"]) == 2
    assert "case.pvd: missing" in capsys.readouterr().err


def test_report_section_shows_survey_areas_anchors_and_maps(tmp_path):
    """reports/generate.py's Yingxiuwan section: the survey table, the contact areas, the
    anchors and the maps (embedded) from post/post.json; without it, a warning."""
    import generate
    from test_report import write_inputs

    root = tmp_path / "root"
    write_inputs(root)
    run, sets = make_run(tmp_path)
    y = root / "results/yingxiuwan"
    y.mkdir(parents=True)
    (y / "summary.json").write_text(json.dumps({"title": "Yingxiuwan", "nodes": 40, "elements": 5, "end_time": 3.0}))
    (y / "histories.csv").write_text((run / "histories.csv").read_text())
    page, md, _ = generate.build(generate.read_inputs(root))
    assert "No post-processing on record" in page and "No post-processing on record" in md
    yp.post(run, sets, y / "post")
    page, md, _ = generate.build(generate.read_inputs(root))
    assert "No post-processing on record" not in page
    # arch: no (0.0 %) at 0 s, yes (33.3 %) at 3 s; turbine floor's set is not in the run.
    assert "| arch | yes: existing cracks propagated, new cracks along and across the axis | yes (damage up to 1.0) | no (0.0 %) | yes (33.3 %) | 0.3 |" in md
    assert "| turbine floor |" in md and "set not in the frames" in md
    assert "| lr | 5 → 3 | – → – | 0 → 2 | – → – |" in md
    assert "| b | 250 | 2 | 200 |" in md
    # Damaged volume by level: D* = 0.1: 0 at 0 s; d_t 7, d_c 0, max 7 m³ at 3 s.
    assert "### Damaged volume by damage level" in md and "of 9 m³ of active concrete" in md
    assert "| 0.1 | 0 | 7 | 0 | 7 |" in md and "| 0.3 | 0 | 1 | 0 | 1 |" in md
    assert page.count('src="data:image/png;base64,') >= 6 + 1  # the maps and the damaged-volume plot
    assert 'alt="contact_3 s"' in page
    # A map that post.json lists but that is gone, and a post.json of another run, are named.
    (y / "post/contact_3s.png").unlink()
    (y / "summary.json").write_text(json.dumps({"title": "Yingxiuwan", "end_time": 60.0}))
    page, md, _ = generate.build(generate.read_inputs(root))
    assert "Maps missing" in page and "contact_3s.png" in page
    assert "is not the run's end" in md


def test_report_names_a_broken_post_json(tmp_path):
    import generate
    from test_report import write_inputs

    write_inputs(tmp_path)
    y = tmp_path / "results/yingxiuwan"
    (y / "post").mkdir(parents=True)
    (y / "summary.json").write_text(json.dumps({"title": "Yingxiuwan", "end_time": 3.0}))
    (y / "post/post.json").write_text(json.dumps({"survey": [{"location": "arch"}]}))
    with pytest.raises(generate.ReportError, match=r"post\.json: survey row 0"):
        generate.read_inputs(tmp_path)
    (y / "post/post.json").write_text(json.dumps({"survey": [], "maps": ["a.png"]}))
    with pytest.raises(generate.ReportError, match=r"post\.json: 'maps' must be an object"):
        generate.read_inputs(tmp_path)
