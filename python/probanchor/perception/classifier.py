"""Category classifier: a small multi-layer perceptron over yaw-invariant shape features.

Trained with scikit-learn (``anchoring train-classifier``, see perception.training; the data:
app.classifier_data) on segments of rendered views of each category; the weights are stored as JSON
(``perception/models/category_mlp.json``) and evaluated here with numpy, so the model file is
small, needs no pickle and does not depend on the scikit-learn version. It never reads ground
truth: its input is the segment's points only.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

#: The shipped model (package data of probanchor.perception)
DEFAULT_MODEL = Path(resources.files(__package__).joinpath("models", "category_mlp.json"))


@dataclass
class CategoryModel:
    categories: list[str]
    mean: np.ndarray
    scale: np.ndarray
    weights: list[np.ndarray]
    biases: list[np.ndarray]
    meta: dict
    temperature: float = 1.0  # softmax temperature, fitted on held-out scenes

    def probabilities(self, features: np.ndarray, temperature: float | None = None
                      ) -> np.ndarray:
        """(N, C) class probabilities for (N, F) features."""
        x = (np.atleast_2d(features) - self.mean) / self.scale
        for i, (w, b) in enumerate(zip(self.weights, self.biases, strict=True)):
            x = x @ w + b
            if i < len(self.weights) - 1:
                x = np.maximum(x, 0.0)
        x = x / (self.temperature if temperature is None else temperature)
        x = x - x.max(axis=1, keepdims=True)
        e = np.exp(x)
        return e / e.sum(axis=1, keepdims=True)

    def top(self, features: np.ndarray, k: int = 3) -> list[dict[str, float]]:
        """The top-k categories with their probabilities, per row, best first."""
        probs = self.probabilities(features)
        out = []
        for row in probs:
            idx = np.argsort(-row)[:k]
            out.append({self.categories[i]: round(float(row[i]), 4) for i in idx})
        return out

    def to_json(self) -> dict:
        return {
            "categories": self.categories,
            "mean": self.mean.tolist(),
            "scale": self.scale.tolist(),
            "weights": [w.tolist() for w in self.weights],
            "biases": [b.tolist() for b in self.biases],
            "temperature": self.temperature,
            "meta": self.meta,
        }

    def save(self, path: str | Path) -> None:
        Path(path).write_text(json.dumps(self.to_json(), separators=(",", ":")),
                              encoding="utf-8")

    @classmethod
    def load(cls, path: str | Path = DEFAULT_MODEL) -> CategoryModel:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
        return cls(
            categories=list(data["categories"]),
            mean=np.asarray(data["mean"], float),
            scale=np.asarray(data["scale"], float),
            weights=[np.asarray(w, float) for w in data["weights"]],
            biases=[np.asarray(b, float) for b in data["biases"]],
            meta=dict(data.get("meta", {})),
            temperature=float(data.get("temperature", 1.0)),
        )


def model_digest(path: str | Path = DEFAULT_MODEL) -> str:
    """A short digest of a model file's bytes (12 hex digits): what perceived a cached stream."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:12]
