"""Data sets shipped with the learner, for its tests and benchmarks.

``financial()`` is DreaML's complete input file for the PKDD'99 Financial data (Kumar, Kuželka
and De Raedt's ``data/FinancialData.pl``, GitHub ``niteshroyal/DreaML``): aggregate helpers, the
declarative bias (``base/1``, ``mode/3``, ``thres/4``, ``randomVariableNames/1``, ``rank/1``, 14
``learn/4`` lines for 13 targets) and about 54,000 facts on clients, accounts, loans and
districts. It ships gzipped in the package (``ddclearn/data``) and is decompressed once into a
cache folder, so that ``ddc learn`` and DreaML both read it as the plain text it is::

    from probanchor.ddclearn.datasets import financial
    path = financial()          # .../ddclearn/FinancialData.pl
"""

from __future__ import annotations

import gzip
import os
from importlib import resources
from pathlib import Path

from probanchor.ddclearn.files import write_atomically

__all__ = ["cache_folder", "financial"]


def cache_folder() -> Path:
    """``$DDCLEARN_DATA``, else ``$XDG_CACHE_HOME/ddclearn``, else ``~/.cache/ddclearn``."""
    if os.environ.get("DDCLEARN_DATA"):
        return Path(os.environ["DDCLEARN_DATA"])
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "ddclearn"


def financial(folder: str | Path | None = None) -> Path:
    """The path of ``FinancialData.pl``, decompressed into ``folder`` (default: the cache).

    Parameters
    ----------
    folder : path, optional
        Where to put the file (created if needed); default :func:`cache_folder`.

    Returns
    -------
    Path
        The plain-text data file (written atomically the first time).
    """
    return _decompressed("FinancialData.pl.gz", Path(folder) if folder else cache_folder())


def _decompressed(name: str, folder: Path) -> Path:
    packed = resources.files("probanchor.ddclearn") / "data" / name
    data = gzip.decompress(packed.read_bytes())
    out = folder / name.removesuffix(".gz")
    if out.is_file() and out.stat().st_size == len(data):
        return out
    return write_atomically(out, data)
