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
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from bridge.learning import Child, LearningData, Outcome
from probanchor.ddclearn.leaves import Leaf, LeafOptions, fit_leaf
from probanchor.ddclearn.tree import Branch, Tree, TreeNode

__all__ = ["LeafRecord", "SearchOptions", "TargetResult", "learn_target"]


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
    leaf : LeafOptions
        The leaf models' settings (smoothing, L2 penalty, variance floor).
    """

    min_leaf: float = 10.0
    max_depth: int = 8
    min_gain: float = 0.0
    lookahead: bool = True
    leaf: LeafOptions = field(default_factory=LeafOptions)

    def __post_init__(self) -> None:
        if not (math.isfinite(self.min_leaf) and self.min_leaf >= 1):
            raise ValueError(f"min_leaf must be >= 1, got {self.min_leaf!r}")
        if not (isinstance(self.max_depth, int) and self.max_depth >= 0):
            raise ValueError(f"max_depth must be an integer >= 0, got {self.max_depth!r}")
        if not math.isfinite(self.min_gain):
            raise ValueError(f"min_gain must be finite, got {self.min_gain!r}")


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

    # -- leaves
    def fit(self, y: np.ndarray, w: np.ndarray, X: np.ndarray) -> Leaf:
        return fit_leaf(self.kind, y, w, X, log_n=self.log_n, n_classes=self.n_classes,  # type: ignore[arg-type]
                        options=self.options.leaf)

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

    def grow(self, nd: _Node, leaves: list[LeafRecord], relaxed: bool = False) -> TreeNode:
        self.tick()
        leaf = self.node_leaf(nd)
        split = None
        if nd.depth < self.options.max_depth and nd.weight >= 2 * self.options.min_leaf:
            split = self.best_split(nd, lookahead=True)
        accept = split is not None and (split.gain > self.options.min_gain
                                        or (relaxed and split.gain >= 0))
        if not accept:
            return self.make_leaf(nd, leaf, leaves, inherited=False)
        assert split is not None
        cand = split.candidate
        children = self.data.split(nd.node, cand["id"])
        step = nd.depth
        tree = TreeNode(rows=len(nd.y), weight=nd.weight, test=_test_text(cand))
        for ch in children:
            c_nd = self.child(nd, ch, cand, step)
            label = str(cand["labels"][ch.branch])
            if c_nd.weight < self.options.min_leaf:
                c_nd.leaf, c_nd.leaf_cols = leaf, nd.leaf_cols
                c_nd.reg_steps = c_nd.reg_steps[:nd.leaf_cols] if leaf.uses_regressors else []
                sub = self.make_leaf(c_nd, leaf, leaves, inherited=True,
                                     steps=nd.reg_steps[:nd.leaf_cols])
            else:
                sub = self.grow(c_nd, leaves, relaxed=split.lookahead and ch.branch == 0)
            tree.branches.append(Branch(label=label, child=sub))
        self.data.forget([nd.node])
        return tree

    def make_leaf(self, nd: _Node, leaf: Leaf, leaves: list[LeafRecord], inherited: bool,
                  steps: list[int] | None = None) -> TreeNode:
        if steps is None:
            steps = nd.reg_steps[:nd.leaf_cols] if leaf.uses_regressors else []
        cols = len(steps)
        ll = leaf.log_likelihood
        if inherited:
            ll = float(np.dot(nd.w, leaf.log_prob(nd.y, nd.X[:, :cols]))) if len(nd.y) else 0.0
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
        self.fill_cache(nd, [c for c in cands if _true(c["root"])])
        leaves: list[LeafRecord] = []
        tree_root = self.grow(nd, leaves)
        ll = sum(r.log_likelihood for r in leaves)
        own = {id(r.leaf): r.leaf.n_params for r in leaves}
        return TargetResult(
            name=str(self.target["name"]), predicate=str(self.target["predicate"]),
            kind=self.kind, domain=self.domain, tree=Tree(str(self.target["name"]), tree_root),
            leaves=leaves, groundings=n_rows, examples=int(len(np.unique(root.example))),
            weight=total, log_likelihood=ll, n_params=int(sum(own.values())),
            seconds=time.perf_counter() - start)


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
