"""Perception: RGB-D frames in, percepts out (see perception.pipeline)."""

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
