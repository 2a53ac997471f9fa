"""The engines that can step a filter's particles (:class:`bridge.Filter`'s ``engine``).

A pure module (it does not start Prolog), so that command-line parsers can offer the choices
(``--engine``) without importing :mod:`bridge.filter`.
"""

from __future__ import annotations

from typing import Literal

Engine = Literal["per_particle", "batched", "auto"]
#: The engines by name, ``auto`` first (the default: the batched engine when the program is
#: in its fragment, else the per-particle one)
ENGINES: tuple[Engine, ...] = ("auto", "batched", "per_particle")
