"""The theories of occlusion the project ships, by name (``--theory hand|learned|hindsight``).

- ``hand``: ``prolog/too.pl``, written by hand;
- ``learned``: ``prolog/too_learned.pl``, its occlusion rules learned from the simulator's
  ground truth (``make learned-theory``);
- ``hindsight``: ``prolog/too_learned_hindsight.pl``, learned from hindsight labels, without
  ground truth.

Any other value is the path of a DDC program.
"""

from __future__ import annotations

from pathlib import Path

from bridge.resources import prolog_file

THEORIES: dict[str, Path] = {
    "hand": prolog_file("too.pl"),
    "learned": prolog_file("too_learned.pl"),
    "hindsight": prolog_file("too_learned_hindsight.pl"),
}
#: The theory of occlusion unless told otherwise: the hand-written one
DEFAULT_THEORY = THEORIES["hand"]


def theory_path(name: str | Path) -> Path:
    """The file of a shipped theory's name, or the path given."""
    return THEORIES.get(str(name), Path(name))
