"""Before/after facts of occlusions for the structure learner (paper, section 4 and 5.2).

From each episode (:mod:`probanchor.learning.experience`), for each pair of consecutive frames
t, t+1, each anchor A hidden at t+1 (not perceived) and each other anchor O perceived at t+1, a
data point:
the states of A and O at t and t+1 as DDC facts, and the label, whether O covers or holds A at t+1.
Both kinds of pairs of the paper are there: A perceived at t (it has just vanished) and A hidden at
t too (an occlusion that goes on, or not). Each data point gets constants of its own
(``ball_1_e3_f120``; ``ball_1_NAME_e3_f120`` in a collection named NAME: `anchoring collect`
names it after its data file, so that data files collected apart can be learned from together),
so that data points are independent worlds.

The states at t are what a particle of the theory of occlusion can know at t, computed from the
labels as an ideal particle would hold them:

- ``occluded_by(A, O):t``: O covered A at t, and the relation could be known: O was perceived
  when it began (an object put under a container while the camera was covered cannot be
  known to be under it), or it was known at t-1;
- ``lost_anywhere(A):t``: A is hidden with no known occluder and the camera saw nothing since it
  vanished (the theory's own definition);
- ``pos(A):t``: where A was perceived, or, hidden, under its known occluder (that occluder's
  place in the table plane), or where it was last seen.

Labels come two ways:

- ``truth``: the simulator's ground truth (the body whose ``under`` or ``held_by`` A's object is);
- ``hindsight``: what a robot knows afterwards, without ground truth: when a hidden anchor is
  re-acquired, the anchor it emerged from labels the whole hidden interval: among the anchors
  perceived where it reappeared (within ``reach``, 6 cm, in the table plane, just before or at the
  reappearance) that rose (was lifted, or a hand rose from what it put down) as it reappeared,
  each with weight exp(-d^2 / 2 sigma^2) (a cover that moved off without rising would have
  taken the object along; one that slid past it only hid it from view); several candidates
  make the label a probabilistic fact
  (``0.7 :: occluded_by(...)``, ``occluder(...) ~ finite([0.7:true, 0.3:false])``); none makes
  it "not covered" (it was behind something, or out of view). An interval whose anchor is never
  re-acquired (lost, or hidden at the end) gives no data.

The background knowledge the learned rules read (``FEATURES``) is written into the data file
and is the same text the learned theory carries, so that a feature means the same in the data
and in the particle filter.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from probanchor.learning.experience import Episode
from probanchor.learning.motion_keep import MOVING
from probanchor.loop.naming import category_atom, symbol_atom
from probanchor.perception.training import CATEGORIES as PERCEIVED_CATEGORIES

__all__ = ["BIAS", "CATEGORIES", "FEATURES", "Collection", "LabelOptions", "episode_facts",
           "hindsight_agreement", "labels"]

Labels = dict[str, float]          # occluder anchor -> probability that it covers A
LabelSource = Literal["truth", "hindsight"]

#: The categories the theory can meet (the perception classifier's and hands' skin).
CATEGORIES = (*PERCEIVED_CATEGORIES, "skin")

#: Background knowledge of the learned rules, in the data and in the learned theory.
FEATURES = """\
% Features of a pair (A, O) from t to t+1: the distance in the table plane and in 3-D from
% where A was to where O is, how far O's centre is above A's, how far O rose and how far it
% moved in the step, each object's category.
distance(A, O):t+1 ~ val(D) :=
    pos(A):t ~= (X, Y, _), pos(O):t+1 ~= (XO, YO, _), D is sqrt((X-XO)**2 + (Y-YO)**2).
distance3(A, O):t+1 ~ val(D) :=
    pos(A):t ~= (X, Y, Z), pos(O):t+1 ~= (XO, YO, ZO),
    D is sqrt((X-XO)**2 + (Y-YO)**2 + (Z-ZO)**2).
rise(A, O):t+1 ~ val(H) :=
    pos(A):t ~= (_, _, Z), pos(O):t+1 ~= (_, _, ZO), H is ZO - Z.
lift(O):t+1 ~ val(H) :=
    pos(O):t ~= (_, _, Z0), pos(O):t+1 ~= (_, _, Z1), H is Z1 - Z0.
moved(O):t+1 ~ val(M) :=
    pos(O):t ~= (X0, Y0, Z0), pos(O):t+1 ~= (X1, Y1, Z1),
    M is sqrt((X1-X0)**2 + (Y1-Y0)**2 + (Z1-Z0)**2).
kind(A):t+1 ~ val(C) :=
    category(A, C).
"""

#: The declarative bias: the target and the literals its clauses may test. The 3-D distance is
#: background knowledge the default bias leaves out: with both distances the leaves' logistic
#: regressions share their weight between two nearly collinear regressors (a container's
#: centre stands a few centimetres above what it covers), and what they learn can no longer be
#: read along the table-plane distance beside the paper's clause; add
#: ``mode(occluder(_, _):t+1, distance3(+, +):t+1).`` to a data file to let the learner use it.
#: Whether O moved in the step is a test at what perception's noise gives an object standing
#: still (``motion_keep.MOVING``): a covering starts when something moves (a container slid
#: over or lowered onto A), and an object hidden behind something stays uncovered beside a
#: container that stands still, however near (pooled, the leaves' logistic regressions gave a
#: ball hidden behind a bottle a chance of 2 % a frame to be under a mug 21 cm away, and within
#: a few seconds every particle had it there).
BIAS = """\
type(occluder(obj, obj):t+1).
type(pair(obj, obj):t+1).
type(occluded_by(obj, obj):t).
type(seen(obj):t).
type(lost_anywhere(obj):t).
type(distance(obj, obj):t+1).
type(distance3(obj, obj):t+1).
type(rise(obj, obj):t+1).
type(lift(obj):t+1).
type(moved(obj):t+1).
type(kind(obj):t+1).
rv(occluder(_, _):t+1, boolean).
rv(distance(_, _):t+1, continuous).
rv(distance3(_, _):t+1, continuous).
rv(rise(_, _):t+1, continuous).
threshold(rise(_, _):t+1, [0.0, 0.1]).
rv(lift(_):t+1, continuous).
rv(moved(_):t+1, continuous).
threshold(moved(_):t+1, [{moving}]).
rv(kind(_):t+1, discrete([{categories}])).
learn(occluder(Occluded, Occluder):t+1).
examples(occluder(A, O):t+1, pair(A, O):t+1).
mode(occluder(_, _):t+1, occluded_by(+, +):t).
mode(occluder(_, _):t+1, seen(+):t).
mode(occluder(_, _):t+1, lost_anywhere(+):t).
mode(occluder(_, _):t+1, distance(+, +):t+1).
mode(occluder(_, _):t+1, rise(+, +):t+1).
mode(occluder(_, _):t+1, lift(+):t+1).
mode(occluder(_, _):t+1, moved(+):t+1).
mode(occluder(_, _):t+1, kind(+):t+1).
"""


@dataclass(frozen=True)
class LabelOptions:
    """How labels are made.

    Parameters
    ----------
    source : "truth" or "hindsight"
        Ground truth, or hindsight (no ground truth).
    reach : float, default=0.06
        Hindsight: a candidate is within this table-plane distance (m) of where the hidden
        anchor reappeared (a container over an object stands within a few centimetres of it;
        one that stood or passed in front of it, 8 cm or more: with a reach of 10 cm, 1.8 times
        as many hidden frames were labelled "covered" against the ground truth on 80 games).
    sigma : float, default=0.04
        Hindsight: the spread (m) of the candidates' weights exp(-d^2 / 2 sigma^2).
    rise : float, default=0.02
        Hindsight: a candidate must have risen by more than this (m) as the anchor reappeared:
        it was lifted off it. (Counting one that only slid past, at half the weight of one that
        rose, had an upright cup that stood behind a can pushed about for 16 s hidden "under"
        the can, and the cans of 80 games hide 1 % of what they are near.)
    moved : float, default=0.02
        Hindsight: a candidate must have moved by more than this (m, in 3-D) in the frames
        around the reappearance (lifted, a hand withdrawn; it must have risen too, ``rise``):
        one that stood still while the anchor came out from behind it hid it from view, it
        did not cover it.
    arrival_reach : float, default=0.06
        Hindsight: a candidate covers the anchor only from the frame it is within this
        table-plane distance (m) of where the anchor was last seen (or out of view); while it
        is still coming (a box carried over a ball hides it from the camera before it is over
        it) the anchor is labelled "not covered", as the ground truth labels it. Without it,
        hindsight labelled every frame from the vanishing on, and the onsets a learned theory
        fitted reached more than twice as far as the ground truth's.
    steady_stride : int, default=5
        Of the *steady* data points (A hidden at t and t+1, its relation to O the same at t+1
        as known at t, O still within 1 cm in the table plane and 5 mm in height), one in this
        many is kept, with that weight (``weight(occluder(A, O):t+1, 5).``: it stands for the
        ones left out); every other data point is kept with weight 1. Steady points are most
        of an episode (an object sitting under a container, a hand out of view); the weights
        keep the learner's counts what they were (without them, the leaves for a still occluder
        would see its lifts five times too often), while the data shrink several times.
    """

    source: LabelSource = "truth"
    reach: float = 0.06
    sigma: float = 0.04
    rise: float = 0.02
    moved: float = 0.02
    arrival_reach: float = 0.06
    steady_stride: int = 5

    def __post_init__(self) -> None:
        if self.source not in ("truth", "hindsight"):
            raise ValueError(f"labels come from 'truth' or 'hindsight', not {self.source!r}")
        if not (self.reach > 0 and self.sigma > 0 and self.rise >= 0 and self.moved >= 0
                and self.arrival_reach > 0):
            raise ValueError("reach, sigma and arrival_reach must be > 0, rise and moved >= 0")
        if not (isinstance(self.steady_stride, int) and self.steady_stride >= 1):
            raise ValueError(f"steady_stride must be an integer >= 1, got {self.steady_stride!r}")


def labels(episode: Episode, options: LabelOptions) -> list[dict[str, Labels | None]]:
    """Per frame, per anchor hidden in that frame: who covers it (None: not known).

    ``result[k][a][o]`` is the probability that anchor ``o`` covers anchor ``a`` in frame
    ``k``; anchors not listed have probability 0.
    """
    if options.source == "truth":
        return _truth_labels(episode)
    return _hindsight_labels(episode, options)


#: Truth labels: a body covers a hidden object while it is within this height (m) above the
#: object's centre and this distance (m) in the table plane, from the frame the object is
#: hidden under it to the frame it is lifted off (the simulator's ``under`` begins only once a
#: container has come down over the object, and ends as soon as a lift starts, while the
#: container still sits over it).
COVER_HEIGHT = 0.12
COVER_REACH = 0.1
#: ... and, before the simulator's ``under`` begins, a container being lowered over it (higher,
#: and still coming in from the side).
LOWERING_HEIGHT = 0.12
LOWERING_REACH = 0.12


def _truth_labels(episode: Episode) -> list[dict[str, Labels | None]]:
    out: list[dict[str, Labels | None]] = []
    # a duplicate anchor (Episode.owners) has a stale place an ideal particle would not hold:
    # it gives no data
    owners = episode.owners()
    for k, frame in enumerate(episode.frames):
        row: dict[str, Labels | None] = {}
        for a, view in frame.anchors.items():
            if view.perceived:
                continue
            obj = episode.truth_of.get(a)
            if obj is None or owners[k].get(obj, a) != a:
                row[a] = None
                continue
            o = episode.covering(k, a)
            if o is None and k > 0:
                before = out[k - 1].get(a) or {}
                o = next((c for c, p in before.items()
                          if p > 0.5 and _still_covers(episode, k, a, c)), None)
            row[a] = {o: 1.0} if o is not None else {}
        out.append(row)
    # and backwards: a container lowered over an object hides it a few frames before the
    # simulator makes it the object's `under` (when it has come down)
    for k in range(len(out) - 2, -1, -1):
        for a, lab in out[k].items():
            later = out[k + 1].get(a)
            if lab == {} and later:
                o = next((c for c, p in later.items()
                          if p > 0.5 and _still_covers(episode, k, a, c, LOWERING_HEIGHT,
                                                       LOWERING_REACH, hidden=False)), None)
                if o is not None:
                    out[k][a] = {o: 1.0}
    return out


def _still_covers(episode: Episode, k: int, a: str, o: str, height: float = COVER_HEIGHT,
                  reach: float = COVER_REACH, hidden: bool = True) -> bool:
    """Ground truth: o's body is over a's object in frame k (within the height above it and
    the reach in the table plane; with ``hidden``, the object is not visible either: the
    anchor may be unperceived while a few of its pixels show)."""
    truth = episode.frames[k].truth or {}
    objects, hands = truth.get("objects", {}), truth.get("hands", {})
    info = objects.get(episode.truth_of.get(a) or "")
    gt_o = episode.truth_of.get(o) or ""
    other = objects.get(gt_o) or hands.get(gt_o)
    if info is None or other is None or (hidden and info.get("visible", False)):
        return False
    (x, y, z), (xo, yo, zo) = info["position"], other["position"]
    return zo - z < height and math.hypot(xo - x, yo - y) < reach


def _hindsight_labels(episode: Episode, options: LabelOptions) -> list[dict[str, Labels | None]]:
    frames = episode.frames
    out: list[dict[str, Labels | None]] = [{} for _ in frames]
    symbols = sorted({s for f in frames for s in f.anchors})
    for a in symbols:
        k = 0
        seen_before = False
        while k < len(frames):
            f = frames[k]
            if a not in f.anchors:
                k += 1
                continue
            if f.anchors[a].perceived:
                seen_before = True
                k += 1
                continue
            start = k
            while k < len(frames) and a in frames[k].anchors and not frames[k].anchors[a].perceived:
                k += 1
            end = k - 1                       # hidden in start..end
            label: Labels | None = None
            if seen_before and k < len(frames) and frames[k].perceived(a):
                label = _emergence(episode, a, end, k, options)
            arrival = _arrivals(episode, a, start, end, label or {}, options.arrival_reach)
            for j in range(start, end + 1):
                out[j][a] = label if not label else \
                    {o: p for o, p in label.items() if arrival[o] <= j}
    return out


def _arrivals(episode: Episode, a: str, start: int, end: int, label: Labels,
              arrival_reach: float) -> dict[str, int]:
    """The frame from which each candidate of ``label`` covers ``a`` (hidden in start..end):
    the first in which it is within ``arrival_reach`` (table plane) of where ``a`` was last seen,
    or not perceived (nothing says it is not there yet). Before it, the candidate is still on
    its way (``a`` is behind something, or out of view): hindsight then says "not covered", as
    the ground truth does. A candidate never perceived that near covers ``a`` from the start
    (nothing says when it came: a hand's percept, the grip point of what the camera sees of
    it, may stand 15 cm off what it holds)."""
    frames = episode.frames
    last = frames[start - 1].anchors.get(a) if start > 0 else None
    out: dict[str, int] = {}
    for o in label:
        if last is None:
            out[o] = start
            continue
        out[o] = start
        for j in range(start, end + 1):
            view = frames[j].anchors.get(o)
            if view is None or not view.perceived or math.hypot(
                    view.position[0] - last.position[0],
                    view.position[1] - last.position[1]) <= arrival_reach:
                out[o] = j
                break
    return out


def _emergence(episode: Episode, a: str, before: int, at: int,
               options: LabelOptions) -> Labels:
    """Who ``a`` emerged from when it reappeared in frame ``at`` (hidden up to ``before``)."""
    frames = episode.frames
    ax, ay, _ = frames[at].anchors[a].position
    weights: dict[str, float] = {}
    for o in frames[at].anchors:
        if o == a:
            continue
        d = math.inf
        for j in (before, at):
            view = frames[j].anchors.get(o)
            if view is not None and view.perceived:
                d = min(d, math.hypot(view.position[0] - ax, view.position[1] - ay))
        if d > options.reach or not _moved(episode, o, before, at, options.moved):
            continue
        if not _rose(episode, o, before, at, options.rise):
            continue
        weights[o] = math.exp(-d * d / (2 * options.sigma ** 2))
    total = sum(weights.values())
    return {o: w / total for o, w in weights.items()} if total > 0 else {}


#: Hindsight: the frames around a reappearance in which a candidate's motion is looked at.
MOTION_WINDOW = 3


def _moved(episode: Episode, o: str, before: int, at: int, moved: float) -> bool:
    """``o`` moved by more than ``moved`` (m) between a few frames before ``before`` and a few
    after ``at`` (where it was perceived)."""
    frames = episode.frames
    ps = [np.asarray(frames[j].anchors[o].position, dtype=float)
          for j in range(max(0, before - MOTION_WINDOW), min(len(frames), at + MOTION_WINDOW + 1))
          if o in frames[j].anchors and frames[j].anchors[o].perceived]
    if len(ps) < 2:
        return False
    first = ps[0]
    return max(float(np.linalg.norm(p - first)) for p in ps[1:]) > moved


def _rose(episode: Episode, o: str, before: int, at: int, rise: float) -> bool:
    frames = episode.frames
    zs = [frames[j].anchors[o].position[2] for j in range(max(0, before - 2), at + 1)
          if o in frames[j].anchors and frames[j].anchors[o].perceived]
    # above the lowest it had been before, at some frame of the window
    return len(zs) >= 2 and bool(np.any(np.asarray(zs) - np.minimum.accumulate(zs) > rise))


@dataclass
class Collection:
    """Facts written so far, and what was seen, for the report."""

    lines: list[str] = field(default_factory=list)
    pairs: int = 0
    weight: float = 0.0
    steady: int = 0
    positive: float = 0.0
    episodes: int = 0
    categories: set[str] = field(default_factory=set)
    per_episode: dict[str, int] = field(default_factory=dict)


def episode_facts(episode: Episode, number: int, options: LabelOptions,
                  out: Collection, collection: str = "") -> None:
    """Append the data points of one episode to ``out`` (see the module docstring):
    episode ``number`` of the collection named ``collection`` (an atom's text, or "").

    Besides the ideal particle's state, a hidden anchor known to be under O at t also gets a
    data point as a particle that has lost it holds it (no occluder known, where it was last
    seen: constants ending in ``_c``), with the same label: the learned rules are used by
    every particle, right or wrong, and a particle that took an object to be behind something
    while it went under a container must be able to pick that container later.
    """
    lab = labels(episode, options)
    frames = episode.frames
    known, lost = _known_states(episode, lab)
    before = out.pairs
    for k in range(len(frames) - 1):
        f0, f1 = frames[k], frames[k + 1]
        written: set[str] = set()
        for a, view in f1.anchors.items():
            if view.perceived or a not in f0.anchors:
                continue
            target = lab[k + 1].get(a)
            if target is None:
                continue
            others = [o for o, v in f1.anchors.items()
                      if o != a and v.perceived and o in f0.anchors]
            ideal = known[k].get(a, {})
            states = [("", ideal, lost[k].get(a, False))]
            if any(p > 0.5 for p in ideal.values()):
                states.append(("_c", {}, False))
            for suffix, state, is_lost in states:
                _data_points(out, (collection, number), k, a, suffix, state, is_lost,
                             others, target, written, options, episode)
    out.episodes += 1
    out.per_episode[episode.name] = out.pairs - before


def _data_points(out: Collection, number: tuple[str, int], k: int, a: str, suffix: str,
                 state: Labels,
                 is_lost: bool, others: list[str], target: Labels, written: set[str],
                 options: LabelOptions, episode: Episode) -> None:
    """The data points of hidden anchor ``a`` from frame k to k+1, in one particle state."""
    f0, f1 = episode.frames[k], episode.frames[k + 1]
    kept = []
    for o in others:
        p = target.get(o, 0.0)
        p_known = state.get(o, 0.0)
        weight = 1
        if (options.steady_stride > 1 and not f0.anchors[a].perceived
                and abs(p - p_known) < 1e-9 and _still(f0.anchors[o], f1.anchors[o])):
            out.steady += 1
            if out.steady % options.steady_stride:
                continue
            weight = options.steady_stride
        kept.append((o, p, p_known, weight))
    if not kept:
        return
    ca = _const(a, number, k) + suffix
    if ca not in written:
        _object_facts(out, ca, f0.anchors[a], f1.anchors[a], None, state, f0)
        if is_lost:
            out.lines.append(f"lost_anywhere({ca}):t.")
        written.add(ca)
    for o, p, p_known, weight in kept:
        co = _const(o, number, k)
        if co not in written:
            _object_facts(out, co, f0.anchors[o], f1.anchors[o], f1.anchors[o], {}, f0)
            written.add(co)
        if p_known >= 1.0 - 1e-12:
            out.lines.append(f"occluded_by({ca}, {co}):t.")
        elif p_known > 1e-12:
            out.lines.append(f"{p_known:.6g} :: occluded_by({ca}, {co}):t.")
        out.lines.append(_target(ca, co, p))
        if weight > 1:
            out.lines.append(f"weight(occluder({ca}, {co}):t+1, {weight}).")
        out.pairs += 1
        out.weight += weight
        out.positive += p * weight


def _still(v0, v1) -> bool:
    (x0, y0, z0), (x1, y1, z1) = v0.position, v1.position
    return math.hypot(x1 - x0, y1 - y0) < 0.01 and abs(z1 - z0) < 0.005


def _const(symbol: str, episode: tuple[str, int], frame: int) -> str:
    """``ball_1_e3_f120``, or ``ball_1_NAME_e3_f120`` for episode 3 of collection NAME."""
    collection, number = episode
    where = f"_{collection}" if collection else ""
    return f"{symbol_atom(symbol)}{where}_e{number}_f{frame}"


def _object_facts(out: Collection, c: str, at_t, at_t1, perceived_t1, known: Labels,
                  frame_t) -> None:
    """pos at t (perceived, under its known occluder, or last seen), pos at t+1 when perceived,
    seen at t, the category."""
    x, y, z = at_t.position
    if not at_t.perceived and known:
        o, p = max(known.items(), key=lambda kv: kv[1])
        view = frame_t.anchors.get(o)
        if p > 0.5 and view is not None:
            x, y = view.position[0], view.position[1]
    out.lines.append(f"pos({c}):t ~= {_tuple((x, y, z))}.")
    if perceived_t1 is not None:
        out.lines.append(f"pos({c}):t+1 ~= {_tuple(perceived_t1.position)}.")
    if at_t.perceived:
        out.lines.append(f"seen({c}):t.")
    cat = category_atom(at_t1.category)
    out.categories.add(cat)
    out.lines.append(f"category({c}, {cat}).")


def _tuple(p: Iterable[float]) -> str:
    return "(" + ", ".join(f"{float(v):.4f}" for v in p) + ")"


def _target(a: str, o: str, p: float) -> str:
    """The pair (an example of examples/2) and its label, as the paper writes data: the atom
    when O covers A, nothing when not (closed world), ``P ::`` when hindsight is unsure."""
    pair = f"pair({a}, {o}):t+1."
    head = f"occluder({a}, {o}):t+1"
    if p >= 1.0 - 1e-12:
        return f"{pair}\n{head}."
    if p <= 1e-12:
        return pair
    return f"{pair}\n{p:.6g} :: {head}."


def _known_states(episode: Episode, lab: list[dict[str, Labels | None]]
                  ) -> tuple[list[dict[str, Labels]], list[dict[str, bool]]]:
    """Per frame: what an ideal particle knows of each hidden anchor's occluder, and whether it
    is lost anywhere (see the module docstring)."""
    frames = episode.frames
    known: list[dict[str, Labels]] = []
    lost: list[dict[str, bool]] = []
    for k, f in enumerate(frames):
        row: dict[str, Labels] = {}
        lrow: dict[str, bool] = {}
        for a, view in f.anchors.items():
            if view.perceived:
                continue
            label = lab[k].get(a) or {}
            prev = known[k - 1].get(a, {}) if k > 0 else {}
            row[a] = {o: p for o, p in label.items()
                      if p > 0 and (f.perceived(o) or prev.get(o, 0.0) > 0)}
            has = any(p > 0.5 for p in row[a].values())
            was_lost = k > 0 and lost[k - 1].get(a, False)
            lrow[a] = not has and (f.blind or was_lost)
        known.append(row)
        lost.append(lrow)
    return known, lost


def data_text(collection: Collection, sources: Sequence[str], options: LabelOptions,
              command: str | None) -> str:
    """The data file: a header, the background knowledge, the bias and the facts."""
    categories = sorted(set(CATEGORIES) | collection.categories)
    header = [
        "% Before/after facts of occlusions collected by `anchoring collect` (perception and",
        "% anchoring alone) for the structure learner (`ddc learn`, `anchoring learn-theory`).",
    ]
    if command:
        header.append(f"% Command: {command}")
    header += [
        f"% Labels: {options.source}; {collection.episodes} episodes, {collection.pairs} pairs "
        f"(anchor hidden at t+1, another perceived; weight {collection.weight:g}), "
        f"{collection.positive:.6g} covered.",
        "% Episodes: " + ", ".join(sources),
        "",
    ]
    bias = BIAS.format(categories=", ".join(categories), moving=MOVING)
    return "\n".join(header) + FEATURES + "\n" + bias + "\n" + "\n".join(collection.lines) + "\n"


def hindsight_agreement(episode: Episode, options: LabelOptions) -> tuple[float, int]:
    """How often hindsight labels agree with the ground truth, over the (frame, hidden anchor,
    other anchor) triples both label: the expected agreement sum, and the count."""
    hind = labels(episode, dataclasses.replace(options, source="hindsight"))
    truth = labels(episode, LabelOptions(source="truth"))
    agree, n = 0.0, 0
    for k, f in enumerate(episode.frames):
        for a, h in hind[k].items():
            t = truth[k].get(a)
            if h is None or t is None:
                continue
            for o, v in f.anchors.items():
                if o == a or not v.perceived:
                    continue
                p = h.get(o, 0.0)
                truly = t.get(o, 0.0) > 0.5
                agree += p if truly else 1.0 - p
                n += 1
    return agree, n
