"""Geometric attributes of a segment: position, size and shape features for the classifier.

Position is the centre of the segment's 3-D axis-aligned bounding box (robust: 1st to 99th
percentile of the points) and size its extents. A segment whose lowest points reach the table
(within ``rest_height``, or lower than 80 % of its own visible height: the lower part of a ball
is not seen from above) stands on it, so its box is extended down to the table plane: the
camera cannot see the bottom of an object, and the height cut above the table removes its
lowest centimetre. (The original system took the PCA mean of the visible points, which lies
on the visible surface, up to a radius away from the centre of a ball; the box centre is
within a few millimetres of the true centre for balls, boxes and cylinders.)
"""

from __future__ import annotations

import numpy as np

from probanchor.perception.plane import Plane

SHAPE_FEATURES = (
    "height",
    "major",
    "minor",
    "height_over_major",
    "minor_over_major",
    "top_fraction",
    "footprint_fill",
    "mean_height",
    "std_height",
    "asymmetry",
    "log_area",
    "top_spread",
)


def _robust_range(v: np.ndarray, trim: float = 0.005) -> tuple[float, float]:
    """(low, high) of ``v`` ignoring the ``trim`` fraction of values at each end."""
    n = len(v)
    k = int(trim * n)
    if k == 0:
        return float(v.min()), float(v.max())
    part = np.partition(v, [k, n - 1 - k])
    return float(part[k]), float(part[n - 1 - k])


def box_attributes(points: np.ndarray, heights: np.ndarray, plane: Plane,
                   rest_height: float = 0.02, pixel_size: float = 0.0,
                   camera_xy: tuple[float, float] | None = None,
                   rounded_top_fraction: float = 0.25) -> tuple[np.ndarray, np.ndarray]:
    """(position, size) in the world frame.

    ``pixel_size`` (metres per pixel at the segment's depth) is added to the horizontal
    extents: points are pixel centres, so the extreme ones lie half a pixel inside the
    silhouette on each side. When ``camera_xy`` is given and the segment's top is rounded
    (fewer than ``rounded_top_fraction`` of its points within 4 mm of its top, as on a ball),
    its footprint is taken as a disc whose diameter is its extent across the horizontal viewing
    direction and whose near edge is the nearest point seen: the far side of a ball is hidden
    from the camera.
    """
    x0, x1 = _robust_range(points[:, 0])
    y0, y1 = _robust_range(points[:, 1])
    z0, z1 = _robust_range(points[:, 2])
    x0, x1 = x0 - pixel_size / 2, x1 + pixel_size / 2
    y0, y1 = y0 - pixel_size / 2, y1 + pixel_size / 2
    lowest, top = _robust_range(heights)
    if camera_xy is not None and float(np.mean(heights > top - 0.004)) < rounded_top_fraction:
        view = np.array([(x0 + x1) / 2 - camera_xy[0], (y0 + y1) / 2 - camera_xy[1]])
        norm = float(np.linalg.norm(view))
        if norm > 1e-6:
            view /= norm
            across = np.array([-view[1], view[0]])
            xy = points[:, :2].astype(np.float64)
            a0, a1 = _robust_range(xy @ across)
            v0, v1 = _robust_range(xy @ view)
            a0, a1 = a0 - pixel_size / 2, a1 + pixel_size / 2
            v0 -= pixel_size / 2
            v1 += pixel_size / 2
            diameter = max(a1 - a0, v1 - v0)
            cx, cy = (a0 + a1) / 2 * across + (v0 + diameter / 2) * view
            x0, x1 = cx - diameter / 2, cx + diameter / 2
            y0, y1 = cy - diameter / 2, cy + diameter / 2
    if lowest < max(rest_height, 0.8 * (top - lowest)):
        z0 = min(z0, plane.z_at((x0 + x1) / 2, (y0 + y1) / 2))
    position = np.array([(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2])
    size = np.array([x1 - x0, y1 - y0, z1 - z0])
    return position, size


def shape_features(points: np.ndarray, heights: np.ndarray, pixel_area: float,
                   rest_height: float = 0.02, floor: float = 0.008) -> np.ndarray:
    """Yaw-invariant shape features (see SHAPE_FEATURES) of a segment's points.

    A segment that does not reach down to the table (by the rule of :func:`box_attributes`: a
    container lifted off what it covered, a mug held in the air) is described as if it stood
    on the table: its heights are taken from its own lowest point (plus ``floor``, the height
    of the lowest pixels kept on a standing object). A lifted mug is still a mug; measured
    from the table it looked like nothing the classifier was trained on (mugs in the air were
    taken for boxes in nearly every frame of the shipped scenarios' lifts).
    """
    h = heights.astype(np.float64)
    lowest, top = _robust_range(h)
    if lowest >= max(rest_height, 0.8 * (top - lowest)):
        h = h - lowest + floor
    top = max(_robust_range(h)[1], 1e-3)
    xy = points[:, :2].astype(np.float64)
    centre = xy.mean(axis=0)
    d = xy - centre
    cov = d.T @ d / max(len(d) - 1, 1)
    evals, evecs = np.linalg.eigh(cov)
    along = d @ evecs[:, 1]
    across = d @ evecs[:, 0]
    a0, a1 = _robust_range(along)
    c0, c1 = _robust_range(across)
    major, minor = max(a1 - a0, 1e-3), max(c1 - c0, 1e-3)
    # occupancy of an 8x8 grid over the footprint
    ia = np.clip(((along - a0) / major * 8).astype(int), 0, 7)
    ic = np.clip(((across - c0) / minor * 8).astype(int), 0, 7)
    fill = float(np.count_nonzero(np.bincount(ia * 8 + ic, minlength=64))) / 64.0
    high = h > top - 0.01
    top_fraction = float(high.mean())
    top_pts = xy[high]
    top_spread = 0.0
    if len(top_pts) > 3:
        tp = top_pts - top_pts.mean(axis=0)
        top_spread = float(np.sqrt(np.linalg.eigvalsh(tp.T @ tp / len(tp))[-1])) / major
    asym = abs((a0 + a1) / 2) / major
    return np.array([
        top,
        major,
        minor,
        top / major,
        minor / major,
        top_fraction,
        fill,
        float(h.mean()) / top,
        float(h.std()) / top,
        asym,
        float(np.log(max(pixel_area, 1e-6))),
        top_spread,
    ])
