"""K-fold cross-validation of the learner (``ddc cross-validate``,
``probanchor.ddclearn.crossval``)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from bridge import DDCError
from bridge.learning import fold_files
from probanchor.ddclearn import evaluate, learn
from probanchor.ddclearn.crossval import SUMMARY_NAME, cross_validate
from probanchor.jobs import parse_cluster

ROOT = Path(__file__).resolve().parents[1]
OCCLUDER = ROOT / "prolog" / "examples" / "learn" / "occluder.pl"
ENTITY = re.compile(r"\(a(\d+),|\(a(\d+)\)")


def small_data(folder: Path, entities: int) -> Path:
    """The first ``entities`` (occluded, occluder) pairs of occluder.pl, with its bias."""
    lines = []
    for line in OCCLUDER.read_text().splitlines():
        m = ENTITY.search(line)
        if m is None or int(m.group(1) or m.group(2)) <= entities:
            lines.append(line)
    path = folder / "data.pl"
    path.write_text("\n".join(lines) + "\n")
    return path


def facts(path: Path) -> set[str]:
    """The fact lines of a data file (those that name an entity), without spaces."""
    lines = (line.replace(" ", "") for line in path.read_text().splitlines())
    return {line for line in lines if ENTITY.search(line)}


def entities(lines: set[str]) -> set[str]:
    return {m.group(1) or m.group(2) for line in lines for m in ENTITY.finditer(line)}


@pytest.fixture(scope="module")
def data(tmp_path_factory) -> Path:
    return small_data(tmp_path_factory.mktemp("cv"), 150)


def test_the_folds_partition_the_worlds(data: Path, tmp_path: Path) -> None:
    parts = [(tmp_path / f"train{i}.pl", tmp_path / f"test{i}.pl") for i in range(1, 5)]
    stats = fold_files([data], parts, seed=3)
    everything = facts(data)
    tests = [facts(te) for _, te in parts]
    assert set().union(*tests) == everything  # each pair is its own world: nothing is cut
    assert sum(len(t) for t in tests) == len(everything)  # and no fact is in two folds
    for (train, _), test, s in zip(parts, tests, stats, strict=True):
        assert facts(train) == everything - test
        assert not entities(test) & entities(facts(train))  # separate worlds
        assert (s["test"], s["train"], s["cut"]) == (len(test), len(everything - test), 0)
        assert "learn(occluder(Occluded, Occluder):t+1)." in train.read_text()  # bias in both
    assert sum(s["test_units"] for s in stats) == stats[0]["units"] == 150
    sizes = [len(t) for t in tests]
    assert max(sizes) - min(sizes) <= 4  # dealt to the lightest fold: at most a unit apart
    again = [(tmp_path / f"again{i}.pl", tmp_path / f"againtest{i}.pl") for i in range(1, 5)]
    fold_files([data], again, seed=3)
    assert [facts(te) for _, te in again] == tests  # the seed decides the folds


def test_more_folds_than_worlds_is_an_error_naming_the_file(tmp_path: Path) -> None:
    data = small_data(tmp_path, 2)
    parts = [(tmp_path / f"tr{i}.pl", tmp_path / f"te{i}.pl") for i in range(3)]
    with pytest.raises(DDCError, match=r"data\.pl.*2 units .*fewer than the 3 folds"):
        fold_files([data], parts)
    assert not any(p.exists() for pair in parts for p in pair)


def test_cross_validation_equals_learning_and_scoring_each_fold_by_hand(
        data: Path, tmp_path: Path, capsys) -> None:
    from probanchor.cli.ddc_cli import main

    out = tmp_path / "cv"
    assert main(["cross-validate", str(data), "--folds", "3", "--out", str(out), "--seed", "1",
                 "--json", "--quiet"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed == json.loads((out / SUMMARY_NAME).read_text())
    hand = tmp_path / "hand"
    hand.mkdir()
    parts = [(hand / f"train{i}.pl", hand / f"test{i}.pl") for i in range(1, 4)]
    fold_files([data], parts, seed=1)
    total_ll = total_w = 0.0
    for i, (train, test) in enumerate(parts, start=1):
        assert facts(out / f"fold-{i}" / "test.pl") == facts(test)
        program = hand / f"learned{i}.pl"
        learn([train], seed=1).write(program)
        scores = evaluate(program, [test])
        assert printed["per_fold"][i - 1]["scores"] == scores
        assert (_body(out / f"fold-{i}" / "learned.pl") == _body(program))
        total_ll += scores["occluder:t+1"]["log_likelihood"]
        total_w += scores["occluder:t+1"]["weight"]
    summary = printed["summary"]["occluder:t+1"]
    assert summary["n"] == 150
    assert summary["mean_log_likelihood"] == pytest.approx(total_ll / total_w, rel=1e-12)
    assert -0.5 < summary["mean_log_likelihood"] < -0.1  # the generator's own is about -0.2
    assert len(summary["folds"]) == 3


def _body(path: Path) -> list[str]:
    """A program without its header comments and its record of the data (the command and the
    files differ)."""
    text = re.sub(r"^learned_from\(.*?\]\)\.$", "", path.read_text(), flags=re.S | re.M)
    return [line for line in text.splitlines() if not line.startswith("% ")
            or line.startswith("% n = ")]


def test_local_processes_and_ray_give_the_same_folds(data: Path, tmp_path: Path,
                                                      ray_two_workers) -> None:
    results = {}
    for name, cluster in (("here", parse_cluster(None, 1)), ("local", parse_cluster(None, 2)),
                          ("ray", parse_cluster("ray", 2))):
        cv = cross_validate([data], 3, tmp_path / name, seed=2, cluster=cluster)
        results[name] = cv
    assert results["ray"].cluster == "ray (local), 2 workers"  # the Ray of the fixture ran them
    for name in ("local", "ray"):
        assert results[name].summary() == results["here"].summary()
        for a, b in zip(results[name].folds, results["here"].folds, strict=True):
            assert (a.split, a.scores) == (b.split, b.scores)
            assert Path(a.program).read_text() == Path(b.program).read_text()


def test_bad_options_are_errors_before_anything_is_written(data: Path, tmp_path: Path,
                                                           capsys) -> None:
    from probanchor.cli.ddc_cli import main

    out = tmp_path / "cv"
    assert main(["cross-validate", str(data), "--folds", "1", "--out", str(out)]) == 1
    assert "at least 2 folds" in capsys.readouterr().err
    assert main(["cross-validate", str(data), "--out", str(out), "--cluster", "spark"]) == 1
    assert "is not local, ray, auto or ray://HOST:PORT" in capsys.readouterr().err
    assert not out.exists()
