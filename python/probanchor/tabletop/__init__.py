"""A simulated table with objects and an RGB-D camera over it (pybullet).

``load_scenario(path)`` reads a scenario file (scenarios/SCHEMA.md), ``ScenarioBuilder``
builds one in Python, ``Simulation(scenario, width=320, height=240, fps=None, seed=0)``
yields :class:`Frame` objects (RGB, depth, intrinsics, camera pose and ground truth).
"""

from probanchor.tabletop.builder import ScenarioBuilder
from probanchor.tabletop.camera import Camera, Intrinsics
from probanchor.tabletop.errors import ScenarioError
from probanchor.tabletop.scenario import (
    CATEGORY_SHAPES,
    SHAPES,
    CameraSpec,
    Event,
    NoiseSpec,
    ObjectSpec,
    Scenario,
    load_scenario,
    parse_scenario,
)
from probanchor.tabletop.simulation import Frame, Simulation, render_frames

__all__ = [
    "CATEGORY_SHAPES",
    "SHAPES",
    "Camera",
    "CameraSpec",
    "Event",
    "Frame",
    "Intrinsics",
    "NoiseSpec",
    "ObjectSpec",
    "Scenario",
    "ScenarioBuilder",
    "ScenarioError",
    "Simulation",
    "load_scenario",
    "parse_scenario",
    "render_frames",
]
