# surfwave: two commands set everything up on a fresh machine.
#   make reproduce   build .venv from environment.lock (if missing or stale), run snakemake -j2
#   make test        build the same environment and run the test suite
#   make test-slurm  opt-in: the SLURM profile on a real single-node cluster (root; see below)
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.surfwave-stamp
JOBS ?= 2

.PHONY: env reproduce test test-slurm bench lint lock clean-results help

help:
	@echo "make reproduce | make test | make test-slurm | make bench | make lint | make lock | make clean-results"

# The environment is rebuilt only when the lock or the project metadata change.
$(STAMP): environment.lock pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps --require-hashes -r environment.lock
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --no-deps --no-build-isolation -e .
	touch $(STAMP)

env: $(STAMP)

reproduce: $(STAMP)
	$(BIN)/snakemake -j$(JOBS)

# One BLAS thread per test worker: two workers on two cores, no oversubscription (dense
# eigensolves in the slab tests run ~2.5x slower with competing BLAS threads).
test: $(STAMP)
	OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 $(BIN)/python -m pytest -n 2 --dist loadgroup -q

# The SLURM profile on a real single-node SLURM cluster on localhost (tests/workflow/test_slurm.py):
# installs Debian's slurmctld, slurmd, slurm-client and munge if missing, runs a tiny scene
# locally and through profiles/slurm, compares the cubes. Needs root and apt, else it skips
# and says why. Bounded: 600 s inside the test, `timeout` as the backstop. CI runs it.
SLURM_TIMEOUT ?= 900
test-slurm: $(STAMP)
	SURFWAVE_SLURM_TEST=1 timeout -k 30 $(SLURM_TIMEOUT) $(BIN)/python -m pytest -p no:cacheprovider -q -rs -s tests/workflow/test_slurm.py

bench: $(STAMP)
	$(BIN)/snakemake -j$(JOBS) benchmarks

lint: $(STAMP)
	$(BIN)/snakemake --lint
	$(BIN)/snakefmt --check Snakefile workflow/rules

# Regenerate the lock from requirements.in (needs network access to PyPI).
lock:
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet pip-tools
	$(BIN)/pip-compile --quiet --generate-hashes --allow-unsafe --strip-extras -o environment.lock requirements.in

clean-results:
	rm -rf results
