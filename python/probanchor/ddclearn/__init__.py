"""Structure learning of Distributional Clauses: distributional logic trees and their leaves.

``learn(files)`` learns one tree per target of the data's declarative bias and returns the DC
program they make; ``evaluate(program, files)`` scores a program on held-out data.
"""

from probanchor.ddclearn.learner import LearnResult, evaluate, learn, target_key
from probanchor.ddclearn.leaves import Leaf, LeafOptions, fit_leaf
from probanchor.ddclearn.search import SearchOptions, TargetResult

__all__ = ["Leaf", "LeafOptions", "LearnResult", "SearchOptions", "TargetResult", "evaluate",
           "fit_leaf", "learn", "target_key"]
