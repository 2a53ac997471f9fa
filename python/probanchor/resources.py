"""Where the shipped scenario files are: package resources of :mod:`probanchor`.

The repository's ``scenarios/`` folder is the package folder ``probanchor/scenarios`` (in the
source tree a link to ``../../scenarios``; an installed distribution carries the files there),
found through :mod:`importlib.resources` like the Prolog files (:mod:`bridge.resources`).
"""

from __future__ import annotations

from pathlib import Path

from bridge.resources import package_file

#: The package folder, below :mod:`probanchor`, that holds the scenario files
SCENARIO_FOLDER = "scenarios"


def scenarios_dir() -> Path:
    """The folder of the shipped scenarios (the repository's ``scenarios/``)."""
    return package_file("probanchor", SCENARIO_FOLDER)


def scenario_file(name: str) -> Path:
    """A shipped scenario by name, e.g. ``scenario_file("shell_game")`` (``.yaml`` added)."""
    return package_file("probanchor", SCENARIO_FOLDER, f"{name}.yaml")
