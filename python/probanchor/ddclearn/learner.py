"""Learn a DC program from data, write it, score it on held-out data.

Example::

    from probanchor.ddclearn import learn, evaluate
    result = learn(["train.pl"], seed=0)
    result.write("learned.pl")            # an ordinary DC program (ddc query, ddc filter, bridge)
    result.report()                       # {"grade": {"clauses": 5, "groundings": ..., ...}}
    evaluate("learned.pl", ["test.pl"])   # {"grade": {"n": ..., "mean_log_likelihood": ...}}
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from contextlib import nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np
from threadpoolctl import threadpool_limits

from bridge.errors import DDCError
from bridge.learning import LearningData
from probanchor.ddclearn.files import write_atomically
from probanchor.ddclearn.search import LeafRecord, SearchOptions, TargetResult, learn_target

__all__ = ["LearnResult", "evaluate", "learn", "leaf_comment", "target_key"]

Form = Literal["clauses", "tree"]


def target_key(name: str) -> str:
    """The short name of a target: ``occluded_by(A,O):t+1`` -> ``occluded_by:t+1``."""
    base, _, rest = name.partition("(")
    time = ""
    if rest:
        _, _, after = rest.rpartition(")")
        time = after
    elif ":" in base:
        base, _, t = base.partition(":")
        time = ":" + t
    return base + time


@dataclass
class LearnResult:
    """What :func:`learn` found: one tree per target and the program made of them."""

    files: list[str]
    targets: list[TargetResult]
    background: list[str]
    warnings: list[str]
    options: SearchOptions
    seed: int | None
    command: str | None = None
    #: The program's record of its data: the DC text of ``learned_from(Dialect, Files,
    #: Targets, Declarations)`` (``bridge.learning.LearningData.record``).
    record: str | None = None
    _program: str | None = field(default=None, repr=False)

    @property
    def program(self) -> str:
        """The learned DC program (text), one clause per path of each tree."""
        if self._program is None:
            self._program = _program_text(self)
        return self._program

    def program_text(self, form: Form = "clauses") -> str:
        """The learned DC program in either form.

        Parameters
        ----------
        form : {"clauses", "tree"}, default="clauses"
            ``"clauses"``: one clause per path from the root to a leaf (the paper's form).
            ``"tree"``: one clause per target whose body is the tree itself, nested
            if-then-else goals binding the head's parameters; the same program, in which a
            test shared by many paths is evaluated once (faster in the particle filter). A
            target whose leaves' distributions differ in family keeps its clauses.
        """
        if form == "clauses":
            return self.program
        if form != "tree":
            raise ValueError(f"form must be 'clauses' or 'tree', got {form!r}")
        return _program_text(self, tree=True)

    def report(self) -> dict[str, dict[str, Any]]:
        """Per target: clauses, groundings, examples, seconds, training log-likelihood."""
        return {
            target_key(t.name): {
                "target": t.name,
                "clauses": t.clauses,
                "groundings": t.groundings,
                "examples": t.examples,
                "seconds": round(t.seconds, 3),
                "log_likelihood": t.log_likelihood,
                "mean_log_likelihood": t.mean_log_likelihood,
                "parameters": t.n_params,
                "depth": t.tree.root.depth(),
            }
            for t in self.targets
        }

    def write(self, path: str | Path, check: bool = True, form: Form = "clauses") -> Path:
        """Write the program (in ``form``, see :meth:`program_text`) to ``path`` atomically.

        With ``check`` the program is first compiled by the DDC system (a program that does not
        load is an error, and ``path`` keeps what it held).
        """
        def loads(tmp: Path) -> None:
            import bridge

            try:
                bridge.load(str(tmp))
            except DDCError as error:
                raise DDCError(f"the learned program does not load: {error}") from None

        return write_atomically(path, self.program_text(form), loads if check else None)


def learn(
    files: Sequence[str | Path],
    targets: Sequence[str] | None = None,
    *,
    seed: int | None = 0,
    options: SearchOptions | None = None,
    samples: int = 20,
    command: str | None = None,
    progress: bool = False,
) -> LearnResult:
    """Learn one distributional logic tree per target from DC data.

    Parameters
    ----------
    files : sequence of path
        Data files: facts, background knowledge and the declarative bias (see
        ``docs/learning.md``; DreaML's input files are read as they are).
    targets : sequence of str, optional
        The targets to learn (short names ``grade``, ``occluded_by:t+1``, or internal ones
        ``occluded_by_t1``); default: every target the bias declares.
    seed : int or None, default=0
        Seeds the samples of continuous uncertain facts (the learner is otherwise
        deterministic).
    options : SearchOptions, optional
        The search's settings.
    samples : int, default=20
        Samples per continuous uncertain fact.
    command : str, optional
        The command line, for the program's header.
    progress : bool, default=False
        Show a progress bar (tqdm, on stderr).

    Returns
    -------
    LearnResult
    """
    options = options or SearchOptions()
    data = LearningData(files, seed=seed, samples=samples)
    # the fits are small: BLAS threads only wait for each other (up to 5 times slower on a
    # shared two-core machine)
    limits = threadpool_limits(limits=1, user_api="blas")
    try:
        declared = data.targets()
        chosen = _select(declared, targets)
        warnings = data.warnings()
        results: list[TargetResult] = []
        bar_context: Any = nullcontext(None)
        if progress:
            from tqdm import tqdm

            bar_context = tqdm(total=len(chosen), unit="target", leave=False)
        with bar_context as bar:
            for t in chosen:
                if bar is not None:
                    bar.set_description(target_key(str(t["name"])))
                nodes = [0]

                def tick(bar: Any = bar, nodes: list[int] = nodes) -> None:
                    nodes[0] += 1
                    if bar is not None:
                        bar.set_postfix(nodes=nodes[0], refresh=False)

                result = learn_target(data, t, options, tick)
                result.tree_clause = data.tree_clause(
                    [(r.node, r.model_term, r.regressors, leaf_comment(r)) for r in result.leaves])
                results.append(result)
                if bar is not None:
                    bar.update(1)
        leaves = [(r.node, r.model_term, r.regressors) for t in results for r in t.leaves]
        background = data.background(leaves)
        record = data.record([Path(f).name for f in files], [t.predicate for t in results])
    finally:
        limits.restore_original_limits()
        data.free()
    return LearnResult(files=[str(Path(f)) for f in files], targets=results,
                       background=background, warnings=warnings, options=options, seed=seed,
                       command=command, record=record)


def _select(declared: list[dict], wanted: Sequence[str] | None) -> list[dict]:
    if not wanted:
        return declared
    chosen = []
    for w in wanted:
        match = [t for t in declared
                 if w in (t["predicate"], t["name"], target_key(str(t["name"])))
                 or w == str(t["name"]).partition("(")[0]]
        if not match:
            names = ", ".join(target_key(str(t["name"])) for t in declared)
            raise DDCError(f"no target {w!r} in the data (targets: {names})")
        for m in match:
            if m not in chosen:
                chosen.append(m)
    return chosen


def leaf_comment(leaf: LeafRecord) -> str:
    """What the program says of a leaf: its groundings, log-likelihood and family."""
    what = (f"n = {leaf.rows}" if abs(leaf.weight - leaf.rows) < 1e-9
            else f"n = {leaf.rows} (weight {leaf.weight:.6g})")
    if leaf.inherited:
        what += ", too few groundings for a model of its own: the parent's model"
    ll = f", log-likelihood {leaf.log_likelihood:.6g}" if leaf.rows else ""
    return f"{what}{ll}, {leaf.leaf.family}"


def root_model_note(t: TargetResult) -> list[str]:
    """What the program says of a target's root model: whether its leaves read one, why."""
    c, m = t.choice, t.root_model
    if c is None and m is None:
        return []
    held = ("" if c is None or not c.rows else
            f" (held out, {c.rows} groundings: {c.gain:+.4g} nats with it, standard error "
            f"{c.se:.3g})")
    if m is not None:
        return [f"Its leaves read a root model: a regression over {len(m.features)} features "
                f"(Score{'' if m.n_scores == 1 else ', Score1, ...'}){held}."]
    if c is not None and c.gain == 0:
        return ["No root model: the tree grown with it read none of its scores."]
    return [f"No root model: the tree alone predicts better{held}."]


def _program_text(r: LearnResult, tree: bool = False) -> str:
    o = r.options
    if tree:
        lines = [
            "% A DC program learned by the project's structure learner (ddc learn): one",
            "% distributional logic tree per target, written as one clause whose body is the",
            "% tree (nested if-then-else goals; each path from the root to a leaf is one clause",
            "% of the tree's other form, whose clauses are mutually exclusive).",
        ]
    else:
        lines = [
            "% A DC program learned by the project's structure learner (ddc learn): one",
            "% distributional logic tree per target, each path from the root to a leaf one "
            "clause;",
            "% the clauses of a target are mutually exclusive and cover every grounding.",
        ]
    if r.command:
        lines.append(f"% Command: {r.command}")
    lines.append("% Data: " + ", ".join(Path(f).name for f in r.files))
    lines.append(f"% Search: min_leaf {o.min_leaf:g}, max_depth {o.max_depth}, min_gain "
                 f"{o.min_gain:g}, lookahead {str(o.lookahead).lower()}, root model "
                 f"{o.root_model}; leaves: smoothing {o.leaf.smoothing:g}, l2 {o.leaf.l2:g}; "
                 f"seed {r.seed}.")
    lines.append("")
    if r.record:
        lines += [
            "% What the program was learned from: the data's dialect, files and targets, and the",
            "% declarations that say how their facts are read (`ddc evaluate` reads test files",
            "% without declarations by them).",
            r.record,
            "",
        ]
    if r.background:
        lines.append("% Background knowledge from the data that the learned clauses call.")
        lines.extend(r.background)
        lines.append("")
    for t in r.targets:
        lines.append(f"% {t.name}: {t.clauses} clauses, {t.groundings} groundings, training "
                     f"log-likelihood {t.log_likelihood:.6g} (mean {t.mean_log_likelihood:.6g} "
                     f"per grounding), {t.n_params} parameters.")
        lines.extend(f"% {line}" for line in root_model_note(t))
        if tree and t.tree_clause is not None:
            lines.append(t.tree_clause)
        else:
            for leaf in t.leaves:
                lines.append(f"% {leaf_comment(leaf)}")
                lines.append(leaf.clause)
        lines.append("")
    return "\n".join(lines)


def evaluate(
    program: str | Path,
    files: Sequence[str | Path],
    targets: Sequence[str] | None = None,
    bias: Sequence[str | Path] | None = None,
    examples: bool = False,
) -> dict[str, dict[str, Any]]:
    """Held-out scores of a DC program's clauses on test data.

    Every grounding of a target in the test data (its facts) is scored by the first clause of
    the program whose body holds in the test data's world: the log density (or mass) of the
    fact's value, natural log; the prediction is the most probable value (accuracy) or the mean
    (RMSE).

    Parameters
    ----------
    program : path
        A DC program (learned or written by hand).
    files : sequence of path
        Test data, in the same format as training data (bias lines are read too).
    targets : sequence of str, optional
        Which targets (default: every random variable the program defines that has facts).
    bias : sequence of path, optional
        When no test file has a declaration (facts only, as DreaML's held-out files): the
        files whose declarations say how the facts are read (the training file; its facts are
        not read). Without it such facts are read in the dialect and with the declarations of
        the data the program was learned from (its ``learned_from/4`` record), or, for a
        program without one, in the project's own dialect.
    examples : bool, default=False
        Also give each grounding's weight and log-likelihood (``example_weight``,
        ``example_log_likelihood``: arrays in the order of the target's groundings in the
        data, the order of :func:`probanchor.ddclearn.baselines.feature_table`'s rows for data
        without uncertain facts).

    Returns
    -------
    dict
        Keyed by target: ``n``, ``weight``, ``log_likelihood``, ``mean_log_likelihood``,
        ``uncovered`` and ``accuracy`` (discrete) or ``rmse`` (continuous).
    """
    data = LearningData(files, targets=False, bias=bias, program=program)
    try:
        preds: list[str] = []
        if targets:
            known = {target_key(str(t["name"])): str(t["predicate"]) for t in data.targets()}
            for w in targets:
                preds.append(known.get(w, w.replace(":t+1", "_t1").replace(":t", "_t")))
        scores = data.program_scores(program, preds, examples=examples)
    finally:
        data.free()
    out: dict[str, dict[str, Any]] = {}
    for s in scores:
        entry: dict[str, Any] = {
            "n": int(s["n"]),
            "weight": float(s["weight"]),
            "mean_log_likelihood": float(s["mean_log_likelihood"]),
            "log_likelihood": float(s["log_likelihood"]),
            "uncovered": int(s["uncovered"]),
        }
        acc, rmse = float(s["accuracy"]), float(s["rmse"])
        if not math.isnan(acc):
            entry["accuracy"] = acc
        if not math.isnan(rmse):
            entry["rmse"] = rmse
        if examples:
            per = np.asarray(s["examples"], dtype=float).reshape(-1, 2)
            entry["example_weight"] = per[:, 0]
            entry["example_log_likelihood"] = per[:, 1]
        out[target_key(str(s["target"]))] = entry
    return out
