"""The measured table of the README: identity kept, ID switches and IDF1 for every shipped
scenario over several seeds and for random shell games, with reasoning, without it, and for
published multi-object trackers run on the same percepts.

Each (scenario, seed) is perceived once (the stream is cached as JSON Lines in the output
directory) and every method runs on that same stream.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from app.runner import RunOptions, run
from evaluation import evaluate, make_summary, results_table
from evaluation.baselines import BASELINES, run_baseline
from percepts import read_percepts, write_percepts

ROOT = Path(__file__).resolve().parents[2]
SHIPPED = ("shell_game", "can_under_box", "ball_under_box_two_balls", "transitive")
METHODS = ("reasoning", "no-reasoning", *BASELINES)


@dataclass
class ExperimentOptions:
    out: Path
    seeds: int = 20
    games: int = 50
    particles: int = 1000
    methods: Sequence[str] = METHODS
    scenarios: Sequence[str] = SHIPPED
    first_game_seed: int = 0


def game_scenarios(out: Path, games: int, first_seed: int = 0) -> list[Path]:
    """``games`` random shell games: 3 to 5 containers, 3 to 10 swaps, saved as YAML."""
    from tabletop.generate import shell_game

    rng = np.random.default_rng(first_seed)
    paths = []
    (out / "games").mkdir(parents=True, exist_ok=True)
    for i in range(games):
        containers = int(rng.integers(3, 6))
        swaps = int(rng.integers(3, 11))
        builder = shell_game(containers=containers, swaps=swaps, seed=first_seed + i)
        path = out / "games" / f"game_{first_seed + i:03d}.yaml"
        builder.save(path)
        paths.append(path)
    return paths


def percept_stream(scenario: Path, seed: int, cache: Path) -> Path:
    """The perceived stream of ``scenario`` with noise seed ``seed`` (cached)."""
    from perception import perceive_scenario

    path = cache / f"{scenario.stem}_seed{seed}.jsonl"
    if not path.exists():
        cache.mkdir(parents=True, exist_ok=True)
        partial = path.with_suffix(".partial")
        write_percepts(partial, perceive_scenario(scenario, seed=seed))
        partial.rename(path)
    return path


def run_method(method: str, stream: Path, particles: int, seed: int) -> dict[str, Any]:
    """One method on one percept stream -> its summary."""
    if method in ("reasoning", "no-reasoning"):
        output = run(RunOptions(percepts=stream, particles=particles, seed=seed,
                                reasoning=method == "reasoning", progress=False))
        return output.summary
    records = run_baseline(method, list(read_percepts(stream)))
    return make_summary(records, evaluate(records), extra={"method": method})


def run_experiment(options: ExperimentOptions,
                   progress: Callable[[str], None] | None = None) -> str:
    """Run everything, write ``OUT/summaries.jsonl`` and ``OUT/results.md``; return the table."""
    out = options.out
    out.mkdir(parents=True, exist_ok=True)
    jobs: list[tuple[str, Path, int]] = []
    for name in options.scenarios:
        for seed in range(options.seeds):
            jobs.append((name, ROOT / "scenarios" / f"{name}.yaml", seed))
    for path in game_scenarios(out, options.games, options.first_game_seed):
        jobs.append(("generated shell games", path, 0))
    rows: list[tuple[str, str, dict[str, Any]]] = []
    with open(out / "summaries.jsonl", "w", encoding="utf-8") as log:
        for label, scenario, seed in jobs:
            stream = percept_stream(scenario, seed, out / "percepts")
            for method in options.methods:
                if progress is not None:
                    progress(f"{scenario.stem} seed {seed}: {method}")
                summary = run_method(method, stream, options.particles, seed)
                rows.append((label, method, summary))
                log.write(json.dumps({"scenario": scenario.stem, "group": label, "seed": seed,
                                      "method": method, "summary": summary}) + "\n")
    table = results_table(rows)
    (out / "results.md").write_text(table, encoding="utf-8")
    return table
