# SoftSculpt: `make run` (the modeler) and `make test` (every test) work on a fresh machine.
SHELL := /bin/bash
CARGO ?= cargo
# Cargo's output directory: CARGO_TARGET_DIR when set (a worktree's own), else target/.
TARGET := $(or $(CARGO_TARGET_DIR),target)
BIN := $(TARGET)/release/softsculpt
WASM := $(TARGET)/wasm32-unknown-unknown/release/softsculpt_wasm.wasm

.PHONY: run test bench setup build wasm wasm-threads web demo test-fine

setup:
	@scripts/setup.sh

build: setup
	$(CARGO) build --release -p softsculpt-cli

# The engine for the browser (WebAssembly with SIMD, see .cargo/config.toml).
wasm: setup
	$(CARGO) build --release -p softsculpt-wasm --target wasm32-unknown-unknown
	@mkdir -p web/public
	cp $(WASM) web/public/softsculpt.wasm

# The same on threads (nightly; web/src/engine/threads.ts): optional, the page runs without it.
wasm-threads: setup
	@scripts/wasm_threads.sh || echo "SoftSculpt: the threaded engine could not be built (see above); the page will run on one thread"

web: wasm wasm-threads
	@scripts/setup.sh web
	cd web && npx tsc --noEmit && npx vite build

# The modeler on http://127.0.0.1:5173, opening on the mushroom resting on the ground.
run: web
	@echo "SoftSculpt modeler: open http://127.0.0.1:5173 (Ctrl+C to stop)"
	cd web && npx vite preview --host 127.0.0.1 --port 5173 --strictPort

# Headless: the built-in mushroom inflating with gas and settling on the ground (Fig. 2).
demo: build
	@mkdir -p out
	$(BIN) simulate builtin:mushroom --out out/mushroom.obj --gas 30 --ground 0 --damping 2 \
		--steps 10000 --until-rest 1e-3 --stats out/mushroom-stats.jsonl
	@echo "SoftSculpt: wrote $(CURDIR)/out/mushroom.obj (statistics: out/mushroom-stats.jsonl)"

test:
	@scripts/run_tests.sh

# The materials at the finer resolution (tests/presets_fine.rs: each preset pressed and pulled on
# the mushroom, sphere and octopus subdivided twice); an hour or more on two cores, not in `test`.
test-fine:
	$(CARGO) test --release -p softsculpt --test presets_fine -- --ignored --nocapture --test-threads=1

# The standard workload side by side with the reference C++ loop in ../shared/bench, then the
# criterion bench of one step.
bench: build
	python3 scripts/bench_compare.py --steps 1000 --rounds 3
	$(CARGO) bench -p softsculpt --bench step
