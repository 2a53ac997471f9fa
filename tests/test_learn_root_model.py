"""The root model (probanchor.ddclearn.root_model) and the leaves that read its scores.

The root model is a regression over every feature the bias allows at a target's root; its
scores are cross-fitted for the search and computed by the learned clause from the features
(DC goals: the features' literals, an undefined value's mean, linear/3). A leaf takes the
scores as an offset (leaves.fit_offset_leaf). Checked here: the feature columns; the model
against scikit-learn's fit of the same penalty; the offset leaves' parameters against their
generating values; the learned clause computes in the engine the probability that
``ddc evaluate`` scores; and the search uses the root model where held-out examples say it
predicts better (an additive university) and not where a tree does (an interaction).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.special import expit

import bridge
from probanchor.ddclearn import evaluate, learn
from probanchor.ddclearn.leaves import LeafOptions, fit_offset_leaf
from probanchor.ddclearn.root_model import (
    L2,
    fit_root_model,
    fold_of,
    root_features,
)
from probanchor.ddclearn.search import SearchOptions
from probanchor.ddclearn.university import university_data


def _cand(cid: int, kind: str, branches: int) -> dict:
    return {"id": cid, "kind": kind, "branches": branches,
            "labels": [f"c{cid} [{b}]" for b in range(branches)]}


def test_root_features_columns() -> None:
    cands = [_cand(1, "numeric", 2), _cand(2, "discrete", 3), _cand(3, "count", 1),
             _cand(4, "numeric", 2), _cand(5, "test", 2), _cand(6, "test", 2)]
    branch = [np.array([0, 0, 1, 0]),          # a value, undefined in row 2
              np.array([0, 1, 2, 2]),          # a discrete attribute: 3 branches
              np.array([0, 0, 0, 0]),          # a count
              np.array([0, -1, 0, 0]),         # not one certain outcome in row 1: left out
              np.array([0, 1, 0, 1]),          # a test
              np.array([0, 1, 0, 1])]          # the same column again: left out
    x = [np.array([1.0, 3.0, np.nan, 5.0]), np.full(4, np.nan), np.array([2.0, 2.0, 2.0, 2.0]),
         np.array([1.0, 1.0, 1.0, 1.0]), np.full(4, np.nan), np.full(4, np.nan)]
    w = np.array([1.0, 1.0, 1.0, 2.0])
    f = root_features(cands, branch, x, w)
    terms = [ft.term() for ft in f.features]
    fill = (1.0 + 3.0 + 2 * 5.0) / 4
    # a candidate's branches but its last one (they sum to 1)
    assert terms == [f"value(1, {fill!r})", "branch(1, 1)", "branch(2, 0)", "branch(2, 1)",
                     "branch(5, 0)"]
    # the count is the same in every row: no column
    np.testing.assert_allclose(f.X[:, 0], [1.0, 3.0, fill, 5.0])
    np.testing.assert_array_equal(f.X[:, 1], [0, 0, 1, 0])
    np.testing.assert_array_equal(f.X[:, 2:4], np.eye(3)[[0, 1, 2, 2]][:, :2])
    np.testing.assert_array_equal(f.X[:, 4], [1, 0, 1, 0])


def _logistic_rows(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    X = np.column_stack([rng.normal(size=n), rng.uniform(0, 10, n), rng.normal(size=n)])
    logit = 1.5 * X[:, 0] - 0.3 * X[:, 1] + 1.0          # the third column is noise
    y = (rng.random(n) < expit(logit)).astype(np.int64)  # class 1 = "true" here
    return X, y


def test_the_root_model_is_a_penalised_regression_cross_fitted() -> None:
    from sklearn.linear_model import LogisticRegression

    X, y = _logistic_rows(3000, seed=3)
    feats = root_features([_cand(i, "numeric", 2) for i in range(3)],
                          [np.zeros(len(y), dtype=int)] * 3, list(X.T), np.ones(len(y)))
    w = np.ones(len(y))
    m = fit_root_model("discrete", y, w, np.arange(len(y)), feats, n_classes=2, smoothing=0.0)
    assert m is not None and m.n_scores == 1 and m.l2 == L2
    assert m.cv_log_likelihood > m.plain_cv_log_likelihood + 0.1
    # the full fit: scikit-learn's on standardised columns, penalty C = 1 / l2
    mu, sd = X.mean(axis=0), X.std(axis=0)
    ref = LogisticRegression(C=1 / L2, tol=1e-10, max_iter=2000).fit((X - mu) / sd, y)
    row = np.asarray(m.rows[0])
    np.testing.assert_allclose(X @ row[:-1] + row[-1], ref.decision_function((X - mu) / sd),
                               atol=2e-3)
    # near the generating weights (3000 rows, a penalty that is small beside them)
    np.testing.assert_allclose(row[:3], [1.5, -0.3, 0.0], atol=0.15)
    # cross-fitted: close to the full fit's scores, not equal to them
    full = X @ row[:-1] + row[-1]
    gap = np.abs(m.scores[:, 0] - full)
    assert 0 < gap.mean() < 0.05 and np.corrcoef(m.scores[:, 0], full)[0, 1] > 0.99


def test_no_root_model_without_signal() -> None:
    rng = np.random.default_rng(4)
    X = rng.normal(size=(2000, 4))
    y = rng.integers(0, 2, 2000)
    feats = root_features([_cand(i, "numeric", 2) for i in range(4)],
                          [np.zeros(2000, dtype=int)] * 4, list(X.T), np.ones(2000))
    assert fit_root_model("discrete", y, np.ones(2000), np.arange(2000), feats,
                          n_classes=2) is None


def test_folds_keep_an_example_together() -> None:
    example = np.array([0, 0, 1, 2, 2, 2, 3, 4, 5, 5])
    f = fold_of(example, 3)
    for e in np.unique(example):
        assert len(set(f[example == e])) == 1
    np.testing.assert_array_equal(f, fold_of(example, 3))      # the same examples, folds


@pytest.mark.parametrize("k", [2, 3])
def test_an_offset_leaf_estimates_its_shift(k: int) -> None:
    """y ~ softmax(score + b): the leaf keeps the score's coefficient at 1 and finds b."""
    rng = np.random.default_rng(k)
    n = 20000
    S = rng.normal(scale=1.5, size=(n, k - 1))
    x = rng.normal(size=n)
    b = np.array([0.4, -0.7])[: k - 1]
    eta = np.column_stack([np.zeros(n), S + b + 0.5 * x[:, None]])
    p = np.exp(eta - eta.max(axis=1, keepdims=True))
    p /= p.sum(axis=1, keepdims=True)
    y = (rng.random((n, 1)) > np.cumsum(p, axis=1)).sum(axis=1)
    X = np.column_stack([S, x])
    leaf = fit_offset_leaf("discrete", y, np.ones(n), X, offsets=k - 1, n_classes=k,
                           options=LeafOptions(smoothing=0.0, l2=0.0))
    assert leaf is not None
    if k == 2:
        # P(class 0) = sigmoid(-(score + c x + d)): weights [-1, -c, -d]
        np.testing.assert_allclose(leaf.weights, [-1.0, -0.5, -0.4], atol=0.06)
    else:
        rows = np.asarray(leaf.weight_rows)
        np.testing.assert_allclose(rows[0], 0.0)
        np.testing.assert_allclose(rows[1:, :2], np.eye(2))          # the offsets
        np.testing.assert_allclose(rows[1:, 2:], [[0.5, 0.4], [0.5, -0.7]], atol=0.08)
    # the leaf's log-probabilities are the softmax's
    lp = np.log(p[np.arange(n), y])
    assert float(np.mean(leaf.log_prob(y, X) - lp)) == pytest.approx(0.0, abs=0.01)


def test_an_offset_leaf_of_a_continuous_and_a_count_target() -> None:
    rng = np.random.default_rng(7)
    n = 5000
    s, x = rng.normal(size=n), rng.normal(size=n)
    y = s + 2.0 * x - 1.0 + rng.normal(scale=0.5, size=n)
    leaf = fit_offset_leaf("continuous", y, np.ones(n), np.column_stack([s, x]), offsets=1)
    assert leaf is not None and leaf.family == "linear_gaussian"
    np.testing.assert_allclose(leaf.weights, [1.0, 2.0, -1.0], atol=0.05)
    assert leaf.variance == pytest.approx(0.25, rel=0.1)
    counts = rng.poisson(np.exp(0.5 * s + 0.3))
    leaf = fit_offset_leaf("count", counts, np.ones(n), s[:, None] * 0.5, offsets=1,
                           options=LeafOptions(l2=0.0))
    assert leaf is not None and leaf.family == "poisson_log_linear"
    np.testing.assert_allclose(leaf.weights, [1.0, 0.3], atol=0.05)
    with pytest.raises(ValueError, match="offsets"):
        fit_offset_leaf("continuous", y, np.ones(n), np.column_stack([s, x]), offsets=2)


# ----------------------------------------------------------------------------- end to end


def _small_university(folder: Path, seed: int, effects: int, students: int = 150) -> Path:
    path = folder / f"u{seed}.pl"
    path.write_text(university_data(seed=seed, effects_seed=effects, students=students,
                                    courses=20, professors=10))
    return path


def test_the_engine_computes_what_evaluate_scores(tmp_path: Path) -> None:
    """A root model's clause (features, scores, an offset leaf) runs in the engine and gives a
    grounding the probability ddc evaluate scores it with."""
    train = _small_university(tmp_path, 1, 5)
    result = learn([train], ["grade"], options=SearchOptions(root_model="always"))
    target = result.targets[0]
    assert target.root_model is not None
    program = result.write(tmp_path / "learned.pl")
    text = program.read_text()
    assert "linear([" in text and "Score" in text and " -> " in text
    test = university_data(seed=2, effects_seed=5, students=150, courses=20, professors=10)
    facts = [ln for ln in test.splitlines() if ln and not ln.startswith("%")]
    facts = facts[:facts.index("type(intelligence(s)).")]
    grades = [ln for ln in facts if ln.startswith("grade(")]
    others = [ln for ln in facts if not ln.startswith(("grade(", "satisfaction(", "hours("))]
    bias = test[test.index("type(intelligence(s))."):]
    dc = [f"{k} ~ val({v})." for k, v in (ln.rstrip(".").split(" ~= ") for ln in others
                                          if " ~= " in ln)]
    dc += [ln.rstrip(".") + " := true." for ln in others if " ~= " not in ln]
    for line in grades[:3]:
        one = tmp_path / "one.pl"
        one.write_text("\n".join(others + [line]) + "\n" + bias)
        expected = math.exp(evaluate(program, [one], ["grade"])["grade"]["mean_log_likelihood"])
        s, c, y = re.match(r"grade\((\w+), (\w+)\) ~= (\w+)\.", line).groups()  # type: ignore[union-attr]
        query = tmp_path / "query.pl"
        query.write_text(text + "\n" + "\n".join(dc) + "\n")
        p = bridge.load(query).query(f"grade({s}, {c}) ~= {y}", samples=50, seed=0).probability
        assert p == pytest.approx(expected, rel=1e-9)


def test_the_tree_form_reads_the_root_model_too(tmp_path: Path) -> None:
    train, test = _small_university(tmp_path, 1, 6), _small_university(tmp_path, 2, 6)
    result = learn([train], ["grade", "hours"], options=SearchOptions(root_model="always"))
    clauses = result.write(tmp_path / "clauses.pl")
    tree = result.write(tmp_path / "tree.pl", form="tree")
    a, b = evaluate(clauses, [test]), evaluate(tree, [test])
    for k in ("grade", "hours"):
        assert b[k]["log_likelihood"] == pytest.approx(a[k]["log_likelihood"], rel=1e-12)


def _interaction_data(path: Path, n: int, seed: int) -> Path:
    """y is likely exactly where a = p and b = r (an interaction no sum of effects gives)."""
    rng = np.random.default_rng(seed)
    a, b = rng.integers(0, 2, n), rng.integers(0, 2, n)
    v = rng.normal(size=n)
    p = np.where((a == 0) & (b == 0), 0.9, 0.15)
    y = rng.random(n) < p
    lines = ["type(y(e)). type(a(e)). type(b(e)). type(v(e)).",
             "rv(y(_), boolean). rv(a(_), discrete([p, q])). rv(b(_), discrete([r, s])).",
             "rv(v(_), continuous).", "learn(y(X)).",
             "mode(y(_), a(+)). mode(y(_), b(+)). mode(y(_), v(+))."]
    for i in range(n):
        lines.append(f"a(e{i}) ~= {'pq'[a[i]]}. b(e{i}) ~= {'rs'[b[i]]}. v(e{i}) ~= {v[i]:.4f}. "
                     f"y(e{i}) ~= {'true' if y[i] else 'false'}.")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_held_out_examples_decide_for_the_tree_or_the_root_model(tmp_path: Path) -> None:
    # an interaction: the tree of a and b, without the root model
    data = _interaction_data(tmp_path / "xor.pl", 1500, seed=8)
    t = learn([data], seed=0).targets[0]
    assert t.choice is not None and not t.choice.offsets and t.root_model is None
    assert t.choice.gain < 0
    # additive effects of many features (a generated university): the root model
    t = learn([_small_university(tmp_path, 1, 9, students=300)], ["grade"]).targets[0]
    assert t.choice is not None and t.choice.offsets and t.root_model is not None
    assert t.choice.gain > t.choice.se > 0
    # never: no root model is fitted
    t = learn([data], seed=0, options=SearchOptions(root_model="never")).targets[0]
    assert t.choice is None and t.root_model is None
    with pytest.raises(ValueError, match="root_model"):
        SearchOptions(root_model="sometimes")
