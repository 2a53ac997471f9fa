"""Anchoring: percepts in, anchors out (section 3 of the paper).

Knows nothing of Prolog or of the simulator. The main entry is :class:`AnchorManager`::

    manager = AnchorManager()                    # the shipped matching model
    result = manager.process(time, percepts)     # acquire / re-acquire / track, one frame
    manager.set_position_particles("ball-1", positions, weights)   # feedback from reasoning
    manager.get("ball-1").position.mean()
"""

from anchoring.anchor import Anchor
from anchoring.attribute import Attribute, AttributeValueError
from anchoring.features import pair_features
from anchoring.hands import HandRules, reasoning_position
from anchoring.manager import (
    Ambiguity,
    AnchorManager,
    AnchorManagerError,
    Assignment,
    FrameResult,
    Rejection,
    SymbolTable,
)
from anchoring.matcher import DEFAULT_MODEL, Matcher, MatcherError, RbfSvm, load_default_matcher
from anchoring.similarity import FEATURES
from anchoring.views import Withheld

__all__ = [
    "DEFAULT_MODEL",
    "FEATURES",
    "Ambiguity",
    "Anchor",
    "AnchorManager",
    "AnchorManagerError",
    "Assignment",
    "Attribute",
    "AttributeValueError",
    "FrameResult",
    "HandRules",
    "Matcher",
    "MatcherError",
    "RbfSvm",
    "Rejection",
    "SymbolTable",
    "Withheld",
    "load_default_matcher",
    "pair_features",
    "reasoning_position",
]
