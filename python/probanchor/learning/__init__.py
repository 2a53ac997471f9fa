"""Learning from experience: episodes played through anchoring (``experience``), the
before/after facts of occlusions they give (``occlusion_data``, ``collect``), the theory of
occlusion learned from them (``learned_theory``, with ``occlusion_affordances`` and
``occlusion_reach``), and the category classifier's data from simulated tables
(``classifier_data``).

It uses the run-time loop's public names only (:mod:`probanchor.loop`); the structure learner
itself is :mod:`probanchor.ddclearn`. Importing this package imports nothing.
"""
