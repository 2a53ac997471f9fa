"""`ddc learn` / `ddc evaluate` end to end, and the learner's promises on its output.

The data: a Boolean target whose probability is the paper's logistic on a distance, gated by an
observed flag and by the occluder's category (a ball hides nothing), written in the project's own
dialect with time-indexed facts, as the paper writes them.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from bridge import DDCError
from ddc_cli_helpers import Run
from ddc_cli_helpers import ddc as run_ddc
from probanchor.ddclearn import evaluate, learn

ROOT = Path(__file__).resolve().parents[1]
DDC = [sys.executable, "-m", "probanchor.cli.ddc_cli"]

BIAS = """\
type(distance(obj, obj):t).
type(occluder(obj, obj):t+1).
type(observed(obj):t+1).
type(category(obj)).
rv(distance(_, _):t, continuous).
rv(category(_), discrete([ball, box, mug])).
rv(occluder(_, _):t+1, boolean).
learn(occluder(Occluded, Occluder):t+1).
examples(occluder(A, O):t+1, pair(A, O)).
mode(occluder(_, _):t+1, distance(+, +):t).
mode(occluder(_, _):t+1, observed(+):t+1).
mode(occluder(_, _):t+1, category(+)).
"""


def occlusion_data(path: Path, n: int, seed: int) -> Path:
    rng = np.random.default_rng(seed)
    d = rng.uniform(0.0, 0.4, n)
    cat = rng.choice(["ball", "box", "mug"], n)
    obs = rng.random(n) < 0.3
    p = 1.0 / (1.0 + np.exp(16.9 * d - 0.8))
    p[(cat == "ball") | obs] = 0.0
    y = rng.random(n) < p
    lines = [BIAS]
    for i in range(n):
        a, o = f"a{i}", f"o{i}"
        lines.append(f"pair({a}, {o}).")
        lines.append(f"distance({a}, {o}):t ~= {d[i]:.5f}.")
        lines.append(f"category({o}) ~= {cat[i]}.")
        if obs[i]:
            lines.append(f"observed({a}):t+1.")
        if y[i]:
            lines.append(f"occluder({a}, {o}):t+1.")
    path.write_text("\n".join(lines) + "\n")
    return path


def ddc(*args: str | Path, check: bool = True) -> Run:
    return run_ddc(*args, check=check)


def test_the_command_runs_from_the_shell(tmp_path: Path) -> None:
    train = occlusion_data(tmp_path / "train.pl", 300, 5)
    out = tmp_path / "learned.pl"
    result = subprocess.run([*DDC, "learn", str(train), "--out", str(out), "--quiet"], cwd=ROOT,
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "occluder:t+1" in result.stdout and out.exists()


@pytest.fixture(scope="module")
def data(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    folder = tmp_path_factory.mktemp("learn")
    return occlusion_data(folder / "train.pl", 3000, 1), occlusion_data(folder / "test.pl", 3000, 2)


def test_learn_and_evaluate_from_the_shell(data: tuple[Path, Path], tmp_path: Path) -> None:
    train, test = data
    out = tmp_path / "learned.pl"
    plot = tmp_path / "tree.svg"
    result = ddc("learn", train, "--out", out, "--json", "--plot", plot)
    report = json.loads(result.stdout)
    entry = report["occluder:t+1"]
    assert entry["groundings"] == 3000
    assert entry["clauses"] >= 3
    assert entry["seconds"] > 0
    assert entry["log_likelihood"] < 0
    text = out.read_text()
    # the paper's clause: a logistic on the distance, features first, the bias last
    assert "logistic([Distance], [-1" in text
    assert "occluder(Occluded, Occluder):t+1 ~ finite([P1:true, P2:false]) :=" in text
    assert "\\+ observed(Occluded):t+1" in text
    svg = plot.read_text()
    assert "category(Occluder) ~= ball" in svg

    scores = json.loads(ddc("evaluate", out, test, "--json").stdout)
    s = scores["occluder:t+1"]
    assert s["n"] == 3000 and s["uncovered"] == 0
    assert -0.5 < s["mean_log_likelihood"] < 0
    assert 0.8 < s["accuracy"] <= 1

    table = ddc("evaluate", out, test).stdout
    assert "occluder:t+1" in table and "3000" in table


def test_the_program_written_gives_back_the_training_log_likelihood(
        data: tuple[Path, Path], tmp_path: Path) -> None:
    train, _ = data
    result = learn([train])
    path = result.write(tmp_path / "learned.pl")
    target = result.targets[0]
    scored = evaluate(path, [train])["occluder:t+1"]
    # the printed parameters have 6 significant digits
    assert scored["log_likelihood"] == pytest.approx(target.log_likelihood, rel=1e-4)
    assert scored["n"] == target.examples


def test_learning_is_deterministic(data: tuple[Path, Path]) -> None:
    train, _ = data
    assert learn([train], seed=3).program == learn([train], seed=3).program


@pytest.mark.parametrize("form", ["clauses", "tree"])
def test_the_learned_program_loads_in_the_engine_and_answers(
        data: tuple[Path, Path], tmp_path: Path, form: str) -> None:
    import bridge

    train, _ = data
    path = learn([train]).write(tmp_path / "learned.pl", form=form)  # type: ignore[arg-type]
    facts = tmp_path / "query.pl"
    # the clauses start with the examples' goal, pair(A, O): the pair they are about
    facts.write_text(path.read_text() + "\npair(a, b) := true.\n"
                     + "distance(a, b):t ~ val(0.05).\ncategory(b) ~ val(box).\n")
    program = bridge.load(facts)
    p = program.query("occluder(a, b):t+1 ~= true", samples=10, seed=0).probability
    expected = 1.0 / (1.0 + math.exp(16.9 * 0.05 - 0.8))
    assert p == pytest.approx(expected, abs=0.08)


def test_the_tree_form_is_one_clause_with_the_same_scores(
        data: tuple[Path, Path], tmp_path: Path) -> None:
    train, test = data
    clauses, tree = tmp_path / "clauses.pl", tmp_path / "tree.pl"
    ddc("learn", train, "--out", clauses, "--quiet")
    ddc("learn", train, "--out", tree, "--form", "tree", "--quiet")
    head = "\noccluder(Occluded, Occluder):t+1 ~ "
    n_clauses = clauses.read_text().count(head)
    text = tree.read_text()
    assert n_clauses >= 3 and text.count(head) == 1
    assert head + "finite([P1:true, P2:false]) :=" in text
    assert text.count("% n = ") == n_clauses          # each leaf's comment, inside the tree
    assert "->" in text and "logistic([Distance], [-1" in text
    a = json.loads(ddc("evaluate", clauses, test, "--json").stdout)["occluder:t+1"]
    b = json.loads(ddc("evaluate", tree, test, "--json").stdout)["occluder:t+1"]
    assert b["uncovered"] == a["uncovered"] == 0
    assert b["log_likelihood"] == pytest.approx(a["log_likelihood"], rel=1e-12)


def test_an_unknown_target_is_an_error(data: tuple[Path, Path]) -> None:
    train, _ = data
    with pytest.raises(DDCError, match="no target 'grade'.*occluder:t\\+1"):
        learn([train], ["grade"])


def test_bad_data_keeps_the_previous_output(tmp_path: Path) -> None:
    good = occlusion_data(tmp_path / "good.pl", 200, 3)
    out = tmp_path / "learned.pl"
    ddc("learn", good, "--out", out)
    before = out.read_text()
    bad = tmp_path / "bad.pl"
    bad.write_text(good.read_text() + "category(o1) ~= chair.\n")
    result = ddc("learn", bad, "--out", out, check=False)
    assert result.returncode == 1
    line = len(good.read_text().splitlines()) + 1
    assert f"{bad}:{line}: category(o1) ~= chair: chair is not among the declared values" \
        in result.stderr
    assert out.read_text() == before
    assert list(tmp_path.glob(".learned.pl.*")) == []


@pytest.mark.parametrize("text, cause", [
    ("mode(occluder(_, _):t+1, size(+)).\n", "mode names size/1, which has no facts"),
    ("distance(a0, o0):t ~= far.\n", "not a number, but the attribute is declared continuous"),
    ("rank([category, distance, category]).\n", "rank/1 lists category twice"),
    ("rv(category(_), discrete([ball, box, mug])).\n", None),
])
def test_bad_bias_names_file_and_line(tmp_path: Path, text: str, cause: str | None) -> None:
    good = occlusion_data(tmp_path / "good.pl", 50, 4)
    bad = tmp_path / "bad.pl"
    bad.write_text(good.read_text() + text)
    result = ddc("learn", bad, "--out", tmp_path / "out.pl", check=False)
    if cause is None:  # the same declaration twice is not an error
        assert result.returncode == 0, result.stderr
        return
    line = len(good.read_text().splitlines()) + 1
    assert result.returncode == 1
    assert f"{bad}:{line}: " in result.stderr and cause in result.stderr
    assert not (tmp_path / "out.pl").exists()


def test_a_target_without_facts(tmp_path: Path) -> None:
    data = tmp_path / "empty.pl"
    data.write_text("rv(y(_), discrete([a, b])).\nlearn(y(X)).\nz(1) ~= a.\n")
    result = ddc("learn", data, "--out", tmp_path / "out.pl", check=False)
    assert result.returncode == 1
    assert f"{data}:2: target y/1 has no facts" in result.stderr


def test_a_test_value_the_program_does_not_know(data: tuple[Path, Path], tmp_path: Path) -> None:
    train, _ = data
    program = tmp_path / "program.pl"
    program.write_text("category(O) ~ finite([0.5:ball, 0.5:box]).\n")
    result = ddc("evaluate", program, train, check=False)
    assert result.returncode == 1
    assert "category(o" in result.stderr and "mug" in result.stderr
