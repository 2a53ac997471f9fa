"""The learned theory of occlusion: the learned rules with the hand-written parts shared with
too.pl included, loaded before it replaces anything, run by the filter; and ``anchoring collect`` /
``anchoring learn-theory`` end to end on a short generated game."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

import bridge
from ddc_cli_helpers import Run
from probanchor.learning.collect import CollectError, CollectOptions, collect
from probanchor.learning.learned_theory import (
    AFTER,
    BEFORE,
    GLUE,
    TheoryError,
    along_distance,
    learn_theory,
    probability_at,
    theory_text,
)
from probanchor.learning.motion_parameters import DESCRIPTIONS, Fitted
from probanchor.learning.motion_samples import samples_path
from probanchor.learning.occlusion_affordances import (
    MIN_SHARE,
    Affordance,
    affordance_clauses,
    affordance_table,
    affordances,
    never_occluders,
)
from probanchor.learning.occlusion_data import LabelOptions
from probanchor.learning.occlusion_reach import OnsetReach, onset_reach
from probanchor.learning.release_data import release_path
from probanchor.loop.reasoning import DEFAULT_THEORY
from probanchor.loop.theories import THEORIES, theory_path

ROOT = Path(__file__).resolve().parents[1]
PROLOG = DEFAULT_THEORY.parent / "too"
REACH = OnsetReach(0.15, 0.12, 1)
#: The hand-written values, as if fitted.
HAND = {m[1]: float(m[2]) for m in re.finditer(r"^(\w+)\(([-\d.eE+]+)\)\.",
                                                (PROLOG / "too_parameters.pl").read_text(), re.M)}
FITTED = [Fitted(name, HAND.get(name, 1e-6), 1) for name in DESCRIPTIONS]
#: Affordances as the data show them (occlusion_affordances.py).
FOUND = {"hides": {"ball": Affordance(1e-4, 9000), "bowl": Affordance(0.2, 900),
                   "mug": Affordance(0.1, 9000),
                   "skin": Affordance(0.4, 900)},
         "hidden": {"ball": Affordance(0.2, 9000), "bottle": Affordance(0.1, 900),
                    "mug": Affordance(0.04, 900), "skin": Affordance(1e-5, 900)},
         "carries": {"skin": Affordance(0.99, 900)}}

LEARNED = """% learned (a header of the learner's)

occluder(A, O):t+1 ~ finite([0.9:true, 0.1:false]) :=
    pair(A, O):t+1, occluded_by(A, O):t.
occluder(A, O):t+1 ~ finite([0.2:true, 0.8:false]) :=
    pair(A, O):t+1, \\+ occluded_by(A, O):t.
"""

RELEASE = """% learned (a header of the learner's)

released(A):t+1 ~ finite([0.7:true, 0.3:false]) :=
    carried(A):t+1.
"""


def test_the_theory_includes_the_hand_written_parts(tmp_path: Path) -> None:
    out = tmp_path / "sub" / "too_learned.pl"
    text = theory_text(LEARNED, "% header\n", base=PROLOG, out=out, reach=REACH, found=FOUND,
                       fitted=FITTED, release_program=RELEASE)
    hand = DEFAULT_THEORY.read_text()
    for name in (*BEFORE, *AFTER):
        assert f":- include('too/{name.removesuffix('.pl')}')." in hand    # too.pl's parts
    # too.pl's hand-written release, the learned theory's learned one
    assert ":- include('too/too_release')." in hand and "too_release" not in text
    assert "released(A):t+1 ~ finite([0.7:true" in text
    for gone in ("release_p(", "release_margin(", "lift_margin(", "raised(A)"):
        assert gone not in text
    includes = [line for line in text.splitlines() if line.startswith(":- include(")]
    assert len(includes) == len(BEFORE) + 1 + len(AFTER)
    for line, name in zip(includes, (*BEFORE, GLUE, *AFTER), strict=True):
        rel = line.removeprefix(":- include('").removesuffix("').")
        assert (out.parent / rel).resolve() == (PROLOG / name).resolve()
    # no text of too.pl or of its parts is repeated: only the learned rules and parameters
    for gone in ("covers(O, A):t+1 :=", "lowered_over(O, A):t+1 :=", "cannot_occlude(ball)",
                 "pos(A):t+1 ~ gaussian", "carrier(skin) := true", "pick_occluder",
                 "cover_height("):
        assert gone not in text
    assert "occluder_candidate(A, O):t+1 :=\n    pair(A, O):t+1" in (PROLOG / GLUE).read_text()
    for name in DESCRIPTIONS:            # every parameter the theory reads, as a fact
        assert re.search(rf"^{name}\([-\d.e]+\)\.", text, re.M), name
    assert text.index(includes[-1]) > text.index("released(A):t+1 ~ finite([0.7:true") \
        > text.index("occluder(A, O):t+1 ~ finite([0.9:true") > text.index(includes[1])
    # without carries in the data: no release, and a comment says why
    bare = theory_text(LEARNED, "% header\n", base=PROLOG, out=out, reach=REACH, found=FOUND,
                       fitted=FITTED, release_program=None)
    assert "released(" not in bare.replace("released(A):t+1 ~= true", "")
    assert "no release learned" in bare


def test_a_base_without_the_hand_written_parts_is_an_error(tmp_path: Path) -> None:
    with pytest.raises(TheoryError, match="too_motion.pl"):
        (tmp_path / "too_base.pl").write_text("x ~ val(1).\n")
        (tmp_path / GLUE).write_text("y ~ val(1).\n")
        theory_text(LEARNED, "", base=tmp_path, out=tmp_path / "t.pl", reach=REACH, found=FOUND,
                    fitted=FITTED, release_program=RELEASE)


def test_the_assembled_theory_loads_and_filters(tmp_path: Path) -> None:
    path = tmp_path / "too_learned.pl"
    path.write_text(theory_text(LEARNED, "", base=PROLOG, out=path, reach=REACH, found=FOUND,
                                fitted=FITTED, release_program=RELEASE))
    f = bridge.Filter(path, particles=200, seed=1, threads=1)
    actions = ["object(ball_1)", "category(ball_1, ball)", "object(mug_1)",
               "category(mug_1, mug)", "object(ball_2)", "category(ball_2, ball)"]
    ball_2 = ["observed(ball_2)", "observation(pos(ball_2)) ~= (0.02, 0.0, 0.03)"]
    f.step(["observed(ball_1)", "observation(pos(ball_1)) ~= (0.0, 0.0, 0.03)",
            "observed(mug_1)", "observation(pos(mug_1)) ~= (0.0, 0.0, 0.05)", *ball_2],
           actions=actions)
    f.step(["observed(mug_1)", "observation(pos(mug_1)) ~= (0.0, 0.0, 0.05)", *ball_2],
           actions=actions)
    # just vanished: the one candidate drawn with 0.2; under nothing when it is not (the
    # tree's share: no `behind` choice besides)
    p = f.probability("occluded_by(ball_1, mug_1):t")
    assert abs(p - 0.2) < 4.5 * (0.2 * 0.8 / 200) ** 0.5   # 4.5 standard errors at N = 200
    # the other ball is no candidate (a ball affords hiding nothing), however near it is
    assert f.probability("occluded_by(ball_1, ball_2):t") == 0.0
    f.close()


def test_a_leaf_along_the_distance_sums_its_distance_weights() -> None:
    """Both distances of a leaf (table plane and 3-D, equal at equal heights) make its slope;
    other regressors (lift) are at 0; the bias is the last weight."""
    leaf = {"regressors": ["Lift", "Distance4", "Distance32"], "weights": [5.0, -10.0, -4.0, 1.5]}
    assert along_distance(leaf) == (-14.0, 1.5)
    d = np.array([0.0, 0.1])
    assert probability_at(leaf, d) == pytest.approx(1 / (1 + np.exp(-(1.5 - 14.0 * d))))


def test_shipped_theories_by_name() -> None:
    assert theory_path("hand") == DEFAULT_THEORY
    assert theory_path("learned") == THEORIES["learned"]
    assert theory_path("prolog/examples/x.pl") == Path("prolog/examples/x.pl")
    for name in ("learned", "hindsight"):
        assert THEORIES[name].is_file(), f"{THEORIES[name]} ships (make learned-theory)"
        bridge.load(THEORIES[name])                    # it loads in the engine


@pytest.fixture(scope="module")
def game_data(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """One short generated game, collected with ground-truth labels (perception included)."""
    folder = tmp_path_factory.mktemp("collect")
    out = folder / "data.pl"
    report = collect(CollectOptions(out=out, games=1, seed=22, cache=folder / "cache",
                                    labels=LabelOptions(source="truth")))
    assert report.episodes == 1 and report.pairs > 0 and report.positive > 0
    assert report.agreement is not None and 0.5 < report.agreement <= 1.0
    return out


def test_learn_theory_writes_a_theory_that_loads(game_data: Path, tmp_path: Path) -> None:
    out = tmp_path / "too_learned.pl"
    result = learn_theory([game_data], out, seed=0, command="anchoring learn-theory ...")
    text = out.read_text()
    assert text.startswith("/*  too_learned.pl -- the theory of occlusion with rules learned")
    assert "occluder(Occluded, Occluder):t+1 ~ finite(" in text
    assert "pair(Occluded, Occluder):t+1" in text
    assert result.result.targets[0].clauses >= 1
    bridge.load(out)


def test_data_collected_apart_are_learned_from_together(game_data: Path,
                                                         tmp_path: Path) -> None:
    """Two collections of the same game, written to files of other names: their constants
    (which name the collection) are apart, so learning from both has twice the data points
    (with the same constants, the second file's facts would be taken for the first's worlds)."""
    import re

    more = tmp_path / "more.pl"
    collect(CollectOptions(out=more, games=1, seed=22, cache=game_data.parent / "cache",
                           labels=LabelOptions(source="truth")))
    pattern = re.compile(r"^pair\(([a-z0-9_]+), ([a-z0-9_]+)\):t\+1\.$", re.M)
    first = {a for pair in pattern.findall(game_data.read_text()) for a in pair}
    second = {a for pair in pattern.findall(more.read_text()) for a in pair}
    assert first and second and not first & second
    assert all("_data_e0_" in c for c in first) and all("_more_e0_" in c for c in second)
    held = re.compile(r"^carried\(([a-z0-9_]+)\):t\+1\.$", re.M)
    assert not (set(held.findall(release_path(game_data).read_text()))
                & set(held.findall(release_path(more).read_text())))
    one = learn_theory([game_data], tmp_path / "one.pl", seed=0)
    both = learn_theory([game_data, more], tmp_path / "both.pl", seed=0)
    assert both.result.targets[0].groundings == 2 * one.result.targets[0].groundings


def test_a_failed_learn_theory_keeps_the_previous_file(game_data: Path, tmp_path: Path) -> None:
    out = tmp_path / "too_learned.pl"
    out.write_text("% the previous theory\n")
    bad = tmp_path / "bad.pl"
    bad.write_text(game_data.read_text() + "category(ball_1_e0_f3, ball, extra).\n"
                   "distance(x, y):t+1 ~= near.\n")
    samples_path(bad).write_text(samples_path(game_data).read_text())
    with pytest.raises(TheoryError, match=rf"{release_path(bad)}: no release data"):
        learn_theory([bad], out)
    release_path(bad).write_text(release_path(game_data).read_text())
    with pytest.raises(bridge.DDCError, match=rf"{bad}:\d+: .*not a number"):
        learn_theory([bad], out)
    assert out.read_text() == "% the previous theory\n"
    broken_base = tmp_path / "base"
    broken_base.mkdir()
    for name in (*BEFORE, GLUE, *AFTER, "too_parameters.pl"):
        (broken_base / name).write_text((PROLOG / name).read_text())
    base_file = broken_base / "too_base.pl"
    base_file.write_text(base_file.read_text().replace(
        "diagonal(V, [V, 0, 0, 0, V, 0, 0, 0, V]).", "diagonal(V, [V, 0, 0, 0, V, 0, 0, 0, V)."))
    line = base_file.read_text().splitlines().index("diagonal(V, [V, 0, 0, 0, V, 0, 0, 0, V).")
    # the error names the included file and its line
    with pytest.raises(TheoryError, match=rf"does not load: {base_file}:{line + 1}: syntax error"):
        learn_theory([game_data], out, base=broken_base)
    assert out.read_text() == "% the previous theory\n"
    assert list(tmp_path.glob(".too_learned.pl.*")) == []


def test_an_empty_collection_is_an_error(tmp_path: Path) -> None:
    out = tmp_path / "data.pl"
    with pytest.raises(CollectError, match="no occlusion happened"):
        collect(CollectOptions(out=out, scenarios=[ROOT / "scenarios" / "static.yaml"],
                               cache=tmp_path / "cache"))
    assert not out.exists()
    with pytest.raises(CollectError, match="nothing to collect"):
        collect(CollectOptions(out=out, cache=tmp_path / "cache"))


def test_the_commands(game_data: Path, tmp_path: Path) -> None:
    import io
    from contextlib import redirect_stderr, redirect_stdout

    from probanchor.cli.anchoring_cli import main

    def anchoring(*args: str | Path) -> Run:
        out, err = io.StringIO(), io.StringIO()
        with redirect_stdout(out), redirect_stderr(err):
            code = main([str(a) for a in args])
        return Run(code, out.getvalue(), err.getvalue())

    theory = tmp_path / "learned.pl"
    run = anchoring("learn-theory", game_data, "--out", theory, "--plots", tmp_path, "--json")
    assert run.returncode == 0, run.stderr
    report = json.loads(run.stdout)
    assert report["clauses"] >= 1 and theory.is_file()
    assert (tmp_path / "learned_tree.png").stat().st_size > 1000
    assert (tmp_path / "learned_distance.png").stat().st_size > 1000
    parameters = (tmp_path / "learned_parameters.md").read_text().splitlines()
    assert parameters[2].startswith("| onset reach (m)")
    assert "| 0.15 (`occluder_reach`) |" in parameters[2]
    assert parameters[4].startswith("| parameter | learned | hand-written | what it is")
    fitted = parameters[6:6 + len(DESCRIPTIONS)]
    assert [row.split(" | ")[0] for row in fitted] == [f"| `{n}`" for n in DESCRIPTIONS]
    assert report["parameters"].keys() == DESCRIPTIONS.keys()
    # the release: learned from the game's carries, or none when no hand carried anything
    has_release = "released(Held):t+1 ~ finite(" in theory.read_text()
    assert (report["release"] is not None) == has_release
    if has_release:
        assert report["release"]["clauses"] >= 1 and report["release"]["groundings"] > 0
    assert (tmp_path / "learned_motion.png").stat().st_size > 1000
    k = parameters.index("", 6)
    assert parameters[k + 1].startswith("| kind | P(it hides a hidden object)")
    table = (tmp_path / "learned_coefficients.md").read_text().splitlines()
    assert table[2] == "| paper (section 4) |  | -16.9 | 0.80 | 0.69 | 0.49 | 0.29 |"
    learned = [line for line in table if line.startswith("| learned")]
    heaviest = sorted(report["logistic_leaves"], key=lambda leaf: -leaf["weight"])[:6]
    assert len(learned) == len(heaviest)
    for line, leaf in zip(learned, heaviest, strict=True):
        slope, bias = along_distance(leaf)
        assert line.split(" | ")[2:4] == [f"{slope:.1f}", f"{bias:.2f}"]
    bad = anchoring("collect", "--out", tmp_path / "x.pl")
    assert bad.returncode == 1 and "nothing to collect" in bad.stderr


def test_the_onset_reach_is_fitted_from_the_onsets(tmp_path: Path) -> None:
    """The distance within which the quantile of the onsets (labelled covered, not known
    covered at t, not lost, the ideal particle's state) lie, times the margin; continuations,
    lost objects, a lost particle's copy (``_c``), unlabelled pairs and excluded occluders'
    kinds do not count."""
    data = tmp_path / "data.pl"
    data.write_text("\n".join([
        "pos(a):t ~= (0.0000, 0.0000, 0.0300).", "pos(o):t+1 ~= (0.0600, 0.0800, 0.0500).",
        "pair(a, o):t+1.", "occluder(a, o):t+1.",                        # onset at 0.10 m
        "pos(b):t ~= (0.0000, 0.0000, 0.0300).", "pos(p):t+1 ~= (0.0300, 0.0400, 0.0500).",
        "pair(b, p):t+1.", "0.7 :: occluder(b, p):t+1.",                 # onset at 0.05 m
        "pos(c):t ~= (0.0000, 0.0000, 0.0300).", "pos(q):t+1 ~= (0.9000, 0.0000, 0.0500).",
        "occluded_by(c, q):t.", "pair(c, q):t+1.", "occluder(c, q):t+1.",  # goes on: not one
        "pos(d):t ~= (0.0000, 0.0000, 0.0300).", "lost_anywhere(d):t.",
        "pair(d, q):t+1.", "occluder(d, q):t+1.",                        # lost: not one
        "pos(a_c):t ~= (0.5000, 0.0000, 0.0300).",
        "pair(a_c, o):t+1.", "occluder(a_c, o):t+1.",                    # a lost copy
        "pos(e):t ~= (0.0000, 0.0000, 0.0300).",
        "pair(e, q):t+1.", "0.2 :: occluder(e, q):t+1.",                 # unlikely: not one
        "pos(h):t+1 ~= (0.9000, 0.0000, 0.0900).", "category(h, skin).",
        "pair(b, h):t+1.", "occluder(b, h):t+1.",                        # a carrier: excluded
    ]) + "\n")
    fitted = onset_reach([data], exclude=["skin"], quantile=0.95, margin=1.25)
    assert fitted.onsets == 2
    assert fitted.quantile == pytest.approx(0.1)
    assert fitted.reach == pytest.approx(0.125)
    assert onset_reach([data], exclude=["skin"], quantile=0.5).quantile == pytest.approx(0.05)
    assert onset_reach([data]).onsets == 3

    empty = tmp_path / "empty.pl"
    empty.write_text("pair(a, o):t+1.\n")
    with pytest.raises(ValueError, match="no occlusion onset"):
        onset_reach([empty])


def test_without_an_onset_the_reach_is_the_hand_written_one_marked_not_fitted(
        tmp_path: Path) -> None:
    """A few games where only hands took objects have no onset to fit the reach from: the
    theory keeps too_parameters.pl's occluder_reach and says so, as for a parameter without
    samples."""
    from probanchor.learning.learned_theory import parameter_table

    reach = OnsetReach(HAND["occluder_reach"], float("nan"), 0)
    path = tmp_path / "too_learned.pl"
    text = theory_text(LEARNED, "", base=PROLOG, out=path, reach=reach, found=FOUND,
                       fitted=FITTED, release_program=RELEASE)
    assert "NOT FITTED" in text and f"onset_reach({HAND['occluder_reach']:.4g})." in text
    assert "none: not fitted" in parameter_table(reach, PROLOG)


def test_a_kind_with_onsets_enough_has_a_reach_of_its_own(tmp_path: Path) -> None:
    """Bowls start covering from farther than mugs: with ``min_onsets`` onsets a kind's reach
    is fitted from its own; a kind with fewer has the reach of all the onsets."""
    lines = []
    for k, (kind, d) in enumerate([("bowl", 0.12)] * 3 + [("mug", 0.03)] * 3 + [("cup", 0.02)]):
        lines += [f"pos(a{k}):t ~= (0.0, 0.0, 0.03).", f"pos(o{k}):t+1 ~= ({d}, 0.0, 0.05).",
                  f"category(o{k}, {kind}).", f"pair(a{k}, o{k}):t+1.",
                  f"occluder(a{k}, o{k}):t+1."]
    data = tmp_path / "data.pl"
    data.write_text("\n".join(lines) + "\n")
    fitted = onset_reach([data], quantile=0.5, margin=2.0, min_onsets=3)
    assert fitted.onsets == 7 and fitted.quantile == pytest.approx(0.03)
    assert sorted(fitted.kinds) == ["bowl", "mug"]
    assert fitted.of("bowl") == pytest.approx(0.24) and fitted.of("mug") == pytest.approx(0.06)
    assert fitted.of("cup") == fitted.of("box") == fitted.of(None) == pytest.approx(0.06)
    assert onset_reach([data], min_onsets=4).kinds == {}


def test_the_tree_is_learned_from_the_pairs_the_filter_asks_about(tmp_path: Path) -> None:
    """Beyond its kind's reach, a pair neither known nor lost is no example (a lost
    particle's copy carried off with its container gave a mug positives a metre away); the
    copies keep their line numbers, and the pairs known at t or lost anywhere stay."""
    from probanchor.learning.occlusion_asked import asked, asked_data
    from probanchor.learning.occlusion_reach import read_points

    data = tmp_path / "data.pl"
    data.write_text("\n".join([
        "category(m, mug).", "category(w, bowl).",
        "pos(a):t ~= (0.0, 0.0, 0.03).", "pos(m):t+1 ~= (0.08, 0.0, 0.05).",
        "pos(w):t+1 ~= (0.08, 0.0, 0.04).",
        "pair(a, m):t+1.", "weight(occluder(a, m):t+1, 5).",          # beyond the mug's reach
        "pair(a, w):t+1.",                                             # within the bowl's
        "pos(a_c):t ~= (0.5, 0.0, 0.03).", "pair(a_c, m):t+1.", "occluder(a_c, m):t+1.",
        "pos(b):t ~= (0.9, 0.0, 0.03).", "occluded_by(b, m):t.", "pair(b, m):t+1.",
        "occluder(b, m):t+1.",                                         # known: asked
        "pos(d):t ~= (0.9, 0.0, 0.03).", "lost_anywhere(d):t.", "pair(d, m):t+1.",  # lost
    ]) + "\n")
    reach = OnsetReach(0.06, 0.03, 4, kinds={"bowl": OnsetReach(0.2, 0.1, 4)})
    points = read_points([data])
    assert asked(points, reach) == {("a", "w"), ("b", "m"), ("d", "m")}
    (copy,), dropped = asked_data([data], points, reach, tmp_path / "asked")
    assert dropped == 2 and copy.name == "data.pl" and copy.parent.parent == tmp_path / "asked"
    before, after = data.read_text().splitlines(), copy.read_text().splitlines()
    assert len(after) == len(before)
    assert [k for k, (x, y) in enumerate(zip(before, after, strict=True)) if x != y] == \
        [5, 6, 9, 10]
    assert all(after[k] == "" for k in (5, 6, 9, 10))


def test_pairs_beyond_the_reach_draw_nothing(tmp_path: Path) -> None:
    """A mug beyond the onset reach of where a ball vanished is no candidate in any particle;
    within it, it is one in about 0.2 x 1/2 of them."""
    path = tmp_path / "too_learned.pl"
    path.write_text(theory_text(LEARNED, "", base=PROLOG, out=path,
                                reach=OnsetReach(0.1, 0.08, 1), found=FOUND, fitted=FITTED,
                                release_program=RELEASE))
    f = bridge.Filter(path, particles=200, seed=1, threads=1)
    actions = ["object(ball_1)", "category(ball_1, ball)", "object(mug_1)",
               "category(mug_1, mug)", "object(mug_2)", "category(mug_2, mug)"]
    mugs = ["observed(mug_1)", "observation(pos(mug_1)) ~= (0.05, 0.0, 0.05)",
            "observed(mug_2)", "observation(pos(mug_2)) ~= (0.0, 0.2, 0.05)"]
    f.step(["observed(ball_1)", "observation(pos(ball_1)) ~= (0.0, 0.0, 0.03)", *mugs],
           actions=actions)
    f.step(mugs, actions=actions)
    assert 0.1 * 0.5 < f.probability("occluded_by(ball_1, mug_1):t") < 0.2
    assert f.probability("occluded_by(ball_1, mug_2):t") == 0.0
    f.close()


def test_a_grip_is_measured_from_the_top_of_its_kind(tmp_path: Path) -> None:
    """A hand closing on a bottle 20 cm tall grips it 17 cm above its centre, 7 cm above its
    top: within grip_height (10 cm) of the top of a kind 20 cm tall, the hand may have taken
    it; a theory without the kinds' heights measures from the centre, and it may not."""
    from probanchor.learning.motion_parameters import kind_height_clauses

    probability = {}
    for name, heights in (("heights", {"bottle": (0.2, 50)}), ("none", None)):
        path = tmp_path / f"too_{name}.pl"
        path.write_text(theory_text(LEARNED, "", base=PROLOG, out=path, reach=REACH,
                                    found=FOUND, fitted=FITTED, release_program=RELEASE,
                                    heights=heights))
        assert ("kind_height(bottle, 0.2)." in path.read_text()) == (heights is not None)
        probability[name] = _vanished_under(path, ("bottle_1", "bottle", (0.0, 0.0, 0.1)),
                                            ("skin_1", "skin", (0.01, 0.0, 0.27)))
    assert probability["heights"] > 0.2 and probability["none"] == 0.0
    assert kind_height_clauses({}).count("kind_height(") == 0


def test_a_kind_s_own_reach_decides_whether_it_is_asked(tmp_path: Path) -> None:
    """The same bowl 20 cm from where a ball vanished is a candidate with a bowl's reach of its
    own (25 cm) and none with the reach of all onsets (10 cm)."""
    probability = {}
    for name, kinds in (("own", {"bowl": OnsetReach(0.25, 0.12, 10)}), ("all", {})):
        path = tmp_path / f"too_{name}.pl"
        path.write_text(theory_text(LEARNED, "", base=PROLOG, out=path,
                                    reach=OnsetReach(0.1, 0.05, 20, kinds=kinds), found=FOUND,
                                    fitted=FITTED, release_program=RELEASE))
        probability[name] = _vanished_under(path, ("ball_1", "ball", (0.0, 0.0, 0.03)),
                                            ("bowl_1", "bowl", (0.2, 0.0, 0.04)))
    assert probability["own"] > 0.0 and probability["all"] == 0.0


def _vanished_under(theory: Path, hidden: tuple[str, str, tuple[float, float, float]],
                    other: tuple[str, str, tuple[float, float, float]]) -> float:
    """P(``hidden`` is under ``other``) one frame after it vanished; each is (atom, category,
    position), ``other`` perceived at its position in both frames (200 particles)."""
    f = bridge.Filter(theory, particles=200, seed=1, threads=1)
    actions = [f"object({a})" for a, _, _ in (hidden, other)]
    actions += [f"category({a}, {c})" for a, c, _ in (hidden, other)]

    def seen(a: str, p: tuple[float, float, float]) -> list[str]:
        return [f"observed({a})", f"observation(pos({a})) ~= ({p[0]}, {p[1]}, {p[2]})"]

    f.step([*seen(hidden[0], hidden[2]), *seen(other[0], other[2])], actions=actions)
    f.step(seen(other[0], other[2]), actions=actions)
    probability = f.probability(f"occluded_by({hidden[0]}, {other[0]}):t")
    f.close()
    return probability


ENDS_AT_ONCE = """% learned (a header of the learner's)

occluder(A, O):t+1 ~ finite([0.0:true, 1.0:false]) :=
    pair(A, O):t+1, occluded_by(A, O):t.
occluder(A, O):t+1 ~ finite([0.5:true, 0.5:false]) :=
    pair(A, O):t+1, \\+ occluded_by(A, O):t.
"""


def test_an_occluder_back_in_view_still_hides_what_it_hid(tmp_path: Path) -> None:
    """A tree that ends every occlusion: a ball under a mug through a blind frame is still under
    it in the frame the mug reappears (far away), and the tree decides from the next frame.
    (An object behind nothing while the camera saw nothing is lost anywhere: any occluder may
    take it.)"""
    path = tmp_path / "too_learned.pl"
    path.write_text(theory_text(ENDS_AT_ONCE, "", base=PROLOG, out=path, reach=REACH, found=FOUND,
                                fitted=FITTED, release_program=RELEASE))
    f = bridge.Filter(path, particles=200, seed=1, threads=1)
    actions = ["object(ball_1)", "category(ball_1, ball)", "object(mug_1)",
               "category(mug_1, mug)"]
    mug = ["observed(mug_1)", "observation(pos(mug_1)) ~= (0.05, 0.0, 0.05)"]
    far = ["observed(mug_1)", "observation(pos(mug_1)) ~= (0.4, 0.3, 0.05)"]
    f.step(["observed(ball_1)", "observation(pos(ball_1)) ~= (0.0, 0.0, 0.03)", *mug],
           actions=actions)
    f.step(mug, actions=actions)                   # vanished: under the mug (the tree's 1/2)
    under = f.probability("occluded_by(ball_1, mug_1):t")
    assert 0.3 < under < 0.7
    f.step([], actions=actions)                    # blind: the transitive clause keeps it
    assert f.probability("occluded_by(ball_1, mug_1):t") == pytest.approx(under, abs=0.15)
    # back in view, far away: the particles that had it under the mug still do (the tree would
    # end it), those that had it under nothing, lost while blind, take the mug as any
    # occluder (the tree's 1/2): 1/2 + 1/2 * 1/2, within 4.5 standard errors at N = 200
    f.step(far, actions=actions)
    p = f.probability("occluded_by(ball_1, mug_1):t")
    assert abs(p - 0.75) < 4.5 * (0.75 * 0.25 / 200) ** 0.5
    # the tree decides again: every occlusion going on ends, the particles that had the ball
    # under nothing take the mug with its 1/2 (1/4 * 1/2)
    f.step(far, actions=actions)
    p = f.probability("occluded_by(ball_1, mug_1):t")
    assert abs(p - 0.125) < 4.5 * (0.125 * 0.875 / 200) ** 0.5
    f.close()


def test_affordances_are_shares_of_the_data_with_a_uniform_prior(tmp_path: Path) -> None:
    """P(hides): covered pairs' weight over all pairs' (Laplace's rule); P(carries): of the
    occlusions going on with O lifted off (its centre more than LIFT above where A stood)."""
    data = tmp_path / "data.pl"
    lines = ["category(b, ball).", "category(m, mug).", "category(h, skin).",
             "pos(a):t ~= (0.0000, 0.0000, 0.0300).",
             "pos(b):t+1 ~= (0.0100, 0.0000, 0.0300).", "pair(a, b):t+1.",
             "weight(occluder(a, b):t+1, 8).",                   # a ball: 8 pairs, none covered
             "pos(m):t+1 ~= (0.0000, 0.0000, 0.0500).", "pair(a, m):t+1.", "occluder(a, m):t+1.",
             "pos(c):t ~= (0.0000, 0.0000, 0.0300).", "occluded_by(c, h):t.",
             "pos(h):t+1 ~= (0.0000, 0.0000, 0.2500).", "pair(c, h):t+1.", "occluder(c, h):t+1.",
             "pos(e):t ~= (0.0000, 0.0000, 0.0300).", "occluded_by(e, m):t.",
             "pair(e, m):t+1."]                                   # the mug at 5 cm: not lifted
    data.write_text("\n".join(lines) + "\n")
    found = affordances([data])
    assert found["hides"]["ball"] == Affordance(1 / 10, 8)
    assert found["hides"]["mug"] == Affordance(2 / 4, 2)
    assert found["carries"] == {"skin": Affordance(2 / 3, 1)}
    table = affordance_table(found).splitlines()
    assert table[2] == "| ball | 0.1 (8) | - | - |"


def test_the_learned_affordances_decide_who_is_asked(tmp_path: Path) -> None:
    """From the data's probabilities: a ball hides too rarely to be asked about, a mug is, a
    hand carries (so is no container), a hand is never asked about as hidden."""
    clauses = affordance_clauses(FOUND)
    assert "hides(ball, 0.0001).  % 9,000" in clauses
    assert never_occluders(FOUND) == ["ball", "skin"]
    path = tmp_path / "affordances.pl"
    path.write_text(clauses + "category(b, ball). category(m, mug). category(h, skin).\n"
                    "object(b). object(m). object(h).\n")
    program = bridge.load(path)

    def holds(goal: str) -> bool:
        return program.query(goal, samples=1, seed=0).probability == 1.0

    assert holds("can_occlude(m)") and not holds("can_occlude(b)")
    assert not holds("can_occlude(h)")
    assert holds("is_carrier(h)") and not holds("is_carrier(m)")
    assert holds("hand_known")
    assert holds("can_be_occluded(b)") and not holds("can_be_occluded(h)")


@pytest.mark.parametrize("name", ["learned", "hindsight"])
def test_the_shipped_learned_theories_have_no_hand_written_affordance(name: str) -> None:
    """The shipped learned theories include neither too.pl's affordances nor its occlusion
    rules, and their affordances, read from the data, say with probabilities that balls, cans
    and bottles hide nothing (below MIN_SHARE), that containers do, and that hands carry."""
    text = THEORIES[name].read_text()
    includes = re.findall(r"^:- include\('([^']+)'\)\.", text, re.M)
    assert includes == [f"too/{name}" for name in (*BEFORE, GLUE, *AFTER)]
    assert "too_affordances" not in text and "cannot_occlude(" not in text
    probability = {(m[0], m[1]): float(m[2])
                   for m in re.findall(r"^(hides|carries)\((\w+), ([\d.e-]+)\)\.", text, re.M)}
    for kind in ("ball", "can", "bottle"):
        assert probability[("hides", kind)] < MIN_SHARE, kind
    for kind in ("box", "bowl", "cup", "mug"):
        assert probability[("hides", kind)] > MIN_SHARE, kind
    assert probability[("hides", "box")] > 10 * MIN_SHARE
    assert probability[("carries", "skin")] > 0.9


def test_without_a_carrier_in_the_data_nothing_is_one(tmp_path: Path, capfd) -> None:
    """Data without hands (no kind carries): the affordances say so, and the theory loads
    without a warning of an undefined carrier/1."""
    found = {**FOUND, "carries": {}}
    path = tmp_path / "affordances.pl"
    path.write_text(affordance_clauses(found) + "category(h, skin). object(h).\n")
    program = bridge.load(path)
    assert program.query("\\+ is_carrier(h)", samples=1, seed=0).probability == 1.0
    assert program.query("\\+ hand_known", samples=1, seed=0).probability == 1.0
    assert "carrier/1" not in capfd.readouterr().err


def test_far_out_onsets_do_not_stretch_the_reach(tmp_path: Path) -> None:
    """Onsets far beyond the others (of objects a particle had lost track of, found again far
    from where they were last seen) are left out before the quantile, as the grip reach's far
    events: 14 boxes' onsets within 4 cm and 3 at 24 cm give a reach from the 14."""
    near = [0.005 * (k + 1) for k in range(8)] + [0.01, 0.015, 0.02, 0.025, 0.03, 0.04]
    lines = []
    for k, d in enumerate(near + [0.24, 0.245, 0.25]):
        lines += [f"pos(a{k}):t ~= (0.0, 0.0, 0.03).", f"pos(o{k}):t+1 ~= ({d}, 0.0, 0.05).",
                  f"category(o{k}, box).", f"pair(a{k}, o{k}):t+1.", f"occluder(a{k}, o{k}):t+1."]
    data = tmp_path / "data.pl"
    data.write_text("\n".join(lines) + "\n")
    fitted = onset_reach([data], min_onsets=10)
    kept = sorted(near)
    q = kept[math.ceil(0.9 * len(kept)) - 1]
    assert fitted.onsets == 17 and fitted.far_out == 3
    assert fitted.quantile == pytest.approx(q) and fitted.of("box") == pytest.approx(2 * q)
    # without the fence the 90 % quantile is one of the far ones
    assert onset_reach([data], far=float("inf")).quantile == pytest.approx(0.245)


def hidden_ball_spread(path: Path, axis: int, seen: int = 4, speed: float = 0.0,
                       particles: int = 400, seed: int = 2) -> tuple[float, np.ndarray]:
    """A ball beside a box perceived ``seen`` frames (moving ``speed`` a frame along x), then
    hidden under nothing for ten: its particles' standard deviation along ``axis``, and their
    positions."""
    f = bridge.Filter(path, particles=particles, seed=seed, threads=1)
    actions = ["object(ball_1)", "category(ball_1, ball)", "object(box_1)",
               "category(box_1, box)"]
    box = ["observed(box_1)", "observation(pos(box_1)) ~= (0.5, 0.3, 0.06)"]
    for k in range(seen):
        f.step([*box, "observed(ball_1)",
                f"observation(pos(ball_1)) ~= ({speed * k}, 0.0, 0.03)"], actions=actions)
    for _ in range(10):
        f.step(box, actions=actions)
    xyz, w = f.samples("P", "pos(ball_1):t ~= P")
    f.close()
    x = xyz[:, axis]
    return float(np.sqrt(np.average((x - np.average(x, weights=w)) ** 2, weights=w))), xyz


def test_a_hidden_object_that_stood_still_rests_and_one_that_moved_coasts(
        tmp_path: Path) -> None:
    """A ball hidden under nothing spreads by rest_var a frame if it stood still as it
    vanished, by wander_var if it was moving (at moving_speed or faster): ten frames later
    its particles' spread is that of ten steps of its own variance (400 particles)."""
    from dataclasses import replace

    rest, wander = 0.001 ** 2, 0.01 ** 2
    fitted = [replace(f, value={"rest_var": rest, "wander_var": wander}.get(f.name, f.value))
              for f in FITTED]
    path = tmp_path / "too_learned.pl"
    path.write_text(theory_text(LEARNED, "", base=PROLOG, out=path, reach=REACH, found=FOUND,
                                fitted=fitted, release_program=RELEASE))
    assert "moving_speed(" in path.read_text()
    spread = {name: hidden_ball_spread(path, axis=1, speed=speed)[0]
              for name, speed in (("still", 0.0), ("moving", 0.01))}
    # the standard deviation of 400 samples' standard deviation: about 1/sqrt(800) of it
    tolerance = 4 / np.sqrt(800)
    assert spread["still"] == pytest.approx(np.sqrt(10 * rest), rel=tolerance)
    assert spread["moving"] == pytest.approx(np.sqrt(10 * wander), rel=tolerance)


def test_a_theory_written_before_rest_var_spreads_every_hidden_object_by_its_wander(
        tmp_path: Path) -> None:
    """A learned theory of an older version has no rest_var/1 and no moving_speed/1: it loads
    (with a warning naming them) and a hidden object still has a belief, spread by wander_var."""
    path = tmp_path / "too_old.pl"
    text = theory_text(LEARNED, "", base=PROLOG, out=path, reach=REACH, found=FOUND,
                       fitted=[f for f in FITTED if f.name != "rest_var"],
                       release_program=RELEASE)
    path.write_text("\n".join(line for line in text.splitlines()
                              if not line.startswith("moving_speed(")) + "\n")
    spread, xyz = hidden_ball_spread(path, axis=0, seen=1, particles=200, seed=3)
    assert not np.isnan(xyz).any()
    wander = next(x.value for x in FITTED if x.name == "wander_var")
    assert spread == pytest.approx(np.sqrt(10 * wander), rel=4 / np.sqrt(400))


def test_a_hidden_object_height_spreads_by_height_var(tmp_path: Path) -> None:
    """A ball standing still behind a box: ten frames later its particles' heights spread by
    ten steps of height_var when the theory has it, by ten of a hundredth of rest_var (too.pl's
    rule) when it has none (400 particles)."""
    from dataclasses import replace

    rest, height = 0.004 ** 2, 0.002 ** 2
    spread = {}
    for name, fitted in (
            ("fitted", [replace(f, value={"rest_var": rest, "height_var": height}.get(
                f.name, f.value)) for f in FITTED]),
            ("none", [replace(f, value=rest) if f.name == "rest_var" else f
                      for f in FITTED if f.name != "height_var"])):
        path = tmp_path / f"too_{name}.pl"
        path.write_text(theory_text(LEARNED, "", base=PROLOG, out=path, reach=REACH,
                                    found=FOUND, fitted=fitted, release_program=RELEASE))
        assert ("height_var(" in path.read_text()) == (name == "fitted")
        spread[name] = hidden_ball_spread(path, axis=2)[0]
    tolerance = 4 / np.sqrt(800)     # the relative error of 400 samples' standard deviation
    assert spread["fitted"] == pytest.approx(np.sqrt(10 * height), rel=tolerance)
    assert spread["none"] == pytest.approx(np.sqrt(10 * rest / 100), rel=tolerance)
