"""The learned matching function: similarity vector -> "same object" score.

A matcher maps feature vectors (..., 5) in the order of :data:`anchoring.similarity.FEATURES`
to a decision value; a positive value means "same object" (re-acquire). :class:`RbfSvm` is an
RBF-kernel SVM evaluated with numpy from a small JSON file (what ``anchoring train-matching``
writes), or from the original ProbAnch OpenCV YAML (``matching_svm.yml``) so the two can be
compared on the same similarity vectors.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from anchoring.similarity import FEATURES

DEFAULT_MODEL = Path(__file__).resolve().parent / "models" / "matching_svm.json"


class MatcherError(ValueError):
    """A model file that cannot be read (names the file and the cause)."""


class Matcher(Protocol):
    features: tuple[str, ...]

    def decision(self, x: np.ndarray) -> np.ndarray:
        """Decision values for feature rows ``x`` (..., F); > 0 means the same object."""
        ...


@dataclass
class RbfSvm:
    """``f(x) = sum_i c_i exp(-gamma ||x - sv_i||^2) + b``; "same object" when ``f(x) > 0``."""

    support_vectors: np.ndarray
    coefficients: np.ndarray
    intercept: float
    gamma: float
    features: tuple[str, ...] = FEATURES
    info: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.support_vectors = np.asarray(self.support_vectors, dtype=float)
        self.coefficients = np.asarray(self.coefficients, dtype=float).reshape(-1)
        if self.support_vectors.ndim != 2 or self.support_vectors.shape[1] != len(self.features):
            raise MatcherError(
                f"support vectors have shape {self.support_vectors.shape}, "
                f"expected (n, {len(self.features)})"
            )
        if self.coefficients.shape[0] != self.support_vectors.shape[0]:
            raise MatcherError("one coefficient per support vector expected")
        self._sv_t_m2 = np.ascontiguousarray(-2.0 * self.support_vectors.T)
        self._sv_sq = (self.support_vectors**2).sum(1)

    def decision(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        shape = x.shape[:-1]
        flat = x.reshape(-1, x.shape[-1])
        d2 = flat @ self._sv_t_m2  # -2 x.sv
        d2 += self._sv_sq
        d2 += np.einsum("ij,ij->i", flat, flat)[:, None]
        np.maximum(d2, 0.0, out=d2)
        d2 *= -self.gamma
        np.exp(d2, out=d2)
        return (d2 @ self.coefficients + self.intercept).reshape(shape)

    def predict(self, x: np.ndarray) -> np.ndarray:
        """1 for "same object", 0 otherwise."""
        return (self.decision(x) > 0).astype(int)

    # --- files ---------------------------------------------------------------------------
    def to_json(self) -> dict[str, Any]:
        return {
            "kind": "rbf_svm",
            "features": list(self.features),
            "gamma": self.gamma,
            "intercept": self.intercept,
            "support_vectors": self.support_vectors.tolist(),
            "coefficients": self.coefficients.tolist(),
            "info": self.info,
        }

    def save(self, path: str | Path) -> None:
        """Indented JSON with one support vector (and its coefficient) per line."""
        record = self.to_json()
        rows = record.pop("support_vectors")
        coefs = record.pop("coefficients")
        head = json.dumps(record, indent=1)[:-2]
        body = ",\n".join(f"  {json.dumps([round(v, 10) for v in r])}" for r in rows)
        text = (f'{head},\n "support_vectors": [\n{body}\n ],\n'
                f' "coefficients": {json.dumps([round(c, 10) for c in coefs])}\n}}\n')
        Path(path).write_text(text, encoding="utf-8")

    @classmethod
    def load(cls, path: str | Path) -> RbfSvm:
        try:
            record = json.loads(Path(path).read_text(encoding="utf-8"))
        except (OSError, json.JSONDecodeError) as exc:
            raise MatcherError(f"{path}: cannot read matching model: {exc}") from exc
        try:
            if record.get("kind") != "rbf_svm":
                raise MatcherError(f"kind is {record.get('kind')!r}, expected 'rbf_svm'")
            return cls(
                support_vectors=np.asarray(record["support_vectors"], dtype=float),
                coefficients=np.asarray(record["coefficients"], dtype=float),
                intercept=float(record["intercept"]),
                gamma=float(record["gamma"]),
                features=tuple(record.get("features", FEATURES)),
                info=dict(record.get("info", {})),
            )
        except (KeyError, TypeError, ValueError) as exc:
            raise MatcherError(f"{path}: not a matching model: {exc}") from exc

    @classmethod
    def from_opencv_yaml(cls, path: str | Path) -> RbfSvm:
        """The original ProbAnch model: an OpenCV 2-class RBF (nu-)SVC stored as YAML.

        OpenCV computes ``s = sum_k alpha_k K(sv[index_k], x) - rho`` and answers its first
        class label (0, "different") when ``s > 0``; so "same object" is ``-s > 0`` here.
        Read with ``cv2.FileStorage`` (present even in wheels without ``cv2.ml``).
        """
        import cv2

        fs = cv2.FileStorage(str(path), cv2.FILE_STORAGE_READ)
        if not fs.isOpened():
            raise MatcherError(f"{path}: cannot open OpenCV model")
        try:
            root = fs.getNode("opencv_ml_svm")
            kernel = root.getNode("kernel")
            if kernel.getNode("type").string() != "RBF":
                raise MatcherError(f"{path}: kernel is not RBF")
            gamma = kernel.getNode("gamma").real()
            labels = root.getNode("class_labels").mat().reshape(-1).tolist()
            if labels != [0, 1]:
                raise MatcherError(f"{path}: class labels {labels}, expected [0, 1]")
            sv_node = root.getNode("support_vectors")
            svs = np.array([sv_node.at(i).mat().reshape(-1) if sv_node.at(i).isMap()
                            else _seq(sv_node.at(i)) for i in range(sv_node.size())])
            df = root.getNode("decision_functions").at(0)
            rho = df.getNode("rho").real()
            alpha = _seq(df.getNode("alpha"))
            index_node = df.getNode("index")
            index = (_seq(index_node).astype(int) if not index_node.empty()
                     else np.arange(len(alpha)))
        finally:
            fs.release()
        coef = np.zeros(svs.shape[0])
        np.add.at(coef, index, alpha)
        return cls(svs, -coef, rho, gamma, FEATURES, {"source": str(path), "kind": "opencv"})


def _seq(node: Any) -> np.ndarray:
    return np.array([node.at(i).real() for i in range(node.size())], dtype=float)


def load_default_matcher() -> RbfSvm:
    """The model shipped with the package (rebuilt by ``anchoring train-matching``)."""
    return RbfSvm.load(DEFAULT_MODEL)
