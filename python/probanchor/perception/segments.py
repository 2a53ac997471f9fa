"""Segments of a frame: table removal, skin detection and connected components.

Works on the depth image: every pixel with depth gets its height above the table plane; the
pixels between ``min_height`` and ``max_height`` inside the workspace are "above the table".
Skin pixels (an HSV window, as the original's hand tracker) are split off as their own
segments. The rest is cut at depth jumps (a pixel farther than a neighbour by more than
``depth_jump`` belongs to the occluded side and is left out) and split into 8-connected
components with OpenCV; components smaller than ``min_pixels`` are dropped.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np


@dataclass
class Segment:
    kind: str  # "object" or "skin"
    rows: np.ndarray
    cols: np.ndarray
    points: np.ndarray  # (N, 3) world frame
    heights: np.ndarray  # (N,) above the table plane
    bbox: tuple[int, int, int, int]  # x0, y0, x1, y1 (inclusive-exclusive)
    label: int = 0
    grip: np.ndarray | None = None  # skin: where the hand closes (perception.grip)


@dataclass
class SkinWindow:
    """HSV window (OpenCV ranges) of skin."""

    h: tuple[int, int] = (4, 20)
    s: tuple[int, int] = (50, 160)
    v: tuple[int, int] = (60, 255)

    def mask(self, hsv_plain: np.ndarray) -> np.ndarray:
        lo = np.array([self.h[0], self.s[0], self.v[0]], np.uint8)
        hi = np.array([self.h[1], self.s[1], self.v[1]], np.uint8)
        return cv2.inRange(hsv_plain, lo, hi)


def components(mask: np.ndarray, min_pixels: int) -> list[tuple[np.ndarray, np.ndarray, int,
                                                                 tuple[int, int, int, int]]]:
    """(rows, cols, label, bbox) of each 8-connected component of ``mask`` (uint8)."""
    n, labels, stats, _ = cv2.connectedComponentsWithStats(mask, connectivity=8)
    keep = [k for k in range(1, n) if stats[k, cv2.CC_STAT_AREA] >= min_pixels]
    if not keep:
        return []
    rows, cols = np.nonzero(labels)
    lab = labels[rows, cols]
    order = np.argsort(lab, kind="stable")
    rows, cols, lab = rows[order], cols[order], lab[order]
    starts = np.searchsorted(lab, np.arange(n + 1))
    out = []
    for k in keep:
        a, b = starts[k], starts[k + 1]
        x, y = stats[k, cv2.CC_STAT_LEFT], stats[k, cv2.CC_STAT_TOP]
        w, h = stats[k, cv2.CC_STAT_WIDTH], stats[k, cv2.CC_STAT_HEIGHT]
        out.append((rows[a:b], cols[a:b], k, (int(x), int(y), int(x + w), int(y + h))))
    return out


def occluded_side(depth: np.ndarray, valid: np.ndarray, jump: float) -> np.ndarray:
    """Pixels farther than one of their 8 neighbours by more than ``jump`` (relative to z).

    Only neighbours in ``valid`` count: pass the above-table mask, so that the table in front
    of an object does not cut off the object's lower rim."""
    far = np.where(valid, depth, np.float32(100.0)).astype(np.float32)
    nearest = cv2.erode(far, np.ones((3, 3), np.uint8))
    return valid & (depth - nearest > jump * np.maximum(depth, 0.5))


def _same_body(a: tuple[np.ndarray, np.ndarray], b: tuple[np.ndarray, np.ndarray],
               touch: float) -> bool:
    """Whether two 3-D boxes touch (within ``touch`` along every axis), overlap over at least
    half of the smaller extent along two axes and have their tops at the same height (within
    1 cm): the near wall and the far inner wall of an upright cup, both ending at its rim.
    An object standing just behind another of another height does not qualify."""
    overlap = np.minimum(a[1], b[1]) - np.maximum(a[0], b[0])
    smaller = np.minimum(a[1] - a[0], b[1] - b[0])
    return bool(np.all(overlap >= -touch) and np.sum(overlap >= 0.5 * smaller) >= 2
                and abs(float(a[1][2] - b[1][2])) <= 0.01)


def merge_fragments(segments: list[Segment], max_pixels: float, gap: float,
                    touch: float = 0.01) -> list[Segment]:
    """Merge the pieces of one object that depth jumps cut apart: a small segment (a mug's
    handle) into the nearest larger one whose 3-D box is within ``gap``, and any segment whose
    3-D box touches a larger one's and overlaps it along two axes (the far inner wall of an
    upright cup, seen over its near rim)."""
    objects = [s for s in segments if s.kind == "object"]
    if len(objects) < 2:
        return segments
    boxes = {id(s): (s.points.min(axis=0), s.points.max(axis=0)) for s in objects}
    order = sorted(objects, key=lambda s: len(s.rows))
    merged: set[int] = set()
    for small in order:
        lo, hi = boxes[id(small)]
        best, best_d = None, gap
        for big in objects:
            if big is small or id(big) in merged or len(big.rows) <= len(small.rows):
                continue
            blo, bhi = boxes[id(big)]
            if _same_body(boxes[id(small)], boxes[id(big)], touch):
                best, best_d = big, -1.0
                break
            if len(small.rows) >= max_pixels:
                continue
            d = float(np.linalg.norm(np.maximum(0.0, np.maximum(blo - hi, lo - bhi))))
            if d <= best_d:
                best, best_d = big, d
        if best is None:
            continue
        best.rows = np.concatenate([best.rows, small.rows])
        best.cols = np.concatenate([best.cols, small.cols])
        best.points = np.concatenate([best.points, small.points])
        best.heights = np.concatenate([best.heights, small.heights])
        x0, y0, x1, y1 = best.bbox
        a0, b0, a1, b1 = small.bbox
        best.bbox = (min(x0, a0), min(y0, b0), max(x1, a1), max(y1, b1))
        boxes[id(best)] = (np.minimum(boxes[id(best)][0], lo), np.maximum(boxes[id(best)][1], hi))
        merged.add(id(small))
    return [s for s in segments if id(s) not in merged]
