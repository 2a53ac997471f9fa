"""The similarity vectors of every (anchor, percept) pair of a frame (Algorithm 1 of the paper)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from anchoring.anchor import Anchor
from anchoring.similarity import (
    BELIEF_RADIUS,
    FEATURES,
    category_similarity,
    colour_similarity,
    position_evidence,
    size_similarity,
    time_similarity,
)
from probanchor.percepts import Percept


def pair_features(anchors: Sequence[Anchor], percepts: Sequence[Percept]) -> np.ndarray:
    """(A, P, 5) similarities in the order of :data:`FEATURES`.

    A probabilistic position contributes the maximum similarity over its particles (those of
    positive weight); every other attribute is compared with its deterministic value.
    """
    return pair_evidence(anchors, percepts)[0]


def pair_evidence(anchors: Sequence[Anchor], percepts: Sequence[Percept],
                  mass_radius: float | None = None) -> tuple[np.ndarray, np.ndarray | None]:
    """:func:`pair_features` and, with ``mass_radius``, each anchor's position belief mass near
    each percept (A, P) (:func:`anchoring.similarity.position_evidence`), from one pass over
    the particles."""
    a, p = len(anchors), len(percepts)
    out = np.zeros((a, p, len(FEATURES)))
    if a == 0 or p == 0:
        return out, (None if mass_radius is None else np.zeros((a, p)))
    out[..., 0] = category_similarity(
        [an.category_average() for an in anchors], [pc.category for pc in percepts]
    )
    out[..., 1] = colour_similarity(
        np.array([an.colour.samples[0] for an in anchors]),
        np.array([_normalised(pc.colour_histogram) for pc in percepts]),
    )
    out[..., 2], mass = position_evidence(
        [an.position.augmented_support() for an in anchors],
        None if mass_radius is None else [an.position.support_weights() for an in anchors],
        np.array([pc.position for pc in percepts]),
        radius=BELIEF_RADIUS if mass_radius is None else mass_radius,
    )
    out[..., 3] = size_similarity(
        np.array([an.size.samples[0] for an in anchors]), np.array([pc.size for pc in percepts])
    )
    out[..., 4] = time_similarity(
        np.array([an.last_seen for an in anchors]), np.array([pc.time for pc in percepts])
    )
    return out, mass


def _normalised(hist: np.ndarray) -> np.ndarray:
    total = hist.sum()
    return hist / total if total > 0 else hist
