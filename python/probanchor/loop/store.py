"""The world model in an SQLite database that survives a restart (``anchoring run --store``,
``--resume``).

Per frame, in one transaction (a kill leaves the store as it was after the last whole frame):
the frame (its time, the anchors' states the filter stepped on, the frame's tracking record),
each anchor's history row (perceived or tracked, position or the particles' mean and spread,
the most probable occluder), every anchor's symbol, category and attributes, the anchor
manager's state, and the filter's particle set (weights and facts). The schema is
:data:`SCHEMA` (documented in docs/robotics.md).

A run is resumed by loading the anchors and replaying the stored filter inputs through a new
filter with the same theory, particles, seed, threads and engine: the filter is deterministic
in them, so its particles are again the stored ones, which is checked against the stored
weights; the hidden anchors get their particles back from it.

One run writes a store at a time: a run takes the store's lock (``WORLD.db.lock``, an
exclusive ``flock`` held for the whole run and let go by the system when the process ends,
however it ends) before it reads or writes anything, and a second run is refused naming the
one that holds it. A resumed run must be the stored one: its source file (scenario, percept
stream, bag) and theory byte for byte, its options and the versions of what computes it.
Readers take no lock: each read is one SQLite read transaction, so it sees the store as it
was after one whole frame, and in SQLite's write-ahead-log mode a reader never blocks the
run nor the run a reader.
"""

from __future__ import annotations

import dataclasses
import datetime
import fcntl
import hashlib
import itertools
import json
import os
import platform
import shlex
import socket
import sqlite3
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from anchoring.identity import AmbiguousPercept, Revision
from anchoring.manager import AnchorManagerError
from bridge.includes import digest_with_includes
from probanchor.evaluation import TrackingRecord
from probanchor.loop.loop import AnchoringLoop, FrameOutcome
from probanchor.loop.naming import symbol_atom
from probanchor.loop.reasoning import AnchorState
from probanchor.loop.world_file import (
    anchor_particle_facts,
    frame_fact,
    particle_lines,
    world_facts,
)

FORMAT = "anchoring-store 2"  # 2: frames.filter_input holds the identity layer's input too

SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS frames (
    frame INTEGER PRIMARY KEY, time REAL NOT NULL,
    filter_input TEXT NOT NULL,   -- JSON {"states": [[symbol, category, [x, y, z] or null],
                                  --  ...], "ambiguous": [...], "evidence": [...],
                                  --  "revisions": [...]} (the identity layer's input)
    record TEXT NOT NULL          -- JSON of the frame's evaluation.TrackingRecord
);
CREATE TABLE IF NOT EXISTS anchors (
    symbol TEXT PRIMARY KEY, atom TEXT NOT NULL, category TEXT NOT NULL,
    created REAL NOT NULL, last_seen REAL NOT NULL, perceived INTEGER NOT NULL,
    x REAL, y REAL, z REAL,                 -- point estimate at the last frame
    size TEXT NOT NULL, colour_names TEXT NOT NULL, categories TEXT NOT NULL  -- JSON
);
CREATE TABLE IF NOT EXISTS history (
    frame INTEGER NOT NULL, symbol TEXT NOT NULL, perceived INTEGER NOT NULL,
    x REAL, y REAL, z REAL,       -- the percept's position, or the particles' weighted mean
    spread REAL,                  -- the particles' weighted RMS distance from it (m); 0 when seen
    occluder TEXT, occluder_p REAL,  -- the most probable occluder of a tracked anchor
    PRIMARY KEY (frame, symbol)
);
CREATE TABLE IF NOT EXISTS particles (i INTEGER PRIMARY KEY, weight REAL NOT NULL);
CREATE TABLE IF NOT EXISTS particle_values (
    i INTEGER NOT NULL, atom TEXT NOT NULL,  -- particle, anchor
    x REAL, y REAL, z REAL,                  -- pos(atom):t in that particle (NULL: none)
    occluder TEXT,                           -- occluded_by(atom, occluder):t (NULL: none)
    PRIMARY KEY (atom, i)
);
CREATE TABLE IF NOT EXISTS state (
    key TEXT PRIMARY KEY, value TEXT NOT NULL  -- manager (AnchorManager.to_json), loop, and
                                               -- world (world.pl's facts but the particles)
);
"""

#: the options a resumed run must share with the stored one
RUN_KEYS = ("source", "particles", "seed", "threads", "engine", "reasoning", "reidentify",
            "identity", "resample_threshold", "width", "height", "bag_topics", "theory_sha1")


#: how the stored text of each run option that a resumed run takes from its store is read back
_STORED_OPTION: dict[str, Any] = {
    "particles": int, "seed": int, "threads": int, "engine": str, "theory": Path,
    "reasoning": lambda text: text == "True", "reidentify": lambda text: text == "True",
    "identity": lambda text: text == "True", "resample_threshold": float,
    "width": lambda text: None if text == "None" else int(text),
    "height": lambda text: None if text == "None" else int(text),
}


def adopt_stored_options(options: Any, meta: dict[str, str]) -> None:
    """Resuming: each run option left at its default takes the stored run's value.

    ``anchoring run --resume WORLD.db`` then continues the run without its options given
    again; an option given with another value than the stored one is still refused by
    :meth:`WorldStore.check_resumable`.
    """
    defaults = {f.name: f.default for f in dataclasses.fields(options)
                if f.default is not dataclasses.MISSING}
    for key, read in _STORED_OPTION.items():
        if key in meta and key in defaults and getattr(options, key) == defaults[key]:
            setattr(options, key, read(meta[key]))
    stored_topics = meta.get("bag_topics", "")
    if stored_topics and getattr(options, "bag_topics", None) is None:
        from probanchor.bags import BagTopics

        given = json.loads(stored_topics)
        pose = given.pop("camera_pose")
        options.bag_topics = BagTopics(**given, camera_pose=None if pose is None
                                       else np.asarray(pose, dtype=float))


class StoreError(ValueError):
    """A store that cannot be written or resumed; the message names the file and the cause."""


def theory_digest(path: Path) -> str:
    """The SHA-1 of a theory: of its file's bytes and of every file it includes
    (:func:`bridge.includes.digest_with_includes`: editing ``prolog/too/too_motion.pl`` makes
    another theory of ``prolog/too.pl``)."""
    return digest_with_includes(path)


def source_digest(path: Path) -> str:
    """The SHA-1 of a source's bytes: a file's, or a folder's files' (a rosbag2 directory:
    each file's name and bytes, in name order)."""
    digest = hashlib.sha1()
    files = sorted(p for p in path.rglob("*") if p.is_file()) if path.is_dir() else [path]
    for file in files:
        if path.is_dir():
            digest.update(str(file.relative_to(path)).encode() + b"\0")
        with open(file, "rb") as data:
            while chunk := data.read(1 << 20):
                digest.update(chunk)
    return digest.hexdigest()


def versions(reasoning: bool) -> dict[str, str]:
    """The versions of what computes a run: this software, Python, numpy and (with reasoning)
    SWI-Prolog; a resumed run replays the filter, which must give the stored particles."""
    from importlib import metadata

    try:
        own = metadata.version("anchoring")
    except metadata.PackageNotFoundError:  # run from a source tree that is not installed
        own = "unknown"
    out = {"anchoring": own, "python": platform.python_version(), "numpy": np.__version__}
    if reasoning:
        from bridge import prolog

        found = prolog.query_once("current_prolog_flag(version, V)")
        out["swipl"] = str(found["V"])
    return out


def _bag_topics_text(topics: Any) -> str:
    """A bag run's topic options as JSON (empty for another source)."""
    if topics is None:
        return ""
    pose = topics.camera_pose
    return json.dumps({"colour": topics.colour, "depth": topics.depth,
                       "camera_info": topics.camera_info, "world_frame": topics.world_frame,
                       "camera_pose": None if pose is None
                       else np.asarray(pose, dtype=float).tolist(),
                       "max_skew": float(topics.max_skew),
                       "max_lead": float(topics.max_lead)}, sort_keys=True)


def run_meta(source: str, options: Any) -> dict[str, str]:
    """What identifies a run, as the store's ``meta`` rows.

    Parameters
    ----------
    source:
        ``scenario:PATH``, ``bag:PATH`` or ``percepts:PATH`` (absolute paths).
    options:
        The run's :class:`probanchor.loop.runner.RunOptions`.

    Returns
    -------
    Key -> text: the options, the source file's and the theory's SHA-1, the versions.
    """
    _, _, path = source.partition(":")
    bag = getattr(options, "bag", None) is not None
    topics = getattr(options, "bag_topics", None)
    if bag and topics is None:
        from probanchor.bags import BagTopics

        topics = BagTopics()
    return {
        "format": FORMAT, "source": source, "particles": str(options.particles),
        "seed": str(options.seed), "threads": str(options.threads),
        "engine": str(options.engine), "reasoning": str(bool(options.reasoning)),
        "reidentify": str(bool(options.reidentify)),
        "identity": str(bool(options.identity)),
        "resample_threshold": repr(float(options.resample_threshold)),
        "width": str(getattr(options, "width", None)),
        "height": str(getattr(options, "height", None)),
        "bag_topics": _bag_topics_text(topics) if bag else "",
        "theory": str(options.theory),
        "theory_sha1": theory_digest(options.theory) if options.reasoning else "",
        "source_sha1": source_digest(Path(path)) if Path(path).exists() else "",
        "versions": json.dumps(versions(bool(options.reasoning)), sort_keys=True),
    }


class StoreLock:
    """The one-writer lock of a store: an exclusive ``flock`` on ``WORLD.db.lock``.

    The lock file holds who has the lock (process id, host, command, since when), for the
    message that refuses a second writer. The system lets the lock go when its process ends,
    however it ends (a kill leaves no stale lock); the file itself stays (deleting it would
    let a third process lock a new file while a second still waits on the old one).
    """

    def __init__(self, store: Path) -> None:
        self.store = store
        self.path = store.with_name(store.name + ".lock")
        self._fd: int | None = None

    def acquire(self) -> None:
        """Take the lock, or a :class:`StoreError` naming the store and who holds it."""
        try:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise StoreError(f"{self.store}: cannot take the store's lock {self.path}: "
                             f"{exc.strerror or exc}") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            holder = _holder_text(os.pread(fd, 4096, 0))
            os.close(fd)
            raise StoreError(f"{self.store}: in use by another run ({holder}); a store is "
                             "written by one run at a time: wait for that one to end, or give "
                             "another file") from None
        holder = {"pid": os.getpid(), "host": socket.gethostname(),
                  "command": shlex.join([Path(sys.argv[0]).name, *sys.argv[1:]])
                  if sys.argv and sys.argv[0] else sys.executable,
                  "since": datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M:%S %z")}
        os.ftruncate(fd, 0)
        os.pwrite(fd, (json.dumps(holder) + "\n").encode(), 0)
        self._fd = fd

    def release(self) -> None:
        """Let the lock go (the file is left, empty)."""
        if self._fd is not None:
            fd, self._fd = self._fd, None
            try:
                os.ftruncate(fd, 0)
            finally:
                os.close(fd)  # closing the last descriptor lets the flock go


def _holder_text(raw: bytes) -> str:
    """Who holds a lock, from its file: ``pid 12 on host since ... : anchoring run ...``."""
    try:
        holder = json.loads(raw.decode())
        return (f"pid {holder['pid']} on {holder['host']} since {holder['since']}: "
                f"{holder['command']}")
    except (ValueError, KeyError, TypeError):
        return "a process that is just starting, or one that gave no name"


@dataclass
class StoredRun:
    """What a resumed run starts from."""

    next_frame: int
    records: list[TrackingRecord]


class WorldStore:
    """One run's world model in an SQLite file.

    Made by :meth:`create` (a new run) or :meth:`open` (``write=True`` to resume: the store's
    lock is taken first); every SQLite error of its methods is a :class:`StoreError` naming
    the file.
    """

    def __init__(self, path: Path, connection: sqlite3.Connection,
                 lock: StoreLock | None = None) -> None:
        self.path = path
        self.db = connection
        self.lock = lock

    # ------------------------------------------------------------------ opening
    @classmethod
    def create(cls, path: Path | str, meta: dict[str, str]) -> WorldStore:
        """A new store for a run; an existing store that holds frames is never overwritten.

        Parameters
        ----------
        path:
            The database file (created with its folder).
        meta:
            :func:`run_meta` of the run.

        Returns
        -------
        The store, ready for :meth:`write_frame`, holding its lock; a :class:`StoreError`
        when another run holds the lock, the file holds a run or cannot be written.
        """
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        lock = StoreLock(path)
        lock.acquire()
        try:
            store = cls._connect(path, lock, write=True)
        except BaseException:
            lock.release()
            raise
        try:
            store._start(meta)  # noqa: SLF001 (its own class's, in its constructor)
        except BaseException:
            store.close()
            raise
        return store

    def _start(self, meta: dict[str, str]) -> None:
        """The schema and ``meta`` written into a file that holds no run."""
        with self._named("starting a run"):
            if self._has_schema() and self._count("frames"):
                raise StoreError(f"{self.path}: already holds a run of "
                                 f"{self._count('frames')} frames; continue it with "
                                 "--resume, or give another file")
            with self.db:
                self.db.executescript(SCHEMA)
                self.db.execute("DELETE FROM meta")
                self.db.executemany("INSERT INTO meta VALUES (?, ?)", sorted(meta.items()))

    @classmethod
    def open(cls, path: Path | str, write: bool = False) -> WorldStore:
        """An existing store, checked to be one (for reading, or resuming with ``write``).

        Parameters
        ----------
        path:
            The database file.
        write:
            Take the store's lock and check that the whole file reads (SQLite's
            ``quick_check``) and can be written, before anything is replayed.

        Returns
        -------
        The store; a :class:`StoreError` naming the file for a missing or unreadable file, a
        database that is not an anchoring store, a damaged or read-only one (``write``), or
        one another run holds (``write``).
        """
        path = Path(path)
        if not path.is_file():
            raise StoreError(f"{path}: no such store")
        lock = None
        if write:
            lock = StoreLock(path)
            lock.acquire()
        try:
            store = cls._connect(path, lock, write=write)
        except BaseException:
            if lock is not None:
                lock.release()
            raise
        try:
            meta = store.meta()
            if meta.get("format") != FORMAT:
                raise StoreError(f"{path}: not an anchoring store (format "
                                 f"{meta.get('format', 'missing')!r}, expected {FORMAT!r})")
            if write:
                store._check_whole()  # noqa: SLF001 (its own class's, in its constructor)
        except BaseException:
            store.close()
            raise
        return store

    @classmethod
    def _connect(cls, path: Path, lock: StoreLock | None = None,
                 write: bool = False) -> WorldStore:
        try:
            db = sqlite3.connect(path, timeout=30)
        except sqlite3.Error as exc:
            raise StoreError(f"{path}: cannot be opened: {exc}") from None
        try:
            if write:
                db.execute("PRAGMA journal_mode=WAL")   # readers while a run writes
                db.execute("PRAGMA synchronous=NORMAL")
            else:
                db.execute("SELECT count(*) FROM sqlite_master").fetchone()
        except sqlite3.DatabaseError as exc:
            db.close()
            if write and "readonly" in str(exc):
                raise StoreError(f"{path}: cannot be written ({exc}); nothing was replayed"
                                 ) from None
            raise StoreError(f"{path}: not a readable SQLite store: {exc}") from None
        return cls(path, db, lock)

    def _check_whole(self) -> None:
        """Before a resume replays anything: every page reads, and the file takes a write."""
        with self._named("checking the store"):
            problems = [row[0] for row in self.db.execute("PRAGMA quick_check(5)")]
        if problems != ["ok"]:
            raise StoreError(f"{self.path}: damaged: {'; '.join(problems)} (SQLite's "
                             "quick_check); the run cannot be resumed from it")
        try:
            with self.db:  # a write that changes nothing, in a transaction of its own
                self.db.execute("UPDATE meta SET value = value WHERE key = 'format'")
        except sqlite3.Error as exc:
            raise StoreError(f"{self.path}: cannot be written ({exc}); nothing was replayed"
                             ) from None

    @contextmanager
    def _named(self, doing: str) -> Iterator[None]:
        """SQLite's errors as :class:`StoreError` naming the file and what was being done."""
        try:
            yield
        except sqlite3.Error as exc:
            raise StoreError(f"{self.path}: {doing}: {exc}") from None

    def close(self) -> None:
        """Close the connection and let the lock go."""
        try:
            self.db.close()
        finally:
            if self.lock is not None:
                self.lock.release()
                self.lock = None

    def _has_schema(self) -> bool:
        return self.db.execute("SELECT count(*) FROM sqlite_master WHERE name = 'frames'"
                               ).fetchone()[0] == 1

    def _count(self, table: str) -> int:
        return int(self.db.execute(f"SELECT count(*) FROM {table}").fetchone()[0])

    def meta(self) -> dict[str, str]:
        """The run's identity (:func:`run_meta`)."""
        try:
            return dict(self.db.execute("SELECT key, value FROM meta").fetchall())
        except sqlite3.DatabaseError as exc:
            raise StoreError(f"{self.path}: not a readable anchoring store: {exc}") from None

    # ------------------------------------------------------------------ reading
    @contextmanager
    def reading(self) -> Iterator[sqlite3.Connection]:
        """One read transaction: every query in it sees the store as it was after one whole
        frame, however many frames a run writes meanwhile (and the run is never blocked).

        Returns
        -------
        A context manager giving the connection; SQLite errors in it are
        :class:`StoreError` naming the file.

        Examples
        --------
        >>> with store.reading() as db:                            # doctest: +SKIP
        ...     frame, = db.execute("SELECT max(frame) FROM frames").fetchone()
        ...     rows = db.execute("SELECT symbol, x, y, z FROM anchors").fetchall()
        """
        with self._named("reading"):
            if self.db.in_transaction:
                raise StoreError(f"{self.path}: a read inside a read (or a write)")
            self.db.execute("BEGIN")
            try:
                yield self.db
            finally:
                self.db.execute("COMMIT")

    def last_frame(self) -> tuple[int, float] | None:
        """The last whole frame stored and its time (s), or None before the first."""
        with self.reading() as db:
            return _last_frame(db)

    # ------------------------------------------------------------------ writing
    def write_frame(self, outcome: FrameOutcome, loop: AnchoringLoop) -> None:
        """Store one frame and the world model after it, in one transaction.

        Parameters
        ----------
        outcome:
            The frame's outcome (its record, the filter's input, the hidden beliefs).
        loop:
            The loop, holding the anchors and the filter after the frame.

        Returns
        -------
        None.
        """
        record = outcome.record
        frame = record.frame
        inputs = filter_input_json(outcome)
        weights, values = self._particle_values(loop)
        history = []
        for anchor in loop.manager.anchors:
            hyp = record.hypotheses.get(anchor.symbol)
            if hyp is None:
                continue
            position, spread = np.asarray(hyp.position, dtype=float), 0.0
            occluder, p = None, None
            belief = outcome.hidden_beliefs.get(anchor.symbol)
            if belief is not None:
                points, share = belief
                position = share @ points
                spread = float(np.sqrt(share @ np.sum((points - position) ** 2, axis=1)))
            if not hyp.perceived and anchor.symbol in values:
                occluder, p = _most_probable(values[anchor.symbol][1], weights, loop)
            history.append((frame, anchor.symbol, int(hyp.perceived), *_xyz(position),
                            spread, occluder, p))
        anchors = []
        for anchor in loop.manager.anchors:
            hyp = record.hypotheses.get(anchor.symbol)
            xyz = _xyz(np.asarray(hyp.position, dtype=float)) if hyp is not None \
                else (None, None, None)
            anchors.append((anchor.symbol, symbol_atom(anchor.symbol), anchor.best_category,
                            anchor.created, anchor.last_seen,
                            int(hyp is not None and hyp.perceived), *xyz,
                            json.dumps(np.asarray(anchor.size.mean()).reshape(-1).tolist()),
                            json.dumps(list(anchor.colour_names)),
                            json.dumps(anchor.category)))
        rows = []
        for symbol, (positions, occluders) in values.items():
            atom = symbol_atom(symbol)
            xyz = np.where(np.isnan(positions), None, positions.astype(object)).tolist()
            rows.extend((i, atom, *p, o) for i, (p, o) in enumerate(zip(xyz, occluders,
                                                                        strict=True)))
        perceived = {s for s, h in record.hypotheses.items() if h.perceived}
        snapshot = loop.snapshot()
        with self._named(f"writing frame {frame}"), self.db:
            db = self.db
            db.execute("INSERT INTO frames VALUES (?, ?, ?, ?)",
                       (frame, record.time, json.dumps(inputs), json.dumps(record.to_json())))
            db.executemany("INSERT INTO history VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)", history)
            db.execute("DELETE FROM anchors")
            db.executemany("INSERT INTO anchors VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                           anchors)
            db.execute("DELETE FROM particles")
            db.execute("DELETE FROM particle_values")
            db.executemany("INSERT INTO particles VALUES (?, ?)", enumerate(weights.tolist()))
            db.executemany("INSERT INTO particle_values VALUES (?, ?, ?, ?, ?, ?)", rows)
            db.executemany("INSERT OR REPLACE INTO state VALUES (?, ?)", [
                ("manager", json.dumps(snapshot["manager"])),
                ("loop", json.dumps(snapshot["loop"])),
                ("world", "\n".join(world_facts(loop, perceived,
                                                 particles=(np.ones(0), [])))),
            ])

    @staticmethod
    def _particle_values(loop: AnchoringLoop
                         ) -> tuple[np.ndarray, dict[str, tuple[np.ndarray, list[Any]]]]:
        """The weights, and per anchor its position (N x 3, NaN: none) and occluder (None:
        none) in every particle."""
        reasoner = loop.reasoner
        if reasoner is None:
            return np.ones(0), {}
        out = {anchor.symbol: (reasoner.positions(anchor.symbol),
                               reasoner.particle_occluders(anchor.symbol))
               for anchor in loop.manager.anchors}
        return reasoner.weights(), out

    # ------------------------------------------------------------------ resuming
    def check_resumable(self, meta: dict[str, str]) -> None:
        """A :class:`StoreError` when the run to resume is not the stored one, naming every
        difference: another theory or source file (their bytes), other options or versions;
        or when nothing was stored."""
        stored = self.meta()
        if stored.get("theory_sha1") and meta.get("theory_sha1") != stored["theory_sha1"]:
            raise StoreError(f"{self.path}: a store from another theory: it was written with "
                             f"{stored.get('theory')} as it was then (sha1 "
                             f"{stored['theory_sha1'][:12]}), this run's theory "
                             f"{meta.get('theory')} differs; resume with that theory")
        wrong = [f"{k} {stored[k]!r} (this run: {meta.get(k)!r})" if k in stored else
                 f"no {k} recorded (a store of an earlier version; this run: {meta.get(k)!r})"
                 for k in RUN_KEYS
                 if k != "theory_sha1" and stored.get(k, "") != meta.get(k, "")]
        if wrong:
            raise StoreError(f"{self.path}: not this run's store: it has " + "; ".join(wrong))
        if stored.get("source_sha1", "") != meta.get("source_sha1", ""):
            kind, path = stored_source(stored)
            then = stored.get("source_sha1", "") or "not recorded"
            now = meta.get("source_sha1", "") or "no such file"
            raise StoreError(f"{self.path}: a store from another {_SOURCE_NAMES[kind]}: "
                             f"{path} changed since the store was written (sha1 {then[:12]} "
                             f"then, {now[:12]} now); resume with the file as it was, or start "
                             "a new store")
        other = _version_differences(stored.get("versions", ""), meta.get("versions", ""))
        if other:
            raise StoreError(f"{self.path}: written by other versions than this run's: "
                             f"{other}; the replay of its frames could give other particles: "
                             "resume with those versions, or start a new store")
        with self._named("reading"):
            if not self._count("frames"):
                raise StoreError(f"{self.path}: holds no frame to resume from")

    def resume(self, loop: AnchoringLoop) -> StoredRun:
        """Bring ``loop`` to the state after the last stored frame.

        Parameters
        ----------
        loop:
            A new loop with the stored run's options (:meth:`check_resumable`).

        Returns
        -------
        The next frame to play and the stored frames' records.
        """
        with self.reading() as db:
            rows = db.execute("SELECT frame, filter_input, record FROM frames ORDER BY frame"
                              ).fetchall()
            state = dict(db.execute("SELECT key, value FROM state").fetchall())
            stored = np.array([w for (w,) in db.execute(
                "SELECT weight FROM particles ORDER BY i")])
        try:
            snapshot = {"manager": json.loads(state["manager"]),
                        "loop": json.loads(state["loop"])}
            records = [TrackingRecord.from_json(json.loads(r)) for _, _, r in rows]
            loop.restore(snapshot, [Revision.from_json(r) for record in records
                                    for r in record.revised], str(self.path))
        except (KeyError, ValueError, AnchorManagerError) as exc:
            raise StoreError(f"{self.path}: the stored world model cannot be read: {exc}"
                             ) from None
        manager = loop.manager
        if loop.reasoner is not None:
            for frame, inputs, _ in rows:
                states, ambiguous, evidence, revised = read_filter_input(inputs)
                again = loop.reasoner.reason(states, ambiguous, int(frame), evidence)
                if [r.to_json() for r in again] != revised:
                    raise StoreError(f"{self.path}: replaying frame {frame} did not revise the "
                                     "identities the store says it revised (was the store "
                                     "changed by another program?)")
            if stored.shape != loop.reasoner.weights().shape or not np.allclose(
                    stored, loop.reasoner.weights(), rtol=1e-9, atol=1e-12):
                raise StoreError(f"{self.path}: replaying the stored frames did not give the "
                                 "stored particles, with the same source, options and "
                                 "versions (was the store changed by another program?)")
            last = records[-1]
            others = sorted(last.hypotheses)
            for symbol, hyp in last.hypotheses.items():
                belief = None if hyp.perceived else loop.reasoner.belief(symbol, others)
                if belief is not None:
                    manager.set_position_particles(symbol, belief.positions, belief.weights,
                                                   belief.occluded)
        return StoredRun(int(rows[-1][0]) + 1, records)

    def world_text(self) -> str:
        """The world model after the last frame as the Prolog facts of a world file
        (``prolog/shell/world.pl``): :meth:`world`'s text."""
        return self.world()[2]

    def world(self) -> tuple[int, float, str]:
        """The last whole frame, its time and the world model after it as the Prolog facts
        of a world file (``prolog/shell/world.pl``): ``world_frame(Frame, Time)``, the facts of
        ``state.world`` and the particles' from ``particles`` and ``particle_values``, all
        read in one read transaction (so from one whole frame while a run writes)."""
        with self.reading() as db:
            row = db.execute("SELECT value FROM state WHERE key = 'world'").fetchone()
            last = _last_frame(db)
            if row is None or last is None:
                raise StoreError(f"{self.path}: holds no frame yet")
            weights = np.array([w for (w,) in db.execute(
                "SELECT weight FROM particles ORDER BY i")])
            facts: list[tuple[int, str]] = []
            rows = db.execute("SELECT atom, x, y, z, occluder FROM particle_values "
                              "ORDER BY atom, i").fetchall()
        for atom, group in itertools.groupby(rows, key=lambda r: r[0]):
            mine = list(group)
            facts.extend(anchor_particle_facts(
                atom, [None if r[1] is None else r[1:4] for r in mine], [r[4] for r in mine]))
        return (*last, "\n".join([str(row[0]), frame_fact(*last),
                                  *particle_lines(weights, facts)]) + "\n")


def _last_frame(db: sqlite3.Connection) -> tuple[int, float] | None:
    row = db.execute("SELECT frame, time FROM frames ORDER BY frame DESC LIMIT 1").fetchone()
    return None if row is None else (int(row[0]), float(row[1]))


_SOURCE_NAMES = {"scenario": "scenario file", "bag": "bag", "percepts": "percept stream"}


def _version_differences(stored: str, now: str) -> str:
    """``numpy '1.26.4' (this run: '2.0.0')``, for each version that differs."""
    try:
        then = json.loads(stored) if stored else {}
        current = json.loads(now) if now else {}
    except ValueError:
        return f"unreadable versions {stored!r}"
    if not then:
        return "not recorded (a store of an earlier version)" if current else ""
    return "; ".join(f"{k} {then.get(k)!r} (this run: {current.get(k)!r})"
                     for k in sorted(set(then) | set(current)) if then.get(k) != current.get(k))


def _most_probable(occluders: list[Any], weights: np.ndarray, loop: AnchoringLoop
                   ) -> tuple[str | None, float | None]:
    """The occluder with the most particle weight, as a symbol, and that weight."""
    mass: dict[str, float] = {}
    for occ, w in zip(occluders, weights.tolist(), strict=True):
        if occ is not None:
            mass[occ] = mass.get(occ, 0.0) + w
    if not mass:
        return None, None
    best = max(mass, key=lambda o: mass[o])
    assert loop.reasoner is not None
    return loop.reasoner.symbol(best), mass[best]


def _xyz(position: np.ndarray) -> tuple[float | None, ...]:
    return tuple(None if not np.isfinite(v) else float(v) for v in position[:3])


def store_source(scenario: Path | None, bag: Path | None, percepts: Path | None) -> str:
    """The ``source`` meta of a run."""
    for kind, path in (("scenario", scenario), ("bag", bag), ("percepts", percepts)):
        if path is not None:
            return f"{kind}:{Path(path).resolve()}"
    raise ValueError("no source")


def stored_source(meta: dict[str, str]) -> tuple[str, Path]:
    """(kind, path) of a stored run's source."""
    kind, _, path = meta["source"].partition(":")
    return kind, Path(path)




def filter_input_json(outcome: FrameOutcome) -> dict[str, Any]:
    """What the filter was given in a frame, as the store keeps it (``frames.filter_input``):
    the anchors' states, the identity layer's ambiguous percepts and evidence, and the
    revisions it made (checked when a resume replays the frame)."""
    return {
        "states": [[s.symbol, s.category, None if s.position is None else list(s.position)]
                   for s in outcome.states],
        "ambiguous": [{"frame": a.frame, "percept": a.percept_index, "label": a.label,
                       "candidates": list(a.candidates), "appearance": dict(a.appearance),
                       "position": np.asarray(a.position, dtype=float).tolist()}
                      for a in outcome.ambiguous],
        "evidence": list(outcome.evidence),
        "revisions": [r.to_json() for r in outcome.revisions],
    }


def read_filter_input(text: str) -> tuple[list[AnchorState], list[AmbiguousPercept], list[str],
                                          list[dict[str, Any]]]:
    """:func:`filter_input_json` read back."""
    data = json.loads(text)
    states = [AnchorState(s, c, None if p is None else tuple(p)) for s, c, p in data["states"]]
    ambiguous = [AmbiguousPercept(int(a["frame"]), int(a["percept"]), str(a["label"]),
                                  tuple(a["candidates"]),
                                  {str(k): float(v) for k, v in a["appearance"].items()},
                                  np.asarray(a["position"], dtype=float))
                 for a in data.get("ambiguous", [])]
    return states, ambiguous, list(data.get("evidence", [])), list(data.get("revisions", []))
