"""Labelled pairs from ground truth, the exported SVM, and the train-matching command."""

from __future__ import annotations

import json

import numpy as np
import pytest

from anchoring import training
from anchoring.synthetic import stream
from probanchor.percepts import write_percepts


def test_labelled_pairs_follow_the_ground_truth():
    frames = stream(3, n_objects=3, seconds=1.0, miss_rate=0.0, spurious_rate=0.0, twins=False)
    pairs = training.labelled_pairs(frames)
    # frame 0 acquires 3 oracle anchors; every later frame pairs 3 percepts with 3 anchors
    assert len(pairs) == 9 * (len(frames) - 1)
    assert pairs.y.sum() == 3 * (len(frames) - 1)
    same, other = pairs.x[pairs.y == 1], pairs.x[pairs.y == 0]
    # the same object one frame later: within a few cm (noise, pushes at <= 25 cm/s, clipped
    # segments); the others stand >= 14 cm apart
    assert same[:, 2].min() > np.exp(-0.05)
    assert other[:, 2].max() < np.exp(-0.12)
    assert np.all(same[:, 4] > 0.9)


def test_pairs_without_truth_are_skipped():
    frames = stream(4, n_objects=2, seconds=0.5, spurious_rate=0.0)
    for f in frames:
        for p in f.percepts:
            p.truth_id = None
    assert len(training.labelled_pairs(frames)) == 0


def test_exported_svm_equals_scikit_learn():
    from sklearn.svm import SVC

    rng = np.random.default_rng(0)
    x = rng.uniform(0, 1, (300, 5))
    y = (x[:, 2] + 0.3 * x[:, 1] > 0.9).astype(int)
    model = training.fit_svm(training.PairSet(x, y, np.zeros(300, int)), c=10.0, gamma=2.0)
    svc = SVC(C=10.0, gamma=2.0, class_weight="balanced").fit(x, y)
    probe = rng.uniform(0, 1, (50, 5))
    assert model.decision(probe) == pytest.approx(svc.decision_function(probe), abs=1e-8)


def test_train_matching_command_writes_a_model(tmp_path, capsys):
    from probanchor.cli.anchoring_cli import main

    paths = []
    for k in range(4):
        path = tmp_path / f"s{k}.jsonl"
        write_percepts(path, stream(50 + k, n_objects=4, seconds=4.0, occlusion_rate=0.1))
        paths.append(str(path))
    out = tmp_path / "m.json"
    assert main(["train-matching", *paths, "--out", str(out), "--max-pairs", "600"]) == 0
    report = json.loads(out.with_suffix(".report.json").read_text())
    assert report["held_out"]["accuracy"] > 0.95
    from anchoring import AnchorManager, RbfSvm

    model = RbfSvm.load(out)
    assert model.info["held_out"] == report["held_out"]
    AnchorManager(matcher=model)
    capsys.readouterr()
    assert main(["train-matching", "--show-report", str(out.with_suffix(".report.json"))]) == 0
    table = capsys.readouterr().out
    assert f"| {report['held_out']['accuracy']:.4f} |" in table and "look-alikes" in table


def test_train_matching_rejects_unlabelled_streams(tmp_path, capsys):
    from probanchor.cli.anchoring_cli import main

    frames = stream(1, n_objects=2, seconds=0.5)
    for f in frames:
        for p in f.percepts:
            p.truth_id = None
    path = tmp_path / "plain.jsonl"
    write_percepts(path, frames)
    assert main(["train-matching", str(path), str(path)]) == 1
    assert "plain.jsonl" in capsys.readouterr().err


def test_lookalike_negatives_move_only_the_position():
    rng = np.random.default_rng(0)
    x = np.tile([0.9, 0.95, 0.99, 0.9, 0.97], (40, 1))
    y = np.array([1] * 30 + [0] * 10)
    looks = training.lookalike_negatives(training.PairSet(x, y, np.zeros(40, int)), rng, 0.5,
                                         0.12, 0.6)
    assert len(looks) == 15 and not looks.y.any()
    assert np.all(looks.x[:, [0, 1, 3, 4]] == [0.9, 0.95, 0.9, 0.97])
    d = -np.log(looks.x[:, 2])
    assert d.min() >= 0.12 and d.max() <= 0.6


def test_stale_positives_change_only_the_time():
    rng = np.random.default_rng(1)
    x = np.tile([0.9, 0.95, 0.99, 0.9, 0.97], (20, 1))
    y = np.array([1] * 10 + [0] * 10)
    stale = training.stale_positives(training.PairSet(x, y, np.zeros(20, int)), rng, 0.5,
                                     1.0, 30.0)
    assert len(stale) == 5 and stale.y.all()
    assert np.all(stale.x[:, :4] == [0.9, 0.95, 0.99, 0.9])
    gap = np.log((2 - stale.x[:, 4]) / stale.x[:, 4])  # inverse of 2 / (1 + e^gap)
    assert gap.min() >= 1.0 - 1e-9 and gap.max() <= 30.0 + 1e-6


def test_grid_search_folds_are_whole_streams_and_prefer_few_support_vectors(monkeypatch):
    from sklearn.model_selection import GridSearchCV

    from probanchor.cli.commands import train_matching

    rng = np.random.default_rng(3)
    x = rng.uniform(0, 1, (600, 5))
    y = (x[:, 2] + 0.3 * x[:, 1] > 0.9).astype(int)
    group = np.repeat(np.arange(6), 100)
    seen = {}
    original_fit = GridSearchCV.fit

    def spy(self, *args, **kwargs):
        seen["cv"] = list(self.cv)
        return original_fit(self, *args, **kwargs)

    monkeypatch.setattr(GridSearchCV, "fit", spy)
    c, gamma = train_matching.choose_parameters(training.PairSet(x, y, group), 200,
                                                np.random.default_rng(0))
    assert c in train_matching.GRID["C"] and gamma in train_matching.GRID["gamma"]
    assert len(seen["cv"]) == train_matching.FOLDS
    for fit, held in seen["cv"]:
        assert not set(group[fit]) & set(group[held])        # no stream on both sides
        assert len(fit) <= 200
    results = {"mean_test_balanced": [0.9, 0.9995, 0.999, 0.95],
               "mean_test_support_vectors": [10, 80, 40, 5]}
    assert train_matching._fewest_support_vectors(results) == 2
    with pytest.raises(ValueError, match="two training streams"):
        train_matching.choose_parameters(training.PairSet(x, y, np.zeros(600, int)), 200,
                                         np.random.default_rng(0))


class _DecisionIsColour:
    """A matching function whose decision is the pair's colour similarity (column 1)."""

    def decision(self, x: np.ndarray) -> np.ndarray:
        return np.asarray(x)[..., 1]


def _calibration_pairs(rng: np.random.Generator, rho: float, n_same: int = 4000,
                       n_other: int = 16000) -> training.PairSet:
    """Decisions f of a known world: same object f ~ N(2, 0.3^2); another object a
    look-alike with probability rho (f as the same object's), else f ~ N(-1, 0.6^2)."""
    lookalike = rng.random(n_other) < rho
    f = np.concatenate([rng.normal(2.0, 0.3, n_same),
                        np.where(lookalike, rng.normal(2.0, 0.3, n_other),
                                 rng.normal(-1.0, 0.6, n_other))])
    x = np.ones((f.size, 5))
    x[:, 1] = f
    y = np.r_[np.ones(n_same, int), np.zeros(n_other, int)]
    return training.PairSet(x, y, np.zeros(f.size, int))


def test_appearance_calibration_recovers_the_share_of_lookalikes():
    """The fitted share is the world's (within 4 binomial standard errors of its 16,000 other
    objects), so log A at the most similar decisions is -log rho, not the unbounded Platt
    line; data without look-alikes give a share near 0 (no bound that the data do not show)."""
    from anchoring.likelihood import AssociationModel, appearance_log_ratio

    rng = np.random.default_rng(0)
    rho, n_other = 0.05, 16000
    cal = training.appearance_calibration(_DecisionIsColour(), _calibration_pairs(rng, rho))
    assert cal["lookalike"] == pytest.approx(rho, abs=4 * np.sqrt(rho * (1 - rho) / n_other))
    model = AssociationModel(appearance_scale=cal["scale"], appearance_offset=cal["offset"],
                             appearance_lookalike=cal["lookalike"])
    top = np.ones((1, 5))
    top[0, 1] = 3.0
    assert appearance_log_ratio(_DecisionIsColour(), top, model)[0] == pytest.approx(
        -np.log(cal["lookalike"]), abs=0.01)
    assert cal["scale"] * 3.0 + cal["offset"] > -np.log(cal["lookalike"]) + 5  # Platt's line
    clean = training.appearance_calibration(_DecisionIsColour(), _calibration_pairs(rng, 0.0))
    assert clean["lookalike"] < 1e-3


def test_a_calibration_without_a_lookalike_share_reads_as_none():
    """Model files calibrated before the share was fitted keep their plain Platt ratio."""
    from anchoring.likelihood import AssociationModel

    class Calibrated(_DecisionIsColour):
        info = {"appearance_calibration": {"scale": 6.0, "offset": -5.5}}

    model = AssociationModel.for_matcher(Calibrated())
    assert (model.appearance_scale, model.appearance_lookalike) == (6.0, 0.0)
    with pytest.raises(ValueError, match="appearance_lookalike"):
        AssociationModel(appearance_lookalike=1.0)


def test_calibrate_writes_the_share_into_an_existing_model(tmp_path, capsys):
    """``train-matching --calibrate MODEL STREAMS``: only the calibration of MODEL changes."""
    import shutil

    from anchoring.matcher import DEFAULT_MODEL, RbfSvm
    from probanchor.cli.anchoring_cli import main

    model_path = tmp_path / "m.json"
    shutil.copy(DEFAULT_MODEL, model_path)
    paths = []
    for k in range(2):
        path = tmp_path / f"s{k}.jsonl"
        write_percepts(path, stream(60 + k, n_objects=4, seconds=4.0, occlusion_rate=0.1))
        paths.append(str(path))
    assert main(["train-matching", "--calibrate", str(model_path), *paths]) == 0
    assert "look-alikes" in capsys.readouterr().out
    before, after = RbfSvm.load(DEFAULT_MODEL), RbfSvm.load(model_path)
    cal = after.info["appearance_calibration"]
    assert set(cal) == {"scale", "offset", "lookalike", "pairs"} and 0.0 <= cal["lookalike"] < 1
    assert cal != before.info["appearance_calibration"]
    np.testing.assert_array_equal(after.support_vectors, before.support_vectors)
