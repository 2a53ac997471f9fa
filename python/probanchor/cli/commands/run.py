"""`anchoring run SCENARIO`: play a scenario (or a recorded RGB-D bag, or a recorded percept
stream) through perception, anchoring and the occlusion reasoning, and report whether
identities were kept."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from probanchor.cli.options import add_engine_option, add_threads_option
from probanchor.loop.theories import DEFAULT_THEORY, theory_path


def add_run_options(parser: argparse.ArgumentParser, particles: int = 1000) -> None:
    parser.add_argument("--particles", type=int, default=particles,
                        help=f"particles of the filter (default {particles})")
    parser.add_argument("--theory", type=theory_path, default=DEFAULT_THEORY,
                        help="theory of occlusion: hand (prolog/too.pl, the default), learned "
                             "(prolog/too_learned.pl), hindsight "
                             "(prolog/too_learned_hindsight.pl), or a DDC program's path")
    parser.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    add_threads_option(parser)
    add_engine_option(parser, ", as prolog/too.pl is")
    parser.add_argument("--resample-threshold", type=float, default=0.9,
                        help="resample when ESS < this fraction of the particles (default 0.9)")
    parser.add_argument("--out", type=Path, default=None,
                        help="write summary.json, records.jsonl, world.pl and the video run.mp4 "
                             "(each anchor drawn over the camera image) here")
    parser.add_argument("--frames", action="store_true",
                        help="with --out: also a PNG per picture (DIR/frames/)")
    parser.add_argument("--every", type=int, default=1,
                        help="draw a picture every N frames (default 1)")
    parser.add_argument("--quiet", action="store_true",
                        help="no progress (a bar on a terminal, a few lines elsewhere)")
    parser.add_argument("--sequential", action="store_true",
                        help="perceive each frame only after the previous one is processed "
                             "(by default the next frame is perceived while the current one "
                             "is reasoned about; the results are the same)")


def add_bag_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("bag topics (with --bag)")
    group.add_argument("--colour-topic", default=None,
                       help="sensor_msgs/Image, rgb8 or bgr8 (default: /camera/color/image_raw"
                            " or another usual name)")
    group.add_argument("--depth-topic", default=None,
                       help="sensor_msgs/Image registered to the colour camera, 16UC1 mm or "
                            "32FC1 m (default: /camera/aligned_depth_to_color/image_raw, "
                            "/camera/depth/image_raw, ...)")
    group.add_argument("--info-topic", default=None,
                       help="sensor_msgs/CameraInfo of the colour camera (default: "
                            "camera_info beside the colour topic)")
    group.add_argument("--world-frame", default="world",
                       help="the tf frame the table is in (default world)")
    group.add_argument("--camera-pose", type=_pose, default=None, metavar="'X Y Z QX QY QZ QW'",
                       help="the colour camera's pose in the world (OpenCV axes) instead of "
                            "/tf and /tf_static")
    group.add_argument("--max-skew", type=float, default=0.02,
                       help="seconds between the stamps of a colour and its depth image "
                            "(default 0.02)")
    group.add_argument("--max-lead", type=float, default=60.0,
                       help="seconds a colour image's stamp may be ahead of the time the bag "
                            "recorded it; a frame stamped further ahead is skipped (default 60)")


def _pose(text: str) -> Any:
    from probanchor.bags.messages import pose_matrix

    try:
        return pose_matrix([float(v) for v in text.replace(",", " ").split()])
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def bag_topics(args: argparse.Namespace) -> Any:
    """The bag options of a parsed command line as a :class:`bags.BagTopics`."""
    from probanchor.bags import BagTopics

    return BagTopics(colour=args.colour_topic, depth=args.depth_topic,
                     camera_info=args.info_topic, world_frame=args.world_frame,
                     camera_pose=args.camera_pose, max_skew=args.max_skew,
                     max_lead=args.max_lead)


def register(sub: Any) -> None:
    parser = sub.add_parser("run", help="play a scenario through anchoring and reasoning",
                            description=__doc__)
    parser.add_argument("scenario", type=Path, nargs="?",
                        help="scenario file (scenarios/*.yaml); or use --percepts")
    parser.add_argument("--percepts", type=Path, default=None,
                        help="a recorded percept stream (JSON Lines) instead of a scenario")
    parser.add_argument("--bag", type=Path, default=None,
                        help="a recorded RGB-D bag (ROS 1 .bag, ROS 2 .db3 or .mcap) instead "
                             "of a scenario")
    add_bag_options(parser)
    parser.add_argument("--no-reasoning", action="store_true",
                        help="anchoring alone: hidden anchors keep their last position")
    parser.add_argument("--no-identity", action="store_true",
                        help="decide look-alikes' identities once, by the most probable "
                             "assignment, instead of keeping them as hypotheses in the "
                             "particles and revising them (docs/anchoring.md)")
    parser.add_argument("--no-reid", action="store_true",
                        help="anchoring does not re-identify a percept by appearance alone "
                             "(a unique look-alike of an anchor left over)")
    parser.add_argument("--rerun", type=Path, default=None, metavar="FILE.rrd",
                        help="log the run for the Rerun 3-D viewer (rerun FILE.rrd): images, "
                             "point cloud, anchors as boxes, particles, occlusion "
                             "probabilities and timings on the frame timeline")
    parser.add_argument("--store", type=Path, default=None, metavar="WORLD.db",
                        help="keep the world model in this SQLite store, written per frame "
                             "(anchors, their history, the particles)")
    parser.add_argument("--resume", type=Path, default=None, metavar="WORLD.db",
                        help="continue the run kept in this store after a restart (the same "
                             "source and options; the source may be left out)")
    parser.add_argument("--serve", type=int, default=None, metavar="PORT",
                        help="answer Prolog queries on the live world model while the run goes "
                             "on, on http://127.0.0.1:PORT (0: any free port, printed): "
                             "anchoring shell --connect PORT, or GET /query?q=QUERY")
    parser.add_argument("--rerun-spawn", action="store_true",
                        help="open the Rerun viewer and stream the run to it")
    add_run_options(parser)
    parser.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from probanchor.loop.runner import RunOptions, format_summary, run

    output = run(RunOptions(
        scenario=args.scenario, percepts=args.percepts, bag=args.bag,
        bag_topics=bag_topics(args) if args.bag is not None else None,
        particles=args.particles,
        theory=args.theory, seed=args.seed, reasoning=not args.no_reasoning,
        resample_threshold=args.resample_threshold, reidentify=not args.no_reid,
        identity=not args.no_identity, out=args.out,
        threads=args.threads, engine=args.engine, overlap=not args.sequential,
        picture_every=args.every, frames=args.frames, progress=not args.quiet, rerun=args.rerun,
        rerun_spawn=args.rerun_spawn, store=args.store, resume=args.resume, serve=args.serve,
    ))
    print(format_summary(output.summary))
    if output.out is not None:
        print(f"wrote {output.out}/summary.json, records.jsonl, world.pl"
              + (f", {output.video}" if output.video else "")
              + (f" and {len(output.pictures)} pictures in {output.out}/frames"
                 if output.pictures else ""))
    if args.store or args.resume:
        print(f"world model in {args.store or args.resume}")
    if args.rerun is not None:
        print(f"wrote {args.rerun} (view it with: .venv/bin/rerun {args.rerun})")
    return 0
