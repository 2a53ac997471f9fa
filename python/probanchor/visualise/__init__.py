"""Pictures of a run: anchors and particles over the camera image (a video, PNG per frame, GIF)
and a top-down plot of the beliefs over the table. See docs/evaluation.md."""

from probanchor.visualise.camera import CameraView
from probanchor.visualise.output import VideoWriter, save_png, write_gif, write_video
from probanchor.visualise.overlay import AnchorView, anchor_colour, draw_anchors, draw_particles
from probanchor.visualise.topdown import plot_topdown, render_topdown

__all__ = [
    "AnchorView",
    "CameraView",
    "VideoWriter",
    "anchor_colour",
    "draw_anchors",
    "draw_particles",
    "plot_topdown",
    "render_topdown",
    "save_png",
    "write_gif",
    "write_video",
]
