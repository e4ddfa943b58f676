"""The main job's reuse of a passing cross-check run (dcfm_reference/freshness.py): the
fingerprint must change with any input's bytes, and fresh.json must only be written for a
complete, passing session on unchanged inputs."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from dcfm_reference import freshness


@pytest.fixture
def sandbox(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A repository stand-in with two inputs and a results folder."""
    (tmp_path / "inputs").mkdir()
    (tmp_path / "inputs" / "a.txt").write_bytes(b"alpha")
    (tmp_path / "inputs" / "__pycache__").mkdir()
    (tmp_path / "inputs" / "__pycache__" / "x.pyc").write_bytes(b"cache")
    (tmp_path / "single.txt").write_bytes(b"one")
    monkeypatch.setattr(freshness, "ROOT", tmp_path)
    monkeypatch.setattr(freshness, "INPUTS", ("inputs", "single.txt", "absent"))
    monkeypatch.setattr(freshness, "FRESH_JSON", tmp_path / "results" / "fresh.json")
    monkeypatch.setattr(freshness, "_module_files", lambda: [])
    return tmp_path


def test_fingerprint_follows_every_input_byte_and_ignores_caches(sandbox: Path) -> None:
    base = freshness.fingerprint()
    assert freshness.fingerprint() == base
    (sandbox / "inputs" / "__pycache__" / "x.pyc").write_bytes(b"other cache")
    assert freshness.fingerprint() == base
    (sandbox / "inputs" / "a.txt").write_bytes(b"alphb")
    changed = freshness.fingerprint()
    assert changed != base
    (sandbox / "inputs" / "a.txt").write_bytes(b"alpha")
    assert freshness.fingerprint() == base
    (sandbox / "absent").write_bytes(b"")
    assert freshness.fingerprint() != base, "an input that appears must change it, even empty"
    (sandbox / "absent").unlink()
    (sandbox / "inputs" / "b.txt").write_bytes(b"")
    assert freshness.fingerprint() != base, "a new file in an input folder must change it"


def test_only_a_complete_passing_session_on_unchanged_inputs_is_recorded(sandbox: Path) -> None:
    start = freshness.fingerprint()
    freshness.record_session(start, ran_all=True, passed=7, exit_ok=True)
    fresh, why = freshness.status()
    assert fresh, why
    assert json.loads(freshness.FRESH_JSON.read_text())["passed"] == 7
    assert "7 cross-check tests" in why

    # An input edited after the run: stale.
    (sandbox / "single.txt").write_bytes(b"two")
    fresh, why = freshness.status()
    assert not fresh and "changed" in why
    (sandbox / "single.txt").write_bytes(b"one")
    assert freshness.status()[0]

    # A failed, partial or edited-during-the-run session removes the record.
    for kwargs in ({"ran_all": True, "exit_ok": False}, {"ran_all": False, "exit_ok": True}):
        freshness.record_session(start, passed=7, **kwargs)
        assert not freshness.FRESH_JSON.exists()
        assert not freshness.status()[0]
        freshness.record_session(start, ran_all=True, passed=7, exit_ok=True)
    (sandbox / "inputs" / "a.txt").write_bytes(b"edited while running")
    freshness.record_session(start, ran_all=True, passed=7, exit_ok=True)
    assert not freshness.FRESH_JSON.exists()
    freshness.record_session(None, ran_all=True, passed=7, exit_ok=True)
    assert not freshness.FRESH_JSON.exists()


def test_an_unreadable_record_is_not_fresh(sandbox: Path) -> None:
    freshness.FRESH_JSON.parent.mkdir(parents=True)
    freshness.FRESH_JSON.write_text("{not json")
    fresh, why = freshness.status()
    assert not fresh and "unreadable" in why


def test_the_installed_module_is_part_of_the_fingerprint() -> None:
    files = freshness._module_files()
    names = {f.name for f in files}
    assert "__init__.py" in names, names
    assert any(n.endswith((".so", ".pyd")) for n in names), f"no compiled extension among {sorted(names)}"
