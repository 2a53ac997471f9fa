"""Learning curve of the learned theory of occlusion: identity and beliefs against episodes.

    .venv/bin/python bench/theory_learning_curve.py [--episodes 5,20,80] [--seeds 5]
        [--labels truth,hindsight] [--particles 1000] [--jobs 2] [--cluster BACKEND]
        [--out out/curve] [--md FILE]

For each number of episodes n and each kind of labels, the first n generated occlusion games (seeds
0..n-1, as ``make learned-theory`` collects them; percept streams cached) are collected (``anchoring
collect``) and a theory is learned from them (``anchoring learn-theory``); each theory then runs the
four shipped scenarios over ``--seeds`` seeds (the simulator's noise and the filter's seed, percept
streams cached as ``anchoring evaluate`` caches them) with ``--particles`` particles in one thread
per run (as ``anchoring evaluate --threads 1``). It prints, and with ``--md`` writes, a Markdown
table: labels, episodes, collected pairs, the seconds of collecting (perception included, summed
over workers) and of learning, the identity kept (objects: every frame and at the end; runs) and the
beliefs' accuracy (summary.json's ``beliefs``: hidden frames whose belief is within 10 cm, the
probability of the true occluder; means over the runs) of the shipped runs; the
hand-written theory's row on the same runs comes last, for reference. The collection episodes and
the theories' runs are jobs (``python/probanchor/jobs``) on ``--jobs`` spawned processes or, with
``--cluster ray|auto|ray://HOST:PORT``, on Ray; the figures are the same on either. """

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "python"))
# Not this folder: Ray puts the script's folder first on its workers' import path, where
# bench/perception.py would hide the perception package.
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != HERE]

SHIPPED = ("shell_game", "can_under_box", "ball_under_box_two_balls", "transitive")


def _run(theory: str, scenario: str, seed: int, particles: int, cache: str) -> dict[str, Any]:
    from probanchor.loop.runner import RunOptions, run
    from probanchor.loop.sources import percept_stream

    stream = percept_stream(ROOT / "scenarios" / f"{scenario}.yaml", seed, Path(cache))
    out = run(RunOptions(percepts=stream, particles=particles, seed=seed, theory=Path(theory),
                         threads=1, progress=False))
    objects = out.summary["objects"]
    beliefs = out.summary.get("beliefs") or {}
    return {"scenario": scenario, "seed": seed, "kept": sum(o["identity_kept"] for o in objects),
            "kept_end": sum(o["identity_kept_at_end"] for o in objects),
            "objects": len(objects), "within": beliefs.get("within"),
            "p_occluder": beliefs.get("true_occluder_probability")}


def identity(theory: Path, seeds: int, particles: int, cache: Path, jobs: int,
             cluster: str | None = None) -> dict[str, Any]:
    """Over the shipped scenarios and seeds: objects kept (every frame, at the end), objects,
    runs kept, runs, and the beliefs' accuracy (summary.json's ``beliefs``: the share of hidden
    frames whose belief is within 10 cm, the probability of the true occluder), averaged over
    the runs that have hidden frames."""
    from probanchor.jobs import Job, parse_cluster, raise_failures, run_jobs

    work = [Job(f"{theory.stem} {s} seed {k}", _run, (str(theory), s, k, particles, str(cache)))
            for s in SHIPPED for k in range(seeds)]
    outcomes = list(run_jobs(work, parse_cluster(cluster, jobs), desc=theory.stem,
                             bar=sys.stderr.isatty()))
    raise_failures(outcomes)
    rows = [o.value for o in outcomes]

    def mean(key: str) -> float | str:
        values = [r[key] for r in rows if r[key] is not None]
        return round(sum(values) / len(values), 3) if values else "-"

    return {"objects_kept": sum(r["kept"] for r in rows),
            "objects_kept_end": sum(r["kept_end"] for r in rows),
            "objects": sum(r["objects"] for r in rows),
            "runs_kept": sum(r["kept"] == r["objects"] for r in rows), "runs": len(rows),
            "within": mean("within"), "p_occluder": mean("p_occluder")}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--episodes", default="5,20,80")
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--labels", default="truth,hindsight")
    parser.add_argument("--particles", type=int, default=1000)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--cluster", default=None,
                        help="local (default), ray, auto or ray://HOST:PORT")
    parser.add_argument("--out", type=Path, default=ROOT / "out" / "curve")
    parser.add_argument("--collect-cache", type=Path, default=ROOT / "out" / "collect")
    parser.add_argument("--percepts", type=Path, default=ROOT / "results" / "percepts",
                        help="the shipped scenarios' percept streams (anchoring evaluate's)")
    parser.add_argument("--md", type=Path, default=None, help="write the table here")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)

    from probanchor.learning.collect import CollectOptions, collect
    from probanchor.learning.learned_theory import learn_theory
    from probanchor.learning.occlusion_data import LabelOptions
    from probanchor.loop.reasoning import DEFAULT_THEORY

    args.out.mkdir(parents=True, exist_ok=True)
    rows: list[dict[str, Any]] = []
    for labels in args.labels.split(","):
        for n in (int(x) for x in args.episodes.split(",")):
            data = args.out / f"data_{labels}_{n}.pl"
            theory = args.out / f"too_{labels}_{n}.pl"
            started = time.perf_counter()
            report = collect(CollectOptions(out=data, games=n, seed=0, jobs=args.jobs,
                                            cluster=args.cluster, cache=args.collect_cache,
                                            labels=LabelOptions(source=labels)))
            collected = time.perf_counter() - started
            learned = learn_theory([data], theory, seed=0)
            kept = identity(theory, args.seeds, args.particles, args.percepts, args.jobs,
                            args.cluster)
            rows.append({"labels": labels, "episodes": n, "pairs": report.pairs,
                         "collect_s": round(collected, 1),
                         "perception_s": round(report.seconds_perception, 1),
                         "learn_s": round(learned.result.targets[0].seconds, 1),
                         "clauses": learned.result.targets[0].clauses, **kept})
            print(json.dumps(rows[-1]), flush=True)
    kept = identity(DEFAULT_THEORY, args.seeds, args.particles, args.percepts, args.jobs,
                    args.cluster)
    rows.append({"labels": "hand-written (prolog/too.pl)", "episodes": "-", "pairs": "-",
                 "collect_s": "-", "perception_s": "-", "learn_s": "-", "clauses": "-", **kept})
    table = _table(rows, args)
    print(table)
    if args.md is not None:
        args.md.write_text(table + "\n", encoding="utf-8")
    if args.json:
        print(json.dumps(rows))
    return 0


def _table(rows: list[dict[str, Any]], args: argparse.Namespace) -> str:
    head = (f"<!-- made by `.venv/bin/python bench/theory_learning_curve.py --episodes "
            f"{args.episodes} --seeds {args.seeds} --labels {args.labels} --particles "
            f"{args.particles}` -->\n\n"
            "| labels | episodes | pairs | collecting s (perception s) | learning s | clauses "
            "| identity kept (objects) | at the end (objects) | identity kept (runs) "
            "| belief within 10 cm | P(true occluder) |\n"
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    lines = [head]
    for r in rows:
        pct_o = 100 * r["objects_kept"] / max(r["objects"], 1)
        pct_r = 100 * r["runs_kept"] / max(r["runs"], 1)
        coll = (f"{r['collect_s']} ({r['perception_s']})" if r["collect_s"] != "-" else "-")
        lines.append(f"| {r['labels']} | {r['episodes']} | {r['pairs']} | {coll} "
                     f"| {r['learn_s']} | {r['clauses']} "
                     f"| {r['objects_kept']}/{r['objects']} ({pct_o:.0f} %) "
                     f"| {r['objects_kept_end']}/{r['objects']} "
                     f"| {r['runs_kept']}/{r['runs']} ({pct_r:.0f} %) "
                     f"| {r['within']} | {r['p_occluder']} |")
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
