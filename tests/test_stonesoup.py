"""The Stone Soup baselines (JPDA, MHT by multi-frame assignment) on short synthetic percept
streams: a moving object keeps its track, a hidden one is coasted, bad input is refused; and the
tuning's grid search."""

from __future__ import annotations

import numpy as np
import pytest

from probanchor.evaluation import evaluate
from probanchor.evaluation.baselines import BASELINES, display_name, run_baseline
from probanchor.evaluation.stonesoup_trackers import (
    STONESOUP,
    TUNED,
    StoneSoupError,
    StoneSoupSettings,
    run_stonesoup,
)
from probanchor.percepts import Percept, PerceptFrame, write_percepts

FPS = 15.0
MUG = (0.15, 0.1, 0.05)


def percept(t, truth_id, pos):
    return Percept(time=t, position=np.array(pos, float), size=np.array([0.06, 0.06, 0.08]),
                   colour_histogram=np.ones(8) / 8, category={"ball": 0.9, "mug": 0.1},
                   truth_id=truth_id)


def stream(ball_at, hidden=(), frames=40, noise=0.002, seed=0):
    """A mug that stays put and a ball at ``ball_at(t)``, not perceived in the frames of
    ``hidden`` (under a box); positions with ``noise`` metres of Gaussian noise, percepts in a
    random order each frame."""
    rng = np.random.default_rng(seed)
    out = []
    for f in range(frames):
        t = f / FPS
        ball = np.asarray(ball_at(t), float)
        ps = [percept(t, "mug_1", MUG + rng.normal(0, noise, 3))]
        if f not in hidden:
            ps.append(percept(t, "ball_1", ball + rng.normal(0, noise, 3)))
        truth = {"objects": {
            "mug_1": {"position": list(MUG), "visible": True},
            "ball_1": {"position": ball.tolist(), "visible": f not in hidden,
                       "hidden_by": "box_1" if f in hidden else None},
        }}
        out.append(PerceptFrame(f, t, [ps[i] for i in rng.permutation(len(ps))], truth))
    return out


def moving(t):
    return (-0.2 + 0.15 * t, -0.1, 0.03)  # 15 cm/s along x


def still(t):
    return (-0.15, -0.1, 0.03)


@pytest.mark.parametrize("method", STONESOUP)
def test_a_visible_moving_object_keeps_its_track(method):
    records = run_stonesoup(method, stream(moving))
    assert len(records) == 40
    report = {o.id: o for o in evaluate(records).objects}
    assert report["ball_1"].identity_kept and report["mug_1"].identity_kept
    assert report["ball_1"].symbols != report["mug_1"].symbols
    assert all(s.startswith(f"{method}-") for o in report.values() for s in o.symbols)
    # the estimate follows the ball (the posterior mean: within a couple of centimetres)
    last = records[-1]
    ball = last.hypotheses[last.assignments["ball_1"]]
    assert ball.perceived
    assert np.linalg.norm(ball.position - last.truth["ball_1"].position) < 0.02
    assert len(last.hypotheses) == 2  # no stray tracks


@pytest.mark.parametrize("method", STONESOUP)
def test_a_hidden_object_is_coasted_and_taken_back(method):
    hidden = range(10, 30)  # 1.3 s under a box, back where it was
    records = run_stonesoup(method, stream(still, hidden))
    during = records[20]
    assert "ball_1" not in during.assignments
    coasting = [h for h in during.hypotheses.values() if not h.perceived]
    assert len(coasting) == 1  # the ball's track, held by its motion model
    assert np.linalg.norm(coasting[0].position - np.array(still(0))) < 0.03
    ev = evaluate(records)
    assert {o.id: o for o in ev.objects}["ball_1"].identity_kept
    assert ev.mot.id_switches == 0 and ev.hota.hota > 0.8
    # with a patience of 1 s the ball's track is deleted before it comes back: a new track
    short = evaluate(run_stonesoup(method, stream(still, hidden), lost_seconds=1.0))
    ball = {o.id: o for o in short.objects}["ball_1"]
    assert not ball.identity_kept and len(ball.symbols) == 2


@pytest.mark.parametrize("method", STONESOUP)
def test_runs_through_run_baseline_and_the_same_run_twice(method):
    assert method in BASELINES and display_name(method).startswith("Stone Soup")
    frames = stream(moving, hidden=range(15, 20))
    first = run_baseline(method, frames)
    second = run_baseline(method, frames)
    assert [r.assignments for r in first] == [r.assignments for r in second]
    # the same estimates, up to rounding (Stone Soup sums over sets, whose order varies)
    for a, b in zip(first, second, strict=True):
        assert sorted(a.hypotheses) == sorted(b.hypotheses)
        for k, h in a.hypotheses.items():
            assert np.allclose(h.position, b.hypotheses[k].position, rtol=0, atol=1e-12)
    # frames without any percept (a covered camera) are fine
    empty = [PerceptFrame(k, k / FPS, [], {"objects": {}}) for k in range(3)]
    assert [r.hypotheses for r in run_baseline(method, empty)] == [{}, {}, {}]


def test_bad_input_is_refused():
    frames = stream(moving, frames=5)
    with pytest.raises(StoneSoupError, match="unknown Stone Soup tracker 'stonesoup-gnn'"):
        run_stonesoup("stonesoup-gnn", frames)
    with pytest.raises(StoneSoupError, match="lost_seconds"):
        run_stonesoup("stonesoup-jpda", frames, lost_seconds=0)
    backwards = frames[:3] + [PerceptFrame(3, 0.0, [], {})]
    with pytest.raises(StoneSoupError, match="frame 3: time 0.0 is not after"):
        run_stonesoup("stonesoup-jpda", backwards)
    frames[2].percepts[0].position = np.array([0.0, np.nan, 0.0])
    with pytest.raises(StoneSoupError, match="frame 2: percept 0 has no finite 3-D position"):
        run_stonesoup("stonesoup-mht", frames)
    for bad in ({"process_noise": -1.0}, {"prob_gate": 1.0}, {"slide_window": 0},
                {"measurement_noise": float("nan")}):
        with pytest.raises(StoneSoupError, match=next(iter(bad))):
            StoneSoupSettings(**bad)
    with pytest.raises(StoneSoupError, match="unknown Stone Soup settings"):
        StoneSoupSettings().replace(gate=3)
    with pytest.raises(ValueError, match="unknown arguments"):
        run_baseline("stonesoup-jpda", frames, track_activation_threshold=0.5)
    assert set(TUNED) == set(STONESOUP)


def test_tuning_ranks_the_settings_of_a_grid(tmp_path):
    from probanchor.evaluation.stonesoup_tuning import format_ranking, tune

    path = tmp_path / "still.jsonl"
    write_percepts(path, stream(still, hidden=range(10, 30)))
    grid = {"process_noise": [0.1], "measurement_noise": [0.01], "prob_gate": [0.99, 0.9999]}
    log = tmp_path / "tuning.jsonl"
    ranking = tune(["stonesoup-jpda"], [path], grid=grid, lost_seconds=1.0, log=log)
    assert len(log.read_text().splitlines()) == 2  # one line per run, as it finished
    # again: everything is in the log, nothing runs, the same ranking
    again = tune(["stonesoup-jpda"], [path], grid=grid, lost_seconds=1.0, log=log)
    assert len(log.read_text().splitlines()) == 2
    assert again == ranking
    scores = ranking["stonesoup-jpda"]
    assert len(scores) == 2 and {s.settings["prob_gate"] for s in scores} == {0.99, 0.9999}
    assert [s.key() for s in scores] == sorted((s.key() for s in scores), reverse=True)
    assert all(s.objects == 2 and s.kept == 1 for s in scores)  # 1 s patience: the ball lost
    text = format_ranking(ranking)
    assert text.splitlines()[0].startswith("| method | process_noise | measurement_noise")
    assert "| stonesoup-jpda | 0.1 | 0.01 |" in text and "| 1/2 (50 %) |" in text


def test_baselines_command_runs_and_tunes_the_stonesoup_trackers(tmp_path, capsys):
    from probanchor.cli.anchoring_cli import main

    path = tmp_path / "still.jsonl"
    write_percepts(path, stream(still, hidden=range(10, 30)))
    assert main(["baselines", str(path), "--methods", "stonesoup-jpda,stonesoup-mht"]) == 0
    rows = [r for r in capsys.readouterr().out.splitlines() if r.startswith("| still |")]
    assert [r.split("|")[2].strip() for r in rows] == ["Stone Soup JPDA", "Stone Soup MHT (MFA)"]
    assert all("| 2/2 (100 %) | 1/1 (100 %) |" in r for r in rows)
    assert main(["baselines", "--tune", "--methods", "sort", str(path)]) == 1
    assert "not a Stone Soup tracker" in capsys.readouterr().err
