# SoftSculpt: `make run` (the main job) and `make test` (every test) work on a fresh machine.
SHELL := /bin/bash
CARGO ?= cargo
BIN := target/release/softsculpt

.PHONY: run test bench setup build

setup:
	@scripts/setup.sh

build: setup
	$(CARGO) build --release -p softsculpt-cli

# The built-in mushroom inflating with gas and settling on the ground (the paper's Fig. 2).
run: build
	@mkdir -p out
	$(BIN) simulate builtin:mushroom --out out/mushroom.obj --gas 30 --ground 0 --damping 2 \
		--steps 10000 --until-rest 1e-3 --stats out/mushroom-stats.jsonl
	@echo "SoftSculpt: wrote $(CURDIR)/out/mushroom.obj (statistics: out/mushroom-stats.jsonl)"

test: setup
	@scripts/run_tests.sh

# The standard workload side by side with the reference C++ loop in ../shared/bench, then the
# criterion bench of one step.
bench: build
	python3 scripts/bench_compare.py --steps 1000 --rounds 3
	$(CARGO) bench -p softsculpt --bench step
