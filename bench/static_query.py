"""Microseconds per sample of the DDC system on the original DC system's example1 workload.

The workload (the original's README test): P(drawn(1) = 1), P(drawn(1) = 2), P(drawn(1) = 3)
and E[g], 10,000 samples each, in ``prolog/examples/example1.pl``. The original system (YAP
Prolog + C++) reports "0.290 CPU in 0.291 seconds" for it, about 7.25 us per sample; the
target is to be at least as fast. The time is Prolog CPU time of the four queries (best of
``--repeat`` runs, program already loaded). For scale, the same run also times a vectorised
numpy Monte Carlo of the same four quantities (no logic, no per-sample interpretation).

    .venv/bin/python bench/static_query.py            # a table
    .venv/bin/python bench/static_query.py --json     # ... and a last line {"us_per_sample": x}
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

from bridge import load  # noqa: E402
from bridge.program import _call  # noqa: E402

ORIGINAL_SECONDS = 0.290
SAMPLES = 10_000
QUERIES = 4
ORIGINAL_US = ORIGINAL_SECONDS / (SAMPLES * QUERIES) * 1e6

WORKLOAD = (
    "statistics(cputime, _T0),"
    " forall(member(_V, [1, 2, 3]),"
    "        ddc:query(true, drawn(1) ~= _V, _, [samples(N), program(M)])),"
    " ddc:expectation(true, g ~= _X, _X, _, [samples(N), program(M)]),"
    " statistics(cputime, _T1), T is _T1 - _T0"
)


def engine_seconds(module: str, samples: int, seed: int) -> float:
    _call("set_random(seed(S))", {"S": seed})
    return float(_call(WORKLOAD, {"M": module, "N": samples})["T"])


def numpy_seconds(samples: int, rng: np.random.Generator) -> float:
    start = time.process_time()
    for value in (1, 2, 3):
        nballs = rng.integers(1, 11, samples)
        drawn = (rng.random(samples) * nballs).astype(int) + 1
        float(np.mean(drawn == value))
    float(np.mean(rng.normal(0.0, 0.1, samples)))
    return time.process_time() - start


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=SAMPLES)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)

    program = load(ROOT / "prolog" / "examples" / "example1.pl")
    engine_seconds(program.module, 500, 0)  # warm up (JIT clause indexes)
    best = min(engine_seconds(program.module, args.samples, seed) for seed in range(args.repeat))
    rng = np.random.default_rng(0)
    numpy_best = min(numpy_seconds(args.samples, rng) for _ in range(args.repeat))

    total = args.samples * QUERIES
    us = best / total * 1e6
    numpy_us = numpy_best / total * 1e6
    print(f"example1 workload: {QUERIES} queries x {args.samples} samples, best of {args.repeat}")
    print(f"  DDC system (SWI-Prolog)      {best:8.3f} s   {us:8.2f} us/sample")
    print(f"  original DC (YAP + C++)      {ORIGINAL_SECONDS:8.3f} s   {ORIGINAL_US:8.2f} us/sample"
          "  (published figure)")
    print(f"  numpy Monte Carlo (same run) {numpy_best:8.3f} s   {numpy_us:8.2f} us/sample")
    print(f"  ratio engine / original: {us / ORIGINAL_US:.2f}"
          f"   engine / numpy: {us / max(numpy_us, 1e-9):.1f}")
    if args.json:
        print(json.dumps({"us_per_sample": round(us, 3),
                          "original_us_per_sample": round(ORIGINAL_US, 3),
                          "numpy_us_per_sample": round(numpy_us, 4)}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
