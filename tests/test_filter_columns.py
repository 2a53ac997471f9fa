"""The batched filter's columns in C (prolog/ddc/batch/c/ddc_columns.c) against its columns in
Prolog.

The compiled library draws from a random stream of its own, so the two give other particles
from the same seed: they are compared in distribution, on the bench's model of occlusion
(bench/filter_numpy_reference.py), each in a process of its own (``DDC_COLUMNS=prolog`` keeps the
library unloaded), over several seeds each: a bootstrap filter's particles are correlated by
resampling, so the spread of an estimate is measured across runs, not read off one run's weights.
The engine's plunit files run with the columns in Prolog too, so that the fallback stays tested.
"""

from __future__ import annotations

import json
import math
import os
import statistics
import subprocess
import sys

import pytest

from plunit_runner import ROOT, run_plunit, swipl_executable

OBJECTS = 6
STEPS = 8
PARTICLES = 1000
SEEDS = 8

_WORKER = """
import json, sys, tempfile
from pathlib import Path
sys.path[:0] = [sys.argv[1] + "/bench", sys.argv[1] + "/python"]
import numpy as np
import filter_numpy_reference as model
from bridge import Filter
from bridge import prolog
objects, steps, particles, first, seeds = (int(a) for a in sys.argv[2:7])
names = model.object_names(objects)
out = {"backend": None, "runs": []}
with tempfile.TemporaryDirectory() as tmp:
    program = Path(tmp) / "occlusion.pl"
    program.write_text(model.ddc_program(objects))
    for seed in range(first, first + seeds):
        run = []
        with Filter(program, particles=particles, seed=seed, threads=1, engine="batched") as f:
            out["backend"] = prolog.query_once("ddc_batch_col:col_backend(B)")["B"]
            for frame in model.scenario(objects, steps, seed=1):
                f.step(frame.terms(names))
                row = {"log_likelihood": f.log_likelihood}
                for name in names:
                    values, weights = f.samples(f"pos({name}):t")
                    row[f"pos({name})"] = (weights / weights.sum() @ values).tolist()
                    row[f"hidden_under({name})"] = {
                        str(v): p for p, v in f.distribution(f"hidden_under({name}):t")}
                run.append(row)
        out["runs"].append(run)
print(json.dumps(out))
"""


def run_model(columns: str | None, first_seed: int) -> dict:
    """SEEDS runs of the model (seeds first_seed, first_seed + 1, ...) in one process."""
    env = dict(os.environ)
    env.pop("DDC_COLUMNS", None)
    if columns:
        env["DDC_COLUMNS"] = columns
    result = subprocess.run(
        [sys.executable, "-c", _WORKER, str(ROOT), str(OBJECTS), str(STEPS), str(PARTICLES),
         str(first_seed), str(SEEDS)], env=env, capture_output=True, text=True, timeout=900,
        cwd=ROOT)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout.strip().splitlines()[-1])


def col_backend() -> str:
    out = subprocess.run(
        [swipl_executable(), "-q", "-g",
         "use_module('prolog/ddc/batch/ddc_batch_col'), col_backend(B), write(B)", "-t", "halt"],
        cwd=ROOT, capture_output=True, text=True, timeout=60,
        env={k: v for k, v in os.environ.items() if k != "DDC_COLUMNS"})
    return out.stdout.strip()


def test_the_column_library_is_built_and_loaded() -> None:
    library = ROOT / "prolog" / "ddc" / "batch" / "c" / "ddc_columns.so"
    assert library.exists(), "run scripts/setup.sh"
    assert col_backend() == "foreign"


@pytest.mark.parametrize("name", ["batch/test_ddc_batch.pl", "batch/test_ddc_batch_col.pl",
                                  "filter/test_ddc_rename.pl"])
def test_plunit_with_the_columns_in_prolog(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("DDC_COLUMNS", "prolog")
    result = run_plunit(ROOT / "tests" / "prolog" / name)
    assert result.returncode == 0, (
        f"{name} with DDC_COLUMNS=prolog:\n{result.stdout}\n{result.stderr}")


@pytest.fixture(scope="module")
def both() -> tuple[dict, dict]:
    return run_model(None, first_seed=100), run_model("prolog", first_seed=200)


def agree(a: list[float], b: list[float], floor: float) -> tuple[bool, float]:
    """The means of a and b (one figure per run) agree within five standard errors of their
    difference (each side's spread across its runs); floor: the least standard error."""
    se = math.sqrt(statistics.variance(a) / len(a) + statistics.variance(b) / len(b))
    se = max(se, floor)
    return abs(statistics.fmean(a) - statistics.fmean(b)) <= 5 * se, se


def test_the_two_runs_used_the_two_column_representations(both: tuple[dict, dict]) -> None:
    compiled, terms = both
    assert compiled["backend"] == "foreign"
    assert terms["backend"] == "prolog"


def test_the_same_marginals_of_positions_within_sampling_error(
        both: tuple[dict, dict]) -> None:
    compiled, terms = both
    for step in range(STEPS):
        for key in compiled["runs"][0][step]:
            if not key.startswith("pos("):
                continue
            for axis in range(3):
                a = [run[step][key][axis] for run in compiled["runs"]]
                b = [run[step][key][axis] for run in terms["runs"]]
                ok, se = agree(a, b, floor=1e-6)
                assert ok, (step + 1, key, axis, a, b, se)


def test_the_same_marginals_of_occluders_within_sampling_error(
        both: tuple[dict, dict]) -> None:
    compiled, terms = both
    compared = 0
    for step in range(STEPS):
        for key in compiled["runs"][0][step]:
            if not key.startswith("hidden_under("):
                continue
            values = {v for side in both for run in side["runs"] for v in run[step][key]}
            for value in values:
                a = [run[step][key].get(value, 0.0) for run in compiled["runs"]]
                b = [run[step][key].get(value, 0.0) for run in terms["runs"]]
                # (the least standard error: one particle's weight over the runs)
                ok, se = agree(a, b, floor=1.0 / (PARTICLES * math.sqrt(SEEDS)))
                assert ok, (step + 1, key, value, a, b, se)
                compared += 1 if 0.05 < statistics.fmean(a) < 0.95 else 0
    assert compared > 0, "no occlusion to compare: the scenario should hide objects"


def test_the_same_log_likelihood_within_monte_carlo_error(both: tuple[dict, dict]) -> None:
    compiled, terms = both
    a = [run[-1]["log_likelihood"] for run in compiled["runs"]]
    b = [run[-1]["log_likelihood"] for run in terms["runs"]]
    ok, se = agree(a, b, floor=1e-3)
    assert ok, (a, b, se)
