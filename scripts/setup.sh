#!/usr/bin/env bash
# Install what building and testing SoftSculpt needs on a fresh machine. Idempotent.
#   scripts/setup.sh          Rust toolchain and the wasm target
#   scripts/setup.sh web      + the web modeler's npm packages (npm ci)
#   scripts/setup.sh browser  + Debian's chromium for the end-to-end tests
set -euo pipefail
cd "$(dirname "$0")/.."
want=${1:-rust}

if ! command -v cargo >/dev/null 2>&1; then
  if [ -x "$HOME/.cargo/bin/cargo" ]; then export PATH="$HOME/.cargo/bin:$PATH"; else
    echo "error: Rust (cargo) is not installed; install it with rustup (https://rustup.rs)" >&2; exit 1
  fi
fi
if command -v rustup >/dev/null 2>&1; then
  rustup show active-toolchain >/dev/null 2>&1 || rustup default stable
  if ! rustup target list --installed | grep -q '^wasm32-unknown-unknown$'; then
    echo "setup: adding the wasm32-unknown-unknown target"
    rustup target add wasm32-unknown-unknown
  fi
fi
command -v python3 >/dev/null 2>&1 || { echo "error: python3 is needed by the scripts" >&2; exit 1; }

if [ "$want" = web ] || [ "$want" = browser ]; then
  command -v npm >/dev/null 2>&1 || { echo "error: Node.js and npm are needed for the web modeler" >&2; exit 1; }
  if [ ! -d web/node_modules ] || [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then
    echo "setup: npm ci (web/)"
    (cd web && npm ci --no-audit --no-fund --loglevel=error)
  fi
fi

if [ "$want" = browser ] && [ ! -x /usr/bin/chromium ]; then
  echo "setup: installing Debian's chromium for the end-to-end tests"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium >/dev/null
fi
