"""Identity hypotheses kept in the particles, weighed by later evidence, and revised.

When anchoring cannot tell which of several look-alike anchors a percept is (two identical
mugs swapped while the camera was covered; a ball seen again where the beliefs of two
identical balls both have mass), it still gives the percept one symbol (the most probable
assignment), but the question stays open: **each particle of the reasoning's filter samples
its own answer** and its world is renamed to match (data association inside the particles,
Särkkä, Vehtari and Lampinen 2007). A particle that has the swapped mugs has, from then on,
the red ball under the *other* mug; when a mug is lifted and shows what it hid, the particles
whose answer explains it keep their weight and the others lose it, so the earlier answer is
re-weighed by evidence that came later. When the particles come to prefer another answer
than the symbols anchoring gave, the symbols are revised.

The hypotheses of one frame's ambiguity group ``G`` (the look-alike anchors involved, ``k``
of them; ``L`` ranges over them) are the permutations ``sigma`` of ``G``: "the track anchoring
now names ``L`` is the object that was named ``sigma(L)``". Particle ``i`` draws one from the
proposal (a defensive mixture: half from how well each answer fits the particle's own belief,
half uniform, so that an answer the beliefs dislike keeps particles until the evidence is
in)::

    q_i(sigma) = 1/2 softmax_sigma( sum_L [ log A(L, sigma(L))
                                            + log N(x_L; s_i(sigma(L)), r^2 I) ] ) + 1/2 (1/k!)

where ``x_L`` is the position of the percept given ``L`` this frame (labels not perceived
this frame contribute nothing), ``s_i(M)`` is ``M``'s position in particle ``i`` and
``log A`` the appearance log likelihood ratio (:mod:`anchoring.likelihood`). The particle's
world is renamed by ``sigma`` (what was ``sigma(L)``'s is now ``L``'s) and its weight is
multiplied by the prior and the appearance over the proposal::

    w_i <- w_i * (1/k!) * prod_L A(L, sigma_i(L)) / A(L, L) / q_i(sigma_i)

then the filter's step multiplies in the likelihood of every observation under the renamed
world (where each hidden object and each reappearing one is), which is what weighs the
answers. Each particle also carries, as data that follows resampling, the original name of
the object each tracked label stands for (``identity``); the posterior of an identity is the
weight of the particles that agree::

    P(label L is the object first named X) = sum_i w_i [identity_i(L) = X]

**Revision.** After each step, for every open group the most probable joint answer (the row
of ``identity`` over the group's labels with the most weight) is compared with the symbols as
given. If another answer has at least ``revise_probability`` of the mass and ``revise_odds``
times the mass of the answer as given (hysteresis: sampling noise around an even split does
not flip symbols back and forth), the anchors are renamed to it
(:meth:`anchoring.AnchorManager.relabel`), so is every particle's world, and a
:class:`Revision` is reported: from this frame on each anchor carries the symbol of the
object it most probably is, and the frames since the group opened are answered anew (the
evaluation's "identity at the end").

**Keeping improbable answers.** An answer with a thousandth of the weight can still be the one
later evidence confirms (two look-alike mugs swapped 60 cm apart while the camera was covered:
where they are seen again makes the swap improbable, what one of them hides then makes it
certain, by a likelihood ratio of e^50). Plain resampling keeps an answer of weight ``p`` in
about ``N p`` particles, so an answer of 1e-4 among 1,000 particles dies by chance, and with it
the question. While a group is open, the filter therefore resamples each answer on its own
(:meth:`strata`: the particles' joint answers to the open groups are the strata of a mixture
resampling, Vermaak, Doucet and Pérez 2003): every answer with at least ``refuted`` of the
weight keeps at least ``keep_share`` of the particles, at a weight that keeps its mass, so
the weights stay a faithful picture of the posterior while the improbable answer keeps enough
particles to be weighed by what comes. Answers below ``refuted`` (evidence against them of
e^20 and more) are resampled with the most probable one, where they die out as before.

**Pruning.** A group is closed (its labels are no longer tracked) once the other answers
hold no more than ``close_tolerance`` of the weight: by default none, i.e. once no particle
holds one, which happens once they fell below ``refuted`` and the resampling let them go.
The ambiguous percepts' own identity columns stay for the world model's
``prob(identity(Percept, Symbol), P)``.

Cost: per ambiguity group and frame it opens, ``k!`` proposals per particle (``k`` <= 5 is
enumerated; larger groups only consider the answers that move one perceived label), one
rename per distinct answer drawn; per frame, one weighted count over the open groups' rows.
Nothing is paid in frames without an open group.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

#: The largest group whose answers are all enumerated (5! = 120 permutations).
MAX_ENUMERATED = 5


class ParticleWorlds(Protocol):
    """What the identity hypotheses need of the reasoning's particle filter."""

    @property
    def particles(self) -> int: ...

    def weights(self) -> np.ndarray:
        """The particles' normalised weights (N,)."""
        ...

    def positions(self, symbol: str) -> np.ndarray:
        """(N, 3): ``symbol``'s position in each particle (NaN where it has none)."""
        ...

    def rename(self, mapping: Mapping[str, str], particles: np.ndarray | None) -> None:
        """In the given particles (all with None), what was named ``old`` is named
        ``mapping[old]`` (a permutation of symbols)."""
        ...

    def reweight(self, log_factors: np.ndarray) -> None:
        """Multiply the particles' weights by ``exp(log_factors)`` (N,)."""
        ...

    def particle_data(self) -> dict[str, np.ndarray]:
        """Arrays with one row per particle that the filter resamples with the particles."""
        ...


@dataclass
class AmbiguousPercept:
    """One percept anchoring could not tell among look-alikes: it was given ``label``;
    ``candidates`` are the anchors it may be (``label`` among them), ``appearance`` the
    appearance log likelihood ratio of the percept against each, ``position`` where it is."""

    frame: int
    percept_index: int
    label: str
    candidates: tuple[str, ...]
    appearance: Mapping[str, float]
    position: np.ndarray


@dataclass
class Revision:
    """Later evidence decided an earlier ambiguity otherwise: from ``frame`` on, the anchor
    that was named ``old`` is named ``mapping[old]`` (each key a symbol before, each value the
    symbol after). ``since`` per symbol (before): the frame from which its answers change;
    ``probability``: the weight of the new answer; ``before``: that of the answer as given;
    ``evidence``: the anchors perceived again in the frame that decided it."""

    frame: int
    mapping: dict[str, str]
    since: dict[str, int]
    probability: float
    before: float
    evidence: list[str] = field(default_factory=list)

    def to_json(self) -> dict[str, object]:
        return {"frame": self.frame, "mapping": dict(self.mapping), "since": dict(self.since),
                "probability": self.probability, "before": self.before,
                "evidence": list(self.evidence)}

    @classmethod
    def from_json(cls, record: Mapping[str, object]) -> Revision:
        return cls(int(record["frame"]),  # type: ignore[arg-type]
                   {str(k): str(v) for k, v in dict(record["mapping"]).items()},  # type: ignore[arg-type]
                   {str(k): int(v) for k, v in dict(record["since"]).items()},  # type: ignore[arg-type]
                   float(record["probability"]), float(record["before"]),  # type: ignore[arg-type]
                   [str(s) for s in record.get("evidence", [])])  # type: ignore[union-attr]


@dataclass
class _Group:
    labels: list[str]
    since: dict[str, int]


class IdentityHypotheses:
    """The identity hypotheses of one run, kept in a :class:`ParticleWorlds`'s particles.

    Parameters
    ----------
    worlds : ParticleWorlds
        The reasoning's particles.
    kernel : float
        ``r``: the spread (metres) of a belief around a particle in the proposal.
    revise_probability : float
        The least weight of another answer than the symbols as given for a revision.
    revise_odds : float
        ... and how many times the weight of the answer as given it must have.
    close_tolerance : float
        A group whose other answers hold at most this much of the weight is closed (0: once
        no particle holds one).
    refuted : float
        An answer with less weight than this is let die out by the resampling; one with
        more keeps particles (:meth:`strata`).
    keep_share : float
        The least share of the particles each answer above ``refuted`` keeps at a
        resampling (at least one particle).
    max_kept : int
        The most answers kept apart at a resampling (the heaviest; with ``keep_share`` this
        bounds the particles given to improbable answers).
    seed : int
        Of the random stream the answers are drawn from.
    """

    def __init__(self, worlds: ParticleWorlds, kernel: float = 0.05,
                 revise_probability: float = 0.5, revise_odds: float = 2.0,
                 close_tolerance: float = 0.0, refuted: float = 1e-9,
                 keep_share: float = 0.01, max_kept: int = 6, seed: int = 0) -> None:
        if not kernel > 0:
            raise ValueError(f"kernel must be positive, not {kernel!r}")
        if not 0.0 < revise_probability <= 1.0:
            raise ValueError(f"revise_probability must be in (0, 1], not {revise_probability!r}")
        if not revise_odds >= 1.0:
            raise ValueError(f"revise_odds must be at least 1, not {revise_odds!r}")
        if not 0.0 <= close_tolerance < 1.0:
            raise ValueError(f"close_tolerance must be in [0, 1), not {close_tolerance!r}")
        self.worlds = worlds
        self.kernel = float(kernel)
        self.revise_probability = float(revise_probability)
        self.revise_odds = float(revise_odds)
        self.close_tolerance = float(close_tolerance)
        if not 0.0 <= refuted < 1.0:
            raise ValueError(f"refuted must be in [0, 1), not {refuted!r}")
        if not 0.0 < keep_share <= 0.1:
            raise ValueError(f"keep_share must be in (0, 0.1], not {keep_share!r}")
        if isinstance(max_kept, bool) or not isinstance(max_kept, int) or max_kept < 1:
            raise ValueError(f"max_kept must be a positive integer, not {max_kept!r}")
        self.refuted = float(refuted)
        self.keep_share = float(keep_share)
        self.max_kept = max_kept
        self._rng = np.random.default_rng(seed)
        self.names: list[str] = []          # identity index -> the name it was first given
        self._index: dict[str, int] = {}
        self.columns: list[str] = []        # the labels whose identity each column tracks
        self.groups: list[_Group] = []
        self.percepts: list[AmbiguousPercept] = []  # each with a data column percept:<k>
        self.revisions: list[Revision] = []

    # --- state in the particles ----------------------------------------------------------
    def _name_index(self, name: str) -> int:
        if name not in self._index:
            self._index[name] = len(self.names)
            self.names.append(name)
        return self._index[name]

    def _table(self) -> np.ndarray:
        data = self.worlds.particle_data()
        table = data.get("identity")
        if table is None or table.shape[1] != len(self.columns):
            raise RuntimeError("the identity table and its columns disagree")
        return table

    def _ensure_columns(self, labels: Sequence[str]) -> None:
        new = [label for label in labels if label not in self.columns]
        if not new:
            return
        data = self.worlds.particle_data()
        n = self.worlds.particles
        added = np.array([[self._name_index(label) for label in new]], dtype=np.int32)
        old = data.get("identity", np.zeros((n, 0), dtype=np.int32))
        data["identity"] = np.concatenate([old, np.repeat(added, n, axis=0)], axis=1)
        self.columns.extend(new)

    @property
    def open(self) -> bool:
        """Whether any group is open (something is still undecided)."""
        return bool(self.groups)

    # --- one frame: before the filter's step ---------------------------------------------
    def associate(self, ambiguous: Sequence[AmbiguousPercept]) -> None:
        """Draw each particle's answer to this frame's ambiguities and rename its world
        (call before the filter steps on the frame's observations)."""
        for group in _connected(ambiguous):
            labels = sorted({c for a in group for c in a.candidates})
            if len(labels) < 2 or not self._draw(labels, group):
                continue
            self._merge_group(labels, min(a.frame for a in group))
            table = self._table()
            for a in group:
                self.worlds.particle_data()[f"percept:{len(self.percepts)}"] = \
                    table[:, self.columns.index(a.label)].copy()
                self.percepts.append(a)

    def _draw(self, labels: list[str], group: Sequence[AmbiguousPercept]) -> bool:
        """Each particle draws its answer for the group and is renamed; False when the group
        has one answer only."""
        n = self.worlds.particles
        index = {label: k for k, label in enumerate(labels)}
        seen = [(a.label, np.asarray(a.position, dtype=float), a.appearance) for a in group]
        # an answer may give a percept only an anchor it could be (one of its candidates)
        perms = [sigma for sigma in _answers(labels, {a.label for a in group})
                 if all(labels[sigma[index[label]]] in app or labels[sigma[index[label]]] == label
                        for label, _, app in seen)]
        if len(perms) < 2:
            return False
        positions = {label: self.worlds.positions(label) for label in labels}
        # log q~ (N, P) and the appearance term (P,)
        fit = np.zeros((n, len(perms)))
        appearance = np.zeros(len(perms))
        for p, sigma in enumerate(perms):
            for label, x, app in seen:
                other = labels[sigma[index[label]]]
                appearance[p] += app.get(other, 0.0) - app.get(label, 0.0)
                d2 = ((positions[other] - x) ** 2).sum(axis=1)
                fit[:, p] += np.where(np.isnan(d2), -50.0, -0.5 * d2 / self.kernel ** 2)
        fit += appearance[None, :]
        fit -= fit.max(axis=1, keepdims=True)
        q = np.exp(fit)
        q /= q.sum(axis=1, keepdims=True)
        q = 0.5 * q + 0.5 / len(perms)
        u = self._rng.random(n)
        drawn = np.minimum((q.cumsum(axis=1) < u[:, None]).sum(axis=1), len(perms) - 1)
        log_prior = -math.log(len(perms))
        with np.errstate(divide="ignore"):
            log_factor = log_prior + appearance[drawn] - np.log(q[np.arange(n), drawn])
        self._ensure_columns(labels)
        table = self._table()
        cols = np.array([self.columns.index(label) for label in labels])
        for p, sigma in enumerate(perms):
            chosen = np.flatnonzero(drawn == p)
            if chosen.size == 0 or all(s == k for k, s in enumerate(sigma)):
                continue
            # what was labels[sigma[k]]'s is now labels[k]'s
            self.worlds.rename({labels[sigma[k]]: labels[k] for k in range(len(labels))},
                               chosen)
            block = table[np.ix_(chosen, cols)]
            table[np.ix_(chosen, cols)] = block[:, list(sigma)]
        self.worlds.reweight(log_factor - np.max(log_factor[np.isfinite(log_factor)]))
        return True

    def _merge_group(self, labels: list[str], frame: int) -> None:
        merged = _Group(list(labels), {label: frame for label in labels})
        keep: list[_Group] = []
        for g in self.groups:
            if set(g.labels) & set(labels):
                for label in g.labels:
                    if label not in merged.since:
                        merged.labels.append(label)
                    merged.since[label] = min(merged.since.get(label, frame), g.since[label])
            else:
                keep.append(g)
        merged.labels.sort()
        self.groups = [*keep, merged]

    # --- one frame: the filter's step ---------------------------------------------------
    @property
    def keep(self) -> int:
        """The least number of particles an answer keeps at a resampling (:meth:`strata`)."""
        return max(1, round(self.keep_share * self.worlds.particles))

    def strata(self) -> np.ndarray | None:
        """Per particle, the stratum of a resampling that keeps the open groups' answers
        (the filter's ``strata``; None when no group is open or one answer holds it all).

        A particle's answer is its row of identities over every open group's labels. The
        :attr:`max_kept` heaviest answers with at least :attr:`refuted` of the weight are
        strata of their own (0 the heaviest); every other answer is resampled with the
        heaviest::

            stratum_i = rank(answer_i)  if answer_i is kept,  else 0
        """
        if not self.groups:
            return None
        labels = [label for g in self.groups for label in g.labels]
        table = self._table()[:, [self.columns.index(label) for label in labels]]
        unique, inverse = np.unique(table, axis=0, return_inverse=True)
        mass = np.bincount(inverse.reshape(-1), weights=self.worlds.weights(),
                           minlength=len(unique))
        order = np.argsort(-mass, kind="stable")
        rank = np.zeros(len(unique), dtype=np.int64)
        kept = [a for a in order[:self.max_kept] if mass[a] >= self.refuted]
        if len(kept) < 2:
            return None
        rank[kept] = np.arange(len(kept))
        return rank[inverse.reshape(-1)]

    # --- one frame: after the filter's step ----------------------------------------------
    def revise(self, frame: int, evidence: Sequence[str] = (),
               alive: Sequence[str] | None = None) -> list[Revision]:
        """Revise the groups whose most probable answer is not the symbols as given; close
        those that are decided; forget groups with an anchor no longer ``alive``. The caller
        renames its anchors by each returned revision's mapping."""
        if not self.groups:
            return []
        if alive is not None:
            living = set(alive)
            self.groups = [g for g in self.groups if set(g.labels) <= living]
        out: list[Revision] = []
        still: list[_Group] = []
        weights = self.worlds.weights()
        for g in self.groups:
            table = self._table()
            cols = [self.columns.index(label) for label in g.labels]
            rows, mass = _answer_mass(table[:, cols], weights)
            given = np.array([self._index[label] for label in g.labels])
            is_given = (rows == given[None, :]).all(axis=1)
            p_given = float(mass[is_given].sum())
            best = int(np.argmax(mass))
            p_best = float(mass[best])
            if (not is_given[best] and p_best >= self.revise_probability
                    and p_best >= self.revise_odds * p_given and p_best > p_given):
                mapping = {label: self.names[int(rows[best, k])]
                           for k, label in enumerate(g.labels)}
                mapping = {k: v for k, v in mapping.items() if k != v}
                if set(mapping) == set(mapping.values()):
                    self._apply(mapping)
                    revision = Revision(frame, mapping, {s: g.since[s] for s in mapping},
                                        p_best, p_given, list(evidence))
                    out.append(revision)
                    g.labels = sorted(mapping.get(s, s) for s in g.labels)
                    g.since = {mapping.get(s, s): f for s, f in g.since.items()}
                    p_given = p_best
            if float(mass.sum()) - p_given > self.close_tolerance:
                still.append(g)
        self.groups = still
        self.revisions.extend(out)
        return out

    def _apply(self, mapping: dict[str, str]) -> None:
        self.worlds.rename(mapping, None)
        self.columns = [mapping.get(label, label) for label in self.columns]

    # --- answers -------------------------------------------------------------------------
    def probabilities(self, label: str) -> dict[str, float]:
        """The identity of the anchor now named ``label``: name -> probability (the name it
        is given with probability 1 when it is not in question)."""
        if label not in self.columns:
            return {label: 1.0}
        return self._distribution(self._table()[:, self.columns.index(label)])

    def percept_probabilities(self, k: int) -> dict[str, float]:
        """The identity of the ``k``-th ambiguous percept (:attr:`percepts`), as the
        particles answer it now."""
        return self._distribution(self.worlds.particle_data()[f"percept:{k}"])

    def _distribution(self, column: np.ndarray) -> dict[str, float]:
        weights = self.worlds.weights()
        mass = np.bincount(column, weights=weights, minlength=len(self.names))
        return {self.names[i]: float(mass[i]) for i in np.argsort(-mass) if mass[i] > 0}


def _connected(ambiguous: Sequence[AmbiguousPercept]) -> list[list[AmbiguousPercept]]:
    """The frame's ambiguous percepts in groups whose candidate sets overlap."""
    groups: list[tuple[set[str], list[AmbiguousPercept]]] = []
    for a in ambiguous:
        names = set(a.candidates) | {a.label}
        joined = [g for g in groups if g[0] & names]
        rest = [g for g in groups if not g[0] & names]
        members = [a]
        for g in joined:
            names |= g[0]
            members = g[1] + members
        groups = [*rest, (names, members)]
    return [members for _, members in groups]


def _answers(labels: list[str], perceived: set[str]) -> list[tuple[int, ...]]:
    """The permutations of ``labels`` (as index tuples) a group may answer: all of them up
    to :data:`MAX_ENUMERATED` labels; beyond, the identity and each transposition that moves
    a label perceived this frame."""
    k = len(labels)
    if k <= MAX_ENUMERATED:
        return list(itertools.permutations(range(k)))
    out = [tuple(range(k))]
    for i, label in enumerate(labels):
        if label not in perceived:
            continue
        for j in range(k):
            if j != i:
                sigma = list(range(k))
                sigma[i], sigma[j] = j, i
                if tuple(sigma) not in out:
                    out.append(tuple(sigma))
    return out


def _answer_mass(rows: np.ndarray, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The distinct rows of ``rows`` (N, k) and the weight of each."""
    unique, inverse = np.unique(rows, axis=0, return_inverse=True)
    return unique, np.bincount(inverse.reshape(-1), weights=weights, minlength=len(unique))
