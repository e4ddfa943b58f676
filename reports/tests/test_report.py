"""The report generator: every case of results.json and crosscheck.json appears in the
report; unreadable files and rows are named; throughput drops of more than 10 % are
flagged; the page is self-contained."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import pytest

REPORTS = Path(__file__).resolve().parents[1]
ROOT = REPORTS.parent
sys.path.insert(0, str(REPORTS))

import generate  # noqa: E402


def row(case: str, quantity: str, ok: bool = True, **extra) -> dict:
    r = {
        "case": case,
        "quantity": quantity,
        "reference": 1.0,
        "computed": 1.001 if ok else 2.0,
        "rel_error": 1e-3 if ok else 1.0,
        "tolerance": 0.01,
        "pass": ok,
        "source": "docs/verification_references.md §W1",
    }
    r.update(extra)
    return r


def write_inputs(root: Path, *, history: list[dict] | None = None) -> None:
    v = root / "results/verification"
    v.mkdir(parents=True)
    cases = [
        {"id": "A1", "title": "Case A", "group": "Waves", "requirement": "req A", "reference": "ref A", "tolerance": "tol A"},
        {"id": "B2", "title": "Case B with | pipe", "group": "Contact", "requirement": "req B", "reference": "ref B", "tolerance": "tol B"},
    ]
    rows = [row("Case A", "peak"), row("Case A", "arrival"), row("Case B with | pipe", "slip", ok=False)]
    (v / "results.json").write_text(json.dumps({"commit": "abc1234", "cases": cases, "rows": rows, "errors": []}))
    (v / "series.json").write_text(json.dumps([
        {"case": "Case A", "name": "curve", "x_label": "t", "y_label": "u", "x": [0, 1, 2], "computed": [0, 1, 4], "reference": [0, 1, 4], "log_log": False}
    ]))
    c = root / "results/crosscheck"
    c.mkdir(parents=True)
    (c / "crosscheck.json").write_text(json.dumps({
        "commit": "abc1234",
        "rows": [row("Cross X", "frequency", peer="scikit-fem"), row("Cross Y", "peak", peer="FiPy")],
        "series": [{"case": "Cross Y", "name": "H", "x_label": "f", "y_label": "|H|", "x": [1, 2], "curves": {"dcfm": [1, 2], "FiPy": [1, 2.1]}}],
        "descriptions": {"Cross Y": "What Y compares & why its tolerance"},
    }))
    (c / "performance.json").write_text(json.dumps({"commit": "abc1234", "rows": [
        {"label": "p dcfm", "problem": "cube", "code": "dcfm", "variant": "full", "threads": 1, "elements": 8, "steps": 10, "wall_s": 1.0, "element_updates_per_s": 80.0},
        {"label": "p scipy", "problem": "cube", "code": "scipy", "variant": "CSR", "threads": 1, "elements": 8, "steps": 10, "wall_s": 3.0, "element_updates_per_s": 26.7},
    ]}))
    b = root / "benchmarks"
    b.mkdir()
    hist = history if history is not None else [
        {"case": "cube40_full", "threads": 2, "cpus": 2, "element_updates_per_s": 6.0e6, "commit": "c1", "mode": "standard"},
        {"case": "cube40_full", "threads": 2, "cpus": 2, "element_updates_per_s": 5.0e6, "commit": "c2", "mode": "standard"},
        {"case": "cube40_full", "threads": 2, "cpus": 2, "element_updates_per_s": 4.9e6, "commit": "c3", "mode": "standard"},
    ]
    (b / "history.jsonl").write_text("\n".join(json.dumps(h) for h in hist) + "\n")


def roots(tmp_path: Path) -> list[Path]:
    write_inputs(tmp_path)
    out = [tmp_path]
    # The repository's own results, when a main job has produced them.
    if (ROOT / "results/verification/results.json").exists():
        out.append(ROOT)
    return out


def test_every_case_appears_in_the_report(tmp_path):
    for root in roots(tmp_path / "in"):
        out = tmp_path / "out" / root.name
        index, md = generate.generate(root, out)
        page = index.read_text(encoding="utf-8")
        text = md.read_text(encoding="utf-8")
        results = json.loads((root / "results/verification/results.json").read_text())
        titles = [c["title"] for c in results["cases"]]
        cross = root / "results/crosscheck/crosscheck.json"
        if cross.exists():
            titles += [r["case"] for r in json.loads(cross.read_text())["rows"]]
        assert titles
        for t in titles:
            assert generate.esc(t) in page, f"{t} missing from {index}"
            assert t in text or t.replace("|", "\\|") in text, f"{t} missing from {md}"
        # Self-contained: no external resources.
        assert not re.search(r'(src|href)="(https?:|//|file:)', page)
        assert "data:image/png;base64," in page


def test_row_results_and_failures_are_shown(tmp_path):
    write_inputs(tmp_path)
    page, md, _ = generate.build(generate.read_inputs(tmp_path))
    assert "FAIL" in page and "❌" in md
    assert "req A" in page and "tol B" in md
    # Summary per group: Waves 2/2, Contact 0/1, cross-checks 2/2.
    assert "| Waves | 2 | 2 | 0 |" in md
    assert "| Contact | 1 | 0 | 1 |" in md
    assert "| Cross-checks against independent codes | 2 | 2 | 0 |" in md
    # The performance ratio against dcfm.
    assert "| cube | scipy | CSR | 1 | 8 | 10 | 3.000 | 2.67e+01 | 3.00 |" in md


def test_cross_check_descriptions_are_shown(tmp_path):
    write_inputs(tmp_path)
    page, md, _ = generate.build(generate.read_inputs(tmp_path))
    assert "What Y compares &amp; why its tolerance" in page
    assert "What Y compares & why its tolerance" in md
    cross = tmp_path / "results/crosscheck/crosscheck.json"
    d = json.loads(cross.read_text())
    d["descriptions"] = {"Cross Y": 3}
    cross.write_text(json.dumps(d))
    with pytest.raises(generate.ReportError, match="crosscheck.json: 'descriptions' must map case titles to texts"):
        generate.read_inputs(tmp_path)


def test_throughput_drop_is_flagged(tmp_path):
    write_inputs(tmp_path)
    inp = generate.read_inputs(tmp_path)
    drops = generate.throughput_drops(inp.history)
    assert [(d.commit, round(d.change, 3)) for d in drops] == [("c2", -0.167)]
    _, md, _ = generate.build(inp)
    assert "`c2`" in md and "-16.7 %" in md


@pytest.mark.parametrize(
    "path, mutate, message",
    [
        ("results/verification/results.json", lambda d: d["rows"][1].pop("computed"), "results.json: row 1 (Case A): missing key 'computed'"),
        ("results/verification/results.json", lambda d: d["rows"][2].update(tolerance="x"), "results.json: row 2 (Case B with | pipe): 'tolerance' = 'x' has the wrong type"),
        ("results/crosscheck/crosscheck.json", lambda d: d["rows"][0].pop("peer"), "crosscheck.json: row 0 (Cross X): missing key 'peer'"),
        ("results/verification/results.json", lambda d: d["rows"][0].update(case="Nowhere"), "results.json: row 0: case 'Nowhere' is not among the registered cases"),
    ],
)
def test_bad_rows_are_named(tmp_path, path, mutate, message):
    write_inputs(tmp_path)
    p = tmp_path / path
    doc = json.loads(p.read_text())
    mutate(doc)
    p.write_text(json.dumps(doc))
    with pytest.raises(generate.ReportError) as e:
        generate.read_inputs(tmp_path)
    assert message in str(e.value)
    assert str(p) in str(e.value)


def test_bad_history_line_is_named(tmp_path):
    write_inputs(tmp_path)
    h = tmp_path / "benchmarks/history.jsonl"
    h.write_text(h.read_text() + "{not json\n")
    with pytest.raises(generate.ReportError, match=r"history.jsonl: line 4: not JSON"):
        generate.read_inputs(tmp_path)


def test_main_reports_the_error_and_fails(tmp_path, capsys):
    write_inputs(tmp_path)
    (tmp_path / "results/verification/results.json").write_text("[1, 2")
    assert generate.main(["--root", str(tmp_path)]) == 1
    assert "results.json: not JSON" in capsys.readouterr().err


def test_yingxiuwan_section_only_with_its_results(tmp_path):
    write_inputs(tmp_path)
    page, _, _ = generate.build(generate.read_inputs(tmp_path))
    assert 'id="yingxiuwan"' not in page
    y = tmp_path / "results/yingxiuwan"
    y.mkdir(parents=True)
    (y / "summary.json").write_text(json.dumps({"title": "Yingxiuwan", "nodes": 10, "elements": 5}))
    (y / "histories.csv").write_text("time,damaged_volume_total_rock\n0,0\n1,63.2\n")
    page, md, _ = generate.build(generate.read_inputs(tmp_path))
    assert 'id="yingxiuwan"' in page and "## Yingxiuwan" in md


def test_recorded_runs_get_their_own_section_with_provenance(tmp_path):
    import shutil

    write_inputs(tmp_path)
    src = ROOT / "reports/recorded/yingxiuwan_ci_60s"
    dst = tmp_path / "reports/recorded/yingxiuwan_ci_60s"
    shutil.copytree(src, dst)
    page, md, _ = generate.build(generate.read_inputs(tmp_path))
    record = json.loads((src / "record.json").read_text())
    assert f'id="recorded-yingxiuwan_ci_60s"' in page and f"## {record['title']}" in md
    assert "Recorded run, not rerun by this report: commit c082d3f" in md
    # The paper's 60 s figure beside ours, the survey table and the 60 s maps.
    assert "paper: 460.3 m³ at 60 s" in md and "ours at 60 s" in md
    assert "damage_lining_60 s" in md
    # A recorded run with a file missing is refused by name.
    (dst / "checks.json").unlink()
    with pytest.raises(generate.ReportError, match="checks.json"):
        generate.read_inputs(tmp_path)


def test_recorded_measures_are_shown_beside_their_recorded_base(tmp_path):
    import shutil

    write_inputs(tmp_path)
    src = ROOT / "reports/recorded/yingxiuwan_ci_60s"
    rec = tmp_path / "reports/recorded"
    shutil.copytree(src, rec / "yingxiuwan_ci_60s")
    measure = rec / "yingxiuwan_ci_60s_measure"
    shutil.copytree(src, measure)
    record = json.loads((src / "record.json").read_text())
    record.update(title="A measure", commit="abc9999", measure_of="yingxiuwan_ci_60s", measure="every measure")
    (measure / "record.json").write_text(json.dumps(record))
    # Half the damage of the base at the last row: the table says -50 %.
    lines = (src / "histories.csv").read_text().splitlines()
    header = lines[0].split(",")
    cols = [header.index("damaged_volume_total_lining"), header.index("damaged_volume_total_inner")]
    rows = []
    for line in lines[1:]:
        v = line.split(",")
        for c in cols:
            v[c] = repr(float(v[c]) / 2)
        rows.append(",".join(v))
    (measure / "histories.csv").write_text("\n".join([lines[0], *rows]) + "\n")
    page, md, _ = generate.build(generate.read_inputs(tmp_path))
    # No section of its own; a row, its provenance and its maps in the base's section.
    assert 'id="recorded-yingxiuwan_ci_60s_measure"' not in page and "## A measure" not in md
    assert "Anti-seismic measures (paper §6) side by side" in md
    assert "every measure: recorded run, not rerun by this report: commit abc9999" in md
    row = next(line for line in md.splitlines() if line.startswith("| every measure |"))
    assert "| -50.0 % |" in row
    assert "every measure: damage lining 60 s" in md
    # A measure whose base is not recorded is refused by name.
    record["measure_of"] = "no_such_run"
    (measure / "record.json").write_text(json.dumps(record))
    with pytest.raises(generate.ReportError, match="'measure_of': 'no_such_run'"):
        generate.read_inputs(tmp_path)


def test_measures_are_shown_beside_the_base_case(tmp_path):
    write_inputs(tmp_path)
    hist = "time,damaged_volume_total_lining,damaged_volume_total_inner\n0,10,0\n3,100,100\n"
    y = tmp_path / "results/yingxiuwan"
    y.mkdir(parents=True)
    (y / "summary.json").write_text(json.dumps({"title": "Yingxiuwan", "end_time": 3.0}))
    (y / "histories.csv").write_text(hist)
    m = tmp_path / "results/yingxiuwan_measures/isolation_layer"
    m.mkdir(parents=True)
    (m / "summary.json").write_text(json.dumps({"title": "Yingxiuwan, isolation", "end_time": 3.0}))
    (m / "histories.csv").write_text(hist.replace("3,100,100", "3,100,50"))
    (m / "checks.json").write_text(json.dumps([{"name": "c", "value": 1, "limit": 2, "passed": True, "what": "w"}]))
    page, md, _ = generate.build(generate.read_inputs(tmp_path))
    assert "Anti-seismic measures (paper §6) side by side" in md
    # Base 200 m³ at the end, the measure 150 m³: −25 %, its checks counted.
    assert "| base case | 3 | 10 | 100 | 100 | 200 | +0.0 % |" in md
    assert "| isolation layer | 3 | 10 | 100 | 50 | 150 | -25.0 % | 1/1 |" in md
    # A measure's folder without its summary is named.
    (m / "summary.json").unlink()
    with pytest.raises(generate.ReportError, match="isolation_layer"):
        generate.read_inputs(tmp_path)
