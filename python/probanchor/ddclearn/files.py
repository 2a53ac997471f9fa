"""Writing a file so that a reader never sees half of it: :func:`write_atomically`."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from pathlib import Path

__all__ = ["write_atomically"]


def write_atomically(path: str | Path, data: str | bytes,
                     check: Callable[[Path], None] | None = None) -> Path:
    """Write ``data`` to ``path`` through a temporary file in the same folder.

    Parameters
    ----------
    path
        The file to write; its folder is made if it is missing.
    data
        Text (written as UTF-8) or bytes.
    check
        Called with the temporary file before it replaces ``path``; whatever it raises is
        raised, and ``path`` keeps what it held (e.g. a program that does not compile).

    Returns
    -------
    Path
        ``path``, readable by everyone as a file written with ``open`` would be (mode 0644).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> write_atomically(folder / "a.pl", "a.\\n").read_text()
    'a.\\n'
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data.encode("utf-8") if isinstance(data, str) else data)
        if check is not None:
            check(Path(tmp))
        os.chmod(tmp, 0o644)  # (mkstemp's file is private to its owner)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path
