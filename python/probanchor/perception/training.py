"""Training of the category classifier on labelled shape features.

A small MLP (scikit-learn) is trained on 60 % of the scenes of a :class:`Dataset`, its softmax
temperature fitted on 20 % and it is tested on the last 20 %; its weights are saved as JSON. The
shipped model's data are random simulated tables (``probanchor.learning.classifier_data``); any
camera's labelled segments will do.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from probanchor.perception.classifier import CategoryModel
from probanchor.perception.features import SHAPE_FEATURES

CATEGORIES = ("ball", "bottle", "bowl", "box", "can", "cup", "mug")


@dataclass
class Dataset:
    features: np.ndarray
    labels: np.ndarray  # index into CATEGORIES
    scene: np.ndarray
    legacy: np.ndarray  # the features as before lifted segments were described from their bottom
    kind: np.ndarray  # "plain"; "behind" (partly hidden by the object in front); "lifted"
    n_scenes: int = 0  # how many scenes the segments come from
    hard: float = 0.0  # the share of scenes with a partly hidden or a lifted object


def _nll(probs: np.ndarray, labels: np.ndarray) -> float:
    return float(-np.mean(np.log(np.clip(probs[np.arange(len(labels)), labels], 1e-12, 1.0))))


def train(data: Dataset, seed: int = 0, hidden: int = 32,
          previous: CategoryModel | None = None) -> tuple[CategoryModel, dict]:
    """Train on 60 % of the scenes, fit a softmax temperature on 20 % (so that the
    probabilities are calibrated, not all 0.999) and test on the last 20 %.

    Parameters
    ----------
    data:
        Labelled shape features (``probanchor.learning.classifier_data.build_dataset`` for the
        shipped model).
    seed:
        Seeds the MLP.
    hidden:
        Units of its hidden layer.
    previous:
        A model to test on the same held-out segments (with the features it was trained on),
        for the report.

    Returns
    -------
    The model and its report.
    """
    import sklearn
    from scipy.optimize import minimize_scalar
    from sklearn.metrics import confusion_matrix
    from sklearn.neural_network import MLPClassifier
    from sklearn.preprocessing import StandardScaler

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
        "scenes": data.n_scenes,
        "seed": seed,
        "confusion": {"labels": list(CATEGORIES), "matrix": confusion.tolist()},
        "features": list(SHAPE_FEATURES),
        "sklearn": sklearn.__version__,
        "hard_share": data.hard,
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
