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
  and lies on the axis of another skin segment, within ``piece_gap`` of it, is joined to it
  (the hand beyond the object), so the hand is where its grip point is. Two arms that both
  enter the view are never joined.

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
    piece_gap: float = 0.12  # a piece that enters nowhere, this close to an arm on its axis


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
    """(low, high) of ``v`` leaving out the ``trim`` fraction at each end (a partition, not a
    sort: this runs on every skin segment of every frame)."""
    n = len(v)
    k = int(trim * n)
    if k == 0:
        return float(v.min()), float(v.max())
    part = np.partition(v, [k, n - 1 - k])
    return float(part[k]), float(part[n - 1 - k])


def _box_centre(points: np.ndarray, trim: float = 0.01) -> np.ndarray:
    """The centre of the points' 3-D box, the ``trim`` fraction left out at each end."""
    n = len(points)
    k = int(trim * n)
    if k == 0:
        return (points.min(axis=0) + points.max(axis=0)) / 2
    part = np.partition(points, [k, n - 1 - k], axis=0)
    return (part[k] + part[n - 1 - k]).astype(np.float64) / 2


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
    low_plus = _robust(segment.heights[proj >= hi - config.hand_length], 0.05)[0]
    low_minus = _robust(segment.heights[proj <= lo + config.hand_length], 0.05)[0]
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
    return _box_centre(points)


def _join(big: Segment, piece: Segment) -> None:
    big.rows = np.concatenate([big.rows, piece.rows])
    big.cols = np.concatenate([big.cols, piece.cols])
    big.points = np.concatenate([big.points, piece.points])
    big.heights = np.concatenate([big.heights, piece.heights])
    x0, y0, x1, y1 = big.bbox
    a0, b0, a1, b1 = piece.bbox
    big.bbox = (min(x0, a0), min(y0, b0), max(x1, a1), max(y1, b1))


def _aligned(a: Segment, b: Segment, gap: float) -> bool:
    """Whether b lies on a's axis (their centroids along it, within 25 degrees) with its
    nearest point within ``gap`` of a's in the table plane: two pieces of one arm."""
    centre, axis = _axis(a.points)
    offset = b.points[:, :2].mean(axis=0) - centre
    norm = float(np.linalg.norm(offset))
    if norm < 1e-6 or abs(float(offset @ axis)) < 0.9 * norm:
        return False
    pa, pb = a.points[::7, :2], b.points[::7, :2]
    nearest = np.sqrt(((pa[:, None, :] - pb[None, :, :]) ** 2).sum(axis=2)).min()
    return float(nearest) <= gap


def arms(skins: list[Segment], image_shape: tuple[int, int],
         workspace: tuple[float, float, float, float], max_height: float,
         config: GripConfig) -> list[tuple[Segment, np.ndarray]]:
    """The skin segments with pieces of one arm joined, each with its grip point.

    Two skin segments are pieces of one arm (an object in front of it hides a stretch) when
    at most one of them enters the view and one lies on the other's axis, within
    ``piece_gap``; two arms that both enter the view are never joined.

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
    joined: set[int] = set()
    changed = True
    while changed:
        changed = False
        for i in range(len(skins)):
            if i in joined or entries[i].any():
                continue
            # a piece that enters nowhere joins the arm it lies along (one that enters first)
            for k in sorted((k for k in range(len(skins)) if k != i and k not in joined),
                            key=lambda k: not entries[k].any()):
                if _aligned(skins[k], skins[i], config.piece_gap) or \
                        _aligned(skins[i], skins[k], config.piece_gap):
                    _join(skins[k], skins[i])
                    entries[k] = np.concatenate([entries[k], entries[i]])
                    joined.add(i)
                    changed = True
                    break
    return [(s, grip_point(s, e, config))
            for i, (s, e) in enumerate(zip(skins, entries, strict=True)) if i not in joined]


def join_across_arms(segments: list[Segment], skin: np.ndarray, hsv: np.ndarray,
                     min_skin: float = 0.6, margin: float = 0.01, min_hue: float = 0.5,
                     depth: float = 0.1) -> list[Segment]:
    """Join the pieces of an object that an arm in front of it cuts in two.

    A forearm reaching over a mug hides the mug's middle; its top is seen above the arm, its
    foot below, as two segments, each described as an object of its own (the top as a
    lifted something, the foot as a small ball). Two object segments are joined when they
    stand in one column of the table plane (:func:`_same_column`; pieces up to ``depth``
    apart: an object's near and far rims), the pixels on the image line
    between their centroids that belong to neither are mostly skin (``min_skin``), and their
    hues agree (the correlation of their hue histograms is at least ``min_hue``, or both are
    grey: the top of a container and its side are shaded differently, not coloured so).

    Parameters
    ----------
    segments:
        The frame's segments (object pieces are joined in place into the larger one).
    skin:
        The frame's skin mask (uint8, non-zero on skin).
    hsv:
        The frame in HSV (OpenCV ranges).

    Returns
    -------
    The segments without the pieces joined into others.
    """
    objects = [s for s in segments if s.kind == "object"]
    if len(objects) < 2 or not skin.any():
        return segments
    objects.sort(key=lambda s: -len(s.rows))
    owner = np.full(skin.shape, -1, np.int32)
    for k, s in enumerate(objects):
        owner[s.rows, s.cols] = k
    lo = [s.points.min(axis=0) for s in objects]
    hi = [s.points.max(axis=0) for s in objects]
    centre = [(float(s.rows.mean()), float(s.cols.mean())) for s in objects]
    hue: list[np.ndarray | None] = [None] * len(objects)
    joined: set[int] = set()
    for a in range(len(objects)):
        if a in joined:
            continue
        for b in range(a + 1, len(objects)):
            if b in joined or not _same_column(lo[a], hi[a], lo[b], hi[b], margin, depth):
                continue
            (r0, c0), (r1, c1) = centre[a], centre[b]
            n = int(max(abs(r1 - r0), abs(c1 - c0))) + 1
            rr = np.rint(np.linspace(r0, r1, n)).astype(int)
            cc = np.rint(np.linspace(c0, c1, n)).astype(int)
            between = (owner[rr, cc] != a) & (owner[rr, cc] != b)
            if between.sum() < 2 or float(np.mean(skin[rr, cc][between] > 0)) < min_skin:
                continue
            for k in (a, b):
                if hue[k] is None:
                    hue[k] = _hue_histogram(hsv, objects[k])
            if not _same_hue(hue[a], hue[b], min_hue):  # type: ignore[arg-type]
                continue
            _join(objects[a], objects[b])
            owner[objects[b].rows, objects[b].cols] = a
            lo[a], hi[a] = np.minimum(lo[a], lo[b]), np.maximum(hi[a], hi[b])
            hue[a] = None
            joined.add(b)
    gone = {id(objects[b]) for b in joined}
    return [s for s in segments if id(s) not in gone]


def _same_column(lo_a: np.ndarray, hi_a: np.ndarray, lo_b: np.ndarray, hi_b: np.ndarray,
                 margin: float, depth: float) -> bool:
    """Whether two 3-D boxes are parts of one object's column in the table plane: they overlap
    over at least half of the smaller extent along one horizontal axis, and along the other
    they overlap (within ``margin``) or are apart by less than ``depth`` or the larger one's
    extent along the first (an arm across a cup hides its middle; the near and far rims are
    as far apart as the cup is wide)."""
    overlap = np.minimum(hi_a[:2], hi_b[:2]) - np.maximum(lo_a[:2], lo_b[:2])
    extent = np.maximum(hi_a[:2] - lo_a[:2], hi_b[:2] - lo_b[:2])
    smaller = np.minimum(hi_a[:2] - lo_a[:2], hi_b[:2] - lo_b[:2])
    for along, other in ((0, 1), (1, 0)):
        if overlap[along] >= 0.5 * smaller[along] and \
                overlap[other] >= -max(margin, depth, extent[along]):
            return True
    return False


#: Below this mean saturation (OpenCV's 0-255) a segment is grey and its hue is noise.
GREY_SATURATION = 40


def _hue_histogram(hsv: np.ndarray, segment: Segment) -> np.ndarray:
    """The segment's normalised 18-bin hue histogram, and its mean saturation last."""
    pixels = hsv[segment.rows, segment.cols]
    hist = np.bincount(pixels[:, 0].astype(np.int64) * 18 // 180, minlength=18).astype(float)
    return np.append(hist / max(hist.sum(), 1.0), float(pixels[:, 1].mean()))


def _same_hue(a: np.ndarray, b: np.ndarray, min_hue: float) -> bool:
    grey_a, grey_b = a[-1] < GREY_SATURATION, b[-1] < GREY_SATURATION
    if grey_a or grey_b:
        return bool(grey_a and grey_b)
    ha, hb = a[:-1] - a[:-1].mean(), b[:-1] - b[:-1].mean()
    norm = float(np.sqrt((ha @ ha) * (hb @ hb)))
    return norm > 0 and float(ha @ hb) / norm >= min_hue
