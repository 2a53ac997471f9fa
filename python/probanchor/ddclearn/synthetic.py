"""Learning data sampled from a DC program with the project's own DDC system.

A *generator* is an ordinary DC program that defines the features' priors and the target's
clauses, e.g. (``tests/data/learn/discrete_tree.pl``)::

    a(X) ~ finite([0.5:p, 0.5:q]).
    y(X) ~ finite([0.9:t, 0.1:f]) := a(X) ~= p, b(X) ~= r.
    ...

:func:`sample_data` draws ONE world of it (``bridge.Program.sample``, the DDC system's backward
sampler) over ``entities`` entities and writes the facts that world holds as a data file of the
learner's own dialect (``docs/learning.md``), followed by the declarative bias::

    text = sample_data("gen.pl", ["a(I) ~= A", "b(I) ~= B", "y(I) ~= Y"], entities=1000,
                       seed=1, bias="rv(a(_), discrete([p, q])).\\n...")
    Path("train.pl").write_text(text)

Entity ``k`` (1 <= k <= entities) binds each variable of ``names`` to an atom, the prefix
followed by k (``names={"I": "e"}``: ``e1``, ``e2``, ...; ``{"A": "a", "O": "o"}`` makes the
pair ``(a1, o1)``). Each fact template is a DC literal proven in the world for each entity: a
random variable read (``a(I) ~= A`` writes ``a(e1) ~= p.``), a derived atom (``link(I, J)``
writes one fact per solution, ``observed(A):t+1`` one if it holds), each optionally under a
condition given as ``(fact, condition)`` (``("v(J) ~= V", "link(I, J)")``: the value of each
neighbour). Every template reads the same world, so the facts are one joint sample of the
program; the same seed gives the same file.

Because the target's clauses of the generator read only the facts, ``probanchor.ddclearn.evaluate``
scores the generator itself on held-out data sampled with another seed: the log-likelihood of the
generating program, which no learned program beats (on average).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import bridge

__all__ = ["sample_data", "sample_facts"]

Template = str | tuple[str, str]

_NAME = re.compile(r"^[A-Z][A-Za-z0-9_]*$")
_PREFIX = re.compile(r"^[a-z][A-Za-z0-9_]*$")


def _goal(facts: Sequence[Template], entities: int, names: Mapping[str, str]) -> str:
    if not facts:
        raise ValueError("no fact templates")
    if isinstance(entities, bool) or not isinstance(entities, int) or entities < 1:
        raise ValueError(f"entities must be a positive integer, got {entities!r}")
    if not names:
        raise ValueError("names must name at least one entity variable")
    binds = []
    for var, prefix in names.items():
        if not _NAME.match(var) or var.startswith("Ddc_"):
            raise ValueError(f"bad entity variable {var!r}")
        if not _PREFIX.match(prefix):
            raise ValueError(f"bad entity prefix {prefix!r} (a lower-case Prolog atom)")
        binds.append(f"atom_concat({prefix}, Ddc_K, {var})")
    alternatives = []
    for t in facts:
        fact, condition = (t, None) if isinstance(t, str) else t
        proof = f"({fact})" if condition is None else f"({condition}), ({fact})"
        alternatives.append(f"Ddc_F = ({fact}), {proof}")
    return (f"between(1, {entities}, Ddc_K), {', '.join(binds)}, ("
            + " ; ".join(alternatives) + ")")


def sample_facts(
    program: str | Path | bridge.Program,
    facts: Sequence[Template],
    entities: int,
    seed: int,
    names: Mapping[str, str] | None = None,
) -> list[str]:
    """The facts of one sampled world, as Prolog term texts (``a(e1)~=p``), entity by entity.

    Parameters are those of :func:`sample_data`. Raises ``bridge.DDCError`` when the program
    does not load or a template does not parse or fails with an error.
    """
    prog = program if isinstance(program, bridge.Program) else bridge.load(program)
    goal = _goal(facts, entities, names or {"I": "e"})
    return prog.sample("Ddc_F", goal, seed)


def sample_data(
    program: str | Path | bridge.Program,
    facts: Sequence[Template],
    entities: int,
    seed: int,
    bias: str = "",
    names: Mapping[str, str] | None = None,
) -> str:
    """A learning data file (own dialect) sampled from the generator ``program``.

    Parameters
    ----------
    program : path or bridge.Program
        The generator: a DC program defining the features' priors and the target's clauses.
    facts : sequence of str or (str, str)
        Fact templates, proven for each entity in the sampled world: a DC literal (``a(I) ~=
        A``, ``link(I, J)``, ``observed(A):t+1``), or ``(literal, condition)`` with a DC goal
        proven first (``("v(J) ~= V", "link(I, J)")``). Each solution is one fact.
    entities : int
        The number of entities k = 1..entities.
    seed : int
        Seeds the world (the same seed, the same data).
    bias : str, default=""
        Declarations appended after the facts (``type/1``, ``rv/2``, ``mode/2,3``, ``learn/1``,
        ``examples/2``), one per line.
    names : mapping, default {"I": "e"}
        Entity variable -> name prefix: entity k binds the variable to ``<prefix>k``.

    Returns
    -------
    str
        The data file's text: a header comment, one fact per line, the bias.
    """
    path = program.path if isinstance(program, bridge.Program) else Path(program)
    lines = sample_facts(program, facts, entities, seed, names)
    header = [
        f"% Sampled from {path.name} by ddclearn.synthetic.sample_data: {entities} entities,",
        f"% seed {seed}, {len(lines)} facts (one world of the program).",
    ]
    out = header + [f"{fact}." for fact in lines]
    if bias.strip():
        out += ["", "% Declarative bias."] + [b.strip() for b in bias.strip().splitlines()]
    return "\n".join(out) + "\n"
