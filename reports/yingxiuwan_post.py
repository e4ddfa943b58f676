"""Post-processing of a Yingxiuwan run (issue #10 items 5 and 7; docs/yingxiuwan.md,
"Outputs and post-processing").

Reads a run directory written by `dcfm run` on a case from `dcfm mesh yingxiuwan`
(histories.csv, summary.json, static_summary.json, case.pvd and its VTU frames: the whole
mesh, or the compact frames of `[output.frames]`) and the element sets the generator wrote
beside the case (`<case>_sets.json`), and writes to --out:

- post.json: the damaged-volume history of the concrete (eq. 27 as the solver sums it in
  histories.csv, lining + inner structure) with its value before the earthquake, the onset
  time, the growth per window of the paper's description and the final value; the survey
  table (per named element set: damaged volume and share at the first and the last frame,
  largest damage, damaged yes/no); the concrete's damaged volume by damage level (d_t,
  d_c, max(d_t, d_c) ≥ D* for D* in DAMAGE_LEVELS, at the first and the last frame); the
  interfaces' contact-state areas at the first and the last row; the anchors' largest
  force; the run's cost;
- maps (PNG, matplotlib, no display needed): the boundary faces of the lining and of the
  inner structure coloured by the damage max(d_t, d_c) on a fixed 0–1 scale, and the
  contact states of the concrete's interface faces, at the first and the last frame, each
  in two views.

Numbers from the frames (the survey table) use the elements' volumes (2×2×2 Gauss
quadrature of the reference hex8, exact for a trilinear element) and their cell damage (the
element's mean over its integration points): an element counts as damaged when
max(d_t, d_c) reaches the case's threshold (0.1). The histories' damaged volume
(`damaged_volume = "point"`) counts integration points instead, so a set's damaged volume
here can differ from the histories' region totals.

The maps are drawn with matplotlib from the VTU directly, not with PyVista/vtk: the vtk
wheel (112 MB, 425 MB installed) links the system's libX11/libXrender and renders
off-screen only through the system's EGL or OSMesa libraries, which a machine with nothing
but pip does not have (docs/yingxiuwan.md).

    .venv/bin/python reports/yingxiuwan_post.py RUN_DIR --sets CASE_sets.json --out DIR [--no-maps]
"""

from __future__ import annotations

import argparse
import functools
import csv
import json
import os
import re
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

import dcfm_vtu

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

# An element counts as damaged when max(d_t, d_c) reaches this (the case's
# `[output] damage_threshold`, docs/plastic_damage.md §5).
DAMAGE_THRESHOLD = 0.1
# A location counts as damaged when this share of its volume is damaged (one element in a
# hundred: a crack, not a single integration point's round-off).
DAMAGED_SHARE = 0.01

# Damage levels D* of the damaged-volume-by-level table: how the concrete's damaged volume
# depends on the threshold, which the paper's eq. (27) does not state (its maps' scale runs
# from 0 to 1 and it says the damage "did not exceed 0.3" before the earthquake, §4.6.2).
DAMAGE_LEVELS = (0.1, 0.3, 0.5, 0.7, 0.9, 0.99)

CONTACT_STATES = {0: "bonded", 1: "stick", 2: "sliding", 3: "separated"}
# The column names of histories.csv for the states (area_<state>_<interface>).
AREA_STATES = {"bonded": "bonded", "stick": "stick", "slide": "sliding", "separated": "separated", "surface": "point-to-surface"}


class PostError(Exception):
    """A run directory or file that cannot be read (named in the message)."""


# ------------------------------------------------------------------------------- VTU


@dataclass
class Frame:
    """One VTU frame: reference coordinates, hex8 connectivity, point and cell fields
    (each of shape (n, components)), the region names of the field data."""

    path: Path
    points: np.ndarray
    cells: np.ndarray
    point_data: dict[str, np.ndarray] = field(default_factory=dict)
    cell_data: dict[str, np.ndarray] = field(default_factory=dict)
    region_names: list[str] = field(default_factory=list)

    @functools.cached_property
    def volumes(self) -> np.ndarray:
        """Every cell's volume (hex8_volumes), computed once per frame."""
        return hex8_volumes(self.points, self.cells)

    def cell(self, name: str) -> np.ndarray:
        """A one-component cell field as a flat array (its absence is an error naming the file)."""
        if name not in self.cell_data:
            raise PostError(f"{self.path}: no cell field '{name}' (has {sorted(self.cell_data)})")
        return self.cell_data[name][:, 0]

    def element_ids(self) -> np.ndarray:
        """The element number of every cell: the compact frames' `element_id` field, the
        cell index in a frame of the whole mesh."""
        if "element_id" in self.cell_data:
            return self.cell_data["element_id"][:, 0].astype(np.int64)
        return np.arange(len(self.cells), dtype=np.int64)


def read_vtu(path: Path) -> Frame:
    """A VTU frame of hex8 cells as dcfm writes it (reports/dcfm_vtu.py for the layouts)."""
    try:
        grid = dcfm_vtu.read_vtu(path)
        cells = grid.hex8()
    except dcfm_vtu.VtuError as e:
        raise PostError(str(e)) from e
    return Frame(path, grid.points.astype(float), cells, grid.point_data, grid.cell_data, grid.region_names)


def read_pvd(path: Path) -> list[tuple[float, Path]]:
    """(time, file) of every frame of a PVD collection, in time order."""
    try:
        return dcfm_vtu.read_pvd(path)
    except dcfm_vtu.VtuError as e:
        raise PostError(str(e)) from e


def hex8_volumes(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Volume of every hex8 cell: 2×2×2 Gauss quadrature of det J (exact for trilinear
    cells, whose det J has degree ≤ 2 in each coordinate). VTK node order."""
    g = 1.0 / np.sqrt(3.0)
    corners = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                        [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
    x = points[cells]  # (m, 8, 3)
    vol = np.zeros(len(cells))
    for q in corners * g:
        # dN/dξ of the 8 shape functions N_a = (1 + ξ ξ_a)(1 + η η_a)(1 + ζ ζ_a)/8.
        f = 1.0 + corners * q  # (8, 3)
        dn = np.empty((8, 3))
        dn[:, 0] = corners[:, 0] * f[:, 1] * f[:, 2] / 8
        dn[:, 1] = corners[:, 1] * f[:, 0] * f[:, 2] / 8
        dn[:, 2] = corners[:, 2] * f[:, 0] * f[:, 1] / 8
        jac = np.einsum("mai,aj->mij", x, dn)
        vol += np.linalg.det(jac)
    return vol


# ------------------------------------------------------------------------ histories


def read_histories(path: Path, wanted: list[str]) -> dict[str, np.ndarray]:
    """The columns of histories.csv whose names match one of the `wanted` regexes."""
    if not path.exists():
        raise PostError(f"{path}: missing (was the case run?)")
    with path.open(encoding="utf-8") as f:
        reader = csv.reader(f)
        try:
            header = next(reader)
        except StopIteration:
            raise PostError(f"{path}: empty (no header line)") from None
        keep = [i for i, h in enumerate(header) if any(re.fullmatch(w, h) for w in wanted)]
        rows: list[list[float]] = []
        for n, row in enumerate(reader, start=2):
            if len(row) != len(header):
                raise PostError(f"{path}: line {n}: {len(row)} values for {len(header)} columns")
            try:
                rows.append([float(row[i]) for i in keep])
            except ValueError as e:
                raise PostError(f"{path}: line {n}: {e}") from e
    if not rows:
        raise PostError(f"{path}: no data row")
    if "time" not in header:
        raise PostError(f"{path}: no 'time' column")
    data = np.array(rows, dtype=float).reshape(-1, len(keep))
    return {header[i]: data[:, k] for k, i in enumerate(keep)}


def damaged_volume_history(cols: dict[str, np.ndarray], path: Path) -> dict[str, Any]:
    """Eq. (27) over the concrete (lining + inner structure) as the solver sums it, with
    its key figures against the paper's description (§4.6.1)."""
    t = cols["time"]
    parts = [k for k in cols if re.fullmatch(r"damaged_volume_total_(lining|inner)", k)]
    if not parts:
        raise PostError(f"{path}: no damaged_volume_total_lining / _inner column")
    v = np.zeros_like(t)
    for k in parts:
        v = v + cols[k]
    v0 = float(v[0])
    # Onset: the first time the damaged volume exceeds its pre-earthquake value by 0.1 m³
    # (a few integration points of the full mesh).
    grown = np.nonzero(v > v0 + 0.1)[0]
    onset = float(t[grown[0]]) if len(grown) else None
    windows = []
    edges = [0.0, 2.6, 20.0, 30.0, 40.0, 60.0]
    for a, b in zip(edges[:-1], edges[1:]):
        if a >= t[-1]:
            break
        b = min(b, float(t[-1]))
        va, vb = np.interp([a, b], t, v)
        windows.append({"from": a, "to": b, "growth": float(vb - va), "rate": float((vb - va) / (b - a))})
    # A thinned copy for plots (≤ 2001 points, the last row kept).
    step = max(1, len(t) // 2000)
    idx = list(range(0, len(t), step))
    if idx[-1] != len(t) - 1:
        idx.append(len(t) - 1)
    return {
        "columns": parts,
        "before": v0,
        "end": float(v[-1]),
        "end_time": float(t[-1]),
        "onset": onset,
        "windows": windows,
        "time": t[idx].tolist(),
        "volume": v[idx].tolist(),
        "paper": PAPER,
    }


def interface_areas(cols: dict[str, np.ndarray]) -> dict[str, dict[str, list[float]]]:
    """Per interface and contact state: [area at the first row, at the last row] (m²)."""
    out: dict[str, dict[str, list[float]]] = {}
    for k, v in cols.items():
        m = re.fullmatch(r"area_(bonded|stick|slide|separated|surface)_(.+)", k)
        if m:
            out.setdefault(m.group(2), {})[AREA_STATES[m.group(1)]] = [float(v[0]), float(v[-1])]
    return out


def anchor_forces(cols: dict[str, np.ndarray]) -> dict[str, dict[str, float]]:
    """Per bolt pattern: the largest axial force over the run (N), at the end, and the
    largest number of yielded bar segments."""
    out: dict[str, dict[str, float]] = {}
    for k, v in cols.items():
        m = re.fullmatch(r"anchor_(.+)_max_force", k)
        if m:
            row = {"max": float(np.max(v)), "time_of_max": float(cols["time"][int(np.argmax(v))]), "end": float(v[-1])}
            y = cols.get(f"anchor_{m.group(1)}_yielded_segments")
            if y is not None:
                row["yielded_segments_max"] = float(np.max(y))
            out[m.group(1)] = row
    return out


# ---------------------------------------------------------------------- survey table


def read_sets(path: Path) -> tuple[dict[str, np.ndarray], list[str]]:
    """The element sets and region names of `<case>_sets.json` (solver/app/src/mesh_cmd.rs)."""
    if not path.exists():
        raise PostError(f"{path}: missing (written by `dcfm mesh yingxiuwan` beside the case)")
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise PostError(f"{path}: not JSON: {e}") from e
    if not isinstance(doc, dict) or not isinstance(doc.get("element_sets"), dict) or not isinstance(doc.get("regions"), list):
        raise PostError(f"{path}: expected an object with 'element_sets' (name → element numbers) and 'regions' (names)")
    sets = {}
    for name, elems in doc["element_sets"].items():
        if not isinstance(elems, list) or not all(isinstance(e, int) and e >= 0 for e in elems):
            raise PostError(f"{path}: element set '{name}': expected a list of element numbers ≥ 0")
        sets[name] = np.asarray(elems, dtype=np.int64)
    return sets, [str(r) for r in doc["regions"]]


def frame_table(frame: Frame, sets: dict[str, np.ndarray], sets_path: Path, threshold: float = DAMAGE_THRESHOLD) -> dict[str, dict[str, float]]:
    """Per element set: volume, damaged volume (elements whose cell max(d_t, d_c) reaches
    `threshold`), its share, the largest damage, and the share of the set's interface
    nodes sliding or separated. Inactive cells (region −1) and elements not in the frame
    (compact frames) are left out."""
    ids = frame.element_ids()
    if "element_id" not in frame.cell_data:
        for name, elems in sets.items():
            if len(elems) and elems.max() >= len(ids):
                raise PostError(f"{sets_path}: element set '{name}' has element {int(elems.max())}, "
                                f"but {frame.path} has {len(ids)} cells (a sets file of another mesh?)")
    where = np.full(int(max(ids.max(initial=-1), max((int(e.max(initial=-1)) for e in sets.values()), default=-1))) + 1, -1, np.int64)
    where[ids] = np.arange(len(ids))
    vol = frame.volumes
    dmax = np.maximum(frame.cell("damage_tension"), frame.cell("damage_compression"))
    active = frame.cell("region") >= 0 if "region" in frame.cell_data else np.ones(len(ids), bool)
    state = frame.point_data["contact_state"][:, 0] if "contact_state" in frame.point_data else None
    out: dict[str, dict[str, float]] = {}
    for name, elems in sets.items():
        idx = where[elems]
        idx = idx[idx >= 0]
        idx = idx[active[idx]]
        if len(idx) == 0:
            continue
        v = vol[idx]
        damaged = dmax[idx] >= threshold
        row: dict[str, float] = {
            "elements": int(len(idx)),
            "volume": float(v.sum()),
            "damaged_elements": int(damaged.sum()),
            "damaged_volume": float(v[damaged].sum()),
            "damaged_share": float(v[damaged].sum() / v.sum()),
            "max_damage": float(dmax[idx].max()),
        }
        if state is not None:
            s = state[np.unique(frame.cells[idx].ravel())]
            on = s >= 0
            s = np.mod(s[on], 10)
            row["interface_nodes"] = int(on.sum())
            row["sliding_or_separated_share"] = float(((s == 2) | (s == 3)).sum() / on.sum()) if on.any() else None
        out[name] = row
    return out


def damage_levels(frame: Frame, concrete: list[int], levels: tuple[float, ...] = DAMAGE_LEVELS) -> dict[str, Any]:
    """The concrete's volume (active elements of the regions numbered `concrete`) whose
    element damage reaches each level: d_t ≥ D*, d_c ≥ D*, max(d_t, d_c) ≥ D* (m³)."""
    region = frame.cell("region").astype(np.int64)
    keep = np.isin(region, concrete)
    vol = frame.volumes[keep]
    dt, dc = frame.cell("damage_tension")[keep], frame.cell("damage_compression")[keep]
    either = np.maximum(dt, dc)
    return {
        "levels": list(levels),
        "concrete_volume": float(vol.sum()),
        "tension": [float(vol[dt >= d].sum()) for d in levels],
        "compression": [float(vol[dc >= d].sum()) for d in levels],
        "either": [float(vol[either >= d].sum()) for d in levels],
    }


def survey_table(first: dict, last: dict) -> list[dict[str, Any]]:
    """The survey's locations (§4.1) against the paper (§4.6, §5.1) and this run: damaged
    yes/no at the first and the last frame (share of the volume ≥ DAMAGED_SHARE)."""
    rows = []
    for location, key, survey, paper in SURVEY:
        a, b = first.get(key), last.get(key)
        if a is None or b is None:
            rows.append({"location": location, "set": key, "survey": survey, "paper": paper, "missing": True})
            continue
        rows.append({
            "location": location,
            "set": key,
            "survey": survey,
            "paper": paper,
            "elements": b["elements"],
            "volume": b["volume"],
            "damaged_volume_0": a["damaged_volume"],
            "damaged_volume_end": b["damaged_volume"],
            "damaged_share_0": a["damaged_share"],
            "damaged_share_end": b["damaged_share"],
            "max_damage_end": b["max_damage"],
            "damaged_0": a["damaged_share"] >= DAMAGED_SHARE,
            "damaged": b["damaged_share"] >= DAMAGED_SHARE,
            "grew_during_earthquake": b["damaged_volume"] > a["damaged_volume"] + 1e-9,
            "sliding_or_separated_share_0": a.get("sliding_or_separated_share"),
            "sliding_or_separated_share_end": b.get("sliding_or_separated_share"),
        })
    return rows


# ------------------------------------------------------------------------------ maps

# Faces of a hex8 in VTK node order.
HEX_FACES = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])
CONTACT_COLOURS = ["#2b83ba", "#abdda4", "#fdae61", "#d7191c"]


def boundary_faces(cells: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The faces of `cells` that no other of them shares: (node numbers (f, 4), cell index
    (f,), outward unit normal (f, 3))."""
    faces = cells[:, HEX_FACES].reshape(-1, 4)
    owner = np.repeat(np.arange(len(cells)), 6)
    key = np.sort(faces, axis=1)
    _, inv, count = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    once = count[inv.ravel()] == 1
    faces, owner = faces[once], owner[once]
    x = points[faces]
    n = np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    out = x.mean(axis=1) - points[cells[owner]].mean(axis=1)
    n[np.einsum("ij,ij->i", n, out) < 0] *= -1.0
    return faces, owner, n


def _view(elev: float, azim: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Orthographic view: towards-the-viewer direction, screen right and up."""
    e, a = np.radians(elev), np.radians(azim)
    d = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    r = np.array([-np.sin(a), np.cos(a), 0.0])
    return d, r, np.cross(d, r)


def _draw(ax, points: np.ndarray, faces: np.ndarray, normals: np.ndarray, colours: np.ndarray,
          elev: float, azim: float, context: tuple[np.ndarray, np.ndarray] | None = None) -> None:
    """Painter's algorithm with back faces culled: the faces facing the viewer, far ones
    first; `context` (faces, normals) drawn in light grey under the same sort."""
    from matplotlib.collections import PolyCollection

    d, r, u = _view(elev, azim)
    allf, alln, allc = faces, normals, colours
    if context is not None and len(context[0]):
        grey = np.tile(np.array([[0.86, 0.86, 0.86, 1.0]]), (len(context[0]), 1))
        allf, alln, allc = np.vstack([faces, context[0]]), np.vstack([normals, context[1]]), np.vstack([colours, grey])
    front = alln @ d > 1e-9
    f, c = allf[front], allc[front]
    x = points[f]
    depth = (x @ d).mean(axis=1)
    order = np.argsort(depth, kind="stable")
    xy = np.stack([x @ r, x @ u], axis=-1)[order]
    ax.add_collection(PolyCollection(xy, facecolors=c[order], edgecolors=(0.15, 0.15, 0.15, 0.35), linewidths=0.25))
    proj = np.stack([points[np.unique(allf)] @ r, points[np.unique(allf)] @ u], axis=-1)
    lo, hi = proj.min(axis=0), proj.max(axis=0)
    pad = 0.03 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_axis_off()


# Views (elevation, azimuth in degrees; x across the cavern, y along its axis, z up).
VIEWS = {
    "lining": [("from upstream, above (rock side)", 30.0, -140.0), ("from below (cavern side)", -40.0, -130.0)],
    "inner": [("from upstream, above", 35.0, -140.0), ("from downstream, above", 35.0, 40.0)],
    "contact": [("from upstream, above", 30.0, -140.0), ("from below", -35.0, -130.0)],
}


def _save(fig, path: Path) -> None:
    fig.savefig(path, dpi=100, metadata={"Software": None})


def render_maps(frames: dict[str, Frame], out: Path, lining: int, inner: int) -> dict[str, str]:
    """Damage of the lining and of the inner structure (boundary faces, cell
    max(d_t, d_c), fixed scale 0–1) and the contact states of the concrete's interface
    faces, at each of `frames` (label → frame), as PNG files in `out`: label → file name."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colormaps
    from matplotlib.colors import BoundaryNorm, ListedColormap, Normalize

    made: dict[str, str] = {}
    cmap, norm = colormaps["viridis"], Normalize(0.0, 1.0)
    for when, frame in frames.items():
        tag = when.replace(" ", "")
        region = frame.cell("region").astype(int)
        dmax = np.maximum(frame.cell("damage_tension"), frame.cell("damage_compression"))
        for what, r in (("lining", lining), ("inner", inner)):
            sel = np.nonzero(region == r)[0]
            if len(sel) == 0:
                continue
            faces, owner, normals = boundary_faces(frame.cells[sel], frame.points)
            colours = cmap(norm(dmax[sel][owner]))
            fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.6), layout="constrained")
            for ax, (title, elev, azim) in zip(axes, VIEWS[what]):
                _draw(ax, frame.points, faces, normals, colours, elev, azim)
                ax.set_title(title, fontsize=9)
            fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=axes, shrink=0.8, label="damage max(d_t, d_c)")
            fig.suptitle(f"{'lining' if what == 'lining' else 'inner structure'}: damage at t = {when}", fontsize=11)
            name = f"damage_{what}_{tag}.png"
            _save(fig, out / name)
            plt.close(fig)
            made[f"damage_{what}_{when}"] = name
        if "contact_state" not in frame.point_data:
            continue
        state = frame.point_data["contact_state"][:, 0]
        sel = np.nonzero((region == lining) | (region == inner))[0]
        faces, owner, normals = boundary_faces(frame.cells[sel], frame.points)
        s = state[faces]
        on = np.all(s >= 0, axis=1)
        # A face shows the furthest-gone state of its corners (bonded < stick < sliding <
        # separated), point-to-surface contact (+10) as its pair state.
        fs = np.mod(s[on], 10).max(axis=1).astype(int)
        ccmap = ListedColormap(CONTACT_COLOURS)
        colours = ccmap(fs)
        fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.6), layout="constrained")
        for ax, (title, elev, azim) in zip(axes, VIEWS["contact"]):
            _draw(ax, frame.points, faces[on], normals[on], colours, elev, azim, context=(faces[~on], normals[~on]))
            ax.set_title(title, fontsize=9)
        cb = fig.colorbar(plt.cm.ScalarMappable(norm=BoundaryNorm(np.arange(-0.5, 4.5), 4), cmap=ccmap), ax=axes, shrink=0.8, ticks=range(4))
        cb.ax.set_yticklabels([CONTACT_STATES[i] for i in range(4)])
        fig.suptitle(f"concrete interface faces (lining, inner structure): contact state at t = {when}", fontsize=11)
        name = f"contact_{tag}.png"
        _save(fig, out / name)
        plt.close(fig)
        made[f"contact_{when}"] = name
    # Each kind of map at every frame side by side: lining, inner structure, contact.
    kinds = ["damage_lining_", "damage_inner_", "contact_"]
    return dict(sorted(made.items(), key=lambda kv: next(i for i, k in enumerate(kinds) if kv[0].startswith(k))))


# ------------------------------------------------------------------------------ main


def _load_json(path: Path) -> Any:
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError, UnicodeDecodeError) as e:
        raise PostError(f"{path}: {e}") from e


def _label(t: float) -> str:
    return f"{t:g} s"


def post(run: Path, sets_path: Path, out: Path, maps: bool = True) -> dict[str, Any]:
    """Everything of the module docstring; writes out/post.json (and the maps) and returns it."""
    t_start = time.perf_counter()
    out.mkdir(parents=True, exist_ok=True)
    summary = _load_json(run / "summary.json") if (run / "summary.json").exists() else None
    static = _load_json(run / "static_summary.json") if (run / "static_summary.json").exists() else None
    sets, regions = read_sets(sets_path)
    for r in ("lining", "inner"):
        if r not in regions:
            raise PostError(f"{sets_path}: regions {regions} lack '{r}'")
    hist = run / "histories.csv"
    cols = read_histories(hist, [r"time", r"damaged_volume_total_.*", r"area_.*", r"anchor_.*"])
    result: dict[str, Any] = {"damaged_volume": damaged_volume_history(cols, hist)}
    result["interface_areas"] = interface_areas(cols)
    result["anchors"] = anchor_forces(cols)
    if summary:
        result["cost"] = {k: summary.get(k) for k in ("status", "nodes", "elements", "steps", "dt", "end_time", "wall_s", "element_updates_per_s", "threads")}
    if static:
        result["static"] = {"steps": [{"name": s.get("name"), "iterations": s.get("iterations"), "damaged_volume": s.get("damaged_volume")}
                                      for s in static.get("steps", [])], "wall_s": static.get("wall_s")}
    frames = read_pvd(run / "case.pvd")
    (t0, p0), (t1, p1) = frames[0], frames[-1]
    first, last = read_vtu(p0), read_vtu(p1)
    if first.region_names and first.region_names != regions:
        raise PostError(f"{sets_path}: regions {regions} differ from {p0}'s region_names {first.region_names}")
    s0, s1 = frame_table(first, sets, sets_path), frame_table(last, sets, sets_path)
    result["sets_0"], result["sets_end"] = s0, s1
    result["survey"] = survey_table(s0, s1)
    concrete = [regions.index("lining"), regions.index("inner")]
    result["damage_levels"] = [damage_levels(first, concrete), damage_levels(last, concrete)]
    result["frame_times"] = [t0, t1]
    result["frame_files"] = [p0.name, p1.name]
    result["threshold"] = DAMAGE_THRESHOLD
    result["damaged_share"] = DAMAGED_SHARE
    t_tables = time.perf_counter() - t_start
    if maps:
        result["maps"] = render_maps({_label(t0): first, _label(t1): last}, out, regions.index("lining"), regions.index("inner"))
    result["post_seconds"] = {"tables": t_tables, "total": time.perf_counter() - t_start}
    fd, tmp = tempfile.mkstemp(dir=out, prefix="post.json", suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    os.chmod(tmp, 0o644)
    os.replace(tmp, out / "post.json")
    return result


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run", type=Path, help="run directory of `dcfm run`")
    ap.add_argument("--sets", type=Path, required=True, help="the case's <case>_sets.json")
    ap.add_argument("--out", type=Path, default=None, help="output folder (default: RUN/post)")
    ap.add_argument("--no-maps", action="store_true", help="tables only")
    a = ap.parse_args(argv)
    try:
        r = post(a.run, a.sets, a.out or a.run / "post", maps=not a.no_maps)
    except PostError as e:
        print(f"yingxiuwan_post: {e}", file=sys.stderr)
        return 2
    dv = r["damaged_volume"]
    print(f"damaged volume (concrete): {dv['before']:.1f} m³ at 0 s, onset {dv['onset']}, {dv['end']:.1f} m³ at {dv['end_time']:g} s")
    t0, t1 = r["frame_times"]
    for row in r["survey"]:
        if row.get("missing"):
            print(f"  {row['location']:<38} (set '{row['set']}' not in the frames)")
            continue
        print(f"  {row['location']:<38} {t0:g} s: {'yes' if row['damaged_0'] else 'no ':<3} {100 * row['damaged_share_0']:5.1f} %   "
              f"{t1:g} s: {'yes' if row['damaged'] else 'no ':<3} {100 * row['damaged_share_end']:5.1f} %  (max d {row['max_damage_end']:.2f})")
    print(f"post-processing: {r['post_seconds']['total']:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
