#!/usr/bin/env bash
# Install what building and testing SoftSculpt needs on a fresh machine. Idempotent.
set -euo pipefail
if ! command -v cargo >/dev/null 2>&1; then
  if [ -x "$HOME/.cargo/bin/cargo" ]; then
    export PATH="$HOME/.cargo/bin:$PATH"
  else
    echo "error: Rust (cargo) is not installed; install it with rustup (https://rustup.rs)" >&2
    exit 1
  fi
fi
if command -v rustup >/dev/null 2>&1; then
  rustup show active-toolchain >/dev/null 2>&1 || rustup default stable
fi
command -v python3 >/dev/null 2>&1 || { echo "error: python3 is needed by the test scripts" >&2; exit 1; }
