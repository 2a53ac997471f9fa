"""Jobs per minute of each back end of ``python/probanchor/jobs`` with 1 and 2 workers, and the
overhead per job: when does Ray pay off?

    .venv/bin/python bench/cluster_jobs.py [--scenarios can_under_box,transitive] [--seeds 3]
        [--particles 300] [--noop 1000] [--backends local,ray] [--out out/bench_jobs]

The sweep is ``anchoring evaluate``'s: one job per (scenario, seed), reasoning with the
hand-written theory in one Prolog thread per filter, on percept streams perceived once before
the clock starts (as a re-run finds them in the results folder). Each back end runs it with 1
and with 2 workers, its start-up included (spawning the pool, or starting a local Ray); the
reference is the same sweep run one job after the other in this process, measured in the same
run. Start-up and the overhead per job are measured on empty jobs with 2 workers: the time of
two (plus, for Ray, starting it), and the median of three measures of ``--noop`` more against
two, so that the start-up cancels. It also checks that every back end gave the same summaries.
"""

from __future__ import annotations

import argparse
import json
import logging
import os
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


def noop() -> int:
    """An empty job."""
    return 0


def sweep(cluster: Any, work: list[Any]) -> tuple[float, list[str]]:
    """Seconds of the whole sweep on ``cluster`` and its summaries (timings left out)."""
    from probanchor.jobs import raise_failures, run_jobs

    started = time.perf_counter()
    outcomes = list(run_jobs(work, cluster))
    seconds = time.perf_counter() - started
    raise_failures(outcomes)
    lines = []
    for outcome in outcomes:
        for line in outcome.value:
            line["summary"].pop("ms_per_frame", None)
            lines.append(json.dumps(line, sort_keys=True))
    return seconds, sorted(lines)


def empty_jobs(cluster: Any, count: int) -> float:
    """Seconds of ``count`` empty jobs on ``cluster``."""
    from probanchor.jobs import Job, run_jobs

    started = time.perf_counter()
    outcomes = list(run_jobs([Job(f"noop {i}", noop) for i in range(count)], cluster))
    seconds = time.perf_counter() - started
    assert all(o.ok for o in outcomes), [o.error for o in outcomes if not o.ok]
    return seconds


def overhead(backend: str, count: int, repeat: int = 3) -> tuple[float, float]:
    """Start-up seconds of 2 workers, and seconds per further empty job (the median of
    ``repeat`` measures of ``2 + count`` empty jobs against 2).

    Local: every measure starts its own pool of two spawned processes. Ray: a local Ray with
    two CPUs is started once (its start is the start-up), warmed up with two empty jobs, and
    kept for the measures."""
    from probanchor.jobs import parse_cluster

    cluster = parse_cluster(backend, 2)
    ray = None
    started = time.perf_counter()
    if backend == "ray":
        import ray

        ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False,
                 logging_level=logging.ERROR)
    try:
        start = time.perf_counter() - started + empty_jobs(cluster, 2)
        per_job = sorted((empty_jobs(cluster, 2 + count) - empty_jobs(cluster, 2)) / count
                         for _ in range(repeat))
    finally:
        if ray is not None:
            ray.shutdown()
    return start, per_job[len(per_job) // 2]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenarios", default="can_under_box,transitive")
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--particles", type=int, default=300)
    parser.add_argument("--noop", type=int, default=1000, help="empty jobs for the overhead")
    parser.add_argument("--backends", default="local,ray")
    parser.add_argument("--out", type=Path, default=ROOT / "out" / "bench_jobs",
                        help="where the percept streams are cached")
    args = parser.parse_args(argv)

    from probanchor.experiments.sweep import run_unit
    from probanchor.jobs import Job, parse_cluster
    from probanchor.loop.sources import percept_stream

    cache = args.out / "percepts"
    units = [(name, ROOT / "scenarios" / f"{name}.yaml", seed)
             for name in args.scenarios.split(",") for seed in range(args.seeds)]
    for _, scenario, seed in units:        # perceived once, before the clock starts
        percept_stream(scenario, seed, cache)
    work = [Job(f"{scenario.stem} seed {seed}", run_unit,
                (name, scenario, seed, ["reasoning"], args.particles, cache, 1, "auto"))
            for name, scenario, seed in units]

    load = os.getloadavg()[0]
    reference, expected = sweep(parse_cluster("local", 1), work)
    rows = [("this process, one after the other (reference)", 1, reference, None, None)]
    same = True
    for backend in args.backends.split(","):
        for workers in (1, 2):
            if backend == "local" and workers == 1:
                continue                     # that is the reference
            seconds, summaries = sweep(parse_cluster(backend, workers), work)
            same &= summaries == expected
            rows.append((backend, workers, seconds, None, None))
        start, per_job = overhead(backend, args.noop)
        rows.append((f"{backend}: empty jobs", 2, None, start, per_job))

    print(f"sweep: {len(work)} jobs ({args.scenarios} x {args.seeds} seeds, reasoning, "
          f"{args.particles} particles, 1 Prolog thread per filter); empty jobs: {args.noop}")
    print("| back end | workers | sweep s | jobs per minute | speed-up | start-up s "
          "| overhead ms per job |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name, workers, seconds, start, per_job in rows:
        if seconds is not None:
            print(f"| {name} | {workers} | {seconds:.1f} | {60 * len(work) / seconds:.1f} "
                  f"| {reference / seconds:.2f} | | |")
        else:
            print(f"| {name} | {workers} | | | | {start:.2f} | {1000 * per_job:.1f} |")
    print(f"same summaries on every back end: {'yes' if same else 'NO'}; load average "
          f"{load:.2f} before, {os.getloadavg()[0]:.2f} after, on {os.cpu_count()} CPUs")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
