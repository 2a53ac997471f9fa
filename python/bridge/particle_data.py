"""Per-particle data that a :class:`bridge.Filter` carries through its resamplings.

A caller that keeps something per particle (a data-association hypothesis, a label, a row of
features) stores it as a numpy array whose first dimension is the number of particles N, under
a name, in ``Filter.particle_data``; whenever the filter resamples its particles it takes the
same rows of every array (``array[indices]``), so row i always belongs to particle i. Pure
numpy, no janus.
"""

from __future__ import annotations

from collections.abc import Iterator, MutableMapping
from typing import Any

import numpy as np


class ParticleData(MutableMapping[str, np.ndarray]):
    """name -> numpy array with first dimension N, resampled with the particles.

    Setting an item converts the value with :func:`numpy.asarray` (a copy is not made for an
    array already) and checks its first dimension is N: a wrong shape raises ``ValueError``, a
    name that is not a string ``TypeError``. Changing an array in place (``data["h"][3] = 1``)
    is the caller's business; the shape is checked when an array is set.
    """

    def __init__(self, particles: int) -> None:
        self._particles = int(particles)
        self._arrays: dict[str, np.ndarray] = {}

    @property
    def particles(self) -> int:
        """N, the first dimension of every array."""
        return self._particles

    def __getitem__(self, name: str) -> np.ndarray:
        return self._arrays[name]

    def __setitem__(self, name: str, value: Any) -> None:
        if not isinstance(name, str):
            raise TypeError(f"particle data names are strings, got {name!r}")
        array = np.asarray(value)
        if array.ndim == 0 or array.shape[0] != self._particles:
            raise ValueError(
                f"particle data {name!r}: the first dimension must be the {self._particles} "
                f"particles, got shape {array.shape}"
            )
        self._arrays[name] = array

    def __delitem__(self, name: str) -> None:
        del self._arrays[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._arrays)

    def __len__(self) -> int:
        return len(self._arrays)

    def __repr__(self) -> str:
        shapes = ", ".join(f"{name!r}: {a.dtype}{list(a.shape)}" for name, a in self.items())
        return f"ParticleData({{{shapes}}})"

    def resample(self, indices: np.ndarray) -> None:
        """Row i of every array becomes the row ``indices[i]`` of before (0-based), as the
        particles do in a resampling; each array is replaced by a new one."""
        chosen = np.asarray(indices, dtype=np.intp)
        for name, array in self._arrays.items():
            self._arrays[name] = array[chosen]
