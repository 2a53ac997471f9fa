# The two commands a new user needs:
#   make demo   set everything up (idempotent) and run the main job
#   make test   set everything up (idempotent) and run every test (pytest + plunit)
.PHONY: setup demo test lint bench learned-theory

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

# The learned theories of occlusion that ship (prolog/too_learned.pl from the simulator's ground
# truth, prolog/too_learned_hindsight.pl from hindsight labels): 80 generated occlusion games
# collected through perception and anchoring, then ddc learn. Deterministic for the seed.
LEARN_GAMES ?= 80
LEARN_SEED ?= 0
learned-theory: setup
	$(VENV)/bin/anchoring collect --games $(LEARN_GAMES) --seed $(LEARN_SEED) --jobs 2 \
		--out out/learn/data_truth.pl
	$(VENV)/bin/anchoring learn-theory out/learn/data_truth.pl --seed $(LEARN_SEED) \
		--out prolog/too_learned.pl --plots docs/images
	$(VENV)/bin/anchoring collect --games $(LEARN_GAMES) --seed $(LEARN_SEED) --jobs 2 \
		--labels hindsight --out out/learn/data_hindsight.pl
	$(VENV)/bin/anchoring learn-theory out/learn/data_hindsight.pl --seed $(LEARN_SEED) \
		--out prolog/too_learned_hindsight.pl --plots docs/images
