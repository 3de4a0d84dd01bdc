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
# (check exit 0 or 1) and fails on an ERROR (exit 2).  Then one counterweight study on the
# shipped inline-4 at the test mesh (six candidates: docs/study.md), its table, Pareto plot
# and recommended candidate in reports/study/ (exit 1: no candidate meets every limit).
demo: $(STAMP)
	$(VENV)/bin/fe-crank check loadcases/ -o reports/ || [ $$? -eq 1 ]
	$(VENV)/bin/fe-crank study loadcases/inline4_rated.toml studies/inline4_demo.toml -o reports/study \
		--mesh-size test || [ $$? -eq 1 ]

test: $(STAMP)
	$(VENV)/bin/lint-imports
	$(VENV)/bin/ruff check fe_crank tests benchmarks tools
	$(VENV)/bin/ruff format --check fe_crank tests benchmarks tools
	$(VENV)/bin/mypy
	OPENBLAS_NUM_THREADS=1 $(PY) -m pytest -q -n 2 --dist loadfile

# The timings of docs/performance.md (a few minutes): mesh, FE stage, cycle and fatigue at the
# test and coarse presets, figures and machine in reports/perf.json (benchmarks/README.md; the
# CalculiX comparison, benchmarks/verification/, installs CalculiX and runs apart).
bench: $(STAMP)
	OPENBLAS_NUM_THREADS=1 $(PY) benchmarks/perf/run.py --loadcase loadcases/v4_90_pneumatic_operating.toml \
		--preset test coarse --json reports/perf.json

clean:
	rm -rf $(VENV) reports .cache
