# `make demo` and `make test` each do all set-up on a fresh machine.
PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed

.PHONY: demo test setup clean bench

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[fast,test]'
	touch $(STAMP)

setup: $(STAMP)

# The shipped single-cylinder crank (assumed shaft sizes) FAILs its fatigue and overspeed
# criteria under the determinate support: the demo succeeds when every case was computed
# (check exit 0 or 1) and fails on an ERROR (exit 2).
demo: $(STAMP)
	$(VENV)/bin/fe-crank check loadcases/ -o reports/ || [ $$? -eq 1 ]

test: $(STAMP)
	$(VENV)/bin/lint-imports
	$(VENV)/bin/ruff check fe_crank tests benchmarks
	$(VENV)/bin/ruff format --check fe_crank tests benchmarks
	OPENBLAS_NUM_THREADS=1 $(PY) -m pytest -q

# The benchmarks of docs/performance.md (a few minutes; the 1M-dof rows and the CalculiX
# comparison, benchmarks/calculix_compare.py: see there).
bench: $(STAMP)
	OPENBLAS_NUM_THREADS=1 $(PY) benchmarks/mesh_bench.py --levels test coarse
	OPENBLAS_NUM_THREADS=1 $(PY) benchmarks/fe_solve.py --geometry geometry/v4_90_pneumatic_seed003.toml --preset coarse
	OPENBLAS_NUM_THREADS=1 $(PY) benchmarks/cycle_bench.py --size 4 --angles 3
	OPENBLAS_NUM_THREADS=1 $(PY) benchmarks/pin_loads.py --preset test
	OPENBLAS_NUM_THREADS=1 $(PY) benchmarks/fatigue_bench.py --nodes 4096
	OPENBLAS_NUM_THREADS=1 $(PY) benchmarks/scaling.py --levels 0 1 --full-recovery

clean:
	rm -rf $(VENV) reports .cache
