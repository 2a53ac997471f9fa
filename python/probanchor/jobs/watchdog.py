"""A watchdog process: when the process that started it ends without saying goodbye (killed),
it ends that process's descendants too.

A local Ray started by a run (``ray.init``) is a tree of processes under the run's process: the
GCS server, the raylet, the raylet's dashboard and runtime-env agents, the workers. Ray shuts
them down when the run calls ``ray.shutdown()``, but a run killed with SIGKILL calls nothing,
and some of them stay (the agents, re-parented to init). The watchdog is a small process that
reads a pipe from the run: every second it notes the run's descendants (``psutil``, which Ray
depends on); when the pipe closes without the word ``done`` first (the run died), it ends
those that are still running, SIGTERM and, three seconds later, SIGKILL.

    python -m probanchor.jobs.watchdog PID      (standard input: the pipe from PID)
"""

from __future__ import annotations

import os
import select
import subprocess
import sys
from typing import Any

#: Seconds between two looks at the watched process's descendants.
LOOK_EVERY = 1.0
#: Seconds between SIGTERM and SIGKILL.
GRACE = 3.0


class Watchdog:
    """The watchdog of this process's descendants; :meth:`stop` when they ended normally."""

    def __init__(self) -> None:
        self._process: subprocess.Popen[bytes] | None = subprocess.Popen(
            [sys.executable, "-m", "probanchor.jobs.watchdog", str(os.getpid())],
            stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            env={**os.environ, "PYTHONPATH": os.pathsep.join(
                p for p in (_package_root(), os.environ.get("PYTHONPATH")) if p)})

    def stop(self) -> None:
        """The descendants ended normally: the watchdog leaves without touching anything."""
        if self._process is None:
            return
        process, self._process = self._process, None
        try:
            assert process.stdin is not None
            process.stdin.write(b"done\n")
            process.stdin.close()
        except OSError:
            pass
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


def _package_root() -> str:
    """The folder the ``probanchor`` package is in (the watchdog imports it from there)."""
    import probanchor

    return os.path.dirname(os.path.dirname(os.path.abspath(probanchor.__file__)))


def _descendants(psutil: Any, pid: int) -> list[Any]:
    me = os.getpid()
    try:
        return [p for p in psutil.Process(pid).children(recursive=True) if p.pid != me]
    except psutil.Error:
        return []


def watch(pid: int) -> int:
    """Watch ``pid`` through standard input; see the module's documentation."""
    import psutil

    seen: list[Any] = _descendants(psutil, pid)
    said = b""
    while True:
        ready, _, _ = select.select([sys.stdin.buffer], [], [], LOOK_EVERY)
        if ready:
            chunk = os.read(sys.stdin.fileno(), 4096)
            if not chunk:
                break
            said += chunk
            continue
        seen = _descendants(psutil, pid) or seen
    if b"done" in said:
        return 0
    seen = [p for p in seen if p.is_running()]  # (is_running also checks the start time)
    for process in seen:
        try:
            process.terminate()
        except psutil.Error:
            pass
    _, alive = psutil.wait_procs(seen, timeout=GRACE)
    for process in alive:
        try:
            process.kill()
        except psutil.Error:
            pass
    return 0


if __name__ == "__main__":
    sys.exit(watch(int(sys.argv[1])))
