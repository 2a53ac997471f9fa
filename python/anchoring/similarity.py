"""Attribute similarities in [0, 1], vectorised over anchors x percepts (and over particles).

Each function compares A anchors with P percepts and returns an (A, P) matrix; 1 means a perfect
correspondence. The five together, in the order of :data:`FEATURES` (the order of the original
ProbAnch matching SVM), are the input of the learned matching function.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

FEATURES: tuple[str, ...] = ("category", "colour", "position", "size", "time")
#: The kernel of a belief's mass near a percept (metres) where no theory says otherwise (a run
#: takes its theory's reappearance spread, sqrt(reappear_var): too.pl's is 5 cm).
BELIEF_RADIUS = 0.05


class _Workspace:
    """Grow-only scratch buffers reused across calls: on a busy machine, first-touching fresh
    multi-megabyte temporaries every frame costs more than the arithmetic itself."""

    def __init__(self) -> None:
        self._buffers: dict[str, np.ndarray] = {}

    def get(self, name: str, shape: tuple[int, int]) -> np.ndarray:
        size = shape[0] * shape[1]
        buf = self._buffers.get(name)
        if buf is None or buf.size < size:
            buf = np.empty(max(size, 1))
            self._buffers[name] = buf
        return buf[:size].reshape(shape)


_WORKSPACE = _Workspace()


def position_similarity(
    anchor_samples: Sequence[np.ndarray], percept_positions: np.ndarray
) -> np.ndarray:
    """``exp(-min_i ||s_i - x||)``: the maximum over each anchor's position samples (particles).

    ``anchor_samples[a]`` is (N_a, 3) (N_a = 1 for a deterministic position); the maximum of the
    similarity over the samples is the paper's point estimate at the modes (section 3.2).
    """
    return position_similarity_augmented([augment(s) for s in anchor_samples], percept_positions)


def augment(samples: np.ndarray) -> np.ndarray:
    """(4, N): the samples' coordinates and squared norms, for :func:`position_similarity_augmented`
    (cache it with the samples: ``Attribute.augmented_support``)."""
    s = np.asarray(samples, dtype=float).reshape(-1, 3)
    out = np.empty((4, s.shape[0]))
    out[:3] = s.T
    out[3] = (s * s).sum(axis=1)
    return out


def position_similarity_augmented(
    anchor_augmented: Sequence[np.ndarray], percept_positions: np.ndarray
) -> np.ndarray:
    """:func:`position_similarity` from :func:`augment`-ed samples.

    ``||x - s||^2 = ||x||^2 + (-2x, 1) . (s, ||s||^2)``: one matrix product over all samples of
    all anchors into a reused buffer, a segmented minimum along its rows, then ``||x||^2`` on
    the small result. No per-particle Python loop, two passes over the big matrix.
    """
    return position_evidence(anchor_augmented, None, percept_positions)[0]


def position_evidence(
    anchor_augmented: Sequence[np.ndarray], anchor_weights: Sequence[np.ndarray] | None,
    percept_positions: np.ndarray, radius: float = BELIEF_RADIUS,
) -> tuple[np.ndarray, np.ndarray | None]:
    """The best particle's similarity and the belief's mass near each percept, (A, P) each.

    Similarity (Algorithm 1 of the paper): ``exp(-min_i ||s_i - x||)``. Mass (with
    ``anchor_weights``, else None): ``sum_i w_i exp(-||s_i - x||^2 / (2 radius^2))``, the
    predictive density of a percept at x under the particles blurred by an isotropic Gaussian
    of standard deviation ``radius``, divided by that Gaussian's peak: 1 when the whole belief
    sits at x, the weight of a mode at x when the belief has several, about 0 where no particle
    is within a few ``radius``. A deterministic position (one sample) is a point belief.
    Both come from one matrix of squared distances (see :func:`position_similarity_augmented`).
    """
    x = np.asarray(percept_positions, dtype=float).reshape(-1, 3)
    if len(anchor_augmented) == 0 or x.shape[0] == 0:
        empty = np.zeros((len(anchor_augmented), x.shape[0]))
        return empty, (None if anchor_weights is None else empty.copy())
    counts = np.fromiter((s.shape[1] for s in anchor_augmented), dtype=np.intp)
    s_aug = np.concatenate(anchor_augmented, axis=1)  # (4, M)
    x_aug = np.empty((x.shape[0], 4))
    x_aug[:, :3] = -2.0 * x
    x_aug[:, 3] = 1.0
    d2 = _WORKSPACE.get("d2", (x.shape[0], s_aug.shape[1]))  # (P, M): reduce along rows
    np.matmul(x_aug, s_aug, out=d2)
    starts = np.concatenate(([0], np.cumsum(counts)[:-1]))
    xx = (x * x).sum(axis=1)
    nearest = np.minimum.reduceat(d2, starts, axis=1).T + xx
    similarity = np.exp(-np.sqrt(np.maximum(nearest, 0.0)))
    if anchor_weights is None:
        return similarity, None
    d2 += xx[:, None]
    np.maximum(d2, 0.0, out=d2)
    d2 *= -0.5 / (radius * radius)
    np.exp(d2, out=d2)
    d2 *= np.concatenate(anchor_weights)
    mass = np.add.reduceat(d2, starts, axis=1).T
    return similarity, np.minimum(mass, 1.0)


def colour_similarity(anchor_hists: np.ndarray, percept_hists: np.ndarray) -> np.ndarray:
    """``(1 + r) / 2`` with r the Pearson correlation of the histograms (cv2 ``HISTCMP_CORREL``).

    Unlike OpenCV (which returns r = 1 when either histogram is constant), a constant histogram
    correlates 1 with another constant one and 0 with anything else.
    """
    a = np.asarray(anchor_hists, dtype=float)
    p = np.asarray(percept_hists, dtype=float)
    a = a - a.mean(axis=1, keepdims=True)
    p = p - p.mean(axis=1, keepdims=True)
    na = np.sqrt((a * a).sum(1))
    np_ = np.sqrt((p * p).sum(1))
    denom = na[:, None] * np_[None, :]
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(denom > 1e-300, (a @ p.T) / denom, 0.0)
    both_flat = (na[:, None] <= 1e-300) & (np_[None, :] <= 1e-300)
    r = np.where(both_flat, 1.0, r)
    return np.clip((1.0 + r) / 2.0, 0.0, 1.0)


def size_similarity(anchor_sizes: np.ndarray, percept_sizes: np.ndarray) -> np.ndarray:
    """Generalised Jaccard ``sum_k min(a_k, q_k) / sum_k max(a_k, q_k)`` over the box extents."""
    a = np.asarray(anchor_sizes, dtype=float)[:, None, :]
    q = np.asarray(percept_sizes, dtype=float)[None, :, :]
    num = np.minimum(a, q).sum(-1)
    den = np.maximum(a, q).sum(-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(den > 0, num / den, 1.0)


def category_matrix(
    distributions: Sequence[Mapping[str, float]], vocabulary: Mapping[str, int]
) -> np.ndarray:
    """Rows of category probabilities over ``vocabulary``, each normalised to sum 1."""
    m = np.zeros((len(distributions), len(vocabulary)))
    for i, dist in enumerate(distributions):
        for name, p in dist.items():
            m[i, vocabulary[name]] = p
    total = m.sum(1, keepdims=True)
    return np.divide(m, total, out=np.zeros_like(m), where=total > 0)


def category_similarity(
    anchor_categories: Sequence[Mapping[str, float]],
    percept_categories: Sequence[Mapping[str, float]],
) -> np.ndarray:
    """Bhattacharyya coefficient ``sum_c sqrt(p_c q_c)`` over the union of category names.

    Each side is renormalised over the categories it lists (a percept carries only its top
    categories); a name missing on one side has probability 0 there. 1 for identical
    distributions, 0 for disjoint ones.
    """
    vocab: dict[str, int] = {}
    for dist in (*anchor_categories, *percept_categories):
        for name in dist:
            vocab.setdefault(name, len(vocab))
    a = np.sqrt(category_matrix(anchor_categories, vocab))
    p = np.sqrt(category_matrix(percept_categories, vocab))
    return np.clip(a @ p.T, 0.0, 1.0)


def time_similarity(anchor_times: np.ndarray, percept_times: np.ndarray) -> np.ndarray:
    """``2 / (1 + e^|dt|)`` with dt in seconds (as the original): 1 at dt = 0, ~0.54 at 1 s."""
    dt = np.abs(np.asarray(anchor_times, dtype=float)[:, None] - np.asarray(percept_times)[None, :])
    e = np.exp(-dt)  # the stable form of 2 / (1 + e^dt)
    return 2.0 * e / (1.0 + e)
