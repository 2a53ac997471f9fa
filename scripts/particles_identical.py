#!/usr/bin/env python3
"""Check that a change left the particle filter's behaviour unchanged, bit for bit.

Runs the shell game (``anchoring run scenarios/shell_game.yaml``) once per configuration
(particles x threads x engine) in this work tree and in another revision checked out into a
temporary git worktree, and compares, configuration by configuration, a SHA-256 digest of
everything the Prolog side returned during the run: every filter step's log weights, every
query's values (the anchors' position samples, the occluders' distributions), and after each
step the values of ``pos(K):t`` and ``occluded_by(K, O):t`` in every particle. Identical
digests mean identical particles, frame after frame.

Usage (from the repository root)::

    .venv/bin/python scripts/particles_identical.py --base main~3
    .venv/bin/python scripts/particles_identical.py --base REV --particles 100 --threads 1 \\
        --engines batched

With ``--particles-only`` the digest leaves out the answers to the run's own queries (the
anchors' position samples, the occluders' distributions) and keeps the particles after each
step and the run's summary: for a change in how the loop reads the filter, whose queries then
differ while the particles must not.

The digest of one configuration alone (of this tree)::

    .venv/bin/python scripts/particles_identical.py --digest 100 1 batched

Exit status 0 when every configuration has the same digest in both trees, 1 otherwise.
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


def digest_run(tree: Path, particles: int, threads: int, engine: str,
               particles_only: bool = False) -> str:
    """Run the shell game in this process (the code of ``tree``) and return its digest (with
    ``particles_only``, of the steps and the particles after them, not of other queries)."""
    import janus_swi as janus

    digest = hashlib.sha256()
    original = janus.query_once
    dumping = [False]

    def recording(goal: str, bindings: dict | None = None, *args, **kwargs):
        result = original(goal, bindings or {}, *args, **kwargs)
        if particles_only and not dumping[0]:
            return result
        if isinstance(result, dict):
            for key in sorted(result):
                value = result[key]
                if isinstance(value, str) and value.startswith("<"):
                    continue  # a blob's printed address differs from run to run
                digest.update(f"{key}={value!r};".encode())
        return result

    janus.query_once = recording
    from bridge.filter import Filter  # the bridge of `tree` (its python/ is first on the path)

    step = Filter.step

    def step_and_dump(self, *args, **kwargs):
        result = step(self, *args, **kwargs)
        dumping[0] = True
        self.values("L", "findall(K-V, pos(K):t ~= V, L)")
        self.values("L", "findall(K-O, occluded_by(K, O):t ~= true, L)")
        dumping[0] = False
        digest.update(self.log_weights.tobytes())
        return result

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
    digest.update(summary.split('"ms_per_frame"')[0].encode())
    return digest.hexdigest()


def tree_digest(tree: Path, particles: int, threads: int, engine: str,
                particles_only: bool = False) -> tuple[str, float]:
    """One configuration's digest, computed by a fresh interpreter on ``tree``'s code."""
    env = dict(os.environ, PYTHONPATH=str(tree / "python"))
    started = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, str(Path(__file__).resolve()), "--tree", str(tree), "--digest",
         str(particles), str(threads), engine, *(["--particles-only"] if particles_only else [])],
        cwd=tree, env=env, capture_output=True, text=True, check=False)
    seconds = time.perf_counter() - started
    lines = [line for line in proc.stdout.splitlines() if line.startswith(DIGEST_PREFIX)]
    if proc.returncode != 0 or not lines:
        raise SystemExit(f"{tree}: {particles} particles, {threads} threads, {engine}: "
                         f"failed ({proc.returncode}):\n{proc.stderr[-3000:]}")
    return lines[-1][len(DIGEST_PREFIX):], seconds


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
                        help="print the digest of one configuration of this tree and stop")
    parser.add_argument("--particles-only", action="store_true",
                        help="digest the steps and the particles after each, not the answers to "
                             "the run's other queries")
    args = parser.parse_args()
    if args.digest:
        particles, threads, engine = args.digest
        print(DIGEST_PREFIX + digest_run(args.tree, int(particles), int(threads), engine,
                                         args.particles_only), flush=True)
        return 0
    with tempfile.TemporaryDirectory(prefix="particles-base-") as tmp:
        base = Path(tmp) / "tree"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(base),
                        args.base], check=True, capture_output=True)
        try:
            build_columns(base)
            failures = 0
            print(f"{'particles':>9} {'threads':>7} {'engine':<13} {'base s':>7} {'this s':>7}"
                  f"  digest")
            for particles, threads, engine in itertools.product(
                    args.particles, args.threads, args.engines):
                before, t_before = tree_digest(base, particles, threads, engine,
                                               args.particles_only)
                after, t_after = tree_digest(ROOT, particles, threads, engine,
                                             args.particles_only)
                same = before == after
                failures += not same
                print(f"{particles:>9} {threads:>7} {engine:<13} {t_before:7.1f} {t_after:7.1f}"
                      f"  {after[:16]} {'identical' if same else 'DIFFERS from ' + before[:16]}",
                      flush=True)
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(base)],
                           check=False, capture_output=True)
    print("identical" if not failures else f"{failures} configuration(s) differ")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
