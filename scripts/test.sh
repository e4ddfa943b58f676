#!/usr/bin/env bash
# The tests: set up (.venv, the dcfm module), the Rust tests of the whole workspace
# (unit, analytic cases, convergence, snapshots, properties), then pytest: the module's
# bindings, the cross-checks against independent codes and the report generator.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cargo test --workspace --release
.venv/bin/python -m pytest -q reference/tests reports/tests
