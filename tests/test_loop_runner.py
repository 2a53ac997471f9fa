"""The main job end to end on a short scenario: perception -> anchoring -> filter -> anchors."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from plunit_runner import ROOT, swipl_executable
from probanchor.loop.runner import RunOptions, run
from scenario_helpers import BALL_UNDER_MUG_MOVED as SCENARIO
from scenario_helpers import scenario_file


@pytest.fixture(scope="module")
def scenario(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return scenario_file(tmp_path_factory)


@pytest.fixture(scope="module")
def reasoning_run(scenario: Path, tmp_path_factory: pytest.TempPathFactory):
    out = tmp_path_factory.mktemp("run")
    return run(RunOptions(scenario=scenario, particles=60, seed=0, out=out, progress=False,
                          picture_every=4))


def test_the_ball_is_reacquired_as_ball_1_after_the_mug_moved(reasoning_run) -> None:
    objects = {o["id"]: o for o in reasoning_run.summary["objects"]}
    assert len(objects["ball_1"]["symbols"]) == 1  # ball-1 or ball-2: whichever it got first
    assert objects["ball_1"]["identity_kept"] is True
    assert objects["ball_2"]["identity_kept"] is True
    assert objects["mug_1"]["identity_kept"] is True


def test_without_reasoning_the_revealed_ball_is_a_new_anchor(scenario: Path) -> None:
    output = run(RunOptions(scenario=scenario, reasoning=False, progress=False))
    objects = {o["id"]: o for o in output.summary["objects"]}
    assert objects["ball_1"]["identity_kept"] is False
    assert len(objects["ball_1"]["symbols"]) >= 2


def test_reidentification_by_appearance_is_anchorings_own_and_can_be_switched_off(
        tmp_path: Path) -> None:
    # one red ball only: without reasoning, anchoring re-identifies it by appearance (the only
    # anchor left over that looks like it); with that switched off it becomes a new anchor
    single = "\n".join(line for line in SCENARIO.splitlines()
                        if "ball_2" not in line and "box_1" not in line)
    path = tmp_path / "one_ball.yaml"
    path.write_text(single + "\n")
    kept = {}
    for reidentify in (True, False):
        output = run(RunOptions(scenario=path, reasoning=False, reidentify=reidentify,
                                progress=False))
        kept[reidentify] = {o["id"]: o for o in output.summary["objects"]}["ball_1"]
    assert kept[True]["identity_kept"] is True
    assert kept[False]["identity_kept"] is False and len(kept[False]["symbols"]) >= 2


def test_outputs_summary_video_and_world(reasoning_run) -> None:
    out = reasoning_run.out
    summary = json.loads((out / "summary.json").read_text())
    for key in ("frames", "objects", "id_switches", "idf1", "ms_per_frame"):
        assert key in summary
    assert set(summary["ms_per_frame"]) >= {"perception", "anchoring", "filter", "total"}
    assert summary["frames"] == len(reasoning_run.records)
    assert (summary["particles"], summary["threads"]) == (60, 2)  # the filter's, as run
    # the video decodes: one picture every 4 frames, none as PNG unless asked for
    assert reasoning_run.video == out / "run.mp4"
    assert len(decoded_frames(reasoning_run.video)) == (summary["frames"] + 3) // 4
    assert reasoning_run.pictures == [] and not (out / "frames").exists()
    # the world file answers questions in swipl through prolog/shell/world.pl
    objects = {o["id"]: o for o in summary["objects"]}
    ball = objects["ball_1"]["symbols"][0].replace("-", "_")  # its anchor's atom
    goal = (f"anchors(As), memberchk({ball}, As), prob(pos({ball}, _), P), "
            f"prob(occluded_by({ball}, _), Q), format('~w ~w~n', [P, Q]), halt")
    result = subprocess.run(
        [swipl_executable(), "-q", "-g", goal, "-t", "halt(1)",
         str(ROOT / "prolog" / "shell" / "world.pl"), str(out / "world.pl")],
        capture_output=True, text=True, timeout=60,
    )
    assert result.returncode == 0, result.stderr
    assert "Warning" not in result.stderr, result.stderr   # it loads without a word
    p_known, p_hidden = (float(v) for v in result.stdout.split())
    assert p_known == pytest.approx(1.0)  # every particle knows where the ball is
    assert p_hidden == pytest.approx(0.0)  # and none has it under the mug: it is seen at the end


def decoded_frames(video: Path) -> list:
    import av

    with av.open(str(video)) as container:
        return [f.to_ndarray(format="rgb24") for f in container.decode(video=0)]


def folder_bytes(folder: Path) -> int:
    return sum(p.stat().st_size for p in folder.rglob("*") if p.is_file())


def test_run_from_the_command_line_to_a_pipe(scenario: Path, tmp_path: Path) -> None:
    """Output to a pipe (CI, a log file): progress as a few whole lines, never carriage-return
    redraws; a run's folder small enough that the 331-frame shell game stays within 10 MB;
    --frames adds the PNGs."""
    out = tmp_path / "out"
    result = subprocess.run(
        [str(Path(sys.executable).parent / "anchoring"), "run", str(scenario), "--particles",
         "30", "--out", str(out), "--frames", "--every", "2"],
        capture_output=True, text=True, timeout=300,
    )
    assert result.returncode == 0, result.stderr
    summary = json.loads((out / "summary.json").read_text())
    frames = summary["frames"]
    progress = [line for line in result.stderr.splitlines() if "frames" in line]
    assert "\r" not in result.stderr
    assert 2 <= len(progress) <= 12, result.stderr  # start, every tenth, end
    assert progress[-1].startswith(f"{scenario.stem}: {frames}/{frames} frames (100 %)")
    assert "run.mp4" in result.stdout
    pictures = sorted((out / "frames").glob("frame_*.png"))
    assert len(pictures) == (frames + 1) // 2
    video = decoded_frames(out / "run.mp4")
    assert len(video) == len(pictures) and video[0].shape == (240, 320, 3)
    # Without the PNGs, a frame costs so little that the shell game's 331 frames (drawn at
    # every frame) stay within 10 MB: the bound per frame, with the video counted twice
    # (this run draws every other frame).
    without_png = folder_bytes(out) - folder_bytes(out / "frames")
    video_bytes = (out / "run.mp4").stat().st_size
    assert (without_png + video_bytes) / frames <= 10e6 / 331


def test_a_theory_with_an_error_stops_the_run_before_the_first_frame(
        scenario: Path, tmp_path: Path) -> None:
    theory = tmp_path / "broken.pl"
    theory.write_text("ok := true.\nbroken(X := .\n")
    result = subprocess.run(
        [str(Path(sys.executable).parent / "anchoring"), "run", str(scenario), "--theory",
         str(theory), "--quiet", "--out", str(tmp_path / "out")],
        capture_output=True, text=True, timeout=120,
    )
    assert result.returncode != 0
    assert f"{theory}:2" in result.stderr
    assert not (tmp_path / "out" / "summary.json").exists()


def test_a_percept_with_nan_is_dropped_counted_and_the_run_goes_on(tmp_path: Path) -> None:
    from percept_helpers import ball_percept as ball
    from probanchor.percepts import PerceptFrame, write_percepts

    frames = []
    for k in range(6):
        percepts = [ball(k / 5, 0.1)]
        if k == 2:
            bad = ball(k / 5, 0.3)
            bad.position[1] = float("nan")
            percepts.append(bad)
        frames.append(PerceptFrame(k, k / 5, percepts))
    stream = tmp_path / "stream.jsonl"
    write_percepts(stream, frames)
    output = run(RunOptions(percepts=stream, particles=20, progress=False))
    assert output.summary["frames"] == 6
    assert output.summary["rejected_percepts"] == 1


def test_the_same_command_and_seed_give_the_same_run(scenario: Path, reasoning_run,
                                                     tmp_path: Path) -> None:
    """Perception (the table plane), anchoring and the filter are all seeded: a second run
    writes the same summary and records, bar the measured milliseconds."""
    again = run(RunOptions(scenario=scenario, particles=60, seed=0, out=tmp_path,
                           progress=False, picture_every=4))

    def without_timings(path: Path) -> list[dict]:
        rows = [json.loads(line) for line in path.read_text().splitlines()]
        for row in rows:
            row.pop("timings", None)
        return rows

    assert again.out is not None and reasoning_run.out is not None
    assert without_timings(again.out / "records.jsonl") == \
        without_timings(reasoning_run.out / "records.jsonl")
    first = json.loads((reasoning_run.out / "summary.json").read_text())
    second = json.loads((again.out / "summary.json").read_text())
    first.pop("ms_per_frame")
    second.pop("ms_per_frame")
    assert first == second


def _ball_stream(tmp_path: Path, frames: int = 8, truth_of: dict | None = None) -> Path:
    from percept_helpers import ball_percept as ball
    from probanchor.percepts import PerceptFrame, write_percepts

    stream = tmp_path / "stream.jsonl"
    write_percepts(stream, [PerceptFrame(k, k / 5, [ball(k / 5, 0.1)],
                                         (truth_of or {}).get(k, {}))
                            for k in range(frames)])
    return stream


def test_lines_that_are_not_frames_are_skipped_counted_and_the_run_goes_on(
        tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    stream = _ball_stream(tmp_path)
    lines = stream.read_text().splitlines()
    lines.insert(3, "this is not JSON")
    stream.write_text("\n".join(lines) + "\n" + lines[-1][:25])  # a truncated last line
    output = run(RunOptions(percepts=stream, particles=20, progress=False, out=tmp_path / "o"))
    assert output.summary["frames"] == 8
    assert output.summary["skipped_frames"] == 2
    assert f"{stream}:4" in caplog.text and f"{stream}:10" in caplog.text
    assert (tmp_path / "o" / "summary.json").exists()


def test_a_run_stopped_by_an_error_writes_what_it_did(tmp_path: Path) -> None:
    """A malformed ground truth in frame 5 stops the run: the error is raised, and the summary
    and the records of frames 0-4 are written first, the summary saying why it stopped."""
    from probanchor.evaluation import RecordError

    bad = {5: {"objects": {"ball_1": {"visible": True}}}}  # no position
    stream = _ball_stream(tmp_path, truth_of=bad)
    out = tmp_path / "o"
    with pytest.raises(RecordError, match="frame 5"):
        run(RunOptions(percepts=stream, particles=20, progress=False, out=out))
    summary = json.loads((out / "summary.json").read_text())
    assert summary["frames"] == 5 and "after 5 frames: RecordError" in summary["stopped"]
    assert len((out / "records.jsonl").read_text().splitlines()) == 5
