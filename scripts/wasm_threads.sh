#!/usr/bin/env bash
# The engine for WebAssembly on threads (issue #36 item 5) into web/public/softsculpt-threads.wasm:
# atomics and bulk memory, std rebuilt with them (nightly, rust-src, -Z build-std), the memory
# imported and shared (up to 4 GiB: web/src/engine/threads.ts MAXIMUM_PAGES must match), and the
# exports a helper Web Worker needs to start a thread on it (its stack pointer, its thread-local
# block). The page uses it where it is cross-origin isolated (web/src/engine/threads.ts) and
# the one-thread build otherwise or when this file is missing; so a machine where the nightly
# toolchain cannot be installed only loses the threads (`make web` says so and goes on).
set -euo pipefail
cd "$(dirname "$0")/.."
rustup toolchain install nightly --profile minimal >/dev/null
rustup component add rust-src --toolchain nightly >/dev/null
rustup target add wasm32-unknown-unknown --toolchain nightly >/dev/null
flags=(-C target-feature=+atomics,+bulk-memory,+mutable-globals,+simd128
  -C link-arg=--shared-memory -C link-arg=--max-memory=4294967296 -C link-arg=--import-memory
  -C link-arg=--export=__wasm_init_tls -C link-arg=--export=__tls_size -C link-arg=--export=__tls_align
  -C link-arg=--export=__tls_base -C link-arg=--export=__stack_pointer)
# Its own directory beside the other builds' (other flags): under CARGO_TARGET_DIR when set.
out="${CARGO_TARGET_DIR:-target}/wasm-threads"
RUSTFLAGS="${flags[*]}" cargo +nightly build -Z build-std=std,panic_abort --target wasm32-unknown-unknown \
  -p softsculpt-wasm --release --target-dir "$out"
mkdir -p web/public
cp "$out/wasm32-unknown-unknown/release/softsculpt_wasm.wasm" web/public/softsculpt-threads.wasm
ls -l web/public/softsculpt-threads.wasm
