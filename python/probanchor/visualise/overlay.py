"""Anchors drawn over the camera image, as in the paper's figures.

Each anchor gets a colour of its own (fixed by its symbol). A perceived anchor is drawn as its
percept's 2-D box (when given) and its symbol; a hidden anchor as its particles, small dots in
its colour whose opacity grows with the particle's weight, and its symbol at its point
estimate. Drawing is vectorised over particles (one scatter of all dots per anchor).
"""

from __future__ import annotations

import zlib
from collections.abc import Sequence
from dataclasses import dataclass

import cv2
import numpy as np

from probanchor.visualise.camera import CameraView

# Distinct, saturated colours (RGB) that read on a grey table and on skin.
PALETTE: tuple[tuple[int, int, int], ...] = (
    (230, 25, 75), (60, 180, 75), (0, 130, 200), (245, 130, 48), (145, 30, 180),
    (70, 240, 240), (240, 50, 230), (210, 245, 60), (0, 128, 128), (255, 225, 25),
    (170, 110, 40), (128, 0, 0), (0, 0, 128), (128, 128, 0),
)


def anchor_colour(symbol: str) -> tuple[int, int, int]:
    """The colour (RGB, 0-255) of an anchor: the same symbol always gets the same colour."""
    return PALETTE[zlib.crc32(symbol.encode("utf-8")) % len(PALETTE)]


@dataclass
class AnchorView:
    """What to draw of one anchor in one frame.

    ``position``: point estimate (3,) in world metres (the perceived position, or e.g.
    ``probanchor.evaluation.point_estimate`` of the particles), or ``None``. ``particles`` (N, 3)
    and ``weights`` (N,) are drawn for anchors that are not ``perceived``. ``bbox`` is the 2-D box
    ``(x0, y0, x1, y1)`` of the anchor's percept in this frame, if any.
    """

    symbol: str
    position: np.ndarray | None = None
    perceived: bool = True
    particles: np.ndarray | None = None
    weights: np.ndarray | None = None
    bbox: tuple[int, int, int, int] | None = None
    colour: tuple[int, int, int] | None = None

    def rgb(self) -> tuple[int, int, int]:
        return self.colour if self.colour is not None else anchor_colour(self.symbol)


def _disk(radius: int) -> tuple[np.ndarray, np.ndarray]:
    r = max(0, int(radius))
    dy, dx = np.mgrid[-r : r + 1, -r : r + 1]
    inside = dx * dx + dy * dy <= r * r + r  # a round-ish dot, 1 px for radius 0
    return dx[inside], dy[inside]


def particle_alpha(weights: np.ndarray | None, n: int, max_alpha: float = 0.9,
                   min_alpha: float = 0.15) -> np.ndarray:
    """Opacity per particle: ``max_alpha`` for the heaviest, proportionally less for lighter
    ones, never below ``min_alpha`` (so that every particle stays visible)."""
    if weights is None:
        return np.full(n, max_alpha)
    w = np.asarray(weights, dtype=float).reshape(-1)
    if w.shape != (n,):
        raise ValueError(f"{w.size} weights for {n} particles")
    top = w.max() if n and np.isfinite(w).all() and w.max() > 0 else 1.0
    return np.clip(max_alpha * w / top, min_alpha, max_alpha)


def draw_particles(
    image: np.ndarray,
    camera: CameraView,
    particles: np.ndarray,
    colour: tuple[int, int, int],
    weights: np.ndarray | None = None,
    radius: int = 1,
    max_alpha: float = 0.9,
) -> np.ndarray:
    """A copy of ``image`` (uint8 HxWx3) with the particles as dots of ``colour``."""
    out = image.copy()
    pts = np.asarray(particles, dtype=float).reshape(-1, 3)
    if len(pts) == 0:
        return out
    h, w = image.shape[:2]
    uv, _ = camera.project(pts)
    alpha = particle_alpha(weights, len(pts), max_alpha)
    ok = np.all(np.isfinite(uv), axis=1)
    pix = np.rint(uv[ok]).astype(np.int64)
    ui, vi, alpha = pix[:, 0], pix[:, 1], alpha[ok]
    dx, dy = _disk(radius)
    px = (ui[:, None] + dx[None, :]).reshape(-1)
    py = (vi[:, None] + dy[None, :]).reshape(-1)
    pa = np.repeat(alpha, len(dx))
    inside = (px >= 0) & (px < w) & (py >= 0) & (py < h)
    px, py, pa = px[inside], py[inside], pa[inside]
    if len(px) == 0:
        return out
    # Blend only the rectangle the dots cover; where dots overlap the most opaque one wins.
    x0, x1, y0, y1 = px.min(), px.max() + 1, py.min(), py.max() + 1
    layer = np.zeros((y1 - y0, x1 - x0), dtype=np.float32)
    np.maximum.at(layer, (py - y0, px - x0), pa.astype(np.float32))
    a = layer[:, :, None]
    region = out[y0:y1, x0:x1].astype(np.float32)
    blended = region * (1.0 - a) + np.asarray(colour, dtype=np.float32) * a
    out[y0:y1, x0:x1] = np.clip(np.rint(blended), 0, 255).astype(np.uint8)
    return out


def _label(image: np.ndarray, text: str, at: tuple[int, int], colour: tuple[int, int, int],
           scale: float) -> None:
    x, y = at
    (tw, th), base = cv2.getTextSize(text, cv2.FONT_HERSHEY_SIMPLEX, scale, 1)
    h, w = image.shape[:2]
    x = int(np.clip(x, 0, max(0, w - tw)))
    y = int(np.clip(y, th, max(th, h - base)))
    cv2.putText(image, text, (x, y), cv2.FONT_HERSHEY_SIMPLEX, scale, (0, 0, 0), 3, cv2.LINE_AA)
    cv2.putText(image, text, (x, y), cv2.FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv2.LINE_AA)


def draw_anchors(
    rgb: np.ndarray,
    camera: CameraView,
    anchors: Sequence[AnchorView],
    *,
    dot_radius: int = 1,
    max_alpha: float = 0.9,
    font_scale: float | None = None,
) -> np.ndarray:
    """The camera image with every anchor drawn on it (see the module doc). Returns a new
    uint8 HxWx3 image; ``rgb`` is left untouched."""
    image = np.asarray(rgb)
    if image.ndim != 3 or image.shape[2] != 3 or image.dtype != np.uint8:
        raise ValueError(f"expected an RGB uint8 HxWx3 image, got {image.dtype} {image.shape}")
    out = np.ascontiguousarray(image.copy())
    scale = font_scale if font_scale is not None else max(0.3, out.shape[0] / 600.0)
    # Particles first, so that every label stays on top.
    for anchor in anchors:
        if not anchor.perceived and anchor.particles is not None:
            out = draw_particles(out, camera, anchor.particles, anchor.rgb(), anchor.weights,
                                 dot_radius, max_alpha)
    for anchor in anchors:
        colour = anchor.rgb()
        anchor_at: tuple[int, int] | None = None
        if anchor.bbox is not None and anchor.perceived:
            x0, y0, x1, y1 = (int(v) for v in anchor.bbox)
            cv2.rectangle(out, (x0, y0), (x1, y1), colour, 1)
            anchor_at = (x0, y0 - 3)
        if anchor.position is not None and np.all(np.isfinite(anchor.position)):
            uv, _ = camera.project(np.asarray(anchor.position, dtype=float))
            if np.all(np.isfinite(uv[0])):
                u, v = (int(round(c)) for c in uv[0])
                if anchor.perceived:
                    cv2.drawMarker(out, (u, v), colour, cv2.MARKER_CROSS, 6, 1)
                else:
                    cv2.circle(out, (u, v), 4, colour, 1, cv2.LINE_AA)
                if anchor_at is None:  # hidden anchors labelled below: their occluder is above
                    anchor_at = (u + 5, v - 5) if anchor.perceived else (u + 6, v + int(30 * scale))
        if anchor_at is not None:
            _label(out, anchor.symbol, anchor_at, colour, scale)
    return out
