"""Metrics on hand-built tracking records, checked against values computed by hand."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from probanchor.evaluation import (
    HOTA_FIELDS,
    SUMMARY_FIELDS,
    FrameTimings,
    Hypothesis,
    RecordError,
    TrackingRecord,
    TruthObject,
    evaluate,
    identity_report,
    make_summary,
    mot_metrics,
    point_estimate,
    read_records,
    read_summary,
    truth_from_dict,
    write_records,
    write_summary,
)


def rec(frame, truth, hyps, assign, timings=None, rejected=0):
    """truth: id -> (pos, visible[, hidden_by]); hyps: symbol -> (pos, perceived)."""
    return TrackingRecord(
        frame=frame,
        time=frame / 10.0,
        truth={k: TruthObject(np.array(v[0], float), v[1], *v[2:]) for k, v in truth.items()},
        hypotheses={k: Hypothesis(np.array(v[0], float), v[1]) for k, v in hyps.items()},
        assignments=dict(assign),
        timings=timings or FrameTimings(),
        rejected_percepts=rejected,
    )


A, B = (0.0, 0.0, 0.0), (0.5, 0.0, 0.0)


def switch_run():
    """Two balls; from frame 2 on the system swaps their symbols."""
    out = []
    for f in range(4):
        s_a, s_b = ("ball-1", "ball-2") if f < 2 else ("ball-2", "ball-1")
        out.append(
            rec(f, {"a": (A, True), "b": (B, True)},
                {s_a: (A, True), s_b: (B, True)}, {"a": s_a, "b": s_b})
        )
    return out


def test_identity_switch_is_counted():
    ev = evaluate(switch_run())
    assert [(o.id, o.symbols, o.identity_kept) for o in ev.objects] == [
        ("a", ["ball-1", "ball-2"], False),
        ("b", ["ball-2", "ball-1"], False),
    ]
    # By hand: each object changes hypothesis once at frame 2 -> 2 switches. Best global ID
    # matching: a<->ball-1 (2 frames) and b<->ball-2 (2 frames): IDTP 4 of 8 truths and 8
    # hypotheses -> IDF1 = 2*4 / (8 + 8) = 0.5.
    assert ev.mot.id_switches == 2
    assert ev.mot.idtp == 4 and ev.mot.idfp == 4 and ev.mot.idfn == 4
    assert ev.mot.idf1 == pytest.approx(0.5)
    assert not ev.all_kept


def occlusion_run(reacquired_as="ball-1"):
    """A ball hidden under a mug in frames 2-4, believed under it, then seen again."""
    mug = (0.3, 0.1, 0.0)
    out = []
    for f in range(6):
        hidden = 2 <= f <= 4
        ball_true = mug if hidden else A
        truth = {"ball": (ball_true, not hidden, "mug" if hidden else None), "mug": (mug, True)}
        ball_sym = "ball-1" if f < 5 else reacquired_as
        hyps = {"mug-1": (mug, True), ball_sym: ((0.31, 0.1, 0.0) if hidden else A, not hidden)}
        assign = {"mug": "mug-1"} if hidden else {"mug": "mug-1", "ball": ball_sym}
        out.append(rec(f, truth, hyps, assign))
    return out


def test_identity_kept_through_occlusion():
    ev = evaluate(occlusion_run())
    report = {o.id: o for o in ev.objects}
    assert report["ball"].symbols == ["ball-1"] and report["ball"].identity_kept
    assert report["mug"].symbols == ["mug-1"] and report["mug"].identity_kept
    assert report["ball"].perceived_frames == 3 and report["ball"].assigned_frames == 3
    assert ev.all_kept
    assert ev.mot.id_switches == 0
    assert ev.mot.idf1 == pytest.approx(1.0)


def test_reacquired_under_a_new_symbol_is_not_kept():
    ev = evaluate(occlusion_run(reacquired_as="ball-2"))
    ball = next(o for o in ev.objects if o.id == "ball")
    assert ball.symbols == ["ball-1", "ball-2"] and not ball.identity_kept
    # The ball is matched to ball-1 in frames 0-4 and to ball-2 in frame 5: one switch.
    assert ev.mot.id_switches == 1
    # IDTP: mug 6 + ball 5 = 11 of 12 truths and 13 hypotheses (ball-1 is also held... no:
    # ball-1 disappears at frame 5, ball-2 appears) -> 12 hypotheses: IDF1 = 22 / 24.
    assert ev.mot.idf1 == pytest.approx(22 / 24)


def hidden_run(follow: bool):
    """A ball hidden in frames 1-3 while its box carries it 0.3 m; seen again in frame 4.

    With ``follow`` the belief goes along (within 1 cm); without, it stays where last seen.
    """
    truth_x = [0.0, 0.0, 0.3, 0.3, 0.3]
    belief_x = [0.0, 0.01, 0.31, 0.3, 0.3] if follow else [0.0, 0.0, 0.0, 0.0, 0.3]
    return [
        rec(f, {"ball": ((truth_x[f], 0, 0), f in (0, 4))},
            {"ball-1": ((belief_x[f], 0, 0), f in (0, 4))},
            {"ball": "ball-1"} if f in (0, 4) else {})
        for f in range(5)
    ]


def test_hidden_object_credited_only_when_belief_stays_near_truth():
    near = mot_metrics(hidden_run(follow=True), threshold=0.1)
    assert near.idf1 == pytest.approx(1.0) and near.idtp == 5
    far = mot_metrics(hidden_run(follow=False), threshold=0.1)
    # Frames 2 and 3: belief 0.3 m from the truth -> unmatched: IDTP 3 of 5 and 5 -> 6/10.
    assert far.idtp == 3 and far.idfn == 2 and far.idfp == 2
    assert far.idf1 == pytest.approx(0.6)
    # The threshold is configurable: at 0.5 m the stale belief is close enough.
    assert mot_metrics(hidden_run(follow=False), threshold=0.5).idf1 == pytest.approx(1.0)
    # Identity from assignments is the same symbol in both runs.
    assert identity_report(hidden_run(follow=False))[0].identity_kept


def test_a_symbol_shared_by_two_objects_keeps_neither():
    run = [
        rec(0, {"a": (A, True), "b": (B, False)}, {"ball-1": (A, True)}, {"a": "ball-1"}),
        rec(1, {"a": (A, False), "b": (B, True)}, {"ball-1": (B, True)}, {"b": "ball-1"}),
    ]
    report = identity_report(run)
    assert [(o.id, o.symbols, o.identity_kept) for o in report] == [
        ("a", ["ball-1"], False),
        ("b", ["ball-1"], False),
    ]


def test_never_perceived_objects_are_not_reported_and_unassigned_ones_are_not_kept():
    run = [
        rec(f, {"ball": (A, False, "mug"), "mug": (B, True), "box": ((1, 0, 0), True)},
            {"mug-1": (B, True)}, {"mug": "mug-1"})
        for f in range(3)
    ]
    report = {o.id: o for o in identity_report(run)}
    assert set(report) == {"mug", "box"}
    assert report["box"].symbols == [] and not report["box"].identity_kept
    assert report["mug"].identity_kept


def test_summary_has_exactly_the_issue_fields(tmp_path):
    run = occlusion_run()
    for i, r in enumerate(run):
        r.timings = FrameTimings(perception=2.0 + i, anchoring=1.0, filter=4.0)
    run[3].rejected_percepts = 2
    run[5].timings.total = 20.0  # measured, not the sum
    path = tmp_path / "out" / "summary.json"
    summary = write_summary(path, run)
    on_disk = json.loads(path.read_text())
    assert on_disk == summary == read_summary(path)
    assert tuple(on_disk) == SUMMARY_FIELDS + HOTA_FIELDS
    assert on_disk["frames"] == 6
    assert on_disk["objects"] == [
        {"id": "ball", "symbols": ["ball-1"], "identity_kept": True,
         "identity_kept_at_end": True},
        {"id": "mug", "symbols": ["mug-1"], "identity_kept": True,
         "identity_kept_at_end": True},
    ]
    assert on_disk["revisions"] == []
    assert on_disk["id_switches"] == 0 and on_disk["idf1"] == pytest.approx(1.0)
    # perception 2..7 -> mean 4.5; totals 7,8,9,10,11 and 20 -> mean 65/6.
    assert on_disk["ms_per_frame"] == {
        "perception": 4.5, "anchoring": 1.0, "filter": 4.0, "total": round(65 / 6, 3)
    }
    assert on_disk["rejected_percepts"] == 2
    # HOTA of this run, by hand in tests/test_hota.py
    assert on_disk["hota"] == pytest.approx((18 + math.sqrt(0.6 * 7 / 9)) / 19, abs=1e-6)
    with pytest.raises(ValueError, match="replace"):
        make_summary(run, extra={"idf1": 1})
    assert make_summary(run, extra={"seed": 3})["seed"] == 3


def test_summary_of_an_empty_run_is_valid_json():
    summary = make_summary([])
    assert summary["frames"] == 0 and summary["objects"] == [] and summary["idf1"] is None
    json.dumps(summary, allow_nan=False)


def test_read_summary_names_the_file(tmp_path):
    bad = tmp_path / "summary.json"
    bad.write_text('{"frames": 3}')
    with pytest.raises(ValueError, match=r"summary.json: not a run summary, missing objects"):
        read_summary(bad)


def test_point_estimate_mode_and_mean():
    rng = np.random.default_rng(0)
    pts = np.concatenate([
        rng.normal([0.0, 0.0, 0.0], 0.005, size=(600, 3)),
        rng.normal([0.52, 0.0, 0.0], 0.005, size=(400, 3)),
    ])
    # Mean of the mixture: 0.4 * 0.52 = 0.208 (standard error ~0.0002).
    assert point_estimate(pts, method="mean")[0] == pytest.approx(0.208, abs=0.002)
    assert np.linalg.norm(point_estimate(pts)) < 0.02  # the heavier mode
    w = np.concatenate([np.full(600, 1.0), np.full(400, 2.0)])
    assert point_estimate(pts, w)[0] == pytest.approx(0.52, abs=0.02)
    assert np.all(np.isnan(point_estimate(np.empty((0, 3)))))
    with pytest.raises(RecordError):
        point_estimate(pts, np.zeros(1000))


def mode_by_definition(pts: np.ndarray, w: np.ndarray, cell: float = 0.05) -> np.ndarray:
    """point_estimate's mode written out cube by cube: the occupied cube whose mass with its
    26 neighbours is largest (the first in lexicographic order on a tie), the weighted mean of
    the particles of it and its neighbours, then one mean-shift step within one cell."""
    keys = [tuple(k) for k in np.floor(pts / cell).astype(np.int64)]
    mass: dict[tuple, float] = {}
    for k, wi in zip(keys, w, strict=True):
        mass[k] = mass.get(k, 0.0) + wi

    def around(k):
        return [(k[0] + a, k[1] + b, k[2] + c)
                for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)]
    best = max(sorted(mass), key=lambda k: sum(mass.get(n, 0.0) for n in around(k)))
    members = np.array([max(abs(a - b) for a, b in zip(k, best, strict=True)) <= 1
                        for k in keys])
    centre = (pts[members] * w[members, None]).sum(axis=0) / w[members].sum()
    near = np.linalg.norm(pts - centre, axis=1) <= cell
    return (pts[near] * w[near, None]).sum(axis=0) / w[near].sum()


def test_point_estimate_mode_is_the_heaviest_neighbourhood():
    rng = np.random.default_rng(7)
    for _ in range(40):
        n = int(rng.integers(1, 400))
        centres = rng.normal(0.0, 0.3, (int(rng.integers(1, 4)), 3))
        spread = rng.choice([0.002, 0.03, 0.12])
        pts = centres[rng.integers(0, len(centres), n)] + rng.normal(0.0, spread, (n, 3))
        w = rng.random(n) + 1e-3
        assert np.allclose(point_estimate(pts, w), mode_by_definition(pts, w), atol=1e-12)


def test_truth_from_dict():
    truth = {"objects": {
        "ball_1": {"position": [0, 0, 0.05], "visible": False, "hidden_by": "mug_1"},
        "mug_1": {"position": [0.1, 0, 0.05], "visible": True},
        "hand": {"position": [0.2, 0, 0.3], "visible": True},
        "gone": {"position": None, "visible": False},
        "removed": {"position": [0.5, 0, 0.05], "visible": False, "present": False},
    }}
    objs = truth_from_dict(truth, ignore=["hand"])
    assert set(objs) == {"ball_1", "mug_1"}
    assert objs["ball_1"].hidden_by == "mug_1" and not objs["ball_1"].visible
    assert objs["mug_1"].visible and objs["mug_1"].hidden_by is None
    with pytest.raises(RecordError, match="ball_1"):
        truth_from_dict({"objects": {"ball_1": {"position": [0, math.nan, 0]}}})
    with pytest.raises(RecordError, match="ball_1"):
        truth_from_dict({"objects": {"ball_1": {"position": [0, 0]}}})


def test_records_round_trip_and_bad_line(tmp_path):
    run = occlusion_run()
    run[0].hypotheses["lost-1"] = Hypothesis(np.array([np.nan] * 3), False)
    run[1].timings = FrameTimings(1.0, 2.0, 3.0, 7.5)
    path = tmp_path / "records.jsonl"
    write_records(path, run)
    back = list(read_records(path))
    assert [r.to_json() for r in back] == [r.to_json() for r in run]
    assert evaluate(back).mot.idf1 == pytest.approx(1.0)
    with open(path, "a") as out:
        out.write('{"frame": 9}\n')
    with pytest.raises(RecordError, match=r"records.jsonl:7: .*'time'"):
        list(read_records(path))


def summary_of(kept: list[bool], switches: int, idf1: float | None) -> dict:
    return {
        "frames": 10,
        "objects": [{"id": f"o{i}", "symbols": ["s"], "identity_kept": k}
                    for i, k in enumerate(kept)],
        "id_switches": switches,
        "idf1": idf1,
        "ms_per_frame": {"perception": 0, "anchoring": 0, "filter": 0, "total": 0},
        "rejected_percepts": 0,
    }


def test_results_table_groups_runs_by_scenario_and_method(tmp_path):
    from probanchor.evaluation import aggregate, results_table, rows_from_summaries

    rows = [
        ("shell_game", "reasoning", summary_of([True, True, True], 0, 1.0)),
        ("shell_game", "reasoning", {**summary_of([True, False, True], 2, 0.8),
                                     "ambiguous_reacquisitions": 3,
                                     "beliefs": {"hidden_frames": 30, "within": 0.5,
                                                 "occluder_frames": 20,
                                                 "true_occluder_probability": 0.4,
                                                 "threshold": 0.1}}),
        ("shell_game", "SORT", switch_run()),  # records are evaluated on the spot
        ("transitive", "reasoning", summary_of([], 0, None)),
    ]
    table = aggregate(rows)
    assert [(r.scenario, r.method, r.runs) for r in table] == [
        ("shell_game", "reasoning", 2), ("shell_game", "SORT", 1), ("transitive", "reasoning", 1)
    ]
    first = table[0]
    assert (first.objects_kept, first.objects, first.runs_kept) == (5, 6, 1)
    assert first.id_switches_mean == 1.0 and first.idf1_mean == pytest.approx(0.9)
    assert (table[1].objects_kept, table[1].id_switches_mean, table[1].idf1_mean) == (0, 2.0, 0.5)
    assert table[2].runs_kept == 0 and table[2].idf1_mean is None  # no objects: not "kept"
    text = results_table(rows)
    lines = text.splitlines()
    assert lines[0].startswith("| scenario | method | runs | identity kept (objects)")
    assert lines[0].endswith("| IDF1 | HOTA | DetA | AssA | LocA | ambiguous (runs) "
                             "| belief within 10 cm | P(true occluder) |")
    # summaries written before HOTA have none: "-"
    assert lines[2] == ("| shell_game | reasoning | 2 | 5/6 (83 %) | 1/2 (50 %) | 1/2 (50 %) "
                        "| 1.00 | 0.900 | - | - | - | - | 1/2 | 50 % | 0.40 |")
    assert lines[4] == ("| transitive | reasoning | 1 | - | 0/1 (0 %) | 0/1 (0 %) | 0.00 | - "
                        "| - | - | - | - | 0/1 | - | - |")
    # records evaluated on the spot have HOTA (the switch run's, by hand in test_hota.py)
    assert lines[3] == ("| shell_game | SORT | 1 | 0/2 (0 %) | 0/1 (0 %) | 0/1 (0 %) | 2.00 "
                        "| 0.500 | 0.577 | 1.000 | 0.333 | 1.000 | 0/1 | - | - |")
    # identity kept at the end: an object whose answers were revised counts there
    revised = summary_of([True, False, True], 2, 0.8)
    revised["objects"][1]["identity_kept_at_end"] = True
    (row,) = aggregate([("s", "m", revised), ("s", "m", summary_of([True], 0, 1.0))])
    assert (row.runs_kept, row.runs_kept_at_end) == (1, 2)

    # From saved summaries: names from the summary's own fields, else from the folders.
    a = tmp_path / "shell_game" / "SORT" / "summary.json"
    write_summary(a, switch_run())
    b = tmp_path / "elsewhere" / "summary.json"
    write_summary(b, occlusion_run(), extra={"scenario": "can_under_box", "method": "reasoning"})
    got = [(s, m, d["idf1"]) for s, m, d in rows_from_summaries([a, b])]
    assert got == [("shell_game", "SORT", 0.5), ("can_under_box", "reasoning", 1.0)]


def test_record_for_frame_from_a_percept_frame():
    from probanchor.evaluation import record_for_frame
    from probanchor.percepts import Percept, PerceptFrame

    def p(truth_id):
        return Percept(0.5, [0, 0, 0.03], [0.06] * 3, [1.0], {"ball": 1.0}, truth_id=truth_id)

    frame = PerceptFrame(
        7, 0.5, [p("ball_1"), p(None), p("hand_1")],
        truth={"objects": {"ball_1": {"position": [0, 0, 0.03], "visible": True}}},
        rejected=["x.jsonl:8: percept 3: position contains NaN"],
    )
    hyps = {"ball-1": Hypothesis(np.array([0, 0, 0.03]), True)}
    matches = [(frame.percepts[0], "ball-1"), (frame.percepts[1], "glitch-1"),
               (frame.percepts[2], "skin-1")]
    r = record_for_frame(frame, hyps, matches, FrameTimings(1, 2, 3), ignore=["hand_1"])
    assert (r.frame, r.time, r.rejected_percepts) == (7, 0.5, 1)
    assert r.assignments == {"ball_1": "ball-1"}
    assert list(r.truth) == ["ball_1"] and r.timings.total_ms() == 6
    frame.truth = {"objects": {"ball_1": {"visible": True}}}
    with pytest.raises(RecordError, match="frame 7: truth object 'ball_1': no position"):
        record_for_frame(frame, hyps, matches)


def test_an_object_split_into_two_percepts_is_judged_by_its_main_view():
    """A mug whose handle is segmented on its own for a frame: the handle's new anchor is a
    phantom, the mug keeps the symbol of its body (the larger percept), whichever comes first."""
    from probanchor.evaluation import record_for_frame
    from probanchor.percepts import Percept, PerceptFrame

    body = Percept(0.5, [0.35, 0.06, 0.05], [0.08, 0.08, 0.1], [1.0], {"mug": 1.0},
                   truth_id="mug_4", bbox=(247, 91, 279, 126))
    handle = Percept(0.5, [0.41, 0.06, 0.04], [0.02, 0.02, 0.08], [1.0], {"cup": 1.0},
                     truth_id="mug_4", bbox=(274, 103, 284, 116))
    frame = PerceptFrame(218, 0.5, [body, handle],
                         truth={"objects": {"mug_4": {"position": [0.36, 0.06, 0.05],
                                                      "visible": True}}})
    hyps = {"mug-4": Hypothesis(np.array([0.35, 0.06, 0.05]), True),
            "cup-1": Hypothesis(np.array([0.41, 0.06, 0.04]), True)}
    for matches in ([(body, "mug-4"), (handle, "cup-1")], [(handle, "cup-1"), (body, "mug-4")]):
        assert record_for_frame(frame, hyps, matches).assignments == {"mug_4": "mug-4"}
    # without boxes, the 3-D size decides
    body.bbox = handle.bbox = (0, 0, 0, 0)
    assert record_for_frame(frame, hyps, [(body, "mug-4"), (handle, "cup-1")]).assignments == {
        "mug_4": "mug-4"}
