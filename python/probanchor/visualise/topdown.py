"""A top-down plot of the anchors' beliefs over the table (matplotlib, Agg; no screen needed).

For a person who wants to see a multi-modal belief: each hidden anchor's particles as dots in
its colour (opacity by weight), each anchor's symbol at its point estimate, and, when given,
the ground truth (black ``+`` where an object is visible, ``x`` where it is hidden). Filled
circles are perceived anchors, hollow circles the point estimates of hidden ones.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from probanchor.visualise.overlay import AnchorView, particle_alpha


def _truth_items(truth: Mapping[str, Any] | None) -> list[tuple[str, np.ndarray, bool]]:
    items = []
    for oid, obj in (truth or {}).items():
        if hasattr(obj, "position"):
            visible = bool(getattr(obj, "visible", True))
            items.append((oid, np.asarray(obj.position, float), visible))
        elif isinstance(obj, Mapping):
            items.append((oid, np.asarray(obj["position"], float), bool(obj.get("visible", True))))
        else:
            items.append((oid, np.asarray(obj, float), True))
    return items


def render_topdown(
    anchors: Sequence[AnchorView],
    truth: Mapping[str, Any] | None = None,
    extent: tuple[float, float, float, float] | None = None,
    title: str | None = None,
    size: tuple[float, float] = (5.0, 4.0),
    dpi: int = 100,
) -> np.ndarray:
    """The plot as an RGB uint8 image. ``truth`` maps ids to positions, to objects with
    ``position``/``visible`` (``evaluation.TruthObject``) or to dicts of the simulator's truth
    format. ``extent`` is ``(x_min, x_max, y_min, y_max)`` in metres (default: fit the data)."""
    fig = Figure(figsize=size, dpi=dpi)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    xs: list[np.ndarray] = []
    for anchor in anchors:
        colour = np.asarray(anchor.rgb(), float) / 255.0
        if not anchor.perceived and anchor.particles is not None and len(anchor.particles):
            pts = np.asarray(anchor.particles, float).reshape(-1, 3)
            rgba = np.empty((len(pts), 4))
            rgba[:, :3] = colour
            rgba[:, 3] = particle_alpha(anchor.weights, len(pts))
            ax.scatter(pts[:, 0], pts[:, 1], s=4, c=rgba, linewidths=0)
            xs.append(pts[:, :2])
        if anchor.position is not None and np.all(np.isfinite(anchor.position)):
            p = np.asarray(anchor.position, float)
            face = colour if anchor.perceived else "none"
            ax.scatter([p[0]], [p[1]], s=40, facecolors=[face] if anchor.perceived else face,
                       edgecolors=[colour], linewidths=1.5, zorder=3)
            # Perceived anchors labelled above right, hidden ones below right (a hidden anchor
            # often sits where its occluder's anchor is).
            ax.annotate(anchor.symbol, (p[0], p[1]), xytext=(6, 6 if anchor.perceived else -14),
                        textcoords="offset points", color=colour, fontsize=8, weight="bold",
                        zorder=4)
            xs.append(p[None, :2])
    for oid, pos, visible in _truth_items(truth):
        ax.scatter([pos[0]], [pos[1]], marker="+" if visible else "x", s=50, c="black",
                   linewidths=1, zorder=5)
        ax.annotate(oid, (pos[0], pos[1]), xytext=(-6, 6 if visible else -14),
                    textcoords="offset points",
                    color="0.3", fontsize=7, ha="right", zorder=5)
        xs.append(pos[None, :2])
    if extent is not None:
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
    elif xs:
        allxy = np.concatenate(xs)
        lo, hi = allxy.min(axis=0), allxy.max(axis=0)
        pad = max(0.05, 0.1 * float(np.max(hi - lo)))
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title, fontsize=9)
    fig.tight_layout()
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())[:, :, :3].copy()


def plot_topdown(
    path: str | Path,
    anchors: Sequence[AnchorView],
    truth: Mapping[str, Any] | None = None,
    extent: tuple[float, float, float, float] | None = None,
    title: str | None = None,
) -> Path:
    """Save :func:`render_topdown` as a PNG; returns the path."""
    from probanchor.visualise.output import save_png

    return save_png(path, render_topdown(anchors, truth, extent, title))
