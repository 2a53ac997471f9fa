"""What the store promises beyond a resume: one run writes it at a time (a second is refused
naming the first); a resume is refused, naming the difference, when the source file, the
options or the versions differ from the stored run's; a damaged or read-only store is refused
naming the file before anything is replayed; a reader sees whole frames while a run writes."""

from __future__ import annotations

import json
import os
import re
import shutil
import socket
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

from plunit_runner import ROOT
from probanchor.loop import reasoning
from probanchor.loop import store as store_module
from probanchor.loop.naming import symbol_atom
from probanchor.loop.runner import RunOptions, run
from probanchor.loop.store import StoreError, WorldStore
from scenario_helpers import BALL_UNDER_MUG_MOVED, scenario_file

PARTICLES = 60
ENV = {**os.environ, "PYTHONPATH": str(ROOT / "python")}
CLI = [sys.executable, "-m", "probanchor.cli.anchoring_cli"]

# The scenario of scenario_helpers at 10 frames per second and twice as slow: a run long
# enough (about 190 frames) to be read and asked while it goes on.
LONG = (BALL_UNDER_MUG_MOVED.replace("fps: 5", "fps: 10")
        .replace("at: 1.0,", "at: 2.0,").replace("at: 3.5,", "at: 7.0,")
        .replace("at: 6.0,", "at: 12.0,").replace("duration: 2.0", "duration: 4.0"))


@pytest.fixture(scope="module")
def scenario(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return scenario_file(tmp_path_factory)


@pytest.fixture(scope="module")
def long_scenario(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return scenario_file(tmp_path_factory, LONG, "long_game")


@pytest.fixture(scope="module")
def whole(scenario: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    db = tmp_path_factory.mktemp("whole") / "world.db"
    run(RunOptions(scenario=scenario, particles=PARTICLES, seed=0, progress=False, store=db))
    return db


def _frames(db: Path) -> int:
    try:
        with sqlite3.connect(db, timeout=5) as c:
            return int(c.execute("SELECT count(*) FROM frames").fetchone()[0])
    except sqlite3.Error:  # not created yet
        return 0


def _start(args: list[str], **kwargs) -> subprocess.Popen:
    return subprocess.Popen([*CLI, *args], env=ENV, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, **kwargs)


def _wait_for(condition, seconds: float, child: subprocess.Popen | None = None) -> None:
    deadline = time.monotonic() + seconds  # a bound on waiting, not a measurement
    while not condition():
        if child is not None and child.poll() is not None:
            raise AssertionError(f"the run ended first: {child.stderr.read()}")
        if time.monotonic() > deadline:
            raise AssertionError("waited too long")
        time.sleep(0.05)


def _copy(db: Path, tmp_path: Path) -> Path:
    copy = tmp_path / "world.db"
    shutil.copy(db, copy)
    return copy


# ---------------------------------------------------------------------------- one writer
def test_a_store_in_use_refuses_a_second_run_and_a_resume_naming_the_holder(
        long_scenario: Path, scenario: Path, tmp_path: Path) -> None:
    db = tmp_path / "world.db"
    first = _start(["run", str(long_scenario), "--particles", str(PARTICLES), "--quiet",
                    "--store", str(db)])
    try:
        _wait_for(lambda: _frames(db) >= 1, 300, first)
        holder = (rf"{re.escape(str(db))}: in use by another run \(pid {first.pid} on "
                  rf"{re.escape(socket.gethostname())} since \d{{4}}-\d\d-\d\d \d\d:\d\d:\d\d "
                  r"[+-]\d{4}: anchoring_cli\.py run .*long_game\.yaml")
        started = time.monotonic()
        with pytest.raises(StoreError, match=holder):  # another scenario, other options
            run(RunOptions(scenario=scenario, reasoning=False, progress=False, store=db))
        with pytest.raises(StoreError, match=holder):  # a resume while it writes
            run(RunOptions(resume=db, progress=False))
        assert time.monotonic() - started < 60  # refused at once, nothing replayed
        assert first.poll() is None  # (while the first one wrote)
    finally:
        first.kill()
        first.communicate()
    with _opened(db) as store:  # the first run's store, nothing of the others
        meta = store.meta()
    assert meta["source"].endswith("long_game.yaml") and meta["particles"] == str(PARTICLES)
    assert meta["reasoning"] == "True"


class _opened:
    """``with _opened(db) as store``: a store opened for reading, closed after."""

    def __init__(self, db: Path) -> None:
        self.store = WorldStore.open(db)

    def __enter__(self) -> WorldStore:
        return self.store

    def __exit__(self, *exc: object) -> None:
        self.store.close()


def test_two_runs_started_at_once_never_mix_in_one_store(scenario: Path,
                                                         long_scenario: Path,
                                                         tmp_path: Path) -> None:
    db = tmp_path / "world.db"
    runs = {
        "reasoning": _start(["run", str(long_scenario), "--particles", str(PARTICLES),
                             "--quiet", "--store", str(db)]),
        "no-reasoning": _start(["run", str(scenario), "--no-reasoning", "--seed", "3",
                                "--quiet", "--store", str(db)]),
    }
    results = {name: (*child.communicate(timeout=600), child.returncode)
               for name, child in runs.items()}
    won = [name for name, (_, _, code) in results.items() if code == 0]
    assert len(won) == 1, results
    lost = next(name for name in results if name not in won)
    assert re.search(r"in use by another run|already holds a run", results[lost][1])
    with _opened(db) as store:
        meta = store.meta()
    winner = won[0]
    assert meta["reasoning"] == str(winner == "reasoning")
    assert meta["source"].endswith("long_game.yaml" if winner == "reasoning"
                                   else "ball_under_mug_moved.yaml")
    frames = int(re.search(r"(\d+) frames", results[winner][0]).group(1))
    assert _frames(db) == frames
    with sqlite3.connect(db) as c:  # the particles are the winner's (none without reasoning)
        particles = c.execute("SELECT count(*) FROM particles").fetchone()[0]
    assert particles == (PARTICLES if winner == "reasoning" else 0)


def test_the_lock_goes_with_a_killed_run(scenario: Path, tmp_path: Path) -> None:
    db = tmp_path / "world.db"
    first = _start(["run", str(scenario), "--particles", str(PARTICLES), "--quiet",
                    "--store", str(db)])
    try:
        _wait_for(lambda: _frames(db) >= 3, 300, first)
    finally:
        first.kill()
        first.communicate()
    resumed = run(RunOptions(resume=db, progress=False))  # no stale lock
    assert len(resumed.records) == _frames(db) == 46


# ---------------------------------------------------------------------------- what a resume checks
def test_a_resume_after_the_scenario_file_changed_is_refused_naming_it(
        scenario: Path, whole: Path, tmp_path: Path) -> None:
    db = _copy(whole, tmp_path)
    edited = tmp_path / "edited"
    edited.mkdir()
    moved = edited / scenario.name
    moved.write_text(scenario.read_text())
    with sqlite3.connect(db) as c:  # the stored run's source is the copy's path
        c.execute("UPDATE meta SET value = ? WHERE key = 'source'", (f"scenario:{moved}",))
    c.close()
    moved.write_text(scenario.read_text().replace("at: 3.5", "at: 3.0"))
    with pytest.raises(StoreError, match=rf"world\.db: a store from another scenario file: "
                                         rf"{re.escape(str(moved))} changed since the store was "
                                         r"written \(sha1 [0-9a-f]{12} then, [0-9a-f]{12} now\)"):
        run(RunOptions(resume=db, progress=False))
    assert _frames(db) == 46


def test_a_resume_after_the_percept_stream_changed_is_refused(tmp_path: Path,
                                                              scenario: Path) -> None:
    from probanchor.loop.sources import perceive_scenario
    from probanchor.percepts import write_percepts

    stream = tmp_path / "game.jsonl"
    write_percepts(stream, perceive_scenario(scenario))
    db = tmp_path / "world.db"
    run(RunOptions(percepts=stream, particles=PARTICLES, progress=False, store=db))
    lines = stream.read_text().splitlines()
    stream.write_text("\n".join(lines[:-1]) + "\n")  # the last frame gone
    with pytest.raises(StoreError, match=r"a store from another percept stream: .*game\.jsonl "
                                         r"changed since the store was written"):
        run(RunOptions(resume=db, progress=False))


def test_a_resume_with_other_options_or_versions_names_the_difference(
        scenario: Path, whole: Path, tmp_path: Path) -> None:
    db = _copy(whole, tmp_path)
    with pytest.raises(StoreError, match=r"not this run's store: it has width 'None' "
                                         r"\(this run: '160'\); height 'None' \(this run: '120'"):
        run(RunOptions(resume=db, width=160, height=120, progress=False))
    with sqlite3.connect(db) as c:
        versions = json.loads(c.execute("SELECT value FROM meta WHERE key = 'versions'"
                                        ).fetchone()[0])
        c.execute("UPDATE meta SET value = ? WHERE key = 'versions'",
                  (json.dumps({**versions, "numpy": "0.9"}),))
    c.close()
    with pytest.raises(StoreError, match=r"written by other versions than this run's: numpy "
                                         r"'0\.9' \(this run: '\d"):
        run(RunOptions(resume=db, progress=False))
    assert set(versions) == {"anchoring", "python", "numpy", "swipl"}


# ---------------------------------------------------------------------------- bad stores
def _count_steps(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    steps: list[int] = []
    original = reasoning.OcclusionReasoner.step

    def counted(self, states):  # noqa: ANN001
        steps.append(1)
        return original(self, states)

    monkeypatch.setattr(reasoning.OcclusionReasoner, "step", counted)
    return steps


def test_a_damaged_store_is_refused_naming_the_file_before_any_replay(
        whole: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    db = _copy(whole, tmp_path)
    with sqlite3.connect(db) as c:
        c.execute("PRAGMA wal_checkpoint(TRUNCATE)")
        root = c.execute("SELECT rootpage FROM sqlite_master WHERE name = 'frames'"
                         ).fetchone()[0]
        page = c.execute("PRAGMA page_size").fetchone()[0]
    c.close()
    with open(db, "r+b") as data:  # a b-tree page of the frames overwritten with rubbish
        data.seek((root - 1) * page + 8)
        data.write(b"\xde\xad\xbe\xef" * 64)
    steps = _count_steps(monkeypatch)
    with pytest.raises(StoreError, match=rf"{re.escape(str(db))}: (damaged|.*malformed)"):
        run(RunOptions(resume=db, progress=False))
    assert steps == []


def test_a_read_only_store_is_refused_before_any_replay(whole: Path, tmp_path: Path,
                                                        monkeypatch: pytest.MonkeyPatch
                                                        ) -> None:
    db = _copy(whole, tmp_path)
    if os.geteuid() != 0:
        db.chmod(0o444)
    else:  # root writes any file: the store opened read-only instead
        connect = sqlite3.connect
        monkeypatch.setattr(store_module.sqlite3, "connect", lambda path, **kw: connect(
            f"file:{path}?mode=ro", uri=True, **kw))
    steps = _count_steps(monkeypatch)
    with pytest.raises(StoreError, match=rf"{re.escape(str(db))}: cannot be written .*readonly"):
        run(RunOptions(resume=db, progress=False))
    assert steps == []


def test_writing_a_frame_the_store_holds_names_the_file(whole: Path, tmp_path: Path) -> None:
    db = _copy(whole, tmp_path)
    store = WorldStore.open(db, write=True)
    try:
        with pytest.raises(StoreError, match=rf"{re.escape(str(db))}: writing frame 0: "
                                             r"UNIQUE constraint failed: frames\.frame"):
            with store._named("writing frame 0"), store.db:
                store.db.execute("INSERT INTO frames VALUES (0, 0.0, '[]', '{}')")
    finally:
        store.close()


# ---------------------------------------------------------------------------- live readers
_PARTICLE = re.compile(r"particle\((\d+), ([^)]+)\)\.")
_OCCLUDED = re.compile(r"particle_fact\((\d+), occluded_by\((\w+), (\w+)\)\)\.")


def _occlusion(text: str) -> tuple[int, dict[tuple[str, str], float]]:
    """The frame of a world file and P(occluded_by(A, O)) from its particles."""
    frame = int(re.search(r"world_frame\((\d+), ", text).group(1))
    weights = {int(i): float(w) for i, w in _PARTICLE.findall(text)}
    mass: dict[tuple[str, str], float] = {}
    for i, a, o in _OCCLUDED.findall(text):
        mass[(a, o)] = mass.get((a, o), 0.0) + weights[int(i)]
    return frame, mass


def _hidden_at(db: Path, frame: int) -> dict[str, tuple[str, float]]:
    """atom -> (occluder atom, its probability) of the hidden anchors in the store's history."""
    with sqlite3.connect(db, timeout=30) as c:
        rows = c.execute("SELECT symbol, occluder, occluder_p FROM history WHERE frame = ? "
                         "AND perceived = 0 AND occluder IS NOT NULL", (frame,)).fetchall()
    c.close()
    return {symbol_atom(s): (symbol_atom(o), p) for s, o, p in rows}


def _consistent(db: Path, frame: int, mass: dict[tuple[str, str], float]) -> bool:
    """The most probable occluder of each hidden anchor at ``frame``, as the history has it,
    has the probability the answer gives."""
    hidden = _hidden_at(db, frame)
    return all(abs(mass.get((a, o), 0.0) - p) < 1e-6 for a, (o, p) in hidden.items())


def test_a_run_is_asked_while_it_runs_from_the_store_the_shell_and_python(
        long_scenario: Path, tmp_path: Path) -> None:
    """Readers of the store (Python, `anchoring shell --store`) and the run's own query
    server (`--serve`, asked from Python and from `anchoring shell --connect`) answer for a
    named frame, consistently with the history the run stored for that frame."""
    from probanchor.loop.live import ask

    db = tmp_path / "world.db"
    err = tmp_path / "run.err"
    with open(err, "w") as stderr:
        child = subprocess.Popen(
            [*CLI, "run", str(long_scenario), "--particles", str(PARTICLES), "--quiet",
             "--store", str(db), "--serve", "0", "--out", str(tmp_path / "out")],
            env=ENV, stdout=subprocess.PIPE, stderr=stderr, text=True)
    try:
        _wait_for(lambda: "--connect" in err.read_text() and _frames(db) >= 1, 300, child)
        port = int(re.search(r"--connect (\d+)", err.read_text()).group(1))
        # the shell on the store, the server from Python and from the shell
        query = "findall([A, O, P], hidden_under(A, O, P), L)"
        shell = subprocess.run([*CLI, "shell", "--store", str(db), "--query", query], env=ENV,
                               capture_output=True, text=True, timeout=120)
        served = ask("hidden_under(A, O, P)", port)
        connected = subprocess.run([*CLI, "shell", "--connect", str(port), "--query",
                                    "hidden_under(A, O, P)"], env=ENV, capture_output=True,
                                   text=True, timeout=120)
        still_running = child.poll() is None
        # Python reads of the store, as fast as it goes, until the run ends
        reads, frames_seen, mixed = 0, set(), []
        store = WorldStore.open(db)
        try:
            while child.poll() is None:
                frame, _, text = store.world()
                read_frame, mass = _occlusion(text)
                if read_frame != frame or not _consistent(db, frame, mass):
                    mixed.append(frame)
                reads += 1
                frames_seen.add(frame)
                time.sleep(0.02)  # (leave the run the machine's cores)
        finally:
            store.close()
        assert not mixed, f"reads that mixed frames: {mixed} of {reads}"
        assert len(frames_seen) >= 5, "too few reads while the run wrote"
    finally:
        out, _ = child.communicate(timeout=600)
    assert child.returncode == 0
    total = int(re.search(r"(\d+) frames", out).group(1))
    assert still_running and served["frame"] < total - 1, "asked after the run"
    answers = [json.loads(shell.stdout), served, json.loads(connected.stdout)]
    for answer in answers:
        assert "error" not in answer, answer
        if answer is answers[0]:
            mass = {(a, o): p for a, o, p in answer["answers"][0]["L"]}
        else:
            mass = {(x["A"], x["O"]): x["P"] for x in answer["answers"]}
        assert _consistent(db, answer["frame"], mass), answer
    world = (tmp_path / "out" / "world.pl").read_text()
    assert f"world_frame({total - 1}, " in world   # which frame the final world model is after


class _WriteAfterFirstRead:
    """A store's connection that lets another connection commit a new frame right after the
    first statement of a read: a reader outside one read transaction would then mix two
    frames."""

    def __init__(self, db: sqlite3.Connection, path: Path) -> None:
        self._db, self._path, self._written = db, path, False

    def __getattr__(self, name: str):
        return getattr(self._db, name)

    def execute(self, sql: str, *args):
        cursor = self._db.execute(sql, *args)
        if sql.lstrip().upper().startswith("SELECT") and not self._written:
            self._written = True
            rows = cursor.fetchall()  # this statement's rows, then the writer's commit
            with sqlite3.connect(self._path) as writer:
                last, = writer.execute("SELECT max(frame) FROM frames").fetchone()
                writer.execute("INSERT INTO frames SELECT frame + 1, time + 1.0, filter_input,"
                               " record FROM frames WHERE frame = ?", (last,))
                writer.execute("UPDATE state SET value = value || char(10) || "
                               "'% written after' WHERE key = 'world'")
                writer.execute("UPDATE particles SET weight = 0.5 * weight")
                writer.execute("DELETE FROM particle_values WHERE i % 2 = 0")
            writer.close()
            return _Rows(rows)
        return cursor


class _Rows(list):
    """Rows already fetched, read as from a cursor."""

    def fetchone(self):
        return self[0] if self else None

    def fetchall(self):
        return list(self)


def test_a_read_sees_one_whole_frame_while_another_is_committed(whole: Path,
                                                                tmp_path: Path) -> None:
    db = _copy(whole, tmp_path)
    before = WorldStore.open(db)
    try:
        expected = before.world()
    finally:
        before.close()
    store = WorldStore.open(db)
    try:
        store.db = _WriteAfterFirstRead(store.db, db)  # type: ignore[assignment]
        assert store.world() == expected        # the frame as it was when the read began
        assert store.world() != expected        # (the next read sees the new frame)
    finally:
        store.close()
