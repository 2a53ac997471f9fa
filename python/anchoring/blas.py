"""Keep BLAS single-threaded while a frame is processed.

The matrices of one frame are small (a few hundred pairs, tens of thousands of particles); a
multi-threaded BLAS spends more time waking and waiting for its threads than computing, and on
a busy two-core machine its latency jumps by an order of magnitude. ``threadpoolctl`` (a
scikit-learn dependency) limits it for the duration of a ``with`` block only.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

_controller: Any = None


@contextlib.contextmanager
def single_threaded_blas() -> Iterator[None]:
    global _controller
    if _controller is None:
        try:
            from threadpoolctl import ThreadpoolController

            _controller = ThreadpoolController()
        except ImportError:  # pragma: no cover - threadpoolctl comes with scikit-learn
            _controller = False
    if not _controller:
        yield
        return
    with _controller.limit(limits=1, user_api="blas"):
        yield
