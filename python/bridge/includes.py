"""A DC file with the files it includes, as the DDC system reads them.

A program may ``:- include(File).`` others (the shipped theories of occlusion include the
parts in ``prolog/too/``), each found relative to the file that includes it. The one reader
of DC files (``prolog/ddc/lang/ddc_source.pl``) follows the includes; :func:`with_includes`
asks it (``bridge_with_includes/2`` in ``prolog/ddc/filter/ddc_bridge.pl``), so that whatever
must know what a program is made of (a digest of a theory, say) finds the same files the
filter reads. Example::

    from bridge.includes import with_includes
    with_includes("prolog/too.pl")   # [.../too.pl, .../too/too_base.pl, ...]
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from bridge.filter import call_helper
from bridge.prolog import OUT

__all__ = ["digest_with_includes", "with_includes"]


def with_includes(path: str | os.PathLike[str]) -> list[Path]:
    """The absolute paths of the DC file at ``path`` and of every file it includes
    (transitively), in reading order, ``path``'s first. An included file with no clause or
    directive in it (comments only) is left out: it changes nothing the program says.

    Raises
    ------
    bridge.errors.UnknownObjectError
        The file, or a file it includes, does not exist (naming the include's file:line).
    bridge.errors.BadArgumentError
        A file does not parse (``file:line: syntax error: ...``).
    """
    found = call_helper("bridge_with_includes", F=os.fspath(path), Fs=OUT)["Fs"]
    return [Path(str(f)) for f in found]


def digest_with_includes(path: str | os.PathLike[str]) -> str:
    """The SHA-1 (hex) of the bytes of :func:`with_includes` (``path``), file after file (each
    after its length): it changes when the file or any file it includes does."""
    sha = hashlib.sha1()
    for file in with_includes(path):
        data = file.read_bytes()
        sha.update(f"{len(data)}\n".encode())
        sha.update(data)
    return sha.hexdigest()
