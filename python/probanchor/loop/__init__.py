"""The application that wires perception, anchoring and reasoning together.

It stands apart from the layers it connects: perception knows nothing of anchors, anchoring knows
nothing of Prolog, and only :mod:`probanchor.app.reasoning` (through :mod:`bridge`) talks to the
particle filter. Per frame the data flows one way: percepts -> anchoring -> bridge -> DDC filter
-> particles -> anchors.
"""
