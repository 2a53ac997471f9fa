"""Many independent jobs (python/probanchor/jobs) on local processes and on Ray: every outcome comes
back, a job that raised is reported with its cause, a job whose worker died is tried again, and a
small evaluation gives the same table whichever back end ran it."""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import pytest

from probanchor.jobs import ClusterError, Job, JobsFailed, parse_cluster, raise_failures, run_jobs
from probanchor.perception.classifier import model_digest


def square(x: int) -> int:
    """x squared; 3 raises (a job that fails for good)."""
    if x == 3:
        raise ValueError("three is not welcome")
    return x * x


def die_once(marker: str, x: int) -> int:
    """Kills its worker process the first time (no ``marker`` file yet), then returns x."""
    if not os.path.exists(marker):
        Path(marker).touch()
        os._exit(9)
    return x


def always_die() -> None:
    """Kills its worker process, every time."""
    os._exit(9)


def thread_settings(_: int) -> tuple[str | None, str | None]:
    """The worker's OpenMP and OpenBLAS thread counts, as its environment gives them."""
    return os.environ.get("OMP_NUM_THREADS"), os.environ.get("OPENBLAS_NUM_THREADS")


def outcomes_of(jobs: list[Job], cluster: str | None, workers: int) -> dict[str, tuple]:
    return {o.job.name: (o.value, o.error)
            for o in run_jobs(jobs, parse_cluster(cluster, workers))}


def test_cluster_names() -> None:
    assert parse_cluster(None, 2).backend == "local" and parse_cluster("local").workers == 1
    assert parse_cluster("ray", 2).address is None
    assert parse_cluster("auto").address == "auto"
    assert parse_cluster("ray://10.0.0.5:10001").address == "ray://10.0.0.5:10001"
    for bad in ("spark", "ray://nohost", "ray://:10001", "ray://h:port"):
        with pytest.raises(ClusterError, match="is not local, ray, auto or ray://HOST:PORT"):
            parse_cluster(bad)
    for workers in (0, -1, 1.5, True):
        with pytest.raises(ClusterError, match="--jobs"):
            parse_cluster("local", workers)  # type: ignore[arg-type]


@pytest.mark.parametrize("workers", [1, 2])
def test_local_jobs_all_come_back_and_a_raising_one_is_reported(workers: int) -> None:
    jobs = [Job(f"square {i}", square, (i,)) for i in range(6)]
    got = outcomes_of(jobs, "local", workers)
    assert got == {f"square {i}": ((i * i, None) if i != 3 else
                                   (None, "ValueError: three is not welcome")) for i in range(6)}


def test_local_workers_run_their_numerical_libraries_on_one_thread(monkeypatch) -> None:
    monkeypatch.delenv("OMP_NUM_THREADS", raising=False)
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "3")  # a setting of the user's is kept
    got = outcomes_of([Job(f"threads {i}", thread_settings, (i,)) for i in range(2)], None, 2)
    assert set(got.values()) == {(("1", "3"), None)}
    assert "OMP_NUM_THREADS" not in os.environ  # this process's environment is as it was


def test_a_local_worker_that_dies_is_replaced_and_its_job_tried_again(tmp_path: Path) -> None:
    jobs = [Job("dies once", die_once, (str(tmp_path / "died"), 7))]
    jobs += [Job(f"square {i}", square, (i,)) for i in (1, 2, 4, 5)]
    outcomes = list(run_jobs(jobs, parse_cluster("local", 2)))
    values = {o.job.name: o.value for o in outcomes}
    assert values == {"dies once": 7, "square 1": 1, "square 2": 4, "square 4": 16,
                      "square 5": 25}
    assert {o.job.name: o.tries for o in outcomes}["dies once"] == 2
    raise_failures(outcomes)  # none failed: nothing raised


def test_a_worker_that_keeps_dying_fails_its_job_after_the_retries() -> None:
    outcomes = list(run_jobs([Job("always dies", always_die), Job("square 2", square, (2,))],
                             parse_cluster("local", 2), retries=1))
    by_name = {o.job.name: o for o in outcomes}
    died = "its worker process died 2 times (killed, or crashed)"
    assert by_name["always dies"].error == died
    # (a job under way beside it when the pool broke counts a try too)
    assert (by_name["square 2"].value, by_name["square 2"].error) in ((4, None), (None, died))
    with pytest.raises(JobsFailed,
                       match=r"of 2 jobs failed: (.*; )?always dies: its worker process"):
        raise_failures(outcomes)


def test_without_ray_the_ray_back_end_says_how_to_install_it(monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "ray", None)  # import ray raises ImportError
    with pytest.raises(ClusterError, match=r"pip install '\.\[cluster\]'"):
        list(run_jobs([Job("square 2", square, (2,))], parse_cluster("ray", 1)))


def test_an_evaluation_with_a_failed_unit_keeps_the_finished_ones(tmp_path, monkeypatch) -> None:
    import probanchor.experiments.sweep as experiment

    ran: list[int] = []

    def unit(label, scenario, seed, methods, particles, cache, threads, engine):
        ran.append(seed)
        if seed == 1 and len(ran) < 3:
            raise RuntimeError("the simulator fell over")
        return [{"scenario": scenario.stem, "group": label, "seed": seed, "method": m,
                 "particles": particles, "threads": threads, "engine": engine,
                 "summary": {"objects": [{"id": "ball_1", "symbols": ["ball-1"],
                                          "identity_kept": True}],
                             "id_switches": 0, "idf1": 1.0, "hota": 1.0}} for m in methods]

    monkeypatch.setattr(experiment, "run_unit", unit)
    options = experiment.ExperimentOptions(out=tmp_path, seeds=3, games=0, particles=50,
                                           methods=("reasoning",), scenarios=("transitive",))
    with pytest.raises(JobsFailed, match=r"1 of 3 jobs failed: transitive seed 1: RuntimeError: "
                                         r"the simulator fell over \(the 2 finished are in"):
        experiment.run_experiment(options)
    assert not (tmp_path / "results.md").exists()
    lines = experiment.read_summaries(tmp_path / "summaries.jsonl")
    assert sorted(line["seed"] for line in lines) == [0, 2]
    table = experiment.run_experiment(options)   # again: only the failed unit runs
    assert ran == [0, 1, 2, 1]
    assert "| transitive | reasoning | 3 | 3/3 (100 %) |" in table


def test_ray_jobs_come_back_raising_ones_reported_dead_workers_retried(
        ray_two_workers, tmp_path: Path) -> None:
    jobs = [Job(f"square {i}", square, (i,)) for i in range(5)]
    jobs.append(Job("dies once", die_once, (str(tmp_path / "died"), 7)))
    got = outcomes_of(jobs, "ray", 2)
    assert got == {**{f"square {i}": ((i * i, None) if i != 3 else
                                      (None, "ValueError: three is not welcome"))
                      for i in range(5)}, "dies once": (7, None)}
    assert ray_two_workers.is_initialized()  # a Ray this process started is left as it was


def test_a_small_evaluation_on_ray_gives_the_local_table(ray_two_workers,
                                                         tmp_path: Path) -> None:
    from probanchor.experiments.sweep import ExperimentOptions, read_summaries, run_experiment

    tables, summaries = {}, {}
    for cluster in ("local", "ray"):
        out = tmp_path / cluster
        tables[cluster] = run_experiment(ExperimentOptions(
            out=out, seeds=2, games=0, particles=30, methods=("reasoning", "no-reasoning"),
            scenarios=("can_under_box", "transitive"), jobs=2, cluster=cluster, threads=1))
        lines = read_summaries(out / "summaries.jsonl")
        for line in lines:
            del line["summary"]["ms_per_frame"]  # (the one thing that may differ)
        summaries[cluster] = sorted(json.dumps(line, sort_keys=True) for line in lines)
    assert tables["ray"] == tables["local"]
    assert "| can_under_box | reasoning | 2 |" in tables["ray"]
    assert "| transitive | no-reasoning | 2 |" in tables["ray"]
    assert summaries["ray"] == summaries["local"] and len(summaries["ray"]) == 8
    for seed in (0, 1):   # the same percept streams
        name = f"percepts/transitive_seed{seed}.{model_digest()}.jsonl"
        assert (tmp_path / "ray" / name).read_bytes() == (tmp_path / "local" / name).read_bytes()
