"""pytest set-up of the cross-checks: the repository root on the path, the rows, curves
and timings collected during the session merged into results/crosscheck/ at its end, and
results/crosscheck/fresh.json written when the session ran every cross-check and all
passed (dcfm_reference/freshness.py: the main job then need not run them again)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

from dcfm_reference import freshness, record  # noqa: E402
from dcfm_reference.paths import CROSSCHECK_JSON, PERFORMANCE_JSON, ROOT  # noqa: E402


def _commit() -> str:
    try:
        out = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True
        )
        return out.stdout.strip() or "unknown"
    except OSError:
        return "unknown"


_INPUTS: dict[str, str] = {}


def pytest_sessionstart(session):  # noqa: ARG001 (pytest hook signature)
    _INPUTS["fingerprint"] = freshness.fingerprint()


def _ran_every_crosscheck(session) -> tuple[bool, int]:
    """Whether the session ran all of reference/tests (no test chosen by node id, keyword,
    mark or last-failed, none deselected), and how many of them passed."""
    opt = session.config.option
    chosen = any("::" in str(a) for a in session.config.args)
    filtered = bool(getattr(opt, "keyword", "")) or bool(getattr(opt, "markexpr", ""))
    filtered |= bool(getattr(opt, "lf", False)) or bool(getattr(opt, "deselect", None))
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    stats = reporter.stats if reporter is not None else {}
    root = Path(session.config.rootpath)
    collected = (Path(item.path).resolve() for item in session.items)
    files = {str(p.relative_to(ROOT)) for p in collected if p.is_relative_to(freshness.TESTS_DIR)}
    passed = sum(
        1
        for r in stats.get("passed", [])
        if r.when == "call" and (root / r.nodeid.split("::")[0]).resolve().is_relative_to(freshness.TESTS_DIR)
    )
    complete = freshness.test_files() <= files and not stats.get("deselected")
    return complete and not chosen and not filtered and reporter is not None, passed


def pytest_sessionfinish(session, exitstatus):
    record.flush(CROSSCHECK_JSON, PERFORMANCE_JSON, _commit())
    ran_all, passed = _ran_every_crosscheck(session)
    freshness.record_session(_INPUTS.get("fingerprint"), ran_all, passed, exitstatus == 0)
