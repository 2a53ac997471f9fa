"""Probabilistic multi-target trackers of Stone Soup run on the same percepts, for comparison.

Two trackers from Stone Soup (``stonesoup``, the Python framework of the target-tracking field),
both on the percepts' 3-D positions (``Percept.position``, metres) as measurements:

- ``stonesoup-jpda``: joint probabilistic data association. Stone Soup's
  ``MultiTargetMixtureTracker`` with ``JPDAwithEHM`` (exact JPDA marginals computed with
  efficient hypothesis management) over a ``PDAHypothesiser``: each track's posterior is the
  mixture of its update with every gated percept and its prediction (missed detection), weighed by
  the joint association probabilities and reduced to one Gaussian.
- ``stonesoup-mht``: multi-hypothesis tracking by multi-frame assignment (MFA, Xia et al. 2019),
  Stone Soup's MHT: ``MFAHypothesiser`` over the same ``PDAHypothesiser`` and
  ``MFADataAssociator``, which keeps each track's association hypotheses over a sliding window
  of ``slide_window`` frames and prunes them to the best global assignment (N-scan pruning).
  Stone Soup has no tracker class for MFA (its own example writes the loop out); the loop here
  adds births and deaths as below.

Common to both: a constant-velocity Kalman model in 3-D (Stone Soup's ``ConstantVelocity``
per axis, process noise ``process_noise`` in m^2/s^3), a linear Gaussian measurement of the
position (standard deviation ``measurement_noise`` in metres per axis), detection probability
``prob_detect``, gate probability ``prob_gate`` and clutter density ``clutter_density`` (false
percepts per cubic metre per frame). A percept that no track takes starts a track at its position
with zero velocity (standard deviation ``initial_speed`` m/s per axis). A track that has taken
no percept for ``lost_seconds`` (60 s by default, the patience of the other baselines) is
deleted; until then it coasts on its Kalman prediction, its covariance growing, so a percept
far from where it was lost can still be given to it.

What the metrics see (:class:`~probanchor.evaluation.record.TrackingRecord`): a track of method
``m`` numbered ``k`` (in order of birth) is the symbol ``"m-k"``; its hypothesis is its posterior
mean position, ``perceived`` when it took a percept this frame. The percept a JPDA track took is
its most probable association when that is more probable than a missed detection (Stone Soup's
own rule for an update). For MFA, each track's reported hypothesis (its estimate, and the percept
it took this frame) is chosen among the hypotheses MFA kept, the most probable first, so that no
two tracks' choices share a percept anywhere in MFA's window.

The settings are tuned on generated shell games that the evaluation does not use
(:mod:`probanchor.evaluation.stonesoup_tuning`, docs/evaluation.md); :data:`TUNED` holds the
best found so far. Stone Soup, and OR-Tools for MFA,
are the ``stonesoup`` extra of the project (``scripts/setup.sh`` installs it).
"""

from __future__ import annotations

import datetime as _dt
import math
import time as _time
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from probanchor.evaluation.record import FrameTimings, Hypothesis, TrackingRecord, record_for_frame
from probanchor.percepts import Percept, PerceptFrame

STONESOUP = ("stonesoup-jpda", "stonesoup-mht")
NAMES = {"stonesoup-jpda": "Stone Soup JPDA", "stonesoup-mht": "Stone Soup MHT (MFA)"}
_EPOCH = _dt.datetime(2000, 1, 1)


class StoneSoupError(ValueError):
    """A Stone Soup baseline that cannot run (unknown method, bad settings, bad frames, or Stone
    Soup not installed)."""


@dataclass(frozen=True)
class StoneSoupSettings:
    """The tunable settings of a Stone Soup tracker (see the module doc for their meaning).

    Parameters
    ----------
    process_noise : float
        Constant-velocity model's noise intensity q per axis, m^2/s^3.
    measurement_noise : float
        Standard deviation of a percept's position per axis, metres.
    prob_detect : float
        Probability that an object present gives a percept in a frame, in (0, 1).
    prob_gate : float
        Probability that a track's gate holds its object's percept, in (0, 1).
    clutter_density : float
        False percepts per cubic metre per frame (> 0). The simulated perception makes almost
        none (none in 2,271 frames of seven streams, shipped scenarios and games): 0.01.
    initial_speed : float
        Standard deviation of a new track's speed per axis, m/s.
    slide_window : int
        Frames in MFA's sliding window (MHT only), at least 1.
    """

    process_noise: float = 0.01
    measurement_noise: float = 0.01
    prob_detect: float = 0.9
    prob_gate: float = 0.999
    clutter_density: float = 0.01
    initial_speed: float = 0.1
    slide_window: int = 3

    def __post_init__(self) -> None:
        for name in ("process_noise", "measurement_noise", "clutter_density", "initial_speed"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise StoneSoupError(f"{name} must be a positive number, got {value!r}")
        for name in ("prob_detect", "prob_gate"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and 0 < value < 1):
                raise StoneSoupError(f"{name} must be a probability in (0, 1), got {value!r}")
        if isinstance(self.slide_window, bool) or not isinstance(self.slide_window, int) \
                or self.slide_window < 1:
            raise StoneSoupError(f"slide_window must be a positive integer, got "
                                 f"{self.slide_window!r}")

    def replace(self, **changes: Any) -> StoneSoupSettings:
        """A copy with ``changes`` (names checked)."""
        known = {f.name for f in fields(self)}
        unknown = sorted(set(changes) - known)
        if unknown:
            raise StoneSoupError(f"unknown Stone Soup settings {unknown}; known: "
                                 f"{', '.join(sorted(known))}")
        values = {f.name: getattr(self, f.name) for f in fields(self)}
        values.update(changes)
        return StoneSoupSettings(**values)


#: The settings each tracker runs with: JPDA's, the best of the grid search of
#: :mod:`probanchor.evaluation.stonesoup_tuning` as far as it has run (all three tuning games);
#: MHT's, the same until its own search has run (its first runs were made before the choice of
#: its reported hypothesis was made consistent over MFA's window, docs/evaluation.md). Run the
#: search to its end (``anchoring baselines --tune --games 3 --jobs 2 --out DIR``) and put its
#: best here before a results table is published.
TUNED: dict[str, StoneSoupSettings] = {
    "stonesoup-jpda": StoneSoupSettings(process_noise=0.1, measurement_noise=0.01,
                                        prob_gate=0.9999),
    "stonesoup-mht": StoneSoupSettings(process_noise=0.1, measurement_noise=0.01,
                                       prob_gate=0.9999),
}


def _stonesoup() -> Any:
    try:
        import stonesoup  # noqa: F401
    except ImportError as exc:  # pragma: no cover - setup installs it
        raise StoneSoupError(
            "the 'stonesoup' package is missing: run `make setup` (scripts/setup.sh installs the "
            "project's 'stonesoup' extra: pip install -e '.[stonesoup]')") from exc
    return stonesoup


def _timestamp(seconds: float) -> _dt.datetime:
    return _EPOCH + _dt.timedelta(seconds=float(seconds))


@dataclass
class _Models:
    """The Kalman components shared by both trackers."""

    transition: Any
    measurement: Any
    predictor: Any
    updater: Any
    hypothesiser: Any
    prior_covar: np.ndarray


def _models(settings: StoneSoupSettings) -> _Models:
    _stonesoup()
    from stonesoup.hypothesiser.probability import PDAHypothesiser
    from stonesoup.models.measurement.linear import LinearGaussian
    from stonesoup.models.transition.linear import (
        CombinedLinearGaussianTransitionModel,
        ConstantVelocity,
    )
    from stonesoup.predictor.kalman import KalmanPredictor
    from stonesoup.updater.kalman import KalmanUpdater

    transition = CombinedLinearGaussianTransitionModel(
        [ConstantVelocity(settings.process_noise) for _ in range(3)])
    measurement = LinearGaussian(ndim_state=6, mapping=(0, 2, 4),
                                 noise_covar=np.eye(3) * settings.measurement_noise ** 2)
    predictor = KalmanPredictor(transition)
    updater = KalmanUpdater(measurement)
    hypothesiser = PDAHypothesiser(predictor=predictor, updater=updater,
                                   clutter_spatial_density=settings.clutter_density,
                                   prob_detect=settings.prob_detect,
                                   prob_gate=settings.prob_gate)
    variances = np.tile([settings.measurement_noise ** 2, settings.initial_speed ** 2], 3)
    return _Models(transition, measurement, predictor, updater, hypothesiser,
                   np.diag(variances))


def _detections(frame: PerceptFrame, models: _Models) -> list[Any]:
    """One Stone Soup detection per percept (its index in ``metadata``)."""
    from stonesoup.types.detection import Detection

    when = _timestamp(frame.time)
    return [Detection(np.asarray(p.position, dtype=float).reshape(3, 1), timestamp=when,
                      measurement_model=models.measurement, metadata={"index": i})
            for i, p in enumerate(frame.percepts)]


def _position(mean: Any) -> np.ndarray:
    return np.asarray(mean, dtype=float).reshape(-1)[[0, 2, 4]].copy()


def _check_frames(frames: Sequence[PerceptFrame]) -> None:
    last = -math.inf
    for fr in frames:
        if not math.isfinite(fr.time) or fr.time < last:
            raise StoneSoupError(f"frame {fr.frame}: time {fr.time} is not after the previous "
                                 f"frame's ({last}); a tracker needs frames in time order")
        last = fr.time
        for i, p in enumerate(fr.percepts):
            pos = np.asarray(p.position, dtype=float).reshape(-1)
            if pos.shape != (3,) or not np.all(np.isfinite(pos)):
                raise StoneSoupError(f"frame {fr.frame}: percept {i} has no finite 3-D position")


class _Numbering:
    """Symbols ``"m-1"``, ``"m-2"``... in order of birth (tracks born in one frame: in the order
    of their percepts), so that a run gives the same symbols every time."""

    def __init__(self, method: str) -> None:
        self.method = method
        self.symbols: dict[Any, str] = {}

    def name(self, tracks: Iterable[Any], first_index: Any) -> None:
        for track in sorted((t for t in tracks if t not in self.symbols), key=first_index):
            self.symbols[track] = f"{self.method}-{len(self.symbols) + 1}"


def run_stonesoup(
    method: str,
    frames: Iterable[PerceptFrame],
    *,
    lost_seconds: float = 60.0,
    settings: StoneSoupSettings | None = None,
    ignore: Iterable[str] = (),
) -> list[TrackingRecord]:
    """Run one Stone Soup tracker over a percept stream; one record per frame.

    Parameters
    ----------
    method : str
        ``"stonesoup-jpda"`` or ``"stonesoup-mht"``.
    frames : iterable of PerceptFrame
        The percept stream, in time order.
    lost_seconds : float
        A track that took no percept for this long is deleted.
    settings : StoneSoupSettings, optional
        The tracker's settings (default: :data:`TUNED` for ``method``).
    ignore : iterable of str
        Ground-truth ids left out of the evaluation (e.g. a hand).

    Returns
    -------
    list of TrackingRecord

    Raises
    ------
    StoneSoupError
        Unknown method, ``lost_seconds`` not positive, frames out of time order or a percept
        without a finite position (naming the frame), Stone Soup not installed.
    """
    if method not in STONESOUP:
        raise StoneSoupError(f"unknown Stone Soup tracker {method!r}; known: "
                             f"{', '.join(STONESOUP)}")
    if not (isinstance(lost_seconds, (int, float)) and lost_seconds > 0):
        raise StoneSoupError(f"lost_seconds must be positive, got {lost_seconds!r}")
    frames = list(frames)
    _check_frames(frames)
    settings = settings if settings is not None else TUNED[method]
    models = _models(settings)
    step = _JPDA(method, models, lost_seconds) if method == "stonesoup-jpda" \
        else _MFA(method, models, lost_seconds, settings.slide_window)
    ignore = tuple(ignore)
    records = []
    for fr in frames:
        start = _time.perf_counter()
        with warnings.catch_warnings():
            # MFA notes when it solves a window's full problem instead of its subproblems'
            # (a fallback, not an error): it would fill a long run's log
            warnings.filterwarnings("ignore", message="Infeasible primal problem")
            hyps, matches = step(fr)
        elapsed = (_time.perf_counter() - start) * 1000.0
        records.append(record_for_frame(fr, hyps, matches, FrameTimings(anchoring=elapsed),
                                        ignore))
    return records


FrameResult = tuple[dict[str, Hypothesis], list[tuple[Percept, str]]]


class _JPDA:
    """Stone Soup's MultiTargetMixtureTracker with JPDA (EHM), one frame per call."""

    def __init__(self, method: str, models: _Models, lost_seconds: float) -> None:
        from stonesoup.dataassociator.probability import JPDAwithEHM
        from stonesoup.deleter.time import UpdateTimeDeleter
        from stonesoup.initiator.simple import SimpleMeasurementInitiator
        from stonesoup.tracker.simple import MultiTargetMixtureTracker
        from stonesoup.types.state import GaussianState

        initiator = SimpleMeasurementInitiator(
            prior_state=GaussianState(np.zeros((6, 1)), models.prior_covar),
            measurement_model=models.measurement)
        self.tracker = MultiTargetMixtureTracker(
            initiator=initiator,
            deleter=UpdateTimeDeleter(_dt.timedelta(seconds=lost_seconds)),
            detector=None,
            data_associator=JPDAwithEHM(models.hypothesiser),
            updater=models.updater)
        self.models = models
        self.numbering = _Numbering(method)

    def __call__(self, frame: PerceptFrame) -> FrameResult:
        from stonesoup.types.update import Update

        detections = _detections(frame, self.models)
        _, tracks = self.tracker.update_tracker(_timestamp(frame.time), set(detections))
        self.numbering.name(tracks, _first_index)
        hyps: dict[str, Hypothesis] = {}
        matches: list[tuple[Percept, str]] = []
        for track in tracks:
            symbol = self.numbering.symbols[track]
            state = track.state
            taken = _taken_by_jpda(state) if isinstance(state, Update) else None
            hyps[symbol] = Hypothesis(_position(state.state_vector), taken is not None)
            if taken is not None:
                matches.append((frame.percepts[taken], symbol))
        return hyps, matches


def _first_index(track: Any) -> int:
    """The index of the percept that started a track (for the order of names)."""
    hypothesis = getattr(track.states[0], "hypothesis", None)
    measurement = getattr(hypothesis, "measurement", None)
    return int(getattr(measurement, "metadata", {}).get("index", 0))


def _taken_by_jpda(update: Any) -> int | None:
    """The percept index a JPDA track took this frame: its most probable association, when that
    is a percept (a new track: the percept it started from)."""
    hypothesis = update.hypothesis
    if hasattr(hypothesis, "measurement"):  # a new track's single hypothesis
        return int(hypothesis.measurement.metadata["index"])
    best = max(hypothesis, key=lambda h: float(h.probability))
    return int(best.measurement.metadata["index"]) if best else None


class _MFA:
    """Stone Soup's MFA data association in the loop of its MHT example, with births from the
    percepts no track took and deaths after ``lost_seconds`` without a percept."""

    def __init__(self, method: str, models: _Models, lost_seconds: float,
                 slide_window: int) -> None:
        try:
            from stonesoup.dataassociator.mfa import MFADataAssociator
        except ImportError as exc:  # pragma: no cover - setup installs it
            raise StoneSoupError(
                "Stone Soup's MFA needs OR-Tools ('ortools'): run `make setup` (the project's "
                "'stonesoup' extra)") from exc
        from stonesoup.hypothesiser.mfa import MFAHypothesiser

        self.associator = MFADataAssociator(MFAHypothesiser(models.hypothesiser),
                                            slide_window=slide_window)
        self.window = slide_window
        self.models = models
        self.lost = _dt.timedelta(seconds=lost_seconds)
        self.numbering = _Numbering(method)
        self.tracks: list[Any] = []  # in order of birth
        self.last_taken: dict[Any, _dt.datetime] = {}
        self.first_index: dict[Any, int] = {}

    def __call__(self, frame: PerceptFrame) -> FrameResult:
        from stonesoup.types.update import GaussianMixtureUpdate

        when = _timestamp(frame.time)
        detections = _detections(frame, self.models)
        hyps: dict[str, Hypothesis] = {}
        matches: list[tuple[Percept, str]] = []
        taken: set[int] = set()
        if self.tracks:
            association = self.associator.associate(set(self.tracks), set(detections), when)
            kept = [association[track] for track in self.tracks]
            chosen = _assign(kept, self.window)
            for track, options, pick in zip(self.tracks, kept, chosen, strict=True):
                components = [self.models.updater.update(h) if h else h.prediction
                              for h in options]
                track.append(GaussianMixtureUpdate(components=components, hypothesis=options))
                best = options[pick]
                symbol = self.numbering.symbols[track]
                state = components[pick]
                if best:
                    index = int(best.measurement.metadata["index"])
                    taken.add(index)
                    matches.append((frame.percepts[index], symbol))
                    self.last_taken[track] = when
                hyps[symbol] = Hypothesis(_position(state.state_vector), bool(best))
            for track in [t for t in self.tracks if when - self.last_taken[t] > self.lost]:
                self.tracks.remove(track)
                del hyps[self.numbering.symbols[track]]
        born = [self._birth(d, when) for d in detections if d.metadata["index"] not in taken]
        self.numbering.name(born, self.first_index.__getitem__)
        for track in born:
            index = self.first_index[track]
            symbol = self.numbering.symbols[track]
            hyps[symbol] = Hypothesis(np.asarray(frame.percepts[index].position, float), True)
            matches.append((frame.percepts[index], symbol))
        return hyps, matches

    def _birth(self, detection: Any, when: _dt.datetime) -> Any:
        from stonesoup.types.mixture import GaussianMixture
        from stonesoup.types.numeric import Probability
        from stonesoup.types.state import TaggedWeightedGaussianState
        from stonesoup.types.track import Track

        mean = np.zeros((6, 1))
        mean[[0, 2, 4], 0] = np.asarray(detection.state_vector, float).reshape(-1)
        track = Track([GaussianMixture([TaggedWeightedGaussianState(
            mean, self.models.prior_covar, timestamp=when, weight=Probability(1), tag=[])])])
        self.tracks.append(track)
        self.last_taken[track] = when
        self.first_index[track] = int(detection.metadata["index"])
        return track


def _assign(options: Sequence[Sequence[Any]], window: int) -> list[int]:
    """Per track, the index of the hypothesis reported for it: the most probable choices that
    are consistent over MFA's window (no two tracks' chosen hypotheses give the same percept to
    both in any of the last ``window`` frames), taken greedily from the most probable down.

    A hypothesis's ``prediction.tag`` is its track's percept history (one index per frame since
    the track's birth, 1-based in that frame's detections, 0 for none), aligned from the end.
    The weights are per track: a branch that took another track's percept two frames ago can
    weigh most in its own track while the window's global assignment has ruled it out, so the
    current frame alone is not enough.
    """
    ranked = sorted(((float(h.prediction.weight), row, k)
                     for row, hyps in enumerate(options) for k, h in enumerate(hyps)),
                    key=lambda c: (-c[0], c[1], c[2]))
    picks: list[int | None] = [None] * len(options)
    used: set[tuple[int, int]] = set()  # (frames back, percept) given to a track
    for _, row, k in ranked:
        if picks[row] is not None:
            continue
        tag = list(options[row][k].prediction.tag)
        marks = {(back, int(tag[-back])) for back in range(1, min(window, len(tag)) + 1)
                 if tag[-back]}
        if marks & used:
            continue
        picks[row] = k
        used |= marks
    # (a track all of whose hypotheses conflict: its most probable; MFA keeps a consistent one)
    def best(row: int) -> int:
        return max(range(len(options[row])), key=lambda i: float(options[row][i].prediction.weight))

    return [k if k is not None else best(row) for row, k in enumerate(picks)]
