"""The local back end: spawned worker processes (or the calling process for one worker)."""

from __future__ import annotations

import ctypes
import multiprocessing
import os
import signal
import sys
import threading
import time
from collections import deque
from collections.abc import Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager

from probanchor.jobs.core import Job, Outcome, Tally, cause

#: The numerical libraries' thread counts, read by each when a worker loads it.
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


@contextmanager
def one_thread_per_worker() -> Iterator[None]:
    """While the pool starts workers: their BLAS and OpenMP use one thread (unless set already).

    Each worker runs one job at a time on one core, as a Ray task does (Ray sets
    ``OMP_NUM_THREADS=1`` for its workers). Otherwise every worker's BLAS starts a thread per
    core and ``workers`` x cores threads fight over the cores: a 4-fold cross-validation of
    FinancialData.pl took twice as long on 2 workers as in one process. A spawned worker reads
    the variables when it starts, and the pool starts workers as jobs are submitted, so they
    are set for the whole run (in this process's environment only; its libraries are loaded).
    """
    saved = {name: os.environ.get(name) for name in THREAD_VARIABLES}
    for name, value in saved.items():
        if value is None:
            os.environ[name] = "1"
    try:
        yield
    finally:
        for name, value in saved.items():
            if value is None:
                os.environ.pop(name, None)


#: prctl(2)'s option that sends a signal to this process when its parent ends (Linux).
_PR_SET_PDEATHSIG = 1


def die_with_parent(parent: int) -> None:
    """A worker's initializer: the worker ends when the process that started it ends.

    A pool's workers wait on a pipe for their next job, and each holds that pipe's writing end
    too: a parent killed (SIGKILL, the out-of-memory killer) would leave them, re-parented to
    init, waiting for good. On Linux the kernel sends the worker SIGKILL when its parent ends
    (``prctl(PR_SET_PDEATHSIG)``; the parent's thread that started the worker, which is the
    thread that submits jobs, must live as long as the pool: :func:`run_local` keeps both in
    the caller's thread); elsewhere a thread of the worker looks for its parent every second.

    Parameters
    ----------
    parent : int
        The process id of the pool's process.
    """
    if sys.platform.startswith("linux"):
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        except (OSError, AttributeError):  # no prctl: the watching thread below instead
            threading.Thread(target=_watch_parent, args=(parent,), daemon=True).start()
    else:
        threading.Thread(target=_watch_parent, args=(parent,), daemon=True).start()
    if os.getppid() != parent:  # the parent ended before the signal was asked for
        os._exit(1)


def _watch_parent(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(1.0)
    os._exit(1)


def run_local(jobs: Sequence[Job], workers: int, retries: int,
              tally: Tally) -> Iterator[Outcome]:
    """Run ``jobs`` in ``workers`` spawned processes; yield each outcome as it finishes.

    Parameters
    ----------
    jobs : sequence of Job
        The jobs.
    workers : int
        Worker processes, one BLAS/OpenMP thread each (:func:`one_thread_per_worker`); with 1
        (or one job) the jobs run one after the other in this process.
    retries : int
        Tries after the first for a job under way when a worker died: the pool is started
        again and those jobs are queued again (which of them killed the worker is not known,
        so each counts a try).
    tally : Tally
        The progress bar.

    Returns
    -------
    iterator of Outcome
    """
    if workers <= 1 or len(jobs) <= 1:
        for job in jobs:
            tally.running(1)
            try:
                outcome = Outcome(job, job.function(*job.args))
            except Exception as error:  # reported, and the next job runs
                outcome = Outcome(job, error=cause(error))
            tally.finished(outcome)
            yield outcome
        return
    with one_thread_per_worker():
        yield from _run_pool(jobs, workers, retries, tally)


def _run_pool(jobs: Sequence[Job], workers: int, retries: int,
              tally: Tally) -> Iterator[Outcome]:
    context = multiprocessing.get_context("spawn")
    queue = deque(range(len(jobs)))
    tries = [0] * len(jobs)
    while queue:
        pool = ProcessPoolExecutor(max_workers=workers, mp_context=context,
                                   initializer=die_with_parent, initargs=(os.getpid(),))
        under_way: dict[Future, int] = {}
        broken = False
        try:
            while queue or under_way:
                # at most `workers` under way, so that what is under way is what runs
                while queue and len(under_way) < workers and not broken:
                    i = queue.popleft()
                    tries[i] += 1
                    under_way[pool.submit(jobs[i].function, *jobs[i].args)] = i
                if not under_way:
                    break
                tally.running(len(under_way))
                done, _ = wait(under_way, return_when=FIRST_COMPLETED)
                for future in done:
                    i = under_way.pop(future)
                    try:
                        outcome = Outcome(jobs[i], future.result(), tries=tries[i])
                    except BrokenProcessPool:
                        broken = True
                        if tries[i] <= retries:
                            queue.appendleft(i)
                            continue
                        outcome = Outcome(jobs[i], error=f"its worker process died {tries[i]} "
                                          "times (killed, or crashed)", tries=tries[i])
                    except Exception as error:
                        outcome = Outcome(jobs[i], error=cause(error), tries=tries[i])
                    tally.finished(outcome)
                    yield outcome
        finally:
            pool.shutdown(wait=True, cancel_futures=True)
