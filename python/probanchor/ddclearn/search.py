"""Top-down induction of one distributional logic tree per target (paper, section 4).

The search owns the choices; :class:`bridge.learning.LearningData` answers the questions about
the data (the groundings of a node, the literals the bias allows, their outcomes) and turns the
leaves into DC clauses; :mod:`probanchor.ddclearn.leaves` fits the statistical models.

At a node with rows ``i`` (groundings of the head, weighted by ``w_i``; several partial worlds
of one example are several rows), target values ``y_i`` and the path's regressors ``x_i``, the
node's own model is a leaf fitted on them. Each candidate literal splits the rows into its
branches; each branch gets its own leaf when its weight is at least ``min_leaf``, else it keeps
the node's model (and so adds no parameters). The gain of the split, in the units of the BIC
``2 log L - k ln N`` (N the target's examples), is::

    gain = 2 * (sum_b LL_b - LL_node) - (sum_b k_b + k_node [if a branch inherits] - k_node) * ln N

The best candidate is added when its gain exceeds ``min_gain`` (default 0: the BIC must
improve), and the search recurses into each branch, to ``max_depth`` at most. A literal that
introduces new variables (``r(X, Y)``, Y new) adds nothing by itself: its positive branch is
scored by the best literal that could follow it there (a lookahead of one literal, as in
DreaML), and when it is chosen that follow-up needs only a gain of at least 0.

Every branch of a split becomes a clause, so the clauses of a tree cover every grounding and
are mutually exclusive (DC's requirement); DreaML instead dropped small branches and appended a
catch-all clause that relies on first-match semantics.

A target may have a *root model* (:mod:`probanchor.ddclearn.root_model`): a regression over every
feature the bias allows at the root. When the tree reads it, every node starts with its scores as
regressors, which the leaves take as an offset (``leaves.fit_offset_leaf``). Whether the tree
reads it is decided on held-out blocks of examples (:meth:`_TargetSearch.choose`): a tree is
grown on the other blocks without and with it, both score the block (:meth:`_TargetSearch.replay`
takes other rows down a grown tree), and the one with the higher held-out log-likelihood wins.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from bridge.learning import Child, LearningData, Outcome, Root
from probanchor.ddclearn.leaves import Leaf, LeafOptions, fit_leaf
from probanchor.ddclearn.root_model import (
    RootFeatures,
    RootModel,
    block_of,
    fit_root_model,
    root_features,
)
from probanchor.ddclearn.tree import Branch, Tree, TreeNode

__all__ = ["LeafRecord", "SearchOptions", "TargetResult", "learn_target"]


#: The values of ``SearchOptions.root_model``.
ROOT_MODEL_USES: tuple[str, ...] = ("auto", "always", "never")


@dataclass(frozen=True)
class SearchOptions:
    """Settings of the tree search.

    Parameters
    ----------
    min_leaf : float, default=10.0
        Smallest total weight (groundings) of a branch that gets a model of its own; a smaller
        branch keeps its parent's model.
    max_depth : int, default=8
        Most literals on a path from the root to a leaf.
    min_gain : float, default=0.0
        A split is added when its gain (BIC units, ``2 log L - k ln N``) exceeds this.
    lookahead : bool, default=True
        Score a literal that introduces new variables by the best literal that could follow it.
    root_model : {"auto", "always", "never"}, default="auto"
        Whether the tree reads the target's root model (:mod:`probanchor.ddclearn.root_model`:
        a regression over every feature the bias allows at the root) whose scores every node
        then starts with (an offset of its leaves' models). ``"auto"``: when the root model
        predicts better than no features in cross-validation and the tree grown with it
        predicts held-out examples better than the tree grown without it, by more than one
        standard error (``HOLDOUT``-fold cross-validation of the search); ``"always"``: when
        the root model predicts better than no features; ``"never"``: the tree alone.
    leaf : LeafOptions
        The leaf models' settings (smoothing, L2 penalty, variance floor).
    """

    min_leaf: float = 10.0
    max_depth: int = 8
    min_gain: float = 0.0
    lookahead: bool = True
    root_model: str = "auto"
    leaf: LeafOptions = field(default_factory=LeafOptions)

    def __post_init__(self) -> None:
        if not (math.isfinite(self.min_leaf) and self.min_leaf >= 1):
            raise ValueError(f"min_leaf must be >= 1, got {self.min_leaf!r}")
        if not (isinstance(self.max_depth, int) and self.max_depth >= 0):
            raise ValueError(f"max_depth must be an integer >= 0, got {self.max_depth!r}")
        if not math.isfinite(self.min_gain):
            raise ValueError(f"min_gain must be finite, got {self.min_gain!r}")
        if self.root_model not in ROOT_MODEL_USES:
            raise ValueError(f"root_model must be one of {ROOT_MODEL_USES}, got "
                             f"{self.root_model!r}")


@dataclass
class LeafRecord:
    """A leaf of a learned tree: its clause and what it was fitted on."""

    node: int
    leaf: Leaf
    regressors: list[int]
    rows: int
    weight: float
    log_likelihood: float
    inherited: bool
    clause: str = ""
    distribution: str = ""
    model: str = ""
    model_term: str = ""


@dataclass
class TargetResult:
    """The tree learned for one target and its figures."""

    name: str
    predicate: str
    kind: str
    domain: list[str]
    tree: Tree
    leaves: list[LeafRecord]
    groundings: int
    examples: int
    weight: float
    log_likelihood: float
    n_params: int
    seconds: float
    #: The whole tree as one clause of nested if-then-else goals (the tree form), or None if
    #: its leaves' distributions are not of one family.
    tree_clause: str | None = None
    #: The root model whose scores the leaves read (None: no leaf reads one).
    root_model: RootModel | None = None
    #: How the use of a root model was decided (None: no root model was fitted).
    choice: RootChoice | None = None

    @property
    def clauses(self) -> int:
        return len(self.leaves)

    @property
    def mean_log_likelihood(self) -> float:
        return self.log_likelihood / self.weight if self.weight > 0 else math.nan

    def bic(self) -> float:
        return 2 * self.log_likelihood - self.n_params * math.log(max(self.weight, 1.0))


@dataclass
class _Node:
    """A node of the tree being grown: its rows (aligned with the Prolog node's rows)."""

    node: int
    root_row: np.ndarray
    y: np.ndarray
    w: np.ndarray
    X: np.ndarray
    reg_steps: list[int]
    depth: int
    leaf: Leaf | None = None
    leaf_cols: int = 0

    @property
    def weight(self) -> float:
        return float(self.w.sum())


@dataclass
class _Grown:
    """A node of a grown tree, before its leaves' models are chosen and written."""

    nd: _Node
    leaf: Leaf
    steps: list[int]
    candidate: dict | None = None
    branches: list[tuple[str, _Grown]] = field(default_factory=list)
    inherited: bool = False


def _nodes(g: _Grown) -> list[int]:
    """The Prolog nodes of a grown tree."""
    return [g.nd.node] + [n for _, c in g.branches for n in _nodes(c)]


def _n_params(g: _Grown) -> int:
    """The parameters of a grown tree's own leaves (an inherited leaf adds none)."""
    if g.inherited:
        return 0
    if not g.branches:
        return g.leaf.n_params
    return sum(_n_params(c) for _, c in g.branches)


def _reads_scores(g: _Grown) -> bool:
    """Whether a leaf of a grown tree gives a root model's score a weight."""
    if not g.branches:
        return g.leaf.uses_regressors and any(s < 0 for s in _clause_columns(g.leaf, g.steps)[1])
    return any(_reads_scores(c) for _, c in g.branches)


def _scores(X: np.ndarray, model: RootModel) -> np.ndarray:
    """The root model's scores of feature rows X (its fit on every training row)."""
    W = np.asarray(model.rows, dtype=float)
    return X @ W[:, :-1].T + W[:, -1]


#: Folds of the examples for the decision to use a root model (each held out in turn).
HOLDOUT: int = 3
#: Standard errors of the held-out difference that decide without the remaining folds.
DECISIVE: float = 4.0


@dataclass(frozen=True)
class RootChoice:
    """The held-out comparison of the trees with and without the root model.

    ``offsets``: the root model is used; ``gain``: the held-out log-likelihood of the tree with
    it minus the tree's without it (nats, summed over ``rows`` held-out rows); ``se``: the
    standard error of that difference; ``params_tree``, ``params_root_model``: the trees'
    numbers of parameters (mean over the held-out blocks; the second counts the root model's
    when a leaf reads it).
    """

    offsets: bool
    gain: float
    se: float
    rows: int
    params_tree: float = 0.0
    params_root_model: float = 0.0


@dataclass
class _Split:
    candidate: dict
    gain: float
    lookahead: bool = False


@dataclass
class _RootCache:
    """Outcomes of candidates that read only the head's variables, per root row."""

    branch: np.ndarray
    x: np.ndarray
    pure: np.ndarray


class _TargetSearch:
    def __init__(self, data: LearningData, target: dict, options: SearchOptions,
                 tick: Callable[[], None] | None) -> None:
        self.data = data
        self.target = target
        self.options = options
        self.tick = tick or (lambda: None)
        self.kind: str = str(target["kind"])
        self.domain = [str(v) for v in target.get("domain", [])]
        self.n_classes = len(self.domain) if self.kind == "discrete" else None
        self.cache: dict[int, _RootCache] = {}
        self.step = 0
        self.log_n = 0.0
        #: The leading regressors of every node that are the root model's scores.
        self.offsets = 0

    # -- leaves
    def fit(self, y: np.ndarray, w: np.ndarray, X: np.ndarray) -> Leaf:
        return fit_leaf(self.kind, y, w, X, log_n=self.log_n, n_classes=self.n_classes,  # type: ignore[arg-type]
                        options=self.options.leaf, offsets=self.offsets)

    def node_leaf(self, nd: _Node) -> Leaf:
        if nd.leaf is None:
            nd.leaf = self.fit(nd.y, nd.w, nd.X)
            nd.leaf_cols = nd.X.shape[1] if nd.leaf.uses_regressors else 0
        return nd.leaf

    # -- outcomes
    def outcomes(self, nd: _Node, cands: list[dict]) -> list[Outcome]:
        out: dict[int, Outcome] = {}
        direct = []
        for c in cands:
            cached = self.cache.get(c["id"]) if _true(c["root"]) else None
            if cached is None:
                direct.append(c["id"])
                continue
            r = nd.root_row
            ok = cached.pure[r]
            idx = np.flatnonzero(ok)
            o = Outcome(row=idx, branch=cached.branch[r[idx]], factor=np.ones(len(idx)),
                        x=cached.x[r[idx]], pure=np.ones(len(idx), dtype=bool))
            if not ok.all():
                extra = self.data.evaluate_rows(nd.node, c["id"], np.flatnonzero(~ok).tolist())
                o = _concat(o, extra)
            out[c["id"]] = o
        for cid, o in zip(direct, self.data.evaluate(nd.node, direct), strict=True):
            out[cid] = o
        return [out[c["id"]] for c in cands]

    def fill_cache(self, nd: _Node, cands: list[dict]) -> None:
        n = len(nd.y)
        for c, o in zip(cands, self.data.evaluate(nd.node, [c["id"] for c in cands]),
                        strict=True):
            counts = np.bincount(o.row, minlength=n)
            single = (counts == 1)[o.row] & o.pure
            branch = np.full(n, -1, dtype=np.int64)
            x = np.full(n, np.nan)
            pure = np.zeros(n, dtype=bool)
            branch[o.row[single]] = o.branch[single]
            x[o.row[single]] = o.x[single]
            pure[o.row[single]] = True
            self.cache[c["id"]] = _RootCache(branch, x, pure)

    # -- scoring
    def score(self, nd: _Node, cand: dict, o: Outcome) -> float:
        """The gain of splitting ``nd`` by ``cand`` (see the module docstring)."""
        parent = self.node_leaf(nd)
        ll = 0.0
        k = 0
        inherits = False
        nonempty = 0
        for b in range(int(cand["branches"])):
            sel = o.branch == b
            if not sel.any():
                continue
            nonempty += 1
            rows = o.row[sel]
            w = nd.w[rows] * o.factor[sel]
            y = nd.y[rows]
            if w.sum() >= self.options.min_leaf:
                X = nd.X[rows]
                if _true(cand["regressor"][b]):
                    X = np.column_stack([X, o.x[sel]])
                leaf = self.fit(y, w, X)
                ll += leaf.log_likelihood
                k += leaf.n_params
            else:
                inherits = True
                ll += float(np.dot(w, parent.log_prob(y, nd.X[rows][:, :nd.leaf_cols])))
        if nonempty <= 1 and not any(_true(r) for r in cand["regressor"]):
            return -math.inf
        if inherits:
            k += parent.n_params
        return 2 * (ll - parent.log_likelihood) - (k - parent.n_params) * self.log_n

    def best_split(self, nd: _Node, lookahead: bool) -> _Split | None:
        cands = self.data.candidates(nd.node)
        if not cands:
            return None
        best: _Split | None = None
        for c, o in zip(cands, self.outcomes(nd, cands), strict=True):
            if _true(c["fresh"]) and lookahead and self.options.lookahead:
                gain = self.lookahead_score(nd, c)
                split = _Split(c, gain, lookahead=True)
            else:
                split = _Split(c, self.score(nd, c, o))
            if best is None or split.gain > best.gain:
                best = split
        return best

    def lookahead_score(self, nd: _Node, cand: dict) -> float:
        """A literal with new variables: its positive branch scored by its best follow-up."""
        children = self.data.split(nd.node, cand["id"])
        try:
            parent = self.node_leaf(nd)
            total = 0.0
            for ch in children:
                c_nd = self.child(nd, ch, cand, step=-1)
                if c_nd.weight < self.options.min_leaf:
                    if len(c_nd.y):
                        total += 2 * float(np.dot(c_nd.w, parent.log_prob(
                            c_nd.y, c_nd.X[:, :nd.leaf_cols])))
                    continue
                leaf = self.node_leaf(c_nd)
                part = 2 * leaf.log_likelihood - leaf.n_params * self.log_n
                if ch.branch == 0 and c_nd.weight >= 2 * self.options.min_leaf:
                    follow = self.best_split(c_nd, lookahead=False)
                    if follow is not None and follow.gain > 0:
                        part += follow.gain
                total += part
            return total - (2 * parent.log_likelihood - parent.n_params * self.log_n)
        finally:
            self.data.forget([ch.node for ch in children])

    # -- growing
    def child(self, nd: _Node, ch: Child, cand: dict, step: int) -> _Node:
        X = nd.X[ch.row]
        steps = list(nd.reg_steps)
        if _true(cand["regressor"][ch.branch]):
            X = np.column_stack([X, ch.x])
            steps.append(step)
        return _Node(node=ch.node, root_row=nd.root_row[ch.row], y=nd.y[ch.row],
                     w=nd.w[ch.row] * ch.factor, X=X, reg_steps=steps, depth=nd.depth + 1)

    def grow(self, nd: _Node, relaxed: bool = False) -> _Grown:
        """Grow the tree below ``nd``: each node's best split while it gains (module docstring)."""
        self.tick()
        leaf = self.node_leaf(nd)
        steps = nd.reg_steps[:nd.leaf_cols] if leaf.uses_regressors else []
        split = None
        if nd.depth < self.options.max_depth and nd.weight >= 2 * self.options.min_leaf:
            split = self.best_split(nd, lookahead=True)
        accept = split is not None and (split.gain > self.options.min_gain
                                        or (relaxed and split.gain >= 0))
        if not accept:
            return _Grown(nd, leaf, steps)
        assert split is not None
        cand = split.candidate
        children = self.data.split(nd.node, cand["id"])
        g = _Grown(nd, leaf, steps, candidate=cand)
        for ch in children:
            c_nd = self.child(nd, ch, cand, nd.depth)
            if c_nd.weight < self.options.min_leaf:
                c_nd.leaf, c_nd.leaf_cols = leaf, nd.leaf_cols
                c_nd.reg_steps = c_nd.reg_steps[:nd.leaf_cols] if leaf.uses_regressors else []
                sub = _Grown(c_nd, leaf, steps, inherited=True)
            else:
                sub = self.grow(c_nd, relaxed=split.lookahead and ch.branch == 0)
            g.branches.append((str(cand["labels"][ch.branch]), sub))
        self.data.forget_rows(nd.node)
        return g

    def finish(self, g: _Grown, leaves: list[LeafRecord]) -> TreeNode:
        """The tree's nodes, its leaves' clauses written (in ``leaves``, left to right)."""
        if g.inherited or not g.branches:
            return self.make_leaf(g.nd, g.leaf, g.steps, leaves, inherited=g.inherited)
        assert g.candidate is not None
        tree = TreeNode(rows=len(g.nd.y), weight=g.nd.weight, test=_test_text(g.candidate))
        for label, c in g.branches:
            tree.branches.append(Branch(label=label, child=self.finish(c, leaves)))
        self.data.forget([g.nd.node])
        return tree

    def replay(self, g: _Grown, nd: _Node) -> np.ndarray:
        """Each row of ``nd`` (other data) scored by the tree ``g``: weighted log-likelihood.

        The rows take the tree's splits (the same candidates, their branches' values as
        regressors) down to a leaf, whose model gives their log-likelihood. The nodes made on
        the way are forgotten.
        """
        if len(nd.y) == 0:
            return np.zeros(0)
        if g.inherited or not g.branches:
            return nd.w * g.leaf.log_prob(nd.y, nd.X[:, :len(g.steps)])
        assert g.candidate is not None
        out = np.zeros(len(nd.y))
        children = self.data.split(nd.node, g.candidate["id"])
        try:
            for ch, (_, sub) in zip(children, g.branches, strict=True):
                c_nd = self.child(nd, ch, g.candidate, nd.depth)
                out += np.bincount(ch.row, weights=self.replay(sub, c_nd), minlength=len(nd.y))
        finally:
            self.data.forget([ch.node for ch in children])
        return out

    def make_leaf(self, nd: _Node, leaf: Leaf, steps: list[int], leaves: list[LeafRecord],
                  inherited: bool) -> TreeNode:
        cols = len(steps)
        ll = leaf.log_likelihood
        if inherited:
            ll = float(np.dot(nd.w, leaf.log_prob(nd.y, nd.X[:, :cols]))) if len(nd.y) else 0.0
        leaf, steps = _clause_columns(leaf, steps)
        term = model_term(leaf, self.domain)
        texts = self.data.leaf_clause(nd.node, term, steps)
        rec = LeafRecord(node=nd.node, leaf=leaf, regressors=steps, rows=len(nd.y),
                         weight=nd.weight, log_likelihood=ll, inherited=inherited,
                         clause=texts["clause"], distribution=texts["distribution"],
                         model=texts["model"], model_term=term)
        leaves.append(rec)
        return TreeNode(rows=len(nd.y), weight=nd.weight, distribution=rec.distribution,
                        model=rec.model or None, log_likelihood=ll, inherited=inherited)

    def run(self) -> TargetResult:
        start = time.perf_counter()
        root = self.data.root(str(self.target["predicate"]))
        n_rows = len(root.y)
        total = float(root.weight.sum())
        self.log_n = math.log(max(total, 1.0))
        nd = _Node(node=root.node, root_row=np.arange(n_rows), y=root.y, w=root.weight,
                   X=np.zeros((n_rows, 0)), reg_steps=[], depth=0)
        cands = self.data.candidates(root.node)
        roots = [c for c in cands if _true(c["root"])]
        self.fill_cache(nd, roots)
        model, choice = None, None
        if self.options.root_model != "never" and roots:
            feats = root_features(roots, [self.cache[c["id"]].branch for c in roots],
                                  [self.cache[c["id"]].x for c in roots], root.weight)
            model = self.root_model(feats, root, np.ones(n_rows, dtype=bool))
            if model is not None and self.options.root_model == "auto":
                choice = self.choose(root, feats)
                if not choice.offsets:
                    model = None
        if model is not None:
            self.offsets = model.n_scores
            nd.X = model.scores
            nd.reg_steps = [-1 - j for j in range(model.n_scores)]
            self.data.set_root_model(str(self.target["predicate"]), model.term())
        leaves: list[LeafRecord] = []
        tree_root = self.finish(self.grow(nd), leaves)
        ll = sum(r.log_likelihood for r in leaves)
        own = {id(r.leaf): r.leaf.n_params for r in leaves}
        if model is not None and any(s < 0 for r in leaves for s in r.regressors):
            own[0] = model.n_scores * (len(model.features) + 1)
        else:
            model = None
        return TargetResult(
            name=str(self.target["name"]), predicate=str(self.target["predicate"]),
            kind=self.kind, domain=self.domain, tree=Tree(str(self.target["name"]), tree_root),
            leaves=leaves, groundings=n_rows, examples=int(len(np.unique(root.example))),
            weight=total, log_likelihood=ll, n_params=int(sum(own.values())),
            seconds=time.perf_counter() - start, root_model=model, choice=choice)

    def root_model(self, feats: RootFeatures, root: Root, rows: np.ndarray) -> RootModel | None:
        """The root model fitted on some root rows (a mask), or None (see fit_root_model)."""
        y = root.y.astype(np.int64) if self.kind == "discrete" else root.y.astype(float)
        return fit_root_model(self.kind, y[rows], root.weight[rows].astype(float),
                              root.example[rows], RootFeatures(feats.X[rows], feats.features),
                              n_classes=self.n_classes, smoothing=self.options.leaf.smoothing)

    def choose(self, root: Root, feats: RootFeatures) -> RootChoice:
        """Whether the tree should read the root model's scores: decided on held-out examples.

        The examples are cut into ``HOLDOUT`` blocks of consecutive examples, in the order of
        the data (:func:`probanchor.ddclearn.root_model.block_of`); for each block, the tree is
        grown on the other blocks twice, without the root model and with it (its scores those
        of the root model fitted on those examples, cross-fitted), and both trees score the
        block's rows. Data are written world by world (an episode's frames, a district's loans,
        one interpretation after another): a block holds worlds the trees have not seen, as
        held-out data do, where examples drawn at random would share their worlds (and what a
        tree learned of them) with the training rows. The tree with the higher held-out
        log-likelihood, summed over the rows, wins (the tree alone on a tie: then the other
        reads no score). Even so the blocks of one world share entities (a university's courses,
        whose attributes a tree can learn by heart): on a new world the root model's advantage
        was larger than in these blocks, on every generated university tried, so a small
        advantage is not discounted. Once the difference is larger than ``DECISIVE`` standard
        errors either way, the remaining blocks are not needed (a large data set usually
        decides on one).
        """
        fold = block_of(root.example, HOLDOUT)
        saved = self.log_n
        plain = np.zeros(len(root.y))
        with_model = np.zeros(len(root.y))
        scored = np.zeros(len(root.y), dtype=bool)
        gain, se = 0.0, 0.0
        k_plain: list[int] = []
        k_model: list[int] = []
        try:
            for k in range(HOLDOUT):
                test = fold == k
                train = ~test
                tr_rows, te_rows = np.flatnonzero(train), np.flatnonzero(test)
                model = self.root_model(feats, root, train)
                if model is None:
                    return RootChoice(False, 0.0, 0.0, 0, 0.0, 0.0)
                self.log_n = math.log(max(float(root.weight[train].sum()), 1.0))
                plain[te_rows], kp = self.held_out(root, tr_rows, te_rows, None)
                with_model[te_rows], km = self.held_out(
                    root, tr_rows, te_rows, (model, _scores(feats.X[te_rows], model)))
                k_plain.append(kp)
                k_model.append(km)
                scored |= test
                d = (with_model - plain)[scored & (root.weight > 0)]
                gain = float(d.sum())
                se = math.sqrt(len(d) * float(np.var(d))) if len(d) else 0.0
                if abs(gain) > DECISIVE * se:
                    break
        finally:
            self.log_n = saved
            self.offsets = 0
        return RootChoice(gain > 0, gain, se, int((scored & (root.weight > 0)).sum()),
                          float(np.mean(k_plain)), float(np.mean(k_model)))

    def held_out(self, root: Root, tr_rows: np.ndarray, te_rows: np.ndarray,
                 model: tuple[RootModel, np.ndarray] | None) -> tuple[np.ndarray, int]:
        """A tree grown on the training rows, scored on the test rows (weighted per row), and
        its number of parameters (with the root model's when a leaf reads its scores)."""
        tr_node = self.data.subset(root.node, tr_rows.tolist())
        te_node = self.data.subset(root.node, te_rows.tolist())

        def node(n: int, rows: np.ndarray, X: np.ndarray) -> _Node:
            return _Node(node=n, root_row=rows, y=root.y[rows], w=root.weight[rows], X=X,
                         reg_steps=[-1 - j for j in range(X.shape[1])], depth=0)

        if model is None:
            self.offsets = 0
            tr_X, te_X = np.zeros((len(tr_rows), 0)), np.zeros((len(te_rows), 0))
        else:
            self.offsets = model[0].n_scores
            tr_X, te_X = model[0].scores, model[1]
        g = self.grow(node(tr_node, tr_rows, tr_X))
        try:
            k = _n_params(g)
            if model is not None and _reads_scores(g):
                k += model[0].n_scores * (len(model[0].features) + 1)
            return self.replay(g, node(te_node, te_rows, te_X)), k
        finally:
            self.data.forget([te_node, *_nodes(g)])


def learn_target(data: LearningData, target: dict, options: SearchOptions | None = None,
                 tick: Callable[[], None] | None = None) -> TargetResult:
    """Learn the tree of one target (a dict of :meth:`LearningData.targets`).

    Parameters
    ----------
    data : LearningData
        The data, read once for every target.
    target : dict
        The target, as :meth:`LearningData.targets` describes it.
    options : SearchOptions, optional
        The search's settings.
    tick : callable, optional
        Called once per node visited (a progress bar).

    Returns
    -------
    TargetResult
        The tree, its leaves with their clauses, and its figures.
    """
    return _TargetSearch(data, target, options or SearchOptions(), tick).run()


def _true(v: object) -> bool:
    return v is True or v == "true"


def _concat(a: Outcome, b: Outcome) -> Outcome:
    return Outcome(row=np.concatenate([a.row, b.row]), branch=np.concatenate([a.branch, b.branch]),
                   factor=np.concatenate([a.factor, b.factor]), x=np.concatenate([a.x, b.x]),
                   pure=np.concatenate([a.pure, b.pure]))


def _clause_columns(leaf: Leaf, steps: list[int]) -> tuple[Leaf, list[int]]:
    """A leaf and its regressors without the root model's scores it gives weight 0.

    A regression leaf on the path's values only, in a tree that reads a root model, has
    weight 0 on the scores (:func:`probanchor.ddclearn.leaves.fit_leaf`): its clause need not
    compute them.
    """
    if not leaf.uses_regressors or not any(s < 0 for s in steps):
        return leaf, steps
    rows = ([list(r) for r in leaf.weight_rows] if leaf.weight_rows is not None
            else [list(leaf.weights or ())])
    keep = [j for j, s in enumerate(steps) if s >= 0 or any(r[j] != 0.0 for r in rows)]
    if len(keep) == len(steps):
        return leaf, steps
    cut = [tuple([r[j] for j in keep] + [r[-1]]) for r in rows]
    if leaf.weight_rows is not None:
        return replace(leaf, weight_rows=tuple(cut)), [steps[j] for j in keep]
    return replace(leaf, weights=cut[0]), [steps[j] for j in keep]


def _test_text(cand: dict) -> str:
    labels = [str(s) for s in cand["labels"]]
    if cand["kind"] in ("discrete", "numeric", "threshold"):
        last = labels[-1]
        return last[3:] if last.startswith("\\+ ") else last
    return labels[0]


# -- model terms -------------------------------------------------------------------------------

_DIGITS = 6


def _num(x: float) -> str:
    """A parameter with 6 significant digits, as Prolog reads it."""
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"a learned parameter is not finite: {x!r}")
    text = repr(float(f"{x:.{_DIGITS}g}"))
    return text


def _probs(ps: np.ndarray) -> str:
    """Probabilities rounded to 6 significant digits that still sum to exactly 1.

    The largest is 1 minus the sum of the others, computed in decimal, so that
    ``dist_check/1`` (sum 1 within 1e-9) accepts what is printed.
    """
    from decimal import Decimal

    ps = np.asarray(ps, dtype=float)
    big = int(np.argmax(ps))
    texts = [f"{p:.{_DIGITS}g}" for p in ps]
    rest = sum((Decimal(t) for i, t in enumerate(texts) if i != big), Decimal(0))
    texts[big] = format(Decimal(1) - rest, "f")
    return "[" + ", ".join(repr(float(t)) if i != big else _trim(texts[big])
                           for i, t in enumerate(texts)) + "]"


def _trim(t: str) -> str:
    if "." in t:
        t = t.rstrip("0")
        if t.endswith("."):
            t += "0"
    return t


def _list(xs) -> str:
    return "[" + ", ".join(_num(x) for x in xs) + "]"


def model_term(leaf: Leaf, domain: list[str]) -> str:
    """The Prolog text of a leaf's model for ``learn_clause/5`` (parameters rounded)."""
    f = leaf.family
    if f == "finite":
        return f"finite({_probs(np.asarray(leaf.probs))})"
    if f == "gaussian":
        return f"gaussian({_num(leaf.mean)}, {_num(leaf.variance)})"  # type: ignore[arg-type]
    if f == "linear_gaussian":
        return f"linear_gaussian({_list(leaf.weights)}, {_num(leaf.variance)})"  # type: ignore[arg-type]
    if f == "logistic":
        return f"logistic({_list(leaf.weights)})"  # type: ignore[arg-type]
    if f == "softmax":
        rows = ", ".join(_list(r) for r in leaf.weight_rows)  # type: ignore[union-attr]
        return f"softmax([{rows}])"
    if f == "poisson":
        return f"poisson({_num(leaf.rate)})"  # type: ignore[arg-type]
    if f == "poisson_log_linear":
        return f"poisson_log_linear({_list(leaf.weights)})"  # type: ignore[arg-type]
    raise ValueError(f"unknown leaf family {f!r}")
