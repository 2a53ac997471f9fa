"""Jobs, their outcomes, the cluster to run them on, the progress bar, and the dispatch."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any, Literal

from probanchor.progress import progress

Backend = Literal["local", "ray"]
BACKENDS = ("local", "ray")
#: Tries after the first for a job whose worker died (a job that raised is not tried again).
DEFAULT_RETRIES = 2


class ClusterError(ValueError):
    """A cluster that cannot be used: an unknown ``--cluster``, Ray missing or unreachable."""


class JobsFailed(RuntimeError):
    """Some jobs failed (the others finished and were handed on); names each with its cause."""

    def __init__(self, failed: Sequence[Outcome], total: int, note: str = "") -> None:
        self.failed = list(failed)
        causes = "; ".join(f"{o.job.name}: {o.error}" for o in self.failed[:5])
        more = f"; and {len(self.failed) - 5} more" if len(self.failed) > 5 else ""
        super().__init__(f"{len(self.failed)} of {total} jobs failed: {causes}{more}"
                         + (f" ({note})" if note else ""))


@dataclass(frozen=True)
class Job:
    """One call of a module-level function (it must be importable by a worker process).

    Parameters
    ----------
    name : str
        What the job is, for the progress bar and error messages (``"transitive seed 3"``).
    function : callable
        A module-level function; its result must be picklable.
    args : tuple
        Its positional arguments (picklable).
    """

    name: str
    function: Callable[..., Any]
    args: tuple[Any, ...] = ()


@dataclass
class Outcome:
    """What became of a job: its value, or the cause of its failure, and how often it ran."""

    job: Job
    value: Any = None
    error: str | None = None
    tries: int = 1

    @property
    def ok(self) -> bool:
        """True when the job returned a value."""
        return self.error is None


@dataclass(frozen=True)
class Cluster:
    """Where jobs run.

    Parameters
    ----------
    backend : "local" or "ray"
        Local worker processes, or Ray tasks.
    address : str, optional
        For Ray: None starts a local Ray for the run; ``"auto"`` or ``"ray://HOST:PORT"`` joins
        an existing cluster.
    workers : int
        Local worker processes, or the CPUs of the local Ray started; a joined cluster runs as
        many jobs at once as it has CPUs.
    """

    backend: Backend = "local"
    address: str | None = None
    workers: int = 1

    def describe(self) -> str:
        """``local, 2 workers`` / ``ray (local), 2 workers`` / ``ray at ray://h:10001``."""
        if self.backend == "local":
            return f"local, {self.workers} worker{'s' * (self.workers != 1)}"
        if self.address is None:
            return f"ray (local), {self.workers} worker{'s' * (self.workers != 1)}"
        return f"ray at {self.address}"


def parse_cluster(text: str | None, workers: int = 1) -> Cluster:
    """The cluster that ``--cluster TEXT --jobs WORKERS`` names.

    Parameters
    ----------
    text : str or None
        None or ``"local"`` (local processes), ``"ray"`` (a local Ray started for the run),
        ``"auto"`` or ``"ray://HOST:PORT"`` (an existing Ray cluster).
    workers : int
        Worker processes (local) or the local Ray's CPUs; at least 1.

    Returns
    -------
    Cluster

    Raises
    ------
    ClusterError
        An unknown back end or a number of workers that is not a positive integer.
    """
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ClusterError(f"--jobs: {workers!r} is not a positive number of workers")
    if text is None or text == "local":
        return Cluster("local", None, workers)
    if text == "ray":
        return Cluster("ray", None, workers)
    if text == "auto" or (text.startswith("ray://") and _has_host_and_port(text[6:])):
        return Cluster("ray", text, workers)
    raise ClusterError(f"--cluster: {text!r} is not local, ray, auto or ray://HOST:PORT")


def _has_host_and_port(rest: str) -> bool:
    host, _, port = rest.rpartition(":")
    return bool(host) and port.isdigit()


class Tally:
    """One progress display over all jobs: finished of total, running and failed (a bar on a
    terminal, a few plain lines elsewhere: :func:`probanchor.progress.progress`)."""

    def __init__(self, total: int, desc: str, show: bool) -> None:
        self.failed = 0
        self._bar = progress(total, desc=desc, unit="job", show=show, dynamic_ncols=True,
                             leave=True)
        self._running = 0

    def running(self, count: int) -> None:
        """``count`` jobs are under way."""
        self._running = count
        self._bar.set_postfix_str(f"running {count}, failed {self.failed}")

    def finished(self, outcome: Outcome) -> None:
        """One job finished (or failed for good)."""
        self.failed += not outcome.ok
        self._running = max(0, self._running - 1)
        self._bar.set_postfix_str(f"running {self._running}, failed {self.failed}",
                                  refresh=False)
        self._bar.update(1)

    def close(self) -> None:
        """Leave the bar as it ends."""
        self._bar.close()


def cause(error: BaseException) -> str:
    """``ValueError: message``: the cause of a failed job, as reported."""
    text = str(error)
    return f"{type(error).__name__}: {text}" if text else type(error).__name__


def run_jobs(jobs: Sequence[Job], cluster: Cluster, *, retries: int = DEFAULT_RETRIES,
             desc: str = "jobs", bar: bool = False) -> Iterator[Outcome]:
    """Run ``jobs`` on ``cluster``; yield each outcome as it finishes (in no fixed order).

    Parameters
    ----------
    jobs : sequence of Job
        Independent jobs.
    cluster : Cluster
        Where they run (:func:`parse_cluster`).
    retries : int
        Tries after the first for a job whose worker died; a job that raised fails at once.
    desc : str
        The progress bar's label.
    bar : bool
        Draw the progress bar (on standard error).

    Returns
    -------
    iterator of Outcome
        One per job, failed ones included; stopping early stops the jobs not yet finished.

    Raises
    ------
    ClusterError
        Ray is not installed, or the cluster cannot be reached.
    """
    if cluster.backend not in BACKENDS:
        raise ClusterError(f"unknown back end {cluster.backend!r}; choose from local, ray")
    tally = Tally(len(jobs), desc, bar)
    try:
        if cluster.backend == "ray":
            from probanchor.jobs.ray_cluster import run_on_ray

            yield from run_on_ray(list(jobs), cluster, retries, tally)
        else:
            from probanchor.jobs.local import run_local

            yield from run_local(list(jobs), cluster.workers, retries, tally)
    finally:
        tally.close()


def raise_failures(outcomes: Sequence[Outcome], note: str = "") -> None:
    """Raise :class:`JobsFailed` naming the failed ``outcomes`` (nothing when all are ok).

    Parameters
    ----------
    outcomes : sequence of Outcome
        Every job's outcome.
    note : str
        What became of the finished ones, added to the message.
    """
    failed = [o for o in outcomes if not o.ok]
    if failed:
        raise JobsFailed(failed, len(outcomes), note)
