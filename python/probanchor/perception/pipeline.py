"""The perception pipeline: one RGB-D frame in, a list of percepts out.

    pipeline = Pipeline()
    percepts = pipeline.process(frame)          # frame: rgbd.RGBDFrame or alike

Steps: depth -> world points (camera intrinsics and pose); table plane by a seeded RANSAC on a
subsample (the same plane on every run); above-table mask; skin segments by an HSV window;
object segments by connected components cut at depth jumps; per segment position and size
(3-D box), HSV histogram and colour names, top-3 categories from the shape classifier; the
skin segments of one arm joined and each given the point where its hand closes
(:mod:`probanchor.perception.grip`).
``truth_id`` is filled from the frame's ground-truth segmentation when the frame carries one
(for training and evaluation only: no attribute is computed from it).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import cv2
import numpy as np

from probanchor.perception.camera import check_frame
from probanchor.perception.classifier import DEFAULT_MODEL, CategoryModel
from probanchor.perception.colour import DEFAULT_BINS, colour_names, histogram, hue_shift
from probanchor.perception.features import box_attributes, shape_features
from probanchor.perception.grip import GripConfig, arms, join_across_arms
from probanchor.perception.plane import Plane, fit_plane
from probanchor.perception.pointcloud import Backprojector
from probanchor.perception.segments import (
    Segment,
    SkinWindow,
    components,
    merge_fragments,
    occluded_side,
)
from probanchor.percepts import Percept, PerceptFrame


@dataclass
class PipelineConfig:
    """Parameters (lengths in metres, pixel counts at 320x240, scaled with the image area)."""

    min_height: float = 0.008  # above the table plane
    max_height: float = 0.5
    workspace: tuple[float, float, float, float] = (-0.6, 0.6, -0.5, 0.5)  # x0 x1 y0 y1
    depth_jump: float = 0.02  # relative depth step that separates two segments
    min_pixels: int = 30
    skin_min_pixels: int = 60
    skin: SkinWindow = field(default_factory=SkinWindow)
    bins: tuple[int, int, int] = DEFAULT_BINS
    peak_ratio: float = 0.65
    plane_stride: int = 6
    plane_threshold: float = 0.01
    rest_height: float = 0.02
    top_k: int = 3
    truth_fraction: float = 0.5  # share of a segment's pixels that names its truth_id
    fragment_pixels: int = 120  # object segments smaller than this may be fragments ...
    fragment_gap: float = 0.015  # ... merged into a larger one whose box is this close (m)
    grip: GripConfig = field(default_factory=GripConfig)  # skin: arms and grip points


class Pipeline:
    """Turns frames into percepts. ``model`` is a :class:`CategoryModel` or a path to one."""

    def __init__(self, config: PipelineConfig | None = None,
                 model: CategoryModel | str | Path | None = None, label_truth: bool = True
                 ) -> None:
        self.config = config or PipelineConfig()
        if model is None or isinstance(model, (str, Path)):
            path = Path(model) if model is not None else DEFAULT_MODEL
            self.model: CategoryModel | None = CategoryModel.load(path) if path.exists() \
                else None
        else:
            self.model = model
        self.label_truth = label_truth
        self.backprojector = Backprojector()
        self.plane: Plane | None = None
        self.last_segments: list[Segment] = []
        self.last_shape_features: dict[int, np.ndarray] = {}  # percept index -> features

    # ------------------------------------------------------------------------------ segments
    def segment(self, frame: Any) -> list[Segment]:
        """Segments of a frame (objects and skin), also kept in ``last_segments``.

        Parameters
        ----------
        frame:
            An :class:`rgbd.RGBDFrame` of any camera, or anything alike.

        Returns
        -------
        The segments; a :class:`perception.FrameError` for a frame that cannot be perceived.
        """
        check_frame(frame)
        cfg = self.config
        depth = frame.depth
        h, w = depth.shape
        scale = (h * w) / (320 * 240)
        valid = np.isfinite(depth) & (depth > 0)
        if not valid.all():
            depth = np.where(valid, depth, np.float32(0.0)).astype(np.float32)
        self.last_segments = []
        if int(valid.sum()) < 100:
            return []  # camera covered or blind: nothing to perceive
        pose, k = frame.camera_pose, frame.intrinsics
        s = cfg.plane_stride
        sub = np.zeros_like(valid)
        sub[::s, ::s] = valid[::s, ::s]
        sr, sc = np.nonzero(sub)
        plane = fit_plane(self.backprojector.world_points(depth, k, pose, sr, sc),
                          threshold=cfg.plane_threshold)
        if plane is None:
            plane = self.plane
        if plane is None:
            return []
        self.plane = plane
        # height above the plane of every pixel, without building the whole cloud:
        # height = n . (R (z ray) + t) + d = z (ray . R^T n) + (n . t + d)
        rot, t = pose[:3, :3], pose[:3, 3]
        rays = self.backprojector.rays(k.fx, k.fy, k.cx, k.cy, k.width, k.height)
        slope = rays @ (rot.T @ plane.normal).astype(np.float32)
        height_img = depth * slope + np.float32(plane.normal @ t + plane.offset)
        candidate = valid & (height_img > cfg.min_height) & (height_img < cfg.max_height)
        rows, cols = np.nonzero(candidate)
        world = self.backprojector.world_points(depth, k, pose, rows, cols)
        heights = height_img[rows, cols]
        x0, x1, y0, y1 = cfg.workspace
        keep = (world[:, 0] > x0) & (world[:, 0] < x1) & (world[:, 1] > y0) & (world[:, 1] < y1)
        rows, cols, world, heights = rows[keep], cols[keep], world[keep], heights[keep]
        if len(rows) == 0:
            return []
        index = np.full((h, w), -1, np.int32)
        index[rows, cols] = np.arange(len(rows), dtype=np.int32)
        above = np.zeros((h, w), np.uint8)
        above[rows, cols] = 255
        hsv = cv2.cvtColor(frame.rgb, cv2.COLOR_RGB2HSV)
        self._hsv_plain = hsv
        skin = cv2.bitwise_and(cfg.skin.mask(hsv), above)
        skin = cv2.morphologyEx(skin, cv2.MORPH_OPEN, np.ones((3, 3), np.uint8))
        skin_grown = cv2.dilate(skin, np.ones((3, 3), np.uint8))
        objects = above.copy()
        objects[skin_grown > 0] = 0
        objects[occluded_side(depth, objects > 0, cfg.depth_jump)] = 0
        segments: list[Segment] = []
        for kind, mask, min_px in (("object", objects, cfg.min_pixels),
                                   ("skin", skin, cfg.skin_min_pixels)):
            if cv2.countNonZero(mask) < min_px * scale:
                continue
            for r, c, label, bbox in components(mask, max(1, int(round(min_px * scale)))):
                idx = index[r, c]
                ok = idx >= 0
                r, c, idx = r[ok], c[ok], idx[ok]
                if len(idx) == 0:
                    continue
                segments.append(Segment(kind, r, c, world[idx], heights[idx], bbox, label))
        segments = merge_fragments(segments, cfg.fragment_pixels * scale, cfg.fragment_gap)
        skins = [s for s in segments if s.kind == "skin"]
        if skins:
            segments = join_across_arms(segments, skin, hsv)
            kept = arms(skins, (h, w), cfg.workspace, cfg.max_height, cfg.grip)
            for seg, grip in kept:
                seg.grip = grip
            ids = {id(seg) for seg, _ in kept}
            segments = [s for s in segments if s.kind != "skin" or id(s) in ids]
        self.last_segments = segments
        return segments

    # ------------------------------------------------------------------------------ percepts
    def process(self, frame: Any) -> list[Percept]:
        """The percepts of one frame (an empty list when nothing is seen)."""
        cfg = self.config
        segments = self.segment(frame)
        if not segments:
            return []
        assert self.plane is not None
        hsv = self._hsv_plain.copy()
        hue = hsv[:, :, 0]
        hue += np.uint8(hue_shift(cfg.bins))
        hue[hue >= 180] -= 180
        k = frame.intrinsics
        camera_xy = (float(frame.camera_pose[0, 3]), float(frame.camera_pose[1, 3]))
        out: list[Percept] = []
        shape_rows = []
        for i, seg in enumerate(segments):
            # distance to the segment: metres per pixel = z / fx
            z = float(np.linalg.norm(seg.points.mean(axis=0) - frame.camera_pose[:3, 3]))
            pixel = z / k.fx
            position, size = box_attributes(seg.points, seg.heights, self.plane,
                                            cfg.rest_height, pixel, camera_xy)
            bx0, by0, bx1, by1 = seg.bbox
            mask = np.zeros((by1 - by0, bx1 - bx0), np.uint8)
            mask[seg.rows - by0, seg.cols - bx0] = 255
            hist = histogram(hsv[by0:by1, bx0:bx1], mask, cfg.bins)
            percept = Percept(
                time=float(frame.time),
                position=position,
                size=size,
                colour_histogram=hist,
                category={"skin": 1.0},
                colour_names=colour_names(hist, cfg.bins, cfg.peak_ratio),
                bbox=seg.bbox,
                source_id=i,
                grip=seg.grip,
            )
            if seg.kind == "object":
                area = len(seg.rows) * pixel * pixel
                shape_rows.append((len(out), shape_features(seg.points, seg.heights, area)))
            out.append(percept)
        self.last_shape_features = {j: f for j, f in shape_rows}
        if shape_rows:
            feats = np.stack([f for _, f in shape_rows])
            if self.model is not None:
                tops = self.model.top(feats, cfg.top_k)
            else:
                tops = [{"object": 1.0} for _ in shape_rows]
            for (j, _), top in zip(shape_rows, tops, strict=True):
                out[j].category = top
        if self.label_truth:
            self._label_truth(frame, segments, out)
        return out

    def _label_truth(self, frame: Any, segments: list[Segment], percepts: list[Percept]
                     ) -> None:
        seg_img = getattr(frame, "segmentation", None)
        names = getattr(frame, "body_names", None) or {}
        objects = (getattr(frame, "truth", None) or {}).get("objects", {})
        if seg_img is None:
            return
        for seg, percept in zip(segments, percepts, strict=True):
            if seg.kind != "object":
                continue
            ids, counts = np.unique(seg_img[seg.rows, seg.cols], return_counts=True)
            best = int(np.argmax(counts))
            name = names.get(int(ids[best]))
            if name in objects and counts[best] >= self.config.truth_fraction * counts.sum():
                percept.truth_id = name

    def percept_frame(self, frame: Any) -> PerceptFrame:
        """The frame's percepts with its ground truth attached (for streams)."""
        return PerceptFrame(frame=int(frame.index), time=float(frame.time),
                            percepts=self.process(frame), truth=dict(frame.truth or {}))

