"""Perception speed: ms per frame and frames per second of the pipeline at 320x240.

Renders frames of a scenario once (rendering is not timed), then times
``perception.Pipeline.process`` over them. Prints the ratio against the 30 frames-per-second
target and, as a reference measured in the same run, the time of the textbook point-cloud
route (open3d voxel grid, RANSAC plane and DBSCAN clustering, no features at all) on the
same frames.

    .venv/bin/python bench/perception.py [--scenario scenarios/shell_game.yaml] [--frames 60]
                                         [--accuracy 40]

With ``--accuracy N`` it also renders N random tables (the classifier's training
distribution, other seeds) and compares the percepts with the ground truth.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

import numpy as np  # noqa: E402
import open3d as o3d  # noqa: E402

from probanchor.perception import Pipeline  # noqa: E402
from probanchor.perception.pointcloud import Backprojector  # noqa: E402
from probanchor.tabletop import Simulation, load_scenario  # noqa: E402

TARGET_FPS = 30.0


def open3d_reference(frame, back: Backprojector, voxel: float) -> int:
    rows, cols = np.nonzero(frame.depth > 0)
    pts = back.world_points(frame.depth, frame.intrinsics, frame.camera_pose, rows, cols)
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(pts.astype(np.float64)))
    cloud = cloud.voxel_down_sample(voxel)
    if len(cloud.points) < 10:
        return 0
    _, inliers = cloud.segment_plane(distance_threshold=0.01, ransac_n=3, num_iterations=100)
    rest = cloud.select_by_index(inliers, invert=True)
    if len(rest.points) == 0:
        return 0
    labels = np.asarray(rest.cluster_dbscan(eps=0.02, min_points=10))
    return int(labels.max() + 1) if len(labels) else 0


def accuracy(tables: int, seed: int) -> None:
    """Percepts against ground truth on random tables (any yaw, every category)."""
    from probanchor.learning.classifier_data import random_scene
    from probanchor.tabletop import parse_scenario

    rng = np.random.default_rng(seed)
    pipe = Pipeline()
    n = wrong_count = far = off_size = colour = category = 0
    for i in range(tables):
        scenario = parse_scenario(random_scene(rng, i), f"<table {i}>")
        with Simulation(scenario, seed=seed + i) as sim:
            frame = sim.step()
        percepts = pipe.process(frame)
        visible = sorted(k for k, v in frame.truth["objects"].items() if v["visible"])
        wrong_count += sorted(str(p.truth_id) for p in percepts) != visible
        for p in percepts:
            if p.truth_id is None:
                continue
            obj, truth = scenario.object(p.truth_id), frame.truth["objects"][p.truth_id]
            n += 1
            far += np.linalg.norm(p.position - np.asarray(truth["position"])) > 0.01
            off_size += np.max(np.abs(p.size / np.asarray(truth["size"]) - 1)) > 0.15
            colour += bool(p.colour_names) and p.colour_names[0] == obj.colour_name
            category += p.best_category == obj.category
    print(f"accuracy on {tables} random tables (seed {seed}), {n} percepts:")
    print(f"  tables where the percepts are not exactly one per visible object: {wrong_count}")
    print(f"  centroid more than 1 cm off: {far / n:.1%}   size more than 15 % off: "
          f"{off_size / n:.1%}")
    print(f"  first colour name right: {colour / n:.1%}   best category right: "
          f"{category / n:.1%}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenario", type=Path, default=ROOT / "scenarios" / "shell_game.yaml")
    parser.add_argument("--frames", type=int, default=60)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--accuracy", type=int, default=0, metavar="TABLES",
                        help="also check percepts against ground truth on TABLES random tables")
    parser.add_argument("--seed", type=int, default=123, help="seed of the random tables")
    args = parser.parse_args()

    scenario = load_scenario(args.scenario)
    with Simulation(scenario, width=args.width, height=args.height) as sim:
        every = max(1, len(sim) // args.frames)
        t0 = time.perf_counter()
        frames = [f for f in sim if f.index % every == 0][: args.frames]
        render_ms = 1000 * (time.perf_counter() - t0) / len(sim)
    pipe = Pipeline()
    for f in frames[:3]:
        pipe.process(f)  # warm up (open3d, caches)
    runs, percepts = [], 0
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        percepts = sum(len(pipe.process(f)) for f in frames)
        runs.append((time.perf_counter() - t0) / len(frames))
    ms = 1000 * statistics.median(runs)
    back = Backprojector()
    ref_runs = []
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        for f in frames:
            open3d_reference(f, back, 0.005)
        ref_runs.append((time.perf_counter() - t0) / len(frames))
    ref_ms = 1000 * statistics.median(ref_runs)
    fps = 1000 / ms
    print(f"scenario {scenario.name}: {len(frames)} frames at {args.width}x{args.height}, "
          f"{percepts / len(frames):.1f} percepts per frame (rendering: {render_ms:.1f} ms "
          "per frame, not counted)")
    print(f"pipeline            {ms:7.2f} ms per frame  {fps:7.1f} frames per second")
    print(f"target              {1000 / TARGET_FPS:7.2f} ms per frame  {TARGET_FPS:7.1f} frames "
          f"per second  -> ratio {fps / TARGET_FPS:.2f} (>= 1 meets the target)")
    print(f"open3d reference    {ref_ms:7.2f} ms per frame  {1000 / ref_ms:7.1f} frames per "
          f"second (voxel 5 mm + RANSAC + DBSCAN, segmentation only) -> pipeline is "
          f"{ref_ms / ms:.2f}x faster")
    if args.accuracy:
        accuracy(args.accuracy, args.seed)
    return 0


if __name__ == "__main__":
    sys.exit(main())
