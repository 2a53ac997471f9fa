"""The run-time loop: a robot's world model frame by frame, and whole runs of it.

Per frame the data flows one way: percepts -> anchoring -> bridge -> DDC filter -> particles ->
anchors (:mod:`probanchor.loop.loop`; :mod:`probanchor.loop.reasoning` is the only module that
uses :mod:`bridge`). Around it: where frames come from (``sources``), a whole run with its
summary, pictures and world file (``runner``, ``pictures``, ``world_file``), the SQLite store a
run resumes from (``store``), the live world model asked during a run (``live``), the Rerun log
(``rerun_frames``), the shipped theories by name (``theories``) and symbols as Prolog atoms
(``naming``).

The loop imports neither :mod:`probanchor.learning` nor :mod:`probanchor.experiments`; they use
its public names (docs/architecture.md, held by tests/test_layers.py). Importing this package
imports nothing.
"""
