"""The tree search on small data sets whose answer is known: thresholds, counts, several
classes, uncertain facts, a relational literal found by lookahead, and the search's settings.

The trees are grown without a root model (``root_model="never"``): on one feature the root
model's regression is the tree's model in another form (tests/test_learn_root_model.py)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from probanchor.ddclearn import SearchOptions, evaluate, learn


def write(path: Path, lines: list[str]) -> Path:
    path.write_text("\n".join(lines) + "\n")
    return path


TREE = SearchOptions(root_model="never")


def leaves(result):
    return result.targets[0].leaves


def test_thresholds_give_one_branch_per_interval(tmp_path: Path) -> None:
    rng = np.random.default_rng(0)
    lines = ["type(y(e)).", "type(d(e)).", "rv(y(_), boolean).", "rv(d(_), continuous).",
             "threshold(d(_), [0.1, 0.2]).", "learn(y(X)).", "mode(y(_), d(+))."]
    p = {0: 0.9, 1: 0.5, 2: 0.1}
    for i in range(3000):
        d = rng.uniform(0, 0.3)
        b = int(d >= 0.1) + int(d >= 0.2)
        lines += [f"d({i}) ~= {d:.4f}.", f"y({i}) ~= {str(rng.random() < p[b]).lower()}."]
    result = learn([write(tmp_path / "t.pl", lines)], options=TREE)
    ls = leaves(result)
    bodies = [leaf.clause.split(":=")[1] for leaf in ls]
    assert "D < 0.1" in bodies[0]
    assert "D >= 0.1" in bodies[1] and "D < 0.2" in bodies[1]
    assert "D >= 0.2" in bodies[2]
    assert "\\+ d(X) ~= _" in bodies[3]
    for leaf, b in zip(ls[:3], range(3), strict=True):
        se = math.sqrt(p[b] * (1 - p[b]) / leaf.rows)
        assert leaf.leaf.probs[0] == pytest.approx(p[b], abs=4 * se)


def test_a_count_target_gets_poisson_leaves(tmp_path: Path) -> None:
    rng = np.random.default_rng(1)
    lines = ["type(n(e)).", "type(x(e)).", "rv(n(_), count).", "rv(x(_), continuous).",
             "learn(n(X)).", "mode(n(_), x(+))."]
    xs = rng.uniform(0, 2, 4000)
    ns = rng.poisson(np.exp(0.7 * xs - 0.2))
    lines += [f"x({i}) ~= {x:.5f}." for i, x in enumerate(xs)]
    lines += [f"n({i}) ~= {n}." for i, n in enumerate(ns)]
    result = learn([write(tmp_path / "c.pl", lines)], options=TREE)
    leaf = leaves(result)[0]
    assert leaf.leaf.family == "poisson_log_linear"
    w, b = leaf.leaf.weights
    assert w == pytest.approx(0.7, abs=0.05) and b == pytest.approx(-0.2, abs=0.08)
    assert "poisson(Rate)" in leaf.clause and "Rate is exp(Z)" in leaf.clause


def test_three_classes_and_a_regressor_give_softmax(tmp_path: Path) -> None:
    rng = np.random.default_rng(2)
    lines = ["type(c(e)).", "type(x(e)).", "rv(c(_), discrete([r, g, b])).",
             "rv(x(_), continuous).", "learn(c(X)).", "mode(c(_), x(+))."]
    W = np.array([[0.0, 0.0], [2.0, -1.0], [-1.5, 0.5]])
    xs = rng.uniform(-2, 2, 6000)
    z = W[:, :1] * xs + W[:, 1:]
    p = np.exp(z) / np.exp(z).sum(axis=0)
    cs = [("r", "g", "b")[rng.choice(3, p=p[:, i])] for i in range(len(xs))]
    lines += [f"x({i}) ~= {x:.5f}." for i, x in enumerate(xs)]
    lines += [f"c({i}) ~= {c}." for i, c in enumerate(cs)]
    path = write(tmp_path / "s.pl", lines)
    result = learn([path], options=TREE)
    leaf = leaves(result)[0]
    assert leaf.leaf.family == "softmax"
    rows = np.array(leaf.leaf.weight_rows)
    assert np.allclose(rows[0], 0)
    assert np.allclose(rows, W, atol=0.25)
    assert "softmax([X1], [[0.0, 0.0]," in leaf.clause
    out = result.write(tmp_path / "s_learned.pl")
    assert evaluate(out, [path])["c"]["log_likelihood"] == pytest.approx(
        result.targets[0].log_likelihood, rel=1e-4)


def test_uncertain_facts_are_weighted_partial_worlds(tmp_path: Path) -> None:
    """Expected counts: P(y | f) = (sum of the label probabilities + 1) / (weight + 2)."""
    lines = ["type(y(e)).", "type(f(e)).", "rv(y(_), boolean).", "learn(y(X)).",
             "examples(y(X), e(X)).", "mode(y(_), f(+))."]
    for i in range(400):
        lines.append(f"e({i}).")
        if i % 2 == 0:
            lines.append(f"0.5 :: f({i}).")
        lines.append(f"{0.2 if i % 2 == 0 else 0.9} :: y({i}).")
    result = learn([write(tmp_path / "p.pl", lines)])
    yes, no = leaves(result)
    assert "f(X)" in yes.clause and "\\+ f(X)" in no.clause
    assert yes.weight == pytest.approx(100.0) and no.weight == pytest.approx(300.0)
    assert yes.leaf.probs[0] == pytest.approx((0.2 * 100 + 1) / (100 + 2))
    assert no.leaf.probs[0] == pytest.approx((0.9 * 200 + 0.2 * 100 + 1) / (300 + 2))


def test_a_relational_literal_is_found_by_lookahead(tmp_path: Path) -> None:
    """y depends on the colour of the one entity X links to: link(X, Y) adds nothing by itself,
    colour(Y) does; with lookahead the tree is link, then colour; without it, a leaf."""
    rng = np.random.default_rng(3)
    lines = ["type(y(e)).", "type(link(e, e)).", "type(colour(e)).", "rv(y(_), boolean).",
             "rv(colour(_), discrete([red, blue])).", "learn(y(X)).",
             "mode(y(_), link(+, -)).", "mode(y(_), colour(+))."]
    for i in range(1500):
        c = rng.choice(["red", "blue"])
        lines += [f"link(a{i}, b{i}).", f"colour(b{i}) ~= {c}.",
                  f"y(a{i}) ~= {str(rng.random() < (0.9 if c == 'red' else 0.1)).lower()}."]
    path = write(tmp_path / "r.pl", lines)
    result = learn([path])
    tree = result.targets[0].tree.root
    assert tree.test == "(link(X, E) -> true)"
    below = tree.branches[0].child
    assert below.test == "colour(E) ~= _"
    assert "(link(X, E) -> true),\n    colour(E) ~= red" in leaves(result)[0].clause
    flat = learn([path], options=SearchOptions(lookahead=False))
    assert flat.targets[0].tree.root.is_leaf


def test_min_leaf_and_max_depth(tmp_path: Path) -> None:
    rng = np.random.default_rng(4)
    lines = ["type(y(e)).", "type(a(e)).", "type(b(e)).", "rv(y(_), boolean).",
             "rv(a(_), discrete([p, q])).", "rv(b(_), discrete([r, s])).", "learn(y(X)).",
             "mode(y(_), a(+)).", "mode(y(_), b(+))."]
    for i in range(2000):
        a, b = rng.choice(["p", "q"], p=[0.99, 0.01]), rng.choice(["r", "s"])
        p = {("p", "r"): 0.9, ("p", "s"): 0.2, ("q", "r"): 0.5, ("q", "s"): 0.5}[(a, b)]
        y = str(rng.random() < p).lower()
        lines += [f"a({i}) ~= {a}.", f"b({i}) ~= {b}.", f"y({i}) ~= {y}."]
    path = write(tmp_path / "m.pl", lines)
    deep = learn([path])
    assert deep.targets[0].tree.root.depth() >= 1
    shallow = learn([path], options=SearchOptions(max_depth=1))
    assert shallow.targets[0].tree.root.depth() <= 1
    stump = learn([path], options=SearchOptions(max_depth=0))
    assert stump.targets[0].tree.root.is_leaf and len(leaves(stump)) == 1
    # few q's: with a large min_leaf their branch keeps its parent's model
    big = learn([path], options=SearchOptions(min_leaf=100))
    inherited = [leaf for leaf in leaves(big) if leaf.inherited]
    assert inherited and all(leaf.weight < 100 for leaf in inherited)
    assert all("too few groundings" in big.program.split(leaf.clause)[0].rsplit("\n", 2)[-2]
               for leaf in inherited)


def test_search_options_are_checked() -> None:
    with pytest.raises(ValueError, match="min_leaf"):
        SearchOptions(min_leaf=0)
    with pytest.raises(ValueError, match="max_depth"):
        SearchOptions(max_depth=-1)
