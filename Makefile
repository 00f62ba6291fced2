# Two commands for a newcomer:  `make demo`  and  `make test`.
# Each sets up its own virtualenv (.venv), installs the package into it, and (as root) the one
# system library off-screen rendering needs (Mesa's OSMesa: VTK renders without any X server).
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
DOCS_STAMP := $(VENV)/.installed-docs
export PYVISTA_OFF_SCREEN := true
export VTK_DEFAULT_OPENGL_WINDOW := vtkOSOpenGLRenderWindow
export MPLBACKEND := Agg

.PHONY: demo test test-slow docs validate bench fuzz system-deps clean

system-deps:
	@if ldconfig -p 2>/dev/null | grep -q libOSMesa; then :; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
		echo "installing libosmesa6 (off-screen rendering)"; \
		apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends libosmesa6 >/dev/null; \
	else \
		echo "note: off-screen rendering needs Mesa's OSMesa: sudo apt-get install libosmesa6 (render steps will say so)"; \
	fi

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $(STAMP)

demo: system-deps $(STAMP)
	$(BIN)/drivefem demo

test: system-deps $(STAMP)
	$(BIN)/python -m pytest -q -m "not slow" -n auto

test-slow: system-deps $(STAMP)
	$(BIN)/python -m pytest -q -m slow -n auto

# The documentation site (mkdocs-material + mkdocstrings, the `docs` extra) into ./site/;
# --strict: a broken link, a missing page or an API name that does not import is an error.
$(DOCS_STAMP): $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[docs]'
	touch $(DOCS_STAMP)

docs: $(DOCS_STAMP)
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict

validate: system-deps $(STAMP)
	$(BIN)/drivefem validate --report validation-report

bench: system-deps $(STAMP)
	$(BIN)/python benchmarks/report.py

fuzz: $(STAMP)
	$(BIN)/python -m tests.fuzzing.run --n 3000 --out fuzz-report

clean:
	rm -rf $(VENV) site drivefem-demo validation-report fuzz-report .pytest_cache build *.egg-info
