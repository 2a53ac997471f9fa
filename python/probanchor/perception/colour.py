"""Colour attribute: an HSV histogram of a segment's pixels and colour names from its peaks.

The histogram is OpenCV's ``calcHist`` over (H, S, V) with ``bins`` = (h, s, v) bins,
normalised to sum 1. Hue bins are centred on multiples of 180/h (OpenCV hue units), so pure
red, yellow, green, cyan, blue and magenta each fall in the middle of a bin rather than on a
bin edge: the hue is rotated by half a bin before binning.

Colour names are the predicate grounding of the paper's section 2.1: each bin is named from
its centre (``black`` when dark, ``white``/``gray`` when unsaturated, else by hue), the mass
of each name is summed, and the names whose mass is at least ``peak_ratio`` of the largest
(0.65, as in the original system) are returned, strongest first.
"""

from __future__ import annotations

import cv2
import numpy as np

DEFAULT_BINS = (18, 3, 4)

# hue (degrees, 0..360) upper bounds of each name, in order
_HUES = (
    (15.0, "red"),
    (45.0, "orange"),
    (70.0, "yellow"),
    (160.0, "green"),
    (200.0, "cyan"),
    (255.0, "blue"),
    (290.0, "purple"),
    (345.0, "pink"),
    (360.0, "red"),
)


def hue_shift(bins: tuple[int, int, int]) -> int:
    return int(round(180 / bins[0] / 2))


def hsv_image(rgb: np.ndarray, bins: tuple[int, int, int] = DEFAULT_BINS) -> np.ndarray:
    """HSV (OpenCV ranges) with the hue rotated by half a bin, ready for :func:`histogram`."""
    hsv = cv2.cvtColor(rgb, cv2.COLOR_RGB2HSV)
    shift = hue_shift(bins)
    h = hsv[:, :, 0]
    h += np.uint8(shift)
    h[h >= 180] -= 180
    return hsv


def histogram(hsv: np.ndarray, mask: np.ndarray, bins: tuple[int, int, int] = DEFAULT_BINS
              ) -> np.ndarray:
    """Normalised, flattened HSV histogram of the pixels where ``mask`` is non-zero."""
    hist = cv2.calcHist([hsv], [0, 1, 2], mask, list(bins), [0, 180, 0, 256, 0, 256])
    hist = hist.reshape(-1).astype(np.float64)
    total = hist.sum()
    return hist / total if total > 0 else hist


def _name(h_deg: float, s: float, v: float) -> str:
    if v < 0.22:
        return "black"
    if s < 0.3:
        return "white" if v > 0.6 else "gray"
    if 15.0 <= h_deg < 45.0 and v < 0.55:
        return "brown"
    for upper, name in _HUES:
        if h_deg < upper:
            return name
    return "red"


_NAME_CACHE: dict[tuple[int, int, int], tuple[list[str], np.ndarray]] = {}


def bin_names(bins: tuple[int, int, int] = DEFAULT_BINS) -> tuple[list[str], np.ndarray]:
    """(names, index) where ``index[i]`` is the name of flattened bin i."""
    if bins in _NAME_CACHE:
        return _NAME_CACHE[bins]
    hb, sb, vb = bins
    names: list[str] = []
    index = np.empty(hb * sb * vb, dtype=np.int64)
    k = 0
    for i in range(hb):
        h_deg = (i * 180.0 / hb) * 2.0  # bin centre after the half-bin rotation
        for j in range(sb):
            s = (j + 0.5) / sb
            for m in range(vb):
                v = (m + 0.5) / vb
                name = _name(h_deg % 360.0, s, v)
                if name not in names:
                    names.append(name)
                index[k] = names.index(name)
                k += 1
    _NAME_CACHE[bins] = (names, index)
    return names, index


def colour_names(hist: np.ndarray, bins: tuple[int, int, int] = DEFAULT_BINS,
                 peak_ratio: float = 0.65) -> list[str]:
    """Colour names grounded from a histogram, strongest first."""
    names, index = bin_names(bins)
    mass = np.bincount(index, weights=hist, minlength=len(names))
    if mass.max() <= 0:
        return []
    order = np.argsort(-mass)
    return [names[i] for i in order if mass[i] >= peak_ratio * mass.max() and mass[i] > 0]
