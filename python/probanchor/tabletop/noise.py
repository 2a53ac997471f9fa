"""Sensor noise added to rendered frames (deterministic given the generator).

Gaussian values are drawn from a bank filled once per simulation and read from a random
offset each frame: drawing 300,000 fresh normal variates per frame costs more than rendering.
"""

from __future__ import annotations

import cv2
import numpy as np

from probanchor.tabletop.scenario import NoiseSpec


class GaussianBank:
    """Standard normal float32 values, read in contiguous slices from random offsets."""

    def __init__(self, rng: np.random.Generator, size: int = 1 << 21) -> None:
        self.rng = rng
        values = rng.standard_normal(size, dtype=np.float32)
        self.values = np.concatenate([values, values])
        self.size = size

    def take(self, shape: tuple[int, ...]) -> np.ndarray:
        n = int(np.prod(shape))
        if n > self.size:
            return self.rng.standard_normal(shape, dtype=np.float32)
        start = int(self.rng.integers(self.size))
        return self.values[start:start + n].reshape(shape)


def add_noise(rgb: np.ndarray, depth: np.ndarray, spec: NoiseSpec, rng: np.random.Generator,
              bank: GaussianBank | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Return noisy copies: depth noise growing with distance, missing depth next to depth
    jumps (object edges), and Gaussian colour noise."""
    if not spec.enabled:
        return rgb, depth
    bank = bank or GaussianBank(rng, size=int(np.prod(rgb.shape)))
    valid = depth > 0
    z = depth.astype(np.float32)
    sigma = spec.depth_sigma_base + spec.depth_sigma_quadratic * z * z
    noisy = z + bank.take(z.shape) * sigma
    # depth jumps: a pixel whose 3x3 neighbourhood spans more than edge_jump
    far = np.where(valid, z, 10.0).astype(np.float32)
    near = np.where(valid, z, 0.0).astype(np.float32)
    kernel = np.ones((3, 3), np.uint8)
    span = cv2.dilate(near, kernel) - cv2.erode(far, kernel)
    edge_r, edge_c = np.nonzero(valid & (span > spec.edge_jump))
    drop = rng.random(len(edge_r)) < spec.edge_dropout
    noisy[edge_r[drop], edge_c[drop]] = 0.0
    noisy[~valid | (noisy < 0)] = 0.0
    colour = rgb.astype(np.float32)
    colour += bank.take(rgb.shape) * np.float32(spec.colour_sigma)
    np.clip(colour, 0, 255, out=colour)
    return colour.astype(np.uint8), noisy
