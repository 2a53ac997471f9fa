"""The structure learner's data, seen from Python: the only module of the learner that calls Prolog.

``prolog/ddc/learn.pl`` owns the data (facts, background knowledge, declarative bias), the
groundings of each node of a tree, the candidate literals and their outcomes in partial possible
worlds, and the translation of a tree's leaves into DC clauses; the search and the leaf models live
in :mod:`probanchor.ddclearn`. Every call returns plain Python values (dicts, lists, numpy arrays).

Example::

    from bridge.learning import LearningData
    data = LearningData(["data.pl"])
    target = data.targets()[0]                  # {'name': 'occluded_by(A,O):t+1', ...}
    root = data.root(target["predicate"])        # node id, y, weight, example per grounding
    candidates = data.candidates(root.node)

Every call goes through the adapter :mod:`bridge.prolog` to a named predicate of the learner
(``library(ddc/learn)``, ``prolog/ddc/learn/ddc_learn_bridge.pl`` for those whose options come as
a dict), with data as its arguments. Errors of the data (a value outside its declared domain, a
mode naming an unknown predicate, a target without facts, ...) raise
:class:`bridge.errors.LearningDataError`, other errors of the engine their subclass of
:class:`bridge.errors.DDCError`, the message naming file:line and
the cause.
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from bridge import prolog
from bridge.errors import UnknownObjectError
from bridge.prolog import OUT

#: The learner's API (library(ddc/learn)) and its predicates that take dicts of options
LEARNER: Path = prolog.PROLOG_DIR / "ddc/learn.pl"
LEARNER_BRIDGE: Path = prolog.PROLOG_DIR / "ddc/learn/ddc_learn_bridge.pl"

_lock = threading.Lock()


def _call(predicate: str, **arguments: Any) -> dict[str, Any]:
    """Call the learner's ``predicate`` once through :func:`bridge.prolog.call` (one call at a
    time, from any thread)."""
    prolog.ensure_loaded(LEARNER)
    prolog.ensure_loaded(LEARNER_BRIDGE, imports=False)
    with _lock:
        return prolog.call(predicate, **arguments)


def _existing(files: Sequence[str | Path]) -> list[str]:
    """The absolute paths of ``files``; an :class:`~bridge.errors.UnknownObjectError` names
    the first that is not a file."""
    paths = [str(Path(f).resolve()) for f in files]
    for p in paths:
        if not Path(p).is_file():
            raise UnknownObjectError(f"{p}: no such file", "existence_error")
    return paths


@dataclass(frozen=True)
class Root:
    """The root node of a target: one entry per grounding row."""

    node: int
    y: np.ndarray
    weight: np.ndarray
    example: np.ndarray


@dataclass(frozen=True)
class Outcome:
    """A candidate's outcome in the rows of a node (one entry per row and partial world)."""

    row: np.ndarray
    branch: np.ndarray
    factor: np.ndarray
    x: np.ndarray
    pure: np.ndarray


@dataclass(frozen=True)
class Child:
    """A child node made by a split: its rows come from the parent's ``row`` entries."""

    node: int
    branch: int
    row: np.ndarray
    factor: np.ndarray
    x: np.ndarray


def _outcome(d: dict[str, Any]) -> Outcome:
    return Outcome(
        row=np.asarray(d["row"], dtype=np.int64),
        branch=np.asarray(d["branch"], dtype=np.int64),
        factor=np.asarray(d["factor"], dtype=float),
        x=np.asarray(d["x"], dtype=float),
        pure=np.asarray(d["pure"], dtype=bool),
    )


class LearningData:
    """Learning data (facts, background knowledge, bias) read into a Prolog module of its own.

    Parameters
    ----------
    files : sequence of path
        The data files (DC facts and clauses, Prolog clauses, declarative bias; DreaML's
        declarations are read too).
    seed : int, optional
        Seeds the samples of continuous uncertain facts (their partial worlds).
    samples : int, default=20
        Samples per continuous uncertain fact.
    max_worlds : int, default=4096
        Most partial worlds one grounding may split into.
    targets : bool, default=True
        False for data that a program is scored on: no target need be declared or have facts.
    bias : sequence of path, optional
        With ``targets=False``, when no data file has a declaration (test facts only): the
        files whose declarations say how the facts are read (a training file; its facts are
        not read), in their dialect.
    program : path, optional
        With ``targets=False``, when no data file has a declaration and no ``bias`` is given:
        the learned program whose record (``learned_from/4``) gives the dialect and the
        declarations of the data it was learned from.
    """

    def __init__(
        self,
        files: Sequence[str | Path],
        *,
        seed: int | None = None,
        samples: int = 20,
        max_worlds: int = 4096,
        targets: bool = True,
        bias: Sequence[str | Path] | None = None,
        program: str | Path | None = None,
    ) -> None:
        paths = _existing(files)
        options: dict[str, Any] = {
            "samples": int(samples), "max_worlds": int(max_worlds),
            "targets": "true" if targets else "false",
            "bias_files": _existing(bias or []),
            "programs": _existing([] if program is None else [program])}
        if seed is not None:
            options["seed"] = int(seed)
        result = _call("ddc_learn_bridge:learn_bridge_load", Fs=paths, O=options, M=OUT)
        self.module: str = str(result["M"])
        self.files = tuple(paths)

    # -- the data
    def targets(self) -> list[dict[str, Any]]:
        """The targets: name (DC head), predicate (internal name), kind, domain, file, line."""
        result = _call("ddc_learn:learn_targets", M=self.module, Ts=OUT)
        return [dict(t) for t in result["Ts"]]

    def warnings(self) -> list[str]:
        """Warnings of the data, as ``file:line: cause`` lines."""
        result = _call("ddc_learn_data:learn_data_warnings", M=self.module, Ss=OUT)
        return [str(s) for s in result["Ss"]]

    # -- nodes
    def root(self, predicate: str) -> Root:
        result = _call("ddc_learn:learn_root", M=self.module, P=predicate, O=[], R=OUT)
        r = result["R"]
        return Root(node=int(r["node"]), y=np.asarray(r["y"], dtype=float),
                    weight=np.asarray(r["weight"], dtype=float),
                    example=np.asarray(r["example"], dtype=np.int64))

    def candidates(self, node: int) -> list[dict[str, Any]]:
        """The literals the bias allows at ``node`` (see ``learn_candidates/3``)."""
        result = _call("ddc_learn:learn_candidates", M=self.module, N=node, Cs=OUT)
        return [dict(c) for c in result["Cs"]]

    def evaluate(self, node: int, candidates: Sequence[int]) -> list[Outcome]:
        """Each candidate's outcome in every row of ``node``."""
        if not candidates:
            return []
        result = _call("ddc_learn:learn_evaluate", M=self.module, N=node,
                       Ids=[int(c) for c in candidates], Os=OUT)
        return [_outcome(o) for o in result["Os"]]

    def evaluate_rows(self, node: int, candidate: int, rows: Sequence[int]) -> Outcome:
        """A candidate's outcome in some rows of ``node`` (row indices from 0)."""
        result = _call("ddc_learn:learn_evaluate_rows", M=self.module, N=node, C=int(candidate),
                       Is=[int(i) for i in rows], O=OUT)
        return _outcome(result["O"])

    def split(self, node: int, candidate: int) -> list[Child]:
        """Split ``node`` by a candidate: one child per branch, in branch order."""
        result = _call("ddc_learn:learn_split", M=self.module, N=node, C=int(candidate), Cs=OUT)
        return [Child(node=int(c["node"]), branch=int(c["branch"]),
                      row=np.asarray(c["row"], dtype=np.int64),
                      factor=np.asarray(c["factor"], dtype=float),
                      x=np.asarray(c["x"], dtype=float)) for c in result["Cs"]]

    def forget(self, nodes: Sequence[int]) -> None:
        """Drop nodes' rows (branches not kept)."""
        if nodes:
            _call("ddc_learn_bridge:learn_bridge_forget", M=self.module,
                  Ns=[int(n) for n in nodes])

    def subset(self, node: int, rows: Sequence[int]) -> int:
        """A new node with ``node``'s path and its rows at the indices ``rows`` (from 0)."""
        result = _call("ddc_learn:learn_subset", M=self.module, N=int(node),
                       Is=[int(i) for i in rows], S=OUT)
        return int(result["S"])

    def forget_rows(self, node: int) -> None:
        """Drop a node's rows but keep its path (a split node that may become a leaf)."""
        _call("ddc_learn:learn_forget_rows", M=self.module, N=int(node))

    # -- clauses
    def leaf_clause(self, node: int, model: str, regressors: Sequence[int]) -> dict[str, str]:
        """The clause of a leaf: ``clause`` (DC text), ``distribution`` and ``model`` texts.

        ``model`` is the Prolog text of the leaf's model term (``logistic([-16.9, 0.8])``),
        ``regressors`` the path steps whose values are its inputs.
        """
        result = _call("ddc_learn:learn_leaf_text", M=self.module, N=node, MT=model,
                       Rs=[int(r) for r in regressors], D=OUT)
        return {k: str(v) for k, v in dict(result["D"]).items()}

    def set_root_model(self, predicate: str, model: str) -> None:
        """Set a target's root model (``learn_root_model/3``), read by the leaves' clauses.

        ``model`` is the Prolog text of ``root_model(Features, Rows)``: a leaf regressor ``-1-J``
        is then the J-th score of that model (:mod:`probanchor.ddclearn.root_model`).
        """
        _call("ddc_learn:learn_root_model", M=self.module, P=predicate, T=model)

    def record(self, files: Sequence[str | Path], predicates: Sequence[str]) -> str:
        """The record a learned program keeps of its data (``learn_data_record/4``).

        The DC text of ``learned_from(Dialect, Files, Targets, Declarations)``: the data's
        dialect, ``files`` as given, the targets of the internal names ``predicates`` and the
        declarations that say how the facts are read.
        """
        result = _call("ddc_learn_data:learn_data_record", M=self.module,
                       Fs=[str(f) for f in files], Ps=list(predicates), T=OUT)
        return str(result["T"])

    def background(self, leaves: Sequence[tuple[int, str, Sequence[int]]]) -> list[str]:
        """The background clauses (DC text) that the leaves' clauses need."""
        result = _call("ddc_learn:learn_background_for", M=self.module,
                       Ls=[[int(n), m, [int(r) for r in rs]] for n, m, rs in leaves], Ts=OUT)
        return [str(t) for t in result["Ts"]]

    def tree_clause(self, leaves: Sequence[tuple[int, str, Sequence[int], str]]) -> str | None:
        """A target's tree as one clause of nested if-then-else goals (``learn_tree_text/3``).

        ``leaves`` are the target's leaves from left to right: node, model text, regressors
        and the comment written at the leaf. None if the leaves' distributions are not of
        one family (no single head).
        """
        result = _call("ddc_learn_bridge:learn_bridge_tree_text", M=self.module,
                       Ls=[[int(n), m, [int(r) for r in rs], c] for n, m, rs, c in leaves],
                       T=OUT)
        return str(result["T"][0]) if result["T"] else None

    def program_scores(self, program: str | Path, predicates: Sequence[str] = (),
                       examples: bool = False) -> list[dict[str, Any]]:
        """Held-out scores of a DC program's clauses on this data (``learn_program_scores/5``).

        With ``examples`` each target's dict has ``examples``: per grounding (in the order of
        the target's groundings) its weight and log-likelihood.
        """
        [path] = _existing([program])
        result = _call("ddc_learn_bridge:learn_bridge_program_scores", M=self.module, F=path,
                       Ts=list(predicates), O={"examples": "true" if examples else "false"},
                       Ss=OUT)
        return [dict(s) for s in result["Ss"]]

    def free(self) -> None:
        """Forget the data (its Prolog module)."""
        _call("ddc_learn:learn_free", M=self.module)

    def __enter__(self) -> LearningData:
        return self

    def __exit__(self, *exc: object) -> None:
        self.free()


def _split_options(seed: int, unit: str | None) -> dict[str, Any]:
    """The options shared by the split's calls."""
    prolog.ensure_loaded(prolog.PROLOG_DIR / "ddc/learn/ddc_learn_split.pl")
    options: dict[str, Any] = {"seed": int(seed)}
    if unit is not None:
        options["unit"] = str(unit)
    return options


def split_files(
    files: Sequence[str | Path],
    train: str | Path,
    test: str | Path,
    fraction: float = 0.2,
    seed: int = 0,
    unit: str | None = None,
) -> dict[str, int]:
    """Split a data set into a training file and a test file of separate worlds (``ddc split``).

    The facts are grouped into units: the connected components of the graph that links the
    constants of each fact's key, or, with ``unit``, the constants of that argument type, every
    other constant following the unit nearest to it. Whole units, in an order shuffled by
    ``seed``, go to the test file until it holds at least ``fraction`` of the facts; a fact whose
    constants fall on both sides is cut (written to neither). Declarations, directives and
    background rules go to both files. See ``learn_split_files/3`` in
    ``prolog/ddc/learn/ddc_learn_split.pl``.

    Parameters
    ----------
    files : sequence of path
        The data files (one dialect: the project's own or DreaML's).
    train, test : path
        The two outputs, created or replaced (only once both are complete).
    fraction : float, default=0.2
        The test part's share of the facts, strictly between 0 and 1.
    seed : int, default=0
        Seeds the order of the units.
    unit : str, optional
        An argument type whose constants are the units (``d`` for FinancialData.pl's
        districts).

    Returns
    -------
    dict
        ``train``, ``test`` (facts in that part only), ``cut`` (in neither), ``both`` (facts
        without constants, in both), ``units`` and ``test_units``.

    Raises
    ------
    ValueError
        ``fraction`` is not strictly between 0 and 1.
    DDCError
        A data file is missing or bad, the facts form one world only (no unit to hold out), the
        unit type is unknown, or an output is an input file (the message names file:line).
    """
    if not 0.0 < float(fraction) < 1.0:
        raise ValueError(f"the test fraction must be between 0 and 1 (exclusive), got {fraction}")
    options = _split_options(seed, unit)
    options.update({"train": str(Path(train).resolve()), "test": str(Path(test).resolve()),
                    "fraction": float(fraction)})
    stats = dict(_call("ddc_learn_bridge:learn_bridge_split_files", Fs=_existing(files),
                       O=options, St=OUT)["St"])
    return {k: int(stats[k]) for k in ("train", "test", "cut", "both", "units", "test_units")}


def fold_files(
    files: Sequence[str | Path],
    parts: Sequence[tuple[str | Path, str | Path]],
    seed: int = 0,
    unit: str | None = None,
) -> list[dict[str, int]]:
    """Split a data set into K folds of separate worlds, one training and test file per fold.

    The units are those of :func:`split_files`; shuffled by ``seed``, each goes to the fold
    with the fewest facts so far, so the folds' test files partition the units. Fold ``i``'s
    training file holds every other fold's facts; a fact whose constants fall in two folds is
    cut in those two. See ``learn_fold_files/3`` in ``prolog/ddc/learn/ddc_learn_split.pl``.

    Parameters
    ----------
    files : sequence of path
        The data files (one dialect).
    parts : sequence of (train, test) paths
        One pair per fold, at least two; each pair created or replaced once both are complete.
    seed : int, default=0
        Seeds the order of the units.
    unit : str, optional
        An argument type whose constants are the units.

    Returns
    -------
    list of dict
        Per fold: ``fold`` (1-based), ``train``, ``test``, ``cut``, ``both``, ``units`` and
        ``test_units``, as :func:`split_files` counts them.

    Raises
    ------
    ValueError
        Fewer than two folds.
    DDCError
        A data file is missing or bad, fewer units than folds, or an output is an input.
    """
    if len(parts) < 2:
        raise ValueError(f"cross-validation needs at least 2 folds, got {len(parts)}")
    options = _split_options(seed, unit)
    pairs = [[str(Path(tr).resolve()), str(Path(te).resolve())] for tr, te in parts]
    folds = _call("ddc_learn_bridge:learn_bridge_fold_files", Fs=_existing(files), Ps=pairs,
                  O=options, St=OUT)["St"]
    keys = ("both", "cut", "fold", "test", "test_units", "train", "units")
    return [{k: int(dict(fold)[k]) for k in keys} for fold in folds]
