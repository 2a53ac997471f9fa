"""The Ray back end: each job a Ray task (``pip install '.[cluster]'``).

Ray is imported here only, when a run asks for it. A run on ``--cluster ray`` starts a local
Ray for itself (``ray.init(num_cpus=workers)``) and stops it at the end; ``auto`` and
``ray://HOST:PORT`` join a running cluster (``ray start --head`` and ``ray start
--address=...`` on its machines), whose nodes need the project installed and the output folder
at the same path (a shared file system): the jobs read scenario files and cached percept
streams there, and results come back through Ray's object store. A process that already called
``ray.init`` keeps its Ray as it is. A local Ray started here ends with the run even when the
run is killed (:mod:`probanchor.jobs.watchdog`).
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from probanchor.jobs.core import Cluster, ClusterError, Job, Outcome, Tally, cause
from probanchor.jobs.watchdog import Watchdog


def _ray() -> Any:
    try:
        import ray
    except ImportError as error:
        raise ClusterError("--cluster ray needs Ray, an optional extra: pip install "
                           "'.[cluster]' (or pip install 'ray[client]>=2.9')") from error
    return ray


def _start(ray: Any, cluster: Cluster) -> bool:
    """Start or join Ray unless this process already has; True when it was started here."""
    if ray.is_initialized():
        return False
    options: dict[str, Any] = {"include_dashboard": False, "log_to_driver": False,
                               "logging_level": logging.ERROR}
    try:
        if cluster.address is None:
            ray.init(num_cpus=cluster.workers, **options)
        else:
            ray.init(address=cluster.address, **options)
    except (ConnectionError, RuntimeError, ValueError) as error:
        what = ("cannot start a local Ray" if cluster.address is None
                else "cannot reach the cluster")
        raise ClusterError(f"--cluster {cluster.address or 'ray'}: {what}: "
                           f"{cause(error)}") from error
    return True


def run_on_ray(jobs: Sequence[Job], cluster: Cluster, retries: int,
               tally: Tally) -> Iterator[Outcome]:
    """Run ``jobs`` as Ray tasks, as many at once as the cluster has CPUs; yield each outcome.

    Parameters
    ----------
    jobs : sequence of Job
        The jobs.
    cluster : Cluster
        A Ray cluster (``backend == "ray"``).
    retries : int
        Ray's ``max_retries``: tries after the first for a task whose worker died; a task that
        raised is not tried again.
    tally : Tally
        The progress bar.

    Returns
    -------
    iterator of Outcome
    """
    ray = _ray()
    started = _start(ray, cluster)
    # a local Ray is a tree of processes under this one: should this process be killed, a
    # watchdog ends them (ray.shutdown() below is never reached then)
    watchdog = Watchdog() if started and cluster.address is None else None
    under_way: dict[Any, int] = {}
    try:
        capacity = max(1, int(ray.cluster_resources().get("CPU", 1)))
        remote: dict[Callable[..., Any], Any] = {}
        queue = list(range(len(jobs)))[::-1]
        while queue or under_way:
            while queue and len(under_way) < capacity:
                i = queue.pop()
                function = jobs[i].function
                if function not in remote:
                    remote[function] = ray.remote(num_cpus=1, max_retries=retries,
                                                  retry_exceptions=False)(function)
                under_way[remote[function].remote(*jobs[i].args)] = i
            tally.running(len(under_way))
            ready, _ = ray.wait(list(under_way), num_returns=1)
            for ref in ready:
                i = under_way.pop(ref)
                try:
                    outcome = Outcome(jobs[i], ray.get(ref))
                except ray.exceptions.RayTaskError as error:
                    outcome = Outcome(jobs[i], error=cause(error.cause or error))
                except ray.exceptions.RayError as error:  # worker or node died, tries used up
                    outcome = Outcome(jobs[i], error=f"its Ray worker died {retries + 1} times "
                                      f"({type(error).__name__})", tries=retries + 1)
                tally.finished(outcome)
                yield outcome
    finally:
        for ref in under_way:  # stopped early: the jobs not finished are stopped too
            ray.cancel(ref, force=True)
        if started:
            ray.shutdown()
        if watchdog is not None:
            watchdog.stop()
