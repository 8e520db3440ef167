# moorline developer targets. Every target creates .venv on first use.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

COMPARE := $(VENV)/.compare
# every optional extra (pyproject.toml): `make verify` runs the tests that need them, so none
# of them may be skipped there
EXTRAS := $(VENV)/.extras

.PHONY: demo test verify bench lint clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test]"
	$(BIN)/moorline compile
	touch $(STAMP)

$(COMPARE): $(STAMP)
	$(BIN)/python -m pip install --quiet -e ".[test,compare]"
	touch $(COMPARE)

$(EXTRAS): $(STAMP)
	$(BIN)/python -m pip install --quiet -e ".[test,compare,bem,dask]"
	$(BIN)/python -c "import capytaine, distributed, moordyn, moorpy"
	touch $(EXTRAS)

demo: $(STAMP)
	$(BIN)/moorline run cases/oc3_line.yaml --out out
	$(BIN)/moorline run cases/oc3_dynamics.yaml --out out
	@echo "results, plots and reports written: out/oc3-line/report.html, out/oc3-dynamics/report.html"

# pytest-xdist: TEST_WORKERS processes share the tests and the kernel cache (`moorline compile`
# filled it at install, in parallel, so the workers do not compile the same step at once)
TEST_WORKERS ?= 2

test: $(STAMP)
	$(BIN)/python -m pytest -q -n $(TEST_WORKERS)

# -rs lists every skipped test with its reason: with all extras installed only the case
# files the compiled backend does not take (test_fast_newmark) may remain.
verify: $(EXTRAS)
	$(BIN)/python -m pytest -q -rs -n $(TEST_WORKERS) -m "slow or not slow"
	$(BIN)/moorline verify

# bench_all.py: P1-P6 and the streaming cost side by side against MoorDyn, CableDyn and MoorPy
# (it runs bench_statics.py and bench_stream.py's measurements); it caches the P1 settings in
# benchmarks/.cache/ (pass BENCH_ARGS=--search to search again); BENCH_ARGS=--quick gives a
# smoke run. bench_dynamics.py (MoorDyn's stable steps for the moordyn-dynamics verification
# case) is run on its own.
bench: $(COMPARE)
	$(BIN)/python benchmarks/bench_all.py $(BENCH_ARGS)
	$(BIN)/python benchmarks/bench_statics_robustness.py
	$(BIN)/python benchmarks/bench_frequency.py
	$(BIN)/python benchmarks/bench_kernels.py $(filter --quick,$(BENCH_ARGS))
	$(BIN)/python benchmarks/bench_coupling.py

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks

clean:
	rm -rf $(VENV) out build *.egg-info src/*.egg-info
