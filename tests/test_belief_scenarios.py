"""Shipped scenarios about what the belief may and may not hold, played end to end."""

from __future__ import annotations

from plunit_runner import ROOT
from probanchor.evaluation import evaluate, make_summary
from probanchor.loop.loop import AnchoringLoop, FrameOutcome, run_frames
from probanchor.loop.runner import RunOptions
from probanchor.loop.sources import scenario_frames


def test_a_ball_removed_unseen_beside_an_upright_can_is_never_under_it() -> None:
    """scenarios/can_beside_removed_ball.yaml: the camera is covered while the ball, 7 cm from
    a can, is taken away; the can is then carried off. The ball's belief may put it under the
    mug, never under the can (which covers nothing), in any frame."""
    options = RunOptions(scenario=ROOT / "scenarios" / "can_beside_removed_ball.yaml",
                         particles=200, seed=0, threads=1)
    loop = AnchoringLoop(options)
    under_can: list[float] = []
    under_mug: list[float] = []

    def on_frame(outcome: FrameOutcome, loop: AnchoringLoop) -> None:
        assert loop.reasoner is not None
        if "ball-1" in loop.manager and "can-1" in loop.manager:
            under_can.append(loop.reasoner.probability("occluded_by(ball_1, can_1):t"))
            under_mug.append(loop.reasoner.probability("occluded_by(ball_1, mug_1):t"))

    try:
        assert options.scenario is not None
        records = run_frames(scenario_frames(options.scenario, seed=0), loop, on_frame,
                             overlap=False)
    finally:
        loop.close()
    assert len(under_can) > 100 and max(under_can) == 0.0
    assert max(under_mug) > 0.5  # the mug, the one candidate, explains the vanished ball
    summary = make_summary(records, evaluate(records))
    assert all(o["identity_kept"] for o in summary["objects"])


def test_look_alikes_swapped_unseen_are_reported_ambiguous() -> None:
    """scenarios/lookalikes_swapped_unseen.yaml: two identical balls under two identical mugs,
    the mugs swapped while the camera is covered. Nothing seen tells the balls apart: the run
    names them (by where the mugs are believed) and reports the mugs' and a ball's
    re-acquisition as ambiguous, each candidate equally likely."""
    from probanchor.loop.runner import run

    output = run(RunOptions(scenario=ROOT / "scenarios" / "lookalikes_swapped_unseen.yaml",
                            particles=200, seed=0, threads=1, progress=False))
    assert output.summary["ambiguous_reacquisitions"] >= 3
    reported = [a for r in output.records for a in r.ambiguous.values()]
    assert {frozenset(c) for c in reported} == {frozenset({"mug-1", "mug-2"}),
                                               frozenset({"ball-1", "ball-2"})}
    assert all(sorted(c.values()) == [0.5, 0.5] for c in reported)


def test_a_look_alike_uncovered_while_the_original_is_hidden_is_a_new_object() -> None:
    """scenarios/lookalike_while_hidden.yaml: ball_2 appears 33 cm from where every particle of
    the boxed ball_1 is; it gets a symbol of its own, and ball_1 keeps its symbol."""
    from probanchor.loop.runner import run

    output = run(RunOptions(scenario=ROOT / "scenarios" / "lookalike_while_hidden.yaml",
                            particles=200, seed=0, threads=1, progress=False))
    objects = {o["id"]: o for o in output.summary["objects"]}
    assert all(o["identity_kept"] for o in objects.values())
    assert objects["ball_1"]["symbols"] != objects["ball_2"]["symbols"]


def test_the_world_model_answers_the_probability_of_an_identity(tmp_path) -> None:
    """After the unseen swap, world.pl answers prob(identity(Percept, Atom), P) for each
    ambiguous re-acquisition, and refuses a percept that was not ambiguous."""
    import subprocess

    from plunit_runner import swipl_executable
    from probanchor.loop.runner import run

    output = run(RunOptions(scenario=ROOT / "scenarios" / "lookalikes_swapped_unseen.yaml",
                            particles=100, seed=0, threads=1, progress=False, out=tmp_path,
                            picture_every=1000))
    ball = next(r for r in output.records for s in r.ambiguous if s.startswith("ball"))
    symbol = next(s for s in ball.ambiguous if s.startswith("ball"))
    query = (f"ambiguous(percept({ball.frame}, I), D), member(_-{symbol.replace('-', '_')}, D),"
             f" prob(identity(percept({ball.frame}, I), ball_1), P1),"
             f" prob(identity(percept({ball.frame}, I), mug_1), P0),"
             " catch(prob(identity(percept(0, 0), ball_1), _), E, true),"
             " format('~w ~w ~w~n', [P1, P0, E]), halt")
    done = subprocess.run([swipl_executable(), "-q", "-g", query, "-t", "halt(1)",
                           str(ROOT / "prolog" / "shell" / "world.pl"), str(tmp_path / "world.pl")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    p1, p0, error = done.stdout.split(maxsplit=2)
    # nothing decides which ball it is: as the particles answer it at the end, either ball
    # keeps a share (the model's prior that things lost while the camera saw nothing stayed
    # about where they were favours the answer as given, so not an even split), a mug none
    assert 0.1 < float(p1) < 0.9 and float(p0) == 0.0
    assert "existence_error(ambiguous_percept" in error


def test_what_a_container_hides_revises_which_container_it_is() -> None:
    """scenarios/identity_revealed.yaml: two identical mugs, a red ball under one and a blue
    one under the other, swapped unseen. Re-acquired, the mugs are named by where they had
    been (wrongly); lifting the left one shows the blue ball, put under the other mug: the
    mugs' symbols are revised, and at the end every object has its own symbol. Without the
    identity hypotheses (decided once), they end with each other's symbols."""
    from probanchor.loop.runner import run

    scenario = ROOT / "scenarios" / "identity_revealed.yaml"
    output = run(RunOptions(scenario=scenario, particles=500, seed=0, threads=1,
                            progress=False))
    summary = output.summary
    revisions = summary["revisions"]
    assert [sorted(r["mapping"].items()) for r in revisions] == \
        [[("mug-1", "mug-2"), ("mug-2", "mug-1")]]
    revision = revisions[0]
    assert revision["probability"] >= 2 * revision["before"]
    assert revision["evidence"] and all(s.startswith("ball") for s in revision["evidence"])
    # re-acquired after the camera was covered, before the lift that decided it
    assert min(revision["since"].values()) < revision["frame"]
    objects = {o["id"]: o for o in summary["objects"]}
    assert all(o["identity_kept_at_end"] for o in objects.values())
    assert not objects["mug_1"]["identity_kept"]  # the answers as given were wrong a while
    record = next(r for r in output.records if r.revised)
    assert record.revised == [revision]
    decided_once = run(RunOptions(scenario=scenario, particles=500, seed=0, threads=1,
                                  progress=False, identity=False)).summary
    assert decided_once["revisions"] == []
    assert not all(o["identity_kept_at_end"] for o in decided_once["objects"])


FAR_SWAP = """\
name: far_swap_revealed
fps: 15
objects:
  - {id: ball_1, category: ball, colour: yellow, radius: 0.03, position: [0.3, -0.1]}
  - {id: ball_2, category: ball, colour: blue, radius: 0.03, position: [-0.3, 0.25]}
  - {id: mug_1, category: mug, colour: gray, radius: 0.045, height: 0.1, position: [0.32, 0.22]}
  - {id: mug_2, category: mug, colour: gray, radius: 0.045, height: 0.1, position: [-0.32, -0.1]}
events:
  - {at: 0.5, do: put_under, object: ball_1, container: mug_1, duration: 1.5}
  - {at: 2.3, do: put_under, object: ball_2, container: mug_2, duration: 1.5}
  - {at: 4.3, do: cover_camera, duration: 3.5}
  - {at: 4.6, do: swap, a: mug_1, b: mug_2, duration: 3.0}
  - {at: 9.0, do: lift, container: mug_1, duration: 2.0}
"""


def test_a_swap_the_theory_finds_improbable_is_kept_until_a_lift_decides_it(tmp_path) -> None:
    """Two look-alike mugs, each over a ball of its own colour, swapped 70 cm apart while the
    camera is covered. The learned theory's prior of an unseen move leaves the swap a weight
    that 200 particles may not hold (plain resampling drops it and, with it, the question, in
    this seed and seeds 1, 2 and 5 to 7; in seeds 3 and 4 it keeps it by chance); resampled by
    the identity answers, the swap keeps its particles (in each of seeds 0 to 7) until lifting
    a mug shows the other's ball, and the mugs' symbols are revised."""
    import anchoring.identity
    from probanchor.loop.runner import run
    from probanchor.loop.theories import theory_path

    scenario = tmp_path / "far_swap.yaml"
    scenario.write_text(FAR_SWAP)
    options = RunOptions(scenario=scenario, particles=200, seed=0, threads=1, progress=False,
                         theory=theory_path("learned"))
    summary = run(options).summary
    assert [sorted(r["mapping"].items()) for r in summary["revisions"]] == \
        [[("mug-1", "mug-2"), ("mug-2", "mug-1")]]
    assert all(o["identity_kept_at_end"] for o in summary["objects"])
    strata = anchoring.identity.IdentityHypotheses.strata
    try:
        anchoring.identity.IdentityHypotheses.strata = lambda self: None  # type: ignore
        plain = run(options).summary
    finally:
        anchoring.identity.IdentityHypotheses.strata = strata  # type: ignore[method-assign]
    assert plain["revisions"] == []
    assert not all(o["identity_kept_at_end"] for o in plain["objects"])


HAND_TAKES_BOX = """\
name: hand_takes_box
fps: 15
objects:
  - {id: ball_1, category: ball, colour: orange, radius: 0.03, position: [0.1, 0.15]}
  - {id: box_1, category: box, colour: green, size: [0.09, 0.09, 0.09], position: [-0.15, 0.0]}
  - {id: ball_2, category: ball, colour: orange, radius: 0.03, position: [-0.3, 0.2]}
events:
  - {at: 0.5, do: put_under, object: ball_1, container: box_1, duration: 2.0}
  - {at: 3.0, do: pick_up, object: box_1, duration: 1.5}
  - {at: 4.6, do: move, object: box_1, to: [0.3, -0.1, 0.15], duration: 1.5}
  - {at: 6.5, do: put_down, object: box_1, to: [0.3, -0.1], duration: 1.5}
  - {at: 9.0, do: move, object: ball_2, to: [0.0, 0.3], duration: 2.0}
"""


def test_a_box_a_hand_carries_off_is_followed_by_the_learned_theories(tmp_path) -> None:
    """A hand lifts a small box off a ball, carries it, hidden in the hand, 50 cm and puts it
    down. The learned theories know boxes are hidden (by hands, in the games they learn from),
    so the box is carried in the particles and re-acquired as itself where it is put down (a
    theory learned from games where hands took only balls and cans lost it: a new anchor)."""
    from probanchor.loop.runner import run
    from probanchor.loop.theories import theory_path

    scenario = tmp_path / "hand_takes_box.yaml"
    scenario.write_text(HAND_TAKES_BOX)
    for theory in ("learned", "hindsight"):
        summary = run(RunOptions(scenario=scenario, particles=300, seed=0, threads=1,
                                 progress=False, theory=theory_path(theory))).summary
        assert all(o["identity_kept"] for o in summary["objects"]), (theory, summary["objects"])
