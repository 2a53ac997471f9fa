"""Training data for the category classifier, rendered with the simulator.

Random tables with three or four objects of the known categories (random sizes within each
category's range, colours, yaws, cups, mugs and bowls upright or turned over, the camera moved a
little) are rendered; the pipeline segments them; each segment's shape features are labelled
with the category of the object whose pixels dominate it (the ground truth is read here, at
training time only). ``probanchor.perception.training.train`` fits the classifier on the result: the
simulator stays out of ``perception``.
"""

from __future__ import annotations

import math

import numpy as np

from probanchor.perception.features import shape_features
from probanchor.perception.pipeline import Pipeline
from probanchor.perception.training import CATEGORIES, Dataset
from probanchor.tabletop import Simulation, parse_scenario
from probanchor.tabletop.errors import ScenarioError
from probanchor.tabletop.scenario import CameraSpec

PALETTE = ("red", "orange", "yellow", "green", "cyan", "blue", "purple", "pink", "brown",
           "white", "gray", "black")


def random_object(rng: np.random.Generator, oid: str, category: str) -> dict:
    colour = str(rng.choice(PALETTE))
    obj: dict = {"id": oid, "category": category, "colour": colour,
                 "yaw": float(rng.uniform(0, 360))}
    if category == "ball":
        obj["radius"] = float(rng.uniform(0.025, 0.045))
    elif category == "mug":
        obj.update(radius=float(rng.uniform(0.035, 0.048)), height=float(rng.uniform(0.08, 0.12)),
                   upside_down=bool(rng.random() < 0.7))
    elif category == "cup":
        obj.update(radius=float(rng.uniform(0.028, 0.046)), height=float(rng.uniform(0.07, 0.11)),
                   upside_down=bool(rng.random() < 0.7))
    elif category == "box":
        obj["size"] = [float(rng.uniform(0.05, 0.17)), float(rng.uniform(0.05, 0.17)),
                       float(rng.uniform(0.04, 0.17))]
    elif category == "can":
        obj.update(radius=float(rng.uniform(0.028, 0.038)), height=float(rng.uniform(0.09, 0.14)))
    elif category == "bottle":
        obj.update(radius=float(rng.uniform(0.025, 0.04)), height=float(rng.uniform(0.16, 0.26)))
    elif category == "bowl":
        obj.update(radius=float(rng.uniform(0.06, 0.09)), height=float(rng.uniform(0.05, 0.09)),
                   upside_down=bool(rng.random() < 0.7))
    return obj


CONTAINERS = ("bowl", "box", "cup", "mug")


def random_scene(rng: np.random.Generator, index: int, hard: float = 0.0) -> dict:
    """A scenario dict with 3 or 4 well separated objects and a slightly moved camera.

    With probability ``hard`` the scene is one of the views that occur while objects hide one
    another: an object standing 8 to 15 cm behind another (partly hidden by it: a mug's rim
    above a box, a sliver beside it), or a container lifted into the air (at the frame taken,
    ``t = 1``, it is between 3 and 20 cm up and moving), half the time off a ball it covered.
    Such views are ambiguous, and a classifier that never saw them answered with confident wrong
    categories.
    """
    cam = CameraSpec()
    position = [float(v + rng.uniform(-0.05, 0.05)) for v in cam.position]
    target = [float(v + rng.uniform(-0.03, 0.03)) for v in cam.target]
    objects: list[dict] = []
    placed: list[tuple[float, float]] = []
    n = int(rng.integers(3, 5))
    kind = str(rng.choice(["behind", "lifted"])) if rng.random() < hard else "plain"
    tries = 0
    while len(objects) < n and tries < 200:
        tries += 1
        x, y = float(rng.uniform(-0.32, 0.32)), float(rng.uniform(-0.2, 0.3))
        if kind == "behind" and len(objects) == 1:
            # partly hidden: behind the first object as the camera (at -y) sees it
            x = placed[0][0] + float(rng.uniform(-0.06, 0.06))
            y = placed[0][1] + float(rng.uniform(0.08, 0.15))
        elif any(math.dist((x, y), p) < 0.2 for p in placed):
            continue
        category = str(rng.choice(CATEGORIES))
        if kind == "lifted" and not objects:
            category = str(rng.choice(CONTAINERS))
        obj = random_object(rng, f"{category}_{len(objects) + 1}", category)
        obj["position"] = [x, y]
        objects.append(obj)
        placed.append((x, y))
    scene: dict = {"name": f"train_{index}_{kind}", "fps": 1, "duration": 0.5,
                   "camera": {"position": position, "target": target}, "objects": objects}
    if kind == "lifted":
        if rng.random() < 0.5:
            # a ball it covered, seen as the container rises off it (the two may be one
            # segment): a classifier that had never seen it called the view a bowl
            objects.append({"id": f"ball_{len(objects) + 1}", "category": "ball",
                            "colour": str(rng.choice(PALETTE)),
                            "radius": float(rng.uniform(0.025, 0.035)),
                            "under": objects[0]["id"]})
        # the lift rises over 35 % of its duration, then moves at height: at t = 1 it is up
        scene["events"] = [{"at": 0.0, "do": "lift", "container": objects[0]["id"],
                            "height": float(rng.uniform(0.03, 0.2)),
                            "duration": float(rng.uniform(1.5, 2.8))}]
        scene["duration"] = 1.0
    return scene


def build_dataset(n_scenes: int, seed: int = 0, hard: float = 0.0) -> Dataset:
    """Shape features and categories of the segments of ``n_scenes`` random tables.

    Parameters
    ----------
    n_scenes:
        How many tables to render.
    seed:
        Seeds the tables and the sensor noise.
    hard:
        The share of tables with a partly hidden or a lifted object (:func:`random_scene`).

    Returns
    -------
    The :class:`probanchor.perception.training.Dataset`.
    """
    rng = np.random.default_rng(seed)
    pipe = Pipeline(model=None)
    feats, labels, scenes, legacy, kinds = [], [], [], [], []
    for i in range(n_scenes):
        while True:  # objects placed close behind one another may overlap: draw again
            spec = random_scene(rng, i, hard)
            try:
                scenario = parse_scenario(spec, f"<training scene {i}>")
                break
            except ScenarioError:
                continue
        scene_kind = spec["name"].rsplit("_", 1)[1]
        special = spec["objects"][1 if scene_kind == "behind" else 0]["id"]
        categories = {o.id: o.category for o in scenario.objects}
        with Simulation(scenario, seed=seed * 100003 + i) as sim:
            frame = list(sim)[-1]  # the last frame (t = 1 in a scene with a lift)
        percepts = pipe.process(frame)
        for j, p in enumerate(percepts):
            if p.truth_id is None or j not in pipe.last_shape_features:
                continue
            feats.append(pipe.last_shape_features[j])
            seg = pipe.last_segments[j]
            pixel = float(np.linalg.norm(seg.points.mean(axis=0) - frame.camera_pose[:3, 3])
                          ) / frame.intrinsics.fx
            legacy.append(shape_features(seg.points, seg.heights, len(seg.rows) * pixel ** 2,
                                         rest_height=np.inf))
            labels.append(CATEGORIES.index(categories[p.truth_id]))
            scenes.append(i)
            kinds.append(scene_kind if p.truth_id == special else "plain")
    return Dataset(np.array(feats), np.array(labels), np.array(scenes), np.array(legacy),
                   np.array(kinds), n_scenes=n_scenes, hard=hard)
