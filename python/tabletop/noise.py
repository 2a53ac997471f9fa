"""Sensor noise added to rendered frames (deterministic given the generator)."""

from __future__ import annotations

import cv2
import numpy as np

from tabletop.scenario import NoiseSpec


def add_noise(rgb: np.ndarray, depth: np.ndarray, spec: NoiseSpec, rng: np.random.Generator
              ) -> tuple[np.ndarray, np.ndarray]:
    """Return noisy copies: depth noise growing with distance, missing depth next to depth
    jumps (object edges), and Gaussian colour noise."""
    if not spec.enabled:
        return rgb, depth
    valid = depth > 0
    z = depth.astype(np.float32)
    sigma = spec.depth_sigma_base + spec.depth_sigma_quadratic * z * z
    noisy = z + rng.standard_normal(z.shape, dtype=np.float32) * sigma
    # depth jumps: a pixel whose 3x3 neighbourhood spans more than edge_jump
    far = np.where(valid, z, 10.0).astype(np.float32)
    near = np.where(valid, z, 0.0).astype(np.float32)
    kernel = np.ones((3, 3), np.uint8)
    span = cv2.dilate(near, kernel) - cv2.erode(far, kernel)
    edge = valid & (span > spec.edge_jump)
    drop = edge & (rng.random(z.shape, dtype=np.float32) < spec.edge_dropout)
    noisy[~valid | drop] = 0.0
    noisy[noisy < 0] = 0.0
    colour = rgb.astype(np.float32) + rng.standard_normal(rgb.shape, dtype=np.float32) * \
        spec.colour_sigma
    return np.clip(colour, 0, 255).astype(np.uint8), noisy.astype(np.float32)
