"""How many Prolog threads step a filter's particles unless told otherwise.

A pure module (it does not start Prolog), so that command-line parsers can show the default
without importing :mod:`bridge.filter`. The particles depend on the thread count (each thread
steps its own group of particles with its own random stream), so the same seed gives the same
particles only with the same number of threads: pass ``threads`` (``--threads``) explicitly
where runs on different machines must agree.
"""

from __future__ import annotations

import os

#: The default's cap: a large machine does not split a step's particles into many small groups
#: (each group has its own per-step costs, its set-up and the join at the end of the step), and
#: the default, with it the particles of a seed, is the same on every machine of 8 cores or more.
MAX_DEFAULT_THREADS = 8


def available_cores() -> int:
    """The CPU cores this process may run on (its affinity mask, where the system has one)."""
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return max(1, os.cpu_count() or 1)


def default_threads(cores: int | None = None) -> int:
    """One thread per available core, at least 1 and at most :data:`MAX_DEFAULT_THREADS`."""
    if cores is None:
        cores = available_cores()
    return max(1, min(cores, MAX_DEFAULT_THREADS))


#: Prolog threads that step the particles unless told otherwise (from the cores available)
DEFAULT_THREADS: int = default_threads()
