"""The one place that imports py-motmetrics.

motmetrics 1.4.0 (the current release) calls ``np.asfarray``, which numpy 2.0 removed. Before
importing it we give numpy an ``asfarray`` that does what the old one did (``np.asarray`` with a
floating dtype) when, and only when, numpy lacks it. Import motmetrics from here, never directly:
``from evaluation.motmetrics_compat import mm``.

motmetrics 1.4.0 also stores object and hypothesis ids as floats, so callers must give it
numeric ids (see :mod:`probanchor.evaluation.metrics`).
"""

from __future__ import annotations

import numpy as np

if not hasattr(np, "asfarray"):

    def _asfarray(a, dtype=np.float64):  # the numpy 1.x semantics
        dtype = np.dtype(dtype)
        if not np.issubdtype(dtype, np.inexact):
            dtype = np.dtype(np.float64)
        return np.asarray(a, dtype=dtype)

    np.asfarray = _asfarray  # type: ignore[attr-defined]

import motmetrics as mm  # noqa: E402

__all__ = ["mm"]
