# The two commands a new user needs:
#   make demo   set everything up (idempotent) and run the main job
#   make test   set everything up (idempotent) and run every test (pytest + plunit)
.PHONY: setup demo test lint bench

VENV := .venv
STAMP := $(VENV)/.anchoring-installed

setup:
	@bash scripts/setup.sh

demo: setup
	$(VENV)/bin/anchoring demo

test: setup
	$(VENV)/bin/python -m pytest -q

lint: setup
	$(VENV)/bin/ruff check python tests bench
