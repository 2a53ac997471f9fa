"""``anchoring learn-theory``: the theory of occlusion with rules learned from experience.

The structure learner (:func:`probanchor.ddclearn.learn`) learns, from the data ``anchoring
collect`` writes, one distributional logic tree for ``occluder(A, O):t+1``: whether O covers (or
holds) the hidden object A at t+1. Its branch where A was known to be under O at t is the *tracking
rule* (does the occlusion go on?), the other branch the *occluder rule* (may O start hiding A?),
both with statistical models (a logistic regression on a distance, ...) in their leaves. And a
second tree, for ``released(A):t+1``: when a hand lets go of what it carries, learned from the
carries ``anchoring collect`` keeps (``DATA.release.pl`` beside the data,
:mod:`probanchor.learning.release_data`).

The theory written includes the hand-written parts it shares with ``prolog/too.pl`` rather than
copying them (``:- include(File).``, relative to the theory written, from ``prolog/too/``):
``too_base.pl`` (the vocabulary and the filter's frame) and, after the learned rules,
``too_motion.pl`` (the transitive clause of section 5.3, the carriers' rules, the motion of
hidden objects: structure whose constants are learned). In place of ``too.pl``'s parameters it
has those it reads fitted from the motion samples beside the data
(:mod:`probanchor.learning.motion_parameters`); in place of its affordances those read from the data
with their probabilities (:mod:`probanchor.learning.occlusion_affordances`); in place of its
occlusion rules the learned clauses and the hand-written glue that uses them as the paper's
theory does (section 2.3; ``too_learned_glue.pl``, shared by every learned theory): a hidden
object's candidate occluders are the perceived objects O for which a particle draws
``occluder(A, O):t+1 ~= true``; it picks one uniformly (or ``behind``, when it has just
vanished, as in ``too.pl``); an occlusion goes on while the particle draws
``occluder(A, O):t+1 ~= true`` and O is perceived.
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from bridge.resources import prolog_dir
from probanchor.ddclearn import LearnResult, SearchOptions, learn
from probanchor.ddclearn.files import write_atomically
from probanchor.ddclearn.learner import Form
from probanchor.learning.motion_parameters import (
    Fitted,
    fit,
    hand_written,
    kind_height_clauses,
    kind_heights,
    parameter_clauses,
    parameter_rows,
)
from probanchor.learning.motion_samples import MotionSamples, read_samples
from probanchor.learning.occlusion_affordances import (
    Affordance,
    affordance_clauses,
    affordance_table,
    affordances,
    never_occluders,
)
from probanchor.learning.occlusion_asked import asked_data
from probanchor.learning.occlusion_reach import (
    MARGIN,
    QUANTILE,
    DataPoints,
    OnsetReach,
    onset_reach,
    read_points,
)
from probanchor.learning.release_data import release_path, release_points

__all__ = ["AFTER", "BEFORE", "DEPLOYED", "GLUE", "PAPER", "LearnedTheory", "TheoryError",
           "along_distance", "coefficient_table", "parameter_table",
           "learn_theory", "logistic_leaves", "plot_theory", "probability_at", "theory_text"]

#: The hand-written parts (in ``prolog/too/``) a learned theory includes before its learned
#: parameters (the vocabulary and the frame), before its learned tree (the glue that uses it) and
#: after it (carriers, motion of hidden objects).
BEFORE = ("too_base.pl",)
GLUE = "too_learned_glue.pl"
AFTER = ("too_motion.pl",)

#: The paper's learned clause, P1 = sigmoid(0.8 - 16.9 d) (section 4).
PAPER = (-16.9, 0.8)
#: The original system's deployed model, sigmoid(1.948 - 16.488 d) (ProbAnch).
DEPLOYED = (-16.488, 1.948)

class TheoryError(ValueError):
    """A theory that cannot be written: a hand-written part to include is missing, or the result
    does not load (the message names the file, line and cause)."""


@dataclass
class LearnedTheory:
    """What ``learn-theory`` wrote and learned."""

    out: Path
    result: LearnResult
    text: str
    reach: OnsetReach | None = None
    base: Path | None = None
    affordances: dict[str, dict[str, Affordance]] | None = None
    parameters: list[Fitted] | None = None
    samples: MotionSamples | None = None
    release: LearnResult | None = None

    @property
    def logistic(self) -> list[dict[str, object]]:
        """The leaves whose model is a logistic regression on the distance: their path, the
        regressors' names and weights (the bias last), their groundings."""
        return logistic_leaves(self.result)


def theory_text(learned_program: str, header: str, *, base: str | Path,
                out: str | Path, reach: OnsetReach,
                found: dict[str, dict[str, Affordance]], fitted: Sequence[Fitted],
                release_program: str | None,
                heights: dict[str, tuple[float, int]] | None = None) -> str:
    """The theory: ``header``, the hand-written parts of ``base`` (a folder) included, the
    parameters fitted from the data (``fitted``, and the kinds' ``heights``,
    :func:`kind_heights`), the affordances read from it (``found``), the
    glue included, the onset reach fitted from the data and the learned programs (the learner's
    output: background knowledge and clauses) of the occluder and of the release (None: no hand
    carried anything in the data, the theory has no carrier and no release).

    The includes name the parts relative to the folder of ``out``, the file the theory is
    written to (the DC reader resolves an include relative to the including file).

    Raises
    ------
    TheoryError
        ``base`` lacks one of the hand-written parts.
    """
    folder = Path(base)
    missing = [name for name in (*BEFORE, GLUE, *AFTER) if not (folder / name).is_file()]
    if missing:
        raise TheoryError(f"{folder}: no hand-written part {', '.join(missing)} to include")
    here = Path(out).resolve().parent

    def include(name: str) -> str:
        rel = os.path.relpath((folder / name).resolve(), here)
        quoted = rel.replace("\\", "\\\\").replace("'", "\\'")
        return f":- include('{quoted}').\n"

    body = _program_body(learned_program, OCCLUDER_INTRO) + "\n" + (
        NO_RELEASE if release_program is None else _program_body(release_program, RELEASE_INTRO))
    onset = (f"% The onset reach (m): {QUANTILE:.0%} of the {reach.onsets} onsets in the data "
             f"{_far_out(reach)}were within {reach.quantile:.4g} m; times {MARGIN}.\n"
             if reach.onsets else
             "% The onset reach (m): NOT FITTED: no onset in the data, too_parameters.pl's "
             "occluder_reach.\n") + f"onset_reach({reach.reach:.4g}).\n"
    if reach.kinds:
        onset += "% The reach of the kinds with onsets enough for one of their own.\n"
    for kind, own in reach.kinds.items():
        onset += f"onset_reach({kind}, {own.reach:.4g}).  % {_fitted_from(own, '.4g')}\n"
    return (header + "".join(include(n) for n in BEFORE) + "\n" + parameter_clauses(fitted)
            + ("" if not heights else kind_height_clauses(heights))
            + "\n" + affordance_clauses(found) + "\n" + include(GLUE) + onset + "\n"
            + body.rstrip()
            + "\n\n" + "".join(include(n) for n in AFTER))


OCCLUDER_INTRO = ("% The learned rules (ddc learn): a distributional logic tree for occluder/2 "
                  "(each path from its\n% root to a leaf is one clause of the tree), with the "
                  "background knowledge it reads.\n")
RELEASE_INTRO = ("% When a hand lets go of what it carries (ddc learn, from the carries beside "
                 "the data): a\n% distributional logic tree for released/1, with the background "
                 "knowledge it reads.\n")

NO_RELEASE = ("% No hand carried an object in the data: no release learned (a carrier, if "
              "any, holds what it\n% took until that is seen again).\n")


def _release_header(release: LearnResult | None) -> list[str]:
    if release is None:
        return ["    no hand carried an object in the data: no release learned;"]
    t = release.targets[0]
    return [f"    and one for released(A):t+1 from {t.groundings} frames a hand held an object",
            f"    ({t.clauses} clauses, training log-likelihood {t.log_likelihood:.6g});"]


def _program_body(program: str, intro: str) -> str:
    """The learned program without its own header comment (the theory's header says it)."""
    lines = program.splitlines()
    k = 0
    while k < len(lines) and (lines[k].startswith("%") or not lines[k].strip()):
        k += 1
    return intro + "\n".join(lines[k:]) + "\n"


def learn_theory(data: Sequence[str | Path], out: str | Path, *, seed: int = 0,
                 options: SearchOptions | None = None, base: str | Path | None = None,
                 command: str | None = None, progress: bool = False,
                 form: Form = "tree") -> LearnedTheory:
    """Learn the occlusion rules from ``data`` and write the complete theory to ``out``.

    Without ``options``, the learner's defaults but for its root model (``never``): a root model
    is a regression over every root feature that every leaf reads, so each draw of
    ``occluder(A, O):t+1`` in the filter would compute every feature (1.5 times the CPU of a
    plain tree, which reads only the features on its path).

    The tree goes into the theory in its tree form (``form="tree"``: one clause whose body is
    the tree, each test evaluated once per particle, as fast in the filter as the hand-written
    rules) or as one clause per path (``form="clauses"``, the paper's form; the same program).

    ``out`` is replaced only once the theory is complete and loads in the engine (a failed run
    leaves the previous file as it was).

    Raises
    ------
    TheoryError
        A hand-written part is missing from ``base`` (default ``prolog/too/``), the motion
        samples or the release data beside the data are missing, or the theory written does
        not load. (A parameter the samples cannot fit keeps too_parameters.pl's value, marked
        NOT FITTED in the theory.)
    bridge.DDCError
        The data has an error (its message names the file and line).
    """
    import bridge

    out = Path(out)
    folder = Path(base) if base is not None else prolog_dir() / "too"
    if options is None:
        options = SearchOptions(root_model="never")
    try:
        samples = read_samples(list(data))
        fitted = fit(samples, hand_written(folder))
    except (ValueError, FileNotFoundError) as error:
        raise TheoryError(str(error)) from None
    releases = [release_path(d) for d in data]
    absent = [str(r) for r in releases if not r.is_file()]
    if absent:
        raise TheoryError(f"{', '.join(absent)}: no release data beside the data (`anchoring "
                          "collect` writes DATA.release.pl; collect again)")
    points = read_points(data)
    found = affordances(points)
    try:
        reach = onset_reach(points, exclude=never_occluders(found))
    except ValueError:
        # no onset to fit (a few games where only hands took objects): the hand-written reach,
        # marked NOT FITTED, as a parameter without samples keeps its hand-written value
        reach = OnsetReach(hand_written(folder)["occluder_reach"], float("nan"), 0)
    result = _learn_asked(data, points, reach, seed=seed, options=options, progress=progress)
    release = None
    if sum(release_points(r) for r in releases):
        release = learn(releases, ["released:t+1"], seed=seed, options=options,
                        progress=progress)
    target = result.targets[0]
    names = ", ".join(Path(d).name for d in data)
    parts = ", ".join((*BEFORE, GLUE, *AFTER))
    header = [
        f"/*  {out.name} -- the theory of occlusion with rules learned from experience.",
        "",
        "    Written by `anchoring learn-theory`: a tree learned (ddc learn) from",
        f"    {names}: {target.groundings} groundings of occluder(A, O):t+1,",
        f"    {target.clauses} clauses, training log-likelihood {target.log_likelihood:.6g};",
        *_release_header(release),
        f"    search seed {seed}.",
    ]
    if command:
        header.append(f"    Command: {command}")
    header += [
        f"    The hand-written parts are included from {folder.parent.name}/{folder.name}/ "
        f"({parts}):",
        "    regenerate this file rather than edit it; edit those for the rest.  The",
        "    parameters are fitted from the motion samples beside the data.",
        "*/",
        "",
    ]
    text = theory_text(result.program_text(form), "\n".join(header) + "\n", base=folder,
                       out=out, reach=reach, found=found, fitted=fitted,
                       release_program=None if release is None else release.program_text(form),
                       heights=kind_heights(samples))

    def loads(tmp: Path) -> None:
        try:
            bridge.load(str(tmp))
        except bridge.DDCError as error:
            raise TheoryError(f"the learned theory does not load: {error}") from None

    write_atomically(out, text, loads)
    return LearnedTheory(out, result, text, reach, folder, found, fitted, samples, release)


def _learn_asked(data: Sequence[str | Path], points: DataPoints, reach: OnsetReach, *,
                 seed: int, options: SearchOptions, progress: bool) -> LearnResult:
    """The occluder tree learned from the examples of ``data`` the filter asks about
    (:mod:`probanchor.learning.occlusion_asked`); an error in a data file names that file."""
    import bridge

    with tempfile.TemporaryDirectory(prefix="learn-theory-") as folder:
        copies, _ = asked_data(data, points, reach, folder)
        try:
            return learn(copies, ["occluder:t+1"], seed=seed, options=options,
                         progress=progress)
        except bridge.DDCError as error:
            message = str(error)
            for copy, path in zip(copies, data, strict=True):
                message = message.replace(str(copy), str(path))
            raise bridge.DDCError(message, error.cause) from None


def logistic_leaves(result: LearnResult) -> list[dict[str, object]]:
    """The leaves of the learned tree whose model is a logistic regression with a distance
    among its regressors (see :func:`along_distance`): path (the tested literals), regressors
    (their variables' names), weights (one per regressor, the bias last), rows, weight."""
    out: list[dict[str, object]] = []
    for leaf in result.targets[0].leaves:
        lf = leaf.leaf
        if lf.family != "logistic" or lf.weights is None:
            continue
        m = re.search(r"logistic\(\[([^\]]*)\]", leaf.clause)
        names = [n.strip() for n in m.group(1).split(",")] if m else []
        if not any(_is_distance(n) for n in names):
            continue
        body = leaf.clause.split(":=", 1)[1]
        path = [line.strip().rstrip(",") for line in body.splitlines()
                if line.strip() and "logistic(" not in line and " is 1-" not in line
                and not line.strip().startswith("pair(")]
        out.append({"path": path, "regressors": names, "weights": [float(w) for w in lf.weights],
                    "rows": leaf.rows, "weight": leaf.weight})
    return out


def along_distance(leaf: dict[str, object]) -> tuple[float, float]:
    """A logistic leaf as sigmoid(bias + slope d) along the table-plane distance d, at equal
    heights (its 3-D distance is then d too) and its other regressors at 0 (e.g. lift 0: an
    occluder that does not move up or down): (slope, bias), comparable with the paper's
    (-16.9, 0.8)."""
    names = list(leaf["regressors"])  # type: ignore[arg-type]
    w = [float(x) for x in leaf["weights"]]  # type: ignore[union-attr]
    slope = sum(wi for n, wi in zip(names, w, strict=False) if _is_distance(n))
    return slope, w[-1]


def _is_distance(name: str) -> bool:
    """A regressor's variable for distance/2 (Distance, Distance2, ...) or distance3/2
    (Distance3, Distance32, ...)."""
    return re.fullmatch(r"Distance\d*", name) is not None


def probability_at(leaf: dict[str, object], distance: np.ndarray) -> np.ndarray:
    """P1 of a logistic leaf along the table-plane ``distance`` (see :func:`along_distance`)."""
    slope, bias = along_distance(leaf)
    return 1.0 / (1.0 + np.exp(-(bias + slope * np.asarray(distance, dtype=float))))


#: The tree's picture shows this many levels (a deeper subtree is one box: its leaves' count).
TREE_PICTURE_DEPTH = 3


def plot_theory(theory: LearnedTheory, folder: str | Path, name: str) -> list[Path]:
    """The learned tree (``<name>_tree.png``, its first levels), P(occluder | distance) of its
    heaviest logistic leaves beside the paper's sigmoid(0.8 - 16.9 d) and the original system's
    deployed sigmoid(1.948 - 16.488 d) (``<name>_distance.png``), and their coefficients
    (``<name>_coefficients.md``, :func:`coefficient_table`)."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from probanchor.ddclearn.plot import plot_trees

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    tree = plot_trees([t.tree for t in theory.result.targets], folder / f"{name}_tree.png",
                      max_depth=TREE_PICTURE_DEPTH)
    d = np.linspace(0.0, 0.35, 200)
    fig = Figure(figsize=(7.5, 4.2))
    ax = fig.add_subplot()
    for label, (w, b), style in (("paper: sigmoid(0.8 - 16.9 d)", PAPER, "k--"),
                                 ("original system: sigmoid(1.948 - 16.488 d)", DEPLOYED, "k:")):
        ax.plot(d, 1.0 / (1.0 + np.exp(-(w * d + b))), style, label=label)
    for leaf in _heaviest(theory):
        ax.plot(d, probability_at(leaf, d),
                label=f"learned ({leaf['rows']} rows): {_path_label(leaf)}")
    ax.set_xlabel("distance d in the table plane (m)")
    ax.set_ylabel("P(occluder)")
    ax.set_ylim(0, 1)
    ax.legend(fontsize=6, loc="upper right")
    ax.set_title("P(O hides A | distance), the learned leaves beside the paper's")
    curve = folder / f"{name}_distance.png"
    fig.tight_layout()
    fig.savefig(curve, dpi=110)
    table = folder / f"{name}_coefficients.md"
    table.write_text(coefficient_table(theory), encoding="utf-8")
    written = [tree, curve, table]
    if theory.reach is not None and theory.base is not None:
        parameters = folder / f"{name}_parameters.md"
        parameters.write_text(parameter_table(theory.reach, theory.base)
                              + ("\n" + parameter_rows(theory.parameters, theory.base)
                                 if theory.parameters else "")
                              + ("\n" + affordance_table(theory.affordances)
                                 if theory.affordances else ""), encoding="utf-8")
        written.append(parameters)
    if theory.parameters and theory.samples is not None:
        written.append(plot_motion(theory.samples, theory.parameters,
                                   folder / f"{name}_motion.png"))
    return written


def plot_motion(samples: MotionSamples, fitted: Sequence[Fitted], path: Path) -> Path:
    """Histograms of the samples of three fitted variances (a perceived object's true
    displacement per frame, a reappearance around its belief, the same after the camera saw
    nothing; per axis, log counts) with the fitted Gaussians' expected counts."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    value = {f.name: f.value for f in fitted}
    panels = (("motion_var", "a perceived object's step (true)",
               [r[4] for r in samples.rows["displacement"] if r[4] is not None]),
              ("reappear_var", "a reappearance around its belief", samples.rows["reappear"]),
              ("lost_var", "lost while blind (the Gaussian: moved anywhere)",
               samples.rows["lost"]))
    fig = Figure(figsize=(11, 3.4))
    for i, (name, title, rows) in enumerate(panels):
        ax = fig.add_subplot(1, 3, i + 1)
        x = np.asarray(rows, dtype=float).reshape(-1)
        if x.size == 0:
            continue
        sd = float(np.sqrt(value[name]))
        edge = max(4 * sd, float(np.quantile(np.abs(x), 0.999)))
        bins = np.linspace(-edge, edge, 61)
        ax.hist(x, bins=bins, color="0.6", label=f"samples ({x.size:,} per-axis values)")
        centre = 0.5 * (bins[1:] + bins[:-1])
        width = bins[1] - bins[0]
        expected = x.size * width * np.exp(-centre ** 2 / (2 * sd * sd)) / (sd * np.sqrt(2 * np.pi))
        ax.plot(centre, expected, "k-", label=f"fitted N(0, {value[name]:.2g})")
        ax.set_yscale("log")
        ax.set_ylim(0.5, None)
        ax.set_xlabel("m")
        ax.set_title(f"{name}: {title}", fontsize=8)
        ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    return path


def parameter_table(reach: OnsetReach, base: str | Path) -> str:
    """A Markdown table: the parameters fitted from the data beside the hand-written values of
    ``base``'s too_parameters.pl that play their part in too.pl."""
    text = (Path(base) / "too_parameters.pl").read_text(encoding="utf-8")
    m = re.search(r"^occluder_reach\(([\d.eE+-]+)\)", text, re.M)
    hand = f"{float(m.group(1)):.3g} (`occluder_reach`)" if m else "-"
    rows = "".join(f"| onset reach of a {kind} (m) | {own.reach:.3g} | {hand} | "
                   f"{_fitted_from(own, '.3g')}, times {MARGIN:g} |\n"
                   for kind, own in reach.kinds.items())
    return ("| parameter | learned | hand-written | fitted from |\n|---|---:|---:|---|\n"
            f"| onset reach (m): how far from where a hidden object was an occluder may start "
            f"hiding it | {reach.reach:.3g} | {hand} | "
            + (f"{_fitted_from(reach, '.3g')}, times {MARGIN:g} |\n" if reach.onsets
               else "none: not fitted |\n") + rows)


def _fitted_from(reach: OnsetReach, digits: str) -> str:
    """``"N onsets, (K far out left out) 90% within Q m"``, Q formatted with ``digits``."""
    return (f"{reach.onsets} onsets, {_far_out(reach)}{QUANTILE:.0%} within "
            f"{reach.quantile:{digits}} m")


def _far_out(reach: OnsetReach) -> str:
    """``"(K far out left out) "`` when the fit left K onsets out, else nothing."""
    return f"({reach.far_out} far out left out) " if reach.far_out else ""


def _heaviest(theory: LearnedTheory, k: int = 6) -> list[dict[str, object]]:
    """The ``k`` logistic leaves with the most (weighted) groundings."""
    return sorted(theory.logistic, key=lambda leaf: -float(leaf["weight"]))[:k]  # type: ignore[arg-type]


def _path_label(leaf: dict[str, object]) -> str:
    path = [p for p in leaf["path"] if "~= Distance" not in p]  # type: ignore[union-attr]
    return ", ".join(p.replace("(Occluded, Occluder)", "").replace("(Occluded)", "(A)")
                     .replace("(Occluder)", "(O)") for p in path)


def coefficient_table(theory: LearnedTheory, k: int = 6) -> str:
    """A Markdown table: the paper's and the original system's P(occluder | distance) and the
    ``k`` heaviest learned logistic leaves as sigmoid(bias + slope d) (:func:`along_distance`),
    with P at 0, 5 and 10 cm."""
    def row(name: str, n: str, slope: float, bias: float) -> str:
        ps = " | ".join(f"{1.0 / (1.0 + np.exp(-(bias + slope * d))):.2f}"
                        for d in (0.0, 0.05, 0.1))
        return f"| {name} | {n} | {slope:.1f} | {bias:.2f} | {ps} |"

    lines = ["| clause | groundings | slope | bias | P(0 cm) | P(5 cm) | P(10 cm) |",
             "|---|---:|---:|---:|---:|---:|---:|",
             row("paper (section 4)", "", *PAPER),
             row("original system (deployed)", "", *DEPLOYED)]
    for leaf in _heaviest(theory, k):
        slope, bias = along_distance(leaf)
        lines.append(row(f"learned: {_path_label(leaf) or '(root)'}".replace("|", "\\|"),
                         str(leaf["rows"]), slope, bias))
    return "\n".join(lines) + "\n"
