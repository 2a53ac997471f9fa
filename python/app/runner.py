"""A whole run: frames from a scenario or a percept stream through the loop, then the summary,
pictures, GIF and world file in an output directory."""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from tqdm import tqdm

from app.loop import AnchoringLoop, FrameOutcome, LoopConfig, run_frames
from app.pictures import FramePictures
from app.sources import bag_frames, scenario_frames, scenario_length, stream_frames
from app.world_file import write_world
from evaluation import TrackingRecord, evaluate, make_summary, write_records, write_summary

logger = logging.getLogger(__name__)


@dataclass
class RunOptions(LoopConfig):
    """The loop's configuration (particles, theory, seed, reasoning, ...) plus what to play
    and where to write."""

    scenario: Path | None = None
    percepts: Path | None = None
    bag: Path | None = None
    bag_topics: Any = None  # bags.BagTopics for the bag (the usual topics by default)
    out: Path | None = None
    picture_every: int = 1
    progress: bool = True
    width: int | None = None
    height: int | None = None
    # perceive the next frame while the current one is reasoned about (run_frames)
    overlap: bool = True
    rerun: Path | None = None  # log the run to this Rerun .rrd file
    rerun_spawn: bool = False  # ... and/or to a Rerun viewer started for it


@dataclass
class RunOutput:
    summary: dict[str, Any]
    records: list[TrackingRecord]
    out: Path | None
    gif: Path | None = None
    pictures: list[Path] = field(default_factory=list)


def run(options: RunOptions) -> RunOutput:
    given = [s for s in (options.scenario, options.percepts, options.bag) if s is not None]
    if len(given) != 1:
        raise ValueError("give one of a scenario, a percept stream (--percepts) or a bag "
                         "(--bag)")
    if options.reasoning and not options.theory.is_file():
        raise FileNotFoundError(f"{options.theory}: no such theory file")
    # The loop's filter loads the theory (once) here, before the first frame: a syntax or
    # distribution error stops the run with the file, line and cause.
    loop = AnchoringLoop(options)
    try:
        return _run(options, loop)
    finally:
        loop.close()


def _run(options: RunOptions, loop: AnchoringLoop) -> RunOutput:
    """Play the frames; what was done is written even when an error stops the run (its summary
    then says ``stopped``: the error), and the error is raised again."""
    skipped: list[str] = []  # lines of a percept stream that are not frames, unpaired images
    if options.scenario is not None:
        frames = scenario_frames(options.scenario, seed=options.seed, width=options.width,
                                 height=options.height)
        total = scenario_length(options.scenario)
        name = options.scenario.stem
    elif options.bag is not None:
        from bags import BagTopics

        topics = options.bag_topics or BagTopics()
        skipped = topics.skipped  # images without a partner, filled in as the bag is read
        frames = bag_frames(options.bag, topics)
        total = None
        name = options.bag.stem
    else:
        assert options.percepts is not None
        frames = stream_frames(options.percepts, skipped)
        total = None
        name = options.percepts.stem
    pictures = None
    if options.out is not None:
        options.out.mkdir(parents=True, exist_ok=True)
        pictures = FramePictures(options.out, every=options.picture_every)
    viewer = None
    if options.rerun is not None or options.rerun_spawn:
        from app.rerun_frames import RerunFrames  # rerun-sdk only when asked for

        viewer = RerunFrames(options.rerun, options.rerun_spawn, name)
    bar = tqdm(total=total, unit="frame", desc=name, disable=not options.progress)

    def on_frame(outcome: FrameOutcome, loop: AnchoringLoop) -> None:
        if pictures is not None:
            pictures(outcome, loop)
        if viewer is not None:
            viewer(outcome, loop)
        bar.update(1)

    records: list[TrackingRecord] = []
    stopped: BaseException | None = None
    try:
        run_frames(frames, loop, on_frame, overlap=options.overlap, records=records)
    except Exception as exc:  # written below with the frames done, then raised again
        stopped = exc
    finally:
        bar.close()
        if viewer is not None:
            viewer.close()
    for message in skipped:
        logger.warning("skipped: %s", message)
    output = _finish(options, loop, name, records, skipped, stopped, pictures)
    if stopped is not None:
        raise stopped
    return output


def _finish(options: RunOptions, loop: AnchoringLoop, name: str,
            records: list[TrackingRecord], skipped: list[str], stopped: BaseException | None,
            pictures: FramePictures | None) -> RunOutput:
    evaluation = evaluate(records)
    extra = {
        "scenario": name,
        "method": "reasoning" if options.reasoning else "no-reasoning",
        "particles": options.particles if options.reasoning else 0,
        "threads": options.threads if options.reasoning else 0,
        "engine": loop.reasoner.filter.engine if loop.reasoner is not None else "",
        "seed": options.seed,
        "zero_weight_events": (loop.reasoner.filter.zero_weight_events
                               if loop.reasoner is not None else 0),
        "skipped_frames": len(skipped),
    }
    if stopped is not None:
        extra["stopped"] = f"after {len(records)} frames: {type(stopped).__name__}: {stopped}"
    if options.out is None:
        return RunOutput(make_summary(records, evaluation, extra=extra), records, None)
    summary = write_summary(options.out / "summary.json", records, evaluation, extra=extra)
    output = RunOutput(summary, records, options.out)
    write_records(options.out / "records.jsonl", records)
    perceived = {s for s, h in records[-1].hypotheses.items() if h.perceived} \
        if records else set()
    write_world(options.out / "world.pl", loop, perceived)
    if pictures is not None and stopped is None:
        output.pictures = pictures.paths
        output.gif = pictures.finish(options.out / "run.gif")
    return output


def format_summary(summary: dict[str, Any]) -> str:
    """The summary a person reads at the end of a run."""
    lines = [f"{summary.get('scenario', 'run')}: {summary['frames']} frames "
             f"({summary.get('method', '')})"]
    for obj in summary["objects"]:
        kept = "identity kept" if obj["identity_kept"] else "IDENTITY LOST"
        lines.append(f"  {obj['id']:<10} {' -> '.join(obj['symbols']) or '(never anchored)':<30}"
                     f" {kept}")
    idf1 = summary.get("idf1")
    lines.append(f"  ID switches {summary['id_switches']}, IDF1 "
                 f"{'n/a' if idf1 is None else f'{idf1:.3f}'}, rejected percepts "
                 f"{summary.get('rejected_percepts', 0)}, ambiguous re-acquisitions "
                 f"{summary.get('ambiguous_reacquisitions', 0)}")
    ms = summary["ms_per_frame"]
    fps = 1000.0 / ms["total"] if ms["total"] > 0 else float("inf")
    lines.append(f"  ms per frame: perception {ms['perception']:.1f}, anchoring "
                 f"{ms['anchoring']:.1f}, filter {ms['filter']:.1f}, total {ms['total']:.1f} "
                 f"({fps:.1f} frames per second)")
    return "\n".join(lines)
