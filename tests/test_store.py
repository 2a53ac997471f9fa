"""The world-model store: a run killed half way and resumed ends with the identities, records
and particles of an uninterrupted run; a kill never leaves the store unreadable; bad stores
name the file and the cause and are left as they were; `anchoring shell --store` answers."""

from __future__ import annotations

import os
import shutil
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

from plunit_runner import ROOT
from probanchor.loop.runner import RunOptions, run
from probanchor.loop.store import StoreError
from scenario_helpers import scenario_file

PARTICLES = 60


def _without_timings(records: list) -> list[dict]:
    rows = [r.to_json() for r in records]
    for row in rows:
        row.pop("timings")
    return rows


def _particles(db: Path) -> tuple[list, list]:
    with sqlite3.connect(db) as c:
        return (c.execute("SELECT i, weight FROM particles ORDER BY i").fetchall(),
                c.execute("SELECT * FROM particle_values ORDER BY atom, i").fetchall())


@pytest.fixture(scope="module")
def scenario(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return scenario_file(tmp_path_factory)


@pytest.fixture(scope="module")
def whole(scenario: Path, tmp_path_factory: pytest.TempPathFactory):
    db = tmp_path_factory.mktemp("whole") / "world.db"
    return run(RunOptions(scenario=scenario, particles=PARTICLES, seed=0, progress=False,
                          store=db)), db


def _frames(db: Path) -> int:
    try:
        with sqlite3.connect(db, timeout=5) as c:
            return int(c.execute("SELECT count(*) FROM frames").fetchone()[0])
    except sqlite3.Error:  # not created yet
        return 0


def test_a_run_killed_half_way_and_resumed_ends_as_an_uninterrupted_run(
        scenario: Path, whole, tmp_path: Path) -> None:
    output, whole_db = whole
    db = tmp_path / "world.db"
    env = {**os.environ, "PYTHONPATH": str(ROOT / "python")}
    child = subprocess.Popen(
        [sys.executable, "-m", "probanchor.cli.anchoring_cli", "run", str(scenario), "--particles",
         str(PARTICLES), "--quiet", "--store", str(db)],
        env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 300  # a bound on waiting, not a measurement
        while _frames(db) < 20 and child.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)
        child.kill()  # SIGKILL, in the middle of whatever it is doing
    finally:
        child.wait()
    done = _frames(db)  # the store is readable after the kill
    assert 20 <= done < len(output.records), "the run ended before it was killed"
    resumed = run(RunOptions(scenario=scenario, particles=PARTICLES, seed=0, progress=False,
                             resume=db))
    assert [o["symbols"] for o in resumed.summary["objects"]] == \
        [o["symbols"] for o in output.summary["objects"]]
    assert _without_timings(resumed.records) == _without_timings(output.records)
    assert _particles(db) == _particles(whole_db)  # the same particle set at the end


def test_the_store_holds_anchors_history_and_particles(whole) -> None:
    output, db = whole
    with sqlite3.connect(db) as c:
        frames = c.execute("SELECT count(*) FROM frames").fetchone()[0]
        symbols = {s for (s,) in c.execute("SELECT symbol FROM anchors")}
        hidden = c.execute("SELECT symbol, occluder, occluder_p, spread FROM history "
                           "WHERE frame = 20 AND perceived = 0").fetchall()
        weights = [w for (w,) in c.execute("SELECT weight FROM particles")]
    assert frames == len(output.records)
    assert symbols == set(output.records[-1].hypotheses)
    assert hidden and all(occ is not None and 0 < p <= 1 and spread > 0
                          for _, occ, p, spread in hidden)
    assert len(weights) == PARTICLES and sum(weights) == pytest.approx(1.0)


def test_a_new_run_never_overwrites_a_store_that_holds_one(scenario: Path, whole,
                                                           tmp_path: Path) -> None:
    _, db = whole
    copy = tmp_path / "kept.db"
    shutil.copy(db, copy)
    before = _particles(copy)
    with pytest.raises(StoreError, match=r"kept\.db: already holds a run of 46 frames"):
        run(RunOptions(scenario=scenario, particles=PARTICLES, progress=False, store=copy))
    assert _particles(copy) == before and _frames(copy) == 46


def test_a_store_from_another_theory_or_run_is_not_resumed(scenario: Path, whole,
                                                            tmp_path: Path) -> None:
    _, db = whole
    theory = tmp_path / "too.pl"
    shutil.copytree(ROOT / "prolog" / "too", tmp_path / "too")
    theory.write_text((ROOT / "prolog" / "too.pl").read_text() + "\n% edited\n")
    with pytest.raises(StoreError, match=r"world\.db: a store from another theory"):
        run(RunOptions(scenario=scenario, particles=PARTICLES, progress=False, resume=db,
                       theory=theory))
    # the same theory file, one of the files it includes edited
    theory.write_text((ROOT / "prolog" / "too.pl").read_text())
    motion = tmp_path / "too" / "too_motion.pl"
    text = motion.read_text()
    edited = text.replace("VZ is V / 100.", "VZ is V / 50.", 1)
    assert edited != text, "the edit must change too_motion.pl"
    motion.write_text(edited)
    with pytest.raises(StoreError, match=r"world\.db: a store from another theory"):
        run(RunOptions(scenario=scenario, particles=PARTICLES, progress=False, resume=db,
                       theory=theory))
    with pytest.raises(StoreError, match=r"not this run's store: it has particles '60' "
                                         r"\(this run: '100'\)"):
        run(RunOptions(scenario=scenario, particles=100, progress=False, resume=db))
    assert _frames(db) == 46


def test_an_unreadable_store_names_the_file(tmp_path: Path, scenario: Path) -> None:
    junk = tmp_path / "junk.db"
    junk.write_bytes(b"this is not a database, it is a sentence" * 40)
    before = junk.read_bytes()
    for options in (RunOptions(resume=junk), RunOptions(scenario=scenario, store=junk)):
        with pytest.raises(StoreError, match=r"junk\.db: not a readable"):
            run(options)
    assert junk.read_bytes() == before
    with pytest.raises(StoreError, match="no such store"):
        run(RunOptions(resume=tmp_path / "missing.db"))


def test_the_shell_loads_the_store_into_the_world_model(whole) -> None:
    output, db = whole
    ball = next(o["symbols"][0] for o in output.summary["objects"] if o["id"] == "ball_2")
    atom = ball.replace("-", "_")  # hidden under the box at the end
    result = subprocess.run(
        [sys.executable, "-m", "probanchor.cli.anchoring_cli", "shell", "--store", str(db)],
        input=f"prob(occluded_by({atom}, box_1), P), format('P=~4f~n', [P]).\n",
        env={**os.environ, "PYTHONPATH": str(ROOT / "python")}, capture_output=True,
        text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    p = float(result.stdout.split("P=")[1].split()[0])
    assert p > 0.5


def test_a_run_resumed_from_its_store_alone_takes_the_stored_options(whole,
                                                                      tmp_path: Path) -> None:
    output, db = whole
    copy = tmp_path / "world.db"
    shutil.copy(db, copy)
    resumed = run(RunOptions(resume=copy, progress=False))   # no source, no --particles 60
    assert resumed.summary["particles"] == PARTICLES
    assert [o["symbols"] for o in resumed.summary["objects"]] == \
        [o["symbols"] for o in output.summary["objects"]]


def test_a_run_resumed_after_an_ambiguity_revises_as_an_uninterrupted_run(tmp_path: Path
                                                                          ) -> None:
    """scenarios/identity_revealed.yaml killed after the mugs were re-acquired ambiguously
    (frame 128) and resumed: the identity hypotheses are replayed into the particles, and the
    run revises the mugs' symbols at the same frame as an uninterrupted one."""
    scenario = ROOT / "scenarios" / "identity_revealed.yaml"
    whole = run(RunOptions(scenario=scenario, particles=200, seed=0, progress=False,
                           store=tmp_path / "whole.db"))
    assert whole.summary["revisions"], "the scene should revise the mugs' symbols"
    db = tmp_path / "world.db"
    env = {**os.environ, "PYTHONPATH": str(ROOT / "python")}
    child = subprocess.Popen(
        [sys.executable, "-m", "probanchor.cli.anchoring_cli", "run", str(scenario),
         "--particles", "200", "--quiet", "--store", str(db)],
        env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 600  # a bound on waiting, not a measurement
        while _frames(db) < 131 and child.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)
        child.kill()
    finally:
        child.wait()
    done = _frames(db)
    assert 131 <= done < len(whole.records), "the run ended before it was killed"
    resumed = run(RunOptions(scenario=scenario, particles=200, seed=0, progress=False,
                             resume=db))
    assert resumed.summary["revisions"] == whole.summary["revisions"]
    assert _without_timings(resumed.records) == _without_timings(whole.records)
    assert _particles(db) == _particles(tmp_path / "whole.db")
