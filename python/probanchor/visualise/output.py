"""Saving frames: PNG per frame, an animated GIF of several (imageio), and a video (MP4 with
H.264, or WebM with VP9) written frame by frame with PyAV, whose wheels ship FFmpeg and its
encoders (nothing to install on the system)."""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from pathlib import Path
from typing import Any

import imageio.v3 as iio
import numpy as np

#: Video codecs by file suffix: (PyAV codec, encoder options). CRF trades size for quality;
#: these keep drawn text and particle dots sharp at 320x240 and a 22-second run near 1 MB.
VIDEO_CODECS: dict[str, tuple[str, dict[str, str]]] = {
    ".mp4": ("libx264", {"crf": "26", "preset": "medium"}),
    ".webm": ("libvpx-vp9", {"crf": "34", "b": "0"}),
}
_MILLISECONDS = Fraction(1, 1000)  # the time base of a video's frames


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


class VideoWriter:
    """A video written one RGB frame at a time (:data:`VIDEO_CODECS` by the path's suffix).

    Frames are shown at their time stamps (seconds; ``add(image, time=t)``), so a run plays in
    real time whatever the stride of its pictures; without a time stamp, frame ``k`` is at
    ``k / fps``. Every frame must have the size of the first; odd sizes are padded by one
    black row or column (the encoders need even sizes). ``close()`` finishes the file; a
    writer is also a context manager.

    Parameters
    ----------
    path : str or Path
        ``.mp4`` (H.264) or ``.webm`` (VP9); the folder is created.
    fps : float
        Frames per second for frames without a time stamp.

    Raises
    ------
    ValueError
        An unknown suffix, ``fps`` not positive, a frame that is not RGB uint8 of the first's
        size, or time stamps that go backwards.
    """

    def __init__(self, path: str | Path, fps: float = 15.0) -> None:
        self.path = Path(path)
        if self.path.suffix.lower() not in VIDEO_CODECS:
            raise ValueError(f"{self.path}: a video is .mp4 or .webm, not "
                             f"{self.path.suffix or 'no suffix'!r}")
        if not fps > 0:
            raise ValueError(f"{self.path}: frames per second must be positive, got {fps}")
        self.fps = float(fps)
        self.frames = 0
        self._container: Any = None
        self._stream: Any = None
        self._shape: tuple[int, int] | None = None
        self._last_pts = -1
        self._start = 0.0

    def add(self, image: np.ndarray, time: float | None = None) -> None:
        """Append one RGB uint8 image (H, W, 3) shown from ``time`` seconds on."""
        import av

        image = np.asarray(image)
        if image.ndim != 3 or image.shape[2] < 3 or image.dtype != np.uint8:
            raise ValueError(f"{self.path}: frame {self.frames} is not an RGB uint8 image "
                             f"(shape {image.shape}, {image.dtype})")
        image = image[:, :, :3]
        if self._shape is None:
            self._open(image.shape[0], image.shape[1])
            self._start = 0.0 if time is None else float(time)  # the video starts at 0
        elif image.shape[:2] != self._shape:
            raise ValueError(f"{self.path}: frame {self.frames} is {image.shape[1]}x"
                             f"{image.shape[0]}, the first was {self._shape[1]}x{self._shape[0]}")
        height, width = self._stream.height, self._stream.width
        if image.shape[:2] != (height, width):
            padded = np.zeros((height, width, 3), np.uint8)
            padded[: image.shape[0], : image.shape[1]] = image
            image = padded
        seconds = self.frames / self.fps if time is None else float(time) - self._start
        pts = int(round(seconds * 1000))
        if pts <= self._last_pts:
            if time is not None and pts < self._last_pts:
                raise ValueError(f"{self.path}: frame {self.frames} at {time} s is before the "
                                 "previous frame")
            pts = self._last_pts + 1
        frame = av.VideoFrame.from_ndarray(np.ascontiguousarray(image), format="rgb24")
        frame.pts = pts
        frame.time_base = _MILLISECONDS  # (not the stream's: the muxer may change that)
        for packet in self._stream.encode(frame):
            self._container.mux(packet)
        self._last_pts = pts
        self.frames += 1

    def _open(self, height: int, width: int) -> None:
        import av

        codec, options = VIDEO_CODECS[self.path.suffix.lower()]
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._container = av.open(str(self.path), mode="w")
        self._stream = self._container.add_stream(codec, rate=int(round(self.fps)),
                                                  options=dict(options))
        self._stream.width, self._stream.height = width + width % 2, height + height % 2
        self._stream.pix_fmt = "yuv420p"
        # time stamps in milliseconds, for the encoder and the container alike (an encoder left
        # at 1/fps would see stamps 1000/fps times too far apart and overflow its counters)
        self._stream.codec_context.time_base = _MILLISECONDS
        self._stream.time_base = _MILLISECONDS
        self._shape = (height, width)

    def close(self) -> Path | None:
        """Finish the file; returns its path (``None`` when no frame was added: no file)."""
        if self._container is None:
            return None
        for packet in self._stream.encode(None):
            self._container.mux(packet)
        self._container.close()
        self._container = None
        return self.path

    def __enter__(self) -> VideoWriter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def write_video(path: str | Path, frames: Sequence[np.ndarray | str | Path],
                fps: float = 15.0) -> int:
    """Write frames (images, or paths of PNGs) as a video at ``fps``; returns the number written.

    See :class:`VideoWriter` for the formats and checks.
    """
    if not frames:
        raise ValueError(f"{path}: no frames to write")
    with VideoWriter(path, fps) as video:
        for f in frames:
            video.add(iio.imread(f) if isinstance(f, (str, Path)) else np.asarray(f))
    return len(frames)
