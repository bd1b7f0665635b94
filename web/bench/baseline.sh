#!/usr/bin/env bash
# Build the modeler as it was at REV (default: the start of the web-worker branch, the engine on
# the main thread) into OUT, for side-by-side benchmarks (frame-gaps.mjs, realtime.mjs).
# Uses this checkout's node_modules and public/softsculpt.wasm (the binding is unchanged).
#   bench/baseline.sh [REV=6c06968] [OUT=/tmp/softsculpt-main-dist]
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-6c06968}
out=${2:-/tmp/softsculpt-main-dist}
src=$(mktemp -d)
git archive "$rev" -- . | tar -x -C "$src"
ln -s "$PWD/node_modules" "$src/node_modules"
mkdir -p "$src/public" && cp public/softsculpt.wasm "$src/public/"
(cd "$src" && node node_modules/vite/bin/vite.js build --outDir "$out" --emptyOutDir --logLevel warn)
rm -rf "$src"
echo "built $rev into $out"
