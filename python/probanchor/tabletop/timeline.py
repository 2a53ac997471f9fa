"""The scripted (kinematic) timeline: where every body is at time t.

Each event is compiled, when it starts, into motion segments (a body moving along a polyline
between two times, with smooth start and stop) and timed actions (attach an object to the
container over it or the hand holding it, detach, remove, cover the camera). Whatever is
attached to a body moves with it, transitively: a ball under a mug under a box moves with the
box. :meth:`Timeline.advance` plays all segments and actions in time order up to t, so the
state does not depend on the frame rate.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from probanchor.tabletop.errors import ScenarioError
from probanchor.tabletop.scenario import Event, ObjectSpec, Scenario

HAND_HOME = np.array([0.95, 0.15, 0.25])  # out of view, to the right of the table
CARRY_Z = 0.22  # height of the hand's centre while it carries something
GRAVITY = 9.81


def _smooth(s: float) -> float:
    s = min(max(s, 0.0), 1.0)
    return s * s * (3.0 - 2.0 * s)


@dataclass
class Segment:
    body: str
    t0: float
    t1: float
    points: list[np.ndarray]
    falling: bool = False  # uniformly accelerated (a free fall) instead of smooth

    def position(self, t: float) -> np.ndarray:
        f = min(max((t - self.t0) / (self.t1 - self.t0), 0.0), 1.0) if self.t1 > self.t0 \
            else 1.0
        s = f * f if self.falling else _smooth(f)
        lengths = [float(np.linalg.norm(b - a)) for a, b in zip(self.points, self.points[1:],
                                                               strict=False)]
        total = sum(lengths)
        if total <= 1e-12:
            return self.points[-1].copy()
        target = s * total
        last = len(lengths) - 1
        for i, (a, b, length) in enumerate(zip(self.points, self.points[1:], lengths,
                                                strict=False)):
            if target <= length or i == last:
                f = 0.0 if length <= 1e-12 else min(target / length, 1.0)
                return a + f * (b - a)
            target -= length
        return self.points[-1].copy()


@dataclass
class Action:
    time: float
    order: int
    apply: Callable[[], None]


@dataclass
class WorldState:
    """Positions (body centres) of objects and hands, and who holds or covers whom."""

    positions: dict[str, np.ndarray]
    parent: dict[str, str] = field(default_factory=dict)  # child -> container or hand
    present: set[str] = field(default_factory=set)
    covered: bool = False

    def children(self, body: str) -> list[str]:
        return [c for c, p in self.parent.items() if p == body]

    def descendants(self, body: str) -> list[str]:
        out, todo = [], [body]
        while todo:
            cur = todo.pop()
            for c in self.children(cur):
                out.append(c)
                todo.append(c)
        return out

    def move_to(self, body: str, position: np.ndarray) -> None:
        delta = position - self.positions[body]
        self.positions[body] = position.copy()
        for c in self.descendants(body):
            self.positions[c] = self.positions[c] + delta


class Timeline:
    """Plays a scenario's events. ``hands`` are the hand ids used by its events."""

    def __init__(self, scenario: Scenario, hand_half: tuple[float, float, float]) -> None:
        self.scenario = scenario
        self.objects: dict[str, ObjectSpec] = {o.id: o for o in scenario.objects}
        self.hand_half = np.asarray(hand_half, dtype=float)
        self.hands = sorted({ev.params.get("hand", "hand_1") for ev in scenario.events
                             if ev.kind in ("pick_up", "put_down")})
        positions = {o.id: np.asarray(o.position, dtype=float) for o in scenario.objects}
        for h in self.hands:
            positions[h] = HAND_HOME.copy()
        self.state = WorldState(positions=positions, present=set(self.objects))
        for o in scenario.objects:
            if o.under is not None:
                self.state.parent[o.id] = o.under
        self.pending = list(scenario.events)
        self.segments: list[Segment] = []
        self.actions: list[Action] = []
        self.time = -math.inf
        self._order = 0

    # ----------------------------------------------------------------------------- playing
    def advance(self, t: float) -> WorldState:
        """Play everything up to time ``t`` (non-decreasing) and return the state."""
        while True:
            candidates = [t]
            if self.pending:
                candidates.append(self.pending[0].at)
            candidates += [s.t1 for s in self.segments if s.t0 <= t]
            candidates += [a.time for a in self.actions]
            tt = min(candidates)
            if tt > t:
                tt = t
            self._play_segments(tt)
            while self.pending and self.pending[0].at <= tt:
                self._start(self.pending.pop(0))
                self._play_segments(tt)
            due = sorted((a for a in self.actions if a.time <= tt), key=lambda a: (a.time,
                                                                                    a.order))
            for a in due:
                self.actions.remove(a)
                a.apply()
            self._play_segments(tt)
            self.segments = [s for s in self.segments if s.t1 > tt]
            if tt >= t:
                break
        self.time = t
        return self.state

    def _play_segments(self, tt: float) -> None:
        for seg in sorted(self.segments, key=lambda s: s.t0):
            if seg.t0 <= tt:
                self.state.move_to(seg.body, seg.position(min(tt, seg.t1)))

    # ----------------------------------------------------------------------------- helpers
    def _fail(self, ev: Event, cause: str) -> ScenarioError:
        return ScenarioError(f"event '{ev.kind}' at {ev.at}: {cause}", self.scenario.source,
                             ev.line)

    def _pos(self, body: str) -> np.ndarray:
        return self.state.positions[body].copy()

    def _segment(self, body: str, t0: float, t1: float, *points: np.ndarray) -> None:
        self.segments.append(Segment(body, t0, t1, [np.asarray(p, float) for p in points]))

    def _action(self, time: float, fn: Callable[[], None]) -> None:
        self._order += 1
        self.actions.append(Action(time, self._order, fn))

    def _attach(self, child: str, parent: str) -> Callable[[], None]:
        def fn() -> None:
            self.state.parent[child] = parent
        return fn

    def _detach(self, child: str) -> Callable[[], None]:
        def fn() -> None:
            self.state.parent.pop(child, None)
        return fn

    def _point(self, xy: tuple[float, ...], z: float) -> np.ndarray:
        return np.array([xy[0], xy[1], xy[2] if len(xy) == 3 else z], dtype=float)

    def _require_free(self, ev: Event, oid: str) -> None:
        if oid not in self.state.present:
            raise self._fail(ev, f"'{oid}' has been removed")
        parent = self.state.parent.get(oid)
        if parent is not None:
            how = "held by" if parent.startswith("hand") else "under"
            raise self._fail(ev, f"'{oid}' is {how} '{parent}'")

    def _hand_offset(self, oid: str) -> np.ndarray:
        """From an object's centre to the centre of the hand holding it (bottoms level)."""
        obj = self.objects[oid]
        return np.array([0.0, 0.0, self.hand_half[2] - obj.half_extents()[2]])

    # ----------------------------------------------------------------------------- events
    def _start(self, ev: Event) -> None:
        getattr(self, f"_ev_{ev.kind}")(ev, ev.at, float(ev.params.get("duration", 2.0)))

    def _ev_move(self, ev: Event, t0: float, d: float) -> None:
        oid = ev.params["object"]
        body = oid
        parent = self.state.parent.get(oid)
        if parent is not None and parent.startswith("hand"):
            body = parent  # moving a held object moves the hand
        else:
            self._require_free(ev, oid)
        start = self._pos(oid)
        offset = self._pos(body) - start
        pts = [start] + [self._point(v, start[2]) for v in ev.params.get("via", [])]
        pts.append(self._point(ev.params["to"], start[2]))
        if "speed" in ev.params:
            length = sum(float(np.linalg.norm(b - a)) for a, b in zip(pts, pts[1:],
                                                                       strict=False))
            d = max(length / ev.params["speed"], 1e-3)
        self._segment(body, t0, t0 + d, *[p + offset for p in pts])
        rest = self.objects[oid].rest_z
        if body == oid and pts[-1][2] > rest + 1e-3:
            # let go above the table: it falls and settles (nothing is stacked)
            drop = float(pts[-1][2] - rest)
            self.segments.append(Segment(oid, t0 + d, t0 + d + math.sqrt(2 * drop / GRAVITY),
                                         [pts[-1], np.array([pts[-1][0], pts[-1][1], rest])],
                                         falling=True))

    def _ev_pick_up(self, ev: Event, t0: float, d: float) -> None:
        oid = ev.params["object"]
        hand = ev.params.get("hand", "hand_1")
        self._require_free(ev, oid)
        if self.state.children(hand):
            raise self._fail(ev, f"'{hand}' already holds {self.state.children(hand)}")
        obj = self.objects[oid]
        if np.any(np.asarray(obj.half_extents()) > self.hand_half - 0.006):
            raise self._fail(ev, f"'{oid}' is too big for the hand")
        grip = self._pos(oid) + self._hand_offset(oid)
        above = grip + np.array([0.0, 0.0, 0.12])
        carry = np.array([grip[0], grip[1], max(CARRY_Z, grip[2] + 0.1)])
        self._segment(hand, t0, t0 + 0.4 * d, self._pos(hand), above)
        self._segment(hand, t0 + 0.4 * d, t0 + 0.6 * d, above, grip)

        def grasp() -> None:
            for child in self.state.children(oid):  # what it covered stays on the table
                self.state.parent.pop(child, None)
            self.state.parent[oid] = hand
        self._action(t0 + 0.6 * d, grasp)
        self._segment(hand, t0 + 0.6 * d, t0 + d, grip, carry)

    def _ev_put_down(self, ev: Event, t0: float, d: float) -> None:
        oid = ev.params["object"]
        hand = self.state.parent.get(oid)
        if hand is None or not hand.startswith("hand"):
            raise self._fail(ev, f"'{oid}' is not held by a hand (pick it up first)")
        obj = self.objects[oid]
        target = self._point(ev.params["to"], obj.rest_z) + self._hand_offset(oid)
        above = target + np.array([0.0, 0.0, 0.12])
        start = self._pos(hand)
        self._segment(hand, t0, t0 + 0.4 * d, start, above)
        self._segment(hand, t0 + 0.4 * d, t0 + 0.6 * d, above, target)
        self._action(t0 + 0.6 * d, self._detach(oid))
        self._segment(hand, t0 + 0.6 * d, t0 + d, target, target + [0.0, 0.0, 0.15],
                      HAND_HOME)

    def _ev_put_under(self, ev: Event, t0: float, d: float) -> None:
        inner, outer = ev.params["object"], ev.params["container"]
        self._require_free(ev, inner)
        self._require_free(ev, outer)
        if self.state.children(outer):
            raise self._fail(ev, f"'{outer}' already covers {self.state.children(outer)}; "
                             "lift it first")
        o_in, o_out = self.objects[inner], self.objects[outer]
        p_in, p_out = self._pos(inner), self._pos(outer)
        top = p_in[2] + o_in.half_extents()[2]
        lift_z = max(top + o_out.half_extents()[2] + 0.03, p_out[2] + 0.05)
        dx, dy = o_out.cavity_offset()
        if ev.params.get("move") == "object":
            # the container is lifted where it stands, the object slides under it
            up = np.array([p_out[0], p_out[1], lift_z])
            spot = np.array([p_out[0] + dx, p_out[1] + dy, p_in[2]])
            self._segment(outer, t0, t0 + 0.3 * d, p_out, up)
            self._segment(inner, t0 + 0.3 * d, t0 + 0.7 * d, p_in, spot)
            self._segment(outer, t0 + 0.7 * d, t0 + d, up, [p_out[0], p_out[1], o_out.rest_z])
            self._action(t0 + d, self._attach(inner, outer))
            return
        final = np.array([p_in[0] - dx, p_in[1] - dy, o_out.rest_z])
        self._segment(outer, t0, t0 + 0.3 * d, p_out, [p_out[0], p_out[1], lift_z])
        self._segment(outer, t0 + 0.3 * d, t0 + 0.7 * d, [p_out[0], p_out[1], lift_z],
                      [final[0], final[1], lift_z])
        self._segment(outer, t0 + 0.7 * d, t0 + d, [final[0], final[1], lift_z], final)
        self._action(t0 + d, self._attach(inner, outer))

    def _ev_lift(self, ev: Event, t0: float, d: float) -> None:
        cont = ev.params["container"]
        self._require_free(ev, cont)
        for child in self.state.children(cont):
            self.state.parent.pop(child, None)
        obj = self.objects[cont]
        p = self._pos(cont)
        h = ev.params.get("height", 0.15)
        to = ev.params.get("to", (p[0], p[1] + 0.13))
        up = p + [0.0, 0.0, h]
        dest = self._point(to, obj.rest_z)
        self._segment(cont, t0, t0 + 0.35 * d, p, up)
        self._segment(cont, t0 + 0.35 * d, t0 + 0.7 * d, up, [dest[0], dest[1], up[2]])
        self._segment(cont, t0 + 0.7 * d, t0 + d, [dest[0], dest[1], up[2]], dest)

    def _swap_segments(self, a: str, b: str, pa: np.ndarray, pb: np.ndarray, t0: float,
                       t1: float) -> None:
        mid = (pa + pb) / 2
        along = pb[:2] - pa[:2]
        n = np.array([-along[1], along[0], 0.0]) / max(float(np.linalg.norm(along)), 1e-9)
        # sideways enough to pass each other, and anything standing between them
        reach = self.objects[a].footprint_radius() + self.objects[b].footprint_radius()
        off = max(0.6 * reach, 0.45 * float(np.linalg.norm(along)))
        oa, ob = self._clear_detour(a, b, pa, pb, mid, n, off, reach)
        self._segment(a, t0, t1, pa, mid + n * oa, pb)
        self._segment(b, t0, t1, pb, mid + n * ob, pa)

    def _clear_detour(self, a: str, b: str, pa: np.ndarray, pb: np.ndarray, mid: np.ndarray,
                      n: np.ndarray, off: float, reach: float) -> tuple[float, float]:
        """Signed sideways offsets of the two swapped containers' waypoints: ``(off, -off)``
        unless one of the paths would go through another object standing on the table (a
        container passing 6 cm from a mug of the row, inside it); then the offsets, on a
        2 cm grid, whose paths keep the most clearance from the other objects and from each
        other (each path sampled at the same fractions of its length, as both are played)."""
        skip = {a, b, *self.state.descendants(a), *self.state.descendants(b)}
        others = [o for o in self.objects if o in self.state.present and o not in skip
                  and self.state.parent.get(o) is None]
        if not others:
            return off, -off
        where = np.array([self._pos(o)[:2] for o in others])  # (K, 2)
        radius = np.array([self.objects[o].footprint_radius() for o in others])
        ra, rb = self.objects[a].footprint_radius(), self.objects[b].footprint_radius()
        f = np.linspace(0.0, 1.0, 21)[:, None]  # fractions of the move

        def path(p0: np.ndarray, w: np.ndarray, p1: np.ndarray) -> np.ndarray:
            # (S, 2): the polyline p0 -> w -> p1 at the fractions f of its length (as
            # Segment.position moves along it)
            l1, l2 = float(np.linalg.norm(w - p0)), float(np.linalg.norm(p1 - w))
            d = f * (l1 + l2)
            first = p0 + (w - p0) * np.minimum(d / max(l1, 1e-9), 1.0)
            return np.where(d <= l1, first, w + (p1 - w) * ((d - l1) / max(l2, 1e-9)))

        def clearance(oa: float, ob: float) -> float:
            wa, wb = mid[:2] + n[:2] * oa, mid[:2] + n[:2] * ob
            qa, qb = path(pa[:2], wa, pb[:2]), path(pb[:2], wb, pa[:2])
            da = np.linalg.norm(qa[:, None] - where[None], axis=2) - 0.9 * (ra + radius)
            db = np.linalg.norm(qb[:, None] - where[None], axis=2) - 0.9 * (rb + radius)
            dab = np.linalg.norm(qa - qb, axis=1) - 0.9 * reach
            return float(min(da.min(), db.min(), dab.min()))

        if clearance(off, -off) >= 0:
            return off, -off
        grid = np.arange(-0.36, 0.3601, 0.02)
        best = max((clearance(x, y), -abs(x) - abs(y), x, y) for x in grid for y in grid
                    if abs(x - y) >= reach)
        return (float(best[2]), float(best[3])) if best[0] > clearance(off, -off) \
            else (off, -off)

    def _ev_swap(self, ev: Event, t0: float, d: float) -> None:
        a, b = ev.params["a"], ev.params["b"]
        self._require_free(ev, a)
        self._require_free(ev, b)
        self._swap_segments(a, b, self._pos(a), self._pos(b), t0, t0 + d)

    def _ev_shuffle(self, ev: Event, t0: float, d: float) -> None:
        conts, order = ev.params["containers"], ev.params["order"]
        for c in conts:
            self._require_free(ev, c)
        slots = [self._pos(c) for c in conts]
        where = {c: i for i, c in enumerate(conts)}  # container -> slot it occupies now
        target = {c: conts.index(o) for c, o in zip(conts, order, strict=True)}
        swaps: list[tuple[str, str, int, int]] = []
        for s in range(len(conts)):
            want = next(c for c in conts if target[c] == s)
            here = next(c for c in conts if where[c] == s)
            if want != here:
                swaps.append((want, here, where[want], s))
                where[want], where[here] = s, where[want]
        step = d / max(len(swaps), 1)
        for k, (x, y, sx, sy) in enumerate(swaps):
            self._swap_segments(x, y, slots[sx], slots[sy], t0 + k * step, t0 + (k + 1) * step)

    def _ev_cover_camera(self, ev: Event, t0: float, d: float) -> None:
        def cover(flag: bool) -> Callable[[], None]:
            def fn() -> None:
                self.state.covered = flag
            return fn
        self._action(t0, cover(True))
        self._action(t0 + d, cover(False))

    def _ev_remove(self, ev: Event, t0: float, d: float) -> None:
        oid = ev.params["object"]

        def fn() -> None:
            self.state.present.discard(oid)
            self.state.parent.pop(oid, None)
            for child in self.state.children(oid):
                self.state.parent.pop(child, None)
        self._action(t0 + d, fn)
