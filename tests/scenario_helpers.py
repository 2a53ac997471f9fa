"""Short scenarios shared by the end-to-end tests."""

from __future__ import annotations

from pathlib import Path

import pytest

# Two look-alike balls, both hidden when ball_1 is revealed: anchoring cannot tell them apart by
# appearance, so only where ball_1 is believed to be (the reasoning) keeps its symbol.
BALL_UNDER_MUG_MOVED = """\
name: ball_under_mug_moved
fps: 5
objects:
  - {id: ball_1, category: ball, colour: red, radius: 0.03, position: [-0.1, -0.05]}
  - {id: mug_1, category: mug, colour: blue, radius: 0.04, height: 0.1, position: [0.05, 0.05]}
  - {id: ball_2, category: ball, colour: red, radius: 0.03, position: [-0.25, 0.2]}
  - {id: box_1, category: box, colour: green, size: [0.12, 0.12, 0.12], position: [-0.05, 0.25]}
events:
  - {at: 1.0, do: put_under, object: ball_1, container: mug_1, duration: 2.0}
  - {at: 1.0, do: put_under, object: ball_2, container: box_1, duration: 2.0}
  - {at: 3.5, do: move, object: mug_1, to: [0.2, 0.1], duration: 2.0}
  - {at: 6.0, do: lift, container: mug_1, duration: 2.0}
"""


def scenario_file(factory: pytest.TempPathFactory, text: str = BALL_UNDER_MUG_MOVED,
                  name: str = "ball_under_mug_moved") -> Path:
    """The scenario ``text`` in a new temporary folder, as ``name.yaml``."""
    path = factory.mktemp("scenario") / f"{name}.yaml"
    path.write_text(text)
    return path
