#!/usr/bin/env bash
# The engine for WebAssembly with threads' prerequisites (issue #36 item 5): atomics and bulk
# memory, std rebuilt with them (nightly, rust-src), the memory imported and shared, the TLS
# exports a Web Worker needs to start a thread. Into /tmp/wasm-mt; check it with
# `node web/bench/threaded-build.mjs` (from web/). Not used by the page yet.
set -euo pipefail
rustup toolchain install nightly --profile minimal >/dev/null
rustup component add rust-src --toolchain nightly >/dev/null
rustup target add wasm32-unknown-unknown --toolchain nightly >/dev/null
RUSTFLAGS="-C target-feature=+atomics,+bulk-memory,+mutable-globals,+simd128 -C link-arg=--shared-memory -C link-arg=--max-memory=1073741824 -C link-arg=--import-memory -C link-arg=--export=__wasm_init_tls -C link-arg=--export=__tls_size -C link-arg=--export=__tls_align -C link-arg=--export=__tls_base" \
  cargo +nightly build -Z build-std=std,panic_abort --target wasm32-unknown-unknown -p softsculpt-wasm --release --target-dir /tmp/wasm-mt
ls -l /tmp/wasm-mt/wasm32-unknown-unknown/release/softsculpt_wasm.wasm
