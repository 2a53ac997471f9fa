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
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import sqlite3
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from anchoring import AnchorManager
from anchoring.manager import AnchorManagerError
from probanchor.app.loop import AnchoringLoop, FrameOutcome
from probanchor.app.naming import symbol_atom
from probanchor.app.reasoning import AnchorState
from probanchor.app.world_file import anchor_particle_facts, particle_lines, world_facts
from probanchor.evaluation import TrackingRecord

FORMAT = "anchoring-store 1"

SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS frames (
    frame INTEGER PRIMARY KEY, time REAL NOT NULL,
    filter_input TEXT NOT NULL,   -- JSON [[symbol, category, [x, y, z] or null], ...]
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
            "resample_threshold", "theory_sha1")


#: how the stored text of each run option that a resumed run takes from its store is read back
_STORED_OPTION: dict[str, Any] = {
    "particles": int, "seed": int, "threads": int, "engine": str, "theory": Path,
    "reasoning": lambda text: text == "True", "reidentify": lambda text: text == "True",
    "resample_threshold": float,
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


class StoreError(ValueError):
    """A store that cannot be written or resumed; the message names the file and the cause."""


def theory_digest(path: Path) -> str:
    """The SHA-1 of a theory file's bytes."""
    return hashlib.sha1(path.read_bytes()).hexdigest()


def run_meta(source: str, options: Any) -> dict[str, str]:
    """What identifies a run, as the store's ``meta`` rows.

    Parameters
    ----------
    source:
        ``scenario:PATH``, ``bag:PATH`` or ``percepts:PATH`` (absolute paths).
    options:
        The run's :class:`probanchor.app.runner.RunOptions`.

    Returns
    -------
    Key -> text.
    """
    return {
        "format": FORMAT, "source": source, "particles": str(options.particles),
        "seed": str(options.seed), "threads": str(options.threads),
        "engine": str(options.engine), "reasoning": str(bool(options.reasoning)),
        "reidentify": str(bool(options.reidentify)),
        "resample_threshold": repr(float(options.resample_threshold)),
        "theory": str(options.theory),
        "theory_sha1": theory_digest(options.theory) if options.reasoning else "",
    }


@dataclass
class StoredRun:
    """What a resumed run starts from."""

    next_frame: int
    records: list[TrackingRecord]


class WorldStore:
    """One run's world model in an SQLite file."""

    def __init__(self, path: Path, connection: sqlite3.Connection) -> None:
        self.path = path
        self.db = connection

    # ------------------------------------------------------------------ opening
    @classmethod
    def create(cls, path: Path, meta: dict[str, str]) -> WorldStore:
        """A new store for a run; an existing store that holds frames is never overwritten.

        Parameters
        ----------
        path:
            The database file (created with its folder).
        meta:
            :func:`run_meta` of the run.

        Returns
        -------
        The store, ready for :meth:`write_frame`.
        """
        store = cls._connect(path)
        if store._has_schema() and store._count("frames"):
            n = store._count("frames")
            store.close()
            raise StoreError(f"{path}: already holds a run of {n} frames; continue it with "
                             "--resume, or give another file")
        with store.db:
            store.db.executescript(SCHEMA)
            store.db.execute("DELETE FROM meta")
            store.db.executemany("INSERT INTO meta VALUES (?, ?)", sorted(meta.items()))
        return store

    @classmethod
    def open(cls, path: Path) -> WorldStore:
        """An existing store, checked to be one (for resuming or reading).

        Parameters
        ----------
        path:
            The database file.

        Returns
        -------
        The store; a :class:`StoreError` naming the file for a missing or unreadable file or
        a database that is not an anchoring store.
        """
        if not path.is_file():
            raise StoreError(f"{path}: no such store")
        store = cls._connect(path)
        try:
            meta = store.meta()
        except StoreError:
            store.close()
            raise
        if meta.get("format") != FORMAT:
            store.close()
            raise StoreError(f"{path}: not an anchoring store (format "
                             f"{meta.get('format', 'missing')!r}, expected {FORMAT!r})")
        return store

    @classmethod
    def _connect(cls, path: Path) -> WorldStore:
        path.parent.mkdir(parents=True, exist_ok=True)
        try:
            db = sqlite3.connect(path, timeout=30)
            db.execute("PRAGMA journal_mode=WAL")   # readers while a run writes
            db.execute("PRAGMA synchronous=NORMAL")
        except sqlite3.DatabaseError as exc:
            raise StoreError(f"{path}: not a readable SQLite store: {exc}") from None
        return cls(path, db)

    def close(self) -> None:
        self.db.close()

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
        inputs = [[s.symbol, s.category, None if s.position is None else list(s.position)]
                  for s in outcome.states]
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
        loop_state = {"rejected_percepts": loop.rejected_percepts,
                      "ambiguities": [[f, i, c] for f, i, c in loop.ambiguities]}
        with self.db:
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
                ("manager", json.dumps(loop.manager.to_json())),
                ("loop", json.dumps(loop_state)),
                ("world", "\n".join(world_facts(loop, perceived,
                                                 particles=(np.ones(0), [])))),
            ])

    @staticmethod
    def _particle_values(loop: AnchoringLoop
                         ) -> tuple[np.ndarray, dict[str, tuple[np.ndarray, list[Any]]]]:
        """The weights, and per anchor its position (N x 3, NaN: none) and occluder (None:
        none) in every particle."""
        if loop.reasoner is None:
            return np.ones(0), {}
        f = loop.reasoner.filter
        out = {}
        for anchor in loop.manager.anchors:
            atom = symbol_atom(anchor.symbol)
            positions, _ = f.samples(f"pos({atom}):t")
            positions = np.asarray(positions, dtype=float).reshape(f.particles, -1)
            if positions.shape[1] != 3:
                positions = np.full((f.particles, 3), np.nan)
            occluders = [None if o is None else str(o)
                         for o in f.values("O", f"occluded_by({atom}, O):t")]
            out[anchor.symbol] = (positions, occluders)
        return f.weights, out

    # ------------------------------------------------------------------ resuming
    def check_resumable(self, meta: dict[str, str]) -> None:
        """A :class:`StoreError` when the run to resume is not the stored one (another
        source, theory, number of particles, ...) or nothing was stored."""
        stored = self.meta()
        if stored.get("theory_sha1") and meta.get("theory_sha1") != stored["theory_sha1"]:
            raise StoreError(f"{self.path}: a store from another theory: it was written with "
                             f"{stored.get('theory')} as it was then (sha1 "
                             f"{stored['theory_sha1'][:12]}), this run's theory "
                             f"{meta.get('theory')} differs; resume with that theory")
        wrong = [f"{k} {stored.get(k)!r} (this run: {meta.get(k)!r})" for k in RUN_KEYS
                 if k != "theory_sha1" and stored.get(k) != meta.get(k)]
        if wrong:
            raise StoreError(f"{self.path}: not this run's store: it has " + "; ".join(wrong))
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
        rows = self.db.execute("SELECT frame, filter_input, record FROM frames ORDER BY frame"
                               ).fetchall()
        state = dict(self.db.execute("SELECT key, value FROM state").fetchall())
        try:
            manager = AnchorManager.from_json(json.loads(state["manager"]),
                                              loop.manager.matcher, str(self.path))
            loop_state = json.loads(state["loop"])
            records = [TrackingRecord.from_json(json.loads(r)) for _, _, r in rows]
        except (KeyError, ValueError, AnchorManagerError) as exc:
            raise StoreError(f"{self.path}: the stored world model cannot be read: {exc}"
                             ) from None
        if not loop.config.reidentify:
            manager.reid_seconds = 0
        loop.manager = manager
        loop.rejected_percepts = int(loop_state["rejected_percepts"])
        loop.ambiguities = [(int(f), int(i), {str(k): float(v) for k, v in c.items()})
                            for f, i, c in loop_state["ambiguities"]]
        if loop.reasoner is not None:
            for _, inputs, _ in rows:
                loop.reasoner.step([AnchorState(s, c, None if p is None else tuple(p))
                                    for s, c, p in json.loads(inputs)])
            stored = np.array([w for (w,) in self.db.execute(
                "SELECT weight FROM particles ORDER BY i")])
            if stored.shape != loop.reasoner.filter.weights.shape or not np.allclose(
                    stored, loop.reasoner.filter.weights, rtol=1e-9, atol=1e-12):
                raise StoreError(f"{self.path}: replaying the stored frames did not give the "
                                 "stored particles (another engine or SWI-Prolog?)")
            last = records[-1]
            for symbol, hyp in last.hypotheses.items():
                belief = None if hyp.perceived else loop.reasoner.belief(symbol)
                if belief is not None:
                    manager.set_position_particles(symbol, belief.positions, belief.weights)
        return StoredRun(int(rows[-1][0]) + 1, records)

    def world_text(self) -> str:
        """The world model after the last frame as the Prolog facts of a world file
        (``prolog/world.pl``), the particles' from ``particles`` and ``particle_values``."""
        row = self.db.execute("SELECT value FROM state WHERE key = 'world'").fetchone()
        if row is None:
            raise StoreError(f"{self.path}: holds no frame yet")
        weights = np.array([w for (w,) in self.db.execute(
            "SELECT weight FROM particles ORDER BY i")])
        facts: list[tuple[int, str]] = []
        for (atom,) in self.db.execute("SELECT DISTINCT atom FROM particle_values ORDER BY atom"
                                       ).fetchall():
            rows = self.db.execute("SELECT x, y, z, occluder FROM particle_values WHERE atom = ?"
                                   " ORDER BY i", (atom,)).fetchall()
            facts.extend(anchor_particle_facts(
                atom, [None if r[0] is None else r[:3] for r in rows], [r[3] for r in rows]))
        return "\n".join([str(row[0]), *particle_lines(weights, facts)]) + "\n"


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


