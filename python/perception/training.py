"""Training data and training of the category classifier.

Random tables with three or four objects of the known categories (random sizes within each
category's range, colours, yaws, cups and mugs upright or turned over, the camera moved a
little) are rendered with the simulator; the pipeline segments them; each segment's shape
features are labelled with the category of the object whose pixels dominate it (the ground
truth is read here, at training time only). A small MLP (scikit-learn) is trained on 60 % of
the scenes, its softmax temperature fitted on 20 % and it is tested on the last 20 %; its
weights are saved as JSON.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from perception.classifier import CategoryModel
from perception.features import SHAPE_FEATURES, shape_features
from perception.pipeline import Pipeline

CATEGORIES = ("ball", "box", "can", "cup", "mug")
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
    return obj


CONTAINERS = ("box", "cup", "mug")


def random_scene(rng: np.random.Generator, index: int, hard: float = 0.0) -> dict:
    """A scenario dict with 3 or 4 well separated objects and a slightly moved camera.

    With probability ``hard`` the scene is one of the views that occur while objects hide one
    another: an object standing 8 to 15 cm behind another (partly hidden by it: a mug's rim
    above a box, a sliver beside it), or a container lifted into the air (at the frame taken,
    ``t = 1``, it is between 3 and 20 cm up and moving). Such views are ambiguous, and a
    classifier that never saw them answered with confident wrong categories.
    """
    from tabletop.scenario import CameraSpec

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
        # the lift rises over 35 % of its duration, then moves at height: at t = 1 it is up
        scene["events"] = [{"at": 0.0, "do": "lift", "container": objects[0]["id"],
                            "height": float(rng.uniform(0.03, 0.2)),
                            "duration": float(rng.uniform(1.5, 2.8))}]
        scene["duration"] = 1.0
    return scene


@dataclass
class Dataset:
    features: np.ndarray
    labels: np.ndarray  # index into CATEGORIES
    scene: np.ndarray
    legacy: np.ndarray  # the features as before lifted segments were described from their bottom
    kind: np.ndarray  # "plain"; "behind" (partly hidden by the object in front); "lifted"


def build_dataset(n_scenes: int, seed: int = 0, hard: float = 0.0) -> Dataset:
    from tabletop import Simulation, parse_scenario
    from tabletop.errors import ScenarioError

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
                   np.array(kinds))


def _nll(probs: np.ndarray, labels: np.ndarray) -> float:
    return float(-np.mean(np.log(np.clip(probs[np.arange(len(labels)), labels], 1e-12, 1.0))))


def train(n_scenes: int = 800, seed: int = 0, hidden: int = 32, hard: float = 0.4,
          previous: CategoryModel | None = None) -> tuple[CategoryModel, dict]:
    """Train on 60 % of the scenes, fit a softmax temperature on 20 % (so that the
    probabilities are calibrated, not all 0.999) and test on the last 20 %. Returns the
    model and a report. ``hard``: the share of scenes with a partly hidden or a lifted object
    (see :func:`random_scene`). ``previous``: a model to test on the same held-out segments
    (with the features it was trained on), for the report."""
    import sklearn
    from scipy.optimize import minimize_scalar
    from sklearn.metrics import confusion_matrix
    from sklearn.neural_network import MLPClassifier
    from sklearn.preprocessing import StandardScaler

    data = build_dataset(n_scenes, seed, hard)
    fold = data.scene % 5
    test, calib = fold == 4, fold == 3
    fit = ~(test | calib)
    scaler = StandardScaler().fit(data.features[fit])
    clf = MLPClassifier(hidden_layer_sizes=(hidden,), alpha=1e-3, max_iter=3000,
                        random_state=seed)
    clf.fit(scaler.transform(data.features[fit]), data.labels[fit])
    classes = [CATEGORIES[c] for c in clf.classes_]
    model = CategoryModel(
        categories=classes,
        mean=scaler.mean_.copy(),
        scale=scaler.scale_.copy(),
        weights=[w.copy() for w in clf.coefs_],
        biases=[b.copy() for b in clf.intercepts_],
        meta={},
    )
    index = {c: i for i, c in enumerate(clf.classes_)}
    calib_labels = np.array([index[c] for c in data.labels[calib]])
    test_labels = np.array([index[c] for c in data.labels[test]])
    result = minimize_scalar(
        lambda log_t: _nll(model.probabilities(data.features[calib], np.exp(log_t)),
                           calib_labels),
        bounds=(-3.0, 4.0), method="bounded")
    model.temperature = float(np.exp(result.x))
    probs = model.probabilities(data.features[test])
    predicted = clf.classes_[np.argmax(probs, axis=1)]
    accuracy = float(np.mean(predicted == data.labels[test]))
    confusion = confusion_matrix(data.labels[test], predicted, labels=range(len(CATEGORIES)))
    report = {
        "held_out_accuracy": round(accuracy, 4),
        "held_out_nll": round(_nll(probs, test_labels), 4),
        "held_out_nll_uncalibrated": round(_nll(model.probabilities(data.features[test], 1.0),
                                                test_labels), 4),
        "mean_top_probability": round(float(probs.max(axis=1).mean()), 4),
        "temperature": round(model.temperature, 4),
        "train_segments": int(fit.sum()),
        "calibration_segments": int(calib.sum()),
        "test_segments": int(test.sum()),
        "scenes": n_scenes,
        "seed": seed,
        "confusion": {"labels": list(CATEGORIES), "matrix": confusion.tolist()},
        "features": list(SHAPE_FEATURES),
        "sklearn": sklearn.__version__,
        "hard_share": hard,
        "held_out_by_view": _by_view(predicted, data.labels[test], data.kind[test]),
    }
    if previous is not None:
        old_probs = previous.probabilities(data.legacy[test])
        old_predicted = np.array([CATEGORIES.index(previous.categories[k])
                                  for k in np.argmax(old_probs, axis=1)])
        report["previous_model"] = {
            "held_out_accuracy": round(float(np.mean(old_predicted == data.labels[test])), 4),
            "held_out_by_view": _by_view(old_predicted, data.labels[test], data.kind[test]),
            "mean_top_probability_when_wrong": round(float(old_probs.max(axis=1)[
                old_predicted != data.labels[test]].mean()), 4)
            if np.any(old_predicted != data.labels[test]) else None,
        }
    wrong = predicted != data.labels[test]
    report["mean_top_probability_when_wrong"] = round(float(probs.max(axis=1)[wrong].mean()), 4) \
        if wrong.any() else None
    model.meta = report
    return model, report


def _by_view(predicted: np.ndarray, labels: np.ndarray, kinds: np.ndarray) -> dict:
    """Accuracy and segment count per kind of view (plain, behind, lifted)."""
    return {str(k): {"accuracy": round(float(np.mean(predicted[kinds == k] == labels[kinds == k])),
                                       4),
                     "segments": int(np.sum(kinds == k))}
            for k in sorted(set(kinds.tolist()))}
