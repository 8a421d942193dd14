# surfwave: two commands set everything up on a fresh machine.
#   make reproduce   build .venv from environment.lock (if missing or stale), run snakemake -j2
#   make test        build the same environment, run the static checks (make check) and the test suite
#   make test-slurm  opt-in: the SLURM profile on a real single-node cluster (root; see below)
#   make cluster-env .venv-cluster from environment-cluster.lock: the above plus the SLURM
#                    executor plugin (kept out of .venv: it probes the cluster on every
#                    snakemake call, ~10 s where no SLURM controller answers)
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.surfwave-stamp
CLUSTER_VENV := .venv-cluster
CLUSTER_STAMP := $(CLUSTER_VENV)/.surfwave-stamp
JOBS ?= 2

.PHONY: env cluster-env reproduce check test test-slurm bench lint lock clean-results help

help:
	@echo "make reproduce | make test | make check | make test-slurm | make cluster-env | make bench | make lint | make lock | make clean-results"

# The environment is rebuilt only when the lock or the project metadata change.
$(STAMP): environment.lock pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps --require-hashes -r environment.lock
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps --no-build-isolation -e .
	touch $(STAMP)

env: $(STAMP)

# The cluster environment: a venv of its own, so that local runs never load the plugin.
$(CLUSTER_STAMP): environment-cluster.lock pyproject.toml
	test -x $(CLUSTER_VENV)/bin/python || $(PYTHON) -m venv $(CLUSTER_VENV)
	$(CLUSTER_VENV)/bin/python -m pip install --quiet --disable-pip-version-check --no-deps --require-hashes -r environment-cluster.lock
	$(CLUSTER_VENV)/bin/python -m pip install --quiet --disable-pip-version-check --no-deps --no-build-isolation -e .
	touch $(CLUSTER_STAMP)

cluster-env: $(CLUSTER_STAMP)

reproduce: $(STAMP)
	$(BIN)/snakemake -j$(JOBS)

# Static checks the house style assumes (pyproject.toml: [tool.ruff], [tool.mypy]): ruff with the
# numpy docstring rules on the code and tests, mypy on the whole library.
check: $(STAMP)
	$(BIN)/ruff check src tests benchmarks workflow/scripts
	$(BIN)/mypy

# One BLAS thread per test worker: two workers on two cores, no oversubscription (dense
# eigensolves in the slab tests run ~2.5x slower with competing BLAS threads).
test: $(STAMP) check
	OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 $(BIN)/python -m pytest -n 2 --dist loadgroup -q

# The SLURM profile on a real single-node SLURM cluster on localhost (tests/workflow/test_slurm.py):
# installs Debian's slurmctld, slurmd, slurm-client and munge if missing, runs a tiny scene
# locally and through profiles/slurm, compares the cubes. Needs root and apt, else it skips
# and says why. Bounded: 600 s inside the test, `timeout` as the backstop. CI runs it.
# It runs in .venv-cluster (make cluster-env), the environment with the SLURM executor plugin.
SLURM_TIMEOUT ?= 900
test-slurm: $(CLUSTER_STAMP)
	SURFWAVE_SLURM_TEST=1 timeout -k 30 $(SLURM_TIMEOUT) $(CLUSTER_VENV)/bin/python -m pytest -p no:cacheprovider -q -rs -s tests/workflow/test_slurm.py

bench: $(STAMP)
	$(BIN)/snakemake -j$(JOBS) benchmarks

lint: $(STAMP)
	$(BIN)/snakemake --lint
	$(BIN)/snakefmt --check Snakefile workflow/rules

# Regenerate both locks (needs network access to PyPI); existing pins are kept (pip-compile
# reads the old lock), so only new or removed requirements change them. pip-tools goes into
# a throwaway venv, not into .venv (it is not part of the locked environment).
LOCK_VENV ?= /tmp/surfwave-lockenv
lock:
	test -x $(LOCK_VENV)/bin/python || $(PYTHON) -m venv $(LOCK_VENV)
	$(LOCK_VENV)/bin/python -m pip install --quiet pip-tools
	$(LOCK_VENV)/bin/pip-compile --quiet --generate-hashes --allow-unsafe --strip-extras -o environment.lock requirements.in
	$(LOCK_VENV)/bin/pip-compile --quiet --generate-hashes --allow-unsafe --strip-extras -o environment-cluster.lock requirements-cluster.in

clean-results:
	rm -rf results
