"""The per-frame loop: perception -> anchoring -> reasoning -> feedback into the anchors."""

from __future__ import annotations

import logging
import time
from collections.abc import Callable, Iterable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from anchoring import AnchorManager, FrameResult, reasoning_position
from anchoring.identity import AmbiguousPercept, Revision
from bridge.engines import Engine
from probanchor.evaluation import (
    FrameTimings,
    Hypothesis,
    TrackingRecord,
    point_estimate,
    record_for_frame,
)
from probanchor.loop.reasoning import (
    DEFAULT_THEORY,
    DEFAULT_THREADS,
    AnchorState,
    OcclusionReasoner,
)
from probanchor.loop.sources import PendingFrame, SourceFrame

logger = logging.getLogger(__name__)

@dataclass
class LoopConfig:
    particles: int = 1000
    theory: Path = DEFAULT_THEORY
    seed: int = 0
    reasoning: bool = True
    # Resample when the effective sample size falls below this fraction of N (the filter's
    # default). The theory gives every perceived object the same position in all particles, so
    # the weights only move on informative events (a hidden object seen again, at the places
    # the particles had it) and resampling happens then, not every frame: hidden objects' modes
    # no longer drift. (With positions sampled per particle, resampling ran nearly every frame
    # for the perceived objects' own noise and randomly thinned the hidden ball's modes.)
    resample_threshold: float = 0.9
    # Prolog threads that step the particles (bridge.Filter's ``threads``): the particles
    # depend on the seed and this number, not on the machine.
    threads: int = DEFAULT_THREADS
    # The filter's engine (bridge.Filter's ``engine``): auto takes the batched one when the
    # theory is in its fragment (prolog/too.pl is), else the per-particle one.
    engine: Engine = "auto"
    # Anchoring may re-identify a percept by appearance alone when it looks like exactly one
    # anchor left over (AnchorManager.reid_seconds); False switches that off, so that only
    # the matcher (and, with reasoning, the particles of hidden anchors) re-acquires.
    reidentify: bool = True
    # Identities of look-alikes kept as hypotheses in the particles and revised by later
    # evidence (anchoring.identity); False decides them once, by the most probable assignment.
    identity: bool = True


@dataclass
class FrameStep:
    """What anchoring and reasoning made of one frame, before its record is written."""

    source: SourceFrame
    result: FrameResult
    hidden: dict[str, tuple[np.ndarray, np.ndarray]]
    timings: FrameTimings
    rejected: int
    states: list[AnchorState] = field(default_factory=list)  # what the filter was given
    # the identity layer's input of the frame (ambiguous percepts) and what it revised
    ambiguous: list[AmbiguousPercept] = field(default_factory=list)
    evidence: list[str] = field(default_factory=list)
    revisions: list[Revision] = field(default_factory=list)
    # hidden anchor -> its belief's occluder symbols and their probabilities
    occluders: dict[str, dict[str, float]] = field(default_factory=dict)


@dataclass
class FrameOutcome:
    """Everything one frame produced, for records, pictures and the world file."""

    source: SourceFrame
    result: FrameResult
    record: TrackingRecord
    hidden_beliefs: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    # the anchors' states the filter stepped on (empty without reasoning): a store replays them
    states: list[AnchorState] = field(default_factory=list)
    # the identity layer's input of the frame and the revisions it made (a store replays them)
    ambiguous: list[AmbiguousPercept] = field(default_factory=list)
    evidence: list[str] = field(default_factory=list)
    revisions: list[Revision] = field(default_factory=list)


class AnchoringLoop:
    """Owns the anchor manager and (with reasoning) the occlusion reasoner for one run."""

    def __init__(self, config: LoopConfig, manager: AnchorManager | None = None) -> None:
        self.config = config
        # (an AnchorManager with no anchors is falsy: compare with None)
        self.manager = manager if manager is not None else (
            AnchorManager() if config.reidentify else AnchorManager(reid_seconds=0))
        self.reasoner = (
            OcclusionReasoner(config.theory, particles=config.particles, seed=config.seed,
                              resample_threshold=config.resample_threshold,
                              threads=config.threads, engine=config.engine)
            if config.reasoning else None
        )
        if manager is None and self.reasoner is not None:
            # a hidden anchor is re-acquired where its theory has it seen again: the blur of
            # its belief's predictive density is the theory's own reappearance spread
            radius = self.reasoner.reappear_radius()
            if radius is not None:
                self.manager.belief_radius = radius
        self.rejected_percepts = 0
        # the anchors the reasoning was told about in the last frame
        self.reasoned_anchors = 0
        # every ambiguous re-acquisition of the run: (frame, percept index, symbol -> P as
        # reported then); identity_answers() gives them as the particles answer them now
        self.ambiguities: list[tuple[int, int, dict[str, float]]] = []
        # every revision of the run, in order
        self.revisions: list[Revision] = []
        self._tracked: set[str] = set()  # the anchors not perceived in the previous frame

    def close(self) -> None:
        if self.reasoner is not None:
            self.reasoner.close()

    def snapshot(self) -> dict[str, Any]:
        """What a store keeps of the loop to resume it (JSON-able): the anchor manager's state
        (``manager``: :meth:`anchoring.AnchorManager.to_json`) and the loop's own counts
        (``loop``: the rejected percepts, the ambiguous re-acquisitions); the filter's
        particles are not in it (a resume replays the frames)."""
        return {"manager": self.manager.to_json(),
                "loop": {"rejected_percepts": self.rejected_percepts,
                         "ambiguities": [[f, i, c] for f, i, c in self.ambiguities]}}

    def restore(self, snapshot: dict[str, Any], revisions: list[Revision],
                source: str = "") -> None:
        """Take the state of a :meth:`snapshot` (as read back from JSON) and the run's
        revisions so far; the filter is not touched (replay the frames' filter input through
        :attr:`reasoner` after this).

        Parameters
        ----------
        snapshot:
            A :meth:`snapshot`, read back from JSON.
        revisions:
            Every revision of the run until then, in order.
        source:
            Where the snapshot was read from, for the errors (a file name).

        Raises
        ------
        KeyError, ValueError, anchoring.manager.AnchorManagerError
            The snapshot is not one; the loop is left as it was.
        """
        manager = AnchorManager.from_json(snapshot["manager"], self.manager.matcher, source)
        counts = snapshot["loop"]
        rejected = int(counts["rejected_percepts"])
        ambiguities = [(int(f), int(i), {str(k): float(v) for k, v in c.items()})
                       for f, i, c in counts["ambiguities"]]
        if not self.config.reidentify:
            manager.reid_seconds = 0
        self.manager = manager
        self.rejected_percepts = rejected
        self.ambiguities = ambiguities
        self.revisions = list(revisions)

    def process(self, source: SourceFrame) -> FrameOutcome:
        """One frame: anchoring and reasoning (:meth:`advance`), then its record."""
        return self.finish(self.advance(source))

    def advance(self, source: SourceFrame) -> FrameStep:
        """Anchoring and reasoning on one frame's percepts (the timed work of the loop)."""
        frame = source.percepts
        started = time.perf_counter()
        result = self.manager.process(frame.time, frame.percepts)
        anchoring_ms = (time.perf_counter() - started) * 1000
        rejected = len(frame.rejected) + len(result.rejected)
        self.rejected_percepts += rejected
        for rejection in result.rejected:
            logger.warning("frame %d: percept %d dropped: %s", frame.frame,
                           rejection.percept_index, rejection.reason)

        filter_ms = 0.0
        hidden: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        states: list[AnchorState] = []
        ambiguous: list[AmbiguousPercept] = []
        evidence: list[str] = []
        revisions: list[Revision] = []
        occluders: dict[str, dict[str, float]] = {}
        if self.reasoner is not None:
            started = time.perf_counter()
            # (a hand's position is its grip point: what it holds is there)
            perceived = {a.symbol: reasoning_position(frame.percepts[a.percept_index])
                         for a in result.assignments}
            # only confirmed anchors (perceived in two frames) are reasoned about: an anchor
            # seen once may be a spurious percept, and a flood of them would make the theory
            # of occlusion, pairwise in the objects, cost seconds per frame
            confirmed = [anchor for anchor in self.manager.anchors if anchor.confirmed]
            states = [
                AnchorState(anchor.symbol, anchor.best_category,
                            tuple(perceived[anchor.symbol]) if anchor.symbol in perceived
                            else None)
                for anchor in confirmed
            ]
            given = result.symbols
            ambiguous = [AmbiguousPercept(frame.frame, a.percept_index, given[a.percept_index],
                                          tuple(a.candidates), dict(a.appearance),
                                          np.asarray(frame.percepts[a.percept_index].position,
                                                     dtype=float))
                         for a in result.ambiguous]
            # seen again after being hidden: what may decide an earlier ambiguity
            evidence = sorted(s for s in result.reacquired if s in self._tracked)
            revisions = self.reasoner.reason(
                states, ambiguous if self.config.identity else [], frame.frame, evidence)
            for revision in revisions:
                self.revise(result, revision)
            self.reasoned_anchors = len(states)
            reasoned = {anchor.symbol for anchor in self.manager.anchors if anchor.confirmed}
            others = sorted(reasoned)
            for symbol in result.tracked:
                if symbol not in reasoned:
                    continue
                belief = self.reasoner.belief(symbol, others)
                if belief is not None:
                    self.manager.set_position_particles(symbol, belief.positions,
                                                        belief.weights, belief.occluded)
                    hidden[symbol] = (belief.positions, belief.weights)
                    occluders[symbol] = belief.occluders()
            filter_ms = (time.perf_counter() - started) * 1000
        self._tracked = set(result.tracked)
        return FrameStep(source, result, hidden,
                         FrameTimings(perception=source.perception_ms, anchoring=anchoring_ms,
                                      filter=filter_ms),
                         rejected, states, ambiguous, evidence, revisions, occluders)

    def revise(self, result: FrameResult, revision: Revision) -> None:
        """Later evidence decided an earlier ambiguity otherwise: the anchors are renamed
        (:meth:`anchoring.AnchorManager.relabel`), and so is this frame's result, so that its
        record already gives the revised symbols."""
        mapping = revision.mapping
        self.manager.relabel(mapping)
        for assignment in result.assignments:
            assignment.symbol = mapping.get(assignment.symbol, assignment.symbol)
        result.tracked = [mapping.get(s, s) for s in result.tracked]
        for ambiguity in result.ambiguous:
            ambiguity.candidates = {mapping.get(s, s): p for s, p in ambiguity.candidates.items()}
            ambiguity.appearance = {mapping.get(s, s): v for s, v in ambiguity.appearance.items()}
        self.revisions.append(revision)
        logger.info("frame %d: identities revised %s (probability %.3f, was %.3f; evidence %s)",
                    revision.frame, revision.mapping, revision.probability, revision.before,
                    ", ".join(revision.evidence) or "none")

    def identity_answers(self) -> list[tuple[int, int, dict[str, float]]]:
        """Every ambiguous re-acquisition of the run, (frame, percept index, symbol -> P), the
        probabilities as the particles answer them now (after every revision); as reported
        at the time without reasoning."""
        if self.reasoner is None:
            return list(self.ambiguities)
        identity = self.reasoner.identity
        answered = {(a.frame, a.percept_index): identity.percept_probabilities(k)
                    for k, a in enumerate(identity.percepts)}
        return [(f, i, answered.get((f, i), c)) for f, i, c in self.ambiguities]

    def finish(self, step: FrameStep) -> FrameOutcome:
        """The frame's tracking record (hypotheses and matches for the evaluation), from the
        anchors as :meth:`advance` left them."""
        frame, result = step.source.percepts, step.result
        self.ambiguities.extend((frame.frame, a.percept_index, a.candidates)
                                for a in result.ambiguous)
        record = record_for_frame(
            frame,
            self.hypotheses(result, step.occluders),
            [(frame.percepts[a.percept_index], a.symbol) for a in result.assignments],
            step.timings,
            rejected_percepts=step.rejected,
            ambiguous={result.symbols[a.percept_index]: a.candidates
                       for a in result.ambiguous},
        )
        record.revised = [r.to_json() for r in step.revisions]
        return FrameOutcome(step.source, result, record, step.hidden, step.states,
                            step.ambiguous, step.evidence, step.revisions)

    def hypotheses(self, result: FrameResult,
                   occluders: dict[str, dict[str, float]] | None = None
                   ) -> dict[str, Hypothesis]:
        perceived = {a.symbol for a in result.assignments}
        occluders = occluders or {}
        out: dict[str, Hypothesis] = {}
        for anchor in self.manager.anchors:
            attribute = anchor.position
            if attribute.is_probabilistic:
                position = point_estimate(attribute.samples, attribute.weights)
            else:
                position = np.asarray(attribute.mean(), dtype=float)
            out[anchor.symbol] = Hypothesis(position=position,
                                            perceived=anchor.symbol in perceived,
                                            occluders=occluders.get(anchor.symbol))
        return out


def run_frames(frames: Iterable[PendingFrame], loop: AnchoringLoop,
               on_frame: Callable[[FrameOutcome, AnchoringLoop], None] | None = None,
               overlap: bool = True, records: list[TrackingRecord] | None = None
               ) -> list[TrackingRecord]:
    """Play frames through ``loop``; ``on_frame`` sees each outcome (pictures, progress).
    The records are appended to ``records`` (a new list if None) as the frames are done, so
    a caller keeps those of the frames before an error.

    With ``overlap``, the next frame is perceived (in a second Python thread) while the loop
    anchors and reasons about the current one: perception needs nothing of the anchors, and
    the filter's Prolog threads leave the machine's cores partly idle (the first particle,
    the copies to and from the worker thread, the belief reads).  Each record's
    ``timings.total`` is then the wall-clock time of its stage: from the moment the camera's
    next frame is there to the moment both that frame's percepts and this frame's anchors and
    beliefs are (the first frame's stage also counts its own perception, which nothing
    overlaps).  The frame rate is 1000 / the mean total; the parts (perception, anchoring,
    filter) are each timed on their own, so with ``overlap`` they add up to more than the
    total.  Without ``overlap`` each frame is perceived just before it is processed and the
    total is the sum of the parts.  Rendering (the simulator), the records (bookkeeping for
    the evaluation) and ``on_frame`` (pictures) are outside every stage.
    """
    records = [] if records is None else records
    pending = iter(frames)
    first = next(pending, None)
    if first is None:
        return records
    started = time.perf_counter()
    current: SourceFrame | None = first()
    lead_ms = (time.perf_counter() - started) * 1000
    with ThreadPoolExecutor(max_workers=1, thread_name_prefix="perception") as perception:
        while current is not None:
            upcoming = next(pending, None)          # the camera's next frame (rendered)
            started = time.perf_counter()
            future = (perception.submit(upcoming)
                      if overlap and upcoming is not None else None)
            step = loop.advance(current)
            if future is not None:
                following: SourceFrame | None = future.result()
                step.timings.total = (time.perf_counter() - started) * 1000 + lead_ms
                lead_ms = 0.0
            else:                                   # total: the sum of the parts
                following = upcoming() if upcoming is not None else None
                # recorded, not left None: the last frame's stage with overlap is its own work
                step.timings.total = ((time.perf_counter() - started) * 1000 + lead_ms
                                      if overlap else step.timings.total_ms())
            outcome = loop.finish(step)
            records.append(outcome.record)
            if on_frame is not None:
                on_frame(outcome, loop)
            current = following
    return records
