# The two commands of the README: `make report` and `make test`. Both install what is missing.
SHELL := /bin/bash
CARGO ?= cargo
VENV := .venv
PYTHON := $(VENV)/bin/python

.PHONY: deps cxx python cgal gmsh fonts venv build report test lint bench fuzz clean

deps: cxx python cgal gmsh fonts venv

# A C++ compiler for the CGAL shim (cxx-build); a Rust toolchain brings only a C linker.
cxx:
	@dpkg -s g++ >/dev/null 2>&1 || { \
	  echo "installing g++"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq g++; }

# python3 with venv and pip, for the virtualenv below (a fresh Debian has neither).
python:
	@dpkg -s python3-venv >/dev/null 2>&1 || { \
	  echo "installing python3-venv"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv; }

# CGAL 5.5 (header-only) with GMP, MPFR and Boost, from Debian, when dpkg says it is missing.
cgal:
	@dpkg -s libcgal-dev >/dev/null 2>&1 || { \
	  echo "installing libcgal-dev"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libcgal-dev; }

# Gmsh (4.8 on Debian), which tests/verify_foreign.rs uses to make .msh meshes for `verify`.
gmsh:
	@dpkg -s gmsh >/dev/null 2>&1 || { \
	  echo "installing gmsh"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gmsh; }

# A font for the text in PNG plots.
fonts:
	@dpkg -s fonts-dejavu-core >/dev/null 2>&1 || { \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq fonts-dejavu-core; }

# meshio and pandas, to check that Python users can read our output.
venv: $(VENV)/.done
$(VENV)/.done: requirements-test.txt | python
	python3 -m venv $(VENV)
	$(PYTHON) -m pip install -q -r requirements-test.txt
	touch $@

build: deps
	$(CARGO) build --release

report: build
	./target/release/hexmesh datasets --out datasets
	./target/release/hexmesh report --out reports

lint: deps
	$(CARGO) fmt --all -- --check
	$(CARGO) clippy --workspace --all-targets -- -D warnings

# proptest draws from a fixed seed so that CI is reproducible; explore others with
# `PROPTEST_RNG_SEED=N make test`, and run long campaigns with `hexmesh fuzz`.
PROPTEST_RNG_SEED ?= 20261123
test: deps lint
	PROPTEST_RNG_SEED=$(PROPTEST_RNG_SEED) HEXMESH_PYTHON=$(abspath $(PYTHON)) $(CARGO) test --workspace --all-targets
	$(CARGO) test --workspace --doc

bench: deps
	$(CARGO) bench

clean:
	$(CARGO) clean
	rm -rf $(VENV)
