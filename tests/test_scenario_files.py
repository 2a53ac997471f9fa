"""Scenario files: the shipped ones load; bad ones fail naming file, line and cause."""

from __future__ import annotations

from pathlib import Path

import pytest

from probanchor.tabletop import ScenarioBuilder, ScenarioError, load_scenario

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = sorted((ROOT / "scenarios").rglob("*.yaml"))

GOOD = """\
name: t
objects:
  - {id: ball_1, category: ball, colour: red, position: [0.0, 0.0]}
  - {id: mug_1, category: mug, colour: blue, position: [0.2, 0.0]}
events:
  - {at: 1.0, do: put_under, object: ball_1, container: mug_1}
  - {at: 4.0, do: lift, container: mug_1}
"""


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "scn.yaml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_shipped_scenarios_load(path: Path) -> None:
    scenario = load_scenario(path)
    assert scenario.objects
    assert all(o.id.split("_")[0] == o.category for o in
               scenario.objects)


def test_good_file_loads(tmp_path: Path) -> None:
    scenario = load_scenario(write(tmp_path, GOOD))
    assert [o.id for o in scenario.objects] == ["ball_1", "mug_1"]
    assert [e.kind for e in scenario.events] == ["put_under", "lift"]
    assert scenario.object("ball_1").position[2] == pytest.approx(0.03)


@pytest.mark.parametrize(
    ("old", "new", "line", "cause"),
    [
        ("category: ball", "category: banana", 3, "unknown category 'banana'"),
        ("category: mug, colour", "category: mug, shape: pyramid, colour", 4,
         "unknown shape 'pyramid'"),
        ("container: mug_1}", "container: mug_9}", 6, "unknown object 'mug_9'"),
        ("[0.2, 0.0]", "[0.02, 0.0]", 4, "overlap at the start"),
        ("at: 4.0", "at: 0.5", 7, "times out of order"),
        ("position: [0.0, 0.0]", "position: [.nan, 0.0]", 3, "NaN"),
        ("colour: red", "colour: mauve", 3, "unknown colour 'mauve'"),
        ("do: lift", "do: levitate", 7, "unknown event 'levitate'"),
    ],
)
def test_bad_input_names_file_line_and_cause(tmp_path: Path, old: str, new: str, line: int,
                                              cause: str) -> None:
    assert old in GOOD
    path = write(tmp_path, GOOD.replace(old, new, 1))
    with pytest.raises(ScenarioError) as info:
        load_scenario(path)
    err = info.value
    assert err.line == line, str(err)
    assert cause in str(err)
    assert str(path) in str(err)


def test_yaml_syntax_error_has_a_line(tmp_path: Path) -> None:
    with pytest.raises(ScenarioError) as info:
        load_scenario(write(tmp_path, GOOD.replace("events:", "events: [", 1)))
    assert info.value.line is not None and "not valid YAML" in str(info.value)


def test_a_file_that_is_not_utf8_names_its_line(tmp_path: Path) -> None:
    path = tmp_path / "latin1.yaml"
    path.write_bytes(b"name: x\nfps: 5\n# caf\xe9\n")
    with pytest.raises(ScenarioError, match="not UTF-8 text: byte 0xe9") as info:
        load_scenario(path)
    assert info.value.line == 3


def test_yaml_nested_ten_thousand_deep_is_a_scenario_error(tmp_path: Path) -> None:
    path = tmp_path / "deep.yaml"
    path.write_text("name: x\nobjects: " + "[" * 10000 + "]" * 10000 + "\n")
    with pytest.raises(ScenarioError, match="nested too deeply"):
        load_scenario(path)


def test_object_too_big_for_its_container(tmp_path: Path) -> None:
    text = GOOD.replace("category: ball, colour: red,", "category: ball, colour: red, "
                        "radius: 0.05,")
    with pytest.raises(ScenarioError, match="does not fit under 'mug_1'") as info:
        load_scenario(write(tmp_path, text))
    assert info.value.line == 6


def test_builder_round_trips_through_yaml(tmp_path: Path) -> None:
    b = ScenarioBuilder("built", fps=10)
    b.add("ball_1", "ball", "red", position=(0.0, 0.0))
    b.add("box_1", "box", "green", position=(0.2, 0.0), size=[0.12, 0.12, 0.12])
    b.put_under(1.0, "ball_1", "box_1").move(4.0, "box_1", (0.0, 0.2), speed=0.1)
    built = b.build()
    loaded = b.save(tmp_path / "built.yaml")
    assert [o.id for o in loaded.objects] == [o.id for o in built.objects]
    assert [e.kind for e in loaded.events] == ["put_under", "move"]
    with pytest.raises(ScenarioError, match="unknown object 'cup_7'"):
        ScenarioBuilder("bad").add("ball_1", "ball", "red", position=(0, 0)).lift(
            1.0, "cup_7").build()


@pytest.mark.parametrize(("change", "cause"), [
    ("fps: 1000000\n", "'fps' must be at most 240"),
    ("camera: {width: 100000, height: 100000}\n", "'width' must be at most 4096"),
    ("camera: {position: [0, 0, 1], target: [0, 0, 0]}\n", "looks along its 'up' vector"),
])
def test_limits_of_the_camera_and_the_frame_rate(tmp_path: Path, change: str,
                                                 cause: str) -> None:
    with pytest.raises(ScenarioError, match=cause):
        load_scenario(write(tmp_path, change + GOOD))
