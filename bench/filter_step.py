"""Milliseconds per DDC filter step on a theory-of-occlusion model, against numpy.

    .venv/bin/python bench/filter_step.py     # the grid N in {100,1000,5000} x M in {3,10,20}
    .venv/bin/python bench/filter_step.py --particles 1000 --objects 10 --json
    .venv/bin/python bench/filter_step.py --scaling   # N=1000 M=10, N=10000 M=10, N=1000 M=30

For each configuration it generates the DDC program of the occlusion model for M objects
(bench/filter_numpy_reference.py: each hidden object picks an occluder uniformly among the
nearby seen objects above it, hidden positions follow their occluder, observed positions weight
the particles with a Gaussian likelihood) and a reproducible scenario, runs ``--steps`` steps
of ``bridge.Filter`` and, in the same run, of the vectorised numpy implementation of the same
model, and prints ms per step for both and their ratio. With ``--json`` (one configuration)
the last line is ``{"ms_per_step": x, "numpy_ms_per_step": y}``.

It also runs bench/filter_floor.pl, the same arithmetic for perceived objects hand-written in
Prolog (per particle and object: a 3-D Gaussian move and a Gaussian log density; no clauses, no
store, no occluder choice), the least any engine that samples particles one by one in
SWI-Prolog can cost, and prints the engine's ratio to it.

The engine steps the particles in ``--threads`` Prolog threads (default 2, as
``bridge.Filter``); the floor is one thread's. ``--engine`` picks it as ``bridge.Filter`` does:
``auto`` (the default: the batched engine, prolog/ddc/batch/ddc_batch.pl, for this model),
``batched`` or ``per_particle`` (prolog/ddc/filter/ddc_filter.pl, one particle at a time).

``--calls K`` (with one configuration) also steps it once more in one thread under SWI-Prolog's
profiler and prints the K most-called predicates per particle and step; with the per-particle
engine also the lookups in the value tables (``store_get``) per particle, step and object.

``--scaling`` runs the three configurations of the targets in one run and prints, beside the
ratio to numpy of each, the scaling: the time at 10 N over the time at N (linear: 10) and at
3 M over M (linear: 3), each with its ratio to linear.  The last column names the batched
engine's columns (``foreign``: the compiled library, prolog/ddc/batch/c/ddc_columns.c; ``prolog``:
terms, as with ``DDC_COLUMNS=prolog``).

Targets: N = 1000, M = 10 in at most 33 ms per step (30 Hz); within 2x of numpy there, within
3x at N = 10000 and at M = 30; time linear in N and in M within 1.2x.
"""

from __future__ import annotations

import argparse
import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "python"))

import filter_numpy_reference as model  # noqa: E402
from bridge import DEFAULT_THREADS, Filter, FilterError  # noqa: E402
from bridge import prolog as bridge_prolog  # noqa: E402
from bridge import resources as bridge_resources  # noqa: E402
from bridge.engines import ENGINES  # noqa: E402

TARGET_MS = 33.0
TARGET_RATIO = {(1000, 10): 2.0, (10000, 10): 3.0, (1000, 30): 3.0}


def write_program(directory: str, objects: int) -> Path:
    """The bench's DDC program for ``objects`` objects, written into ``directory``."""
    program = Path(directory) / f"occlusion_{objects}.pl"
    program.write_text(model.ddc_program(objects))
    return program


def find_swipl() -> str | None:
    """The swipl next to this Python (the set-up's link), else the one on PATH."""
    return shutil.which("swipl", path=str(Path(sys.executable).parent)) or shutil.which("swipl")


def time_ddc(particles: int, objects: int, steps: int, seed: int,
             threads: int, engine: str = "auto") -> dict[str, float]:
    frames = model.scenario(objects, steps, seed=seed)
    names = model.object_names(objects)
    with tempfile.TemporaryDirectory() as tmp:
        program = write_program(tmp, objects)
        started = time.perf_counter()
        f = Filter(program, particles=particles, seed=seed, threads=threads, engine=engine)
        new_ms = 1000 * (time.perf_counter() - started)
        with f:
            cpu_started = time.process_time()
            for frame in frames:
                f.step(frame.terms(names))
            cpu_ms = 1000 * (time.process_time() - cpu_started) / len(frames)
            step_ms = [1000 * s for s in f.step_seconds]
            prolog_ms = [1000 * s for s in f.step_prolog_seconds]
            return {
                "ms_per_step": statistics.fmean(step_ms),
                "new_ms": new_ms,
                "median_ms": statistics.median(step_ms),
                "resamplings": f.resample_count,
                "zero_weight_events": f.zero_weight_events,
                "prolog_share": sum(prolog_ms) / sum(step_ms),
                "cpu_ms_per_step": cpu_ms,
            }


_CALL_COUNTS = (  # (janus returns every named variable but _-prefixed ones: only Counts)
    "atom_string(_F, K), "
    "ddc:filter_call(_F, (profiler(_, false), profile_data(_D))), "
    "get_dict(nodes, _D, _Nodes), "
    "findall(_C-_P, ( member(_Node, _Nodes), get_dict(call, _Node, _C), "
    "get_dict(predicate, _Node, _P0), format(string(_P), '~w', [_P0]) ), Counts)"
)


def call_counts(particles: int, objects: int, steps: int, seed: int,
                engine: str = "auto") -> dict[str, int]:
    """Calls per predicate over ``steps`` steps in one thread, by SWI-Prolog's profiler
    (switched on around the steps only, in the filter's Prolog engine, where its particles
    are stepped)."""
    frames = model.scenario(objects, steps, seed=seed)
    names = model.object_names(objects)
    with tempfile.TemporaryDirectory() as tmp:
        program = write_program(tmp, objects)
        with Filter(program, particles=particles, seed=seed, threads=1, engine=engine) as f:
            handle = {"K": f.handle}
            bridge_prolog.query_once("use_module(library(statistics)), atom_string(_F, K), "
                                     "ddc:filter_call(_F, (reset_profiler, "
                                     "profiler(_, cputime)))", handle)
            try:
                for frame in frames:
                    f.step(frame.terms(names))
            finally:
                counts = bridge_prolog.query_once(_CALL_COUNTS, handle)["Counts"]
    return {str(name): int(calls) for calls, name in counts}


def print_call_counts(particles: int, objects: int, steps: int, seed: int, top: int,
                      engine: str) -> None:
    counts = call_counts(particles, objects, steps, seed, engine)
    per_step = particles * steps
    print(f"most-called predicates per particle and step (N={particles}, M={objects}, "
          f"one thread, {steps} steps):")
    for name, calls in sorted(counts.items(), key=lambda kv: -kv[1])[:top]:
        print(f"  {calls / per_step:>8.1f}  {name}")
    lookups = sum(calls for name, calls in counts.items()
                  if name.startswith("ddc_store:store_get/"))
    if lookups:
        print(f"  value-table lookups (store_get) per particle, step and object: "
              f"{lookups / per_step / objects:.1f}")


def time_floor(particles: int, objects: int) -> float | None:
    """ms per step of bench/filter_floor.pl: per-particle Prolog arithmetic alone, no engine."""
    swipl = find_swipl()
    if swipl is None:
        return None
    out = subprocess.run([swipl, "-O", str(HERE / "filter_floor.pl"), str(particles),
                          str(objects)], capture_output=True, text=True, check=True).stdout
    return float(json.loads(out.strip().splitlines()[-1])["floor_ms_per_step"])


def column_backend() -> str:
    """The batched engine's columns in this process: foreign or prolog."""
    path = str(bridge_resources.prolog_file("ddc/batch/ddc_batch_col.pl"))
    return str(bridge_prolog.query_once("use_module(P), ddc_batch_col:col_backend(B)",
                                        {"P": path})["B"])


def time_numpy(particles: int, objects: int, steps: int, seed: int) -> float:
    return time_numpy_both(particles, objects, steps, seed)[0]


def time_numpy_both(particles: int, objects: int, steps: int,
                    seed: int) -> tuple[float, float]:
    """(wall, CPU) ms per step of the numpy twin."""
    frames = model.scenario(objects, steps, seed=seed)
    f = model.NumpyOcclusionFilter(objects, particles, seed=seed)
    started, cpu_started = time.perf_counter(), time.process_time()
    for frame in frames:
        f.step(frame)
    return (1000 * (time.perf_counter() - started) / steps,
            1000 * (time.process_time() - cpu_started) / steps)


def print_scaling(measured: dict[tuple[int, int], tuple[float, float, float, float]]) -> None:
    """The targets' ratios to numpy and the scaling in N and in M, from one run: in wall
    time (what the targets are about, on an idle machine) and in CPU time (the whole process's,
    every Prolog thread's included; steadier on a shared machine)."""
    print("ratios to numpy in this run (wall; CPU of the process):")
    for (n, m), target in TARGET_RATIO.items():
        ddc_ms, numpy_ms, ddc_cpu, numpy_cpu = measured[(n, m)]
        ratio = ddc_ms / numpy_ms
        verdict = "meets" if ratio <= target else "misses"
        print(f"  N={n} M={m}: {ddc_ms:.1f} / {numpy_ms:.2f} ms = {ratio:.1f}x "
              f"({verdict} the {target:.0f}x target); CPU {ddc_cpu:.1f} / {numpy_cpu:.2f} ms "
              f"= {ddc_cpu / numpy_cpu:.1f}x")
    base, base_cpu = measured[(1000, 10)][0], measured[(1000, 10)][2]
    for label, (n, m), linear in (("10 N", (10000, 10), 10.0), ("3 M", (1000, 30), 3.0)):
        scale = measured[(n, m)][0] / base
        verdict = "within" if scale <= 1.2 * linear else "beyond"
        print(f"  time at {label} / time at N=1000 M=10: {scale:.2f} (linear {linear:.0f}; "
              f"{scale / linear:.2f}x linear, {verdict} 1.2x); CPU "
              f"{measured[(n, m)][2] / base_cpu:.2f}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--particles", type=int, help="one configuration: N particles")
    parser.add_argument("--objects", type=int, help="one configuration: M objects")
    parser.add_argument("--steps", type=int, default=10, help="filter steps timed (default 10)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--threads", type=int, default=DEFAULT_THREADS,
                        help="Prolog threads stepping the particles (default: bridge.Filter's)")
    parser.add_argument("--json", action="store_true", help="end with a JSON line")
    parser.add_argument("--engine", choices=ENGINES, default="auto",
                        help="the filter engine, as bridge.Filter's engine (default auto)")
    parser.add_argument("--scaling", action="store_true",
                        help="N=1000 M=10, N=10000 M=10 and N=1000 M=30 in one run, with the "
                             "ratios to numpy and the scaling in N and in M")
    parser.add_argument("--calls", type=int, default=0, metavar="K",
                        help="with one configuration: also print the K most-called predicates "
                             "(one thread, profiled)")
    args = parser.parse_args(argv)
    if (args.particles is None) != (args.objects is None):
        parser.error("give both --particles and --objects, or neither (the full grid)")
    if args.calls and args.particles is None:
        parser.error("--calls needs one configuration (--particles and --objects)")
    if args.scaling and args.particles is not None:
        parser.error("--scaling runs its own configurations")
    if args.scaling:
        configs = list(TARGET_RATIO)
    elif args.particles is not None:
        configs = [(args.particles, args.objects)]
    else:
        configs = [(n, m) for m in (3, 10, 20) for n in (100, 1000, 5000)]
    print(f"engine: {args.engine}, {args.threads} thread(s), columns: {column_backend()}")
    print(f"{'N':>6} {'M':>4} {'ddc ms/step':>12} {'numpy ms/step':>14} {'ratio':>8} "
          f"{'floor ms':>9} {'/floor':>7} "
          f"{'us/particle':>12} {'in Prolog':>9} {'new ms':>9} {'resampled':>9}", flush=True)
    last = None
    failed = False
    measured: dict[tuple[int, int], tuple[float, float]] = {}
    for n, m in configs:
        numpy_ms, numpy_cpu_ms = time_numpy_both(n, m, args.steps, args.seed)
        try:
            ddc = time_ddc(n, m, args.steps, args.seed, args.threads, args.engine)
        except FilterError as exc:  # e.g. the engine ran out of stack: report, go on
            first_line = str(exc).splitlines()[0]
            print(f"{n:>6} {m:>4} {'failed':>12} {numpy_ms:>14.2f}   {first_line}", flush=True)
            failed = True
            continue
        ratio = ddc["ms_per_step"] / numpy_ms
        measured[(n, m)] = (ddc["ms_per_step"], numpy_ms, ddc["cpu_ms_per_step"],
                            numpy_cpu_ms)
        floor = time_floor(n, m)
        floor_text = (f"{floor:>9.1f} {ddc['ms_per_step'] / floor:>7.1f}" if floor
                      else f"{'-':>9} {'-':>7}")
        print(f"{n:>6} {m:>4} {ddc['ms_per_step']:>12.1f} {numpy_ms:>14.2f} {ratio:>8.0f} "
              f"{floor_text} "
              f"{1000 * ddc['ms_per_step'] / n:>12.1f} {ddc['prolog_share']:>9.0%} "
              f"{ddc['new_ms']:>9.0f} "
              f"{ddc['resamplings']:>6}/{args.steps}", flush=True)
        if (n, m) == (1000, 10):
            verdict = "meets" if ddc["ms_per_step"] <= TARGET_MS else "misses"
            print(f"  N=1000 M=10: {ddc['ms_per_step']:.1f} ms/step {verdict} the "
                  f"{TARGET_MS:.0f} ms target", flush=True)
        last = {"ms_per_step": ddc["ms_per_step"], "numpy_ms_per_step": numpy_ms,
                "floor_ms_per_step": floor}
    if args.scaling and not failed:
        print_scaling(measured)
    if args.calls and not failed:
        print_call_counts(args.particles, args.objects, args.steps, args.seed, args.calls,
                          args.engine)
    if args.json and last is not None:
        print(json.dumps(last))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
