"""Percept records: what a perception pipeline hands to the anchoring system.

This package is the contract between perception (which produces percepts) and anchoring
(which consumes them); it knows nothing of either side.
"""

from probanchor.percepts.record import Percept, PerceptError
from probanchor.percepts.stream import PerceptFrame, read_percepts, write_percepts

__all__ = ["Percept", "PerceptError", "PerceptFrame", "read_percepts", "write_percepts"]
