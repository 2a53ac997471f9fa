"""No process outlives a killed sweep: a process running jobs on local workers or on a local Ray
is killed (SIGKILL) while its jobs run, and every process it started ends soon after (workers,
multiprocessing's resource tracker, Ray's GCS, raylet, agents and workers)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from plunit_runner import ROOT

HERE = Path(__file__).resolve().parent

SWEEP = """
import sys
from probanchor.jobs import Job, parse_cluster, run_jobs
from test_jobs_killed import wait_for_ever
folder, cluster = sys.argv[1], sys.argv[2]
jobs = [Job(f"job {i}", wait_for_ever, (folder, i)) for i in range(2)]
for outcome in run_jobs(jobs, parse_cluster(cluster, 2)):
    print(outcome)
"""


def wait_for_ever(folder: str, i: int) -> None:
    """A job that says where it runs (its process id in FOLDER/i.pid), then waits."""
    Path(folder, f"{i}.pid").write_text(str(os.getpid()))
    time.sleep(3600)


def _alive(pid: int) -> bool:
    """The process exists and is not a zombie waiting to be reaped."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _in_session(sid: int) -> set[int]:
    pids = set()
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[3]) == sid and fields[0] != "Z":
                pids.add(int(entry.name))
    return pids


def _descendants(pid: int) -> set[int]:
    parents: dict[int, int] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                parents[int(entry.name)] = int(
                    (entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except (OSError, ValueError):
                continue
    found, frontier = set(), {pid}
    while frontier:
        frontier = {child for child, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found


def _names(pids: set[int]) -> list[str]:
    names = []
    for pid in sorted(pids):
        try:
            names.append(f"{pid}: {Path(f'/proc/{pid}/cmdline').read_bytes()[:120]!r}")
        except OSError:
            pass
    return names


def _kill_the_sweep_and_look(tmp_path: Path, cluster: str, start_within: float,
                             end_within: float) -> None:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT / "python"), str(HERE)])}
    sweep = subprocess.Popen([sys.executable, "-c", SWEEP, str(tmp_path), cluster], env=env,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                             start_new_session=True)
    started: set[int] = set()
    try:
        deadline = time.monotonic() + start_within  # bounds on waiting, not measurements
        while len(list(tmp_path.glob("*.pid"))) < 2 and sweep.poll() is None \
                and time.monotonic() < deadline:
            time.sleep(0.1)
        assert len(list(tmp_path.glob("*.pid"))) == 2, "the jobs did not start"
        started = _descendants(sweep.pid) | _in_session(sweep.pid)
        workers = {int(p.read_text()) for p in tmp_path.glob("*.pid")}
        assert workers <= started
        sweep.send_signal(signal.SIGKILL)
        sweep.wait()
        deadline = time.monotonic() + end_within
        left = started
        while time.monotonic() < deadline:
            left = {pid for pid in started | _in_session(sweep.pid) if _alive(pid)}
            if not left:
                break
            time.sleep(0.2)
        assert not left, f"outlived the killed sweep: {_names(left)}"
    finally:
        for pid in started | _in_session(sweep.pid):  # whatever is left, for the next tests
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
        if sweep.poll() is None:
            sweep.kill()
            sweep.wait()


def test_local_workers_end_with_their_killed_parent(tmp_path: Path) -> None:
    _kill_the_sweep_and_look(tmp_path, "local", start_within=120, end_within=20)


def test_a_local_ray_ends_with_its_killed_driver(tmp_path: Path) -> None:
    pytest.importorskip("ray")
    pytest.importorskip("psutil")
    _kill_the_sweep_and_look(tmp_path, "ray", start_within=240, end_within=60)
