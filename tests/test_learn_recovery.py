"""Recovery of known programs by the structure learner (probanchor.ddclearn.learn).

Data are sampled with the project's own engine (``bridge.Program.sample`` through
``probanchor.ddclearn.synthetic.sample_data``) from DC programs whose structure and parameters are
known, the generators of ``tests/data/learn/``:

(a) ``discrete_tree.pl``: a discrete tree of depth 2 (a at the root, b in each of its
    subtrees) and an irrelevant discrete feature c;
(b) ``logistic.pl``: the paper's occluder clause, P(true) = sigmoid(-16.9 d + 0.8) on a
    distance d in [0, 0.3], gated by a Boolean feature (observed: false);
(c) ``linear_gaussian.pl``: y ~ gaussian(2.0 x + 0.5, 0.04) and an irrelevant feature z;
(d) ``relational_mean.pl``: y ~ gaussian(1.5 M + 0.2, 0.25), M the mean of v over the 1-5
    neighbours of the entity, beside distracting aggregates (the mean of w, the max of v, the
    count of neighbours, a single neighbour's v).

For each, on training data of n groundings the tree learned without a root model
(``root_model="never"``: the tree search alone) has the generator's structure (the tested
literals on each path, the irrelevant features absent), each parameter lies within 4 standard
errors of the generator's (the standard errors of the sample size, or of a statsmodels fit on the
same rows) and the learned leaf agrees with that unpenalised fit; on held-out data sampled with
another seed, the learned program's mean log-likelihood (``probanchor.ddclearn.evaluate``) is within
1 % of the generating program's and not better than it by more than sampling noise: the excess of an
estimate with k parameters fitted on n_train rows, scored on n_test rows, has a standard deviation
of about sqrt(k / (n_train n_test)) (its mean is minus the Kullback-Leibler divergence, about -k /
(2 n_train)), so the bound is 5 of those. The program learned with the default settings (which
may read a root model: a regression over every feature at the root, where held-out examples say
it predicts better) meets the same held-out bounds.

Sizes are chosen for tight statistics in about 10 s per case (sampling, learning, two
evaluations): 100,000 groundings of (c) take about 35 s on two cores (sampling 8 s, learning
21 s, half of it reading the 300,000 facts), too long for this file.
"""

from __future__ import annotations

import math
import re
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
import statsmodels.api as sm

import bridge
from probanchor.ddclearn import evaluate, learn
from probanchor.ddclearn.search import SearchOptions, TargetResult
from probanchor.ddclearn.synthetic import sample_data, sample_facts
from probanchor.ddclearn.tree import TreeNode

DATA = Path(__file__).resolve().parent / "data" / "learn"

#: Standard errors a parameter may lie from the generator's.
SE_BOUND = 4.0
#: Relative gap allowed between the learned and the generating program's held-out mean LL.
REL_GAP = 0.01
#: Standard deviations of the held-out noise by which the learned program may beat the generator.
NOISE_BOUND = 5.0


# ----------------------------------------------------------------------------- helpers


_FACT = re.compile(r"^(\w+)\(([^()]*)\)(:t\+1|:t)?(?:~=\s*(.+))?\.$")


def _facts(text: str) -> dict[str, dict[tuple[str, ...], object]]:
    """The facts of a sampled data file: predicate (with ``:t`` / ``:t+1``) -> key -> value.

    An atom's value is True; a number's is a float, an atom's the atom's text.
    """
    out: dict[str, dict[tuple[str, ...], object]] = defaultdict(dict)
    for line in text.splitlines():
        if not line or line.startswith("%") or line.startswith(("type(", "rv(", "mode(",
                                                                  "learn(", "examples(")):
            continue
        m = _FACT.match(line)
        assert m, f"not a fact of the sampler: {line!r}"
        name, args, time, value = m.groups()
        key = tuple(a.strip() for a in args.split(","))
        v: object = True
        if value is not None:
            try:
                v = float(value)
            except ValueError:
                v = value.strip()
        out[name + (time or "")][key] = v
    return out


@dataclass
class Run:
    """One recovery case: the data, the learned target and the held-out scores."""

    train: dict[str, dict[tuple[str, ...], object]]
    target: TargetResult
    n_train: int
    n_test: int
    learned: dict
    generator: dict
    default: TargetResult | None = None
    default_learned: dict | None = None


def _run(tmp: Path, generator: str, facts: list, bias: str, key: str, n_train: int,
         n_test: int, names: dict[str, str] | None = None) -> Run:
    gen = DATA / generator
    train_text = sample_data(gen, facts, n_train, seed=1, bias=bias, names=names)
    test_text = sample_data(gen, facts, n_test, seed=2, bias=bias, names=names)
    train, test = tmp / "train.pl", tmp / "test.pl"
    train.write_text(train_text)
    test.write_text(test_text)
    result = learn([train], seed=0, options=SearchOptions(root_model="never"))
    assert len(result.targets) == 1
    program = result.write(tmp / "learned.pl")
    learned = evaluate(program, [test], targets=[key])[key]
    generating = evaluate(gen, [test], targets=[key])[key]
    # The tree form (one clause, nested if-then-else) is the same program: the same score of
    # every held-out grounding, none left uncovered that the clauses cover.
    assert result.targets[0].tree_clause is not None
    tree = evaluate(result.write(tmp / "learned_tree.pl", form="tree"), [test], targets=[key])[key]
    assert tree["uncovered"] == learned["uncovered"]
    assert tree["log_likelihood"] == pytest.approx(learned["log_likelihood"], rel=1e-12, abs=1e-9)
    default = learn([train], seed=0)
    default_learned = evaluate(default.write(tmp / "learned_default.pl"), [test],
                               targets=[key])[key]
    return Run(_facts(train_text), result.targets[0], n_train, n_test, learned, generating,
               default.targets[0], default_learned)


def _paths(node: TreeNode, path: tuple[str, ...] = ()) -> list[tuple[tuple[str, ...], TreeNode]]:
    """(the branch labels from the root, the leaf) for each leaf, in clause order."""
    if node.is_leaf:
        return [(path, node)]
    return [p for b in node.branches for p in _paths(b.child, path + (_norm(b.label),))]


def _norm(text: str) -> str:
    return re.sub(r"\s+", "", text)


def _structure(target: TargetResult) -> list[tuple[tuple[str, ...], str]]:
    """The paths of the leaves that have groundings, each with its leaf's family.

    The leaves without groundings (a branch no training grounding reaches, such as the
    "undefined" branch of a feature every entity has) must keep their parent's model.
    """
    assert len(target.leaves) == len(_paths(target.tree.root))
    out = []
    for (path, node), record in zip(_paths(target.tree.root), target.leaves, strict=True):
        assert node.rows == record.rows
        if record.rows == 0:
            assert record.inherited, path
            continue
        out.append((path, record.leaf.family))
    return out


def _free_parameters(target: TargetResult) -> int:
    """The parameters of the learned program's models: those of the leaves with groundings
    (a leaf without keeps its parent's model, which no grounding is scored by) and of the root
    model its leaves read."""
    m = target.root_model
    root = 0 if m is None else m.n_scores * (len(m.features) + 1)
    return root + sum(r.leaf.n_params for r in target.leaves if r.rows > 0 and not r.inherited)


def _assert_heldout(run: Run) -> None:
    """Within 1 % of the generator's mean log-likelihood, and not better beyond noise; the
    same for the program learned with the default settings."""
    assert run.default is not None and run.default_learned is not None
    for target, got in ((run.target, run.learned), (run.default, run.default_learned)):
        gen = run.generator
        for score in (gen, got):
            assert score["n"] == run.n_test and score["uncovered"] == 0
        g, mine = gen["mean_log_likelihood"], got["mean_log_likelihood"]
        assert abs(mine - g) <= REL_GAP * abs(g), (mine, g)
        noise = math.sqrt(_free_parameters(target) / (run.n_train * run.n_test))
        assert mine - g <= NOISE_BOUND * noise, (mine, g, noise)


def _within(estimate: float, truth: float, se: float, what: str) -> None:
    assert abs(estimate - truth) <= SE_BOUND * se, \
        f"{what}: {estimate} vs {truth}, se {se} ({(estimate - truth) / se:+.2f} se)"


def _leaf(target: TargetResult, *path: str):
    """The leaf record at the end of ``path`` (normalised labels)."""
    want = tuple(_norm(p) for p in path)
    for (labels, _), record in zip(_paths(target.tree.root), target.leaves, strict=True):
        if labels == want:
            return record
    raise AssertionError(f"no leaf at {want}")


# ----------------------------------------------------------------------------- the sampler


@pytest.fixture(scope="module")
def tree_program() -> bridge.Program:
    return bridge.load(DATA / "discrete_tree.pl")


def test_sample_is_one_world_and_reproducible(tree_program: bridge.Program) -> None:
    goal = "between(1, 5, I), atom_concat(e, I, E), a(E) ~= A, a(E) ~= A2, y(E) ~= Y"
    first = tree_program.sample("E-A-A2-Y", goal, seed=3)
    assert first == tree_program.sample("E-A-A2-Y", goal, seed=3)
    assert first != tree_program.sample("E-A-A2-Y", goal, seed=4)
    assert len(first) == 5
    for k, text in enumerate(first, 1):
        e, a, a2, y = text.split("-")
        assert e == f"e{k}" and a == a2 and a in ("p", "q") and y in ("t", "f")
    # Term texts: a negative number and a quoted atom read back as Prolog terms.
    assert tree_program.sample("X-'A b'", "member(X, [-0.5])", seed=0) == ["-0.5-'A b'"]


def test_sample_errors_are_ddc_errors(tree_program: bridge.Program) -> None:
    with pytest.raises(bridge.DDCError, match="[Ss]yntax"):
        tree_program.sample("X", "a(X) ~= ", seed=0)
    with pytest.raises(bridge.DDCError):
        tree_program.sample("X", "X is foo + 1", seed=0)


def test_sample_facts_frequencies(tree_program: bridge.Program) -> None:
    """a(X) ~ finite([0.5:p, 0.5:q]) and y given (a, b): frequencies within 4 se."""
    n = 4000
    facts = _facts("\n".join(f + "." for f in sample_facts(
        tree_program, ["a(I) ~= A", "b(I) ~= B", "y(I) ~= Y"], n, seed=5)))
    assert len(facts["a"]) == len(facts["b"]) == len(facts["y"]) == n
    p_hat = sum(v == "p" for v in facts["a"].values()) / n
    _within(p_hat, 0.5, math.sqrt(0.25 / n), "P(a = p)")
    rows = [k for k, v in facts["a"].items() if v == "p" and facts["b"][k] == "r"]
    t_hat = sum(facts["y"][k] == "t" for k in rows) / len(rows)
    _within(t_hat, 0.9, math.sqrt(0.9 * 0.1 / len(rows)), "P(y = t | p, r)")


# ----------------------------------------------------------------------------- (a) discrete tree

TREE_PROBS = {("p", "r"): 0.9, ("p", "s"): 0.6, ("q", "r"): 0.1, ("q", "s"): 0.4}
TREE_BIAS = """
type(a(ent)).  type(b(ent)).  type(c(ent)).  type(y(ent)).
rv(a(_), discrete([p, q])).
rv(b(_), discrete([r, s])).
rv(c(_), discrete([u, v])).
rv(y(_), discrete([t, f])).
mode(y(_), a(+)).
mode(y(_), b(+)).
mode(y(_), c(+)).
learn(y(_)).
"""


@pytest.fixture(scope="module")
def tree_run(tmp_path_factory: pytest.TempPathFactory) -> Run:
    return _run(tmp_path_factory.mktemp("tree"), "discrete_tree.pl",
                ["a(I) ~= A", "b(I) ~= B", "c(I) ~= C", "y(I) ~= Y"], TREE_BIAS, "y",
                n_train=10_000, n_test=10_000)


def test_tree_structure(tree_run: Run) -> None:
    got = _structure(tree_run.target)
    assert got == [((f"a(Ent)~={a}", f"b(Ent)~={b}"), "finite")
                   for a in ("p", "q") for b in ("r", "s")]
    assert tree_run.target.tree.root.depth() == 2
    assert not any("c(" in label for path, _ in _paths(tree_run.target.tree.root)
                   for label in path)


def test_tree_parameters(tree_run: Run) -> None:
    a, b, y = tree_run.train["a"], tree_run.train["b"], tree_run.train["y"]
    for (va, vb), p in TREE_PROBS.items():
        record = _leaf(tree_run.target, f"a(Ent) ~= {va}", f"b(Ent) ~= {vb}")
        rows = [k for k in a if a[k] == va and b[k] == vb]
        n_t = sum(y[k] == "t" for k in rows)
        assert record.rows == len(rows)
        # Laplace smoothing (1): (n_t + 1) / (n + 2), of the rows with these values.
        assert record.leaf.probs[0] == pytest.approx((n_t + 1) / (len(rows) + 2), rel=1e-12)
        _within(record.leaf.probs[0], p, math.sqrt(p * (1 - p) / len(rows)), f"P(t | {va}, {vb})")


def test_tree_heldout(tree_run: Run) -> None:
    _assert_heldout(tree_run)


# ----------------------------------------------------------------------------- (b) logistic

LOGISTIC_W, LOGISTIC_B = -16.9, 0.8
LOGISTIC_BIAS = """
type(d(obj, obj):t).
type(observed(obj):t+1).
type(occluder(obj, obj):t+1).
rv(d(_, _):t, continuous).
rv(occluder(_, _):t+1, boolean).
mode(occluder(_, _):t+1, d(+, +):t).
mode(occluder(_, _):t+1, observed(+):t+1).
learn(occluder(_, _):t+1).
"""
LOGISTIC_FACTS = ["d(A, O):t ~= D", "observed(A):t+1", "occluder(A, O):t+1 ~= Y"]
PAIRS = {"A": "a", "O": "o"}


@pytest.fixture(scope="module")
def logistic_run(tmp_path_factory: pytest.TempPathFactory) -> Run:
    return _run(tmp_path_factory.mktemp("logistic"), "logistic.pl", LOGISTIC_FACTS,
                LOGISTIC_BIAS, "occluder:t+1", n_train=10_000, n_test=10_000, names=PAIRS)


def test_logistic_structure(logistic_run: Run) -> None:
    # The generator's clauses test {observed} and {\+ observed, d}. Every pair has a
    # distance, so the learner's root test "d defined" (the regressor's introduction) holds
    # for all of them and its "undefined" branch is empty; the seen pairs get a finite leaf
    # (the distance unused), the others the logistic of the distance.
    assert _structure(logistic_run.target) == [
        (("d(Obj,Obj1):t~=D", "observed(Obj):t+1"), "finite"),
        (("d(Obj,Obj1):t~=D", r"\+observed(Obj):t+1"), "logistic"),
    ]


def test_logistic_parameters(logistic_run: Run) -> None:
    d, seen, y = (logistic_run.train[p] for p in ("d:t", "observed:t+1", "occluder:t+1"))
    # Seen: never an occluder; the leaf has only its smoothing, 1 / (n + 2).
    record = _leaf(logistic_run.target, "d(Obj, Obj1):t ~= D", "observed(Obj):t+1")
    n_seen = sum(1 for k in y if (k[0],) in seen)
    assert record.rows == n_seen and all(y[k] == "false" for k in y if (k[0],) in seen)
    assert record.leaf.probs[0] == pytest.approx(1 / (n_seen + 2), rel=1e-12)
    # Not seen: the logistic, P(true) = sigmoid(w d + b), against statsmodels on the same rows.
    record = _leaf(logistic_run.target, "d(Obj, Obj1):t ~= D", r"\+ observed(Obj):t+1")
    keys = [k for k in y if (k[0],) not in seen]
    assert record.rows == len(keys) and record.regressors
    x = np.array([d[k] for k in keys])
    t = np.array([y[k] == "true" for k in keys], dtype=float)
    fit = sm.Logit(t, sm.add_constant(x)).fit(disp=0)
    (b_mle, w_mle), (b_se, w_se) = fit.params, fit.bse
    w, b = record.leaf.weights
    assert abs(w - w_mle) < 0.1 * w_se and abs(b - b_mle) < 0.1 * b_se, (w, b, w_mle, b_mle)
    _within(w, LOGISTIC_W, w_se, "w")
    _within(b, LOGISTIC_B, b_se, "b")


def test_logistic_heldout(logistic_run: Run) -> None:
    _assert_heldout(logistic_run)


def test_evaluate_reads_the_engine_sugar(tmp_path: Path) -> None:
    """evaluate with no targets scores every target of the generator with facts, d:t too."""
    test = tmp_path / "test.pl"
    test.write_text(sample_data(DATA / "logistic.pl", LOGISTIC_FACTS, 200, seed=3,
                                bias=LOGISTIC_BIAS, names=PAIRS))
    scores = evaluate(DATA / "logistic.pl", [test])
    assert scores["d:t"]["mean_log_likelihood"] == pytest.approx(-math.log(0.3), rel=1e-9)


# ----------------------------------------------------------------------------- (c) linear-Gaussian

LINEAR_W, LINEAR_B, LINEAR_VAR = 2.0, 0.5, 0.04
LINEAR_BIAS = """
type(x(ent)).  type(z(ent)).  type(y(ent)).
rv(x(_), continuous).
rv(z(_), discrete([u, v])).
rv(y(_), continuous).
mode(y(_), x(+)).
mode(y(_), z(+)).
learn(y(_)).
"""


@pytest.fixture(scope="module")
def linear_run(tmp_path_factory: pytest.TempPathFactory) -> Run:
    return _run(tmp_path_factory.mktemp("linear"), "linear_gaussian.pl",
                ["x(I) ~= X", "z(I) ~= Z", "y(I) ~= Y"], LINEAR_BIAS, "y",
                n_train=20_000, n_test=10_000)


def test_linear_structure(linear_run: Run) -> None:
    assert _structure(linear_run.target) == [(("x(Ent)~=X",), "linear_gaussian")]


def _ols_check(record, x: np.ndarray, y: np.ndarray, w0: float, b0: float, var0: float) -> None:
    """The learned linear-Gaussian leaf against OLS on the same rows and the generator."""
    fit = sm.OLS(y, sm.add_constant(x)).fit()
    (b_mle, w_mle), (b_se, w_se) = fit.params, fit.bse
    w, b = record.leaf.weights
    assert w == pytest.approx(w_mle, abs=1e-6 * w_se) and b == pytest.approx(b_mle, abs=1e-6 * b_se)
    var = record.leaf.variance
    assert var == pytest.approx(np.mean(fit.resid ** 2), rel=1e-9)  # the ML variance
    _within(w, w0, w_se, "w")
    _within(b, b0, b_se, "b")
    _within(var, var0, var0 * math.sqrt(2 / len(y)), "variance")


def test_linear_parameters(linear_run: Run) -> None:
    x, y = linear_run.train["x"], linear_run.train["y"]
    record = _leaf(linear_run.target, "x(Ent) ~= X")
    keys = sorted(y)
    assert record.rows == len(keys) == linear_run.n_train and record.regressors
    _ols_check(record, np.array([x[k] for k in keys]), np.array([y[k] for k in keys]),
               LINEAR_W, LINEAR_B, LINEAR_VAR)


def test_linear_heldout(linear_run: Run) -> None:
    _assert_heldout(linear_run)


# ----------------------------------------------------------------------------- (d) relational

RELATIONAL_W, RELATIONAL_B, RELATIONAL_VAR = 1.5, 0.2, 0.25
RELATIONAL_BIAS = """
type(link(ent, nb)).  type(v(nb)).  type(w(nb)).  type(y(ent)).
rv(v(_), continuous).
rv(w(_), continuous).
rv(y(_), continuous).
mode(y(_), mean, (link(+, -), v(+))).
mode(y(_), mean, (link(+, -), w(+))).
mode(y(_), max, (link(+, -), v(+))).
mode(y(_), count, link(+, -)).
mode(y(_), link(+, -)).
mode(y(_), v(+)).
learn(y(_)).
"""


@pytest.fixture(scope="module")
def relational_run(tmp_path_factory: pytest.TempPathFactory) -> Run:
    return _run(tmp_path_factory.mktemp("relational"), "relational_mean.pl",
                ["y(I) ~= Y", "link(I, J)", ("v(J) ~= V", "link(I, J)"),
                 ("w(J) ~= W", "link(I, J)")], RELATIONAL_BIAS, "y",
                n_train=5_000, n_test=5_000)


MEAN_V = "(findall_forward(V, (link(Ent, Nb), v(Nb) ~= V), L), mean_list(L, MeanV))"


def test_relational_structure(relational_run: Run) -> None:
    # Every entity has a neighbour: the branch where the mean is undefined is empty.
    assert _structure(relational_run.target) == [((_norm(MEAN_V),), "linear_gaussian")]


def test_relational_parameters(relational_run: Run) -> None:
    link, v, y = (relational_run.train[p] for p in ("link", "v", "y"))
    neighbours: dict[str, list[str]] = defaultdict(list)
    for entity, nb in link:
        neighbours[entity].append(nb)
    keys = sorted(y)
    assert {len(neighbours[k[0]]) for k in keys} == {1, 2, 3, 4, 5}
    m = np.array([np.mean([v[(nb,)] for nb in neighbours[k[0]]]) for k in keys])
    record = _leaf(relational_run.target, MEAN_V)
    assert record.rows == len(keys) == relational_run.n_train and record.regressors
    _ols_check(record, m, np.array([y[k] for k in keys]),
               RELATIONAL_W, RELATIONAL_B, RELATIONAL_VAR)


def test_relational_heldout(relational_run: Run) -> None:
    _assert_heldout(relational_run)
