# Two commands for a newcomer:  `make demo`  and  `make test`.
# Each sets up its own virtualenv (.venv) and installs the package into it.
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: demo test test-slow validate bench clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/drivefem demo

test: $(STAMP)
	MPLBACKEND=Agg $(BIN)/python -m pytest -q -m "not slow"

test-slow: $(STAMP)
	MPLBACKEND=Agg $(BIN)/python -m pytest -q -m slow

validate: $(STAMP)
	$(BIN)/drivefem validate --report validation-report

bench: $(STAMP)
	$(BIN)/python benchmarks/modal_scaling.py

clean:
	rm -rf $(VENV) drivefem-demo validation-report .pytest_cache build *.egg-info
