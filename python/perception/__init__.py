"""Perception: RGB-D frames in, percepts out.

    from perception import Pipeline, perceive_scenario
    pipeline = Pipeline()                    # PipelineConfig() defaults, the shipped model
    percepts = pipeline.process(frame)       # list[percepts.Percept]; [] when nothing is seen
    frames = perceive_scenario("scenarios/shell_game.yaml", seed=0)  # Iterator[PerceptFrame]

``frame`` is a :class:`tabletop.Frame` or anything with ``index, time, rgb (HxWx3 uint8),
depth (HxW float32 metres, 0 = none), intrinsics (fx, fy, cx, cy, width, height),
camera_pose (4x4 world-from-camera, OpenCV axes)``; ``truth``, ``segmentation`` and
``body_names`` are optional and used only to fill ``Percept.truth_id``.
"""

from perception.classifier import CategoryModel
from perception.colour import colour_names, histogram
from perception.pipeline import Pipeline, PipelineConfig, perceive_scenario

__all__ = [
    "CategoryModel",
    "Pipeline",
    "PipelineConfig",
    "colour_names",
    "histogram",
    "perceive_scenario",
]
