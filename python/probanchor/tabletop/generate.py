"""Random shell games, built with :class:`tabletop.ScenarioBuilder`.

K containers (mugs, boxes and cups, turned over, in a row), one ball; a hand covers the
camera while the ball goes under a random container; S random swaps of two containers (the
ball moves with its container); then the containers are lifted one by one in random order.
The same seed gives the same game.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence

import numpy as np

from probanchor.tabletop.builder import ScenarioBuilder
from probanchor.tabletop.errors import ScenarioError
from probanchor.tabletop.scenario import Scenario

#: A box that covers a can, a cup or a mug in the occlusion games has at least this side (m);
#: a hand takes boxes of at most HAND_BOX.
BIG_BOX = 0.13
HAND_BOX = 0.11
#: the share of the balls and cans an occlusion game slides under a container where it stands
SLIDE_UNDER = 0.5
#: |x| (m) of a spot out of the camera's view, beside the table.
OUT_OF_VIEW = 0.95

CONTAINER_KINDS = (
    ("mug", {"radius": 0.04, "height": 0.1}),
    ("box", {"size": [0.12, 0.12, 0.12]}),
    ("cup", {"radius": 0.04, "height": 0.1}),
)
COLOURS = ("blue", "green", "white", "purple", "yellow", "cyan", "black", "orange")


def shell_game(containers: int = 3, swaps: int = 3, seed: int = 0, fps: float = 15.0,
               swap_duration: float = 2.0) -> ScenarioBuilder:
    """A random shell game with ``containers`` (2..5) containers and ``swaps`` swaps."""
    if not 2 <= containers <= 5:
        raise ValueError(f"containers must be 2 to 5, got {containers}")
    if swaps < 0:
        raise ValueError(f"swaps must be >= 0, got {swaps}")
    rng = np.random.default_rng(seed)
    b = ScenarioBuilder(f"shell_game_k{containers}_s{swaps}_seed{seed}", fps=fps)
    b.add("ball_1", "ball", "red", position=(0.0, -0.17), radius=0.03)
    spacing = 0.18  # wide enough for two 12 cm boxes side by side (their footprints must not touch)
    xs = (np.arange(containers) - (containers - 1) / 2) * spacing
    colours = rng.permutation(COLOURS)[:containers]
    counts: dict[str, int] = {}
    ids = []
    for i, x in enumerate(xs):
        kind, params = CONTAINER_KINDS[int(rng.integers(len(CONTAINER_KINDS)))]
        if i == 0 and containers >= 2:
            kind, params = CONTAINER_KINDS[0]
        counts[kind] = counts.get(kind, 0) + 1
        oid = f"{kind}_{counts[kind]}"
        ids.append(oid)
        b.add(oid, kind, str(colours[i]), position=(float(x), 0.06), **params)
    hider = ids[int(rng.integers(containers))]
    # where each container stands: the row, and the ball's place for the one put over it
    spot = {oid: (float(x), 0.06) for oid, x in zip(ids, xs, strict=True)}
    spot[hider] = (0.0, -0.17)
    t = 1.0
    b.cover_camera(t, duration=2.6)
    b.put_under(t + 0.2, "ball_1", hider, duration=2.2)
    t += 3.2
    for _ in range(swaps):
        a, c = rng.choice(containers, size=2, replace=False)
        b.swap(t, ids[int(a)], ids[int(c)], duration=swap_duration)
        spot[ids[int(a)]], spot[ids[int(c)]] = spot[ids[int(c)]], spot[ids[int(a)]]
        t += swap_duration + 0.4
    for i in rng.permutation(containers):
        x, y = spot[ids[int(i)]]
        # set down 13 cm further back, clear of the row; the one on the ball's place (in
        # front of the row) 13 cm to the side instead: further back it would land on the
        # row's middle container (two boxes 10 cm apart), in front it would hide the ball
        to = (x, y + 0.13) if y > 0 else (x + 0.13, y)
        b.lift(t, ids[int(i)], to=to, duration=2.0)
        t += 2.5
    return b


def _free_spot(rng: np.random.Generator, spots: list[tuple[float, float]],
               gap: float = 0.16) -> tuple[float, float]:
    """A table spot ``gap`` from the others (remembered: later objects keep clear of it)."""
    for _ in range(200):
        xy = (float(rng.uniform(-0.3, 0.3)), float(rng.uniform(-0.17, 0.2)))
        if all(np.hypot(xy[0] - a, xy[1] - c) > gap for a, c in spots):
            break
    spots.append(xy)
    return xy


SCENE_COLOURS = ["red", "orange", "yellow", "green", "cyan", "blue", "purple", "pink", "brown",
                 "white", "gray", "black"]


def _place_objects(b: ScenarioBuilder, rng: np.random.Generator,
                   free: Callable[[], tuple[float, float]], chosen: Sequence[str],
                   colours: Sequence[str], box_side: tuple[float, float] = (0.13, 0.16),
                   upright: float = 0.0
                   ) -> tuple[dict[str, list[str]], dict[str, tuple[float, float]]]:
    """Add one object per chosen category at a free spot, sized as its kind is: the ids per
    category and each object's position. Boxes are cubes with sides drawn from ``box_side``;
    bowls are 13 to 17 cm wide and 7.5 to 9 cm deep (a ball fits under), bottles 17 to 24 cm
    tall; a cup, mug or bowl stands upright (open side up: it cannot cover anything) with
    probability ``upright``, and is then listed under ``"upright"`` instead of its category."""
    ids: dict[str, list[str]] = {}
    where: dict[str, tuple[float, float]] = {}
    for k, (cat, col) in enumerate(zip(chosen, colours, strict=True)):
        oid = f"{cat}_{k}"
        xy = free()
        where[oid] = xy
        if cat == "ball":
            b.add(oid, cat, col, position=xy, radius=float(rng.uniform(0.025, 0.035)))
        elif cat in ("mug", "cup", "bowl"):
            params = ({"radius": float(rng.uniform(0.065, 0.085)),
                       "height": float(rng.uniform(0.075, 0.09))} if cat == "bowl" else
                      {"radius": float(rng.uniform(0.04, 0.045)),
                       "height": float(rng.uniform(0.09, 0.11))})
            stands = bool(upright) and rng.random() < upright
            if stands:
                params["upside_down"] = False
            b.add(oid, cat, col, position=xy, **params)
            if stands:
                ids.setdefault("upright", []).append(oid)
                continue
        elif cat == "can":
            b.add(oid, cat, col, position=xy, radius=0.033, height=0.12)
        elif cat == "bottle":
            b.add(oid, cat, col, position=xy, radius=float(rng.uniform(0.028, 0.038)),
                  height=float(rng.uniform(0.17, 0.24)))
        else:
            side = float(rng.uniform(*box_side))
            b.add(oid, cat, col, position=xy, size=[side, side, side])
        ids.setdefault(cat, []).append(oid)
    return ids, where


# Events both random tables use; each returns the time after it (``t`` itself when the event
# cannot take place on this table and nothing was added).


def _swap(b: ScenarioBuilder, rng: np.random.Generator, t: float, containers: Sequence[str],
          where: dict[str, tuple[float, float]]) -> float:
    """Two random containers swapped (whatever they cover goes with them)."""
    a, c = (str(x) for x in rng.choice(containers, 2, replace=False))
    b.swap(t, a, c, duration=float(rng.uniform(1.5, 2.5)))
    where[a], where[c] = where[c], where[a]
    return t + 3.0


def _lift(b: ScenarioBuilder, rng: np.random.Generator, t: float, hidden: dict[str, str],
          where: dict[str, tuple[float, float]], free: Callable[[float], tuple[float, float]]
          ) -> float:
    """The container over a random hidden object lifted off it, set down at a free spot."""
    obj = str(rng.choice(sorted(hidden)))
    box = hidden.pop(obj)
    where[box] = free(0.12)
    b.lift(t, box, to=where[box], duration=2.5)
    return t + 3.0


def _pass_in_front(b: ScenarioBuilder, rng: np.random.Generator, t: float,
                   boxes: Sequence[str], ids: dict[str, list[str]], hidden: dict[str, str],
                   where: dict[str, tuple[float, float]], spots: list[tuple[float, float]]
                   ) -> float:
    """A container (one of ``boxes``) moved in front of another object (between it and the
    camera, which looks from -y): the object is partly hidden, its percept a fragment."""
    box = str(rng.choice(boxes))
    others = [o for os_ in ids.values() for o in os_ if o != box and o not in hidden]
    if box in hidden.values() or not others:
        return t
    target = str(rng.choice(others))
    tx, ty = where[target]
    spot = (tx + float(rng.uniform(-0.03, 0.03)), ty - float(rng.uniform(0.15, 0.18)))
    if not (-0.32 < spot[0] < 0.32 and -0.2 < spot[1] < 0.22):
        return t
    spots.append(spot)
    b.move(t, box, to=spot, speed=float(rng.uniform(0.08, 0.2)))
    where[box] = spot
    return t + float(rng.uniform(3.0, 4.5))


def _cover(b: ScenarioBuilder, rng: np.random.Generator, t: float) -> float:
    """A hand over the camera for 1 to 2.5 s."""
    b.cover_camera(t, duration=float(rng.uniform(1.0, 2.5)))
    return t + 3.0


def _reveal_all(b: ScenarioBuilder, t: float, hidden: dict[str, str],
                free: Callable[[float], tuple[float, float]]) -> None:
    """The end of a table: every hidden object's container lifted off it, one after the
    other, and the scenario's duration set (1 s after the last)."""
    for obj in sorted(hidden):
        b.lift(t, hidden[obj], to=free(0.12), duration=2.5)
        t += 3.0
    b.data["duration"] = t + 1.0


def _leave_view(b: ScenarioBuilder, rng: np.random.Generator, t: float, movable: Sequence[str],
                hidden: dict[str, str], where: dict[str, tuple[float, float]],
                free: Callable[[float], tuple[float, float]]) -> float:
    """An object pushed out of the view sideways (what it covers goes with it), left there for
    1 to 3 s and pushed back to a free spot."""
    obj = str(rng.choice(movable))
    x, y = where[obj]
    out = (OUT_OF_VIEW if x >= 0 else -OUT_OF_VIEW, y)
    speed = float(rng.uniform(0.15, 0.3))
    b.move(t, obj, to=out, speed=speed)
    t += abs(out[0] - x) / speed + float(rng.uniform(1.0, 3.0))
    back = free(0.16)
    b.move(t, obj, to=back, speed=speed)
    t += float(np.hypot(back[0] - out[0], back[1] - out[1])) / speed + 1.0
    where[obj] = back
    for a, c in hidden.items():
        if c == obj:
            where[a] = back
    return t


def random_scene(seed: int) -> Scenario:
    """A random table scene with the events the scenarios use: objects pushed around (also past
    each other), balls and cans put under containers, containers swapped, moved and lifted, the
    camera covered; look-alike objects on purpose. About 12-18 s at 15 fps."""
    for attempt in range(50):
        rng = np.random.default_rng([seed, attempt])
        b = ScenarioBuilder(f"training-{seed}", fps=15)
        kinds = ["ball", "ball", "mug", "box", "can", "mug", "box", "cup"]
        n = int(rng.integers(3, 7))
        chosen = list(rng.choice(kinds, n, replace=False))
        colours = list(rng.choice(SCENE_COLOURS, n, replace=True))
        if rng.random() < 0.5 and chosen.count("ball") == 2:  # twins
            i, j = [k for k, c in enumerate(chosen) if c == "ball"]
            colours[j] = colours[i]
        spots: list[tuple[float, float]] = []
        free = functools.partial(_free_spot, rng, spots)
        ids, where = _place_objects(b, rng, free, chosen, colours)  # where: rough, for "front"
        containers = ids.get("mug", []) + ids.get("box", []) + ids.get("cup", [])
        small = ids.get("ball", []) + ids.get("can", [])
        t = 1.0
        hidden: dict[str, str] = {}
        for _ in range(int(rng.integers(3, 7))):
            what = rng.choice(["move", "move", "under", "swap", "lift", "cover", "front"])
            if what == "under" and small and containers:
                obj = str(rng.choice(small))
                free_c = [c for c in containers if c not in hidden.values()]
                if obj in hidden or not free_c:
                    continue
                box = str(rng.choice(free_c))
                if obj.startswith("can") and not box.startswith("box"):
                    continue
                b.put_under(t, obj, box, duration=2.5)
                hidden[obj] = box
                where[box] = where[obj]
                t += 3.0
            elif what == "swap" and len(containers) >= 2:
                t = _swap(b, rng, t, containers, where)
            elif what == "lift" and hidden:
                t = _lift(b, rng, t, hidden, where, free)
            elif what == "front" and containers:
                free_c = [c for c in containers if c not in hidden.values()]
                t = _pass_in_front(b, rng, t, free_c or containers, ids, hidden, where, spots)
            elif what == "cover":
                t = _cover(b, rng, t)
            else:
                movable = [o for os_ in ids.values() for o in os_ if o not in hidden]
                obj = str(rng.choice(movable))
                where[obj] = free(0.12)
                b.move(t, obj, to=where[obj], speed=float(rng.uniform(0.08, 0.25)))
                t += float(rng.uniform(2.0, 3.5))
        _reveal_all(b, t, hidden, free)
        try:
            return b.build()
        except ScenarioError:
            continue
    raise ValueError(f"could not build a valid random scene for seed {seed}")


def occlusion_game(seed: int) -> ScenarioBuilder:
    """A random table with many kinds of occlusion, for learning a theory of occlusion.

    Three to six objects (balls, cans, bottles, mugs, cups, bowls, boxes of 9 to 16 cm; balls,
    cans and bottles cover nothing; a cup, mug or bowl stands upright one time in five, and
    then covers nothing either) and six to ten events of: an object covered by a container
    (carried over it, with other containers near and far, or, half the balls and cans, slid
    under it where it stands; a ball under a mug, cup, bowl or box, a can, a mug or a cup under
    a box of 13 cm or more), a container carried with what it
    covers, two containers swapped, a container lifted off what it covers, an object (a ball,
    a can, a bottle, a bowl, a cup or mug that covers nothing, a box of 11 cm or less) grasped
    by a hand, carried
    and put down elsewhere, a container passing in front of an object (it is only behind, not
    under), the camera covered (sometimes while an object goes under a container), an object
    pushed elsewhere, an object (a container with what it covers) pushed out of the view and
    back to another place. Everything hidden is revealed at the end. About 15-35 s at 15 fps;
    the same seed gives the same game.
    """
    for attempt in range(50):
        rng = np.random.default_rng([seed, attempt, 17])
        b = ScenarioBuilder(f"occlusion_game_{seed}", fps=15)
        kinds = ["ball", "ball", "can", "mug", "cup", "box", "mug", "box", "cup", "bottle",
                 "bowl"]
        n = int(rng.integers(3, 7))
        chosen = list(rng.choice(kinds, n, replace=False))
        if not any(c in ("mug", "cup", "box", "bowl") for c in chosen):
            chosen[-1] = str(rng.choice(["mug", "cup", "box", "bowl"]))
        colours = list(rng.choice(SCENE_COLOURS, n, replace=True))
        spots: list[tuple[float, float]] = []
        free = functools.partial(_free_spot, rng, spots)
        ids, where = _place_objects(b, rng, free, chosen, colours, box_side=(0.09, 0.16),
                                    upright=0.2)   # where: rough, for "front"
        containers = (ids.get("mug", []) + ids.get("box", []) + ids.get("cup", [])
                      + ids.get("bowl", []))
        small = ids.get("ball", []) + ids.get("can", [])
        side = {o["id"]: float(o["size"][0]) for o in b.data["objects"] if "size" in o}
        t = 1.0
        hidden: dict[str, str] = {}       # object -> container over it
        events = int(rng.integers(6, 11))
        choices = ["under", "under", "under", "carry", "swap", "lift", "grasp", "front",
                   "cover", "cover_under", "move", "leave"]
        for _ in range(events):
            what = str(rng.choice(choices))
            # a container that covers something or is covered itself stays where it is
            free_c = [c for c in containers if c not in hidden.values() and c not in hidden]
            visible_small = [o for o in small if o not in hidden]
            coverable = visible_small + [c for c in free_c if c.startswith(("cup", "mug"))]
            if what in ("under", "cover_under") and coverable and free_c:
                box = str(rng.choice(free_c))
                fits = [o for o in coverable if o != box
                        and (o.startswith("ball") or side.get(box, 0.0) >= BIG_BOX)]
                if not fits:
                    continue
                obj = str(rng.choice(fits))
                # a ball or a can slid under the container where it stands half the time (the
                # container is carried over it otherwise): which container an object went
                # under is not always the one nearest to where it was last seen
                move = "object" if obj in small and rng.random() < SLIDE_UNDER else None
                if what == "cover_under":
                    b.cover_camera(t, duration=2.6)
                    b.put_under(t + 0.2, obj, box, duration=2.2, move=move)
                    t += 3.4
                else:
                    b.put_under(t, obj, box, duration=float(rng.uniform(2.0, 3.0)), move=move)
                    t += 3.2
                hidden[obj] = box
                if move:
                    where[obj] = where[box]
                else:
                    where[box] = where[obj]
            elif what == "carry" and hidden:
                obj = str(rng.choice(sorted(hidden)))
                box = hidden[obj]
                to = free(0.16)
                b.move(t, box, to=to, speed=float(rng.uniform(0.08, 0.18)))
                where[box] = where[obj] = to
                t += float(rng.uniform(3.0, 4.5))
            elif what == "swap" and len([c for c in containers if c not in hidden]) >= 2:
                t = _swap(b, rng, t, [c for c in containers if c not in hidden], where)
            elif what == "lift" and hidden:
                t = _lift(b, rng, t, hidden, where, free)
            elif what == "grasp" and (graspable := [
                    o for os_ in ids.values() for o in os_
                    if o not in hidden and o not in hidden.values()
                    and side.get(o, 0.0) <= HAND_BOX]):
                obj = str(rng.choice(graspable))
                b.pick_up(t, obj, duration=2.0)
                t += 2.5
                where[obj] = free(0.12)
                b.put_down(t, obj, to=where[obj], duration=float(rng.uniform(2.0, 3.0)))
                t += 3.5
            elif what == "front" and free_c:
                t = _pass_in_front(b, rng, t, free_c, ids, hidden, where, spots)
            elif what == "cover":
                t = _cover(b, rng, t)
            elif what == "leave":
                t = _leave_view(b, rng, t, [o for os_ in ids.values() for o in os_
                                            if o not in hidden], hidden, where, free)
            else:
                movable = [o for os_ in ids.values() for o in os_
                           if o not in hidden and o not in hidden.values()]
                if not movable:
                    continue
                obj = str(rng.choice(movable))
                where[obj] = free(0.12)
                b.move(t, obj, to=where[obj], speed=float(rng.uniform(0.08, 0.25)))
                t += float(rng.uniform(2.0, 3.5))
        _reveal_all(b, t, hidden, free)
        try:
            b.build()
        except ScenarioError:
            continue
        return b
    raise ValueError(f"could not build a valid occlusion game for seed {seed}")
