"""Held-out quality of the learned program on generated universities, against baselines.

    .venv/bin/python bench/learn_university.py [--effects 101,102,103] [--students 400] [--json]

Each data set is a generated university (``probanchor.ddclearn.university``: students, courses
and professors; a student's grade in a course, her satisfaction with it and the hours she spends
on it depend on attributes of the student, the course, its professor and aggregates of related
students), its effect sizes drawn from one ``--effects`` seed: the learner and the baselines are
fitted on one world (seed 1) and scored on another world of the same effects (seed 2), as the
original's University experiments hold out independent interpretations. The table is
``bench/learn_financial.py``'s (the learned program, logistic or linear regression, gradient
boosting and the constant model, fitted in the same run on the same aggregate features), one row
per target and data set.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))
sys.path.insert(0, str(HERE))

from learn_financial import compare, markdown, summary  # noqa: E402
from probanchor.ddclearn.university import university_data  # noqa: E402

#: Effect seeds of the generated data sets (not those the learner was developed on).
EFFECTS: tuple[int, ...] = (101, 102, 103)


def run(effects: int, students: int, folder: Path) -> list[dict[str, Any]]:
    """Learn on one world of a generated university, score on another: one row per target."""
    train, test = folder / f"train_{effects}.pl", folder / f"test_{effects}.pl"
    train.write_text(university_data(seed=1, effects_seed=effects, students=students))
    test.write_text(university_data(seed=2, effects_seed=effects, students=students))
    rows = compare([train], [test], folder)
    for r in rows:
        r["target"] = f"{r['target']} ({effects})"
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--effects", default=",".join(map(str, EFFECTS)),
                        help="the data sets' effect seeds, comma-separated")
    parser.add_argument("--students", type=int, default=400, help="students per world")
    parser.add_argument("--json", action="store_true", help="end with one JSON line of figures")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory(prefix="learn_university_") as tmp:
        for e in (int(x) for x in args.effects.split(",")):
            rows += run(e, args.students, Path(tmp))
    seconds = time.perf_counter() - start
    print(f"Generated universities ({args.students} students; effects {args.effects}): learned "
          "on world 1, held-out mean log-likelihood per grounding on world 2.\n")
    print(markdown(rows))
    counts = summary(rows)
    print(f"The learned program is at or above the best baseline on {counts['above']} of "
          f"{counts['targets']} targets, and above or behind by less than the test's noise "
          f"(two standard errors of the paired difference, at least one nat in all) on "
          f"{counts['level']}; {seconds:.0f} s in all (learning "
          f"{sum(r['seconds'] for r in rows):.0f} s).")
    if args.json:
        print(json.dumps({"seconds": seconds, "summary": counts, "targets": rows},
                         default=float))
    return 0


if __name__ == "__main__":
    sys.exit(main())
