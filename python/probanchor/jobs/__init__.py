"""Many independent jobs, run on local processes or on a Ray cluster.

A *job* is one call of a module-level function on its own arguments (a scenario or game under
one configuration, a collection episode, a learned theory's run): jobs share nothing but the
files they read and write, and their results come back to the caller, which records them as
they arrive. Two back ends run them:

- ``local`` (the default, no extra dependency): worker processes started with the ``spawn``
  method (a forked child of a process that has janus loaded can hang); one worker runs the
  jobs in the calling process;
- ``ray``: tasks on a Ray cluster (``pip install '.[cluster]'``; Ray is imported only then): a
  local Ray started for the run (``ray``), or an existing cluster (``ray://HOST:PORT`` through
  Ray Client, ``auto`` for the cluster this machine belongs to).

Both keep at most ``workers`` jobs under way, so the progress bar's "running" is what runs; a
job whose worker died (killed, out of memory) is tried again up to ``retries`` times; a job
that raised is reported as failed with its cause. Finished jobs are never lost: every result is
handed to the caller the moment it is there, failed or not, and the caller decides
(:func:`raise_failures`).

    >>> from probanchor.jobs import Job, parse_cluster, run_jobs
    >>> outcomes = list(run_jobs([Job("a", divmod, (7, 2))], parse_cluster(None, 1)))
    >>> outcomes[0].value
    (3, 1)
"""

from __future__ import annotations

from probanchor.jobs.core import (
    Cluster,
    ClusterError,
    Job,
    JobsFailed,
    Outcome,
    parse_cluster,
    raise_failures,
    run_jobs,
)

__all__ = ["Cluster", "ClusterError", "Job", "JobsFailed", "Outcome", "parse_cluster",
           "raise_failures", "run_jobs"]
