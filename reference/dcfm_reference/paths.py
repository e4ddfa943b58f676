"""Where the cross-checks read and write (relative to the repository root)."""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CROSSCHECK_DIR = ROOT / "results" / "crosscheck"
CROSSCHECK_JSON = CROSSCHECK_DIR / "crosscheck.json"
PERFORMANCE_JSON = CROSSCHECK_DIR / "performance.json"
CASES = ROOT / "cases"
