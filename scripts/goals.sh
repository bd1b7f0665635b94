#!/usr/bin/env bash
# Every speed goal of issue #9 measured in one run (BENCHMARKS.md, "Where issue #9's goals
# stand"): the implicit standard workload (dt = 1/60 s, k = 1000 N/m) at levels 4-7 on 1 and 2
# threads natively and in wasm, at the default tolerance and at 1e-3; the explicit standard
# workload next to the C++ loop on 2 and 1 threads; with `browser`, the largest sphere in real
# time in Chromium at the modeler's defaults.
#   scripts/goals.sh [browser]      (after `make web` and `cargo build --release -p softsculpt-cli`)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=target/release/softsculpt
[ -x "$bin" ] || { echo "error: $bin is missing: cargo build --release -p softsculpt-cli" >&2; exit 1; }
[ -f web/public/softsculpt.wasm ] || { echo "error: web/public/softsculpt.wasm is missing: make wasm" >&2; exit 1; }
dt=0.0166666666667
date; uptime; grep -m1 'model name' /proc/cpuinfo || true
for tol in "" 1e-3; do
  echo "== implicit native, tolerance ${tol:-default}"
  for t in 1 2; do
    echo "-- threads $t"
    "$bin" bench --levels 4,5,6,7 --steps 10 --reps 2 --integrator implicit --dt "$dt" --threads "$t" ${tol:+--tolerance "$tol"}
  done
done
# wasm-bench.mjs times the native one-thread step again beside each wasm run: the ratio comes
# from one pair, the loop above gives the thread comparison.
echo "== implicit wasm vs native, one thread"
(cd web && node bench/wasm-bench.mjs 4,5,6,7 10 implicit && node bench/wasm-bench.mjs 4,5,6,7 10 implicit:1e-3)
echo "== explicit vs the C++ loop"
for t in 2 1; do
  echo "-- threads $t"
  python3 scripts/bench_compare.py --levels 4,5,6,7 --steps 500 --rounds 3 --threads "$t"
done
if [ "${1:-}" = browser ]; then
  echo "== Chromium, the modeler's defaults (simulated s per real s), 2-7 s and 80-90 s after the import"
  [ -f web/dist/index.html ] || { echo "error: web/dist is missing: make web" >&2; exit 1; }
  (cd web && SETTLE=2 MEASURE=5 node bench/realtime.mjs 3,4,5 default && SETTLE=80 MEASURE=10 node bench/realtime.mjs 5 default)
fi
date; uptime
