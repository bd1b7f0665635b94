#!/usr/bin/env bash
# Run every test suite, log each to target/test-logs/, and print one closing line
# "N passed, N failed" over all of them. Exits non-zero if any suite failed.
set -uo pipefail
cd "$(dirname "$0")/.."
logs=target/test-logs
rm -rf "$logs"
mkdir -p "$logs"
status=0

echo "== Rust: core and CLI (cargo test --workspace)"
cargo test --workspace --color never 2>&1 | tee "$logs/cargo.log"
[ "${PIPESTATUS[0]}" -eq 0 ] || status=1

echo
python3 scripts/test_summary.py "$logs"/*.log
exit $status
