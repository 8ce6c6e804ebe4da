# Two commands do all the set-up on a fresh machine (Python >= 3.11, pip, make):
#   make run    install into .venv and run the main job on defaults (andoyer paper)
#   make test   install into .venv (with test tools) and run lint, types and tests
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin

.PHONY: run test install clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip

$(VENV)/.installed: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q -e ".[test]"
	touch $@

install: $(VENV)/.installed

run: install
	$(BIN)/andoyer paper

test: install
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/mypy
	$(BIN)/lint-imports
	$(BIN)/python -m pytest -m "not slow" --doctest-modules src tests

clean:
	rm -rf $(VENV) build src/*.egg-info
