"""Experiments: many runs of the loop and of baseline trackers over scenarios and seeds, and the
measured table they make (``sweep``, the ``anchoring evaluate`` command).

It uses the run-time loop's public names (:mod:`probanchor.loop`) and the metrics of
:mod:`probanchor.evaluation`. Importing this package imports nothing.
"""
