"""dcfm's VTK XML files read back with numpy only (docs/outputs.md), for the report scripts.

- `read_vtu`: an UnstructuredGrid as dcfm writes it — appended base64 (one stream per
  array: a UInt64 byte count, then the values; solver/app/src/output/vtu.rs), appended raw
  with zlib-compressed blocks (VTK's vtkZLibDataCompressor layout, the compact frames and
  the anchors; output/vtu_compressed.rs), plain raw appended, or inline ASCII arrays — with
  its region names (the `region_names` string array of the field data).
- `read_pvd`: the (time, file) entries of a PVD collection, in time order.

Every failure is a `VtuError` naming the file and what is wrong.
"""

from __future__ import annotations

import base64
import binascii
import xml.etree.ElementTree as ET
import zlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

HEX8 = 12  # VTK cell type

_TYPES = {"Float64": "<f8", "Float32": "<f4", "Int64": "<i8", "Int32": "<i4", "UInt8": "u1", "UInt64": "<u8", "Int8": "i1"}


class VtuError(Exception):
    """A VTU or PVD file that cannot be read (named in the message)."""


@dataclass
class Grid:
    """One UnstructuredGrid: points, the three cell arrays, point and cell fields (each of
    shape (n, components)), the region names of the field data."""

    path: Path
    points: np.ndarray
    cells: dict[str, np.ndarray]
    point_data: dict[str, np.ndarray] = field(default_factory=dict)
    cell_data: dict[str, np.ndarray] = field(default_factory=dict)
    region_names: list[str] = field(default_factory=list)

    def hex8(self) -> np.ndarray:
        """The connectivity as (cells, 8), after checking that every cell is a hex8."""
        types = self.cells["types"][:, 0]
        if np.any(types != HEX8):
            bad = sorted(set(types.tolist()) - {HEX8})
            raise VtuError(f"{self.path}: cells must be hex8 (VTK type 12), found types {bad}")
        n = len(types)
        offsets = self.cells["offsets"][:, 0].astype(np.int64)
        if not np.array_equal(offsets, 8 * np.arange(1, n + 1)):
            raise VtuError(f"{self.path}: cell offsets are not those of hex8 cells (8, 16, …)")
        return self.cells["connectivity"][:, 0].astype(np.int64).reshape(n, 8)

    def array(self, name: str) -> np.ndarray:
        """A named array: `Points`, a cell array (`connectivity`, `offsets`, `types`) or a
        field; a name that is both a cell and a point field (`active`) is the cell field."""
        if name == "Points":
            return self.points
        for source in (self.cells, self.cell_data, self.point_data):
            if name in source:
                return source[name]
        raise VtuError(f"{self.path}: no array '{name}'")


def read_vtu(path: Path) -> Grid:
    """The UnstructuredGrid of `path` (module docstring for the layouts)."""
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise VtuError(f"{path}: cannot read: {e}") from e
    marker = raw.find(b"<AppendedData")
    head = raw if marker < 0 else raw[:marker]
    try:
        root = ET.fromstring(close_open_tags(head.decode("utf-8")))
    except (ET.ParseError, UnicodeDecodeError) as e:
        raise VtuError(f"{path}: unreadable XML header: {e}") from e
    if root.tag != "VTKFile" or root.get("type") != "UnstructuredGrid":
        raise VtuError(f"{path}: not a VTK UnstructuredGrid file (root <{root.tag} type={root.get('type')!r}>)")
    if root.get("byte_order", "LittleEndian") != "LittleEndian":
        raise VtuError(f"{path}: byte_order {root.get('byte_order')!r}, expected LittleEndian")
    if root.get("header_type", "UInt32") != "UInt64" and marker >= 0:
        raise VtuError(f"{path}: header_type {root.get('header_type')!r}, expected UInt64 (dcfm's)")
    compressed = root.get("compressor") is not None
    start, encoding = -1, None
    if marker >= 0:
        tag_end = raw.index(b">", marker)
        encoding = "base64" if b'encoding="base64"' in raw[marker:tag_end] else "raw"
        start = raw.index(b"_", tag_end) + 1

    def values(arr: ET.Element, where: str) -> np.ndarray:
        name = arr.get("Name")
        dtype = _TYPES.get(arr.get("type", ""))
        if dtype is None:
            raise VtuError(f"{path}: {where} array '{name}': unsupported type {arr.get('type')!r}")
        ncomp = int(arr.get("NumberOfComponents", "1"))
        fmt = arr.get("format")
        try:
            if fmt == "ascii":
                data = np.array((arr.text or "").split(), dtype=dtype)
            elif fmt == "appended" and start >= 0:
                off = start + int(arr.get("offset", "0"))
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
                data = np.frombuffer(payload, dtype)
            else:
                raise VtuError(f"{path}: {where} array '{name}': format {fmt!r} (expected ascii or appended)")
        except (ValueError, zlib.error, binascii.Error, IndexError) as e:
            raise VtuError(f"{path}: {where} array '{name}' cannot be decoded: {e}") from e
        if data.size % ncomp:
            raise VtuError(f"{path}: {where} array '{name}': {data.size} values for {ncomp} components")
        return data.reshape(-1, ncomp)

    piece = root.find("UnstructuredGrid/Piece")
    if piece is None:
        raise VtuError(f"{path}: no <UnstructuredGrid><Piece>")
    n_points, n_cells = int(piece.get("NumberOfPoints", "-1")), int(piece.get("NumberOfCells", "-1"))

    def arrays(section: str, expected: int) -> dict[str, np.ndarray]:
        out = {}
        for arr in piece.findall(f"{section}/DataArray"):
            a = values(arr, section)
            if len(a) != expected:
                raise VtuError(f"{path}: {section} array '{arr.get('Name')}': {len(a)} tuples, expected {expected}")
            out[arr.get("Name", "")] = a
        return out

    pts = arrays("Points", n_points)
    if len(pts) != 1:
        raise VtuError(f"{path}: expected one <Points> array, found {len(pts)}")
    points = next(iter(pts.values()))
    if points.shape[1] != 3:
        raise VtuError(f"{path}: points have {points.shape[1]} components, expected 3")
    cells = {a.get("Name", ""): values(a, "Cells") for a in piece.findall("Cells/DataArray")}
    for k in ("connectivity", "offsets", "types"):
        if k not in cells:
            raise VtuError(f"{path}: <Cells> has no '{k}' array")
    if len(cells["types"]) != n_cells or len(cells["offsets"]) != n_cells:
        raise VtuError(f"{path}: <Cells> lists {len(cells['types'])} types and {len(cells['offsets'])} offsets "
                       f"for {n_cells} cells")
    conn = cells["connectivity"]
    if conn.size and (conn.min() < 0 or conn.max() >= n_points):
        raise VtuError(f"{path}: connectivity refers to point {int(conn.max())} of {n_points}")
    names: list[str] = []
    for arr in root.iter("Array"):
        if arr.get("Name") == "region_names":
            codes = [int(c) for c in (arr.text or "").split()]
            names = bytes(codes).decode("utf-8").split("\0")[:-1]
    return Grid(path, points, cells, arrays("PointData", n_points), arrays("CellData", n_cells), names)


def close_open_tags(text: str) -> str:
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
    """(time, file) of every frame of a PVD collection, in time order."""
    if not path.exists():
        raise VtuError(f"{path}: missing (was the case run?)")
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        raise VtuError(f"{path}: unreadable XML: {e}") from e
    out = []
    for ds in root.iter("DataSet"):
        try:
            out.append((float(ds.attrib["timestep"]), path.parent / ds.attrib["file"]))
        except (KeyError, ValueError) as e:
            raise VtuError(f"{path}: DataSet {ds.attrib}: needs a numeric timestep and a file ({e})") from e
    if not out:
        raise VtuError(f"{path}: no frame")
    return sorted(out, key=lambda x: x[0])
