"""The final world state as a Prolog file a person can query with ``prolog/shell/world.pl``.

The file holds plain facts:

- ``anchor(Atom, Symbol, Category, Perceived, LastSeen)``: every anchor;
- ``attribute(Atom, Name, Value)``: its attributes (position mean, size, colour names,
  category probabilities);
- ``particle(I, Weight)`` and ``particle_fact(I, Fact)``: the particle set of the filter, each
  particle's facts being ``pos(Atom, (X,Y,Z))`` and ``occluded_by(Atom, Occluder)``;
- ``identity(percept(Frame, Index), Atom, P)``: for each re-acquisition the run reported
  ambiguous, the probability of each candidate anchor;
- ``world_frame(Frame, Time)``: the frame the world model is after, and its time (s).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from bridge.terms import quote_atom, to_term
from probanchor.loop.loop import AnchoringLoop
from probanchor.loop.naming import category_atom, symbol_atom


def _fmt(x: float) -> str:
    return repr(float(round(x, 5)))


def frame_fact(frame: int, time: float) -> str:
    """``world_frame(Frame, Time).``: which frame a world model is after."""
    return f"world_frame({int(frame)}, {float(time)!r})."


def world_facts(loop: AnchoringLoop, perceived: set[str],
                particles: tuple[np.ndarray, list[tuple[int, str]]] | None = None,
                frame: tuple[int, float] | None = None) -> list[str]:
    """The world file's lines; ``particles``: :func:`particle_rows` when already at hand;
    ``frame``: the (frame, time) the world model is after, for ``world_frame/2``."""
    lines = [
        "% World state written by `anchoring run`; load with: "
        "swipl prolog/shell/world.pl THIS_FILE",
        ":- dynamic anchor/5, attribute/3, particle/2, particle_fact/2, identity/3, "
        "world_frame/2.",
        # each anchor's facts stand together (its anchor/5, then its attributes)
        ":- discontiguous anchor/5, attribute/3.",
    ]
    if frame is not None:
        lines.append(frame_fact(*frame))
    for anchor in loop.manager.anchors:
        atom = symbol_atom(anchor.symbol)
        mean = np.asarray(anchor.position.mean(), dtype=float)
        lines.append(
            f"anchor({atom}, {quote_atom(anchor.symbol)}, "
            f"{category_atom(anchor.best_category)}, "
            f"{'true' if anchor.symbol in perceived else 'false'}, "
            f"{_fmt(anchor.last_seen)})."
        )
        lines.append(f"attribute({atom}, position, ({', '.join(_fmt(v) for v in mean)})).")
        extents = np.asarray(anchor.size.mean(), dtype=float).reshape(-1)
        lines.append(f"attribute({atom}, size, ({', '.join(_fmt(v) for v in extents)})).")
        lines.append(f"attribute({atom}, colour_names, {to_term(list(anchor.colour_names))}).")
        categories = sorted(anchor.category.items(), key=lambda kv: -kv[1])
        pairs = ", ".join(f"{_fmt(p)}-{category_atom(c)}" for c, p in categories)
        lines.append(f"attribute({atom}, category, [{pairs}]).")
    for frame, index, candidates in loop.identity_answers():
        lines.extend(f"identity(percept({frame}, {index}), {symbol_atom(symbol)}, {_fmt(p)})."
                     for symbol, p in candidates.items())
    if loop.reasoner is not None:
        lines.extend(particle_facts(loop, particles))
    return lines


def particle_facts(loop: AnchoringLoop,
                   particles: tuple[np.ndarray, list[tuple[int, str]]] | None = None
                   ) -> list[str]:
    weights, facts = particles if particles is not None else particle_rows(loop)
    return particle_lines(weights, facts)


def particle_lines(weights: np.ndarray, facts: list[tuple[int, str]]) -> list[str]:
    """``particle(I, W).`` and ``particle_fact(I, Fact).`` lines of a particle set."""
    lines = [f"particle({i}, {float(w)!r})." for i, w in enumerate(weights)]
    lines.extend(f"particle_fact({i}, {fact})." for i, fact in facts)
    return lines


def particle_rows(loop: AnchoringLoop) -> tuple[np.ndarray, list[tuple[int, str]]]:
    """The filter's particle set: the weights, and each particle's facts as Prolog text.

    Parameters
    ----------
    loop:
        A loop with reasoning.

    Returns
    -------
    (weights, [(particle index, fact), ...]).
    """
    reasoner = loop.reasoner
    assert reasoner is not None
    facts: list[tuple[int, str]] = []
    for anchor in loop.manager.anchors:
        facts.extend(anchor_particle_facts(symbol_atom(anchor.symbol),
                                           reasoner.position_values(anchor.symbol),
                                           reasoner.particle_occluders(anchor.symbol)))
    return reasoner.weights(), facts


def anchor_particle_facts(atom: str, positions: Sequence[Any], occluders: Sequence[Any]
                          ) -> list[tuple[int, str]]:
    """One anchor's facts per particle: ``pos(Atom, (X,Y,Z))`` where the particle has a
    position (None or NaN: none), ``occluded_by(Atom, Occluder)`` where it has an occluder.

    Parameters
    ----------
    atom:
        The anchor's atom.
    positions, occluders:
        Per particle, its position (3 numbers) or None, its occluder or None.

    Returns
    -------
    [(particle index, fact), ...].
    """
    facts: list[tuple[int, str]] = []
    for i, (pos, occ) in enumerate(zip(positions, occluders, strict=True)):
        if pos is not None and not any(math.isnan(float(v)) for v in pos):
            x, y, z = (float(v) for v in pos)
            facts.append((i, f"pos({atom}, ({_fmt(x)}, {_fmt(y)}, {_fmt(z)}))"))
        if occ is not None:
            facts.append((i, f"occluded_by({atom}, {to_term(str(occ))})"))
    return facts


def write_world(path: Path, loop: AnchoringLoop, perceived: set[str],
                frame: tuple[int, float] | None = None) -> str | None:
    """Write the world file; the anchors' facts are written even when the filter's particles
    cannot be read (a filter that ran out of memory or stack).

    Parameters
    ----------
    path:
        The file to write.
    loop:
        The run's loop after its last frame.
    perceived:
        The symbols perceived in the last frame.
    frame:
        The last frame and its time, for ``world_frame/2``.

    Returns
    -------
    None, or why the particles are missing from the file (also said in the file).
    """
    try:
        lines = world_facts(loop, perceived, frame=frame)
        missing = None
    except Exception as exc:  # the particles could not be read: keep the anchors
        missing = f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}"
        lines = world_facts(loop, perceived, particles=(np.ones(0), []), frame=frame)
        lines.insert(1, f"% the particles could not be read from the filter: {missing}")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return missing
