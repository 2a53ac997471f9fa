"""Perception: RGB-D frames of any camera in, percepts out.

    from probanchor.perception import Pipeline
    pipeline = Pipeline()                    # PipelineConfig() defaults, the shipped model
    percepts = pipeline.process(frame)       # list[percepts.Percept]; [] when nothing is seen

``frame`` is an :class:`RGBDFrame` or anything with ``index, time, rgb (HxWx3 uint8),
depth (HxW float32 metres, 0 = none), intrinsics (fx, fy, cx, cy, width, height),
camera_pose (4x4 world-from-camera, OpenCV axes)``; ``truth``, ``segmentation`` and
``body_names`` are optional and used only to fill ``Percept.truth_id``. A frame that cannot be
perceived (images of different sizes, intrinsics of another size) is a :class:`FrameError`.
Where frames come from (the simulator, a recorded bag) is the caller's business: see
``probanchor.loop.sources``.
"""

from probanchor.perception.camera import CameraIntrinsics, FrameError, RGBDFrame, check_frame
from probanchor.perception.classifier import CategoryModel
from probanchor.perception.colour import colour_names, histogram
from probanchor.perception.pipeline import Pipeline, PipelineConfig

__all__ = [
    "CameraIntrinsics",
    "CategoryModel",
    "FrameError",
    "Pipeline",
    "PipelineConfig",
    "RGBDFrame",
    "check_frame",
    "colour_names",
    "histogram",
]
