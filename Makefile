# mazesim: the single entry point for building, testing and running.
# `make demo` and `make test` are all a new checkout needs (Rust and Python >= 3.9 installed).

# The interpreter of the venv: python3.11 (what the figures were measured with) if present, else
# python3; override with `make PYTHON=/path/to/python3.x`. It must be 3.9 or newer.
PYTHON ?= $(shell command -v python3.11 2>/dev/null || command -v python3 2>/dev/null || echo python3)
PYTHON_MIN := 3.9
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
# What `make demo` needs: maturin, which builds the extension, and mazesim's own dependencies
# (pyproject's [project] dependencies), installed here so that `maturin develop` finds them.
PY_PACKAGES := maturin numpy matplotlib pillow tqdm quickjs lupa
# Python 3.9 and 3.10 read TOML with tomli (pyproject's dependency of the same marker).
PY_BEFORE_311 := "tomli; python_version < '3.11'"
# What `make test`, `lint`, `typecheck` and `fmt` need beside (pyproject's extra "dev", plus Ray):
# installed by `make dev-deps` (a stamp of its own), so `make demo` does not pay for them.
DEV_PACKAGES := pytest pytest-xdist hypothesis ruff mypy typing_extensions gymnasium ray imageio imageio-ffmpeg \
	moviepy selenium tensorboardX nbclient nbformat ipykernel
DEV_STAMP := $(VENV)/.dev-installed
PY_SOURCES := python tests examples benches
# Only `make bench-peers` needs these: the peers mazesim is measured against, and its
# options (e.g. PEER_ARGS="--envs 64,1024 --json").
PEER_PACKAGES := pymunk "jax[cpu]"
PEER_ARGS ?=
# Only `make docs` needs these (pyproject's extra "docs"): mkdocs, its Material theme, mkdocstrings.
DOCS_PACKAGES := "mkdocs>=1.6" "mkdocs-material>=9.5" "mkdocstrings[python]>=0.26"
# Only `make sb3-deps` (and so `make test`) needs these (pyproject's extra "sb3"): Stable-Baselines3
# 2.x and torch, for mazesim.integrations.sb3, its tests and the examples' PPO scripts. torch from
# PyPI is a large download the first time (pip's cache makes later installs quick).
SB3_PACKAGES := "stable-baselines3>=2.3,<3" "sb3-contrib>=2.3,<3"
# What `make marl-deps` (and so `make test` and `make typecheck`) installs (pyproject's extra
# "marl"): PettingZoo, for mazesim.marl's multi-robot environments, their tests and examples.
MARL_PACKAGES := "pettingzoo>=1.24"
# The packages the compatibility corpus's controllers import (pyproject's webots-corpus extra).
# OpenCV below 5: the projects were written for OpenCV 4 (its HoughLinesP returns None when it
# finds no line, OpenCV 5's an empty array, which a controller testing for None crashes on).
WEBOTS_CORPUS_PACKAGES := "scikit-fuzzy>=0.5" "scipy>=1.8" "networkx>=2.6" "deap>=1.3" "nnfs>=0.5" "pandas>=1.3" \
	"opencv-python>=4.5,<5" "scikit-learn>=1.0" "gym>=0.26" "tensorboardX>=2.6"
# deepbots (the Webots RL framework several corpus projects build on) pins gym 0.21, which no
# longer builds on this Python; it runs on gym 0.26, so it is installed without its pins.
WEBOTS_CORPUS_NO_DEPS := "deepbots==1.0.0"
# The binding crate's build script asks this interpreter for its configuration.
export PYO3_PYTHON := $(CURDIR)/$(BIN)/python
# matplotlib's font cache lives with the environment, so that a checkout's tests never read one
# that another checkout's matplotlib is rewriting (a half-written cache adds warnings to stderr).
export MPLCONFIGDIR := $(CURDIR)/$(VENV)/matplotlib

.DEFAULT_GOAL := help

.PHONY: help venv build test demo lint typecheck fmt bench wheel clean ros-deps ros2-deps ros2-peer ros-demo bench-peers \
	bench-tasks bench-transfer webots-compat corpus-libs \
	browser-deps replay-screenshot docs docs-deps sb3-deps marl-deps fuzz dev-deps wheel-deps oldest-glibc-deps \
	wheel-oldest newcomer-check

help: ## list the targets
	@echo "mazesim make targets:"
	@grep -E '^[a-z-]+:.*## ' $(MAKEFILE_LIST) | sed -E 's/^([a-z-]+):.*## (.*)/  \1\t\2/' | expand -t 14

# PYTHON= makes a new .venv only: one already there keeps its Python, which is said when the
# asked-for one is another version (`make PYTHON=python3.9 demo` after a first `make demo`).
PYTHON_VERSION_OF = $(1) -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null

venv: $(STAMP) ## create .venv (python3.11, else python3 >= 3.9) with maturin, numpy, matplotlib, pillow, tqdm
	@if [ "$(origin PYTHON)" = "command line" ]; then \
		asked=$$($(call PYTHON_VERSION_OF,$(PYTHON))); has=$$($(call PYTHON_VERSION_OF,$(BIN)/python)); \
		[ "$$asked" = "$$has" ] || echo "make venv: $(VENV) already exists with Python $$has, and" \
			"keeps it: PYTHON=$(PYTHON) (Python $${asked:-not found}) makes a new one only;" \
			"remove $(VENV) first (rm -rf $(VENV)) to make it with $(PYTHON)" >&2; fi

$(STAMP): Makefile
	@test -x $(BIN)/python || $(PYTHON) -c 'import sys; sys.exit(sys.version_info < (3, 9))' 2>/dev/null \
		|| { echo "make venv: mazesim needs Python >= $(PYTHON_MIN); found '$(PYTHON)':" \
			"$$($(PYTHON) --version 2>/dev/null || echo not installed). Install python3.11 (or any" \
			"python3 >= $(PYTHON_MIN)), or run 'make PYTHON=/path/to/python3.x ...'" >&2; exit 1; }
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	@$(BIN)/python -m pip --version >/dev/null 2>&1 || { echo "make venv: $(VENV) has no pip: it was" \
		"left half-made (on Debian and Ubuntu a venv gets pip from the package python3-venv, or" \
		"python3.X-venv); making it again with $(PYTHON)" >&2; $(PYTHON) -m venv --clear $(VENV); }
	$(BIN)/python -m pip install --quiet --upgrade pip
	@echo "make venv: installing $(PY_PACKAGES) into $(VENV) (about 55 MB to download the first time, 225 MB in $(VENV))"
	@start=$$(date +%s); $(BIN)/python -m pip install --progress-bar on $(PY_PACKAGES) $(PY_BEFORE_311) | grep -v '^Requirement already satisfied' || true; \
		echo "make venv: installed in $$(( $$(date +%s) - start )) s"
	@$(BIN)/python -c 'import maturin, numpy, matplotlib, PIL, tqdm' && touch $@

# pip's "Ignoring ...: markers 'extra == ...'" lines (the extras maturin develop does not install)
# are no warnings: PIP_QUIET keeps them out. Cargo's progress shows.
build: venv ## build the extension in release mode and install mazesim into .venv
	@test -f $(VENV)/.built || echo "make build: compiling the Rust core and its dependencies in release mode; the first build takes about 2 minutes on 2 quiet cores (more on a busy machine), later ones seconds"
	@start=$$(date +%s); PIP_QUIET=1 VIRTUAL_ENV=$(CURDIR)/$(VENV) $(BIN)/maturin develop --release \
		&& echo "make build: built and installed in $$(( $$(date +%s) - start )) s"
	@touch $(VENV)/.built

dev-deps: $(DEV_STAMP) ## install the developer tools into .venv (pytest, hypothesis, ruff, mypy, gymnasium, Ray, selenium, ...)

$(DEV_STAMP): $(STAMP)
	@echo "make dev-deps: installing the developer tools into $(VENV): $(DEV_PACKAGES) (about 600 MB in $(VENV), Ray and its dependencies most of it)"
	$(BIN)/python -m pip install --progress-bar on $(DEV_PACKAGES) | grep -v '^Requirement already satisfied' || true
	@$(BIN)/python -c 'import pytest, xdist, hypothesis, mypy, gymnasium, ray, selenium, moviepy' && touch $@

# pytest's --durations: every run's log ends with its slowest tests (set-up, call and tear-down
# each), so the place the suite's time goes is read from the CI machine itself. The Python tests
# run in two parts: first every test not marked `alone`, in PYTEST_WORKERS processes (pytest-xdist;
# `auto`: one per core; each test file wholly in one process, as the code blocks of a docs page
# build on each other), then the tests marked `alone` one at a time (tests/conftest.py marks the
# ROS 1 and ROS 2 tests so: they time a bridge against its nodes, and one of them failed once when
# it shared the cores with other tests). On 2 cores shared with other work, the first part took
# 22 min in two processes and the second 7 min (measured 2026-12-03, 2-core machine; the whole
# suite in one process took 26-31 min on a quiet machine). PYTEST_WORKERS=0 runs it in one.
PYTEST_WORKERS ?= auto
test: build dev-deps ros-deps ros2-deps ros2-peer browser-deps display-deps docs-deps sb3-deps marl-deps oldest-glibc-deps ## run the Rust tests, then the Python tests (ROS 1 and ROS 2 bridges, browser, SB3 and oldest-glibc tests included)
	cargo test --workspace --exclude mazesim-py
	cargo test --release --locked --quiet --manifest-path $(ROS2_PEER_MANIFEST) --target-dir $(ROS2_PEER_TARGET)
	$(BIN)/python -m pytest -n $(PYTEST_WORKERS) --dist loadfile -m "not alone" --durations=40
	$(BIN)/python -m pytest -m alone --durations=20
	$(BIN)/python -m mypy.stubtest mazesim._core

# `make fuzz`: the readers' fuzz tests with more mutated inputs, and hostile calls over every module
# of the public surface (docs/reliability.md).
FUZZ_CASES ?= 20000
FUZZ_CALLS ?= 5
FUZZ_WORLD_RUNS ?= 200
# The seed of the surface walk's hostile values: a new one each run, so that each run tries calls
# the last did not (a fixed seed tries the same calls every run); printed, to run again.
FUZZ_SEED ?= $(shell date +%s)

fuzz: build dev-deps ## fuzz the readers (FUZZ_CASES inputs each), every public entry point (FUZZ_CALLS hostile calls each, drawn from FUZZ_SEED: a new seed each run) and FUZZ_WORLD_RUNS mutated Webots worlds run whole
	PROPTEST_CASES=$(FUZZ_CASES) cargo test -p mazesim-core --release --test parser_fuzz --test wbt_fuzz
	@echo "make fuzz: the surface walk's seed is $(FUZZ_SEED) (make fuzz FUZZ_SEED=$(FUZZ_SEED) runs it again)"
	MAZESIM_SURFACE=all MAZESIM_SURFACE_CALLS=$(FUZZ_CALLS) MAZESIM_SURFACE_SEED=$(FUZZ_SEED) $(BIN)/python -m pytest tests/test_public_surface.py
	MAZESIM_WORLD_RUNS=$(FUZZ_WORLD_RUNS) $(BIN)/python -m pytest -n 2 tests/webots/test_world_run_fuzz.py

demo: build ## the shipped hierarchical navigator drives seed-maze to its goal; writes mazesim-demo/ (replay.html: watch it)
	$(BIN)/mazesim demo --controller hrl --out mazesim-demo --html mazesim-demo/replay.html
	@echo "make demo: the mazesim command is $(BIN)/mazesim (try $(BIN)/mazesim --help, or 'source $(BIN)/activate' first); a maze of your own next: docs/own-maze.md"

# Debian's ROS 1 (docs/ros.md): installed only when /usr/bin/python3 cannot import rospy.
# The venv sees /usr/lib/python3/dist-packages through a .pth file, at the END of sys.path (first
# would break rosbag).
ROS_DEBS := python3-rosmaster python3-roslaunch python3-rospy python3-rostopic python3-std-msgs \
	python3-rosgraph-msgs python3-rosbag rosout python3-sensor-msgs python3-nav-msgs \
	python3-geometry-msgs python3-tf2-msgs python3-tf2-ros python3-std-srvs
ROS_PTH = $$($(BIN)/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')/zz-debian-ros.pth

ros-deps: venv ## install Debian's ROS 1 packages if missing; let .venv import them
	@if /usr/bin/python3 -c 'import rospy, rosbag, sensor_msgs.msg, nav_msgs.msg, geometry_msgs.msg, tf2_msgs.msg, tf2_ros, std_srvs.srv' 2>/dev/null; then :; \
	elif command -v apt-get >/dev/null; then \
		sudo=; [ "$$(id -u)" -eq 0 ] || sudo=sudo; \
		$$sudo apt-get update && $$sudo apt-get install -y --no-install-recommends $(ROS_DEBS); \
	else echo "ros-deps: no apt-get; install ROS 1 yourself (the ROS tests are skipped without it)"; fi
	@if [ -d /usr/lib/python3/dist-packages ]; then \
		echo /usr/lib/python3/dist-packages > "$(ROS_PTH)"; fi

ros-demo: build ros-deps ## bridge + HRL node (perform-learning) over ROS in lockstep to seed-maze's goal; records mazesim-ros-demo/maze.bag
	$(BIN)/mazesim ros demo --controller hrl --out mazesim-ros-demo

# ROS 2 over DDS needs no ROS 2 installation (docs/ros2.md): pyproject's extra "ros2" (Cyclone DDS and
# rosbags), and the independent bag reader its tests check the bags with (mcap, mcap-ros2-support).
ROS2_PACKAGES := "cyclonedds>=0.10.5,<12" "rosbags>=0.10,<1" "mcap>=1.1" "mcap-ros2-support>=0.5"

ros2-deps: venv ## install the ROS 2 extra (cyclonedds, rosbags) and the tests' bag reader (mcap) into .venv
	$(BIN)/python -m pip install --quiet $(ROS2_PACKAGES)

# The ROS 2 tests' second driver of the bridge, on an independent ROS 2 implementation: ros2-client
# over RustDDS from crates.io (tests/ros2_peer, outside the workspace, with its own lock file).
# Its first build compiles about 180 crates: some 3 CPU-minutes; later builds are incremental.
ROS2_PEER_MANIFEST := tests/ros2_peer/Cargo.toml
ROS2_PEER_TARGET := target/ros2-peer

ros2-peer: ## build the ROS 2 tests' peer (tests/ros2_peer: ros2-client over RustDDS) into target/ros2-peer
	cargo build --release --locked --quiet --manifest-path $(ROS2_PEER_MANIFEST) --target-dir $(ROS2_PEER_TARGET)

# Debian's Chromium and its WebDriver, for the browser tests of the HTML replay (selenium drives
# them headless); installed only when missing. Without them those tests are skipped, and say why.
BROWSER_DEBS := chromium chromium-driver

browser-deps: ## install Debian's chromium and chromium-driver if missing (the HTML replay's browser tests)
	@if command -v chromium >/dev/null && command -v chromedriver >/dev/null; then :; \
	elif command -v apt-get >/dev/null; then \
		sudo=; [ "$$(id -u)" -eq 0 ] || sudo=sudo; \
		$$sudo apt-get update && $$sudo apt-get install -y --no-install-recommends $(BROWSER_DEBS) \
		|| echo "browser-deps: could not install $(BROWSER_DEBS); the browser tests of the HTML replay will be skipped"; \
	else echo "browser-deps: no apt-get; install Chromium and chromedriver yourself (the browser tests of the HTML replay are skipped without them)"; fi

display-deps: ## install Debian's xvfb and cmake if missing (Webots controllers' Tk windows on a virtual display; controllers built by their project's CMakeLists.txt)
	@if command -v Xvfb >/dev/null && command -v cmake >/dev/null; then :; \
	elif command -v apt-get >/dev/null; then \
		sudo=; [ "$$(id -u)" -eq 0 ] || sudo=sudo; \
		$$sudo apt-get update && $$sudo apt-get install -y --no-install-recommends xvfb cmake \
		|| echo "display-deps: could not install xvfb and cmake; the Tk and CMake controllers' tests will be skipped"; \
	else echo "display-deps: no apt-get; install Xvfb and cmake yourself (the Tk and CMake controllers' tests are skipped without them)"; fi

corpus-libs: ## install Debian's libgsl-dev if missing (the C libraries the corpus's controller Makefiles link: -lgsl -lgslcblas)
	@if [ -e /usr/include/gsl/gsl_matrix.h ]; then :; \
	elif command -v apt-get >/dev/null; then \
		sudo=; [ "$$(id -u)" -eq 0 ] || sudo=sudo; \
		$$sudo apt-get update && $$sudo apt-get install -y --no-install-recommends libgsl-dev \
		|| echo "corpus-libs: could not install libgsl-dev; the corpus rows that link GSL will name it as missing"; \
	else echo "corpus-libs: no apt-get; install GSL yourself (the corpus rows that link it name it as missing without it)"; fi

replay-screenshot: build browser-deps ## the shipped navigator's demo replayed in headless Chromium: docs/replay.png
	$(BIN)/mazesim demo --controller hrl --out mazesim-demo --html mazesim-demo/replay.html
	@echo "make demo: the mazesim command is $(BIN)/mazesim (try $(BIN)/mazesim --help, or 'source $(BIN)/activate' first); a maze of your own next: docs/own-maze.md"
	$(BIN)/python -m mazesim.replay.screenshot mazesim-demo/replay.html docs/replay.png

lint: dev-deps ## rustfmt, clippy (warnings are errors), ruff check and ruff format
	cargo fmt --all --check
	cargo clippy --workspace --all-targets -- -D warnings
	cargo fmt --check --manifest-path $(ROS2_PEER_MANIFEST)
	cargo clippy --release --locked --quiet --manifest-path $(ROS2_PEER_MANIFEST) --target-dir $(ROS2_PEER_TARGET) \
		--all-targets -- -D warnings
	$(BIN)/ruff check $(PY_SOURCES)
	$(BIN)/ruff format --check $(PY_SOURCES)

typecheck: build dev-deps marl-deps ## mypy on the package, stubtest of _core.pyi against the built extension
	$(BIN)/python -m mypy
	$(BIN)/python -m mypy.stubtest mazesim._core

fmt: dev-deps ## format Rust and Python sources in place
	cargo fmt --all
	$(BIN)/ruff check --fix --quiet $(PY_SOURCES)
	$(BIN)/ruff format $(PY_SOURCES)

bench: ## run the criterion benches
	cargo bench

bench-tasks: build dev-deps ## one env of every registered task through gymnasium.make against CartPole-v1; fails if any is slower
	$(BIN)/python benches/bench_tasks.py

bench-transfer: build ## time the full default transfer study of the shipped and randomised navigators (budget 10 min each)
	$(BIN)/python benches/bench_transfer.py

# The Webots compatibility corpus (tests/webots_corpus/, docs/webots-compat.md) runs from local
# git mirrors of its repositories, one per repository in MIRRORS (named owner+name, bare or a
# clone; tests/webots_corpus/mirrors.py lists the names looked for). A missing one is skipped.
MIRRORS ?= mirrors

webots-compat: build display-deps corpus-libs ## run the Webots compatibility corpus from local git mirrors (MIRRORS=DIR); writes docs/webots-compat.md
	@$(BIN)/python -c 'import skfuzzy, scipy, networkx, deap, nnfs, pandas, cv2, sklearn, gym, deepbots' 2>/dev/null || echo "make webots-compat: installing the Python packages the corpus's controllers import (mazesim[webots-corpus]: scikit-fuzzy, SciPy, NetworkX, DEAP, nnfs, pandas, OpenCV with its windows, scikit-learn, gym, and deepbots; about 140 MB to download, 600 MB in $(VENV))"
	$(BIN)/python -m pip install --quiet $(WEBOTS_CORPUS_PACKAGES)
	$(BIN)/python -m pip install --quiet --no-deps $(WEBOTS_CORPUS_NO_DEPS)
	$(BIN)/python tests/webots_corpus/run_corpus.py --mirrors $(MIRRORS)

bench-peers: build ## mazesim against hand-written numpy, pymunk and JAX peers (installs pymunk and jax)
	@$(BIN)/python -c 'import jax, pymunk' 2>/dev/null || echo "make bench-peers: installing pymunk and jax[cpu] (about 140 MB to download the first time: jaxlib 85 MB, scipy 35 MB)"
	$(BIN)/python -m pip install --quiet $(PEER_PACKAGES)
	$(BIN)/python benches/bench_vs_peers.py $(PEER_ARGS)

sb3-deps: venv ## install Stable-Baselines3 and torch into .venv (mazesim[sb3]: the SB3 adapter, the PPO examples)
	@$(BIN)/python -c 'import stable_baselines3' 2>/dev/null || echo "make sb3-deps: installing Stable-Baselines3 and torch: torch from PyPI brings its CUDA libraries, about 3 GB to download and 5.2 GB in $(VENV) the first time (pip's cache makes later installs quick)"
	$(BIN)/python -m pip install --progress-bar on $(SB3_PACKAGES) | grep -v '^Requirement already satisfied' || true
	@$(BIN)/python -c 'import stable_baselines3, sb3_contrib'

marl-deps: venv ## install PettingZoo into .venv (mazesim[marl]: the multi-robot RL environments)
	@$(BIN)/python -c 'import pettingzoo' 2>/dev/null || echo "make marl-deps: installing PettingZoo into $(VENV) (about 5 MB)"
	$(BIN)/python -m pip install --quiet $(MARL_PACKAGES)
	@$(BIN)/python -c 'import pettingzoo'

docs-deps: venv ## install the docs tools (mkdocs, Material, mkdocstrings) into .venv
	@$(BIN)/python -c 'import mkdocs, material, mkdocstrings' 2>/dev/null || echo "make docs-deps: installing mkdocs, mkdocs-material and mkdocstrings (about 80 MB in $(VENV))"
	$(BIN)/python -m pip install --quiet $(DOCS_PACKAGES)

# The API page is read from the sources (griffe), never imported: the SB3 adapter's page needs
# neither Stable-Baselines3 nor torch, nor the multi-robot pages PettingZoo.
docs: docs-deps ## build the documentation site into site/ (mkdocs --strict; no torch needed)
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict --quiet

# manylinux2014 (glibc 2.17 and newer: Ubuntu 20.04, Debian 11, RHEL 8, ...): maturin links the
# extension with zig's linker against glibc 2.17's symbols (`--zig`; ziglang from PyPI), then
# auditwheel checks the wheel against the tag's policy. `make wheel-deps` installs both.
WHEEL_COMPATIBILITY ?= manylinux2014
WHEEL_PACKAGES := ziglang auditwheel
DIST ?= dist

wheel-deps: venv ## install ziglang (zig's linker for maturin --zig, about 410 MB) and auditwheel into .venv
	@$(BIN)/python -c 'import ziglang, auditwheel' 2>/dev/null || echo "make wheel-deps: installing ziglang (zig's toolchain, about 410 MB installed) and auditwheel"
	$(BIN)/python -m pip install --quiet $(WHEEL_PACKAGES)

# The zig build is a build of its own in target/ (the first takes as long as `make build`'s first).
wheel: wheel-deps ## build the release wheel (abi3, manylinux2014 via zig, checked by auditwheel) and the sdist into dist/
	@rm -f $(DIST)/mazesim-*.whl
	PATH="$(CURDIR)/$(BIN):$$PATH" $(BIN)/maturin build --release --zig --compatibility $(WHEEL_COMPATIBILITY) --out $(DIST)
	$(BIN)/auditwheel show $(DIST)/mazesim-*.whl
	$(BIN)/maturin sdist --out $(DIST)
	@wheel=$$(ls $(DIST)/mazesim-*.whl); echo "make wheel: wrote $$wheel; install it into any" \
		"virtual environment of Python >= $(PYTHON_MIN): python -m pip install '$$wheel'" \
		"(with the RL environments: python -m pip install '$$wheel[gym]')"

# The wheel on the oldest glibc reachable here (tests/oldest_glibc.py; docs/install.md): Debian
# bullseye (glibc 2.31, Python 3.9), the oldest release deb.debian.org serves, in a chroot that
# debootstrap makes once into OLDEST_CACHE, outside the checkout, beside the wheel's dependencies
# fetched from PyPI for its Python. Needs root; the first time about 45 MB from deb.debian.org
# and 45 MB from PyPI, 450 MB on disk, 11 minutes on a loaded 2-core machine. Installing and
# running there needs no network.
OLDEST_CACHE ?= $(HOME)/.cache/mazesim/oldest-glibc

oldest-glibc-deps: venv ## make the Debian bullseye chroot (glibc 2.31) the wheel is tried on, once, in OLDEST_CACHE
	@if [ "$$(id -u)" -ne 0 ]; then \
		echo "oldest-glibc-deps: needs root (debootstrap, chroot); the wheel's test on the oldest glibc is skipped"; \
	elif [ -f "$(OLDEST_CACHE)/bullseye/.mazesim-ready" ] && [ -f "$(OLDEST_CACHE)/bullseye-wheelhouse/.mazesim-ready" ]; then :; \
	else { command -v debootstrap >/dev/null || { apt-get update && apt-get install -y --no-install-recommends debootstrap; }; } \
		&& MAZESIM_OLDEST_CACHE="$(OLDEST_CACHE)" $(BIN)/python tests/oldest_glibc.py prepare \
		|| echo "oldest-glibc-deps: the chroot could not be made (above); the wheel's test on the oldest glibc is skipped"; fi

wheel-oldest: wheel oldest-glibc-deps ## build the wheel, install it in the bullseye chroot, run the quick start and mazesim eval there
	MAZESIM_OLDEST_CACHE="$(OLDEST_CACHE)" $(BIN)/python tests/oldest_glibc.py check $(DIST)/mazesim-*.whl

# A newcomer's path (tests/newcomer_path.py): a fresh clone of HEAD in a temporary folder, `make
# demo` there (its own .venv, the Rust core built from nothing), the own-maze recipe of
# docs/own-maze.md as printed, and a maze without checkpoints that `mazesim train` must refuse.
newcomer-check: ## replay a newcomer's path on a fresh clone: make demo, the own-maze recipe, a maze refused (30 min or more)
	$(PYTHON) tests/newcomer_path.py

clean: ## remove build products, .venv, dist and demo output
	cargo clean
	rm -rf $(VENV) dist site mazesim-demo mazesim-ros-demo .pytest_cache .ruff_cache .mypy_cache .hypothesis
	find python tests -name __pycache__ -type d -prune -exec rm -rf {} +
	rm -f python/mazesim/_core*.so python/mazesim/_core*.pyd
