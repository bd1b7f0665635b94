#!/usr/bin/env bash
# Run every test suite, log each to target/test-logs/, and print one closing line
# "N passed, N failed" over all of them. Exits non-zero if any suite failed.
set -uo pipefail
cd "$(dirname "$0")/.."
logs=target/test-logs
rm -rf "$logs"
mkdir -p "$logs"
status=0
suite() { # name, command...
  local name=$1; shift
  echo "== $name"
  "$@" 2>&1 | tee "$logs/$name.log"
  local rc=${PIPESTATUS[0]}
  if [ "$rc" -ne 0 ]; then
    status=1
    # A suite that failed before reporting any count still counts as a failure.
    python3 scripts/test_summary.py "$logs/$name.log" | grep -q '^0 passed, 0 failed$' && echo "test result: FAILED. 0 passed; 1 failed" >> "$logs/$name.log"
  fi
}

suite setup scripts/setup.sh browser
suite cargo cargo test --workspace --no-fail-fast --color never
suite clippy cargo clippy --workspace --all-targets --color never -- -D warnings
suite wasm make --no-print-directory web
suite python scripts/python_tests.sh
suite vitest bash -c 'cd web && npx vitest run --reporter=default'
suite e2e bash -c 'cd web && node e2e/run.mjs'

echo
python3 scripts/test_summary.py "$logs"/*.log
exit $status
