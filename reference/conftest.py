"""pytest set-up of the cross-checks: the repository root on the path, and the rows,
curves and timings collected during the session merged into results/crosscheck/ at its
end."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

from dcfm_reference import record  # noqa: E402
from dcfm_reference.paths import CROSSCHECK_JSON, PERFORMANCE_JSON, ROOT  # noqa: E402


def _commit() -> str:
    try:
        out = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True
        )
        return out.stdout.strip() or "unknown"
    except OSError:
        return "unknown"


def pytest_sessionfinish(session, exitstatus):  # noqa: ARG001 (pytest hook signature)
    record.flush(CROSSCHECK_JSON, PERFORMANCE_JSON, _commit())
