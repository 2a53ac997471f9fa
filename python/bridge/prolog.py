"""The one place that starts SWI-Prolog through janus and loads the project's Prolog files."""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

import janus_swi as janus

from bridge.resources import prolog_dir

#: The project's Prolog files (package resources, see :mod:`bridge.resources`)
PROLOG_DIR = prolog_dir()

_lock = threading.Lock()
_consulted: set[Path] = set()


def ensure_loaded(path: str | Path) -> None:
    """Consult a Prolog file once per process (``use_module`` semantics for module files)."""
    resolved = Path(path).resolve()
    with _lock:
        if resolved in _consulted:
            return
        janus.query_once("ensure_loaded(F)", {"F": str(resolved)})
        _consulted.add(resolved)


def query_once(goal: str, bindings: dict[str, Any] | None = None) -> dict[str, Any]:
    """Run ``goal`` once; return its bindings (``truth`` is False when it failed)."""
    return janus.query_once(goal, bindings or {})
