"""Crash safety of the world-model store, measured: runs killed with SIGKILL at random moments,
each resumed, each compared with an uninterrupted run of the same scenario and options.

Prints, per kill, the frames the store held after it and whether the resumed run ended with
the uninterrupted run's records (timings aside), symbols and final particle set; then how many
of the kills ended identical. Run:

    .venv/bin/python bench/store_kills.py [--kills 12] [--particles 60] [--seed 0]
"""

from __future__ import annotations

import argparse
import os
import random
import sqlite3
import subprocess
import sys
import tempfile
import time
from pathlib import Path

# bench/perception.py would shadow the perception package
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]

ROOT = Path(__file__).resolve().parent.parent

from probanchor.loop.runner import RunOptions, run  # noqa: E402

SCENARIO = """\
name: store_kills
fps: 5
objects:
  - {id: ball_1, category: ball, colour: red, radius: 0.03, position: [-0.1, -0.05]}
  - {id: mug_1, category: mug, colour: blue, radius: 0.04, height: 0.1, position: [0.05, 0.05]}
  - {id: ball_2, category: ball, colour: red, radius: 0.03, position: [-0.25, 0.2]}
  - {id: box_1, category: box, colour: green, size: [0.12, 0.12, 0.12], position: [-0.05, 0.25]}
events:
  - {at: 1.0, do: put_under, object: ball_1, container: mug_1, duration: 2.0}
  - {at: 1.0, do: put_under, object: ball_2, container: box_1, duration: 2.0}
  - {at: 3.5, do: move, object: mug_1, to: [0.2, 0.1], duration: 2.0}
  - {at: 6.0, do: lift, container: mug_1, duration: 2.0}
"""


def _frames(db: Path) -> int:
    try:
        with sqlite3.connect(db, timeout=5) as c:
            return int(c.execute("SELECT count(*) FROM frames").fetchone()[0])
    except sqlite3.Error:
        return 0


def _particles(db: Path) -> tuple[list, list]:
    with sqlite3.connect(db) as c:
        return (c.execute("SELECT i, weight FROM particles ORDER BY i").fetchall(),
                c.execute("SELECT * FROM particle_values ORDER BY atom, i").fetchall())


def _records(output) -> list[dict]:  # noqa: ANN001
    rows = [r.to_json() for r in output.records]
    for row in rows:
        row.pop("timings")
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--kills", type=int, default=12)
    ap.add_argument("--particles", type=int, default=60)
    ap.add_argument("--seed", type=int, default=0, help="the kill moments' random seed")
    args = ap.parse_args()
    pick = random.Random(args.seed)
    env = {**os.environ, "PYTHONPATH": str(ROOT / "python")}
    with tempfile.TemporaryDirectory() as tmp:
        scenario = Path(tmp) / "store_kills.yaml"
        scenario.write_text(SCENARIO)
        whole_db = Path(tmp) / "whole.db"
        whole = run(RunOptions(scenario=scenario, particles=args.particles, progress=False,
                               store=whole_db))
        total = len(whole.records)
        identical = 0
        for k in range(args.kills):
            db = Path(tmp) / f"killed{k}.db"
            at = pick.randint(1, total - 2)  # kill once the store holds this many frames
            child = subprocess.Popen(
                [sys.executable, "-m", "probanchor.cli.anchoring_cli", "run", str(scenario),
                 "--particles", str(args.particles), "--quiet", "--store", str(db)],
                env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            while _frames(db) < at and child.poll() is None:
                time.sleep(0.002)
            child.kill()
            child.wait()
            held = _frames(db)
            resumed = run(RunOptions(resume=db, progress=False))
            same = (_records(resumed) == _records(whole)
                    and [o["symbols"] for o in resumed.summary["objects"]]
                    == [o["symbols"] for o in whole.summary["objects"]]
                    and _particles(db) == _particles(whole_db))
            identical += same
            print(f"kill {k + 1}: store held {held} of {total} frames; resumed run "
                  f"{'identical' if same else 'DIFFERENT'}", flush=True)
        print(f"{identical} of {args.kills} killed and resumed runs ended identical to the "
              f"uninterrupted run ({args.particles} particles, {total} frames)")


if __name__ == "__main__":
    main()
