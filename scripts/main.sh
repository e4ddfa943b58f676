#!/usr/bin/env bash
# The main job: set up (.venv, the dcfm module), build, run every verification case
# (results/verification/results.json + series.json), the cross-checks against independent
# codes (results/crosscheck/), and generate the report (reports/index.html,
# reports/verification.md). Every stage runs even if an earlier one found failures, so
# that the report shows them; the exit status is non-zero if any stage failed.
set -euo pipefail
cd "$(dirname "$0")/.."

status=0
bash scripts/setup.sh
# The whole workspace with every target: the same feature resolution as the tests'
# `cargo test --workspace --release`, so the two share one build of the dependencies
# (a `cargo run -p` would resolve features for one package and rebuild them).
cargo build --release --workspace --all-targets
echo "main: verification cases"
"${CARGO_TARGET_DIR:-target}/release/dcfm-verification" || status=1
echo "main: cross-checks"
.venv/bin/python -m pytest -q reference/tests || status=1
echo "main: report"
.venv/bin/python reports/generate.py || status=1
exit "$status"
