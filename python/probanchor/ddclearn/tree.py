"""The learned tree of one target: the record the search builds and the plot draws.

A distributional logic tree (paper, section 4): each internal node tests one body literal and
has one branch per outcome (a value of a discrete attribute, "defined" for a continuous one or
a relation that holds, and always a last branch where the literal is undefined or does not
hold); each leaf holds the distribution of the head and the statistical model that gives its
parameters. The path from the root to a leaf, read as a conjunction, is the body of one clause.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class Branch:
    """One outcome of a node's test and the subtree below it.

    ``label`` is the branch's literal in DC syntax as it appears in the clause body
    (``observed(A):t+1``, ``\\+ distance(A,O):t ~= _``, ``colour(A) ~= red``).
    """

    label: str
    child: TreeNode


@dataclass
class TreeNode:
    """A node of the tree: internal (``test`` and ``branches``) or a leaf (``distribution``).

    ``rows`` is the number of groundings (substitutions of the head, one per example unless
    probabilistic facts split an example into weighted partial worlds) that reach the node,
    ``weight`` their total weight (the number of examples when every fact is certain).
    """

    rows: int
    weight: float
    test: str | None = None
    branches: list[Branch] = field(default_factory=list)
    distribution: str | None = None
    model: str | None = None
    log_likelihood: float | None = None
    inherited: bool = False

    @property
    def is_leaf(self) -> bool:
        return not self.branches

    def leaves(self) -> list[TreeNode]:
        """The leaves, left to right (the order of the clauses)."""
        if self.is_leaf:
            return [self]
        return [leaf for b in self.branches for leaf in b.child.leaves()]

    def depth(self) -> int:
        return 0 if self.is_leaf else 1 + max(b.child.depth() for b in self.branches)


@dataclass
class Tree:
    """The tree learned for one target, e.g. ``occluded_by(A,O):t+1``."""

    target: str
    root: TreeNode
