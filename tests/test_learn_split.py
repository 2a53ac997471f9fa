"""`ddc split`: a data set split into a training and a test file whose facts form separate worlds.

The own-dialect data are independent episodes (objects ``o1_eK``, ``o2_eK`` of episode K) with
time-indexed facts, a Boolean target given by ``examples/2`` and a background DC clause; the
DreaML data are the PKDD'99 Financial data set, split by district (``--unit d``).
"""

from __future__ import annotations

import json
import re
import time
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

from bridge import DDCError
from bridge.learning import LearningData, split_files
from ddc_cli_helpers import ddc
from probanchor.ddclearn import evaluate, learn
from probanchor.ddclearn.datasets import financial

FINANCIAL = financial()

BIAS = """\
:- discontiguous pair/2.
type(distance(obj, obj):t).
type(occluder(obj, obj):t+1).
type(category(obj)).
type(pair(obj, obj)).
type(near(obj, obj):t).
rv(distance(_, _):t, continuous).
rv(category(_), discrete([ball, box])).
rv(occluder(_, _):t+1, boolean).
learn(occluder(Occluded, Occluder):t+1).
examples(occluder(A, O):t+1, pair(A, O)).
mode(occluder(_, _):t+1, distance(+, +):t).
mode(occluder(_, _):t+1, category(+)).
mode(occluder(_, _):t+1, near(+, +):t).
near(A, O):t := distance(A, O):t ~= D, D < 0.1.
"""


def episodes(path: Path, n: int, seed: int = 1) -> Path:
    """``n`` independent episodes: in each, o1 may be hidden by o2 and by o3 (two groundings)."""
    rng = np.random.default_rng(seed)
    lines = [BIAS]
    for e in range(1, n + 1):
        agent = f"o1_e{e}"
        lines.append(f"pos({agent}):t ~= {rng.uniform(0, 1):.4f}.")
        for k in (2, 3):
            other = f"o{k}_e{e}"
            d = rng.uniform(0.0, 0.3)
            cat = "ball" if rng.random() < 0.3 else "box"
            lines.append(f"pair({agent}, {other}).")
            lines.append(f"distance({agent}, {other}):t ~= {d:.5f}.")
            lines.append(f"category({other}) ~= {cat}.")
            if cat == "box" and rng.random() < 1.0 / (1.0 + np.exp(30.0 * d - 2.0)):
                lines.append(f"occluder({agent}, {other}):t+1.")
        if rng.random() < 0.3:
            lines.append(f"0.6 :: seen({agent}):t+1.")
    path.write_text("\n".join(lines) + "\n")
    return path


def split_json(*args: str | Path) -> dict[str, int]:
    run = ddc("split", *args, "--json")
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


def fact_lines(path: Path) -> list[str]:
    """The facts of a written own-dialect part (one clause per line; no rules, no declarations)."""
    skip = ("%", ":-", "type(", "rv(", "learn(", "examples(", "mode(", "near(")
    return [ln for ln in path.read_text().splitlines() if ln and not ln.startswith(skip)]


def episode_ids(path: Path) -> set[int]:
    return {int(m) for ln in fact_lines(path) for m in re.findall(r"_e(\d+)\b", ln)}


def facts_per_episode(path: Path) -> Counter[int]:
    return Counter(int(re.findall(r"_e(\d+)\b", ln)[0]) for ln in fact_lines(path))


# ----------------------------------------------------------------------------- own dialect


def test_episodes_split_whole_within_one_episode_of_the_fraction(tmp_path: Path) -> None:
    data = episodes(tmp_path / "episodes.pl", 60)
    train, test = tmp_path / "train.pl", tmp_path / "test.pl"
    stats = split_json(data, "--train", train, "--test", test, "--fraction", "0.25")
    assert stats["units"] == 60 and stats["cut"] == 0 and stats["both"] == 0
    per_episode = facts_per_episode(data)
    total = sum(per_episode.values())
    assert stats["train"] + stats["test"] == total
    test_eps, train_eps = episode_ids(test), episode_ids(train)
    assert not test_eps & train_eps
    assert test_eps | train_eps == set(range(1, 61))
    assert len(test_eps) == stats["test_units"]
    assert sum(per_episode[e] for e in test_eps) == stats["test"]
    # at least the fraction, and less than one more episode's facts over it
    assert 0.25 * total <= stats["test"] < 0.25 * total + max(per_episode.values())
    # the bias and the background clause are in both parts
    for part in (train, test):
        text = part.read_text()
        assert text.startswith("% ")
        assert "examples(occluder(A, O):t+1, pair(A, O))." in text
        assert "near(A, O):t:=distance(A, O):t~=D, D<0.1." in text
        assert ":-discontiguous pair/2." in text


def test_same_seed_same_split_other_seed_other_split(tmp_path: Path) -> None:
    data = episodes(tmp_path / "episodes.pl", 40)
    outs = {}
    for name, seed in (("a", 5), ("b", 5), ("c", 6)):
        train, test = tmp_path / f"train_{name}.pl", tmp_path / f"test_{name}.pl"
        split_json(data, "--train", train, "--test", test, "--seed", str(seed))
        outs[name] = (train.read_text(), test.read_text(), episode_ids(test))
    assert outs["a"][:2] == outs["b"][:2]
    assert outs["a"][2] != outs["c"][2]


def test_learned_on_the_training_part_scored_on_the_test_part(tmp_path: Path) -> None:
    data = episodes(tmp_path / "episodes.pl", 120)
    train, test = tmp_path / "train.pl", tmp_path / "test.pl"
    stats = split_files([data], train, test, fraction=0.25, seed=0)
    assert stats["cut"] == 0
    # both parts load as learning data
    with LearningData([train]) as d:
        assert [t["predicate"] for t in d.targets()] == ["occluder_t1"]
    with LearningData([test], targets=False):
        pass
    result = learn([train], seed=0)
    program = result.write(tmp_path / "learned.pl")
    scores = evaluate(program, [test])
    (key,) = scores
    assert key.startswith("occluder")
    assert scores[key]["n"] == 2 * stats["test_units"]  # two pairs per test episode
    assert scores[key]["uncovered"] == 0
    assert -0.7 < scores[key]["mean_log_likelihood"] < 0.0


def test_cli_prints_one_line_of_counts(tmp_path: Path) -> None:
    data = episodes(tmp_path / "episodes.pl", 20)
    train, test = tmp_path / "train.pl", tmp_path / "test.pl"
    run = ddc("split", data, "--train", train, "--test", test)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.strip().splitlines()
    assert len(lines) == 1
    assert re.fullmatch(r"train \d+ facts, test \d+ facts \(\d+ of 20 units\), 0 cut, 0 in both: "
                        r"wrote .*train\.pl and .*test\.pl", lines[0])


# ----------------------------------------------------------------------------- errors


def test_one_connected_world_without_unit(tmp_path: Path) -> None:
    data = tmp_path / "chain.pl"
    data.write_text("type(link(node, node)).\nlink(a, b).\nlink(b, c).\n")
    train, test = tmp_path / "train.pl", tmp_path / "test.pl"
    run = ddc("split", data, "--train", train, "--test", test)
    assert run.returncode == 1
    assert run.stderr.startswith(f"ddc split: error: {data}:2: the facts form one connected world")
    assert "unit(Type) (ddc split --unit TYPE), one of: node" in run.stderr
    assert not train.exists() and not test.exists()


def test_unknown_unit_type(tmp_path: Path) -> None:
    data = episodes(tmp_path / "episodes.pl", 5)
    train, test = tmp_path / "train.pl", tmp_path / "test.pl"
    train.write_text("old\n")
    with pytest.raises(DDCError, match=r"episodes\.pl: unknown unit type district: the data's "
                                       r"argument types are obj$"):
        split_files([data], train, test, unit="district")
    assert train.read_text() == "old\n" and not test.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["episodes.pl", "train.pl"]


@pytest.mark.parametrize("fraction", ["0", "1", "1.5", "-0.2"])
def test_bad_fraction(tmp_path: Path, fraction: str) -> None:
    data = episodes(tmp_path / "episodes.pl", 5)
    run = ddc("split", data, "--train", tmp_path / "a.pl", "--test", tmp_path / "b.pl",
              "--fraction", fraction)
    assert run.returncode == 1
    assert "ddc split: error: --fraction" in run.stderr
    assert "between 0 and 1" in run.stderr
    with pytest.raises(ValueError, match="between 0 and 1"):
        split_files([data], tmp_path / "a.pl", tmp_path / "b.pl", fraction=float(fraction))


def test_output_that_is_an_input(tmp_path: Path) -> None:
    data = episodes(tmp_path / "episodes.pl", 5)
    before = data.read_text()
    run = ddc("split", data, "--train", data, "--test", tmp_path / "b.pl")
    assert run.returncode == 1 and "is an input file" in run.stderr
    assert data.read_text() == before


# ----------------------------------------------------------------------------- Financial


def test_financial_split_by_district(tmp_path: Path) -> None:
    train, test = tmp_path / "train.pl", tmp_path / "test.pl"
    start = time.perf_counter()
    stats = split_files([FINANCIAL], train, test, fraction=0.2, seed=0, unit="d")
    seconds = time.perf_counter() - start
    print(f"FinancialData.pl --unit d --fraction 0.2 --seed 0: {stats}, {seconds:.2f} s")
    assert seconds < 30
    assert stats["units"] == 77  # the districts
    assert stats["both"] == 0
    # every fact line of the source is in one part, or cut
    fact = re.compile(r"^[a-zA-Z]\w*\([^():]*\)\.$")
    not_facts = ("base(", "thres(", "mode(", "learn(", "rank(", "randomVariableNames(",
                 "list2set(")  # list2set([], []): the base case of a background rule

    def facts(path: Path) -> list[str]:
        lines = (ln.replace(" ", "") for ln in path.read_text().splitlines())
        return [ln for ln in lines if fact.match(ln) and not ln.startswith(not_facts)]

    src = facts(FINANCIAL)
    facts_of = {"train": facts(train), "test": facts(test)}
    n_src = len(src)
    assert len(facts_of["train"]) == stats["train"] and len(facts_of["test"]) == stats["test"]
    assert stats["train"] + stats["test"] + stats["cut"] == n_src
    assert 0.2 * n_src <= stats["test"] < 0.3 * n_src
    # the test districts, clients, accounts and loans are not in the training part
    consts = {name: set(re.findall(r"\b[cdal]_\d+\b", "\n".join(lines)))
              for name, lines in facts_of.items()}
    assert not consts["train"] & consts["test"]
    test_districts = {c for c in consts["test"] if c.startswith("d_")}
    assert len(test_districts) == stats["test_units"]
    # a client follows its district: every test client's district is a test district
    for ln in facts_of["test"]:
        if ln.startswith("clientDistrict("):
            assert ln.split(",")[1] in test_districts
    # what is cut: mostly DreaML's negative links hasAccount(C, A, false) between districts
    cut = Counter(src) - Counter(facts_of["train"]) - Counter(facts_of["test"])
    cut_kinds = Counter(ln.split("(")[0] for ln in cut.elements())
    assert sum(cut_kinds.values()) == stats["cut"]
    assert set(cut_kinds) <= {"hasAccount", "hasLoan", "clientLoan"}
    false_links = sum(n for ln, n in cut.items() if ln.endswith(",false)."))
    assert false_links > stats["cut"] / 2
    # every learned target still has test facts
    targets = set(re.findall(r"^learn\((\w+),", FINANCIAL.read_text(), re.M))
    assert len(targets) == 13
    per_pred = Counter(ln.split("(")[0] for ln in facts_of["test"])
    assert all(per_pred[t] > 0 for t in targets), per_pred
    # the bias and the rules are in both parts: each reads as DreaML's dialect
    with LearningData([test], targets=False) as d:
        assert {t["predicate"] for t in d.targets()} == targets
