"""Arms: the skin segments of one arm joined, and the point where its hand closes.

A hand reaching into the view is seen as one skin segment from the image's border (where the
arm enters) to the hand at its free end; the segment's centre (its ``position``) lies between
hand and forearm, 20 cm or more from where the hand closes over what it picks up. So each skin
segment also gets a *grip point* (``Percept.grip``): the centre of the 3-D box of its points
within ``hand_length`` of its free end along the arm's horizontal axis.

- The arm *enters* where its segment touches the image's border (``edge_pixels``) or the
  boundary of the perceived space (the workspace's sides, ``edge_margin``; the top of the
  height band); the free end is the far end of the axis from the entry. A segment that enters
  nowhere (a hand whose arm is hidden) has its box centre as grip point.
- An object standing in front of the arm cuts its segment in two: a piece that enters nowhere
  and whose points come within ``piece_gap`` of an arm's free end is joined to that arm (the
  hand beyond the object), so the hand is where its grip point is. Two arms that both enter
  the view are never joined.

Nothing here knows of anchors or of the simulator.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from probanchor.perception.segments import Segment


@dataclass
class GripConfig:
    """Lengths in metres."""

    hand_length: float = 0.10  # the hand: the segment's last part along the arm's axis
    edge_pixels: int = 2  # pixels this close to the image's border: the arm enters there
    edge_margin: float = 0.01  # points this close to the workspace's sides or top: likewise
    piece_gap: float = 0.12  # a piece that enters nowhere, this close to an arm's free end


def _axis(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(centre, unit axis) of the points' horizontal principal direction."""
    xy = points[:, :2].astype(np.float64)
    centre = xy.mean(axis=0)
    d = xy - centre
    if len(d) < 2:
        return centre, np.array([1.0, 0.0])
    _, evecs = np.linalg.eigh(d.T @ d)
    return centre, evecs[:, -1]


def _robust(v: np.ndarray, trim: float = 0.01) -> tuple[float, float]:
    lo, hi = np.quantile(v, [trim, 1.0 - trim]) if len(v) > 20 else (v.min(), v.max())
    return float(lo), float(hi)


def entering(segment: Segment, image_shape: tuple[int, int],
             workspace: tuple[float, float, float, float], max_height: float,
             config: GripConfig) -> np.ndarray:
    """Which of the segment's points lie where an arm enters the perceived space: at the
    image's border, at the workspace's sides or at the top of the height band."""
    h, w = image_shape
    e = config.edge_pixels
    at = ((segment.rows < e) | (segment.rows >= h - e) | (segment.cols < e)
          | (segment.cols >= w - e))
    x0, x1, y0, y1 = workspace
    m = config.edge_margin
    p = segment.points
    at |= (p[:, 0] < x0 + m) | (p[:, 0] > x1 - m) | (p[:, 1] < y0 + m) | (p[:, 1] > y1 - m)
    at |= segment.heights > max_height - m
    return np.asarray(at, bool)


def _projections(segment: Segment) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(centre, unit axis, projections of the points on it) in the table plane."""
    centre, axis = _axis(segment.points)
    return centre, axis, (segment.points[:, :2] - centre) @ axis


def free_end(segment: Segment, entry: np.ndarray, config: GripConfig
             ) -> np.ndarray | None:
    """The projections of the segment's points on the arm's horizontal axis, signed so that
    the free end (the hand) is at the largest; None when no end can be told.

    The arm enters at ``entry``; a segment that enters nowhere (the whole arm in view) has its
    hand at the end that reaches lower, by more than 1 cm (fingers reach down to what they
    hold; the forearm rises towards the elbow). A segment shorter than 1.5 hand lengths is
    a hand alone."""
    _, _, proj = _projections(segment)
    if entry.any():
        return -proj if proj[entry].mean() > 0 else proj
    lo, hi = _robust(proj)
    if hi - lo < 1.5 * config.hand_length:
        return None
    low_plus = float(np.quantile(segment.heights[proj >= hi - config.hand_length], 0.05))
    low_minus = float(np.quantile(segment.heights[proj <= lo + config.hand_length], 0.05))
    if low_plus < low_minus - 0.01:
        return proj
    if low_minus < low_plus - 0.01:
        return -proj
    return None


def grip_point(segment: Segment, entry: np.ndarray, config: GripConfig) -> np.ndarray:
    """Where the hand of an arm's segment closes (see the module docstring)."""
    proj = free_end(segment, entry, config)
    points = segment.points
    if proj is not None:
        hand = proj >= _robust(proj)[1] - config.hand_length
        if hand.sum() >= 3:
            points = points[hand]
    lo = np.array([_robust(points[:, k])[0] for k in range(3)])
    hi = np.array([_robust(points[:, k])[1] for k in range(3)])
    return (lo + hi) / 2


def _end_point(segment: Segment, entry: np.ndarray) -> np.ndarray | None:
    """The free end, in the table plane, of a segment that enters the view (else None)."""
    if not entry.any():
        return None
    centre, axis, proj = _projections(segment)
    if proj[entry].mean() > 0:
        proj, axis = -proj, -axis
    return centre + _robust(proj)[1] * axis


def _join(big: Segment, piece: Segment) -> None:
    big.rows = np.concatenate([big.rows, piece.rows])
    big.cols = np.concatenate([big.cols, piece.cols])
    big.points = np.concatenate([big.points, piece.points])
    big.heights = np.concatenate([big.heights, piece.heights])
    x0, y0, x1, y1 = big.bbox
    a0, b0, a1, b1 = piece.bbox
    big.bbox = (min(x0, a0), min(y0, b0), max(x1, a1), max(y1, b1))


def arms(skins: list[Segment], image_shape: tuple[int, int],
         workspace: tuple[float, float, float, float], max_height: float,
         config: GripConfig) -> list[tuple[Segment, np.ndarray]]:
    """The skin segments with pieces of one arm joined, each with its grip point.

    Parameters
    ----------
    skins:
        The frame's skin segments (changed in place when a piece is joined to one).
    image_shape:
        (height, width) of the image.
    workspace, max_height:
        The perceived space (x0, x1, y0, y1) and the top of its height band (metres).
    config:
        The lengths of :class:`GripConfig`.

    Returns
    -------
    ``[(segment, grip), ...]``, in the order of ``skins`` (joined pieces left out).
    """
    entries = [entering(s, image_shape, workspace, max_height, config) for s in skins]
    ends = [_end_point(s, e) for s, e in zip(skins, entries, strict=True)]
    joined: set[int] = set()
    for i, piece in enumerate(skins):
        if ends[i] is not None:
            continue
        best, best_d = None, config.piece_gap
        for k, end in enumerate(ends):
            if end is None:
                continue
            d = float(np.min(np.linalg.norm(piece.points[:, :2] - end, axis=1)))
            if d < best_d:
                best, best_d = k, d
        if best is not None:
            _join(skins[best], piece)
            entries[best] = np.concatenate([entries[best], np.zeros(len(piece.rows), bool)])
            joined.add(i)
    return [(s, grip_point(s, e, config))
            for i, (s, e) in enumerate(zip(skins, entries, strict=True)) if i not in joined]
