"""Generate the dcfm verification report: reports/index.html (self-contained: styles and
plots embedded, opens from the file system) and reports/verification.md.

Reads (paths relative to the repository root, or given on the command line):

- results/verification/results.json — the verification cases' metadata (id, title,
  group, requirement, reference, tolerance and why), one row per checked quantity, the
  errors of cases that could not run;
- results/verification/series.json — the curves the cases computed, with their
  reference curves;
- results/crosscheck/crosscheck.json — cross-check rows (results.json's keys + peer)
  and curves;
- results/crosscheck/performance.json — the timings of the performance table;
- benchmarks/history.jsonl — throughput over commits;
- reports/recorded/NAME/ — recorded runs kept in the repository (record.json with the
  provenance, and the files of a Yingxiuwan run folder), one section each; a recorded
  anti-seismic measure (record.json's "measure_of" names its base's folder, "measure"
  its label) is shown in its base's section, beside it;
- results/yingxiuwan/ — the Yingxiuwan case's run (summary.json, histories.csv,
  checks.json, and post/post.json with its maps from reports/yingxiuwan_post.py), when
  that case exists.

A file or row that cannot be read stops the generator with a message naming the file
and the row. Before writing, it checks that every case of results.json and of
crosscheck.json appears in the report.

    .venv/bin/python reports/generate.py [--root DIR] [--out DIR]
"""

from __future__ import annotations

import argparse
import base64
import csv
import html
import io
import json
import math
import os
import sys
import tempfile
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams.update({"font.size": 10, "axes.titlesize": 10, "legend.fontsize": 9})

ROW_KEYS = {
    "case": str,
    "quantity": str,
    "reference": (int, float, type(None)),
    "computed": (int, float, type(None)),
    "rel_error": (int, float, type(None)),
    "tolerance": (int, float),
    "pass": bool,
    "source": str,
}
CASE_KEYS = ("id", "title", "group", "requirement", "reference", "tolerance")
DROP = 0.10  # a throughput record more than 10 % below the previous one is flagged


class ReportError(Exception):
    """A file or row the report cannot use."""


# ---------------------------------------------------------------------------- reading


def _load_json(path: Path) -> Any:
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise ReportError(f"{path}: cannot be read: {e.strerror}") from e
    except json.JSONDecodeError as e:
        raise ReportError(f"{path}: not JSON: line {e.lineno}, column {e.colno}: {e.msg}") from e


def _check_row(path: Path, i: int, row: Any, keys: dict[str, Any]) -> dict[str, Any]:
    if not isinstance(row, dict):
        raise ReportError(f"{path}: row {i}: expected an object, got {type(row).__name__}")
    for k, t in keys.items():
        if k not in row:
            raise ReportError(f"{path}: row {i} ({row.get('case', '?')}): missing key '{k}'")
        v = row[k]
        if not isinstance(v, t) or (k != "pass" and isinstance(v, bool)):
            raise ReportError(
                f"{path}: row {i} ({row.get('case', '?')}): '{k}' = {row[k]!r} has the wrong type"
            )
    return row


def _check_series(path: Path, i: int, s: Any, curves_key: str) -> dict[str, Any]:
    if not isinstance(s, dict):
        raise ReportError(f"{path}: series {i}: expected an object")
    for k in ("case", "name", "x_label", "y_label", "x"):
        if k not in s:
            raise ReportError(f"{path}: series {i} ({s.get('name', '?')}): missing key '{k}'")
    n = len(s["x"])
    curves = s.get(curves_key)
    if curves_key == "curves":
        if not isinstance(curves, dict):
            raise ReportError(f"{path}: series {i} ({s['name']}): missing object 'curves'")
        for label, ys in curves.items():
            if len(ys) != n:
                raise ReportError(f"{path}: series {i} ({s['name']}): curve '{label}' has {len(ys)} points, x has {n}")
    else:
        for k in ("computed", "reference"):
            ys = s.get(k)
            if ys is not None and len(ys) != n:
                raise ReportError(f"{path}: series {i} ({s['name']}): '{k}' has {len(ys)} points, x has {n}")
    return s


@dataclass
class Inputs:
    commit: str = "unknown"
    cases: list[dict[str, Any]] = field(default_factory=list)
    rows: list[dict[str, Any]] = field(default_factory=list)
    errors: list[tuple[str, str]] = field(default_factory=list)
    series: list[dict[str, Any]] = field(default_factory=list)
    cross_rows: list[dict[str, Any]] = field(default_factory=list)
    cross_series: list[dict[str, Any]] = field(default_factory=list)
    cross_commit: str | None = None
    cross_descriptions: dict[str, str] = field(default_factory=dict)
    performance: list[dict[str, Any]] = field(default_factory=list)
    history: list[dict[str, Any]] = field(default_factory=list)
    yingxiuwan: dict[str, Any] | None = None
    recorded: list[dict[str, Any]] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)


def read_inputs(root: Path) -> Inputs:
    inp = Inputs()
    results = root / "results/verification/results.json"
    doc = _load_json(results)
    if not isinstance(doc, dict) or "rows" not in doc or "cases" not in doc:
        raise ReportError(f"{results}: expected an object with 'cases' and 'rows'")
    inp.commit = str(doc.get("commit", "unknown"))
    for i, c in enumerate(doc["cases"]):
        for k in CASE_KEYS:
            if not isinstance(c, dict) or not isinstance(c.get(k), str):
                raise ReportError(f"{results}: cases[{i}]: missing text '{k}'")
        inp.cases.append(c)
    inp.rows = [_check_row(results, i, r, ROW_KEYS) for i, r in enumerate(doc["rows"])]
    titles = {c["title"] for c in inp.cases}
    for i, r in enumerate(inp.rows):
        if r["case"] not in titles:
            raise ReportError(f"{results}: row {i}: case '{r['case']}' is not among the registered cases")
    inp.errors = [(str(e[0]), str(e[1])) for e in doc.get("errors", [])]

    series = root / "results/verification/series.json"
    if series.exists():
        s = _load_json(series)
        if not isinstance(s, list):
            raise ReportError(f"{series}: expected a list of curves")
        inp.series = [_check_series(series, i, x, "computed") for i, x in enumerate(s)]
    else:
        inp.missing.append(str(series.relative_to(root)))

    cross = root / "results/crosscheck/crosscheck.json"
    if cross.exists():
        c = _load_json(cross)
        if not isinstance(c, dict) or "rows" not in c:
            raise ReportError(f"{cross}: expected an object with 'rows'")
        keys = dict(ROW_KEYS, peer=str)
        inp.cross_rows = [_check_row(cross, i, r, keys) for i, r in enumerate(c["rows"])]
        inp.cross_series = [_check_series(cross, i, x, "curves") for i, x in enumerate(c.get("series", []))]
        inp.cross_commit = c.get("commit")
        desc = c.get("descriptions", {})
        if not isinstance(desc, dict) or not all(isinstance(k, str) and isinstance(v, str) for k, v in desc.items()):
            raise ReportError(f"{cross}: 'descriptions' must map case titles to texts")
        inp.cross_descriptions = desc
    else:
        inp.missing.append(str(cross.relative_to(root)))

    perf = root / "results/crosscheck/performance.json"
    if perf.exists():
        p = _load_json(perf)
        rows = p.get("rows") if isinstance(p, dict) else None
        if not isinstance(rows, list):
            raise ReportError(f"{perf}: expected an object with 'rows'")
        for i, r in enumerate(rows):
            for k in ("label", "code", "problem", "steps", "threads", "wall_s"):
                if not isinstance(r, dict) or k not in r:
                    raise ReportError(f"{perf}: row {i}: missing key '{k}'")
        inp.performance = rows
    else:
        inp.missing.append(str(perf.relative_to(root)))

    hist = root / "benchmarks/history.jsonl"
    if hist.exists():
        for n, line in enumerate(hist.read_text(encoding="utf-8").splitlines(), start=1):
            if not line.strip():
                continue
            try:
                r = json.loads(line)
            except json.JSONDecodeError as e:
                raise ReportError(f"{hist}: line {n}: not JSON: {e.msg}") from e
            for k in ("case", "threads", "element_updates_per_s", "commit"):
                if not isinstance(r, dict) or k not in r:
                    raise ReportError(f"{hist}: line {n}: missing key '{k}'")
            r["_line"] = n
            inp.history.append(r)
    else:
        inp.missing.append(str(hist.relative_to(root)))

    inp.yingxiuwan = read_yingxiuwan(root)
    rec = root / "reports/recorded"
    if rec.is_dir():
        runs = [read_recorded(d) for d in sorted(p for p in rec.iterdir() if (p / "record.json").exists())]
        by_name = {r["anchor"].removeprefix("recorded-"): r for r in runs}
        for name, r in by_name.items():
            base = r["record"].get("measure_of")
            if base is None:
                inp.recorded.append(r)
                continue
            # A recorded measure (record.json: "measure_of", the base's folder, and
            # "measure", its label) is shown beside its recorded base, not on its own.
            where = rec / name / "record.json"
            if base not in by_name or by_name[base]["record"].get("measure_of") is not None:
                raise ReportError(f"{where}: 'measure_of': {base!r} is not a recorded base run in {rec}")
            label = r["record"].get("measure")
            if not isinstance(label, str) or not label:
                raise ReportError(f"{where}: a recorded measure needs 'measure', its label (a text)")
            by_name[base]["measures"][label] = r
    return inp


def read_yingxiuwan(root: Path) -> dict[str, Any] | None:
    """The Yingxiuwan case's run, when there is one: results/yingxiuwan/summary.json (the
    run summary of `dcfm run`) and histories.csv (time, energies, damaged volume)."""
    run = read_run(root / "results/yingxiuwan")
    if run is None:
        return None
    # The paper's anti-seismic measures run beside it by the main job, one folder each.
    measures = root / "results/yingxiuwan_measures"
    if measures.is_dir():
        for m in sorted(p for p in measures.iterdir() if p.is_dir()):
            r = read_run(m)
            if r is None:
                raise ReportError(f"{m}: a measure's run needs summary.json (scripts/main.sh)")
            run["measures"][m.name] = r
    return run


def read_recorded(d: Path) -> dict[str, Any]:
    """A recorded run kept in the repository (reports/recorded/NAME/: record.json with its
    provenance, and the files of `read_run`); every file must be there."""
    record = _load_json(d / "record.json")
    for k in ("title", "commit", "date", "machine", "threads", "command", "note"):
        if not isinstance(record, dict) or k not in record:
            raise ReportError(f"{d / 'record.json'}: missing key '{k}'")
    run = read_run(d)
    if run is None:
        raise ReportError(f"{d}: a recorded run needs summary.json")
    for what, present in (("checks.json", run["checks"] is not None), ("post/post.json", run["post"] is not None),
                          ("histories.csv", bool(run["columns"]))):
        if not present:
            raise ReportError(f"{d}: a recorded run needs {what}")
    run["record"] = record
    run["anchor"] = "recorded-" + d.name
    return run


def read_run(d: Path) -> dict[str, Any] | None:
    """A run folder of the Yingxiuwan case: summary.json, histories.csv, checks.json and
    post/ (None without summary.json)."""
    summary = d / "summary.json"
    if not summary.exists():
        return None
    out: dict[str, Any] = {"summary": _load_json(summary), "columns": {}}
    hist = d / "histories.csv"
    if hist.exists():
        with hist.open(encoding="utf-8") as f:
            reader = csv.reader(f)
            header = next(reader)
            cols: dict[str, list[float]] = {h: [] for h in header}
            for n, row in enumerate(reader, start=2):
                if len(row) != len(header):
                    raise ReportError(f"{hist}: line {n}: {len(row)} values for {len(header)} columns")
                for h, v in zip(header, row):
                    try:
                        cols[h].append(float(v))
                    except ValueError as e:
                        raise ReportError(f"{hist}: line {n}: column '{h}': {v!r} is not a number") from e
        out["columns"] = cols
    checks = d / "checks.json"
    out["checks"] = _load_json(checks) if checks.exists() else None
    out["post"] = read_yingxiuwan_post(d / "post")
    out["measures"] = {}
    return out


def read_yingxiuwan_post(d: Path) -> dict[str, Any] | None:
    """The post-processing of the run (reports/yingxiuwan_post.py): post.json and its maps
    (PNG, base64 here; a map it lists but that is missing is named in `missing_maps`)."""
    path = d / "post.json"
    if not path.exists():
        return None
    post = _load_json(path)
    if not isinstance(post, dict) or not isinstance(post.get("survey"), list):
        raise ReportError(f"{path}: expected an object with a 'survey' list (reports/yingxiuwan_post.py)")
    for i, r in enumerate(post["survey"]):
        if not isinstance(r, dict) or not all(isinstance(r.get(k), str) for k in ("location", "survey", "paper")):
            raise ReportError(f"{path}: survey row {i}: expected an object with 'location', 'survey' and 'paper' texts, got {r!r}")
    for key in ("maps", "interface_areas", "anchors"):
        if not isinstance(post.get(key) or {}, dict):
            raise ReportError(f"{path}: '{key}' must be an object, got {type(post[key]).__name__}")
    images, missing = {}, []
    for key, name in (post.get("maps") or {}).items():
        png = d / name
        if png.exists():
            images[key] = base64.b64encode(png.read_bytes()).decode("ascii")
        else:
            missing.append(str(png))
    post["images"], post["missing_maps"] = images, missing
    return post


# ---------------------------------------------------------------------------- plots


def _png(fig) -> str:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    return base64.b64encode(buf.getvalue()).decode("ascii")


def plot_series(s: dict[str, Any]) -> str:
    """A case's computed curve against its reference (verification series) or several
    codes' curves (cross-check series), as base64 PNG."""
    fig, ax = plt.subplots(figsize=(5.6, 3.3))
    x = s["x"]
    if "curves" in s:
        styles = ["-", "--", ":", "-."]
        for k, (label, ys) in enumerate(s["curves"].items()):
            ax.plot(x, ys, styles[k % len(styles)], lw=1.6 if k == 0 else 1.3, label=label)
        if s.get("log_y"):
            ax.set_yscale("log")
    else:
        if s.get("log_log"):
            ax.loglog(x, s["computed"], "o-", label="computed (dcfm)")
            if s.get("reference") is not None:
                ax.loglog(x, s["reference"], "k--", label="reference")
        else:
            ax.plot(x, s["computed"], "-", lw=1.6, label="computed (dcfm)")
            if s.get("reference") is not None:
                ax.plot(x, s["reference"], "k--", lw=1.2, label="reference")
    ax.set_xlabel(s["x_label"])
    ax.set_ylabel(s["y_label"])
    ax.grid(True, alpha=0.3)
    ax.legend()
    return _png(fig)


@dataclass
class Drop:
    config: str
    line: int
    commit: str
    before: float
    after: float
    cpu_share: float | None = None

    @property
    def change(self) -> float:
        return self.after / self.before - 1.0


def history_configs(history: list[dict[str, Any]]) -> dict[str, list[dict[str, Any]]]:
    """Standard-mode records grouped by configuration (case, threads, cpus)."""
    out: dict[str, list[dict[str, Any]]] = {}
    for r in history:
        if r.get("mode", "standard") != "standard":
            continue
        key = f"{r['case']}, {r['threads']} thread{'s' if r['threads'] != 1 else ''}"
        if r.get("cpus") is not None:
            key += f", {r['cpus']} cpus"
        out.setdefault(key, []).append(r)
    return out


def throughput_drops(history: list[dict[str, Any]]) -> list[Drop]:
    """Records more than 10 % below the previous record of the same configuration."""
    drops = []
    for key, recs in history_configs(history).items():
        for prev, cur in zip(recs, recs[1:]):
            a, b = prev["element_updates_per_s"], cur["element_updates_per_s"]
            if a > 0 and b < (1.0 - DROP) * a:
                drops.append(Drop(key, cur["_line"], str(cur["commit"]), a, b, cur.get("cpu_share")))
    return drops


def plot_history(history: list[dict[str, Any]], drops: list[Drop]) -> str | None:
    configs = history_configs(history)
    if not configs:
        return None
    fig, ax = plt.subplots(figsize=(8.0, 4.2))
    flagged = {(d.config, d.line) for d in drops}
    commits: list[str] = []
    for recs in configs.values():
        for r in recs:
            if r["commit"] not in commits:
                commits.append(r["commit"])
    pos = {c: i for i, c in enumerate(commits)}
    markers = ["o", "s", "^", "D"]
    for k, (key, recs) in enumerate(configs.items()):
        xs = [pos[r["commit"]] for r in recs]
        ys = [r["element_updates_per_s"] for r in recs]
        # Ten colours repeat: the marker and line style tell the next ten apart.
        style = ["-", "--", ":", "-."][(k // 10) % 4]
        ax.plot(xs, ys, style, marker=markers[(k // 10) % 4], ms=3, lw=1.2, label=key)
        fx = [pos[r["commit"]] for r in recs if (key, r["_line"]) in flagged]
        fy = [r["element_updates_per_s"] for r in recs if (key, r["_line"]) in flagged]
        if fx:
            ax.plot(fx, fy, "x", ms=9, mew=2, color="red")
    ax.set_yscale("log")
    ax.set_xticks(range(len(commits)), commits, rotation=60, fontsize=7)
    ax.set_ylabel("element updates / s")
    ax.set_title("Throughput over commits (× = drop of more than 10 %)", fontsize=10)
    ax.grid(True, alpha=0.3)
    # Many configurations: the legend goes beside the axes, not over the data.
    ax.legend(fontsize=7, ncol=1, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    return _png(fig)


# ---------------------------------------------------------------------------- formatting


def num(x: Any) -> str:
    if x is None:
        return "–"
    if isinstance(x, bool):
        return str(x)
    x = float(x)
    if x == 0.0:
        return "0"
    if not math.isfinite(x):
        return str(x)
    return f"{x:.6g}" if 1e-3 <= abs(x) < 1e6 else f"{x:.4e}"


def short(x: Any) -> str:
    return "–" if x is None else f"{float(x):.2e}"


def share(x: Any) -> str:
    return "–" if x is None else f"{float(x):.2f}"


def esc(s: Any) -> str:
    return html.escape(str(s))


def anchor(s: str) -> str:
    out = "".join(ch.lower() if ch.isalnum() else "-" for ch in s)
    while "--" in out:
        out = out.replace("--", "-")
    return out.strip("-")


def mark(ok: bool) -> str:
    return "pass" if ok else "FAIL"


# ---------------------------------------------------------------------------- report


@dataclass
class Report:
    html_parts: list[str] = field(default_factory=list)
    md_parts: list[str] = field(default_factory=list)

    def h(self, s: str) -> None:
        self.html_parts.append(s)

    def m(self, s: str) -> None:
        self.md_parts.append(s)


def row_table(rep: Report, rows: list[dict[str, Any]], peer: bool) -> None:
    cols = ["quantity", "reference", "computed", "error", "tolerance", "result", "source"]
    if peer:
        cols.insert(6, "peer")
    rep.h('<div class="scroll"><table class="rows"><thead><tr>' + "".join(f"<th>{c}</th>" for c in cols) + "</tr></thead><tbody>")
    rep.m("| " + " | ".join(cols) + " |\n|" + "|".join("---" if c in ("quantity", "source", "peer") else "---:" for c in cols) + "|")
    for r in rows:
        cells = [
            esc(r["quantity"]),
            num(r["reference"]),
            num(r["computed"]),
            short(r["rel_error"]),
            short(r["tolerance"]),
            f'<span class="{"ok" if r["pass"] else "bad"}">{mark(r["pass"])}</span>',
            esc(r["source"]),
        ]
        mcells = [
            r["quantity"].replace("|", "\\|"),
            num(r["reference"]),
            num(r["computed"]),
            short(r["rel_error"]),
            short(r["tolerance"]),
            "✅" if r["pass"] else "❌",
            r["source"].replace("|", "\\|"),
        ]
        if peer:
            cells.insert(6, esc(r["peer"]))
            mcells.insert(6, r["peer"].replace("|", "\\|"))
        rep.h("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
        rep.m("| " + " | ".join(mcells) + " |")
    rep.h("</tbody></table></div>")
    rep.m("")


def build(inp: Inputs) -> tuple[str, str, list[str]]:
    """The HTML and Markdown texts, and the list of case titles the report shows."""
    rep = Report()
    shown: list[str] = []
    now = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    n_pass = sum(r["pass"] for r in inp.rows)
    c_pass = sum(r["pass"] for r in inp.cross_rows)

    # Summary -----------------------------------------------------------------
    groups: dict[str, list[int]] = {}
    by_title = {c["title"]: c for c in inp.cases}
    for r in inp.rows:
        g = groups.setdefault(by_title[r["case"]]["group"], [0, 0])
        g[0] += r["pass"]
        g[1] += 1
    cross_cases: list[str] = []
    for r in inp.cross_rows:
        if r["case"] not in cross_cases:
            cross_cases.append(r["case"])
    if inp.cross_rows:
        groups["Cross-checks against independent codes"] = [c_pass, len(inp.cross_rows)]

    rep.h("<header><h1>dcfm verification report</h1>")
    rep.h(
        f'<p class="meta">Commit <code>{esc(inp.commit)}</code> · generated {now} · '
        f"{n_pass} of {len(inp.rows)} verification checks and {c_pass} of {len(inp.cross_rows)} "
        "cross-checks pass</p>"
    )
    rep.m("# dcfm verification report\n")
    rep.m(
        f"Commit `{inp.commit}`, generated {now} by `reports/generate.py` (the HTML version with "
        f"plots is `reports/index.html`). {n_pass} of {len(inp.rows)} verification checks and "
        f"{c_pass} of {len(inp.cross_rows)} cross-checks pass.\n"
    )
    if inp.missing:
        rep.h('<p class="warn">Not found (sections left out): ' + ", ".join(f"<code>{esc(m)}</code>" for m in inp.missing) + "</p>")
        rep.m("Not found (sections left out): " + ", ".join(f"`{m}`" for m in inp.missing) + "\n")
    rep.h("</header>")

    rep.h('<nav><a href="#summary">Summary</a> · <a href="#cases">Verification cases</a> · '
          '<a href="#crosschecks">Cross-checks</a> · <a href="#performance">Performance</a> · '
          '<a href="#history">Throughput history</a>' + (' · <a href="#yingxiuwan">Yingxiuwan</a>' if inp.yingxiuwan else "")
          + "".join(f' · <a href="#{esc(r["anchor"])}">{esc(r["record"]["title"].split(" (")[0])}</a>' for r in inp.recorded) + "</nav>")
    rep.h('<section id="summary"><h2>Summary</h2><div class="scroll"><table><thead><tr><th>group</th><th>checks</th><th>pass</th><th>fail</th></tr></thead><tbody>')
    rep.m("## Summary\n\n| group | checks | pass | fail |\n|---|---:|---:|---:|")
    for g, (p, n) in groups.items():
        cls = "ok" if p == n else "bad"
        rep.h(f'<tr><td>{esc(g)}</td><td>{n}</td><td class="{cls}">{p}</td><td>{n - p}</td></tr>')
        rep.m(f"| {g} | {n} | {p} | {n - p} |")
    rep.h("</tbody></table></div>")
    rep.m("")
    if inp.errors:
        rep.h("<p class=\"bad\">Cases that stopped with an error:</p><ul>" + "".join(f"<li><b>{esc(i)}</b>: {esc(e)}</li>" for i, e in inp.errors) + "</ul>")
        rep.m("Cases that stopped with an error:\n\n" + "\n".join(f"- **{i}**: {e}" for i, e in inp.errors) + "\n")
    rep.h("<ul class=\"toc\">")
    for c in inp.cases:
        rows = [r for r in inp.rows if r["case"] == c["title"]]
        ok = all(r["pass"] for r in rows) and rows
        label = c["title"] if c["title"].startswith(c["id"]) else f'{c["id"]} — {c["title"]}'
        rep.h(f'<li><a href="#{anchor(c["id"])}">{esc(label)}</a> '
              f'<span class="{"ok" if ok else "bad"}">{sum(r["pass"] for r in rows)}/{len(rows)}</span></li>')
    for cc in cross_cases:
        rows = [r for r in inp.cross_rows if r["case"] == cc]
        ok = all(r["pass"] for r in rows)
        rep.h(f'<li><a href="#{anchor("x-" + cc)}">{esc(cc)}</a> <span class="{"ok" if ok else "bad"}">{sum(r["pass"] for r in rows)}/{len(rows)}</span></li>')
    rep.h("</ul></section>")

    # Verification cases -----------------------------------------------------
    rep.h('<section id="cases"><h2>Verification cases</h2>')
    rep.m("## Verification cases\n")
    for c in inp.cases:
        rows = [r for r in inp.rows if r["case"] == c["title"]]
        shown.append(c["title"])
        heading = c["title"] if c["title"].startswith(c["id"]) else f'{c["id"]} — {c["title"]}'
        rep.h(f'<article id="{anchor(c["id"])}"><h3>{esc(heading)}</h3>')
        rep.h(f'<dl><dt>Group</dt><dd>{esc(c["group"])}</dd><dt>Requirement</dt><dd>{esc(c["requirement"])}</dd>'
              f'<dt>Reference</dt><dd>{esc(c["reference"])}</dd><dt>Tolerance</dt><dd>{esc(c["tolerance"])}</dd></dl>')
        rep.m(f"### {heading}\n")
        rep.m(f"- **Group:** {c['group']}\n- **Requirement:** {c['requirement']}\n- **Reference:** {c['reference']}\n- **Tolerance:** {c['tolerance']}\n")
        err = [e for i, e in inp.errors if i == c["id"]]
        if err:
            rep.h(f'<p class="bad">Stopped with an error: {esc(err[0])}</p>')
            rep.m(f"Stopped with an error: {err[0]}\n")
        if rows:
            row_table(rep, rows, peer=False)
        plots = [s for s in inp.series if s["case"] == c["title"]]
        if plots:
            rep.h('<div class="plots">')
            for s in plots:
                rep.h(f'<figure><img alt="{esc(s["name"])}" src="data:image/png;base64,{plot_series(s)}"><figcaption>{esc(s["name"])}</figcaption></figure>')
            rep.h("</div>")
            rep.m("Plots: " + "; ".join(s["name"] for s in plots) + " (in index.html).\n")
        rep.h("</article>")
    rep.h("</section>")

    # Cross-checks ------------------------------------------------------------
    rep.h('<section id="crosschecks"><h2>Cross-checks against independent codes</h2>')
    rep.m("## Cross-checks against independent codes\n")
    if inp.cross_commit:
        rep.h(f'<p class="meta">From <code>results/crosscheck/crosscheck.json</code> (commit <code>{esc(inp.cross_commit)}</code>), written by the pytest cross-checks in <code>reference/tests/</code>.</p>')
        rep.m(f"From `results/crosscheck/crosscheck.json` (commit `{inp.cross_commit}`), written by the pytest cross-checks in `reference/tests/`.\n")
    for cc in cross_cases:
        rows = [r for r in inp.cross_rows if r["case"] == cc]
        shown.append(cc)
        peers = sorted({r["peer"] for r in rows})
        rep.h(f'<article id="{anchor("x-" + cc)}"><h3>{esc(cc)}</h3><p>Peer: {esc(", ".join(peers))}</p>')
        rep.m(f"### {cc}\n\nPeer: {', '.join(peers)}\n")
        if cc in inp.cross_descriptions:
            rep.h(f'<p class="desc">{esc(inp.cross_descriptions[cc])}</p>')
            rep.m(f"{inp.cross_descriptions[cc]}\n")
        row_table(rep, rows, peer=True)
        plots = [s for s in inp.cross_series if s["case"] == cc]
        if plots:
            rep.h('<div class="plots">')
            for s in plots:
                rep.h(f'<figure><img alt="{esc(s["name"])}" src="data:image/png;base64,{plot_series(s)}"><figcaption>{esc(s["name"])}</figcaption></figure>')
            rep.h("</div>")
        rep.h("</article>")
    rep.h("</section>")

    # Performance -------------------------------------------------------------
    rep.h('<section id="performance"><h2>Performance: the same problem in three codes</h2>')
    rep.m("## Performance: the same problem in three codes\n")
    if inp.performance:
        rep.h("<p>Wall time of the step loop alone, measured in one pytest run on one machine "
              "(<code>reference/tests/test_performance.py</code>, <code>test_opensees.py</code>). "
              "Time ratio: time per element update over that of dcfm (full integration, 1 thread) on the same problem "
              "(runs of different step counts compare per step).</p>")
        rep.m("Wall time of the step loop alone, measured in one pytest run on one machine. Time ratio: time per element update over that of dcfm (full integration, 1 thread) on the same problem.\n")
        problems: list[str] = []
        for r in inp.performance:
            if r["problem"] not in problems:
                problems.append(r["problem"])
        cols = ["problem", "code", "variant", "threads", "elements", "steps", "wall (s)", "element updates/s", "time ratio"]
        rep.h('<div class="scroll"><table><thead><tr>' + "".join(f"<th>{c}</th>" for c in cols) + "</tr></thead><tbody>")
        rep.m("| " + " | ".join(cols) + " |\n|---|---|---|---:|---:|---:|---:|---:|---:|")
        for p in problems:
            rs = [r for r in inp.performance if r["problem"] == p]
            base = next((r for r in rs if r["code"] == "dcfm" and r.get("threads") == 1 and r.get("variant", "full") == "full"), None)
            for r in rs:
                ratio = None
                if base and r.get("element_updates_per_s") and base.get("element_updates_per_s"):
                    ratio = base["element_updates_per_s"] / r["element_updates_per_s"]
                cells = [p, r["code"], r.get("variant", ""), r["threads"], r.get("elements", ""), r["steps"], f"{r['wall_s']:.3f}",
                         short(r.get("element_updates_per_s")), "–" if ratio is None else f"{ratio:.2f}"]
                rep.h("<tr>" + "".join(f"<td>{esc(c)}</td>" for c in cells) + "</tr>")
                rep.m("| " + " | ".join(str(c) for c in cells) + " |")
        rep.h("</tbody></table></div>")
        rep.m("")
    rep.h("</section>")

    # Throughput history ----------------------------------------------------
    rep.h('<section id="history"><h2>Throughput over commits</h2>')
    rep.m("## Throughput over commits\n")
    if inp.history:
        drops = throughput_drops(inp.history)
        img = plot_history(inp.history, drops)
        rep.h("<p>Standard runs of <code>cargo run --release -p dcfm-benchmarks --bin throughput</code> "
              "(<code>benchmarks/history.jsonl</code>), one line per configuration. A record more than 10 % below the "
              "previous record of the same configuration is flagged, with the share of the cores the run had "
              "(<code>cpu_share</code>: well below 1 means a busy machine, not necessarily a slower solver).</p>")
        if img:
            rep.h(f'<figure class="wide"><img alt="throughput history" src="data:image/png;base64,{img}"></figure>')
        rep.m("Standard runs of the throughput runner (`benchmarks/history.jsonl`). Drops of more than 10 % against the previous record of the same configuration:\n")
        if drops:
            rep.h("<h3>Drops of more than 10 %</h3>")
            rep.h('<div class="scroll"><table><thead><tr><th>configuration</th><th>commit</th><th>line</th><th>before</th><th>after</th><th>change</th><th>cpu share</th></tr></thead><tbody>')
            rep.m("| configuration | commit | line | before | after | change | cpu share |\n|---|---|---:|---:|---:|---:|---:|")
            for d in drops:
                rep.h(f'<tr><td>{esc(d.config)}</td><td><code>{esc(d.commit)}</code></td><td>{d.line}</td><td>{short(d.before)}</td><td>{short(d.after)}</td><td class="bad">{d.change * 100:+.1f} %</td><td>{share(d.cpu_share)}</td></tr>')
                rep.m(f"| {d.config} | `{d.commit}` | {d.line} | {short(d.before)} | {short(d.after)} | {d.change * 100:+.1f} % | {share(d.cpu_share)} |")
            rep.h("</tbody></table></div>")
            rep.m("")
        else:
            rep.h("<p>No drop of more than 10 %.</p>")
            rep.m("No drop of more than 10 %.\n")
        latest: dict[str, dict[str, Any]] = {}
        for key, recs in history_configs(inp.history).items():
            latest[key] = recs[-1]
        rep.h("<h3>Latest record of each configuration</h3>")
        rep.h('<div class="scroll"><table><thead><tr><th>configuration</th><th>latest commit</th><th>element updates/s</th><th>cpu share</th></tr></thead><tbody>')
        rep.m("| configuration | latest commit | element updates/s | cpu share |\n|---|---|---:|---:|")
        for key, r in latest.items():
            rep.h(f"<tr><td>{esc(key)}</td><td><code>{esc(r['commit'])}</code></td><td>{short(r['element_updates_per_s'])}</td><td>{share(r.get('cpu_share'))}</td></tr>")
            rep.m(f"| {key} | `{r['commit']}` | {short(r['element_updates_per_s'])} | {share(r.get('cpu_share'))} |")
        rep.h("</tbody></table></div>")
        rep.m("")
    rep.h("</section>")

    # Yingxiuwan (only when the case has been run) ---------------------------------
    if inp.yingxiuwan:
        yingxiuwan_section(rep, inp.yingxiuwan)
    for r in inp.recorded:
        yingxiuwan_section(rep, r)

    body = "\n".join(rep.html_parts)
    page = HTML_TEMPLATE.replace("{{BODY}}", body).replace("{{TITLE}}", f"dcfm verification report ({esc(inp.commit)})")
    return page, "\n".join(rep.md_parts) + "\n", shown


def yingxiuwan_section(rep: Report, y: dict[str, Any]) -> None:
    """The Yingxiuwan powerhouse case (paper §4): its run summary and the damaged volume
    over time from its histories."""
    s = y["summary"]
    record = y.get("record")
    if record is None:
        rep.h('<section id="yingxiuwan"><h2>Yingxiuwan underground powerhouse</h2>')
        rep.m("## Yingxiuwan underground powerhouse\n")
    else:
        rep.h(f'<section id="{esc(y["anchor"])}"><h2>{esc(record["title"])}</h2>')
        rep.m(f"## {record['title']}\n")
        line = (f"Recorded run, not rerun by this report: commit {record['commit']}, {record['date']}, {record['threads']} threads "
                f"on {record['machine']}. {record['note']} How it was made: {record['command']}.")
        if record.get("reduction"):
            line += f" Histories: {record['reduction']}."
        rep.h(f'<p class="meta">{esc(line)}</p>')
        rep.m(line + "\n")
    keys = [k for k in ("title", "nodes", "elements", "steps", "dt", "end_time", "wall_s", "element_updates_per_s", "energy_residual_relative", "contact_unsettled_steps", "contact_joint") if k in s]

    def shown(v: Any) -> Any:
        if isinstance(v, dict):
            return ", ".join(f"{k} {v[k]}" for k in v)
        return num(v) if isinstance(v, (int, float)) else v

    rep.h('<div class="scroll"><table><tbody>' + "".join(f"<tr><th>{esc(k)}</th><td>{esc(shown(s[k]))}</td></tr>" for k in keys) + "</tbody></table></div>")
    rep.m("| quantity | value |\n|---|---|\n" + "\n".join(f"| {k} | {shown(s[k]) if isinstance(s[k], dict) else s[k]} |" for k in keys) + "\n")
    checks = y.get("checks")
    if checks is None:
        rep.h('<p class="warn">No physics checks on record (results/yingxiuwan/checks.json, reports/yingxiuwan_checks.py).</p>')
        rep.m("No physics checks on record.\n")
    else:
        rows = "".join(
            f'<tr><td>{esc(c["name"])}</td><td>{esc(num(c["value"]))}</td><td>{esc(num(c["limit"]))}</td>'
            f'<td class="{"ok" if c["passed"] else "bad"}">{"pass" if c["passed"] else "FAIL"}</td><td>{esc(c["what"])}</td></tr>'
            for c in checks
        )
        rep.h('<h3>Physics checks</h3><div class="scroll"><table class="rows"><thead><tr><th>check</th><th>measured</th>'
              f'<th>limit</th><th>result</th><th>what</th></tr></thead><tbody>{rows}</tbody></table></div>')
        rep.m("### Physics checks\n\n| check | measured | limit | result |\n|---|---|---|---|\n"
              + "\n".join(f'| {c["name"]} | {num(c["value"])} | {num(c["limit"])} | {"pass" if c["passed"] else "FAIL"} |' for c in checks) + "\n")
    cols = y["columns"]
    dv = {k: v for k, v in cols.items() if k.startswith("damaged_volume_total_")}
    if "time" in cols and dv:
        fig, axes = plt.subplots(1, 2, figsize=(11.0, 3.4))
        ax = axes[0]
        for k, v in dv.items():
            ax.plot(cols["time"], v, label=k.removeprefix("damaged_volume_total_"))
        ax.set_xlabel("time (s)")
        ax.set_ylabel("damaged volume (m³)")
        ax.set_title("every region")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        # The paper's concrete (lining + inner structure): 63.2 m³ before the earthquake,
        # onset of growth at t ≈ 2.6 s (Yang, Chen & Xiao 2014, §4.6.1).
        concrete = [v for k, v in dv.items() if k.removeprefix("damaged_volume_total_") in ("lining", "inner")]
        ax = axes[1]
        if concrete:
            ax.plot(cols["time"], [sum(x) for x in zip(*concrete)], label="dcfm, lining + inner")
        ax.axhline(63.2, color="k", ls="--", lw=1, label="paper: 63.2 m³ before the earthquake")
        ax.axvline(2.6, color="r", ls=":", lw=1, label="paper: onset t ≈ 2.6 s")
        if cols["time"][-1] >= 60.0 - 1e-6:
            # The paper's steep growth in 2.6–20 s and 30–40 s and 460.3 m³ at 60 s (§4.6.1).
            for k, (a, b) in enumerate(((2.6, 20.0), (30.0, 40.0))):
                ax.axvspan(a, b, color="0.85", alpha=0.5, lw=0, label="paper: steep growth" if k == 0 else None)
            ax.plot([60.0], [460.3], "k*", ms=9, label="paper: 460.3 m³ at 60 s")
        ax.set_xlabel("time (s)")
        ax.set_title("concrete, against the paper's marks")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        rep.h(f'<figure class="wide"><img alt="damaged volume" src="data:image/png;base64,{_png(fig)}"><figcaption>Damaged volume over time '
              "(the CI mesh and a synthetic record: differences from the paper are expected and reported, not tuned)</figcaption></figure>")
    yingxiuwan_post_section(rep, y.get("post"), s)
    if y.get("measures"):
        measures_section(rep, y)
    rep.h("</section>")


def _concrete_history(run: dict[str, Any]) -> tuple[list[float], list[float]] | None:
    """Time and concrete damaged volume (lining + inner structure) of every history row."""
    cols = run.get("columns") or {}
    t, lin, inn = cols.get("time"), cols.get("damaged_volume_total_lining"), cols.get("damaged_volume_total_inner")
    if not t or not lin or not inn:
        return None
    return t, [a + b for a, b in zip(lin, inn)]


def _concrete_damage(run: dict[str, Any]) -> tuple[float | None, float | None, float | None, float | None]:
    """Concrete damaged volume (lining + inner structure, histories) at the first and the
    last row, and the lining's and the inner structure's at the last row."""
    history = _concrete_history(run)
    if history is None:
        return None, None, None, None
    cols = run["columns"]
    return history[1][0], history[1][-1], cols["damaged_volume_total_lining"][-1], cols["damaged_volume_total_inner"][-1]


def measures_section(rep: Report, y: dict[str, Any]) -> None:
    """The anti-seismic measures of paper §6 (generator `--measure`), each run like the
    base case: damaged volumes, physics checks and survey side by side, and the maps at
    the last frame."""
    runs = {"base case": y, **{m.replace("_", " "): r for m, r in y["measures"].items()}}
    rep.h("<h3>Anti-seismic measures (paper §6) side by side</h3><p>Each variant is the base case with the measures it "
          "names (`dcfm mesh yingxiuwan --measure NAME[,NAME…]`, or `all`; docs/yingxiuwan.md): a reinforced (stiffer) rock "
          "zone around the cavern, anchorage of the upper structure, a soft isolation layer between the lower structure "
          "and the rock; run over the same record and time. The paper shows the damaged areas after adopting the "
          "measures as smaller (its Figs. 15–16) without a volume.</p>")
    rep.m("### Anti-seismic measures (paper §6) side by side\n")
    for name, r in runs.items():
        record = r.get("record")
        if record is not None and r is not y:
            line = (f"{name}: recorded run, not rerun by this report: commit {record['commit']}, {record['date']}, "
                    f"{record['threads']} threads on {record['machine']}. {record['note']} How it was made: {record['command']}.")
            rep.h(f'<p class="meta">{esc(line)}</p>')
            rep.m(line + "\n")
    base_end = _concrete_damage(y)[1]
    rows, md = [], []
    for name, r in runs.items():
        v0, v1, lin, inn = _concrete_damage(r)
        s = r["summary"]
        checks = r.get("checks")
        passed = "–" if checks is None else f"{sum(1 for c in checks if c['passed'])}/{len(checks)}"
        survey = (r.get("post") or {}).get("survey") or []
        damaged = sum(1 for row in survey if row.get("damaged"))
        change = "–" if (v1 is None or not base_end) else f"{100.0 * (v1 / base_end - 1.0):+.1f} %"
        cells = [name, num(s.get("end_time")), num(v0), num(lin), num(inn), num(v1), change, passed,
                 f"{damaged}/{len(survey)}" if survey else "–", num(s.get("energy_residual_relative"))]
        rows.append("<tr>" + "".join(f"<td>{esc(c)}</td>" for c in cells) + "</tr>")
        md.append("| " + " | ".join(str(c) for c in cells) + " |")
    head = ["case", "end (s)", "concrete at 0 s (m³)", "lining at end (m³)", "inner at end (m³)", "concrete at end (m³)",
            "against base", "physics checks", "survey locations damaged", "energy residual"]
    rep.h('<div class="scroll"><table class="rows"><thead><tr>' + "".join(f"<th>{esc(h)}</th>" for h in head)
          + f"</tr></thead><tbody>{''.join(rows)}</tbody></table></div>")
    rep.m("| " + " | ".join(head) + " |\n|" + "---|" * len(head) + "\n" + "\n".join(md) + "\n")
    curves = {name: _concrete_history(r) for name, r in runs.items()}
    curves = {name: c for name, c in curves.items() if c is not None}
    if len(curves) > 1:
        fig, ax = plt.subplots(figsize=(7.0, 3.4))
        for name, (t, v) in curves.items():
            ax.plot(t, v, label=name)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("concrete damaged volume (m³)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        rep.h(f'<figure><img alt="damaged volume of each variant" src="data:image/png;base64,{_png(fig)}"><figcaption>'
              "Concrete damaged volume (lining + inner structure, histories) of the base case and of each variant</figcaption></figure>")
    maps = []
    for name, r in runs.items():
        images = (r.get("post") or {}).get("images") or {}
        last = [k for k in images if k.startswith("damage_") and not k.endswith("_0 s")]
        for k in last:
            maps.append((f"{name}: {k.replace('_', ' ')}", images[k]))
    if maps:
        rep.h('<div class="plots">')
        for caption, data in maps:
            rep.h(f'<figure><img alt="{esc(caption)}" src="data:image/png;base64,{data}"><figcaption>{esc(caption)}</figcaption></figure>')
        rep.h("</div>")
        rep.m("Maps at the last frame: " + ", ".join(c for c, _ in maps) + " (in index.html).\n")


def _yes(flag: Any, part: Any) -> str:
    return "–" if flag is None else f"{'yes' if flag else 'no'} ({100 * float(part):.1f} %)"


def _nth(d: dict[str, Any], key: str, k: int) -> Any:
    """Item k of the list d[key], or None where the list is missing or shorter."""
    values = d.get(key) or []
    return values[k] if k < len(values) else None


def yingxiuwan_post_section(rep: Report, post: dict[str, Any] | None, summary: dict[str, Any]) -> None:
    """The post-processing of the run (reports/yingxiuwan_post.py): the survey table, the
    interfaces' contact areas and the anchors' largest force at the first and the last
    frame, and the maps."""
    if post is None:
        rep.h('<p class="warn">No post-processing on record (results/yingxiuwan/post/post.json, reports/yingxiuwan_post.py): '
              "no survey table, contact areas, anchor forces or maps.</p>")
        rep.m("No post-processing on record (results/yingxiuwan/post/post.json).\n")
        return
    t0, t1 = (post.get("frame_times") or [0.0, summary.get("end_time")])[:2]
    end = summary.get("end_time")
    if end is not None and t1 is not None and abs(float(t1) - float(end)) > 1e-9:
        rep.h(f'<p class="warn">The post-processing\'s last frame (t = {esc(num(t1))} s) is not the run\'s end ({esc(num(end))} s): '
              "post.json is from another run.</p>")
        rep.m(f"Warning: the post-processing's last frame (t = {num(t1)} s) is not the run's end ({num(end)} s).\n")
    dv = post.get("damaged_volume") or {}
    if dv:
        line = (f"Concrete damaged volume (histories, integration points): {num(dv.get('before'))} m³ at 0 s (paper: 63.2 m³), "
                f"growth from {num(dv.get('onset'))} s (paper: 2.6 s), {num(dv.get('end'))} m³ at {num(dv.get('end_time'))} s "
                "(paper: 460.3 m³ at 60 s).")
        rep.h(f"<p>{esc(line)}</p>")
        rep.m(line + "\n")
    thr, shr = post.get("threshold", 0.1), post.get("damaged_share", 0.01)
    rep.h(f"<h3>Damaged locations against the post-earthquake survey</h3><p>Per element set of the generator: an element is damaged "
          f"when max(d<sub>t</sub>, d<sub>c</sub>) of the element reaches {esc(num(thr))}; a location is damaged (yes) when "
          f"{esc(num(100 * shr))} % of its volume is. The share in brackets is the damaged share of its volume "
          f"(survey: paper §4.1; paper's computation: §4.6, §5.1).</p>")
    rows, md = [], []
    for r in post["survey"]:
        if r.get("missing"):
            ours0 = ours1 = "set not in the frames"
        else:
            ours0, ours1 = _yes(r.get("damaged_0"), r.get("damaged_share_0")), _yes(r.get("damaged"), r.get("damaged_share_end"))
        rows.append(f"<tr><td>{esc(r['location'])}</td><td>{esc(r['survey'])}</td><td>{esc(r['paper'])}</td>"
                    f"<td>{esc(ours0)}</td><td>{esc(ours1)}</td><td>{esc(num(r.get('max_damage_end')))}</td></tr>")
        md.append(f"| {r['location']} | {r['survey']} | {r['paper']} | {ours0} | {ours1} | {num(r.get('max_damage_end'))} |")
    rep.h('<div class="scroll"><table class="rows"><thead><tr><th>location</th><th>survey found</th><th>paper shows</th>'
          f"<th>ours at {esc(num(t0))} s</th><th>ours at {esc(num(t1))} s</th><th>largest damage at {esc(num(t1))} s</th></tr></thead>"
          f"<tbody>{''.join(rows)}</tbody></table></div>")
    rep.m(f"### Damaged locations against the survey\n\n| location | survey found | paper shows | ours at {num(t0)} s | ours at {num(t1)} s | largest damage |\n"
          "|---|---|---|---|---|---|\n" + "\n".join(md) + "\n")
    levels = post.get("damage_levels") or []
    if len(levels) == 2 and all(isinstance(x, dict) for x in levels):
        a, b = levels
        rows, md = [], []
        for k, d in enumerate(b.get("levels") or []):
            cells = [_nth(a, "either", k)] + [_nth(b, c, k) for c in ("tension", "compression", "either")]
            rows.append(f"<tr><td>{esc(num(d))}</td>" + "".join(f"<td>{esc(num(v))}</td>" for v in cells) + "</tr>")
            md.append(f"| {num(d)} | " + " | ".join(num(v) for v in cells) + " |")
        what = (f"Concrete volume (m³; of {num(b.get('concrete_volume'))} m³ of active concrete) whose element damage reaches each level D*: "
                "the damaged volume of eq. (27) for other thresholds than the case's (the paper states none; its maps run from 0 to 1, "
                "460.3 m³ at 60 s).")
        rep.h(f"<h3>Damaged volume by damage level</h3><p>{esc(what)}</p>"
              '<div class="scroll"><table class="rows"><thead><tr><th>D*</th>'
              f"<th>max(d<sub>t</sub>, d<sub>c</sub>) at {esc(num(t0))} s</th><th>d<sub>t</sub> at {esc(num(t1))} s</th>"
              f"<th>d<sub>c</sub> at {esc(num(t1))} s</th><th>max(d<sub>t</sub>, d<sub>c</sub>) at {esc(num(t1))} s</th></tr></thead>"
              f"<tbody>{''.join(rows)}</tbody></table></div>")
        rep.m(f"### Damaged volume by damage level\n\n{what}\n\n| D* | max at {num(t0)} s | d_t at {num(t1)} s | d_c at {num(t1)} s | max at {num(t1)} s |\n"
              "|---|---|---|---|---|\n" + "\n".join(md) + "\n")
    areas = post.get("interface_areas") or {}
    if areas:
        states = ["bonded", "stick", "sliding", "separated"]
        rows, md = [], []
        for iface, a in areas.items():
            cells = [(a.get(k) or [None, None]) for k in states]
            rows.append(f"<tr><td>{esc(iface)}</td>" + "".join(f"<td>{esc(num(c[0]))}</td><td>{esc(num(c[1]))}</td>" for c in cells) + "</tr>")
            md.append(f"| {iface} | " + " | ".join(f"{num(c[0])} → {num(c[1])}" for c in cells) + " |")
        rep.h(f"<h3>Contact zones (m²) at {esc(num(t0))} s and {esc(num(t1))} s</h3>"
              '<div class="scroll"><table class="rows"><thead><tr><th rowspan="2">interface</th>'
              + "".join(f'<th colspan="2">{s}</th>' for s in states) + "</tr><tr>"
              + f"<th>{esc(num(t0))} s</th><th>{esc(num(t1))} s</th>" * len(states)
              + f"</tr></thead><tbody>{''.join(rows)}</tbody></table></div>")
        rep.m(f"### Contact zones (m², {num(t0)} s → {num(t1)} s)\n\n| interface | " + " | ".join(states) + " |\n|---|"
              + "---|" * len(states) + "\n" + "\n".join(md) + "\n")
    anchors = post.get("anchors") or {}
    if anchors:
        rows = "".join(f"<tr><td>{esc(k)}</td><td>{esc(num(v.get('max')))}</td><td>{esc(num(v.get('time_of_max')))}</td>"
                       f"<td>{esc(num(v.get('end')))}</td><td>{esc(num(v.get('yielded_segments_max')))}</td></tr>" for k, v in anchors.items())
        rep.h("<h3>Anchors</h3><div class=\"scroll\"><table class=\"rows\"><thead><tr><th>bolt pattern</th><th>largest axial force (N)</th>"
              f"<th>at (s)</th><th>largest at the end (N)</th><th>yielded segments (most)</th></tr></thead><tbody>{rows}</tbody></table></div>")
        rep.m("### Anchors\n\n| bolt pattern | largest axial force (N) | at (s) | at the end (N) |\n|---|---|---|---|\n"
              + "\n".join(f"| {k} | {num(v.get('max'))} | {num(v.get('time_of_max'))} | {num(v.get('end'))} |" for k, v in anchors.items()) + "\n")
    sec = post.get("post_seconds") or {}
    if sec:
        rep.h(f"<p>Post-processing: {esc(num(sec.get('total')))} s (tables {esc(num(sec.get('tables')))} s).</p>")
        rep.m(f"Post-processing: {num(sec.get('total'))} s.\n")
    images = post.get("images") or {}
    if images:
        rep.h("<h3>Maps</h3><p>Boundary faces of the lining and of the inner structure coloured by the element damage "
              "max(d<sub>t</sub>, d<sub>c</sub>) on a fixed 0–1 scale, and the contact state of the concrete's interface faces "
              "(concrete–rock and lining–inner structure; a face shows the furthest-gone state of its corners), at the first "
              "and the last frame. Drawn from the VTU by reports/yingxiuwan_post.py.</p><div class=\"plots\">")
        for key, data in images.items():
            rep.h(f'<figure><img alt="{esc(key)}" src="data:image/png;base64,{data}"><figcaption>{esc(key.replace("_", " "))}</figcaption></figure>')
        rep.h("</div>")
        rep.m("Maps: " + ", ".join(f"{k}" for k in images) + " (in index.html).\n")
    missing = post.get("missing_maps") or []
    if missing or not images:
        what = ", ".join(missing) if missing else "none rendered (run without maps?)"
        rep.h(f'<p class="warn">Maps missing: {esc(what)}.</p>')
        rep.m(f"Maps missing: {what}.\n")


HTML_TEMPLATE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{{TITLE}}</title>
<style>
:root { --fg: #1d2330; --muted: #5b6475; --line: #d9dee7; --ok: #17803d; --bad: #c62828; --bg: #f6f8fb; }
* { box-sizing: border-box; }
body { margin: 0; font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; color: var(--fg); background: #fff; }
header, nav, section { max-width: 1180px; margin: 0 auto; padding: 0 20px; }
header { padding-top: 24px; }
h1 { font-size: 1.7em; margin: 0 0 4px; }
h2 { font-size: 1.35em; margin: 34px 0 10px; padding-bottom: 4px; border-bottom: 2px solid var(--line); }
h3 { font-size: 1.1em; margin: 26px 0 8px; }
nav { position: sticky; top: 0; background: #fffffff0; padding: 8px 20px; border-bottom: 1px solid var(--line); z-index: 2; font-size: 0.95em; }
nav a { color: #1f4fa3; text-decoration: none; white-space: nowrap; }
.meta { color: var(--muted); margin: 4px 0; }
.warn { background: #fff4e5; border-left: 4px solid #f0a020; padding: 6px 10px; }
article { background: var(--bg); border: 1px solid var(--line); border-radius: 6px; padding: 4px 16px 12px; margin: 14px 0; }
dl { display: grid; grid-template-columns: max-content 1fr; gap: 4px 14px; margin: 8px 0 12px; }
dt { font-weight: 600; color: var(--muted); }
dd { margin: 0; }
.scroll { overflow-x: auto; max-width: 100%; }
table { border-collapse: collapse; width: 100%; font-size: 0.88em; background: #fff; }
th, td { border: 1px solid var(--line); padding: 4px 7px; text-align: left; vertical-align: top; }
th { background: #eef1f6; }
td:nth-child(2), td:nth-child(3), td:nth-child(4), td:nth-child(5) { font-variant-numeric: tabular-nums; white-space: nowrap; }
.ok { color: var(--ok); font-weight: 600; }
.bad { color: var(--bad); font-weight: 700; }
.toc { columns: 2; padding-left: 18px; }
.toc li { break-inside: avoid; }
.plots { display: grid; grid-template-columns: repeat(auto-fill, minmax(440px, 1fr)); gap: 12px; margin-top: 12px; }
figure { margin: 0; background: #fff; border: 1px solid var(--line); border-radius: 4px; padding: 6px; }
figure.wide { max-width: 1100px; }
figure img { width: 100%; height: auto; display: block; }
figcaption { font-size: 0.85em; color: var(--muted); text-align: center; }
code { background: #eef1f6; padding: 0 3px; border-radius: 3px; }
@media (max-width: 700px) {
  body { font-size: 14px; }
  header, nav, section { padding-left: 10px; padding-right: 10px; }
  .toc { columns: 1; }
  dl { grid-template-columns: 1fr; }
  dt { margin-top: 6px; }
  .plots { grid-template-columns: 1fr; }
  .scroll table.rows { min-width: 600px; }
  article { padding: 4px 8px 10px; }
}
</style>
</head>
<body>
{{BODY}}
<footer style="max-width:1180px;margin:30px auto;padding:0 20px;color:#5b6475;font-size:0.85em">
Generated by <code>reports/generate.py</code> from <code>results/</code> and <code>benchmarks/history.jsonl</code>.
</footer>
</body>
</html>
"""


def _write_atomic(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        f.write(text)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)


def generate(root: Path, out: Path) -> tuple[Path, Path]:
    """Read the inputs under ``root`` and write index.html and verification.md to ``out``."""
    inp = read_inputs(root)
    page, md, shown = build(inp)
    expected = [c["title"] for c in inp.cases] + [r["case"] for r in inp.cross_rows]
    missing = sorted({c for c in expected if c not in shown})
    if missing:
        raise ReportError(f"cases missing from the report: {missing}")
    index, verification = out / "index.html", out / "verification.md"
    _write_atomic(index, page)
    _write_atomic(verification, md)
    return index, verification


def main(argv: list[str] | None = None) -> int:
    here = Path(__file__).resolve().parent
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--root", type=Path, default=here.parent, help="repository root (default: this file's parent folder)")
    ap.add_argument("--out", type=Path, default=None, help="output folder (default: ROOT/reports)")
    a = ap.parse_args(argv)
    out = a.out or a.root / "reports"
    try:
        index, md = generate(a.root, out)
    except ReportError as e:
        print(f"reports/generate.py: {e}", file=sys.stderr)
        return 1
    print(f"wrote {index} and {md}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
