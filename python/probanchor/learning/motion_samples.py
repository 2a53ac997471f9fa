"""The samples the motion and carrying parameters of a learned theory are fitted from.

``anchoring collect`` writes them beside its data file (``DATA.motion.json``, see
:func:`samples_path`), gathered from the same episodes (:mod:`probanchor.learning.experience`):

- ``displacement``: a perceived object's frame-to-frame displacement (dx, dy, dz, category),
  of the position the theory is told (a hand's grip point), and its true displacement (tdx,
  tdy, tdz; None where the simulator does not know the object);
- ``reappear``, ``lost``: where a hidden object was seen again against where an ideal particle
  believed it (under its true occluder, or where it was last seen): (dx, dy, dz); ``lost``
  for an object that vanished while the camera saw nothing and was covered by nothing since;
- ``follow``: a hidden object's true position relative to its occluder's perceived one, at t
  and t+1 under the same occluder: (ox0, oy0, ox1, oy1, occluder's category);
- ``coast``: a hidden object under nothing, its true velocity (table plane) before and in the
  step: (vx0, vy0, vx1, vy1);
- ``coast_gap``: an object hidden under nothing from when it vanished until it reappeared
  (behind something, or out of the view; not while the camera saw nothing), its true velocity
  as it vanished, how far it truly went until it reappeared and the frames between, and how
  far its height went (vx0, vy0, dx, dy, n, dz): what the theory predicts over a whole time
  hidden, which the steps do not show (an object pushed out of the view stops there and comes
  back);
- ``grasp``: a hand taking an object: the table-plane distance and the height of its grip
  point above the top of the object where an ideal particle believed it (its centre and half
  its height as anchoring knows it), in the frame the object vanished
  under the hand in the second before it held it (the moment the carriers' rules take it),
  else the frame it started holding it, and the grip's height as it starts holding it (the
  lowest it comes); an object perceived within the second before;
- ``hold``: how far the grip point is above the centre of what the hand holds;
- ``carries``: per carry, the held object's true height above where it stood, frame by frame,
  whether the hand let it go (the carry did not run to the episode's end) and the hand's grip
  height frame by frame (None while unperceived);
- ``uncover``: how far a lifted container's centre stood above what stayed on the table when
  that became visible again;
- ``places``: where the perceived objects (not hands) stand in the table plane, every
  ``PLACES_EVERY`` frames;
- ``heights``: the perceived objects' (not hands') categories and heights (m), as often.

Positions of hidden objects are the simulator's ground truth; the rest is what perception gave.
For the samples of a collection labelled in hindsight, which read no truth (``follow_gap`` and
``coast_gap`` from the perceived ends, no ``follow`` or ``coast``), see
:mod:`probanchor.learning.motion_hindsight`.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from probanchor.learning.experience import AnchorView, Episode
from probanchor.learning.occlusion_data import LabelOptions, LabelSource, labels

__all__ = ["KINDS", "MotionSamples", "coast_gap_row", "covering", "episode_samples",
           "hidden_runs", "places", "read_samples", "reappearances", "samples_path", "told"]

#: The rows each kind of sample may have (see the module docstring): per column ``n`` a
#: number, ``s`` a string, ``*`` anything; ``n`` alone a number (not a list), ``{}`` an object.
#: ``coast_gap`` rows written before the change of height was kept have five columns.
ROW_SHAPES: dict[str, tuple[str, ...]] = {
    "displacement": ("nnns**", "nnns*"), "reappear": ("nnn",), "lost": ("nnn",),
    "follow": ("nnnns",), "coast": ("nnnn",), "grasp": ("nnn",), "hold": ("n",),
    "carries": ("{}",), "uncover": ("n",), "places": ("nn",), "follow_gap": ("nnnnns",),
    "coast_gap": ("nnnnnn", "nnnnn"), "heights": ("sn",),
}

#: The kinds of samples (see the module docstring), in the order they are written.
KINDS = tuple(ROW_SHAPES)

#: ``places`` keeps where the perceived objects stand every this many frames.
PLACES_EVERY = 15


@dataclass
class MotionSamples:
    """Samples by kind (lists of JSON-able rows)."""

    rows: dict[str, list[Any]] = field(default_factory=lambda: {k: [] for k in KINDS})

    def extend(self, other: MotionSamples) -> None:
        for k in KINDS:
            self.rows[k] += other.rows[k]

    def to_json(self) -> str:
        return json.dumps(self.rows, separators=(",", ":"))


def samples_path(data: str | Path) -> Path:
    """Where the samples of data file ``data`` are: ``DATA.motion.json`` beside it."""
    p = Path(data)
    return p.with_name(p.stem + ".motion.json")


def read_samples(data: list[str | Path] | tuple[str | Path, ...]) -> MotionSamples:
    """The samples of the data files, merged.

    Raises
    ------
    FileNotFoundError
        A data file does not exist, or has no samples beside it (collected by an older
        ``anchoring collect``).
    ValueError
        A samples file is not JSON, or a row is not of its kind's shape (:data:`ROW_SHAPES`):
        the message names the file and the line, or the kind and the row.
    """
    out = MotionSamples()
    for d in data:
        if not Path(d).is_file():
            raise FileNotFoundError(f"{d}: no such data file (write it with `anchoring "
                                    "collect`)")
        path = samples_path(d)
        if not path.is_file():
            raise FileNotFoundError(f"{path}: no motion samples beside {d} (collect it again "
                                    "with `anchoring collect`, which writes them)")
        try:
            rows = json.loads(path.read_text(encoding="utf-8"))
        except json.JSONDecodeError as error:
            raise ValueError(f"{path}:{error.lineno}: not JSON: {error.msg}") from None
        if not isinstance(rows, dict):
            raise ValueError(f"{path}: not an object of sample kinds")
        for kind in KINDS:
            for k, row in enumerate(rows.get(kind, [])):
                if not _row_fits(row, ROW_SHAPES[kind]):
                    raise ValueError(f"{path}: {kind} row {k}: {row!r} is not "
                                     f"{' or '.join(map(_shape_text, ROW_SHAPES[kind]))}")
        out.extend(MotionSamples({k: list(rows.get(k, [])) for k in KINDS}))
    return out


def _is_number(v: object) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)


def _row_fits(row: object, shapes: tuple[str, ...]) -> bool:
    for shape in shapes:
        if shape == "n":
            if _is_number(row):
                return True
        elif shape == "{}":
            if isinstance(row, dict):
                return True
        elif isinstance(row, list) and len(row) == len(shape) and all(
                c == "*" or (c == "n" and _is_number(v)) or (c == "s" and isinstance(v, str))
                for c, v in zip(shape, row, strict=True)):
            return True
    return False


def _shape_text(shape: str) -> str:
    if shape == "n":
        return "a number"
    if shape == "{}":
        return "an object"
    names = {"n": "number", "s": "string", "*": "value"}
    return "[" + ", ".join(names[c] for c in shape) + "]"


def told(view: AnchorView) -> tuple[float, float, float]:
    """Where the theory is told a perceived anchor is (a hand's grip point)."""
    return view.grip if view.grip is not None else view.position


def _true(episode: Episode, k: int, a: str) -> dict[str, Any] | None:
    """The simulator's record of anchor ``a``'s object in frame ``k``."""
    obj = episode.truth_of.get(a)
    truth = episode.frames[k].truth
    if obj is None or truth is None:
        return None
    return truth.get("objects", {}).get(obj)


def _true_position(episode: Episode, k: int, a: str) -> list[float] | None:
    """Anchor ``a``'s object's (or hand's) true position in frame ``k``."""
    obj = episode.truth_of.get(a)
    truth = episode.frames[k].truth
    if obj is None or truth is None:
        return None
    info = truth.get("objects", {}).get(obj) or truth.get("hands", {}).get(obj)
    return None if info is None else list(info["position"])


def covering(episode: Episode, source: LabelSource) -> Callable[[int, str], str | None]:
    """``covered_by(k, a)``: the anchor the labels of ``source`` say covers ``a`` in frame
    ``k`` (more likely than not), or None."""
    lab = labels(episode, LabelOptions(source=source))

    def covered_by(k: int, a: str) -> str | None:
        return next((o for o, p in (lab[k].get(a) or {}).items() if p > 0.5), None)

    return covered_by


def places(episode: Episode, s: MotionSamples) -> None:
    """Where the perceived objects (not hands) stand, and their categories and heights, every
    :data:`PLACES_EVERY` frames."""
    for k in range(0, len(episode.frames), PLACES_EVERY):
        for v in episode.frames[k].anchors.values():
            if v.perceived and v.grip is None:
                s.rows["places"].append([round(v.position[0], 4), round(v.position[1], 4)])
                s.rows["heights"].append([v.category, round(v.height, 4)])


def episode_samples(episode: Episode) -> MotionSamples:
    """The samples of one episode (see the module docstring)."""
    s = MotionSamples()
    frames = episode.frames
    covered_by = covering(episode, "truth")
    places(episode, s)
    for k in range(len(frames) - 1):
        f0, f1 = frames[k], frames[k + 1]
        for a, v1 in f1.anchors.items():
            v0 = f0.anchors.get(a)
            if v0 is None:
                continue
            if v0.perceived and v1.perceived:
                p0, p1 = told(v0), told(v1)
                q0, q1 = _true_position(episode, k, a), _true_position(episode, k + 1, a)
                moved = (None if q0 is None or q1 is None
                         else [round(q1[i] - q0[i], 5) for i in range(3)])
                s.rows["displacement"].append([round(p1[i] - p0[i], 5) for i in range(3)]
                                              + [v1.category, moved])
            if v1.perceived:
                continue
            t1 = _true(episode, k + 1, a)
            t0 = _true(episode, k, a)
            if t0 is None or t1 is None:
                continue
            o0, o1 = covered_by(k, a), covered_by(k + 1, a)
            if (o1 is not None and o1 == o0 and f0.perceived(o1) and f1.perceived(o1)
                    and not v0.perceived):
                q0, q1 = told(f0.anchors[o1]), told(f1.anchors[o1])
                s.rows["follow"].append([round(t0["position"][0] - q0[0], 5),
                                         round(t0["position"][1] - q0[1], 5),
                                         round(t1["position"][0] - q1[0], 5),
                                         round(t1["position"][1] - q1[1], 5),
                                         f1.anchors[o1].category])
            if (o1 is None and t1.get("held_by") is None and t1.get("under") is None
                    and k > 0):
                tm = _true(episode, k - 1, a)
                if tm is not None:
                    (xm, ym, _), (x0, y0, _), (x1, y1, _) = (tm["position"], t0["position"],
                                                             t1["position"])
                    s.rows["coast"].append([round(x0 - xm, 5), round(y0 - ym, 5),
                                            round(x1 - x0, 5), round(y1 - y0, 5)])
    reappearances(episode, covered_by, s)
    _coast_gaps(episode, covered_by, s)
    _hands(episode, covered_by, s)
    _uncovering(episode, s)
    return s


def _coast_gaps(episode: Episode, covered_by, s: MotionSamples) -> None:
    """The ``coast_gap`` rows: from the true positions two frames before an object vanished
    under nothing, one before, and where it reappeared."""
    frames = episode.frames
    for a in sorted({x for f in frames for x in f.anchors}):
        for start, end in hidden_runs(episode, a):
            run = range(start, end + 1)
            if start < 2 or any(covered_by(j, a) is not None or frames[j].blind for j in run):
                continue
            truths = [_true(episode, j, a) for j in run]
            ps = [_true_position(episode, j, a) for j in (start - 2, start - 1, end + 1)]
            if any(p is None for p in ps) or any(
                    t is None or t.get("held_by") or t.get("under") for t in truths):
                continue
            s.rows["coast_gap"].append(coast_gap_row(*ps, end - start + 2))  # type: ignore[arg-type]


def coast_gap_row(before: Sequence[float], last: Sequence[float], back: Sequence[float],
                  n: int) -> list[float]:
    """A ``coast_gap`` row: the velocity from ``before`` to ``last`` (one frame apart) and the
    displacement from ``last`` to ``back``, ``n`` frames later, in the table plane, then the
    change of height from ``last`` to ``back``."""
    return [round(last[0] - before[0], 5), round(last[1] - before[1], 5),
            round(back[0] - last[0], 5), round(back[1] - last[1], 5), n,
            round(back[2] - last[2], 5)]


def hidden_runs(episode: Episode, a: str) -> list[tuple[int, int]]:
    """(start, end) of each run of frames anchor ``a`` is hidden in, having been perceived
    before it and perceived again in frame end + 1."""
    frames = episode.frames
    runs, k, seen_before = [], 0, False
    while k < len(frames):
        view = frames[k].anchors.get(a)
        if view is None or view.perceived:
            seen_before = seen_before or view is not None
            k += 1
            continue
        start = k
        while k < len(frames) and a in frames[k].anchors and not frames[k].perceived(a):
            k += 1
        if seen_before and k < len(frames) and frames[k].perceived(a):
            runs.append((start, k - 1))
    return runs


def reappearances(episode: Episode, covered_by, s: MotionSamples) -> None:
    frames = episode.frames
    for a in sorted({x for f in frames for x in f.anchors}):
        for start, end in hidden_runs(episode, a):
            k = end + 1
            last = frames[end].anchors[a].position        # where it was last seen
            x, y, z = last
            o = covered_by(end, a)
            if o is not None and frames[end].perceived(o):
                q = told(frames[end].anchors[o])
                x, y = q[0], q[1]
                if frames[end].anchors[o].grip is not None:      # a hand: carried in 3-D
                    z = q[2]
            blind = [j for j in range(start, end + 1) if frames[j].blind]
            lost = bool(blind) and all(covered_by(j, a) is None
                                       for j in range(blind[0], end + 1))
            p = frames[k].anchors[a].position
            s.rows["lost" if lost else "reappear"].append(
                [round(p[0] - x, 5), round(p[1] - y, 5), round(p[2] - z, 5)])


#: A grasp sample needs the object perceived within this many frames before it is taken (an
#: object out of view for longer may have been moved unseen: anchoring alone does not know
#: where it is, nor does an ideal particle).
RECENT = 15


def _hand_anchor(episode: Episode, k: int, hand: str) -> AnchorView | None:
    """The perceived anchor of ground-truth hand ``hand`` in frame ``k`` with a grip point."""
    for a, view in episode.frames[k].anchors.items():
        if episode.truth_of.get(a) == hand and view.perceived and view.grip is not None:
            return view
    return None


def _hands(episode: Episode, covered_by, s: MotionSamples) -> None:
    frames = episode.frames
    owners = episode.owners()
    for a in sorted({x for f in frames for x in f.anchors}):
        run: list[int] = []
        holder = None
        for k in range(len(frames) + 1):
            t = _true(episode, k, a) if k < len(frames) and a in frames[k].anchors else None
            h = t.get("held_by") if t is not None else None
            if h is not None and h == holder:
                run.append(k)
                continue
            if run:
                _carry(episode, a, holder, run, released=k < len(frames), covered_by=covered_by,
                       s=s, owners=owners)
            run, holder = ([k], h) if h is not None else ([], None)


def _belief(episode: Episode, k: int, a: str, covered_by, hand: str
            ) -> tuple[float, float, float]:
    """Where an ideal particle believes anchor ``a`` in frame ``k`` before ``hand`` takes it:
    where it is perceived, under its true occluder (in the table plane) unless that is the
    hand (closing over it: it has not moved it yet), or where it was last seen."""
    view = episode.frames[k].anchors[a]
    x, y, z = view.position
    o = None if view.perceived else covered_by(k, a)
    if (o is not None and episode.frames[k].perceived(o)
            and episode.truth_of.get(o) != hand):
        q = told(episode.frames[k].anchors[o])
        x, y = q[0], q[1]
    return x, y, z


def _carry(episode: Episode, a: str, hand: str, run: list[int], released: bool,
           covered_by, s: MotionSamples, owners: list[dict[str, str]]) -> None:
    frames = episode.frames
    first = run[0]
    before = _true(episode, first - 1, a) if first > 0 else None
    rest = (before or _true(episode, first, a))["position"][2]        # type: ignore[index]
    # the moment the rules use: the object vanishing under the grip (in the second before
    # the hand holds it), else the hand starting to hold it
    at = first
    for j in range(first, max(0, first - RECENT), -1):
        if (a in frames[j].anchors and a in frames[j - 1].anchors and not frames[j].perceived(a)
                and frames[j - 1].perceived(a)):
            at = j
            break
    grip = _hand_anchor(episode, at, hand)
    recent = [j for j in range(max(0, at - RECENT), at)
              if a in frames[j].anchors and frames[j].perceived(a)]
    holding = _hand_anchor(episode, first, hand)
    owner = owners[at - 1].get(episode.truth_of.get(a) or "") if at > 0 else None
    if (grip is not None and holding is not None and recent and a in frames[at - 1].anchors
            and owner == a):                       # not a duplicate with a stale place
        x, y, z = _belief(episode, at - 1, a, covered_by, hand)
        top = z + frames[at - 1].anchors[a].height / 2
        gx, gy, gz = grip.grip                                          # type: ignore[misc]
        hz = holding.grip[2]                                            # type: ignore[index]
        s.rows["grasp"].append([round(math.hypot(gx - x, gy - y), 5), round(gz - top, 5),
                                round(hz - z, 5)])
    heights, grips = [], []
    for k in run:
        t = _true(episode, k, a)
        heights.append(round(t["position"][2] - rest, 5))                  # type: ignore[index]
        g = _hand_anchor(episode, k, hand)
        grips.append(None if g is None else round(g.grip[2], 5))          # type: ignore[index]
        if g is not None and not frames[k].perceived(a):
            s.rows["hold"].append(round(g.grip[2] - t["position"][2], 5))  # type: ignore[index]
    s.rows["carries"].append({"heights": heights, "released": released, "grips": grips})


def _uncovering(episode: Episode, s: MotionSamples) -> None:
    frames = episode.frames
    for k in range(1, len(frames)):
        truth0, truth1 = frames[k - 1].truth or {}, frames[k].truth or {}
        objects0, objects1 = truth0.get("objects", {}), truth1.get("objects", {})
        for obj, t1 in objects1.items():
            t0 = objects0.get(obj)
            if t0 is None or t0.get("visible") or not t1.get("visible"):
                continue
            if t1.get("held_by") is not None:
                continue
            # the container that covered it until now, lifted off
            cover = t0.get("under") or t0.get("hidden_by")
            c1 = objects1.get(cover) if cover else None
            c0 = objects0.get(cover) if cover else None
            if c0 is None or c1 is None or c1["position"][2] <= c0["position"][2]:
                continue
            s.rows["uncover"].append(round(c1["position"][2] - t1["position"][2], 5))
