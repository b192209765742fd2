# mazesim: the single entry point for building, testing and running.
# `make demo` and `make test` are all a new checkout needs (Rust and Python 3.11 installed).

PYTHON ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
PY_PACKAGES := maturin numpy matplotlib pytest hypothesis ruff mypy typing_extensions
PY_SOURCES := python tests
# The binding crate's build script asks this interpreter for its configuration.
export PYO3_PYTHON := $(CURDIR)/$(BIN)/python

.DEFAULT_GOAL := help

.PHONY: help venv build test demo lint typecheck fmt bench wheel clean

help: ## list the targets
	@echo "mazesim make targets:"
	@grep -E '^[a-z-]+:.*## ' $(MAKEFILE_LIST) | sed -E 's/^([a-z-]+):.*## (.*)/  \1\t\2/' | expand -t 14

venv: $(STAMP) ## create .venv (Python 3.11) with maturin, numpy, matplotlib and the dev tools

$(STAMP):
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet $(PY_PACKAGES)
	@touch $@

build: venv ## build the extension in release mode and install mazesim into .venv
	VIRTUAL_ENV=$(CURDIR)/$(VENV) $(BIN)/maturin develop --release --quiet

test: build ## run the Rust tests, then the Python tests
	cargo test --workspace --exclude mazesim-py
	$(BIN)/python -m pytest
	$(BIN)/python -m mypy.stubtest mazesim._core

demo: build ## run the avoid-collision demo in seed-maze; writes mazesim-demo/
	$(BIN)/mazesim demo --out mazesim-demo

lint: venv ## rustfmt, clippy (warnings are errors), ruff check and ruff format
	cargo fmt --all --check
	cargo clippy --workspace --all-targets -- -D warnings
	$(BIN)/ruff check $(PY_SOURCES)
	$(BIN)/ruff format --check $(PY_SOURCES)

typecheck: build ## mypy on the package, stubtest of _core.pyi against the built extension
	$(BIN)/python -m mypy
	$(BIN)/python -m mypy.stubtest mazesim._core

fmt: venv ## format Rust and Python sources in place
	cargo fmt --all
	$(BIN)/ruff check --fix --quiet $(PY_SOURCES)
	$(BIN)/ruff format $(PY_SOURCES)

bench: ## run the criterion benches
	cargo bench

wheel: venv ## build a release wheel into dist/
	$(BIN)/maturin build --release --out dist

clean: ## remove build products, .venv, dist and demo output
	cargo clean
	rm -rf $(VENV) dist mazesim-demo .pytest_cache .ruff_cache .mypy_cache .hypothesis
	find python tests -name __pycache__ -type d -prune -exec rm -rf {} +
	rm -f python/mazesim/_core*.so python/mazesim/_core*.pyd
