"""``python -m probanchor.evaluation SUMMARY.json...``: the results table of saved runs
(see table.py)."""

import sys

from probanchor.evaluation.table import main

sys.exit(main())
