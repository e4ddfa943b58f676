#!/usr/bin/env bash
# Set up the Python side on a machine with a Rust toolchain and CPython 3.11 (venv + pip):
# a project-local virtual environment .venv with the pinned packages of
# reference/requirements.txt, and the dcfm module built into it by maturin.
# Idempotent: the venv is reused while requirements.txt is unchanged (its hash is kept in
# .venv/requirements.sha256); the module is rebuilt incrementally by cargo.
set -euo pipefail
cd "$(dirname "$0")/.."

PYTHON="${PYTHON:-python3.11}"
if ! command -v "$PYTHON" >/dev/null 2>&1; then
    PYTHON=python3
fi
"$PYTHON" - <<'PY'
import sys
if sys.version_info[:2] != (3, 11):
    sys.exit(f"scripts/setup.sh: Python 3.11 is required, found {sys.version.split()[0]} "
             "(set PYTHON=/path/to/python3.11)")
PY

REQ=reference/requirements.txt
want="$(sha256sum "$REQ" | cut -d' ' -f1)"
have="$(cat .venv/requirements.sha256 2>/dev/null || true)"
if [[ ! -x .venv/bin/python || "$want" != "$have" ]]; then
    echo "setup: creating .venv with the pinned packages of $REQ"
    rm -rf .venv
    "$PYTHON" -m venv .venv
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -r "$REQ"
    echo "$want" > .venv/requirements.sha256
else
    echo "setup: reusing .venv ($REQ unchanged)"
fi

echo "setup: building the dcfm module (maturin, release)"
VIRTUAL_ENV="$PWD/.venv" PATH="$PWD/.venv/bin:$PATH" \
    .venv/bin/maturin develop --release --quiet -m reference/dcfm-py/Cargo.toml
.venv/bin/python -c "import dcfm; print('setup: dcfm', dcfm.__version__, 'importable from .venv')"
