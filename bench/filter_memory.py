"""The filter's memory over a long run: resident memory every K frames, and its growth.

    .venv/bin/python bench/filter_memory.py                       # 10,000 frames, 10,000 particles
    .venv/bin/python bench/filter_memory.py --frames 2000 --particles 1000 --every 200

Steps ``bridge.Filter`` on the bench's model of occlusion (bench/filter_numpy_reference.py, M
objects, boxes drifting and small objects hidden under them) for ``--frames`` frames, the
scenario repeated as often as needed (its positions carried on), and prints the process's
resident memory (VmRSS) every ``--every`` frames, the atoms SWI-Prolog holds (the batched
engine's columns are blobs, freed by the atom garbage collector) and, at the end, the growth
from the end of the first quarter on (the least-squares slope of the samples), in MB per 1,000
frames. A flat run grows by
about nothing once the first frames have sized the stacks and tables; a leak grows with the
frames. Not a test: a long run, for a person to read (the final line says flat or growing,
against ``--tolerance`` MB per 1,000 frames).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "python"))

import filter_numpy_reference as model  # noqa: E402
from bridge import DEFAULT_THREADS, Filter  # noqa: E402
from bridge import prolog as bridge_prolog  # noqa: E402


def slope(points: list[tuple[int, float]]) -> float:
    """The least-squares slope of (frame, MB) points, MB per frame."""
    n = len(points)
    mx = sum(k for k, _ in points) / n
    my = sum(m for _, m in points) / n
    sxx = sum((k - mx) ** 2 for k, _ in points)
    return sum((k - mx) * (m - my) for k, m in points) / sxx if sxx else 0.0


def rss_mb() -> float:
    """The process's resident memory in MB (Linux: /proc/self/status)."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def prolog_atoms() -> int:
    return int(bridge_prolog.query_once("statistics(atoms, N)")["N"])


def frames_forever(objects: int, block: int, seed: int):
    """The scenario's frames, again and again (each block a new draw of the noise)."""
    k = 0
    while True:
        yield from model.scenario(objects, block, seed=seed + k)
        k += 1


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--frames", type=int, default=10_000)
    parser.add_argument("--particles", type=int, default=10_000)
    parser.add_argument("--objects", type=int, default=10)
    parser.add_argument("--every", type=int, default=500, help="frames between samples")
    parser.add_argument("--threads", type=int, default=DEFAULT_THREADS)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--tolerance", type=float, default=1.0,
                        help="MB per 1,000 frames below which the run is called flat")
    args = parser.parse_args(argv)
    names = model.object_names(args.objects)
    samples: list[tuple[int, float]] = []
    print(f"N={args.particles} M={args.objects}, {args.frames} frames, {args.threads} thread(s)")
    print(f"{'frame':>7} {'RSS MB':>9} {'atoms':>9} {'ms/frame':>9}", flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        program = Path(tmp) / "occlusion.pl"
        program.write_text(model.ddc_program(args.objects))
        with Filter(program, particles=args.particles, seed=args.seed,
                    threads=args.threads) as f:
            started = time.perf_counter()
            for k, frame in enumerate(frames_forever(args.objects, 50, args.seed), 1):
                f.step(frame.terms(names))
                if k % args.every == 0 or k == args.frames:
                    ms = 1000 * (time.perf_counter() - started) / args.every
                    samples.append((k, rss_mb()))
                    print(f"{k:>7} {samples[-1][1]:>9.1f} {prolog_atoms():>9} {ms:>9.1f}",
                          flush=True)
                    started = time.perf_counter()
                if k == args.frames:
                    break
    late = [(k, m) for k, m in samples if k >= args.frames // 4] or samples
    growth = 1000 * slope(late) if len(late) > 1 else 0.0
    verdict = "flat" if growth <= args.tolerance else "growing"
    print(f"RSS {late[0][1]:.1f} MB at frame {late[0][0]} -> {late[-1][1]:.1f} MB at frame "
          f"{late[-1][0]} (max {max(m for _, m in samples):.1f}): least-squares growth "
          f"{growth:+.2f} MB per 1,000 frames from frame {late[0][0]} on ({verdict}, "
          f"tolerance {args.tolerance} MB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
