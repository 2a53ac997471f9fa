"""Which percepts of a frame the anchor manager refuses to look at, and why.

A percept is rejected (with a reason, logged by the manager, never raised) when it is not a
:class:`~percepts.Percept`, when ``Percept.validate`` refuses it, or when its colour histogram
has a different number of bins than the anchors': such a percept cannot be compared with any
anchor, and one bad percept must not stop the frame.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from anchoring.anchor import Anchor
from probanchor.percepts import Percept, PerceptError


def histogram_bins(anchors: Iterable[Anchor], percepts: Sequence[Percept]) -> int | None:
    """The colour histogram size every percept must have: the anchors' (the first anchor's),
    else the first valid percept's, else ``None`` (anything goes)."""
    for anchor in anchors:
        return anchor.colour.dim
    for percept in percepts:
        if invalid_reason(percept, None) is None:
            return int(percept.colour_histogram.size)
    return None


def invalid_reason(percept: Percept, bins: int | None) -> str | None:
    """Why ``percept`` is rejected, or ``None`` if it is valid (``bins``: the histogram size
    required, see :func:`histogram_bins`)."""
    if not isinstance(percept, Percept):
        return f"not a Percept: {type(percept).__name__}"
    try:
        percept.validate()
    except PerceptError as exc:
        return str(exc)
    if bins is not None and percept.colour_histogram.size != bins:
        return f"colour histogram has {percept.colour_histogram.size} bins, anchors have {bins}"
    return None
