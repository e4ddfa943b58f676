"""Rows of ``results/crosscheck/crosscheck.json``: the keys of results.json (case,
quantity, reference, computed, rel_error, tolerance, pass, source) plus ``peer``, the
independent code the row compares with.

Rows are collected during a pytest session and merged into the file at its end: rows of
the cases that ran replace their earlier rows, rows of other cases are kept, so running
one test file does not erase the others' results. Writes are atomic (temp file + rename).
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from pathlib import Path
from typing import Any

_ROWS: list[dict[str, Any]] = []
_SERIES: list[dict[str, Any]] = []
_PERFORMANCE: list[dict[str, Any]] = []
_DESCRIPTIONS: dict[str, str] = {}


def check(
    case: str,
    quantity: str,
    reference: float,
    computed: float,
    tolerance: float,
    source: str,
    peer: str,
    *,
    absolute: bool = False,
) -> dict[str, Any]:
    """Record one compared quantity and return its row (``pass`` says whether it is
    within ``tolerance``: relative |c − r|/|r|, or absolute |c − r| when ``absolute``)."""
    reference = float(reference)
    computed = float(computed)
    err = abs(computed - reference)
    if not absolute:
        err = err / abs(reference) if reference != 0.0 else math.inf
    row = {
        "case": case,
        "quantity": quantity,
        "reference": reference,
        "computed": computed,
        "rel_error": err,
        "tolerance": float(tolerance),
        "pass": bool(math.isfinite(err) and err <= tolerance),
        "source": source,
        "peer": peer,
    }
    _ROWS.append(row)
    return row


def series(
    case: str,
    name: str,
    x_label: str,
    y_label: str,
    x: Any,
    curves: dict[str, Any],
    *,
    log_y: bool = False,
) -> None:
    """Record curves of a case for the report's plots: ``curves`` maps a label (the code
    or the closed form) to values at ``x``."""
    _SERIES.append(
        {
            "case": case,
            "name": name,
            "x_label": x_label,
            "y_label": y_label,
            "x": [float(v) for v in x],
            "curves": {k: [float(v) for v in vals] for k, vals in curves.items()},
            "log_y": log_y,
        }
    )


def describe(case: str, text: str) -> None:
    """What a cross-check compares, with which set-up, and why its tolerances are what
    they are (shown under the case's heading in the report)."""
    _DESCRIPTIONS[case] = " ".join(text.split())


def performance(entry: dict[str, Any]) -> None:
    """Record one timing of the performance table (same mesh, same machine, same run)."""
    _PERFORMANCE.append(entry)


def failures(rows: list[dict[str, Any]]) -> list[str]:
    """Readable lines for the rows that fail."""
    return [
        f"{r['case']} / {r['quantity']}: computed {r['computed']:.6e}, reference "
        f"{r['reference']:.6e}, error {r['rel_error']:.3e} > {r['tolerance']:.3e} ({r['peer']})"
        for r in rows
        if not r["pass"]
    ]


def write_atomic(path: Path, doc: Any) -> None:
    """Write ``doc`` as JSON to ``path`` through a temporary file and a rename."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)


def _merge(path: Path, new: list[dict[str, Any]], key: str) -> list[dict[str, Any]]:
    old: list[dict[str, Any]] = []
    if path.exists():
        try:
            doc = json.loads(path.read_text(encoding="utf-8"))
            old = doc.get("rows", []) if isinstance(doc, dict) else []
        except (json.JSONDecodeError, OSError):
            old = []
    replaced = {r[key] for r in new}
    return [r for r in old if r.get(key) not in replaced] + new


def flush(crosscheck_json: Path, performance_json: Path, commit: str) -> None:
    """Merge this session's rows, curves and timings into the files."""
    if _ROWS or _SERIES:
        rows = _merge(crosscheck_json, _ROWS, "case")
        old_series: list[dict[str, Any]] = []
        old_desc: dict[str, str] = {}
        if crosscheck_json.exists():
            try:
                old = json.loads(crosscheck_json.read_text("utf-8"))
                old_series = old.get("series", [])
                old_desc = old.get("descriptions", {})
            except (json.JSONDecodeError, OSError, AttributeError):
                old_series, old_desc = [], {}
        cases = {s["case"] for s in _SERIES} | {r["case"] for r in _ROWS}
        series_all = [s for s in old_series if s.get("case") not in cases] + _SERIES
        desc = {c: t for c, t in old_desc.items() if c not in cases} | _DESCRIPTIONS
        desc = {c: t for c, t in desc.items() if c in {r["case"] for r in rows}}
        write_atomic(crosscheck_json, {"commit": commit, "rows": rows, "series": series_all, "descriptions": desc})
    if _PERFORMANCE:
        rows = _merge(performance_json, _PERFORMANCE, "label")
        write_atomic(performance_json, {"commit": commit, "rows": rows})
