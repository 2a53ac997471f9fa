"""One interface for deterministic and probabilistic attribute values (section 3.2 of the paper).

An attribute value at a time step is either *deterministic* (one value) or *probabilistic*
(N weighted samples, e.g. the particles of an anchor's position that the reasoning sends back).
Both are an :class:`Attribute`: a deterministic value is simply one sample of weight 1.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

_ONE = np.ones(1)
_ONE.flags.writeable = False


class AttributeValueError(ValueError):
    """Samples or weights that cannot form an attribute value (wrong shape, NaN, zero mass)."""


@dataclass
class Attribute:
    """A volatile attribute value at ``time``: ``samples`` (N, D), ``weights`` (N,) summing to 1.

    ``N == 1`` is the deterministic case. Weights are normalised on construction. Treat an
    Attribute as immutable (make a new one to change it): derived arrays are cached.
    """

    samples: np.ndarray
    weights: np.ndarray
    time: float = 0.0

    def __post_init__(self) -> None:
        samples = np.asarray(self.samples, dtype=float)
        if samples.ndim == 1:
            samples = samples.reshape(1, -1)
        weights = np.asarray(self.weights, dtype=float).reshape(-1)
        if samples.ndim != 2 or samples.shape[0] == 0:
            raise AttributeValueError(f"samples must be (N, D) with N >= 1, got {samples.shape}")
        if weights.shape != (samples.shape[0],):
            raise AttributeValueError(
                f"weights have shape {weights.shape}, expected ({samples.shape[0]},)"
            )
        if not np.all(np.isfinite(samples)):
            raise AttributeValueError("samples contain NaN or infinity")
        if not np.all(np.isfinite(weights)) or np.any(weights < 0):
            raise AttributeValueError("weights must be finite and non-negative")
        total = weights.sum()
        if total <= 0:
            raise AttributeValueError("weights sum to zero")
        self.samples = samples
        self.weights = weights / total

    @classmethod
    def deterministic(cls, value: Any, time: float = 0.0, *, checked: bool = True) -> Attribute:
        """One value. ``checked=False`` skips validation for values already validated (the
        fields of a validated percept): the hot path of re-acquire."""
        value = np.asarray(value, dtype=float).reshape(1, -1)
        if checked:
            return cls(value, np.ones(1), time)
        attr = object.__new__(cls)
        attr.samples, attr.weights, attr.time = value, _ONE, time
        return attr

    @classmethod
    def probabilistic(
        cls, samples: Any, weights: Any | None = None, time: float = 0.0
    ) -> Attribute:
        samples = np.asarray(samples, dtype=float)
        if weights is None:
            weights = np.ones(samples.shape[0])
        return cls(samples, weights, time)

    @property
    def is_probabilistic(self) -> bool:
        return self.samples.shape[0] > 1

    @property
    def n(self) -> int:
        return int(self.samples.shape[0])

    @property
    def dim(self) -> int:
        return int(self.samples.shape[1])

    def mean(self) -> np.ndarray:
        """The expected value (for a deterministic attribute: the value itself)."""
        return self.weights @ self.samples

    @property
    def value(self) -> np.ndarray:
        """The deterministic value, or the mean of a probabilistic one."""
        return self.samples[0].copy() if self.n == 1 else self.mean()

    def cov(self) -> np.ndarray:
        d = self.samples - self.mean()
        return (self.weights[:, None] * d).T @ d

    def support(self) -> np.ndarray:
        """Samples with positive weight: the candidates for the max-over-particles estimate."""
        return self._positive_part()[0]

    def support_weights(self) -> np.ndarray:
        """The weights of :meth:`support`'s samples (they still sum to 1)."""
        return self._positive_part()[1]

    def _positive_part(self) -> tuple[np.ndarray, np.ndarray]:
        cached = self.__dict__.get("_support")
        if cached is None:
            positive = self.weights > 0
            cached = ((self.samples, self.weights) if positive.all()
                      else (self.samples[positive], self.weights[positive]))
            self.__dict__["_support"] = cached
        return cached

    def augmented_support(self) -> np.ndarray:
        """(D + 1, N) support samples transposed with their squared norms (cached)."""
        cached = self.__dict__.get("_augmented")
        if cached is None:
            support = self.support()
            cached = np.empty((self.dim + 1, support.shape[0]))
            coords = cached[:-1]
            coords[...] = support.T
            np.einsum("ij,ij->j", coords, coords, out=cached[-1])
            self.__dict__["_augmented"] = cached
        return cached

    def to_json(self) -> dict[str, Any]:
        if not self.is_probabilistic:
            return {"time": self.time, "value": self.samples[0].tolist()}
        return {
            "time": self.time,
            "samples": np.round(self.samples, 6).tolist(),
            "weights": self.weights.tolist(),
        }

    @classmethod
    def from_json(cls, record: dict[str, Any]) -> Attribute:
        time = float(record.get("time", 0.0))
        if "value" in record:
            return cls.deterministic(record["value"], time)
        return cls.probabilistic(record["samples"], record["weights"], time)
