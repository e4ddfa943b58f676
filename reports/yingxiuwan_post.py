"""Post-processing of a Yingxiuwan run (docs/yingxiuwan.md, "Outputs and post-processing").

Reads a run directory written by `dcfm run` on a case from `dcfm mesh yingxiuwan`
(histories.csv, summary.json, static_summary.json, case.pvd with the compact frames of
the concrete, anchors.pvd) and the element sets the generator wrote beside the case
(`<case>_sets.json`), and writes to --out:

- post.json: the damaged-volume history of the concrete (eq. 27, lining + inner
  structure) with its value before the earthquake, the onset time, the growth per window
  of the paper's description and the final value; the survey table (per named element
  set: damaged volume and share at 0 s and at the end, largest damage, damaged yes/no);
  the sliding/separation areas of the interfaces at 0 s and at the end, and the share of
  interface nodes sliding or separated per survey location; the anchors' largest force;
  the run's cost;
- maps rendered off-screen with PyVista (damage of the lining and of the inner structure,
  contact states, at 0 s and at the end) as PNG (PyVista and vtk are optional:
  `.venv/bin/pip install -r reference/requirements-post.txt`).

    .venv/bin/python reports/yingxiuwan_post.py RUN_DIR --sets CASE_sets.json --out DIR
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import numpy as np

# Paper's values (Yang, Chen & Xiao 2014, §4.6.1).
PAPER = {"before": 63.2, "onset": 2.6, "end": 460.3, "strong": [(2.6, 20.0), (30.0, 40.0)]}

# The survey table: location, element set, what the survey found (§4.1) and what the
# paper's computation shows (§4.6, §5.1).
SURVEY = [
    ("arch", "arch", "yes: existing cracks propagated, new cracks along and across the axis", "yes (damage up to 1.0)"),
    ("upper sidewalls", "upper_sidewalls", "yes: part of the sidewall lining cracked, limited width and length", "yes"),
    ("generator floor", "generator_floor", "yes: closed cracks, floor uplifted", "yes (damage close to 1.0)"),
    ("turbine floor", "turbine_floor", "yes: closed cracks", "yes (damage close to 1.0)"),
    ("inner wall of the generator pedestal", "pedestal_inner_wall", "yes: a large number of cracks", "yes (damage close to 1.0)"),
    ("cavern junctions", "junctions", "not reported", "yes"),
    ("crane-beam corbels", "crane_beam_corbels", "not reported", "yes, small damage"),
]

# A location counts as damaged when this share of its volume reached the damage threshold.
DAMAGED_SHARE = 0.01

CONTACT_STATES = {0: "bonded", 1: "stick", 2: "sliding", 3: "separated"}


class PostError(Exception):
    """A run directory or file that cannot be read (named in the message)."""


def read_histories(path: Path, wanted: list[str]) -> dict[str, np.ndarray]:
    """The columns of histories.csv whose names match one of the `wanted` regexes."""
    if not path.exists():
        raise PostError(f"{path}: missing (was the case run?)")
    with path.open(encoding="utf-8") as f:
        reader = csv.reader(f)
        header = next(reader)
        keep = [i for i, h in enumerate(header) if any(re.fullmatch(w, h) for w in wanted)]
        rows: list[list[float]] = []
        for n, row in enumerate(reader, start=2):
            if len(row) != len(header):
                raise PostError(f"{path}: line {n}: {len(row)} values for {len(header)} columns")
            rows.append([float(row[i]) for i in keep])
    data = np.array(rows, dtype=float).reshape(-1, len(keep))
    return {header[i]: data[:, k] for k, i in enumerate(keep)}


def damaged_volume_history(cols: dict[str, np.ndarray]) -> dict[str, Any]:
    """Eq. (27) over the concrete (lining + inner structure), its key figures."""
    t = cols["time"]
    v = np.zeros_like(t)
    for k, c in cols.items():
        if re.fullmatch(r"damaged_volume_total_(lining|inner)", k):
            v = v + c
    v0 = float(v[0])
    # Onset: the first time the damaged volume exceeds its pre-earthquake value by 0.1 m³
    # (a few integration points of the full mesh).
    grown = np.nonzero(v > v0 + 0.1)[0]
    onset = float(t[grown[0]]) if len(grown) else None
    windows = []
    edges = [0.0, 2.6, 20.0, 30.0, 40.0, float(t[-1])]
    for a, b in zip(edges[:-1], edges[1:]):
        if b <= a or a > t[-1]:
            continue
        va, vb = np.interp([a, min(b, t[-1])], t, v)
        windows.append({"from": a, "to": float(min(b, t[-1])), "growth": float(vb - va),
                        "rate": float((vb - va) / max(min(b, t[-1]) - a, 1e-12))})
    # A thinned copy for plots (≤ 2000 points).
    step = max(1, len(t) // 2000)
    return {
        "before": v0,
        "end": float(v[-1]),
        "end_time": float(t[-1]),
        "onset": onset,
        "windows": windows,
        "time": t[::step].tolist() + ([float(t[-1])] if (len(t) - 1) % step else []),
        "volume": v[::step].tolist() + ([float(v[-1])] if (len(t) - 1) % step else []),
        "paper": PAPER,
    }


def read_pvd(path: Path) -> list[tuple[float, Path]]:
    if not path.exists():
        raise PostError(f"{path}: missing")
    root = ET.parse(path).getroot()
    out = []
    for ds in root.iter("DataSet"):
        out.append((float(ds.attrib["timestep"]), path.parent / ds.attrib["file"]))
    if not out:
        raise PostError(f"{path}: no frame")
    return out


def frame_table(frame, sets: dict[str, list[int]], threshold: float) -> dict[str, dict[str, float]]:
    """Per element set: volume, damaged volume (elements whose volume-averaged D_t or D_c
    reaches `threshold`), largest damage, and the share of its interface nodes sliding or
    separated."""
    ids = np.asarray(frame.cell_data["element_id"]).astype(np.int64)
    vol = np.asarray(frame.compute_cell_sizes(length=False, area=False, volume=True).cell_data["Volume"])
    dmax = np.maximum(np.asarray(frame.cell_data["damage_tension"]), np.asarray(frame.cell_data["damage_compression"]))
    state = np.asarray(frame.point_data["contact_state"]) if "contact_state" in frame.point_data else None
    where = {int(e): k for k, e in enumerate(ids)}
    conn = frame.cells_dict[12] if hasattr(frame, "cells_dict") else None
    out: dict[str, dict[str, float]] = {}
    for name, elems in sets.items():
        idx = np.array([where[e] for e in elems if e in where], dtype=np.int64)
        if len(idx) == 0:
            continue
        v = vol[idx]
        damaged = dmax[idx] >= threshold
        row = {
            "elements": int(len(idx)),
            "volume": float(v.sum()),
            "damaged_volume": float(v[damaged].sum()),
            "damaged_share": float(v[damaged].sum() / v.sum()),
            "max_damage": float(dmax[idx].max()),
        }
        if state is not None and conn is not None:
            nodes = np.unique(conn[idx].ravel())
            s = state[nodes] % 10
            on = s >= 0
            row["interface_nodes"] = int(on.sum())
            row["sliding_or_separated_share"] = float(((s == 2) | (s == 3)).sum() / max(on.sum(), 1))
        out[name] = row
    return out


def survey_table(first: dict, last: dict) -> list[dict[str, Any]]:
    rows = []
    for location, key, survey, paper in SURVEY:
        a, b = first.get(key), last.get(key)
        if a is None or b is None:
            continue
        rows.append({
            "location": location,
            "set": key,
            "survey": survey,
            "paper": paper,
            "damaged_volume_0": a["damaged_volume"],
            "damaged_volume_end": b["damaged_volume"],
            "damaged_share_end": b["damaged_share"],
            "max_damage_end": b["max_damage"],
            "damaged": b["damaged_share"] >= DAMAGED_SHARE,
            "grew_during_earthquake": b["damaged_volume"] > a["damaged_volume"] + 1e-9,
            "sliding_or_separated_share_0": a.get("sliding_or_separated_share"),
            "sliding_or_separated_share_end": b.get("sliding_or_separated_share"),
        })
    return rows


def render_maps(frames: dict[str, Any], out: Path, lining: int, inner: int) -> dict[str, str]:
    """Damage of the lining and of the inner structure and the contact states, at 0 s
    and at the end, off-screen (PyVista)."""
    import pyvista as pv

    pv.OFF_SCREEN = True
    made: dict[str, str] = {}
    for when, frame in frames.items():
        region = np.asarray(frame.cell_data["region"]).astype(int)
        frame.cell_data["damage_max"] = np.maximum(frame.cell_data["damage_tension"], frame.cell_data["damage_compression"])
        for what, r, view in (("lining", lining, "arch"), ("inner", inner, "inner")):
            part = frame.extract_cells(np.nonzero(region == r)[0])
            p = pv.Plotter(off_screen=True, window_size=(1100, 720))
            p.set_background("white")
            p.add_mesh(part, scalars="damage_max", cmap="jet", clim=(0.0, 1.0), show_edges=False,
                       scalar_bar_args={"title": "damage max(Dt, Dc)", "color": "black"})
            p.add_text(f"{what}, t = {when}", color="black", font_size=12)
            _camera(p, part, view)
            name = f"damage_{what}_{when.replace(' ', '')}.png"
            p.screenshot(str(out / name))
            p.close()
            made[f"damage_{what}_{when}"] = name
        if "contact_state" in frame.point_data:
            surf = frame.extract_surface()
            s = np.asarray(surf.point_data["contact_state"])
            surf.point_data["contact"] = np.where(s < 0, np.nan, s % 10)
            on = surf.threshold(-0.5, scalars="contact", preference="point", all_scalars=True)
            p = pv.Plotter(off_screen=True, window_size=(1100, 720))
            p.set_background("white")
            p.add_mesh(surf, color="lightgrey", opacity=0.25)
            if on.n_cells:
                p.add_mesh(on, scalars="contact", cmap=["#2b83ba", "#abdda4", "#fdae61", "#d7191c"],
                           clim=(-0.5, 3.5), n_colors=4,
                           scalar_bar_args={"title": "0 bonded 1 stick 2 sliding 3 separated", "color": "black"})
            p.add_text(f"interface states, t = {when}", color="black", font_size=12)
            _camera(p, surf, "arch")
            name = f"contact_{when.replace(' ', '')}.png"
            p.screenshot(str(out / name))
            p.close()
            made[f"contact_{when}"] = name
    return made


def _camera(p, mesh, view: str) -> None:
    b = mesh.bounds
    c = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
    size = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
    if view == "arch":
        # From upstream, above and along the axis: the arch and the upstream sidewall.
        p.camera_position = [(c[0] - 1.3 * size, c[1] - 0.9 * size, c[2] + 0.9 * size), c, (0, 0, 1)]
    else:
        p.camera_position = [(c[0] - 1.1 * size, c[1] - 0.8 * size, c[2] + 1.2 * size), c, (0, 0, 1)]


def post(run: Path, sets_path: Path, out: Path, maps: bool = True) -> dict[str, Any]:
    out.mkdir(parents=True, exist_ok=True)
    summary = json.loads((run / "summary.json").read_text()) if (run / "summary.json").exists() else None
    static = json.loads((run / "static_summary.json").read_text()) if (run / "static_summary.json").exists() else None
    sets_doc = json.loads(sets_path.read_text())
    sets = sets_doc["element_sets"]
    regions = sets_doc["regions"]
    cols = read_histories(run / "histories.csv", [r"time", r"damaged_volume_total_.*", r"area_.*", r"anchor_.*",
                                                   r"kinetic", r"internal", r"damping", r"contact", r"external",
                                                   r"input", r"boundary", r"residual"])
    result: dict[str, Any] = {"run": str(run), "damaged_volume": damaged_volume_history(cols)}
    # Interface states at the first and the last row.
    areas = {k: (float(v[0]), float(v[-1])) for k, v in cols.items() if k.startswith("area_")}
    result["interface_areas"] = areas
    result["anchors"] = {k: {"max": float(np.max(v)), "end": float(v[-1])} for k, v in cols.items() if k.startswith("anchor_")}
    e = {k: float(cols[k][-1]) for k in ("kinetic", "internal", "damping", "contact", "external", "input", "boundary", "residual") if k in cols}
    result["energies_end"] = e
    if summary:
        result["cost"] = {k: summary.get(k) for k in ("nodes", "elements", "steps", "dt", "end_time", "wall_s", "element_updates_per_s", "threads")}
    if static:
        result["static"] = {"steps": [{"name": s.get("name"), "iterations": s.get("iterations"),
                                        "damaged_volume": s.get("damaged_volume")} for s in static.get("steps", [])],
                            "wall_s": static.get("wall_s")}
    import pyvista as pv

    frames = read_pvd(run / "case.pvd")
    first, last = pv.read(str(frames[0][1])), pv.read(str(frames[-1][1]))
    threshold = 0.1
    t0, t1 = frame_table(first, sets, threshold), frame_table(last, sets, threshold)
    result["sets_0"], result["sets_end"] = t0, t1
    result["survey"] = survey_table(t0, t1)
    result["frame_times"] = [frames[0][0], frames[-1][0]]
    if maps:
        when = {"0 s": first, f"{frames[-1][0]:.0f} s": last}
        result["maps"] = render_maps(when, out, regions.index("lining"), regions.index("inner"))
    (out / "post.json").write_text(json.dumps(result, indent=1))
    return result


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run", type=Path)
    ap.add_argument("--sets", type=Path, required=True)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--no-maps", action="store_true")
    a = ap.parse_args(argv)
    try:
        r = post(a.run, a.sets, a.out, maps=not a.no_maps)
    except PostError as e:
        print(f"yingxiuwan_post: {e}", file=sys.stderr)
        return 2
    dv = r["damaged_volume"]
    print(f"damaged volume: {dv['before']:.1f} m³ before, onset {dv['onset']}, {dv['end']:.1f} m³ at {dv['end_time']:.1f} s")
    for row in r["survey"]:
        print(f"  {row['location']:<38} {'yes' if row['damaged'] else 'no ':<4} {row['damaged_volume_end']:.2f} m³ ({100 * row['damaged_share_end']:.1f} %)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
