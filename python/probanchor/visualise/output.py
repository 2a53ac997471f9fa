"""Saving frames: PNG per frame and an animated GIF of several (imageio)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import imageio.v3 as iio
import numpy as np


def save_png(path: str | Path, image: np.ndarray) -> Path:
    """Write an RGB uint8 image as PNG (creating the folder); returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    iio.imwrite(path, np.asarray(image, dtype=np.uint8), extension=".png")
    return path


def write_gif(
    path: str | Path, frames: Sequence[np.ndarray | str | Path], fps: float = 10.0
) -> int:
    """Write frames (images, or paths of PNGs) as a looping GIF; returns the number given.

    All frames must have the same size. The GIF encoder (Pillow) merges consecutive frames that
    are exactly identical into one longer frame, so a still scene may give fewer frames.
    """
    if not frames:
        raise ValueError(f"{path}: no frames to write")
    if fps <= 0:
        raise ValueError(f"{path}: frames per second must be positive, got {fps}")
    images = [iio.imread(f) if isinstance(f, (str, Path)) else np.asarray(f) for f in frames]
    images = [img[:, :, :3] if img.ndim == 3 else img for img in images]
    shapes = {img.shape for img in images}
    if len(shapes) != 1:
        raise ValueError(f"{path}: frames differ in size: {sorted(shapes)}")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    iio.imwrite(path, np.stack(images).astype(np.uint8), extension=".gif",
                duration=1000.0 / fps, loop=0)
    return len(images)
