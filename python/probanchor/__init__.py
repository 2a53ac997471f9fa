"""Probabilistic anchoring: everything but the anchoring core and the Prolog bridge.

The subpackages: ``loop`` (the run-time loop that wires perception, anchoring and reasoning;
whole runs), ``learning`` (theories and data learned from experience), ``experiments`` (many
runs measured), ``cli`` (the ``anchoring`` and ``ddc`` commands), ``percepts``
(the percept record and its streams), ``tabletop`` (the simulated table), ``perception`` (RGB-D
frames to percepts), ``rgbd``, ``bags`` (RGB-D bags), ``evaluation``, ``visualise``,
``ddclearn`` (learning DDC programs), ``jobs`` (many independent jobs). The top-level packages
``anchoring`` (percepts in, anchors out) and ``bridge`` (the only door to Prolog) stand apart.

Importing this package imports nothing else.
"""
