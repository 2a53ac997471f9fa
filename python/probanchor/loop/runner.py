"""A whole run: frames from a scenario or a percept stream through the loop, then the summary,
the video (and, on request, a picture per frame) and world file in an output directory."""

from __future__ import annotations

import logging
import sys
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from probanchor.evaluation import (
    TrackingRecord,
    evaluate,
    make_summary,
    write_records,
    write_summary,
)
from probanchor.loop.loop import AnchoringLoop, FrameOutcome, LoopConfig, run_frames
from probanchor.loop.pictures import FramePictures
from probanchor.loop.sources import bag_frames, scenario_frames, scenario_length, stream_frames
from probanchor.loop.store import (
    StoredRun,
    WorldStore,
    adopt_stored_options,
    run_meta,
    store_source,
    stored_source,
)
from probanchor.loop.world_file import world_facts, write_world
from probanchor.progress import progress

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
    frames: bool = False  # also write a PNG per picture (DIR/frames/), besides DIR/run.mp4
    progress: bool = True  # a bar on a terminal, a few plain lines elsewhere
    width: int | None = None
    height: int | None = None
    # perceive the next frame while the current one is reasoned about (run_frames)
    overlap: bool = True
    rerun: Path | None = None  # log the run to this Rerun .rrd file
    rerun_spawn: bool = False  # ... and/or to a Rerun viewer started for it
    store: Path | None = None  # keep the world model in this SQLite store, frame by frame
    resume: Path | None = None  # continue the run kept in this store
    serve: int | None = None  # answer queries on the live world model on this port (0: any)


@dataclass
class RunOutput:
    summary: dict[str, Any]
    records: list[TrackingRecord]
    out: Path | None
    video: Path | None = None
    pictures: list[Path] = field(default_factory=list)  # the PNGs (with RunOptions.frames)


#: The most particles a run's filter takes: every step hands each particle's values of every
#: anchor between Prolog and Python as lists, and at some millions of particles these outgrow
#: SWI-Prolog's stack (1 GB per thread) after the step has run (docs/limits.md).
MAX_PARTICLES = 1_000_000


def check_particles(particles: Any) -> None:
    """A ValueError for a number of particles a run cannot take (before it is tried)."""
    if isinstance(particles, bool) or not isinstance(particles, int) or particles < 1:
        raise ValueError(f"--particles {particles!r}: not a positive whole number")
    if particles > MAX_PARTICLES:
        raise ValueError(f"--particles {particles:,}: more than the {MAX_PARTICLES:,} a run's "
                         "filter takes (the particles' values, handed between Prolog and "
                         "Python each frame, would outgrow SWI-Prolog's stack)")


def run(options: RunOptions) -> RunOutput:
    if options.store is not None and options.resume is not None:
        raise ValueError("give --store (a new run) or --resume (continue one), not both")
    if options.reasoning:
        check_particles(options.particles)
    # a resumed run takes the store's lock before it reads anything of it
    store = WorldStore.open(options.resume, write=True) if options.resume is not None \
        else None
    try:
        if store is not None and options.scenario is options.percepts is options.bag is None:
            kind, path = stored_source(store.meta())  # the stored run's own source
            setattr(options, kind, path)
        if store is not None:
            adopt_stored_options(options, store.meta())
            if options.reasoning:
                check_particles(options.particles)
        given = [s for s in (options.scenario, options.percepts, options.bag) if s is not None]
        if len(given) != 1:
            raise ValueError("give one of a scenario, a percept stream (--percepts) or a bag "
                             "(--bag)")
        if options.reasoning and not options.theory.is_file():
            raise FileNotFoundError(f"{options.theory}: no such theory file")
        meta = run_meta(store_source(options.scenario, options.bag, options.percepts), options)
        if store is not None:
            store.check_resumable(meta)
        elif options.store is not None:
            store = WorldStore.create(options.store, meta)
        # The loop's filter loads the theory (once) here, before the first frame: a syntax or
        # distribution error stops the run with the file, line and cause.
        loop = AnchoringLoop(options)
        try:
            stored = store.resume(loop) if options.resume is not None and store is not None \
                else StoredRun(0, [])
            return _run(options, loop, store, stored)
        finally:
            loop.close()
    finally:
        if store is not None:
            store.close()


def _run(options: RunOptions, loop: AnchoringLoop, store: WorldStore | None = None,
         stored: StoredRun | None = None) -> RunOutput:
    """Play the frames (from ``stored.next_frame`` on, after its records); what was done is
    written even when an error stops the run (its summary then says ``stopped``: the error),
    and the error is raised again."""
    stored = stored or StoredRun(0, [])
    start = stored.next_frame
    skipped: list[str] = []  # lines of a percept stream that are not frames, unpaired images
    if options.scenario is not None:
        frames = scenario_frames(options.scenario, seed=options.seed, width=options.width,
                                 height=options.height, start=start)
        total = scenario_length(options.scenario)
        name = options.scenario.stem
    elif options.bag is not None:
        from probanchor.bags import BagTopics

        topics = options.bag_topics or BagTopics()
        skipped = topics.skipped  # images without a partner, filled in as the bag is read
        frames = bag_frames(options.bag, topics, start=start)
        total = None
        name = options.bag.stem
    else:
        assert options.percepts is not None
        frames = stream_frames(options.percepts, skipped, start=start)
        total = None
        name = options.percepts.stem
    pictures = None
    if options.out is not None:
        options.out.mkdir(parents=True, exist_ok=True)
        pictures = FramePictures(options.out, every=options.picture_every,
                                 frames=options.frames)
    viewer = None
    if options.rerun is not None or options.rerun_spawn:
        from probanchor.loop.rerun_frames import RerunFrames  # rerun-sdk only when asked for

        viewer = RerunFrames(options.rerun, options.rerun_spawn, name)
    live = None
    if options.serve is not None:
        from probanchor.loop.live import LiveWorld

        live = LiveWorld(options.serve)
        print(f"serving the world model at {live.url}/query?q=QUERY (anchoring shell "
              f"--connect {live.port})", file=sys.stderr, flush=True)
    bar = progress(None if total is None else max(0, total - start), desc=name, unit="frame",
                   show=options.progress)

    def on_frame(outcome: FrameOutcome, loop: AnchoringLoop) -> None:
        if store is not None:
            store.write_frame(outcome, loop)
        if live is not None:
            record = outcome.record
            perceived = {s for s, h in record.hypotheses.items() if h.perceived}
            live.frame_done(record.frame, record.time, lambda: world_facts(
                loop, perceived, frame=(record.frame, record.time)))
        if pictures is not None:
            pictures(outcome, loop)
        if viewer is not None:
            viewer(outcome, loop)
        bar.update(1)

    records: list[TrackingRecord] = list(stored.records)
    stopped: BaseException | None = None
    source_error: list[BaseException] = []
    try:
        try:
            run_frames(_until_error(frames, source_error), loop, on_frame,
                       overlap=options.overlap, records=records)
            if source_error:  # the source's error, after every frame before it was done
                stopped = source_error[0]
        except Exception as exc:  # written below with the frames done, then raised again
            stopped = exc
        finally:
            bar.close()
            if viewer is not None:
                viewer.close()
        for message in skipped:
            logger.warning("skipped: %s", message)
        output = _finish(options, loop, name, records, skipped, stopped, pictures)
    finally:
        if live is not None:
            _end_serving(live, loop, records)
    if stopped is not None:
        raise stopped
    return output


def _end_serving(live: Any, loop: AnchoringLoop, records: list[TrackingRecord]) -> None:
    """Queries under way get the last frame's world model; then the server stops."""
    last = records[-1] if records else None
    try:
        live.finish(None if last is None else lambda: world_facts(
            loop, {s for s, h in last.hypotheses.items() if h.perceived},
            frame=(last.frame, last.time)))
    except Exception as exc:  # (the particles could not be read: world.pl says why)
        logger.warning("the query server's last world model: %s", exc)
        live.finish(None)
    finally:
        live.close()


def _until_error(frames: Iterator[Any], error: list[BaseException]) -> Iterator[Any]:
    """The source's frames until it raises; its error goes into ``error`` and the frames end.

    The loop asks for the next frame before it processes the current one (to perceive it
    meanwhile): a source that raised there would lose the frame before its error (a bag's
    image that changes size at frame 8 would end the run after frame 6).
    """
    try:
        yield from frames
    except Exception as exc:
        error.append(exc)


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
    missing = write_world(options.out / "world.pl", loop, perceived,
                          (records[-1].frame, records[-1].time) if records else None)
    if missing is not None:
        logger.warning("%s: written without the particles: %s", options.out / "world.pl",
                       missing)
    if pictures is not None:  # (the video of the frames done, also after an error)
        output.pictures = pictures.paths
        output.video = pictures.finish()
    return output


def _revision_lines(summary: dict[str, Any]) -> list[str]:
    """The revisions of a run and how its beliefs about hidden objects fared, for a person."""
    lines = []
    for revision in summary.get("revisions", []):
        swaps = ", ".join(f"{a} -> {b}" for a, b in revision["mapping"].items())
        seen = ", ".join(revision["evidence"]) or "nothing"
        lines.append(f"  frame {revision['frame']}: revised {swaps} (probability "
                     f"{revision['probability']:.2f}, was {revision['before']:.2f}; seen again: "
                     f"{seen}), answers since frame {min(revision['since'].values())}")
    beliefs = summary.get("beliefs") or {}
    if beliefs.get("hidden_frames"):
        occluder = beliefs.get("true_occluder_probability")
        extra = "" if occluder is None else f", P(true occluder) {occluder:.2f}"
        lines.append(f"  hidden objects' beliefs within {100 * beliefs['threshold']:.0f} cm in "
                     f"{100 * beliefs['within']:.0f} % of {beliefs['hidden_frames']} "
                     f"object-frames{extra}")
    return lines


def format_summary(summary: dict[str, Any]) -> str:
    """The summary a person reads at the end of a run."""
    lines = [f"{summary.get('scenario', 'run')}: {summary['frames']} frames "
             f"({summary.get('method', '')})"]
    for obj in summary["objects"]:
        kept = "identity kept" if obj["identity_kept"] else "IDENTITY LOST"
        if not obj["identity_kept"] and obj.get("identity_kept_at_end"):
            kept = "identity kept at the end (revised)"
        lines.append(f"  {obj['id']:<10} {' -> '.join(obj['symbols']) or '(never anchored)':<30}"
                     f" {kept}")
    lines.extend(_revision_lines(summary))
    idf1 = summary.get("idf1")
    lines.append(f"  ID switches {summary['id_switches']}, IDF1 "
                 f"{'n/a' if idf1 is None else f'{idf1:.3f}'}, rejected percepts "
                 f"{summary.get('rejected_percepts', 0)}, ambiguous re-acquisitions "
                 f"{summary.get('ambiguous_reacquisitions', 0)}")
    if summary.get("hota") is not None:
        lines.append("  HOTA {hota:.3f} (DetA {deta:.3f}, AssA {assa:.3f}, LocA {loca:.3f})"
                     .format(**{k: summary.get(k) or 0.0 for k in ("hota", "deta", "assa",
                                                                    "loca")}))
    ms = summary["ms_per_frame"]
    fps = 1000.0 / ms["total"] if ms["total"] > 0 else float("inf")
    lines.append(f"  ms per frame: perception {ms['perception']:.1f}, anchoring "
                 f"{ms['anchoring']:.1f}, filter {ms['filter']:.1f}, total {ms['total']:.1f} "
                 f"({fps:.1f} frames per second)")
    return "\n".join(lines)
