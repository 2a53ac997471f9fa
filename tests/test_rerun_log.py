"""The Rerun log of a run, read back with Rerun's own reader: every entity on the frame
timeline, the anchors' boxes and labels, the hidden ball's particles and its occluder's
probability."""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest
from rerun.chunk import RrdReader

from probanchor.loop.runner import RunOptions, run
from probanchor.visualise.rerun_log import RerunLog
from scenario_helpers import scenario_file

SCENARIO = """\
name: ball_under_mug
fps: 5
objects:
  - {id: ball_1, category: ball, colour: red, radius: 0.03, position: [-0.1, -0.05]}
  - {id: mug_1, category: mug, colour: blue, radius: 0.04, height: 0.1, position: [0.05, 0.05]}
events:
  - {at: 1.0, do: put_under, object: ball_1, container: mug_1, duration: 2.0}
  - {at: 4.0, do: lift, container: mug_1, duration: 2.0}
"""


def _read(path: Path) -> dict[str, dict[int, dict[str, object]]]:
    """entity -> frame -> column -> value (the last row of that frame)."""
    out: dict[str, dict[int, dict[str, object]]] = defaultdict(dict)
    for chunk in RrdReader(path).store().stream():
        batch = chunk.to_record_batch()
        if "frame" not in batch.schema.names:
            continue
        columns = {n: batch.column(n).to_pylist() for n in batch.schema.names}
        for row, frame in enumerate(columns["frame"]):
            out[chunk.entity_path][frame] = {n: v[row] for n, v in columns.items()}
    return out


@pytest.fixture(scope="module")
def logged(tmp_path_factory: pytest.TempPathFactory):
    root = tmp_path_factory.mktemp("rerun")
    scenario = scenario_file(tmp_path_factory, SCENARIO, "ball_under_mug")
    output = run(RunOptions(scenario=scenario, particles=60, seed=0, progress=False,
                            rerun=root / "run.rrd"))
    return output, _read(root / "run.rrd"), root / "run.rrd"


def test_every_entity_is_on_the_frame_timeline(logged) -> None:
    output, entities, _ = logged
    frames = set(range(len(output.records)))
    for entity in ("/world/camera", "/world/camera/image", "/world/camera/depth",
                   "/world/cloud", "/world/anchors", "/timings/perception", "/timings/filter"):
        assert set(entities[entity]) == frames, entity


def test_anchors_are_labelled_boxes_and_the_hidden_ball_has_particles(logged) -> None:
    output, entities, _ = logged
    symbols = {o["id"]: o["symbols"][0] for o in output.summary["objects"]}
    ball, mug = symbols["ball_1"], symbols["mug_1"]
    hidden = [r.frame for r in output.records if not r.hypotheses[ball].perceived]
    assert hidden and set(entities[f"/world/particles/{ball}"]) >= set(hidden)
    frame = hidden[len(hidden) // 2]
    boxes = entities["/world/anchors"][frame]
    assert sorted(boxes["Boxes3D:labels"]) == sorted([f"{ball} hidden", mug])
    centres = np.asarray(boxes["Boxes3D:centers"])
    estimate = output.records[frame].hypotheses[ball].position
    assert np.allclose(centres[boxes["Boxes3D:labels"].index(f"{ball} hidden")], estimate,
                       atol=1e-5)
    particles = entities[f"/world/particles/{ball}"][frame]["Points3D:positions"]
    assert len(particles) == 60
    # while hidden the ball is believed under the mug more than anywhere else; once seen
    # again the relation's series falls to 0
    series = {e: v for e, v in entities.items() if e.startswith(f"/occlusion/{ball}/")}
    under = series[f"/occlusion/{ball}/{mug}"]
    assert under[frame]["Scalars:scalars"][0] > 0.5
    assert all(under[frame]["Scalars:scalars"][0] >= v[frame]["Scalars:scalars"][0]
               for v in series.values() if frame in v)
    seen_again = next(r.frame for r in output.records
                      if r.frame > hidden[-1] and r.hypotheses[ball].perceived)
    assert under[seen_again]["Scalars:scalars"] == [0.0]


def test_a_log_needs_a_file_or_the_viewer() -> None:
    with pytest.raises(ValueError, match="needs a file or the viewer"):
        RerunLog(None, spawn=False)


def test_a_frame_of_the_log_is_drawn_from_the_logged_data(logged, tmp_path: Path) -> None:
    from probanchor.visualise.rrd_picture import draw, frame_data

    output, entities, path = logged
    frame = len(output.records) // 2
    data = frame_data(path, frame)
    assert data["/world/anchors"]["Boxes3D:labels"] == \
        entities["/world/anchors"][frame]["Boxes3D:labels"]
    png = draw(path, frame, tmp_path / "view.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
