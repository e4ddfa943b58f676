#!/usr/bin/env bash
# The main job: set up (.venv, the dcfm module), build, run every verification case
# (results/verification/results.json + series.json), the Yingxiuwan CI case with its physics
# checks and post-processing (results/yingxiuwan/) and its three anti-seismic measures
# (results/yingxiuwan_measures/), the cross-checks against independent
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
echo "main: Yingxiuwan CI case, 3 s of shaking, physics checks"
# The paper's case on the CI mesh (≈ 13.6k hex8): static stage, then 3 s of the synthetic
# Wolong-like record (the paper's damage onset is at 2.6 s), checked against physics
# (reports/yingxiuwan_checks.py), not golden numbers. About 5 min on 2 cores.
dcfm="${CARGO_TARGET_DIR:-target}/release/dcfm"
yx=results/yingxiuwan
"$dcfm" mesh yingxiuwan --variant ci --end 3 --out results/yingxiuwan_case \
  && "$dcfm" run results/yingxiuwan_case/yingxiuwan_ci.toml --out "$yx" --quiet \
  && .venv/bin/python reports/yingxiuwan_checks.py "$yx" --case results/yingxiuwan_case/yingxiuwan_ci.toml \
  || status=1
# Its post-processing (reports/yingxiuwan_post.py: damaged-volume history, survey table,
# contact areas, anchors, maps at the first and last frame; a few seconds), also when a
# physics check failed, so that the report shows what happened. The old output goes first:
# the report must not show maps of an earlier run.
rm -rf "$yx/post"
.venv/bin/python reports/yingxiuwan_post.py "$yx" --sets results/yingxiuwan_case/yingxiuwan_ci_sets.json --out "$yx/post" \
  || status=1
echo "main: Yingxiuwan anti-seismic measures, 3 s each"
# Paper §6: the base case with one measure each (a reinforced rock zone, anchorage of the
# upper structure, a soft isolation layer under the lower structure), same record and
# time, checked and post-processed like the base case; the report shows them side by
# side. About 2.5 min each on 2 cores.
rm -rf results/yingxiuwan_measures
for m in reinforced_rock upper_anchorage isolation_layer; do
  case_dir="results/yingxiuwan_case_$m"
  run="results/yingxiuwan_measures/$m"
  "$dcfm" mesh yingxiuwan --variant ci --end 3 --measure "$m" --out "$case_dir" \
    && "$dcfm" run "$case_dir/yingxiuwan_ci_$m.toml" --out "$run" --quiet \
    && .venv/bin/python reports/yingxiuwan_checks.py "$run" --case "$case_dir/yingxiuwan_ci_$m.toml" \
    || status=1
  .venv/bin/python reports/yingxiuwan_post.py "$run" --sets "$case_dir/yingxiuwan_ci_${m}_sets.json" --out "$run/post" \
    || status=1
done
echo "main: cross-checks"
# Not run a second time when results/crosscheck/ already holds a passing run of all of
# them on the same module and inputs (the tests' run, in CI): reference/dcfm_reference/
# freshness.py fingerprints what they read; anything changed, missing or failed reruns them.
if ! PYTHONPATH=reference .venv/bin/python -m dcfm_reference.freshness; then
  .venv/bin/python -m pytest -q reference/tests || status=1
fi
echo "main: report"
.venv/bin/python reports/generate.py || status=1
exit "$status"
