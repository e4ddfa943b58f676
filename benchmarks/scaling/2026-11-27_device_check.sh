#!/bin/bash
# The script of the 2026-11-27 16-core check (docs/benchmarks.md). Copy it into a folder
# holding: dcfm and throughput (release, stripped), checkpoint.bin (a `dcfm run` of the
# Yingxiuwan CI case stopped at 3.0 s), stretch.toml (that case with end = 3.3),
# static_cg.toml (the generated CI case with [static] linear_solver =
# "conjugate_gradients" and end = 0.001) and yingxiuwan_ci.msh; $OUT receives the records.
set -u
cd "$(dirname "$0")"
nproc; grep -m1 "model name" /proc/cpuinfo; grep -o -m1 "avx512f" /proc/cpuinfo
for T in 1 16 2 4 8; do
  rm -rf r$T; mkdir r$T; cp checkpoint.bin r$T/
  /usr/bin/time -f "T=$T wall %e s, peak %M kB" timeout 120 ./dcfm run stretch.toml --out r$T --resume --threads $T --quiet 2>&1 | tail -2 | sed "s/^/T=$T /"
  cmp -s r1/checkpoint.bin r$T/checkpoint.bin && echo "T=$T stretch checkpoint identical to T=1" || echo "T=$T stretch checkpoint DIFFERS"
  cmp -s r1/histories.csv r$T/histories.csv && echo "T=$T stretch histories identical to T=1" || echo "T=$T stretch histories DIFFER"
  cp r$T/summary.json "$OUT/stretch_summary_$T.json"
done
for T in 1 16; do
  rm -rf s$T
  /usr/bin/time -f "T=$T static wall %e s, peak %M kB" timeout 120 ./dcfm run static_cg.toml --out s$T --threads $T --quiet 2>&1 | tail -2 | sed "s/^/T=$T /"
  for f in static_histories.csv histories.csv checkpoint.bin; do
    cmp -s s1/$f s$T/$f && echo "T=$T static $f identical to T=1" || echo "T=$T static $f DIFFERS"
  done
  cp s$T/static_summary.json "$OUT/static_summary_$T.json"
done
timeout 150 ./throughput --no-scipy --history "$OUT/history.jsonl" --filter cube40_full --sizes 40 --large-sizes "" --static-sizes "" --threads 1,2,4,8,16 --min-wall 1 2>&1 | grep -E "element-updates/s|speed-up|over the fixed|2/1|16/1" | head -80
