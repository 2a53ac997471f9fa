"""Drawing learned distributional logic trees (paper, Figure 5) with matplotlib (Agg; no screen).

One panel per tree, titled with the target. The layout is top-down: the leaves are evenly spaced
left to right in clause order and every internal node is centred over its children. Internal
nodes are rounded blue boxes holding the tested body literal; leaves are orange boxes holding
the head's distribution, the model that gives its parameters (if any) and ``n = rows`` (with
``w = weight`` when the two differ); a leaf that inherited its parent's model (too few
groundings) is drawn dashed. Each edge carries its branch's literal, the "undefined / does not
hold" branch (``\\+ ...``) in grey. Literals are set in a monospace font.

The geometry is computed in inches from the lengths of the (wrapped) texts, so boxes and labels
do not overlap however many leaves the tree has; :func:`plot_trees` sizes the figure to fit.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

import matplotlib
import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure

from probanchor.ddclearn.tree import Branch, Tree, TreeNode

__all__ = ["layout", "plot_tree", "plot_trees", "pruned", "tree_size", "wrap_text"]

#: Node path: the indices of the branches taken from the root (the root is ``()``).
NodePath = tuple[int, ...]

_FAMILY = "monospace"
_NODE_PT = 8.0  # font size of node texts
_LABEL_PT = 7.0  # font size of edge labels
_TITLE_PT = 10.0
# DejaVu Sans Mono: advance 0.602 em (rendered ~0.58 at 100 dpi); line pitch 1.2 em.
_CHAR_EM = 0.62
_LINE_EM = 1.2
_NODE_PAD_EM = 0.4  # box pad around the text, in units of the font size (each side)
_LABEL_PAD_EM = 0.2
_NODE_WRAP = 32  # characters per line in node boxes
_LABEL_WRAP = 26
_TITLE_WRAP = 90
_H_GAP = 0.22  # inches between neighbouring boxes / labels
_V_GAP = 0.08  # inches between a label and the boxes above and below it
_LABEL_FRAC = 0.3  # how far up its edge (from the child) a label may sit
_MIN_STEP = 0.8  # inches between the centres of two levels, at least
_MARGIN = 0.15  # inches around a panel
_TITLE_H = 0.40  # inches above a panel for its title
_DPI = 100

_INTERNAL_STYLE = {"facecolor": "#dbe9f6", "edgecolor": "#2b5d8a"}
_LEAF_STYLE = {"facecolor": "#fde9cf", "edgecolor": "#b5651d"}
_EDGE_COLOUR = "#555555"
_YES_COLOUR = "#1f3b57"
_NO_COLOUR = "#7a7a7a"

# Break opportunities: after a comma or an opening parenthesis or bracket, and at a space
# (but not the one after a negation ``\+``, which stays with its literal).
_BREAK = re.compile(r"(?<=[,(\[])|(?<= )(?<!\\\+ )")
_SPACE = re.compile(r"(?<= )")


def wrap_text(text: str, width: int) -> list[str]:
    """Split ``text`` into lines of at most ``width`` characters for display.

    Like :func:`textwrap.wrap`, but made for DC literals: lines break at spaces (not the one
    after ``\\+``) and also after a comma or an opening parenthesis or bracket, so that
    ``finite([0.92:true,0.08:false])`` or ``rel(Object,Other):t`` can be split; a piece longer
    than ``width`` with no break opportunity is cut. Joining the lines (with a space where a
    space was dropped) gives back the text.
    """
    if width < 1:
        raise ValueError(f"width must be positive, got {width}")
    lines: list[str] = []
    current = ""
    tokens = [
        piece
        for token in _BREAK.split(text)
        # A negated literal too long for a line gives up keeping ``\+`` with it.
        for piece in (_SPACE.split(token) if len(token.rstrip()) > width else [token])
        if piece
    ]
    for token in tokens:
        if current and len(current) + len(token.rstrip()) > width:
            lines.append(current.rstrip())
            current = ""
        current += token
        while len(current.rstrip()) > width:
            lines.append(current[:width])
            current = current[width:]
    if current.rstrip() or not lines:
        lines.append(current.rstrip())
    return lines


def layout(root: TreeNode) -> dict[NodePath, tuple[float, float]]:
    """Abstract top-down positions of the nodes, keyed by node path (branch indices from the
    root; the root is ``()``).

    ``x`` is in leaf columns: the i-th leaf in clause order is at ``x = i`` and an internal
    node is at the midpoint of its first and last child. ``y`` is the depth (0 at the root,
    growing downwards).
    """
    pos: dict[NodePath, tuple[float, float]] = {}
    next_leaf = 0

    def place(node: TreeNode, path: NodePath) -> float:
        nonlocal next_leaf
        if node.is_leaf:
            x = float(next_leaf)
            next_leaf += 1
        else:
            xs = [place(b.child, (*path, i)) for i, b in enumerate(node.branches)]
            x = 0.5 * (xs[0] + xs[-1])
        pos[path] = (x, float(len(path)))
        return x

    place(root, ())
    return pos


def _leaf_text(node: TreeNode) -> list[str]:
    lines = wrap_text(node.distribution or "?", _NODE_WRAP)
    if node.model is not None:
        lines += wrap_text(node.model, _NODE_WRAP)
    count = f"n = {node.rows}"
    if abs(node.weight - node.rows) > 1e-9:
        count += f", w = {node.weight:.5g}"
    return [*lines, count]


@dataclass
class _Geometry:
    """Everything :func:`plot_tree` draws, in inches (``y`` grows upwards, root at 0)."""

    nodes: list[TreeNode]  # pre-order
    texts: list[str]  # box text per node
    xy: np.ndarray  # (N, 2) box centres
    edges: np.ndarray  # (E, 2) int: parent index, child index
    labels: list[str]  # wrapped branch label per edge
    negated: np.ndarray  # (E,) bool: the branch label starts with ``\+``
    label_xy: np.ndarray  # (E, 2) anchor of each label (centre x, bottom y)
    xlim: tuple[float, float]
    ylim: tuple[float, float]  # without the title band
    title: str


def _geometry(tree: Tree) -> _Geometry:
    pos = layout(tree.root)
    nodes: list[TreeNode] = []
    paths: list[NodePath] = []
    edges: list[tuple[int, int]] = []
    raw_labels: list[str] = []

    def visit(node: TreeNode, path: NodePath, parent: int | None, label: str | None) -> None:
        index = len(nodes)
        nodes.append(node)
        paths.append(path)
        if parent is not None and label is not None:
            edges.append((parent, index))
            raw_labels.append(label)
        for i, branch in enumerate(node.branches):
            visit(branch.child, (*path, i), index, branch.label)

    visit(tree.root, (), None, None)

    line_lists = [
        _leaf_text(n) if n.is_leaf else wrap_text(n.test or "?", _NODE_WRAP) for n in nodes
    ]
    label_lists = [wrap_text(lab, _LABEL_WRAP) for lab in raw_labels]
    abstract = np.array([pos[p] for p in paths], dtype=float).reshape(-1, 2)
    depth = abstract[:, 1].astype(int)
    n_levels = int(depth.max()) + 1

    node_pt, label_pt = _NODE_PT / 72.0, _LABEL_PT / 72.0  # font sizes in inches
    chars = np.array([max(len(s) for s in ls) for ls in line_lists], dtype=float)
    rows = np.array([len(ls) for ls in line_lists], dtype=float)
    node_w = chars * _CHAR_EM * node_pt + 2 * _NODE_PAD_EM * node_pt
    node_h = rows * _LINE_EM * node_pt + 2 * _NODE_PAD_EM * node_pt

    edge_arr = np.array(edges, dtype=int).reshape(-1, 2)
    lab_chars = np.array([max(len(s) for s in ls) for ls in label_lists], dtype=float)
    lab_rows = np.array([len(ls) for ls in label_lists], dtype=float)
    lab_w = lab_chars * _CHAR_EM * label_pt + 2 * _LABEL_PAD_EM * label_pt
    lab_h = lab_rows * _LINE_EM * label_pt + 2 * _LABEL_PAD_EM * label_pt

    # Per level: half the tallest box and the tallest label above it (labels sit on their
    # child's level, above all of its boxes, so they line up and never touch a box).
    half = np.zeros(n_levels)
    np.maximum.at(half, depth, node_h / 2)
    lab_level = np.zeros(n_levels)
    if len(edge_arr):
        np.maximum.at(lab_level, depth[edge_arr[:, 1]], lab_h)
    # Level d-1 to level d: room for both boxes and the label, and tall enough that the
    # labels sit at most a fraction _LABEL_FRAC of the way back up to their parents.
    label_rise = half[1:] + _V_GAP + lab_level[1:]
    step = np.maximum.reduce([
        half[:-1] + label_rise + 2 * _V_GAP,
        label_rise / _LABEL_FRAC,
        np.full(n_levels - 1, _MIN_STEP),
    ])
    level_y = -np.concatenate([[0.0], np.cumsum(step)])

    # Column width: the widest box, and wide enough that the labels of neighbouring children,
    # which lean towards their parents by up to _LABEL_FRAC of a column, stay apart.
    col = float(node_w.max()) + _H_GAP
    if len(edge_arr):
        col = max(col, float(lab_w.max() + _H_GAP) / (1.0 - _LABEL_FRAC))

    xy = np.column_stack([abstract[:, 0] * col, level_y[depth]])
    n_leaves = sum(n.is_leaf for n in nodes)
    title_lines = wrap_text(tree.target, _TITLE_WRAP)
    title_w = max(len(s) for s in title_lines) * _CHAR_EM * _TITLE_PT / 72.0
    span = max(n_leaves * col, title_w)
    centre = 0.5 * (n_leaves - 1) * col
    xlim = (centre - span / 2 - _MARGIN, centre + span / 2 + _MARGIN)
    ylim = (float(level_y[-1] - half[-1]) - _MARGIN, float(half[0]) + _MARGIN)

    label_xy = np.zeros((len(edge_arr), 2))
    if len(edge_arr):
        parent_xy, child_xy = xy[edge_arr[:, 0]], xy[edge_arr[:, 1]]
        child_depth = depth[edge_arr[:, 1]]
        bottom = level_y[child_depth] + half[child_depth] + _V_GAP + _LABEL_PAD_EM * label_pt
        mid_y = bottom + (lab_h / 2 - _LABEL_PAD_EM * label_pt)
        t = (mid_y - child_xy[:, 1]) / (parent_xy[:, 1] - child_xy[:, 1])
        label_xy = np.column_stack([child_xy[:, 0] + t * (parent_xy[:, 0] - child_xy[:, 0]),
                                    bottom])

    return _Geometry(
        nodes=nodes,
        texts=["\n".join(ls) for ls in line_lists],
        xy=xy,
        edges=edge_arr,
        labels=["\n".join(ls) for ls in label_lists],
        negated=np.array([lab.lstrip().startswith("\\+") for lab in raw_labels], dtype=bool),
        label_xy=label_xy,
        xlim=xlim,
        ylim=ylim,
        title="\n".join(title_lines),
    )


def _title_height(geom: _Geometry) -> float:
    return _TITLE_H + (geom.title.count("\n")) * _LINE_EM * _TITLE_PT / 72.0


def tree_size(tree: Tree) -> tuple[float, float]:
    """The size ``(width, height)`` in inches that the panel of ``tree`` needs, title included;
    give :func:`plot_tree` an axes of this size (as :func:`plot_trees` does) for a picture
    without overlaps."""
    geom = _geometry(tree)
    return (geom.xlim[1] - geom.xlim[0], geom.ylim[1] - geom.ylim[0] + _title_height(geom))


def plot_tree(tree: Tree, ax: Axes) -> None:
    """Draw ``tree`` into ``ax``, titled with its target.

    The data coordinates are inches; the limits are set to the tree's extent with an equal
    aspect, so on an axes of the size :func:`tree_size` gives (minus the title band) one data
    unit is one inch and no texts overlap.
    """
    _draw(_geometry(tree), ax)


def _draw(geom: _Geometry, ax: Axes) -> None:
    if len(geom.edges):
        segments = np.stack([geom.xy[geom.edges[:, 0]], geom.xy[geom.edges[:, 1]]], axis=1)
        inherited = np.array([geom.nodes[c].inherited for c in geom.edges[:, 1]], dtype=bool)
        ax.add_collection(
            LineCollection(
                segments,
                colors=_EDGE_COLOUR,
                linewidths=1.0,
                linestyles=[(0, (4, 3)) if i else "solid" for i in inherited],
                zorder=1,
            )
        )
        for (x, y), text, neg in zip(geom.label_xy, geom.labels, geom.negated, strict=True):
            ax.text(
                x, y, text, ha="center", va="bottom", multialignment="center",
                family=_FAMILY, fontsize=_LABEL_PT, color=_NO_COLOUR if neg else _YES_COLOUR,
                zorder=4,
                bbox={"boxstyle": f"square,pad={_LABEL_PAD_EM}", "facecolor": "white",
                      "edgecolor": "none", "alpha": 0.9},
            )
    for node, (x, y), text in zip(geom.nodes, geom.xy, geom.texts, strict=True):
        if node.is_leaf:
            box = {"boxstyle": f"square,pad={_NODE_PAD_EM}", **_LEAF_STYLE,
                   "linestyle": (0, (4, 3)) if node.inherited else "solid",
                   "linewidth": 1.2}
        else:
            box = {"boxstyle": f"round,pad={_NODE_PAD_EM}", **_INTERNAL_STYLE, "linewidth": 1.2}
        ax.text(x, y, text, ha="center", va="center", multialignment="center", family=_FAMILY,
                fontsize=_NODE_PT, zorder=3, bbox=box)
    ax.set_title(geom.title, family=_FAMILY, fontsize=_TITLE_PT, fontweight="bold")
    ax.set_xlim(*geom.xlim)
    ax.set_ylim(*geom.ylim)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_axis_off()


_FORMATS = {".png": "png", ".svg": "svg"}


def pruned(tree: Tree, max_depth: int) -> Tree:
    """``tree`` with each subtree below depth ``max_depth`` drawn as one box (its number of
    leaves and groundings), for a tree too big to read whole."""
    def cut(node: TreeNode, depth: int) -> TreeNode:
        if node.is_leaf:
            return node
        if depth >= max_depth:
            k = len(node.leaves())
            return TreeNode(rows=node.rows, weight=node.weight,
                            distribution=f"a subtree of {k} leaves")
        return replace(node, branches=[Branch(b.label, cut(b.child, depth + 1))
                                       for b in node.branches])

    return replace(tree, root=cut(tree.root, 0))


def plot_trees(trees: Sequence[Tree], path: str | Path, max_depth: int | None = None) -> Path:
    """Draw each tree (one panel per tree, stacked vertically) into a PNG or SVG file (by
    suffix; other suffixes -> ``ValueError`` naming the suffix). Returns the path.

    The figure is as wide as the widest panel and as tall as all of them: each panel gets the
    size :func:`tree_size` gives, so it grows with the number of leaves and the depth. With
    ``max_depth``, the subtrees below that depth are drawn as one box each (:func:`pruned`).
    """
    if max_depth is not None:
        trees = [pruned(t, max_depth) for t in trees]
    path = Path(path)
    fmt = _FORMATS.get(path.suffix.lower())
    if fmt is None:
        raise ValueError(
            f"cannot plot trees to {path.suffix or 'a file without suffix'!r}: "
            f"use one of {', '.join(_FORMATS)}"
        )
    if not trees:
        raise ValueError("no trees to plot")
    geoms = [_geometry(t) for t in trees]
    sizes = np.array(
        [(g.xlim[1] - g.xlim[0], g.ylim[1] - g.ylim[0], _title_height(g)) for g in geoms]
    )
    fig_w = float(sizes[:, 0].max())
    fig_h = float(sizes[:, 1:].sum())
    fig = Figure(figsize=(fig_w, fig_h), dpi=_DPI)
    FigureCanvasAgg(fig)
    try:
        top = fig_h
        for geom, (w, h, title_h) in zip(geoms, sizes, strict=True):
            top -= title_h
            rect = ((fig_w - w) / 2 / fig_w, (top - h) / fig_h, w / fig_w, h / fig_h)
            _draw(geom, fig.add_axes(rect))
            top -= h
        path.parent.mkdir(parents=True, exist_ok=True)
        with matplotlib.rc_context({"svg.hashsalt": "ddclearn"}):
            fig.savefig(path, format=fmt, dpi=_DPI, facecolor="white")
    finally:
        fig.clear()
    return path
