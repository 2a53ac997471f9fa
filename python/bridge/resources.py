"""Where the project's Prolog files are: package resources of :mod:`bridge`.

The repository's ``prolog/`` folder (the DDC system, the theories of occlusion, ``world.pl``, the
examples) is the package folder ``bridge/engine``: in the source tree ``python/bridge/engine``
is a link to ``../../prolog``, and an installed distribution carries the files themselves
there (package data). Either way they are found through :mod:`importlib.resources`, relative to
the imported :mod:`bridge`, never through the layout of a checkout. A pure module: it does not
start Prolog.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

#: The package folder, below :mod:`bridge`, that holds the Prolog files
PROLOG_FOLDER = "engine"


def package_file(package: str, *parts: str) -> Path:
    """The file (or folder) ``parts`` inside ``package``'s resources, as a file-system path.

    Raises
    ------
    FileNotFoundError
        The package is not installed as files (e.g. imported from a zip archive): Prolog and
        the other readers need real files.
    """
    found = resources.files(package).joinpath(*parts)
    if not isinstance(found, Path):
        raise FileNotFoundError(f"{package}: its resources are not files on disk ({found})")
    return found.resolve()


def prolog_dir() -> Path:
    """The folder of the Prolog files (the repository's ``prolog/``)."""
    return package_file("bridge", PROLOG_FOLDER)


def prolog_file(*parts: str) -> Path:
    """A Prolog file (or folder) by its path below ``prolog/``, e.g. ``prolog_file("too.pl")``."""
    return package_file("bridge", PROLOG_FOLDER, *parts)
