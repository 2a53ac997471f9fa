"""Re-identification by appearance: what the matcher left unmatched, when it is unambiguous.

A percept that looks like exactly one of the anchors left over (category, colour and size
similarities of at least ``reid_similarity``, position not asked), an anchor not perceived for
``reid_seconds`` that looks like no other percept left over, re-acquires it (the manager
reports ``score`` 0). Why: the learned matcher refuses an object seen again 12 cm or more from
where it was believed (an identical-looking object elsewhere is another object); but when the
camera was covered while a container was carried over the ball, or a cup came out from behind
a passing container, the only black cup on the table is still the black cup. With two
look-alikes left over, nothing is decided by appearance.
"""

from __future__ import annotations

import numpy as np

from anchoring.anchor import Anchor


def looks_alike(features: np.ndarray, reid_similarity: tuple[float, ...]) -> np.ndarray:
    """(A, P): the anchor and the percept look alike (category, colour and size similarities
    of the frame's (A, P, 5) ``features`` at least ``reid_similarity``; position not asked)."""
    cat, col, size = (float(v) for v in reid_similarity)
    return (features[..., 0] >= cat) & (features[..., 1] >= col) & (features[..., 3] >= size)


def unique_lookalikes(anchors: list[Anchor], features: np.ndarray,
                      matched_anchor: dict[int, int], refuse: np.ndarray, time: float,
                      reid_seconds: float, reid_similarity: tuple[float, ...]
                      ) -> dict[int, int]:
    """Re-identification by appearance for what the matcher left unmatched: percept ->
    anchor (indices) where the percept looks like that anchor (category, colour and size
    similarities at least ``reid_similarity``), the anchor has not been perceived for
    ``reid_seconds`` or more, and neither has another such look-alike among the anchors
    and percepts left over. Position is not asked: after the camera was covered, or
    after a container was carried over something while unseen, an object may be anywhere
    on the table; but it is still the only black cup.

    ``features``: the frame's (A, P, 5) similarity vectors; ``matched_anchor``: percept ->
    anchor already matched; ``refuse``: (A, P) pairs refused as merged views. ``reid_seconds``
    <= 0 switches re-identification off."""
    if reid_seconds <= 0 or not anchors or features.shape[1] == 0:
        return {}
    taken = set(matched_anchor.values())
    free_a = np.array([k not in taken and anchors[k].confirmed
                       and time - anchors[k].last_seen >= reid_seconds
                       for k in range(len(anchors))])
    free_p = np.array([j not in matched_anchor for j in range(features.shape[1])])
    alike = looks_alike(features, reid_similarity) & ~refuse
    # uniqueness counts every anchor and percept left over, even one too recent to take
    left_a = np.array([k not in taken for k in range(len(anchors))])
    alike_left = alike & left_a[:, None] & free_p[None, :]
    return {j: k for j, k in one_to_one(alike_left).items() if free_a[k]}


def one_to_one(pairs: np.ndarray) -> dict[int, int]:
    """Percept -> anchor (indices) for each pair that is the only one of ``pairs`` (A, P) in
    both its column and its row: what a percept is when nothing else could be it, and it
    could be nothing else."""
    per_percept, per_anchor = pairs.sum(axis=0), pairs.sum(axis=1)
    return {int(j): int(k) for k, j in zip(*np.nonzero(pairs), strict=True)
            if per_percept[j] == 1 and per_anchor[k] == 1}
