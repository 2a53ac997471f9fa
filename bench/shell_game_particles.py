"""The shell game's frame rate at 10,000 particles against 1,000, side by side in one run.

    .venv/bin/python bench/shell_game_particles.py
    .venv/bin/python bench/shell_game_particles.py --scenario scenarios/shell_game.yaml \\
        --runs 1000:prolog 1000 10000

Plays the scenario through ``anchoring run`` (perception, anchoring and the filter, as a user
runs it) once per configuration, each in a process of its own, and prints the frame rate and
the per-stage milliseconds that ``anchoring run`` prints. A configuration is ``N`` (particles,
the batched filter's columns in C where the library is built) or ``N:prolog`` (the columns in
Prolog, ``DDC_COLUMNS=prolog``: the batched engine before the column library). The default runs
1,000 particles without the library (the engine as it was), 1,000 and 10,000 with it, and says
whether 10,000 with it runs at least as fast as 1,000 without it (the target).
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LINE = re.compile(r"ms per frame: perception ([\d.]+), anchoring ([\d.]+), filter ([\d.]+), "
                  r"total ([\d.]+) \(([\d.]+) frames per second\)")


def run(scenario: str, particles: int, columns: str | None, seed: int) -> dict[str, float]:
    env = dict(os.environ)
    env.pop("DDC_COLUMNS", None)
    if columns:
        env["DDC_COLUMNS"] = columns
    env["PYTHONPATH"] = str(ROOT / "python") + os.pathsep + env.get("PYTHONPATH", "")
    command = [str(Path(sys.executable).parent / "anchoring"), "run", scenario,
               "--particles", str(particles), "--seed", str(seed)]
    out = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True,
                         check=True).stdout
    match = LINE.search(out)
    if match is None:
        raise RuntimeError(f"no 'ms per frame' line in the output of {' '.join(command)}")
    keys = ("perception", "anchoring", "filter", "total", "fps")
    return dict(zip(keys, (float(g) for g in match.groups()), strict=True))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenario", default="scenarios/shell_game.yaml")
    parser.add_argument("--runs", nargs="+", default=["1000:prolog", "1000", "10000"],
                        help="configurations N or N:prolog (default 1000:prolog 1000 10000)")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    print(f"{args.scenario}, seed {args.seed}")
    print(f"{'particles':>10} {'columns':>8} {'filter ms':>10} {'total ms':>9} {'fps':>6}",
          flush=True)
    results = {}
    for spec in args.runs:
        n_text, _, columns = spec.partition(":")
        n = int(n_text)
        r = run(args.scenario, n, columns or None, args.seed)
        results[spec] = r
        print(f"{n:>10} {columns or 'C':>8} {r['filter']:>10.1f} {r['total']:>9.1f} "
              f"{r['fps']:>6.1f}", flush=True)
    if "1000:prolog" in results and "10000" in results:
        before, after = results["1000:prolog"]["fps"], results["10000"]["fps"]
        verdict = "meets" if after >= before else "misses"
        print(f"10,000 particles with the column library: {after:.1f} fps; 1,000 without it: "
              f"{before:.1f} fps ({after / before:.2f}x: {verdict} the target)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
