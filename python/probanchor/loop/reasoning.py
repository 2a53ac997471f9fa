"""The reasoning side of the loop: anchors in, one filter step over the theory of occlusion,
position particles of hidden anchors out. The only module of :mod:`probanchor.loop` that uses
:mod:`bridge`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from anchoring.identity import AmbiguousPercept, IdentityHypotheses, Revision
from bridge import DEFAULT_THREADS, Filter, terms
from bridge.engines import Engine
from probanchor.loop.naming import category_atom, symbol_atom
from probanchor.loop.theories import DEFAULT_THEORY


@dataclass(frozen=True)
class AnchorState:
    """What the reasoning is told about one anchor in one frame."""

    symbol: str
    category: str
    position: tuple[float, float, float] | None  # perceived position, None when not perceived


@dataclass
class Belief:
    """The particles of one anchor's position (N x 3), their normalised weights, and which
    occluder each has the anchor under (``occluder``, (N,) int: an index into the symbols the
    belief was asked about, -1 for none; anchoring.likelihood, the records)."""

    positions: np.ndarray
    weights: np.ndarray
    occluder: np.ndarray | None = None
    symbols: tuple[str, ...] = ()

    @property
    def occluded(self) -> np.ndarray | None:
        """(N,) bool: whether each particle has the anchor under an occluder."""
        return None if self.occluder is None else self.occluder >= 0

    def occluders(self) -> dict[str, float]:
        """Occluder symbol -> probability (the rest of the mass: under nothing)."""
        if self.occluder is None:
            return {}
        inside = self.occluder >= 0
        mass = np.bincount(self.occluder[inside], weights=self.weights[inside],
                           minlength=len(self.symbols))
        return {self.symbols[i]: float(mass[i]) for i in np.argsort(-mass) if mass[i] > 0}


class OcclusionReasoner:
    """A particle filter over the theory of occlusion, fed with anchors frame by frame, with
    the identity hypotheses of look-alike anchors kept in its particles
    (:class:`anchoring.identity.IdentityHypotheses`, to which it is the
    :class:`anchoring.identity.ParticleWorlds`)."""

    def __init__(self, theory: str | Path = DEFAULT_THEORY, particles: int = 1000,
                 seed: int = 0, resample_threshold: float = 0.9,
                 threads: int = DEFAULT_THREADS, engine: Engine = "auto",
                 identity_kernel: float = 0.05) -> None:
        self.theory = Path(theory)
        self.filter = Filter(self.theory, particles=particles, seed=seed,
                             resample_threshold=resample_threshold, threads=threads,
                             engine=engine)
        self._symbols: dict[str, str] = {}  # atom -> symbol
        self.identity = IdentityHypotheses(self, kernel=identity_kernel,
                                           seed=seed + 7919)

    @property
    def particles(self) -> int:
        return self.filter.particles

    # --- anchoring.identity.ParticleWorlds ----------------------------------------------
    def weights(self) -> np.ndarray:
        return self.filter.weights

    def positions(self, symbol: str) -> np.ndarray:
        values, _ = self.filter.samples(f"pos({self.atom(symbol)}):t")
        values = np.asarray(values, dtype=float)
        if values.ndim != 2 or values.shape[1] != 3:
            return np.full((self.particles, 3), np.nan)
        return values

    def position_values(self, symbol: str) -> list[object]:
        """Per particle, ``symbol``'s position as Prolog gave it (an (x, y, z) tuple), None
        where the particle has none (:meth:`positions` as an array)."""
        return self.filter.values("P", f"pos({self.atom(symbol)}):t ~= P")

    def particle_occluders(self, symbol: str) -> list[str | None]:
        """Per particle, the atom of the occluder it has ``symbol`` under (None: none)."""
        return [None if o is None else str(o)
                for o in self.filter.values("O", f"occluded_by({self.atom(symbol)}, O):t")]

    def rename(self, mapping: Mapping[str, str], particles: np.ndarray | None) -> None:
        self.filter.rename({self.atom(a): self.atom(b) for a, b in mapping.items()}, particles)

    def reweight(self, log_factors: np.ndarray) -> None:
        self.filter.reweight(log_factors)

    def particle_data(self):  # type: ignore[no-untyped-def]
        return self.filter.particle_data

    # --- one frame ----------------------------------------------------------------------
    def reason(self, anchors: Sequence[AnchorState], ambiguous: Sequence[AmbiguousPercept] = (),
               frame: int = 0, evidence: Sequence[str] = ()) -> list[Revision]:
        """One frame: each particle answers the frame's ambiguities (renamed to its answer),
        the filter steps on the anchors, then the answers later evidence decided otherwise
        are revised (the caller renames its anchors by each revision's mapping)."""
        known = {a.symbol for a in anchors}
        usable = [a for a in ambiguous if set(a.candidates) <= known]
        if usable:
            self.identity.associate(usable)
        self.step(anchors)
        if not self.identity.open:
            return []
        return self.identity.revise(frame, evidence, alive=sorted(known))

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
        # (while identity answers are open, a resampling keeps each of them alive)
        self.filter.step(observations, actions=facts, strata=self.identity.strata(),
                         keep=self.identity.keep)

    def belief(self, symbol: str, occluders: Sequence[str] = ()) -> Belief | None:
        """The position particles of ``symbol`` (None where no particle knows the anchor),
        read with the occluder each particle has it under (one of ``occluders``, by index;
        -1 for none or another): two queries that read the filter's columns as they are."""
        atom = self.atom(symbol)
        values, weights = self.filter.samples(f"pos({atom}):t")
        if values.dtype == object or values.ndim != 2 or values.shape[1] != 3:
            return None  # no particle has a position for it
        defined = ~np.isnan(values).any(axis=1)
        if not defined.any():
            return None
        w = weights[defined]
        total = float(w.sum())
        if total <= 0:
            return None
        under = self.filter.indices("O", f"occluded_by({atom}, O):t",
                                    [self.atom(o) for o in occluders])
        return Belief(values[defined], w / total, under[defined], tuple(occluders))

    def occluders(self, symbol: str) -> list[tuple[float, str]]:
        """``[(p, occluder symbol), ...]`` most probable first; the rest of the mass is on
        'not occluded'."""
        atom = self.atom(symbol)
        dist = self.filter.distribution("O", f"occluded_by({atom}, O):t")
        return [(p, self.symbol(str(o))) for p, o in dist]

    def probability(self, goal: str) -> float:
        return self.filter.probability(goal)

    def reappear_radius(self) -> float | None:
        """The standard deviation (metres) of where the theory has a hidden object seen again
        around its belief: the square root of its ``reappear_var/1`` (hand-written in too.pl,
        fitted from the data in a learned theory), None for a theory without one."""
        values = [v for v in self.filter.values("V", "reappear_var(V)") if v is not None]
        if not values or not isinstance(values[0], int | float) or not values[0] > 0:
            return None
        return float(values[0]) ** 0.5

    def close(self) -> None:
        self.filter.close()

