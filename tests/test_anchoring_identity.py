"""Identity hypotheses in the particles (anchoring.identity) on a small numpy world: two
look-alike mugs swapped unseen, each hiding a ball of its own colour; what one of them turns
out to hide decides which mug is which."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import pytest

from anchoring.identity import AmbiguousPercept, IdentityHypotheses, Revision, _answers

LEFT, RIGHT = np.array([-0.12, 0.12, 0.05]), np.array([0.12, 0.12, 0.05])


class World:
    """N particles, each a position per object; a hidden ball sits under the mug named by
    ``under`` in that particle. Observing an object weighs each particle by a Gaussian of
    its position there, then resamples (multinomial) with the particle data."""

    def __init__(self, n: int, seed: int = 0) -> None:
        self.n = n
        self.rng = np.random.default_rng(seed)
        self.pos: dict[str, np.ndarray] = {}
        self.under: dict[str, np.ndarray] = {}  # ball -> (N,) mug name per particle
        self.log_w = np.zeros(n)
        self.data: dict[str, np.ndarray] = {}

    @property
    def particles(self) -> int:
        return self.n

    def weights(self) -> np.ndarray:
        w = np.exp(self.log_w - self.log_w.max())
        return w / w.sum()

    def positions(self, symbol: str) -> np.ndarray:
        return self.pos[symbol].copy()

    def rename(self, mapping: Mapping[str, str], particles: np.ndarray | None) -> None:
        idx = np.arange(self.n) if particles is None else np.asarray(particles)
        old = {k: v[idx].copy() for k, v in self.pos.items()}
        for a, b in mapping.items():
            self.pos[b][idx] = old[a]
        old_under = {k: v[idx].copy() for k, v in self.under.items()}
        for ball in list(self.under):
            self.under[mapping.get(ball, ball)][idx] = old_under[ball]
        for ball, mugs in self.under.items():
            sel = mugs[idx]
            self.under[ball][idx] = np.array([mapping.get(m, m) for m in sel], dtype=object)

    def reweight(self, log_factors: np.ndarray) -> None:
        self.log_w = self.log_w + log_factors

    def particle_data(self) -> dict[str, np.ndarray]:
        return self.data

    # --- the "filter step" --------------------------------------------------------------
    def mugs_seen(self) -> None:
        """The step of the frame the mugs are seen again: each where anchoring put it; lost
        while the camera was covered, they could have been anywhere (no weight)."""
        self.see("mug-1", LEFT, 10.0)
        self.see("mug-2", RIGHT, 10.0)
        self.follow()

    def follow(self) -> None:
        for ball, mugs in self.under.items():
            for i in range(self.n):
                self.pos[ball][i] = self.pos[mugs[i]][i]

    def see(self, symbol: str, x: np.ndarray, sd: float) -> None:
        d2 = ((self.pos[symbol] - x) ** 2).sum(axis=1)
        self.log_w += -0.5 * d2 / sd ** 2
        self.pos[symbol][:] = x
        w = self.weights()
        idx = self.rng.choice(self.n, self.n, p=w)
        for k in self.pos:
            self.pos[k] = self.pos[k][idx]
        for k in self.under:
            self.under[k] = self.under[k][idx]
        for k in self.data:
            self.data[k] = self.data[k][idx]
        self.log_w = np.zeros(self.n)


def shell(n: int = 400, seed: int = 0) -> World:
    world = World(n, seed)
    world.pos = {"mug-1": np.tile(LEFT, (n, 1)), "mug-2": np.tile(RIGHT, (n, 1)),
                 "ball-1": np.tile(LEFT, (n, 1)), "ball-2": np.tile(RIGHT, (n, 1))}
    world.under = {"ball-1": np.array(["mug-1"] * n, dtype=object),
                   "ball-2": np.array(["mug-2"] * n, dtype=object)}
    return world


def mugs_seen_again(frame: int = 10) -> list[AmbiguousPercept]:
    """After the camera was covered, anchoring names the left mug mug-1 and the right one
    mug-2 (where they had been); either could be either."""
    both = ("mug-1", "mug-2")
    return [AmbiguousPercept(frame, 0, "mug-1", both, {"mug-1": 3.0, "mug-2": 3.0}, LEFT),
            AmbiguousPercept(frame, 1, "mug-2", both, {"mug-1": 3.0, "mug-2": 3.0}, RIGHT)]


def test_the_answers_stay_open_until_evidence_decides() -> None:
    world = shell()
    hyp = IdentityHypotheses(world, seed=1)
    hyp.associate(mugs_seen_again())
    # the observation of where the mugs are does not tell them apart (lost while blind)
    world.mugs_seen()
    p = hyp.probabilities("mug-1")
    tolerance = 4 * math.sqrt(0.25 / world.n)
    assert abs(p["mug-1"] - 0.5) < tolerance and abs(p["mug-2"] - 0.5) < tolerance
    assert hyp.revise(11) == []
    # each particle's ball follows the mug its own answer says: ball-1 is left or right
    left = np.isclose(world.pos["ball-1"][:, 0], LEFT[0])
    assert abs(float(world.weights() @ left) - 0.5) < tolerance


def test_what_a_mug_hides_revises_which_mug_it_is() -> None:
    world = shell()
    hyp = IdentityHypotheses(world, seed=2)
    hyp.associate(mugs_seen_again())
    world.mugs_seen()
    # the left mug is lifted: under it is ball-2, which had been put under mug-2
    world.see("ball-2", LEFT, 0.05)
    revisions = hyp.revise(30, evidence=["ball-2"])
    assert len(revisions) == 1
    rev = revisions[0]
    assert rev.mapping == {"mug-1": "mug-2", "mug-2": "mug-1"}
    assert rev.since == {"mug-1": 10, "mug-2": 10} and rev.evidence == ["ball-2"]
    assert rev.probability > 0.99 and rev.before < 0.01
    # the worlds were renamed: the left track is now mug-2 in every particle, with ball-2
    assert np.allclose(world.pos["mug-2"][:, 0], LEFT[0])
    assert set(world.under["ball-2"]) == {"mug-2"}
    assert hyp.probabilities("mug-2")["mug-2"] > 0.99
    # the ambiguous percepts are answered anew: the left one (index 0) was mug-2
    assert hyp.percept_probabilities(0)["mug-2"] > 0.99
    assert Revision.from_json(rev.to_json()) == rev
    assert not hyp.open  # decided: the group is closed


def test_evidence_for_the_answer_as_given_revises_nothing() -> None:
    world = shell()
    hyp = IdentityHypotheses(world, seed=3)
    hyp.associate(mugs_seen_again())
    world.mugs_seen()
    world.see("ball-1", LEFT, 0.05)
    assert hyp.revise(30) == []
    assert hyp.probabilities("mug-1")["mug-1"] > 0.99
    assert hyp.percept_probabilities(1)["mug-2"] > 0.99


def test_appearance_weighs_the_answers() -> None:
    """A percept that looks more like mug-2 (log A 2 nats more) makes the swap e^2 times as
    probable as the answer as given, before any other evidence."""
    world = shell(n=4000)
    hyp = IdentityHypotheses(world, seed=4)
    both = ("mug-1", "mug-2")
    hyp.associate([AmbiguousPercept(5, 0, "mug-1", both, {"mug-1": 1.0, "mug-2": 3.0}, LEFT)])
    p_swap = hyp.probabilities("mug-1")["mug-2"]
    expected = math.exp(2) / (1 + math.exp(2))
    assert abs(p_swap - expected) < 4 * math.sqrt(expected * (1 - expected) / 4000) + 0.02


def test_answers_of_large_groups_are_limited() -> None:
    assert len(_answers(list("abc"), {"a"})) == 6
    big = _answers(list("abcdefg"), {"a"})
    assert len(big) == 7 and big[0] == tuple(range(7))


@pytest.mark.parametrize("bad", [dict(kernel=0), dict(revise_probability=0),
                                 dict(revise_odds=0.5), dict(close_tolerance=1.0),
                                 dict(refuted=-1e-9), dict(keep_share=0.0),
                                 dict(keep_share=0.5), dict(max_kept=0),
                                 dict(max_kept=True)])
def test_bad_parameters_are_refused(bad: dict) -> None:
    with pytest.raises(ValueError):
        IdentityHypotheses(shell(10), **bad)


def test_a_cycle_of_three_is_revised_by_what_two_containers_hide() -> None:
    """Three look-alike cups in a row, each hiding its own ball, permuted unseen (a 3-cycle:
    the cup now on the left is cup-2's object, the middle one cup-3's, the right one cup-1's).
    Two lifts decide it: the answers are renamed accordingly, a 3-cycle and not a swap."""
    xs = {"cup-1": np.array([-0.25, 0.1, 0.05]), "cup-2": np.array([0.0, 0.1, 0.05]),
          "cup-3": np.array([0.25, 0.1, 0.05])}
    n = 3000
    world = World(n, seed=5)
    world.pos = {c: np.tile(x, (n, 1)) for c, x in xs.items()}
    world.pos.update({f"ball-{k}": np.tile(xs[f"cup-{k}"], (n, 1)) for k in (1, 2, 3)})
    world.under = {f"ball-{k}": np.array([f"cup-{k}"] * n, dtype=object) for k in (1, 2, 3)}
    hyp = IdentityHypotheses(world, seed=6)
    cups = ("cup-1", "cup-2", "cup-3")
    hyp.associate([AmbiguousPercept(20, k, c, cups, dict.fromkeys(cups, 3.0), xs[c])
                   for k, c in enumerate(cups)])
    for c, x in xs.items():
        world.see(c, x, 10.0)
    world.follow()
    world.see("ball-3", xs["cup-2"], 0.05)  # the middle cup hid ball-3
    world.see("ball-1", xs["cup-3"], 0.05)  # the right one ball-1
    revisions = hyp.revise(40)
    assert [r.mapping for r in revisions] == [{"cup-1": "cup-2", "cup-2": "cup-3",
                                               "cup-3": "cup-1"}]
    # the worlds follow: the cup named cup-3 now is on the middle, with ball-3 under it
    assert np.allclose(world.pos["cup-3"][:, 0], 0.0)
    assert set(world.under["ball-3"]) == {"cup-3"}
    for c in cups:
        assert hyp.probabilities(c)[c] > 0.99


def test_an_improbable_answer_stays_open_while_particles_hold_it() -> None:
    """The mugs are seen again each nearly where it had been: the swap keeps a few particles
    and less than a thousandth of the weight; what the left mug then hides (ball-2) makes it
    certain, and the symbols are revised. (Closing the question at a thousandth, the swap
    could no longer be revised.)"""
    world = shell(n=20000, seed=5)
    hyp = IdentityHypotheses(world, seed=5)
    hyp.associate(mugs_seen_again())
    world.see("mug-1", LEFT, 0.08)
    world.see("mug-2", RIGHT, 0.08)
    world.follow()
    p_swap = hyp.probabilities("mug-1").get("mug-2", 0.0)
    assert 0.0 < p_swap < 1e-3
    assert hyp.revise(11) == [] and hyp.open
    world.see("ball-2", LEFT, 0.05)
    (revision,) = hyp.revise(30, evidence=["ball-2"])
    assert revision.mapping == {"mug-1": "mug-2", "mug-2": "mug-1"}
    assert revision.probability > 0.9


def test_strata_keep_each_open_answer_apart_until_it_is_refuted() -> None:
    """While the mugs' question is open, the filter is told which answer each particle holds
    (the strata of its resampling): the swap, with a ten-thousandth of the weight, is a stratum
    of its own; once what a mug hides refutes it (below ``refuted``), it is resampled with the
    answer as given, and nothing is open any more."""
    world = shell(n=1000, seed=2)
    hyp = IdentityHypotheses(world, seed=2)
    assert hyp.strata() is None                      # nothing open
    hyp.associate(mugs_seen_again())
    log_w = world.log_w.copy()
    strata = hyp.strata()
    assert strata is not None and set(np.unique(strata)) == {0, 1}
    swapped = hyp._table()[:, hyp.columns.index("mug-1")] != hyp._index["mug-1"]
    assert np.array_equal(strata == 1, swapped) or np.array_equal(strata == 0, swapped)
    assert hyp.keep == 10
    # the swap made improbable (1e-4), but not refuted: still a stratum of its own, the
    # heaviest answer (as given) stratum 0
    world.log_w = log_w + np.where(swapped, math.log(1e-4), 0.0)
    strata = hyp.strata()
    assert strata is not None and np.array_equal(strata == 1, swapped)
    # refuted: one stratum, so no preserving resampling
    world.log_w = log_w + np.where(swapped, -30.0, 0.0)
    assert hyp.strata() is None
    assert IdentityHypotheses(world, keep_share=0.001).keep == 1
