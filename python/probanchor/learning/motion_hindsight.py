"""The motion samples of an episode from what the robot perceived alone (``anchoring collect
--labels hindsight``): no simulator truth is read.

The samples of :mod:`probanchor.learning.motion_samples` read where hidden objects truly were;
a robot has only where it saw them vanish and reappear, what its hindsight labels say hid them
(:func:`probanchor.learning.occlusion_data.labels` with ``source="hindsight"``), and where the
occluders it perceived went. The same kinds of samples are written, those that need a hidden
object's position replaced by what spans its whole time hidden:

- ``displacement``: the perceived displacement, with no true one (None) but whether the
  object stood still as perception sees it (within :data:`STILL_SPAN` of where it was
  :data:`STILL_WINDOW` frames before and after): the variances are then fitted from the
  perceived ones (:mod:`probanchor.learning.motion_variances`);
- ``reappear``, ``lost``, ``places``: as from ground truth, the occluder a hidden object was
  under being the hindsight label's;
- ``follow_gap`` (instead of ``follow``): an object hidden under one perceived occluder
  throughout: its offset from the occluder's perceived centre as it vanished (where it was
  last seen against the occluder in the first frame that hid it) and as it reappeared (where
  it is seen against the occluder in the last frame that hid it), and the frames between
  (ox0, oy0, ox1, oy1, n);
- ``coast_gap`` (instead of ``coast``): an object hidden under nothing throughout (behind
  something): its perceived velocity before it vanished, how far it went until it reappeared
  and the frames between (vx0, vy0, dx, dy, n), measured :data:`PARTIAL` frames before it
  vanished and after it reappeared (the views between may be partial); only when something
  was perceived in front of it (between it and the camera, which looks along +y) as it
  vanished: with nothing in front it left the view, and what perception saw of its way out
  is a view cut by the image's border (with those gaps, 428 instead of 124 on the 80 games,
  the fit kept 0.59 of the velocity with a jitter of 3 mm; from the true ends of all of them,
  0.90 and 1.5 cm);
- ``grasp``, ``hold``, ``carries``: a carry is a run of frames the hindsight labels give a hand
  (an anchor with a grip point) as what hides the object; the grasp: how near, in the table
  plane, the grip came to where the object was believed as it vanished, within the second the
  hand took it (ground truth knows the frame it took it; hindsight that it did), how high it
  was as the object vanished and how low it came; what
  the hand holds rises with its grip, from the grip's lowest in the carry's first second
  (where it closed on the object, standing where it was last seen: one ``hold`` sample per
  carry, the grip's height over it there); the hand let go where its grip's last rise began
  (it put the object down, then rose empty until the object was seen; the labels give the
  hand until then); a hand whose grip never rose :data:`LIFTED` with the object carried
  nothing.

:mod:`probanchor.learning.motion_keep` fits the AR(1) of the gaps by maximum likelihood over
the gap's frames.
"""

from __future__ import annotations

import math

from probanchor.learning.experience import Episode
from probanchor.learning.motion_samples import (
    RECENT,
    MotionSamples,
    coast_gap_row,
    covering,
    hidden_runs,
    places,
    reappearances,
    told,
)

__all__ = ["hindsight_samples"]


def hindsight_samples(episode: Episode) -> MotionSamples:
    """The samples of one episode from perception and hindsight labels (see the module
    docstring)."""
    s = MotionSamples()
    frames = episode.frames
    covered_by = covering(episode, "hindsight")
    places(episode, s)
    for k in range(len(frames) - 1):
        f0, f1 = frames[k], frames[k + 1]
        for a, v1 in f1.anchors.items():
            v0 = f0.anchors.get(a)
            if v0 is not None and v0.perceived and v1.perceived:
                p0, p1 = told(v0), told(v1)
                s.rows["displacement"].append([round(p1[i] - p0[i], 5) for i in range(3)]
                                              + [v1.category, None, _still(episode, a, k)])
    reappearances(episode, covered_by, s)
    _gaps(episode, covered_by, s)
    _carries(episode, covered_by, s)
    return s


#: An object stood still in a frame when it is perceived within STILL_SPAN (m, table plane) of
#: where it was STILL_WINDOW frames before and after (perception alone cannot see a
#: displacement under its noise; an object moved by a hand or pushed is a few centimetres
#: away in that time).
STILL_WINDOW = 5
STILL_SPAN = 0.005


def _still(episode: Episode, a: str, k: int) -> bool:
    frames = episode.frames
    lo, hi = k - STILL_WINDOW, k + 1 + STILL_WINDOW
    if lo < 0 or hi >= len(frames):
        return False
    v0, v1 = frames[lo].anchors.get(a), frames[hi].anchors.get(a)
    if v0 is None or v1 is None or not v0.perceived or not v1.perceived:
        return False
    (x0, y0, _), (x1, y1, _) = told(v0), told(v1)
    return math.hypot(x1 - x0, y1 - y0) < STILL_SPAN


#: Something stands in front of a vanishing object when it is perceived nearer the camera
#: (smaller y) within this much to the side and this much nearer (m).
FRONT_SIDE = 0.08
FRONT_DEPTH = 0.2


def _in_front(frame, a: str, where: tuple[float, ...]) -> bool:
    """Whether an anchor other than ``a`` is perceived in front of ``where`` in ``frame``."""
    return any(o != a and v.perceived and abs(v.position[0] - where[0]) < FRONT_SIDE
               and 0.0 < where[1] - v.position[1] < FRONT_DEPTH
               for o, v in frame.anchors.items())


#: The views of an object this many frames before it vanishes and after it reappears may be
#: partial (part of it behind what hides it): their centres are off its own, and the velocity
#: of the last two of them is the visible part shrinking, not the object moving (an object
#: standing still behind a passing hand "moved" 2 cm a frame as it vanished and was back where
#: it stood). A coasting gap is measured between the views before and after them.
PARTIAL = 2


def _coast_gap(episode: Episode, a: str, start: int, end: int, s: MotionSamples) -> None:
    """The ``coast_gap`` of ``a`` hidden under nothing from ``start`` to ``end``: from the view
    PARTIAL frames before it vanished (its velocity from the one before) to the view PARTIAL
    frames after it reappeared, if all those frames perceived it."""
    frames = episode.frames
    r0, r1 = start - 1 - PARTIAL, end + 1 + PARTIAL
    if r0 < 1 or r1 >= len(frames) or not all(
            frames[j].perceived(a) for j in [*range(r0 - 1, start), *range(end + 1, r1 + 1)]):
        return
    before, last, back = (frames[j].anchors[a].position for j in (r0 - 1, r0, r1))
    s.rows["coast_gap"].append(coast_gap_row(before, last, back, r1 - r0))


def _gaps(episode: Episode, covered_by, s: MotionSamples) -> None:
    frames = episode.frames
    for a in sorted({x for f in frames for x in f.anchors}):
        for start, end in hidden_runs(episode, a):
            if not frames[start - 1].perceived(a):
                continue                           # (seen just before it vanished only)
            n = end - start + 2                    # steps from the last sight to the next
            last = frames[start - 1].anchors[a].position
            back = frames[end + 1].anchors[a].position
            occluders = {covered_by(j, a) for j in range(start, end + 1)}
            if occluders == {None}:
                if any(frames[j].blind for j in range(start, end + 1)):
                    continue                       # (lost: moved anywhere, not coasting)
                if _in_front(frames[start], a, last):
                    _coast_gap(episode, a, start, end, s)
                continue                           # (else it left the view: not coasting)
            if len(occluders) != 1:
                continue
            (o,) = occluders
            first, final = frames[start].anchors.get(o), frames[end].anchors.get(o)
            if (o is None or first is None or final is None or not first.perceived
                    or not final.perceived or first.grip is not None):
                continue                           # (a hand's carry: see _carries)
            q0, q1 = told(first), told(final)
            s.rows["follow_gap"].append([round(last[0] - q0[0], 5), round(last[1] - q0[1], 5),
                                         round(back[0] - q1[0], 5), round(back[1] - q1[1], 5),
                                         n - 2, first.category])


def _carries(episode: Episode, covered_by, s: MotionSamples) -> None:
    frames = episode.frames
    # the hands: anchors perceived with a grip point in some frame
    hands = {o for f in frames for o, v in f.anchors.items() if v.grip is not None}
    for a in sorted({x for f in frames for x in f.anchors}):
        run: list[int] = []
        holder = None
        for k in range(len(frames) + 1):
            h = None
            if k < len(frames) and a in frames[k].anchors and not frames[k].perceived(a):
                o = covered_by(k, a)
                h = o if o in hands else None
            if h is not None and h == holder:
                run.append(k)
                continue
            if run and holder is not None:
                _carry(episode, a, holder, run, released=k < len(frames),
                       covered_by=covered_by, s=s)
            run, holder = ([k], h) if h is not None else ([], None)


def _grip(episode: Episode, k: int, hand: str) -> tuple[float, float, float] | None:
    view = episode.frames[k].anchors.get(hand)
    return view.grip if view is not None and view.perceived else None


#: A carry's grip rises at least this far (m) above where it closed on the object: a hand the
#: labels give as hiding an object that it never lifted is no carry the release can learn from.
LIFTED = 0.02


def _carry(episode: Episode, a: str, hand: str, run: list[int], released: bool,
           covered_by, s: MotionSamples) -> None:
    frames = episode.frames
    first = run[0]
    seen = [j for j in range(first - 1, -1, -1)
            if a in frames[j].anchors and frames[j].perceived(a)]
    if not seen:
        return
    rest = frames[seen[0]].anchors[a].position[2]        # where it stood, last seen
    opening = [g for j in range(seen[0] + 1, first + RECENT)
               if j < len(frames) and (g := _grip(episode, j, hand)) is not None]
    if not opening or first - seen[0] > RECENT:
        return
    # the grasp: where the grip came nearest (table plane) to where the object was believed as
    # it vanished, in the second it took it (hindsight knows the hand took it there)
    x, y, z = frames[seen[0]].anchors[a].position
    o = covered_by(seen[0], a)
    if o is not None and o != hand and frames[seen[0]].perceived(o):
        q = told(frames[seen[0]].anchors[o])
        x, y = q[0], q[1]
    nearest = min(math.hypot(g[0] - x, g[1] - y) for g in opening)
    vanishing = _grip(episode, seen[0] + 1, hand) or opening[0]
    low = min(g[2] for g in opening)
    heights, grips, lowest_seen = [], [], False
    last = 0.0
    for k in run:
        g = _grip(episode, k, hand)
        grips.append(None if g is None else round(g[2], 5))
        if g is not None:
            lowest_seen = lowest_seen or g[2] <= low + 1e-9
            last = max(0.0, g[2] - low) if lowest_seen else 0.0
        heights.append(round(last, 5))
    if released:
        # the hand let go where its last rise began (it put the object down, then rose empty
        # until the object was seen; the labels give the hand until then): the carry ends there
        end = len(heights) - 1
        while end > 0 and heights[end - 1] <= heights[end]:
            end -= 1
        heights, grips = heights[:end + 1], grips[:end + 1]
    if max(heights, default=0.0) < LIFTED:
        return                     # (the hand never rose with it: a hand hovering, no carry)
    top = z + frames[seen[0]].anchors[a].height / 2
    s.rows["grasp"].append([round(nearest, 5), round(vanishing[2] - top, 5), round(low - z, 5)])
    s.rows["hold"].append(round(low - rest, 5))
    s.rows["carries"].append({"heights": heights, "released": released, "grips": grips})
