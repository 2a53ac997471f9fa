"""The live world model's query server (`anchoring run --serve`), without a run: a query is
answered on the world model of a frame done after it came, says which frame; a query that could
do more than read is refused, one that takes too long is stopped; only this machine's names are
served; the run's end leaves its last world model to answer."""

from __future__ import annotations

import http.client
import json
import threading
import time

import pytest

from probanchor.loop import live
from probanchor.loop.live import LiveError, LiveWorld, ask


def facts(frame: int) -> list[str]:
    """A world file of one hidden ball, under the mug in even frames and the box in odd."""
    occluder = "mug_1" if frame % 2 == 0 else "box_1"
    return [":- dynamic anchor/5, attribute/3, particle/2, particle_fact/2, identity/3, "
            "world_frame/2.",
            f"world_frame({frame}, {frame / 10!r}).",
            "anchor(ball_1, 'ball-1', ball, false, 0.0).",
            "particle(0, 0.75).", "particle(1, 0.25).",
            f"particle_fact(0, occluded_by(ball_1, {occluder})).",
            "particle_fact(1, occluded_by(ball_1, table)).",
            "particle_fact(0, pos(ball_1, (0.1, 0.2, 0.03))).",
            "particle_fact(1, pos(ball_1, (0.3, 0.2, 0.03))).", ""]


@pytest.fixture
def world():
    served = LiveWorld(0)
    yield served
    served.close()


def _frames_until(world: LiveWorld, done: threading.Event, start: int = 0) -> int:
    """Play frames (one per 20 ms) until ``done``; the last frame played."""
    frame = start
    while not done.is_set() and frame < start + 2000:
        world.frame_done(frame, frame / 10, lambda f=frame: facts(f))
        frame += 1
        time.sleep(0.02)
    return frame - 1


def _ask_while_playing(world: LiveWorld, query: str, **kwargs) -> tuple[dict, int]:
    """Ask while frames are played; the answer and the last frame done when it was asked."""
    world.frame_done(0, 0.0, lambda: facts(0))
    result: dict = {}
    done = threading.Event()

    def asking() -> None:
        try:
            result["asked_after"] = world.last_frame()[0]
            result["reply"] = ask(query, world.port, **kwargs)
        except LiveError as exc:
            result["error"] = str(exc)
        done.set()

    thread = threading.Thread(target=asking)
    thread.start()
    _frames_until(world, done, 1)
    thread.join(timeout=120)
    if "error" in result:
        raise LiveError(result["error"])
    return result["reply"], result["asked_after"]


def test_a_query_is_answered_on_a_frame_done_after_it_came_and_names_it(world) -> None:
    reply, asked_after = _ask_while_playing(world, "hidden_under(ball_1, O, P), P > 0.5")
    frame = reply["frame"]
    assert frame >= asked_after and reply["time"] == pytest.approx(frame / 10)
    expected = "mug_1" if frame % 2 == 0 else "box_1"  # the named frame's own world model
    assert reply["answers"] == [{"O": expected, "P": 0.75}] and not reply["truncated"]


def test_queries_that_could_do_more_than_read_are_refused(world) -> None:
    for query in ("shell('touch /tmp/x')", "prob(shell(ls), P)",
                  "open('/etc/passwd', read, S)", "consult('/etc/passwd')"):
        with pytest.raises(LiveError, match="No permission"):
            _ask_while_playing(world, query)



def test_what_a_query_changes_is_undone_after_it() -> None:
    answers = live.PrologAnswers()
    snapshot = live.Snapshot(3, 0.3, "\n".join(facts(3)))
    try:  # two queries on one loaded world model: the first's changes are gone for the second
        changed = answers.ask(snapshot, "retractall(particle(_, _)), assertz(anchor(x, y, z, "
                                        "true, 0.0)), anchors(As)", 10)
        assert changed["answers"] == [{"As": ["ball_1", "x"]}]
        again = answers.ask(snapshot, "anchors(As), aggregate_all(count, particle(_, _), N)", 10)
        assert again["answers"] == [{"As": ["ball_1"], "N": 2}]
    finally:
        answers.close()


def test_a_query_past_its_time_limit_is_stopped(world, monkeypatch) -> None:
    monkeypatch.setattr(live, "TIME_LIMIT", 1.0)
    with pytest.raises(LiveError, match="took longer than its time limit"):
        _ask_while_playing(world, "repeat, fail")
    reply, _ = _ask_while_playing(world, "anchor(A, _, _, _, _)")  # and it answers on
    assert reply["answers"] == [{"A": "ball_1"}]


def test_answers_are_truncated_and_bad_queries_named(world) -> None:
    reply, _ = _ask_while_playing(world, "between(1, 5000, X)")
    assert len(reply["answers"]) == live.MAX_ANSWERS and reply["truncated"]
    with pytest.raises(LiveError, match="Syntax error"):
        _ask_while_playing(world, "hidden_under(A, O")


def test_only_this_machines_names_are_served(world) -> None:
    world.frame_done(0, 0.0, lambda: facts(0))
    connection = http.client.HTTPConnection("127.0.0.1", world.port, timeout=30)
    connection.request("GET", "/frame", headers={"Host": "attacker.example:80"})
    assert connection.getresponse().status == 403
    connection = http.client.HTTPConnection("127.0.0.1", world.port, timeout=30)
    connection.request("GET", "/frame")
    response = connection.getresponse()
    assert response.status == 200 and json.loads(response.read()) == {"frame": 0, "time": 0.0}


def test_after_the_run_its_last_world_model_answers(world) -> None:
    world.frame_done(6, 0.6, lambda: facts(6))
    world.finish(lambda: facts(7))  # (the run hands over its last frame's facts)
    reply = ask("world_frame(F, T)", world.port)
    assert reply["answers"] == [{"F": 7, "T": 0.7}]


def test_nothing_served_says_how_to_serve() -> None:
    with pytest.raises(LiveError, match="no world model served there .*--serve PORT"):
        ask("true", 1, timeout=5)
