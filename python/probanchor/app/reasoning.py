"""The reasoning side of the loop: anchors in, one filter step over the theory of occlusion,
position particles of hidden anchors out. The only module of :mod:`probanchor.app` that uses
:mod:`bridge`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from bridge import DEFAULT_THREADS, Filter, terms
from bridge.engines import Engine
from probanchor.app.naming import category_atom, symbol_atom
from probanchor.app.theories import DEFAULT_THEORY


@dataclass(frozen=True)
class AnchorState:
    """What the reasoning is told about one anchor in one frame."""

    symbol: str
    category: str
    position: tuple[float, float, float] | None  # perceived position, None when not perceived


@dataclass
class Belief:
    """The particles of one anchor's position (N x 3) and their normalised weights."""

    positions: np.ndarray
    weights: np.ndarray


class OcclusionReasoner:
    """A particle filter over the theory of occlusion, fed with anchors frame by frame."""

    def __init__(self, theory: str | Path = DEFAULT_THEORY, particles: int = 1000,
                 seed: int = 0, resample_threshold: float = 0.9,
                 threads: int = DEFAULT_THREADS, engine: Engine = "auto") -> None:
        self.theory = Path(theory)
        self.filter = Filter(self.theory, particles=particles, seed=seed,
                             resample_threshold=resample_threshold, threads=threads,
                             engine=engine)
        self._symbols: dict[str, str] = {}  # atom -> symbol

    @property
    def particles(self) -> int:
        return self.filter.particles

    def atom(self, symbol: str) -> str:
        atom = symbol_atom(symbol)
        self._symbols[atom] = symbol
        return atom

    def symbol(self, atom: str) -> str:
        return self._symbols.get(atom, atom)

    def step(self, anchors: Sequence[AnchorState]) -> None:
        """One frame: every anchor exists (``object/1``, ``category/2``); perceived ones are
        ``observed/1`` with ``observation(pos(A)) ~= (X,Y,Z)``."""
        facts: list[object] = []
        observations: list[object] = []
        for anchor in anchors:
            atom = self.atom(anchor.symbol)
            facts.append(terms.fact("object", atom))
            facts.append(terms.fact("category", atom, category_atom(anchor.category)))
            if anchor.position is not None:
                x, y, z = (float(v) for v in anchor.position)
                observations.append(terms.fact("observed", atom))
                observations.append(terms.observation(terms.fact("pos", atom), (x, y, z)))
        self.filter.step(observations, actions=facts)

    def belief(self, symbol: str) -> Belief | None:
        """The position particles of ``symbol`` (None where no particle knows the anchor)."""
        atom = self.atom(symbol)
        values, weights = self.filter.samples(f"pos({atom}):t")
        values = np.asarray(values, dtype=float).reshape(self.particles, -1)
        defined = ~np.isnan(values).any(axis=1)
        if not defined.any() or values.shape[1] != 3:
            return None
        w = weights[defined]
        total = float(w.sum())
        if total <= 0:
            return None
        return Belief(values[defined], w / total)

    def occluders(self, symbol: str) -> list[tuple[float, str]]:
        """``[(p, occluder symbol), ...]`` most probable first; the rest of the mass is on
        'not occluded'."""
        atom = self.atom(symbol)
        dist = self.filter.distribution("O", f"occluded_by({atom}, O):t")
        return [(p, self.symbol(str(o))) for p, o in dist]

    def probability(self, goal: str) -> float:
        return self.filter.probability(goal)

    def close(self) -> None:
        self.filter.close()

