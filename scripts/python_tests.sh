#!/usr/bin/env bash
# The Python package (crates/softsculpt-py): a virtual environment in target/py-venv with what
# crates/softsculpt-py/requirements-test.txt pins, the package built into it (maturin develop
# --release: one abi3 wheel), then its pytest suite, which compares it with the CLI it builds
# (target/debug/softsculpt). Idempotent; the first run on a fresh machine downloads ~100 MB.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=$PWD/target/py-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv" || { echo "error: python3 -m venv failed (Debian: apt-get install python3-venv)" >&2; exit 1; }
fi
"$venv/bin/pip" install -q --disable-pip-version-check -r crates/softsculpt-py/requirements-test.txt
cargo build -q -p softsculpt-cli
VIRTUAL_ENV=$venv PATH="$venv/bin:$PATH" maturin develop -q --release -m crates/softsculpt-py/Cargo.toml
cd crates/softsculpt-py
SOFTSCULPT_CLI=$OLDPWD/target/debug/softsculpt "$venv/bin/python" -m pytest -p no:cacheprovider -p no:logging tests
