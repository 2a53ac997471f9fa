"""The measured table (docs/evaluation.md): identity kept, ID switches, IDF1 and HOTA for every
shipped scenario over several seeds and for random shell games, with reasoning, without it, and
for published multi-object trackers (2-D box trackers, Stone Soup's JPDA and MHT) run on the
same percepts.

Each (scenario, seed) is perceived once (the stream is cached as JSON Lines in the output
directory) and every method runs on that same stream. The (scenario, seed) units are
independent jobs (:mod:`probanchor.jobs`): on ``jobs`` spawned worker processes, or on a Ray cluster
(``cluster``); each unit's lines go into ``OUT/summaries.jsonl`` the moment it finishes, and a
unit whose every method is already there (an interrupted, failed or extended run) is not run
again. The table is made from those lines, so it is the same whichever back end ran them.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from bridge.engines import Engine
from bridge.includes import digest_with_includes
from probanchor.evaluation import evaluate, make_summary, results_table
from probanchor.evaluation.baselines import BASELINES, run_baseline
from probanchor.jobs import Job, JobsFailed, parse_cluster, run_jobs
from probanchor.loop.reasoning import DEFAULT_THREADS
from probanchor.loop.runner import RunOptions, run
from probanchor.loop.sources import percept_stream
from probanchor.loop.theories import theory_path
from probanchor.percepts import read_percepts
from probanchor.resources import scenario_file

SHIPPED = ("shell_game", "can_under_box", "ball_under_box_two_balls", "transitive")
#: Reasoning with each shipped theory of occlusion (loop.theories): the hand-written one, the one
#: learned from ground-truth labels, the one learned from hindsight labels.
REASONING = {"reasoning": "hand", "learned": "learned", "learned-hindsight": "hindsight"}
METHODS = ("reasoning", "no-reasoning", *BASELINES)
ALL_METHODS = (*REASONING, "no-reasoning", *BASELINES)


@dataclass
class ExperimentOptions:
    out: Path
    seeds: int = 20
    games: int = 50
    particles: int = 1000
    methods: Sequence[str] = METHODS
    scenarios: Sequence[str] = SHIPPED
    first_game_seed: int = 0
    jobs: int = 1                   # worker processes (local), or the local Ray's CPUs
    cluster: str | None = None      # None or "local", "ray", "auto", "ray://HOST:PORT"
    threads: int = DEFAULT_THREADS  # Prolog threads per filter (the particles depend on it)
    engine: Engine = "auto"         # the filter's engine (bridge.Filter's; the particles too)


def game_scenarios(out: Path, games: int, first_seed: int = 0) -> list[Path]:
    """``games`` random shell games: 3 to 5 containers, 3 to 10 swaps, saved as YAML."""
    from probanchor.tabletop.generate import shell_game

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


def theory_digest(method: str) -> str | None:
    """The SHA-1 of the theory a reasoning method runs (None for the others): of its file and
    of every file it includes (``:- include/1``, followed as the DDC system's reader follows
    them: :func:`bridge.includes.digest_with_includes`), so that a run recorded with another
    version of the theory or of any part of it is run again."""
    if method not in REASONING:
        return None
    return digest_with_includes(theory_path(REASONING[method]))[:12]


def run_method(method: str, stream: Path, particles: int, seed: int,
               threads: int = DEFAULT_THREADS, engine: Engine = "auto") -> dict[str, Any]:
    """One method on one percept stream -> its summary."""
    if method in REASONING or method == "no-reasoning":
        theory = theory_path(REASONING.get(method, "hand"))
        output = run(RunOptions(percepts=stream, particles=particles, seed=seed,
                                reasoning=method != "no-reasoning", theory=theory,
                                progress=False, threads=threads, engine=engine))
        return output.summary
    records = run_baseline(method, list(read_percepts(stream)))
    return make_summary(records, evaluate(records), extra={"method": method})


def run_unit(label: str, scenario: Path, seed: int, methods: Sequence[str], particles: int,
             cache: Path, threads: int = DEFAULT_THREADS,
             engine: Engine = "auto") -> list[dict[str, Any]]:
    """Every method on one (scenario, seed): the lines of ``summaries.jsonl``."""
    stream = percept_stream(scenario, seed, cache)
    return [{"scenario": scenario.stem, "group": label, "seed": seed, "method": method,
             "particles": particles, "threads": threads, "engine": engine,
             "theory": theory_digest(method),
             "summary": run_method(method, stream, particles, seed, threads, engine)}
            for method in methods]


def read_summaries(path: Path) -> list[dict[str, Any]]:
    """The lines of a ``summaries.jsonl`` (none if it does not exist)."""
    if not path.exists():
        return []
    with open(path, encoding="utf-8") as lines:
        return [json.loads(line) for line in lines if line.strip()]


def run_experiment(options: ExperimentOptions, progress: bool = False) -> str:
    """Run everything, write ``OUT/summaries.jsonl`` and ``OUT/results.md``; return the table.

    Runs already in ``OUT/summaries.jsonl`` with the same particle count (and, with reasoning,
    the same thread count: lines without one were made with one thread) are kept, not run
    again; the table covers exactly the units of ``options``.

    Parameters
    ----------
    options : ExperimentOptions
        What to run, and where (``jobs``, ``cluster``).
    progress : bool
        Draw one progress bar over the units (on standard error).

    Returns
    -------
    str
        The Markdown table (also written to ``OUT/results.md``).

    Raises
    ------
    jobs.JobsFailed
        Some units failed (each named with its cause); the finished ones are recorded in
        ``OUT/summaries.jsonl``, and running again runs only what is missing.
    """
    cluster = parse_cluster(options.cluster, options.jobs)
    out = options.out
    out.mkdir(parents=True, exist_ok=True)
    units: list[tuple[str, Path, int]] = []
    for name in options.scenarios:
        for seed in range(options.seeds):
            units.append((name, scenario_file(name), seed))
    for path in game_scenarios(out, options.games, options.first_game_seed):
        units.append(("generated shell games", path, 0))

    log_path = out / "summaries.jsonl"
    digests = {m: theory_digest(m) for m in REASONING if m in options.methods}
    done: dict[tuple[str, int, str], dict[str, Any]] = {
        (line["scenario"], line["seed"], line["method"]): line
        for line in read_summaries(log_path)
        if line.get("particles", options.particles) == options.particles
        # (runs recorded before HOTA was have no HOTA columns: run again)
        and "hota" in line["summary"]
        and (line["method"] not in REASONING
             or (line.get("threads", 1) == options.threads
                 # (runs recorded before the engine was, ran the per-particle one)
                 and line.get("engine", "per_particle") == options.engine
                 # (runs recorded before the theory was, ran prolog/too.pl as it was then)
                 and line.get("theory", digests.get(line["method"]))
                 == digests.get(line["method"])))
    }
    todo = [(label, scenario, seed,
             [m for m in options.methods if (scenario.stem, seed, m) not in done])
            for label, scenario, seed in units]
    work = [Job(f"{scenario.stem} seed {seed}", run_unit,
                (label, scenario, seed, methods, options.particles, out / "percepts",
                 options.threads, options.engine))
            for label, scenario, seed, methods in todo if methods]
    failed = []
    with open(log_path, "a", encoding="utf-8") as log:
        for outcome in run_jobs(work, cluster, desc="evaluate", bar=progress):
            if not outcome.ok:
                failed.append(outcome)
                continue
            for line in outcome.value:
                done[(line["scenario"], line["seed"], line["method"])] = line
                log.write(json.dumps(line) + "\n")
            log.flush()
    if failed:
        raise JobsFailed(failed, len(work), f"the {len(work) - len(failed)} finished are in "
                         f"{log_path}; the same command again runs only what is missing")

    rows = [(label, method, done[(scenario.stem, seed, method)]["summary"])
            for label, scenario, seed in units for method in options.methods]
    table = results_table(rows)
    (out / "results.md").write_text(table, encoding="utf-8")
    return table
