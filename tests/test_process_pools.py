"""Worker processes are spawned, never forked: a forked child of a process that has janus
(SWI-Prolog, with its threads) loaded can hang. Every process pool in python/ is made with the
spawn start method, and the local jobs back end (what ``anchoring evaluate``, ``collect`` and
the learner's cross-validation run on) does start its pool that way."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import probanchor.jobs.local as local
from probanchor.jobs import Job, parse_cluster, run_jobs

PYTHON = Path(__file__).resolve().parents[1] / "python"
POOLS = re.compile(r"\b(ProcessPoolExecutor|Pool|get_context)\(")


def test_every_process_pool_in_the_code_is_started_with_spawn() -> None:
    made = []
    for path in sorted(PYTHON.rglob("*.py")):
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            code = line.split("#")[0]
            if POOLS.search(code):
                made.append((f"{path.relative_to(PYTHON)}:{number}", code.strip()))
    assert made, "no process pool found: the search is broken"
    for where, code in made:
        assert "mp_context=" in code or '"spawn"' in code, f"{where}: {code}"


def test_the_local_jobs_pool_is_spawned(monkeypatch: pytest.MonkeyPatch) -> None:
    methods: list[str] = []
    real = local.ProcessPoolExecutor

    def recording(*args, mp_context=None, **kwargs):
        methods.append(mp_context.get_start_method() if mp_context else "default")
        return real(*args, mp_context=mp_context, **kwargs)

    monkeypatch.setattr(local, "ProcessPoolExecutor", recording)
    jobs = [Job(str(n), divmod, (n, 3)) for n in (7, 8)]
    outcomes = sorted(run_jobs(jobs, parse_cluster(None, 2)), key=lambda o: o.job.name)
    assert [o.value for o in outcomes] == [(2, 1), (2, 2)]
    assert methods == ["spawn"]
