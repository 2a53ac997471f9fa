r"""A picture of one frame of a Rerun log, drawn with matplotlib from the logged data (for
documents, and where the viewer cannot run): the point cloud, the anchors' boxes and labels,
the hidden anchors' particles in 3-D, beside the camera image.

    .venv/bin/python -m probanchor.visualise.rrd_picture out/shell_game.rrd --frame 150 \
        --out view.png
"""

from __future__ import annotations

import argparse
import io
from collections import defaultdict
from itertools import product
from pathlib import Path
from typing import Any

import numpy as np


def frame_data(path: Path, frame: int) -> dict[str, dict[str, Any]]:
    """Entity -> column -> value of the last row logged at or before ``frame``.

    Parameters
    ----------
    path:
        The ``.rrd`` file.
    frame:
        The frame on the ``frame`` timeline.

    Returns
    -------
    The entities' latest values, as Rerun's reader gives them (lists).
    """
    from rerun.chunk import RrdReader

    best: dict[str, tuple[int, dict[str, Any]]] = {}
    for chunk in RrdReader(path).store().stream():
        batch = chunk.to_record_batch()
        if "frame" not in batch.schema.names:
            continue
        frames = batch.column("frame").to_pylist()
        for row, f in enumerate(frames):
            if f is not None and f <= frame and f >= best.get(chunk.entity_path, (-1, {}))[0]:
                best[chunk.entity_path] = (f, {n: batch.column(n)[row].as_py()
                                              for n in batch.schema.names})
    out: dict[str, dict[str, Any]] = defaultdict(dict)
    for entity, (_, row) in best.items():
        out[entity] = row
    return out


def _box_edges(centre: np.ndarray, half: np.ndarray) -> list[np.ndarray]:
    corners = np.array([centre + half * np.array(s) for s in product((-1, 1), repeat=3)])
    return [np.stack([corners[i], corners[j]]) for i in range(8) for j in range(i + 1, 8)
            if np.sum(np.abs(corners[i] - corners[j]) > 1e-12) == 1]


def draw(path: Path, frame: int, out: Path, elevation: float = 35.0,
         azimuth: float = -70.0) -> Path:
    """Draw one frame of a log as a PNG.

    Parameters
    ----------
    path:
        The ``.rrd`` file (``anchoring run --rerun``).
    frame:
        The frame to draw.
    out:
        The PNG to write.
    elevation, azimuth:
        The 3-D view's angles (degrees).

    Returns
    -------
    ``out``.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from PIL import Image

    data = frame_data(path, frame)
    fig = plt.figure(figsize=(11, 4.6), dpi=90)
    ax = fig.add_subplot(1, 2, 2, projection="3d")
    cloud = data.get("/world/cloud", {})
    if cloud.get("Points3D:positions"):
        pts = np.asarray(cloud["Points3D:positions"])
        colours = np.asarray(cloud["Points3D:colors"], dtype=np.uint32)
        rgb = np.stack([(colours >> s) & 255 for s in (24, 16, 8)], axis=1) / 255.0
        ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], c=rgb, s=2.0, linewidths=0,
                   depthshade=False, alpha=0.6)
    boxes = data.get("/world/anchors", {})
    for centre, half, colour, label in zip(boxes.get("Boxes3D:centers") or [],
                                           boxes.get("Boxes3D:half_sizes") or [],
                                           boxes.get("Boxes3D:colors") or [],
                                           boxes.get("Boxes3D:labels") or [], strict=False):
        c = np.array([(colour >> s) & 255 for s in (24, 16, 8)]) / 255.0
        for edge in _box_edges(np.asarray(centre), np.asarray(half)):
            ax.plot(edge[:, 0], edge[:, 1], edge[:, 2], color=c, linewidth=1.2)
        ax.text(centre[0], centre[1], centre[2] + half[2] + 0.02, label, color=c,
                fontsize=8, weight="bold")
    for entity, row in data.items():
        if entity.startswith("/world/particles/") and row.get("Points3D:positions"):
            pts = np.asarray(row["Points3D:positions"])
            colours = np.asarray(row["Points3D:colors"], dtype=np.uint32)
            rgba = np.stack([(colours >> s) & 255 for s in (24, 16, 8, 0)], axis=1) / 255.0
            ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], c=rgba, s=7, linewidths=0,
                       depthshade=False)
    ax.set(xlim=(-0.45, 0.45), ylim=(-0.3, 0.45), zlim=(0, 0.3), xlabel="x (m)",
           ylabel="y (m)", zlabel="z (m)")
    ax.set_box_aspect((0.9, 0.75, 0.3))
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.pane.set_visible(False)
    ax.grid(False)
    ax.view_init(elev=elevation, azim=azimuth)
    ax.set_title(f"3-D view, frame {frame}", fontsize=9)
    image = data.get("/world/camera/image", {})
    left = fig.add_subplot(1, 2, 1)
    if image.get("EncodedImage:blob"):
        blob = image["EncodedImage:blob"]
        blob = blob[0] if isinstance(blob, list) and blob and isinstance(blob[0], list) else blob
        left.imshow(Image.open(io.BytesIO(bytes(blob))))
    left.set_axis_off()
    left.set_title("world/camera/image", fontsize=9)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out)
    plt.close(fig)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rrd", type=Path)
    ap.add_argument("--frame", type=int, required=True)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--elevation", type=float, default=35.0)
    ap.add_argument("--azimuth", type=float, default=-70.0)
    args = ap.parse_args(argv)
    print(draw(args.rrd, args.frame, args.out, args.elevation, args.azimuth))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
