# Two commands do all the set-up on a fresh machine (Python >= 3.11, pip, make):
#   make run    install into .venv and run the main job on defaults (andoyer paper)
#   make test   install into .venv (with test tools) and run lint, types and tests (the
#               tests on every core: pytest-xdist, one worker per core, a file per worker)
#   make docs   build the documentation site into docs/_build/html
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin

.PHONY: run test docs install clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip

# The main job needs andoyer and its dependencies only; the test tools come with `make test`.
$(VENV)/.installed: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q -e .
	touch $@

$(VENV)/.test: pyproject.toml | $(VENV)/.installed
	$(BIN)/python -m pip install -q -e ".[test]"
	touch $@

install: $(VENV)/.installed

run: install
	$(BIN)/andoyer paper

test: $(VENV)/.test
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/mypy
	$(BIN)/lint-imports
	$(BIN)/python -m pytest -n auto --dist loadfile -m "not slow" --doctest-modules src tests

# The documentation site (notebooks executed; any warning or failed cell fails it).
$(VENV)/.docs: pyproject.toml | $(VENV)/.installed
	$(BIN)/python -m pip install -q -e ".[docs]"
	touch $@

# Offline by default (ANDOYER_DOCS_ONLINE=1 adds the links to Python, NumPy, ...). The
# pages are read once (the doctest builder reuses the html builder's doctrees) and
# incrementally: a build with nothing changed reads nothing and takes seconds (the
# executed notebooks are cached in docs/_build/.jupyter_cache, a change of andoyer's
# sources runs them again). -q: only warnings and errors in the log.
docs: $(VENV)/.docs
	$(BIN)/python -m sphinx -q -W --keep-going -d docs/_build/doctrees -b html docs docs/_build/html
	$(BIN)/python -m sphinx -q -W --keep-going -d docs/_build/doctrees -b doctest docs docs/_build/doctest

clean:
	rm -rf $(VENV) build src/*.egg-info docs/_build docs/api/generated .jupyter_cache
