#!/usr/bin/env python3
"""Check that a change left the particle filter's behaviour unchanged, bit for bit.

Runs the shell game (``anchoring run scenarios/shell_game.yaml``) once per configuration
(particles x threads x engine) in this work tree and in another revision checked out into a
temporary git worktree, and compares, configuration by configuration, two SHA-256 digests of
what the filter (``bridge.Filter``) gave the run, taken at its public methods so that they do
not depend on how the bridge calls Prolog:

- the particles: every query's values (``values``, ``holds``, the values of ``samples``: the
  anchors' position samples, the occluders' distributions), after each step the values of
  ``pos(K):t`` and ``occluded_by(K, O):t`` in every particle, each step's time, frame and
  whether it resampled or was a zero-weight step;
- the weights: each step's normalised log weights, ESS and log-likelihood increment, the weights
  ``samples`` returns, the run's summary (but its timings).

Identical digests mean identical particles and weights, frame after frame. Where the weights'
digests differ, the largest difference of the log weights is printed.

Usage (from the repository root)::

    .venv/bin/python scripts/particles_identical.py --base main~3
    .venv/bin/python scripts/particles_identical.py --base REV --particles 100 --threads 1 \\
        --engines batched

With ``--particles-only`` the particles' digest leaves out the answers to the run's own
queries (the anchors' position samples, the occluders' indices and distributions) and keeps the
particles after each step: for a change in how the loop reads the filter, whose queries then
differ while the particles must not.

The digests of one configuration alone (of this tree)::

    .venv/bin/python scripts/particles_identical.py --digest 100 1 batched

Exit status 0 when every configuration has the same digests in both trees, 1 otherwise.
The revision's Python code and Prolog files are those of the checkout (its ``python/`` first
on the path), the virtual environment and SWI-Prolog are this tree's.
"""

from __future__ import annotations

import argparse
import hashlib
import itertools
import os
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = "scenarios/shell_game.yaml"
DIGEST_PREFIX = "particles-digest "


def _entry_point(tree: Path) -> tuple[str, str]:
    """The ``anchoring`` command's module and function in ``tree``'s pyproject.toml."""
    with (tree / "pyproject.toml").open("rb") as handle:
        scripts = tomllib.load(handle)["project"]["scripts"]
    module, _, function = scripts["anchoring"].partition(":")
    return module, function


def _bytes(value) -> bytes:
    """A query's answer as bytes (numeric arrays by their bytes, anything else by repr)."""
    import numpy as np

    if isinstance(value, np.ndarray) and value.dtype != object:
        return np.ascontiguousarray(value).tobytes()
    if isinstance(value, np.ndarray):
        value = value.tolist()
    return repr(value).encode()


def digest_run(tree: Path, particles: int, threads: int, engine: str,
               weights_file: Path | None = None,
               particles_only: bool = False) -> tuple[str, str]:
    """Run the shell game in this process (the code of ``tree``) and return its two digests:
    of the particles (every query's values and, after each step, every particle's ``pos`` and
    ``occluded_by``; each step's time, frame, resampled and zero-weight flags) and of the
    weights (each step's normalised log weights, ESS and log-likelihood increment, the weights
    that queries return, the run's summary). With ``weights_file``, each step's log weights
    are saved there (numpy ``.npy``) for a comparison by value. With ``particles_only``, the
    queries the run makes itself are not digested (those after each step are)."""
    import numpy as np

    particles_digest, weights_digest = hashlib.sha256(), hashlib.sha256()
    log_weights: list[np.ndarray] = []
    from bridge.filter import Filter  # the bridge of `tree` (its python/ is first on the path)

    step = Filter.step
    dumping = [False]  # (in step_and_dump's own queries)

    def recorded(method, tag: bytes):
        """``method`` with its answer digested (unless ``particles_only`` and the run asked)."""
        def answer(self, *args, **kwargs):
            result = method(self, *args, **kwargs)
            if dumping[0] or not particles_only:
                found, weights = result if tag == b"samples:" else (result, None)
                particles_digest.update(tag + _bytes(found))
                if weights is not None:
                    weights_digest.update(tag + _bytes(weights))
            return result
        return answer

    def step_and_dump(self, *args, **kwargs):
        result = step(self, *args, **kwargs)
        particles_digest.update(repr((result.time, result.frame, result.resampled,
                                      result.zero_weight)).encode())
        weights_digest.update(repr((result.ess, result.log_likelihood)).encode())
        dumping[0] = True
        self.values("L", "findall(K-V, pos(K):t ~= V, L)")
        self.values("L", "findall(K-O, occluded_by(K, O):t ~= true, L)")
        dumping[0] = False
        weights_digest.update(self.log_weights.tobytes())
        log_weights.append(self.log_weights)
        return result

    for name in ("values", "holds", "samples", "indices"):
        setattr(Filter, name, recorded(getattr(Filter, name), name.encode() + b":"))
    Filter.step = step_and_dump
    module, function = _entry_point(tree)
    main = getattr(__import__(module, fromlist=[function]), function)
    with tempfile.TemporaryDirectory() as out:
        argv = ["run", str(tree / SCENARIO), "--particles", str(particles), "--threads",
                str(threads), "--engine", engine, "--seed", "0", "--quiet", "--out", out,
                "--every", "1000"]
        code = main(argv)
        summary = (Path(out) / "summary.json").read_text()
    if code not in (None, 0):
        raise SystemExit(f"anchoring run exited with {code}")
    weights_digest.update(summary.split('"ms_per_frame"')[0].encode())
    if weights_file is not None:
        np.save(weights_file, np.array(log_weights))
    return particles_digest.hexdigest(), weights_digest.hexdigest()


def tree_digest(tree: Path, particles: int, threads: int, engine: str,
                weights_file: Path, particles_only: bool = False) -> tuple[str, str, float]:
    """One configuration's digests (particles, weights), computed by a fresh interpreter on
    ``tree``'s code; its log weights saved in ``weights_file``."""
    env = dict(os.environ, PYTHONPATH=str(tree / "python"))
    started = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, str(Path(__file__).resolve()), "--tree", str(tree), "--digest",
         str(particles), str(threads), engine, "--weights-file", str(weights_file),
         *(["--particles-only"] if particles_only else [])],
        cwd=tree, env=env, capture_output=True, text=True, check=False)
    seconds = time.perf_counter() - started
    lines = [line for line in proc.stdout.splitlines() if line.startswith(DIGEST_PREFIX)]
    if proc.returncode != 0 or not lines:
        raise SystemExit(f"{tree}: {particles} particles, {threads} threads, {engine}: "
                         f"failed ({proc.returncode}):\n{proc.stderr[-3000:]}")
    particles_hex, weights_hex = lines[-1][len(DIGEST_PREFIX):].split()
    return particles_hex, weights_hex, seconds


def weights_difference(before: Path, after: Path) -> str:
    """How far apart two runs' log weights are: the largest absolute difference where both are
    finite, or why they cannot be compared."""
    import numpy as np

    a, b = np.load(before), np.load(after)
    if a.shape != b.shape:
        return f"steps x particles {a.shape} vs {b.shape}"
    if not np.array_equal(np.isfinite(a), np.isfinite(b)):
        return "weight 0 in other particles"
    finite = np.isfinite(a)
    return f"max |d log w| {float(np.max(np.abs(a[finite] - b[finite]), initial=0.0)):.1e}"


def build_columns(tree: Path) -> None:
    """Compile the batched engine's column library of ``tree`` (a fresh checkout has none: it
    is built by scripts/setup.sh, wherever that revision keeps its source), so that without
    DDC_COLUMNS both trees run the same backend; a tree that cannot build it runs its columns
    in Prolog (a warning says so)."""
    swipl = (Path(sys.executable).parent / "swipl").resolve()  # the SWI-Prolog set up
    bin_dir = str(swipl.parent) if swipl.exists() else ""
    env = dict(os.environ, PATH=os.pathsep.join(p for p in (bin_dir, os.environ["PATH"]) if p))
    for source in sorted((tree / "prolog").rglob("ddc_columns.c")):
        built = subprocess.run(
            ["swipl-ld", "-shared", "-cc-options,-O2,-Wall", "-o", "ddc_columns",
             "ddc_columns.c"],
            cwd=source.parent, capture_output=True, text=True, check=False, env=env)
        if built.returncode != 0:
            print(f"warning: {source} not compiled: {built.stderr[-500:]}", file=sys.stderr)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--base", default="HEAD",
                        help="the revision to compare this work tree with (default HEAD)")
    parser.add_argument("--particles", type=int, nargs="+", default=[100, 1000])
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--engines", nargs="+", default=["batched", "per_particle"])
    parser.add_argument("--tree", type=Path, default=ROOT, help=argparse.SUPPRESS)
    parser.add_argument("--digest", nargs=3, metavar=("PARTICLES", "THREADS", "ENGINE"),
                        help="print the digests of one configuration of this tree and stop")
    parser.add_argument("--weights-file", type=Path, help=argparse.SUPPRESS)
    parser.add_argument("--particles-only", action="store_true",
                        help="digest the particles after each step, not the answers to the "
                             "run's own queries")
    args = parser.parse_args()
    if args.digest:
        particles, threads, engine = args.digest
        digests = digest_run(args.tree, int(particles), int(threads), engine,
                             args.weights_file, args.particles_only)
        print(DIGEST_PREFIX + " ".join(digests), flush=True)
        return 0
    with tempfile.TemporaryDirectory(prefix="particles-base-") as tmp:
        base = Path(tmp) / "tree"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(base),
                        args.base], check=True, capture_output=True)
        try:
            build_columns(base)
            failures = 0
            print(f"{'particles':>9} {'threads':>7} {'engine':<13} {'base s':>7} {'this s':>7}"
                  f"  particles{'':10} weights")
            for particles, threads, engine in itertools.product(
                    args.particles, args.threads, args.engines):
                files = [Path(tmp) / f"{side}-{particles}-{threads}-{engine}.npy"
                         for side in ("base", "this")]
                p_before, w_before, t_before = tree_digest(base, particles, threads, engine,
                                                           files[0], args.particles_only)
                p_after, w_after, t_after = tree_digest(ROOT, particles, threads, engine,
                                                        files[1], args.particles_only)
                same_particles, same_weights = p_before == p_after, w_before == w_after
                failures += not (same_particles and same_weights)
                weights = ("identical" if same_weights
                           else "differ: " + weights_difference(*files))
                print(f"{particles:>9} {threads:>7} {engine:<13} {t_before:7.1f} {t_after:7.1f}"
                      f"  {'identical' if same_particles else 'DIFFER':<18} {weights}",
                      flush=True)
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(base)],
                           check=False, capture_output=True)
    print("identical" if not failures else f"{failures} configuration(s) differ")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
