"""The experiment behind the measured table (docs/evaluation.md), on a tiny scale."""

from __future__ import annotations

import json
from pathlib import Path

import yaml

from probanchor.evaluation import results_table
from probanchor.experiments.sweep import game_scenarios, run_method
from probanchor.loop.sources import percept_stream
from test_loop_runner import SCENARIO


def test_generated_games_have_3_to_5_containers_and_3_to_10_swaps(tmp_path: Path) -> None:
    paths = game_scenarios(tmp_path, games=6, first_seed=3)
    assert len(paths) == 6 and len({p.read_text() for p in paths}) == 6
    for path in paths:
        data = yaml.safe_load(path.read_text())
        containers = [o for o in data["objects"] if o["category"] != "ball"]
        assert 3 <= len(containers) <= 5
        swaps = [e for e in data["events"] if e["do"] in ("swap", "shuffle")]
        assert swaps


def test_every_method_runs_on_the_same_cached_stream(tmp_path: Path) -> None:
    scenario = tmp_path / "tiny.yaml"
    scenario.write_text(SCENARIO)
    stream = percept_stream(scenario, seed=1, cache=tmp_path / "percepts")
    mtime = stream.stat().st_mtime_ns
    assert percept_stream(scenario, seed=1, cache=tmp_path / "percepts") == stream
    assert stream.stat().st_mtime_ns == mtime  # cached, not perceived again
    rows = []
    for method in ("reasoning", "no-reasoning", "sort"):
        summary = run_method(method, stream, particles=40, seed=0)
        ball = {o["id"]: o for o in summary["objects"]}["ball_1"]
        assert ball["identity_kept"] is (method == "reasoning"), method
        rows.append(("tiny", method, summary))
    table = results_table(rows)
    assert "| tiny | reasoning | 1 |" in table and "| tiny | sort | 1 |" in table


def test_a_stream_perceived_by_another_classifier_is_perceived_again(tmp_path: Path,
                                                                    monkeypatch) -> None:
    import probanchor.perception.classifier as classifier

    scenario = tmp_path / "tiny.yaml"
    scenario.write_text(SCENARIO)
    cache = tmp_path / "percepts"
    legacy = cache / "tiny_seed1.jsonl"   # a stream cached before streams carried the model
    cache.mkdir()
    legacy.write_text("")
    first = percept_stream(scenario, seed=1, cache=cache)
    assert first.name == f"tiny_seed1.{classifier.model_digest()}.jsonl"
    assert not legacy.exists()
    other = percept_stream(scenario, seed=2, cache=cache)   # another seed's stream stays
    monkeypatch.setattr(classifier, "model_digest", lambda path=None: "0123456789ab")
    again = percept_stream(scenario, seed=1, cache=cache)
    assert again.name == "tiny_seed1.0123456789ab.jsonl" and again.stat().st_size > 0
    assert not first.exists() and other.exists()


def test_a_rerun_keeps_recorded_units_and_runs_only_new_ones(tmp_path, monkeypatch) -> None:
    import probanchor.experiments.sweep as experiment

    calls: list[tuple[str, int]] = []
    methods_run: list[tuple[str, int, list[str]]] = []

    def fake_unit(label, scenario, seed, methods, particles, cache, threads, engine):
        calls.append((scenario.stem, seed))
        methods_run.append((scenario.stem, seed, list(methods)))
        kept = seed % 2 == 0
        return [{"scenario": scenario.stem, "group": label, "seed": seed, "method": m,
                 "particles": particles, "threads": threads, "engine": engine,
                 "summary": {"objects": [{"id": "ball_1", "symbols": ["ball-1"],
                                          "identity_kept": kept}],
                             "id_switches": 0, "idf1": 1.0, "hota": 1.0}}
                for m in methods]

    monkeypatch.setattr(experiment, "run_unit", fake_unit)
    options = experiment.ExperimentOptions(out=tmp_path, seeds=2, games=0, particles=50,
                                           methods=("reasoning",), scenarios=("transitive",))
    table = experiment.run_experiment(options)
    assert calls == [("transitive", 0), ("transitive", 1)]
    assert "| transitive | reasoning | 2 | 1/2 (50 %) | 1/2 (50 %) |" in table

    calls.clear()
    options.seeds = 3                      # one more seed: only it runs
    table = experiment.run_experiment(options)
    assert calls == [("transitive", 2)]
    assert "| transitive | reasoning | 3 | 2/3 (67 %) | 2/3 (67 %) |" in table
    assert len(experiment.read_summaries(tmp_path / "summaries.jsonl")) == 3

    calls.clear()
    options.particles = 100                # another particle count: everything runs again
    experiment.run_experiment(options)
    assert calls == [("transitive", 0), ("transitive", 1), ("transitive", 2)]

    calls.clear()
    options.threads = 1                    # another thread count (other random streams): too
    experiment.run_experiment(options)
    assert calls == [("transitive", 0), ("transitive", 1), ("transitive", 2)]

    # lines recorded before the thread count was (no "threads") were made with one thread
    log = tmp_path / "summaries.jsonl"
    lines = experiment.read_summaries(log)
    log.write_text("".join(json.dumps({k: v for k, v in line.items() if k != "threads"}) + "\n"
                           for line in lines if line.get("threads") == 1))
    calls.clear()
    experiment.run_experiment(options)
    assert calls == []

    # another engine (other draws) runs the reasoning again; lines recorded before the engine
    # was (no "engine") were made with the per-particle one
    calls.clear()
    options.engine = "per_particle"
    experiment.run_experiment(options)
    assert calls == [("transitive", 0), ("transitive", 1), ("transitive", 2)]
    lines = experiment.read_summaries(log)
    log.write_text("".join(json.dumps({k: v for k, v in line.items() if k != "engine"}) + "\n"
                           for line in lines if line.get("engine") == "per_particle"))
    calls.clear()
    experiment.run_experiment(options)
    assert calls == []

    # the thread count matters for reasoning only: another one reruns only the reasoning
    options.methods = ("reasoning", "no-reasoning")
    experiment.run_experiment(options)
    assert [m for _, _, ms in methods_run for m in ms][-3:] == ["no-reasoning"] * 3
    methods_run.clear()
    options.threads = 2
    experiment.run_experiment(options)
    assert methods_run == [("transitive", s, ["reasoning"]) for s in range(3)]

    # lines recorded before HOTA was (no "hota" in the summary) are run again
    lines = experiment.read_summaries(log)
    log.write_text("".join(json.dumps({**line, "summary": {k: v for k, v in
                                                           line["summary"].items()
                                                           if k != "hota"}}) + "\n"
                           for line in lines))
    methods_run.clear()
    experiment.run_experiment(options)
    assert methods_run == [("transitive", s, ["reasoning", "no-reasoning"]) for s in range(3)]


def test_the_theory_digest_covers_the_files_the_theory_includes(tmp_path, monkeypatch) -> None:
    """A reasoning method's runs are run again when a file its theory includes changes, not
    only the theory's own file (the shipped theories include prolog/too/*.pl)."""
    import probanchor.experiments.sweep as experiment

    (tmp_path / "parts").mkdir()
    part = tmp_path / "parts" / "motion.pl"
    part.write_text("step:0 ~ val(1).\n")
    theory = tmp_path / "theory.pl"
    theory.write_text(":- include('parts/motion').\nx:0 ~ val(0).\n")
    monkeypatch.setitem(experiment.REASONING, "reasoning", str(theory))
    before = experiment.theory_digest("reasoning")

    calls: list[int] = []

    def fake_unit(label, scenario, seed, methods, particles, cache, threads, engine):
        calls.append(seed)
        return [{"scenario": scenario.stem, "group": label, "seed": seed, "method": m,
                 "particles": particles, "threads": threads, "engine": engine,
                 "theory": experiment.theory_digest(m),
                 "summary": {"objects": [], "id_switches": 0, "idf1": 1.0, "hota": 1.0}}
                for m in methods]

    monkeypatch.setattr(experiment, "run_unit", fake_unit)
    options = experiment.ExperimentOptions(out=tmp_path / "out", seeds=1, games=0,
                                           particles=50, methods=("reasoning",),
                                           scenarios=("transitive",))
    experiment.run_experiment(options)
    experiment.run_experiment(options)
    assert calls == [0]                        # recorded with this theory: kept
    part.write_text("step:0 ~ val(2).\n")     # the included file edited
    assert experiment.theory_digest("reasoning") != before
    experiment.run_experiment(options)
    assert calls == [0, 0]                     # run again


def test_evaluate_plays_the_games_from_the_seed_given(tmp_path, monkeypatch, capsys):
    """``anchoring evaluate --first-game-seed 200``: games the evaluation never used, named by
    their seeds (the options reach the experiment; generating them is game_scenarios')."""
    import probanchor.experiments.sweep as experiment
    from probanchor.cli.anchoring_cli import main

    seen = {}

    def run(options, progress=False):
        seen["games"] = experiment.game_scenarios(options.out, options.games,
                                                  options.first_game_seed)
        return ""

    monkeypatch.setattr(experiment, "run_experiment", run)
    assert main(["evaluate", "--games", "2", "--first-game-seed", "200", "--seeds", "0",
                 "--methods", "sort", "--out", str(tmp_path)]) == 0
    assert [p.name for p in seen["games"]] == ["game_200.yaml", "game_201.yaml"]
    assert "seed200" in seen["games"][0].read_text()
    capsys.readouterr()
    assert main(["evaluate", "--first-game-seed", "-1", "--out", str(tmp_path)]) != 0
    assert "--first-game-seed must be 0 or more, not -1" in capsys.readouterr().err
