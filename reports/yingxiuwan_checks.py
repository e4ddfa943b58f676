"""Physics checks of a Yingxiuwan run (issue #10, item 7): the CI variant's few seconds of
shaking in the main job are checked against physics, not against golden numbers.

Reads a run directory of `dcfm run` on a case from `dcfm mesh yingxiuwan` (summary.json,
histories.csv, case.pvd and its VTU frames — the raw appended VTU that dcfm writes) and the
case file, and writes RUN_DIR/checks.json: one entry per check with its measured value, its
limit, where the limit comes from and whether it passed. Exit status 1 if any check fails.

The checks:

- energy balance (VERIFICATION.md W12): on every row of the histories, |residual| ≤ 1 % of
  the largest energy term of the run;
- no penetration: on the first and the last frame of the shaking, every node of a pair or
  point-to-surface contact in contact (bonded, stick, sliding) has |gap| ≤ 1 µm and no
  separated node overlaps its partner by more than 1 µm (the contact method closes gaps to
  round-off: measured 1e-15 m; 1 µm is a thousandth of the smallest element);
- damage is irreversible (Lee–Fenves: d_t and d_c grow with the plastic-damage variables
  κ_t, κ_c, which never decrease; the combined d = 1 − (1 − d_c)(1 − s d_t) may fall when a
  crack closes, through the stiffness recovery s): element by element d_t and d_c of the
  last frame are ≥ those of the first, and 0 ≤ d < 1; the damaged volume of every region
  never decreases from row to row;
- anchors: no bar's axial force exceeds its yield force f_y π d²/4 (elastic–perfectly
  plastic steel, docs/anchors.md);
- contact areas: every interface's area split bonded / stick / slide / separated / surface
  sums to the same total on every row (each node's area is in exactly one state);
- the joint contact solve: steps accepted without settling to the tolerance stay below
  the accepted change (summary.json `contact_unsettled_steps`, contact/joint.rs).

    .venv/bin/python reports/yingxiuwan_checks.py RUN_DIR --case CASE.toml
"""

from __future__ import annotations

import argparse
import base64
import binascii
import csv
import json
import math
import os
import sys
import tempfile
import tomllib
import xml.etree.ElementTree as ET
import zlib
from pathlib import Path
from typing import Any

import numpy as np

# Limits, with their sources in the module docstring.
ENERGY_RESIDUAL_SHARE = 0.01
GAP_TOLERANCE_M = 1e-6
AREA_TOLERANCE = 1e-9
UNSETTLED_ACCEPTED = 1e-6


class CheckError(Exception):
    """A run directory that cannot be read: the file and what is wrong."""


def read_vtu(path: Path, names: list[str]) -> dict[str, np.ndarray]:
    """The named point and cell arrays of a VTU file as written by dcfm, as arrays of shape
    (n, components): appended data either base64 (one stream per array: a UInt64 byte
    count, then the values; solver/app/src/output/vtu.rs) or raw with zlib-compressed
    blocks (VTK's vtkZLibDataCompressor layout; output/vtu_compressed.rs)."""
    raw = path.read_bytes()
    marker = raw.find(b"<AppendedData")
    if marker < 0:
        raise CheckError(f"{path}: no <AppendedData> section (expected a VTU written by dcfm)")
    tag_end = raw.index(b">", marker)
    encoding = "base64" if b'encoding="base64"' in raw[marker:tag_end] else "raw"
    start = raw.index(b"_", tag_end) + 1
    try:
        root = ET.fromstring(_close_open_tags(raw[:marker].decode("utf-8")))
    except (ET.ParseError, UnicodeDecodeError) as e:
        raise CheckError(f"{path}: unreadable XML header: {e}") from e
    compressed = root.get("compressor") is not None
    types = {"Float64": "<f8", "Float32": "<f4", "Int64": "<i8", "Int32": "<i4", "UInt8": "u1", "UInt64": "<u8"}
    out: dict[str, np.ndarray] = {}
    for arr in root.iter("DataArray"):
        name = arr.get("Name")
        if name not in names:
            continue
        if arr.get("format") != "appended":
            raise CheckError(f"{path}: array '{name}' is not in the appended section")
        dtype = types.get(arr.get("type", ""))
        if dtype is None:
            raise CheckError(f"{path}: array '{name}' has unsupported type {arr.get('type')}")
        off = start + int(arr.get("offset", "0"))
        try:
            if encoding == "base64":
                nbytes = int(np.frombuffer(base64.b64decode(raw[off : off + 12])[:8], "<u8")[0])
                length = 4 * ((8 + nbytes + 2) // 3)
                payload = base64.b64decode(raw[off : off + length])[8 : 8 + nbytes]
            elif compressed:
                nblocks = int(np.frombuffer(raw, "<u8", 1, off)[0])
                sizes = np.frombuffer(raw, "<u8", nblocks, off + 24)
                pos = off + 24 + 8 * nblocks
                blocks = []
                for size in sizes:
                    blocks.append(zlib.decompress(raw[pos : pos + int(size)]))
                    pos += int(size)
                payload = b"".join(blocks)
            else:
                nbytes = int(np.frombuffer(raw, "<u8", 1, off)[0])
                payload = raw[off + 8 : off + 8 + nbytes]
        except (ValueError, zlib.error, binascii.Error) as e:
            raise CheckError(f"{path}: array '{name}' cannot be decoded: {e}") from e
        ncomp = int(arr.get("NumberOfComponents", "1"))
        out[name] = np.frombuffer(payload, dtype).reshape(-1, ncomp)
    missing = [n for n in names if n not in out]
    if missing:
        raise CheckError(f"{path}: missing arrays {missing}")
    return out


def _close_open_tags(text: str) -> str:
    """Close the elements still open where the appended data begins."""
    stack: list[str] = []
    for piece in text.split("<")[1:]:
        if piece.startswith("?") or piece.startswith("!"):
            continue
        tag = piece.split(">", 1)[0]
        if tag.startswith("/"):
            if stack:
                stack.pop()
        elif not tag.rstrip().endswith("/"):
            stack.append(tag.split()[0])
    return text + "".join(f"</{t}>" for t in reversed(stack))


def read_pvd(path: Path) -> list[tuple[float, Path]]:
    """(time, file) of every frame of a PVD collection."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        raise CheckError(f"{path}: {e}") from e
    return [(float(d.get("timestep", "nan")), path.parent / d.get("file", "")) for d in root.iter("DataSet")]


def read_histories(path: Path) -> dict[str, np.ndarray]:
    try:
        with path.open(encoding="utf-8") as f:
            reader = csv.reader(f)
            header = next(reader)
            rows = [[float(v) for v in row] for row in reader]
    except (OSError, StopIteration, ValueError) as e:
        raise CheckError(f"{path}: {e}") from e
    data = np.array(rows)
    return {h: data[:, k] for k, h in enumerate(header)}


def check(name: str, value: float, limit: float, passed: bool, what: str) -> dict[str, Any]:
    return {"name": name, "value": value, "limit": limit, "passed": bool(passed), "what": what}


def run_checks(run: Path, case_file: Path) -> list[dict[str, Any]]:
    summary = json.loads((run / "summary.json").read_text(encoding="utf-8"))
    cols = read_histories(run / "histories.csv")
    case = tomllib.loads(case_file.read_text(encoding="utf-8"))
    checks: list[dict[str, Any]] = []

    energy_terms = ["kinetic", "internal", "damping", "contact", "external", "input", "boundary"]
    largest = max(float(np.max(np.abs(cols[t]))) for t in energy_terms if t in cols)
    share = float(np.max(np.abs(cols["residual"]))) / largest
    checks.append(check("energy balance", share, ENERGY_RESIDUAL_SHARE, share <= ENERGY_RESIDUAL_SHARE,
                        "largest |residual| of the energy balance over all rows / largest energy term (W12)"))

    frames = read_pvd(run / "case.pvd")
    if len(frames) < 2:
        raise CheckError(f"{run / 'case.pvd'}: {len(frames)} frames, expected the start and the end")
    fields = ["contact_state", "contact_gap", "damage", "damage_tension", "damage_compression"]
    first = read_vtu(frames[0][1], fields)
    last = read_vtu(frames[-1][1], fields)
    worst_contact = 0.0
    worst_overlap = 0.0
    for f in (first, last):
        state = f["contact_state"][:, 0]
        gap = f["contact_gap"][:, 0]
        base = np.where(state >= 10, state - 10, state)
        touching = (state >= 0) & (base <= 2)
        separated = (state >= 0) & (base == 3)
        if np.any(touching):
            worst_contact = max(worst_contact, float(np.max(np.abs(gap[touching]))))
        if np.any(separated):
            worst_overlap = max(worst_overlap, float(np.max(-gap[separated])))
    checks.append(check("no penetration, pairs in contact", worst_contact, GAP_TOLERANCE_M,
                        worst_contact <= GAP_TOLERANCE_M,
                        f"largest |gap| (m) of a bonded, sticking or sliding node, frames at t = {frames[0][0]:g} and {frames[-1][0]:g} s"))
    checks.append(check("no penetration, separated nodes", worst_overlap, GAP_TOLERANCE_M,
                        worst_overlap <= GAP_TOLERANCE_M, "largest overlap (m) of a separated node"))

    d1 = last["damage"][:, 0]
    finite = bool(np.all(np.isfinite(d1)))
    healed = 0.0
    for var in ("damage_tension", "damage_compression"):
        grew = last[var][:, 0] - first[var][:, 0]
        finite = finite and bool(np.all(np.isfinite(grew)))
        healed = max(healed, float(np.max(-grew))) if finite else math.inf
    checks.append(check("damage never heals", healed, 0.0, finite and healed <= 0.0,
                        "largest decrease of an element's tensile or compressive damage d_t, d_c "
                        "from the first to the last frame (the combined d may fall when a crack closes: "
                        "stiffness recovery s)"))
    checks.append(check("damage in [0, 1)", float(np.max(d1)) if finite else math.inf, 1.0,
                        finite and float(np.min(d1)) >= 0.0 and float(np.max(d1)) < 1.0,
                        "largest damage of an element at the last frame (smallest ≥ 0)"))
    worst_drop = 0.0
    for k, v in cols.items():
        if k.startswith("damaged_volume_total_") and len(v) > 1:
            worst_drop = max(worst_drop, float(np.max(v[:-1] - v[1:])))
    checks.append(check("damaged volume never decreases", worst_drop, 1e-9, worst_drop <= 1e-9,
                        "largest drop (m³) of a region's damaged volume between two rows"))

    anchors = case.get("anchors", {})
    worst_ratio = 0.0
    for a in anchors.get("patterns", []) + anchors.get("bars", []):
        col = f"anchor_{a['name']}_max_force"
        if col not in cols:
            raise CheckError(f"{run / 'histories.csv'}: no column '{col}' for anchors '{a['name']}'")
        yield_force = a["yield_stress"] * math.pi * a["diameter"] ** 2 / 4.0
        worst_ratio = max(worst_ratio, float(np.max(np.abs(cols[col]))) / yield_force)
    if anchors:
        checks.append(check("anchors within yield", worst_ratio, 1.0, worst_ratio <= 1.0 + 1e-9,
                            "largest |axial force| of a bar / its yield force f_y π d²/4"))

    worst_area = 0.0
    for iface in case.get("interfaces", []):
        name = iface["name"]
        parts = [f"area_{s}_{name}" for s in ("bonded", "stick", "slide", "separated", "surface")]
        if not all(p in cols for p in parts):
            raise CheckError(f"{run / 'histories.csv'}: missing area columns of interface '{name}'")
        total = sum(cols[p] for p in parts)
        worst_area = max(worst_area, float((np.max(total) - np.min(total)) / np.max(total)))
    checks.append(check("interface areas conserved", worst_area, AREA_TOLERANCE, worst_area <= AREA_TOLERANCE,
                        "largest relative spread over the rows of an interface's summed state areas"))

    count, change = summary.get("contact_unsettled_steps", [0, 0.0])
    checks.append(check("joint contact solve", float(change), UNSETTLED_ACCEPTED, change <= UNSETTLED_ACCEPTED,
                        f"largest force change left in the {count} of {summary.get('steps')} steps accepted without settling to 1e-10"))
    return checks


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run", type=Path, help="run directory of `dcfm run`")
    ap.add_argument("--case", type=Path, required=True, help="the case file the run used")
    args = ap.parse_args(argv)
    try:
        checks = run_checks(args.run, args.case)
    except CheckError as e:
        print(f"yingxiuwan_checks: {e}", file=sys.stderr)
        return 2
    fd, tmp = tempfile.mkstemp(dir=args.run, prefix="checks.json", suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        json.dump(checks, f, indent=1)
    os.replace(tmp, args.run / "checks.json")
    for c in checks:
        print(f"{'ok  ' if c['passed'] else 'FAIL'} {c['name']}: {c['value']:.3e} (limit {c['limit']:.3e})")
    return 0 if all(c["passed"] for c in checks) else 1


if __name__ == "__main__":
    sys.exit(main())
