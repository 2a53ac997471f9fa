"""Named colours a scenario may use, as RGB in [0, 1], and the skin colour of hands."""

from __future__ import annotations

NAMED_COLOURS: dict[str, tuple[float, float, float]] = {
    "red": (0.85, 0.08, 0.08),
    "orange": (1.0, 0.5, 0.0),
    "yellow": (0.95, 0.85, 0.08),
    "green": (0.1, 0.65, 0.15),
    "cyan": (0.08, 0.75, 0.8),
    "blue": (0.08, 0.25, 0.85),
    "purple": (0.5, 0.15, 0.75),
    "pink": (1.0, 0.4, 0.7),
    "brown": (0.45, 0.25, 0.08),
    "white": (0.95, 0.95, 0.95),
    "gray": (0.45, 0.45, 0.45),
    "black": (0.08, 0.08, 0.08),
}
#: Other spellings a scenario may use for a named colour.
COLOUR_ALIASES: dict[str, str] = {"grey": "gray"}

SKIN_RGB: tuple[float, float, float] = (0.87, 0.67, 0.55)
TABLE_RGB: tuple[float, float, float] = (0.62, 0.64, 0.68)
