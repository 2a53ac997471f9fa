"""Filters and programs used from several Python threads, and reloads while a filter is live.

A filter's particles live in a Prolog engine of their own that any thread may run, and its
program in a module of its own that no reload replaces (prolog/ddc/filter/ddc_filter.pl, "Threads
and reloads"). Every run here is compared, particle by particle, with the same filter (same
program, seed, engine and Prolog threads) created and stepped on the main thread alone.
"""

from __future__ import annotations

import shutil
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

import bridge
from bridge import DDCError, Filter, FilterError, terms

EXAMPLES = Path(__file__).resolve().parents[1] / "prolog" / "examples" / "filter"
PIT_WORLD = EXAMPLES / "pit_world.pl"
PIT_FRAMES = [("null", "false"), ("up", "true"), ("down", "false"), ("right", "true")]

#: (engine, Prolog threads per step): the batched engine, the per-particle one stepping in
#: one thread and in two (its worker threads are shared by every filter of the process)
SETUPS = pytest.mark.parametrize(
    ("engine", "threads"), [("batched", 1), ("per_particle", 1), ("per_particle", 2)]
)

Run = tuple[float, list[Any], list[Any]]


def pit_step(f: Filter, move: str, breeze: str) -> None:
    f.step([terms.observation("breeze", terms.Text(breeze))], actions=[terms.action(move)])


def particles_of(f: Filter) -> Run:
    """What identifies the particles: the log-likelihood and two variables in every one."""
    return (f.log_likelihood, f.values("P", "position ~= P"),
            f.values("M", "maze(1,1) ~= M"))


def pit_run(engine: str, threads: int, seed: int, program: Path = PIT_WORLD) -> Run:
    with Filter(program, particles=200, seed=seed, engine=engine, threads=threads) as f:
        for move, breeze in PIT_FRAMES:
            pit_step(f, move, breeze)
        return particles_of(f)


def in_threads(*jobs: Callable[[], Any]) -> list[Any]:
    """Run each job in a thread of its own, started together; their results (a job's
    exception is raised here, after every thread ended)."""
    start = threading.Barrier(len(jobs))
    results: list[Any] = [None] * len(jobs)
    errors: list[BaseException] = []

    def worker(i: int, job: Callable[[], Any]) -> None:
        start.wait()
        try:
            results[i] = job()
        except BaseException as exc:  # reported below, in the test's thread
            errors.append(exc)

    workers = [threading.Thread(target=worker, args=(i, job)) for i, job in enumerate(jobs)]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    if errors:
        raise errors[0]
    return results


@SETUPS
def test_a_filter_made_and_stepped_in_a_worker_thread_gives_the_main_threads_particles(
        engine: str, threads: int) -> None:
    reference = pit_run(engine, threads, seed=5)
    [off_main] = in_threads(lambda: pit_run(engine, threads, seed=5))
    assert off_main == reference
    assert len(reference[1]) == 200 and reference[0] < 0.0


@SETUPS
def test_two_filters_in_two_threads_at_once(engine: str, threads: int) -> None:
    references = [pit_run(engine, threads, seed) for seed in (1, 2)]
    together = in_threads(lambda: pit_run(engine, threads, 1),
                          lambda: pit_run(engine, threads, 2))
    assert together == references
    assert references[0] != references[1]


def test_a_handle_is_valid_in_every_thread() -> None:
    # made on the main thread, stepped in one worker, queried in another, closed in a third
    reference = pit_run("per_particle", 2, seed=3)
    f = Filter(PIT_WORLD, particles=200, seed=3, engine="per_particle", threads=2)
    in_threads(lambda: [pit_step(f, *frame) for frame in PIT_FRAMES[:2]])
    in_threads(lambda: [pit_step(f, *frame) for frame in PIT_FRAMES[2:]])
    [queried] = in_threads(lambda: particles_of(f))
    assert queried == reference and f.time == 4
    in_threads(f.close)
    with pytest.raises(FilterError, match="closed"):
        f.step()


def test_one_filter_stepped_from_two_threads_takes_one_step_at_a_time() -> None:
    # eight steps, four from each thread: whatever their order, each is whole (the same
    # frame every time, so any order gives the same particles)
    def steps(f: Filter) -> None:
        for _ in range(4):
            pit_step(f, "null", "false")

    with Filter(PIT_WORLD, particles=200, seed=4, engine="per_particle") as alone:
        for _ in range(8):
            pit_step(alone, "null", "false")
        reference = particles_of(alone)
    with Filter(PIT_WORLD, particles=200, seed=4, engine="per_particle") as shared:
        in_threads(lambda: steps(shared), lambda: steps(shared))
        assert shared.frames == 8 and shared.time == 8
        assert particles_of(shared) == reference


@SETUPS
def test_a_reload_of_the_same_file_leaves_a_live_filter_as_it_was(
        engine: str, threads: int, tmp_path: Path) -> None:
    program = tmp_path / "pit_world.pl"
    shutil.copy(PIT_WORLD, program)
    reference = pit_run(engine, threads, seed=6, program=program)
    with Filter(program, particles=200, seed=6, engine=engine, threads=threads) as f:
        for move, breeze in PIT_FRAMES:
            Filter(program, particles=10, seed=1, engine=engine).close()  # another filter,
            bridge.load(program)           # then the file's static program, loaded again
            pit_step(f, move, breeze)
        assert particles_of(f) == reference


def test_a_changed_file_reaches_new_filters_and_queries_not_live_ones(tmp_path: Path) -> None:
    program = tmp_path / "x.pl"
    program.write_text("x:0 ~ val(1).\nx:t+1 ~ val(X) := x:t ~= X.\n")
    with Filter(program, particles=20, seed=1) as old:
        # the new text changes both the start and the transition
        program.write_text("x:0 ~ val(2).\nx:t+1 ~ val(Y) := x:t ~= X, Y is X + 10.\n")
        assert bridge.load(program).query("x:0 ~= 2", samples=10, seed=1).probability == 1.0
        with Filter(program, particles=20, seed=1) as new:
            old.step()
            new.step()
            assert old.values("X", "x ~= X") == [1] * 20
            assert new.values("X", "x ~= X") == [12] * 20


@pytest.mark.parametrize("engine", ["batched", "per_particle"])
def test_a_reloader_in_another_thread_does_not_break_a_live_filter(
        engine: str, tmp_path: Path) -> None:
    program = tmp_path / "pit_world.pl"
    shutil.copy(PIT_WORLD, program)
    rounds = 30
    # the four frames, then standing still where the breeze is felt
    frames = PIT_FRAMES + [("null", "true")] * (rounds - len(PIT_FRAMES))
    with Filter(program, particles=100, seed=8, engine=engine) as alone:
        for frame in frames:
            pit_step(alone, *frame)
        reference = particles_of(alone)

    reloading, done = threading.Event(), threading.Event()
    reloads = 0

    def reloader() -> None:
        nonlocal reloads
        while not done.is_set():
            bridge.load(program)
            reloads += 1
            reloading.set()

    def stepper() -> Run:
        reloading.wait()
        try:
            with Filter(program, particles=100, seed=8, engine=engine) as f:
                for frame in frames:
                    pit_step(f, *frame)     # each of the 30 rounds steps during reloads
                return particles_of(f)
        finally:
            done.set()

    _, stepped = in_threads(reloader, stepper)
    assert stepped == reference
    assert reloads >= 1


def test_errors_in_a_worker_thread_are_the_bridges_own(tmp_path: Path) -> None:
    broken = tmp_path / "broken.pl"
    broken.write_text("x:0 ~ val(1).\nx:t+1 ~ val(X) := x:t ~= X, (.\n")

    def bad_inputs() -> list[str]:
        caught = []
        with Filter(PIT_WORLD, particles=10, seed=1) as f:
            for bad in (lambda: f.step(["breeze ~= "]),               # does not parse
                        lambda: f.step(["observation(smell) ~= yes"]),  # no clause for it
                        lambda: f.probability("maze(0,0 ~= free")):
                with pytest.raises(FilterError) as error:
                    bad()
                caught.append(str(error.value))
            assert f.time == 0                 # nothing held was lost
            pit_step(f, "up", "true")
        with pytest.raises(FilterError, match=r"broken\.pl:2"):
            Filter(broken, particles=10, seed=1)
        with pytest.raises(DDCError, match=r"broken\.pl:2"):
            bridge.load(broken)
        with pytest.raises(DDCError, match="syntax"):
            bridge.load(PIT_WORLD).query("maze(0,0) ~=", samples=10)
        return caught

    [messages] = in_threads(bad_inputs)
    assert "observation 1" in messages[0] and "observation(smell)" in messages[1]
