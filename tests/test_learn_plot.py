"""Drawing learned distributional logic trees: layout, text wrapping, PNG and SVG output."""

from __future__ import annotations

import struct
import xml.etree.ElementTree as ET
from pathlib import Path

import matplotlib
import pytest
from matplotlib import _pylab_helpers
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from probanchor.ddclearn.plot import layout, plot_tree, plot_trees, pruned, tree_size, wrap_text
from probanchor.ddclearn.tree import Branch, Tree, TreeNode

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def leaf(distribution, rows, model=None, weight=None, inherited=False):
    return TreeNode(rows=rows, weight=float(rows if weight is None else weight),
                    distribution=distribution, model=model, inherited=inherited)


def node(test, rows, *branches, weight=None):
    return TreeNode(rows=rows, weight=float(rows if weight is None else weight), test=test,
                    branches=[Branch(label, child) for label, child in branches])


def occluder_tree():
    """The tree of the paper's Figure 5 for ``occluded_by(A,O):t+1``."""
    observed_yes = node(
        "observed(A):t+1", 60,
        ("observed(A):t+1", leaf("finite([1.0:false])", 25)),
        ("\\+ observed(A):t+1", leaf("finite([0.92:true,0.08:false])", 35)),
    )
    distance = node(
        "distance(A,O):t ~= D", 90,
        ("distance(A,O):t ~= D", leaf("finite([P1:true,P2:false])", 80,
                                      model="logistic([D],[-16.9,0.8],P1)", weight=77.5)),
        ("\\+ distance(A,O):t ~= _", leaf("finite([1.0:false])", 10, inherited=True)),
        weight=87.5,
    )
    observed_no = node(
        "observed(A):t+1", 140,
        ("observed(A):t+1", leaf("finite([1.0:false])", 50)),
        ("\\+ observed(A):t+1", distance),
        weight=137.5,
    )
    root = node(
        "occluded_by(A,O):t", 200,
        ("occluded_by(A,O):t", observed_yes),
        ("\\+ occluded_by(A,O):t", observed_no),
        weight=197.5,
    )
    return Tree("occluded_by(A,O):t+1", root)


def comb_tree(n_leaves):
    """A right comb: ``n_leaves`` leaves, each test's "yes" branch a leaf."""
    sub = leaf("gaussian(0.0,1.0)", 5)
    for i in range(n_leaves - 1):
        sub = node(f"near(A,B{i}):t", 10, (f"near(A,B{i}):t", leaf(f"gaussian({i}.0,1.0)", 5)),
                   (f"\\+ near(A,B{i}):t", sub))
    return Tree("position(A):t+1", sub)


def svg_texts(path):
    root = ET.parse(path).getroot()  # raises on invalid XML
    return ["".join(el.itertext()) for el in root.iter("{http://www.w3.org/2000/svg}text")]


def png_size(path):
    data = Path(path).read_bytes()
    assert data[:8] == PNG_MAGIC
    return struct.unpack(">II", data[16:24])


# --- layout ---------------------------------------------------------------------------------


def test_layout_leaves_in_clause_order_and_parents_centred():
    tree = occluder_tree()
    pos = layout(tree.root)
    leaves = [p for p in pos if p not in {(), (0,), (1,), (1, 1)}]
    # Leaves in clause order (pre-order of paths) get x = 0, 1, 2, ...
    in_order = sorted(leaves)
    assert [pos[p][0] for p in in_order] == [0.0, 1.0, 2.0, 3.0, 4.0]
    assert in_order == [(0, 0), (0, 1), (1, 0), (1, 1, 0), (1, 1, 1)]
    # Depth is the path length.
    assert all(pos[p][1] == len(p) for p in pos)
    # Each internal node centred over its children.
    assert pos[(1, 1)][0] == pytest.approx(3.5)
    assert pos[(0,)][0] == pytest.approx(0.5)
    assert pos[(1,)][0] == pytest.approx(0.5 * (2.0 + 3.5))
    assert pos[()][0] == pytest.approx(0.5 * (pos[(0,)][0] + pos[(1,)][0]))


def test_layout_many_branches_and_single_leaf():
    tree = node("colour(A) ~= C", 9,
                ("colour(A) ~= red", leaf("a", 3)),
                ("colour(A) ~= green", node("near(A,B):t", 3, ("near(A,B):t", leaf("b", 1)),
                                            ("\\+ near(A,B):t", leaf("c", 2)))),
                ("colour(A) ~= blue", leaf("d", 3)),
                ("\\+ colour(A) ~= _", leaf("e", 0)))
    pos = layout(tree)
    leaf_paths = [(0,), (1, 0), (1, 1), (2,), (3,)]
    assert [pos[p][0] for p in leaf_paths] == [0.0, 1.0, 2.0, 3.0, 4.0]
    assert pos[(1,)][0] == 1.5
    assert pos[()][0] == 2.0  # midpoint of the first and the last child
    assert len(pos) == 7
    assert layout(leaf("finite([1.0:true])", 4)) == {(): (0.0, 0.0)}


def test_wrap_text_breaks_literals_sensibly():
    assert wrap_text("finite([0.92:true,0.08:false])", 32) == ["finite([0.92:true,0.08:false])"]
    assert wrap_text("finite([0.92:true,0.08:false])", 20) == ["finite([0.92:true,", "0.08:false])"]
    assert wrap_text("\\+ near(A,B):t", 16) == ["\\+ near(A,B):t"]
    # The negation stays with its literal while it fits on a line.
    assert wrap_text("\\+ rel(Object,Other):t", 14) == ["\\+ rel(Object,", "Other):t"]
    # ... and gives up when it does not.
    assert wrap_text("\\+ relation(Obj):t", 11) == ["\\+", "relation(", "Obj):t"]
    assert all(len(line) <= 10 for line in wrap_text("x" * 35, 10))
    assert "".join(wrap_text("x" * 35, 10)) == "x" * 35
    assert wrap_text("", 10) == [""]
    with pytest.raises(ValueError):
        wrap_text("a", 0)


# --- drawing --------------------------------------------------------------------------------


def test_svg_holds_literals_and_leaf_texts(tmp_path):
    with matplotlib.rc_context({"svg.fonttype": "none"}):
        out = plot_trees([occluder_tree()], tmp_path / "tree.svg")
    assert out == tmp_path / "tree.svg" and out.is_file()
    texts = svg_texts(out)
    for literal in ["occluded_by(A,O):t", "\\+ occluded_by(A,O):t", "observed(A):t+1",
                    "\\+ observed(A):t+1", "distance(A,O):t ~= D", "\\+ distance(A,O):t ~= _"]:
        assert literal in texts, literal
    for line in ["finite([1.0:false])", "finite([0.92:true,0.08:false])",
                 "finite([P1:true,P2:false])", "logistic([D],[-16.9,0.8],P1)", "n = 25",
                 "n = 35", "n = 50", "n = 10", "n = 80, w = 77.5"]:
        assert line in texts, line
    assert "occluded_by(A,O):t+1" in texts  # the title
    assert texts.count("observed(A):t+1") == 4  # two tests, two branch labels
    assert not any(t.startswith("n = 200") for t in texts)  # internal nodes show only the test


def test_png_size_grows_with_leaves_and_depth(tmp_path):
    out = plot_trees([occluder_tree()], str(tmp_path / "tree.png"))
    assert isinstance(out, Path) and out.stat().st_size > 5000
    w, h = png_size(out)
    assert w > 400 and h > 200
    sizes = [png_size(plot_trees([comb_tree(n)], tmp_path / f"comb{n}.png")) for n in (2, 4, 8)]
    widths, heights = zip(*sizes, strict=True)
    assert widths[0] < widths[1] < widths[2]
    assert heights[0] < heights[1] < heights[2]
    assert tree_size(comb_tree(30))[0] > 2 * tree_size(comb_tree(15))[0] * 0.95


def test_single_leaf_and_several_trees(tmp_path):
    single = Tree("colour(A)", leaf("finite([0.5:red,0.5:blue])", 7))
    w1, h1 = png_size(plot_trees([single], tmp_path / "leaf.png"))
    assert w1 > 50 and h1 > 50
    with matplotlib.rc_context({"svg.fonttype": "none"}):
        out = plot_trees([occluder_tree(), single], tmp_path / "two.svg")
    texts = svg_texts(out)
    assert {"occluded_by(A,O):t+1", "colour(A)", "finite([0.5:red,0.5:blue])", "n = 7"} <= set(
        texts
    )
    both = png_size(plot_trees([occluder_tree(), single], tmp_path / "two.png"))
    alone = png_size(plot_trees([occluder_tree()], tmp_path / "one.png"))
    assert both[0] == alone[0] and both[1] > alone[1] + h1 * 0.9
    assert _pylab_helpers.Gcf.get_num_fig_managers() == 0  # nothing left open in pyplot


def test_plot_tree_styles(tmp_path):
    fig = Figure(figsize=tree_size(occluder_tree()))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    plot_tree(occluder_tree(), ax)
    assert ax.get_title() == "occluded_by(A,O):t+1"
    by_text = {t.get_text(): t for t in ax.texts}
    internal = by_text["distance(A,O):t ~= D"]
    inherited = by_text["finite([1.0:false])\nn = 10"]
    normal = by_text["finite([1.0:false])\nn = 25"]
    model = by_text["finite([P1:true,P2:false])\nlogistic([D],[-16.9,0.8],P1)\nn = 80, w = 77.5"]
    assert "monospace" in internal.get_fontfamily()
    assert internal.get_bbox_patch().get_facecolor() != normal.get_bbox_patch().get_facecolor()
    assert normal.get_bbox_patch().get_linestyle() == "solid"
    assert inherited.get_bbox_patch().get_linestyle() != "solid"
    assert model.get_bbox_patch().get_facecolor() == normal.get_bbox_patch().get_facecolor()
    assert len(ax.texts) == 5 + 4 + 8  # leaves, tests, branch labels
    fig.savefig(tmp_path / "ax.png")


def test_bad_suffix(tmp_path):
    with pytest.raises(ValueError, match=r"\.pdf"):
        plot_trees([occluder_tree()], tmp_path / "tree.pdf")
    with pytest.raises(ValueError):
        plot_trees([occluder_tree()], tmp_path / "tree")
    with pytest.raises(ValueError):
        plot_trees([], tmp_path / "tree.png")
    assert not list(tmp_path.iterdir())


def test_a_pruned_tree_keeps_its_first_levels_and_counts_what_it_cuts(tmp_path):
    tree = comb_tree(8)                       # depth 7, 8 leaves
    cut = pruned(tree, 3)
    assert cut.root.depth() == 3
    leaves = cut.root.leaves()
    assert len(leaves) == 4                   # three leaves above the cut, one box below it
    assert leaves[-1].distribution == "a subtree of 5 leaves"
    assert leaves[-1].rows == 10              # the cut node's own counts
    assert [lf.distribution for lf in leaves[:3]] == [lf.distribution
                                                      for lf in tree.root.leaves()[:3]]
    full = png_size(plot_trees([tree], tmp_path / "full.png"))
    small = png_size(plot_trees([tree], tmp_path / "small.png", max_depth=3))
    assert small[1] < full[1]
