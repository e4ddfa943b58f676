"""Whether ``results/crosscheck/`` already holds a passing run of every cross-check on the
inputs as they are now, so that the main job need not run them a second time after the
tests did (CI runs the tests, then the main job, on the same tree and module).

The fingerprint is a SHA-256 over everything the cross-checks read: the compiled ``dcfm``
module (every file of the installed package, the extension included), the cross-checks'
own code (``reference/``), the scripts, fixtures and cases they load, and the pinned
Python environment (``.venv/requirements.sha256``, written by scripts/setup.sh). A pytest
session writes ``fresh.json`` only when it ran all of ``reference/tests`` (no test chosen
by node id, keyword, mark or last-failed) and every test passed; any other session
removes it. The main job reruns the cross-checks unless ``fresh.json`` holds the
fingerprint of the inputs as they are when it looks.

Run as ``python -m dcfm_reference.freshness`` (with ``reference`` on the path): exit
status 0 and a line saying so when the results are fresh, 1 and the reason otherwise.
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import os
import sys
from pathlib import Path
from typing import Any

from dcfm_reference import record
from dcfm_reference.paths import CROSSCHECK_DIR, ROOT

FRESH_JSON = CROSSCHECK_DIR / "fresh.json"
TESTS_DIR = ROOT / "reference" / "tests"

# What the cross-checks read from the repository, relative to its root.
INPUTS = (
    "reference/conftest.py",
    "reference/dcfm_reference",
    "reference/tests",
    "reference/requirements.txt",
    ".venv/requirements.sha256",
    "benchmarks/python",
    "verification/fixtures",
    "cases",
)


def _files_under(path: Path) -> list[Path]:
    if path.is_file():
        return [path]
    if not path.is_dir():
        return []
    found = []
    for dirpath, dirnames, filenames in os.walk(path):
        dirnames[:] = sorted(d for d in dirnames if d != "__pycache__")
        found.extend(Path(dirpath) / f for f in sorted(filenames) if not f.endswith(".pyc"))
    return found


def _module_files() -> list[Path]:
    """The files of the installed ``dcfm`` package (its Python stubs and the compiled
    extension), found without importing it."""
    spec = importlib.util.find_spec("dcfm")
    if spec is None:
        return []
    dirs = list(spec.submodule_search_locations or [])
    if not dirs and spec.origin:
        return [Path(spec.origin)]
    return [p for d in dirs for p in _files_under(Path(d))]


def fingerprint() -> str:
    """SHA-256 over the names and contents of every input; a missing input counts too."""
    digest = hashlib.sha256()
    groups = [(name, _files_under(ROOT / name)) for name in INPUTS]
    groups.append(("dcfm module", _module_files()))
    for name, files in groups:
        digest.update(f"[{name}] {len(files)}\n".encode())
        for f in files:
            digest.update(f.name.encode() + b"\0" + str(f.stat().st_size).encode() + b"\0")
            digest.update(f.read_bytes())
    return digest.hexdigest()


def test_files() -> set[str]:
    """The cross-check test files, relative to the repository root."""
    return {str(p.relative_to(ROOT)) for p in TESTS_DIR.glob("test_*.py")}


def record_session(inputs: str | None, ran_all: bool, passed: int, exit_ok: bool) -> None:
    """After a pytest session: write ``fresh.json`` if the session ran every cross-check
    and all passed on the inputs fingerprinted at its start, else remove it."""
    if inputs is None or not ran_all or not exit_ok or inputs != fingerprint():
        FRESH_JSON.unlink(missing_ok=True)
        return
    record.write_atomic(FRESH_JSON, {"fingerprint": inputs, "passed": passed})


def status() -> tuple[bool, str]:
    """Whether the recorded results are fresh, and a line that says why or why not."""
    try:
        doc: Any = json.loads(FRESH_JSON.read_text(encoding="utf-8"))
    except FileNotFoundError:
        return False, "no passing run of all cross-checks is recorded"
    except (OSError, json.JSONDecodeError) as err:
        return False, f"{FRESH_JSON.relative_to(ROOT)} is unreadable ({err})"
    now = fingerprint()
    if not isinstance(doc, dict) or doc.get("fingerprint") != now:
        return False, "the module, the cross-checks or their inputs changed since the last passing run"
    return True, (
        f"results/crosscheck/ is from a passing run of all {doc.get('passed')} cross-check "
        f"tests on these inputs (fingerprint {now[:12]}); not run again"
    )


def main() -> int:
    fresh, why = status()
    print(f"crosscheck: {why}")
    return 0 if fresh else 1


if __name__ == "__main__":
    sys.exit(main())
