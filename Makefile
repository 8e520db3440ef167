# moorline developer targets. Every target creates .venv on first use.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

COMPARE := $(VENV)/.compare

.PHONY: demo test verify bench lint clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test]"
	touch $(STAMP)

$(COMPARE): $(STAMP)
	$(BIN)/python -m pip install --quiet -e ".[test,compare]"
	touch $(COMPARE)

demo: $(STAMP)
	$(BIN)/moorline run cases/oc3_line.yaml --out out
	$(BIN)/moorline run cases/oc3_dynamics.yaml --out out
	@echo "results and plots written under out/oc3-line/ and out/oc3-dynamics/"

test: $(STAMP)
	$(BIN)/python -m pytest -q

verify: $(COMPARE)
	$(BIN)/python -m pytest -q -m "slow or not slow"
	$(BIN)/moorline verify

# bench_dynamics.py caches MoorDyn's largest stable steps in benchmarks/.cache/ (delete it or
# pass --refresh to search again); BENCH_ARGS=--quick gives a shorter run.
bench: $(COMPARE)
	$(BIN)/python benchmarks/bench_statics.py
	$(BIN)/python benchmarks/bench_statics_robustness.py
	$(BIN)/python benchmarks/bench_frequency.py
	$(BIN)/python benchmarks/bench_dynamics.py $(BENCH_ARGS)

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks

clean:
	rm -rf $(VENV) out build *.egg-info src/*.egg-info
