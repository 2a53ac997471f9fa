"""DC programs seen from Python: load a program, ask it for probabilities.

Example::

    from bridge import load
    program = load("prolog/examples/tutorial.pl")
    result = program.query("drawn(1) ~= X, color(X) ~= black", samples=10000, seed=1)
    result.probability, result.stderr, result.ess   # ~0.3833, its standard error, its ESS

Queries and evidence are Prolog text in the DC syntax (``coin ~= true``,
``(g ~= A, A > 0)``, ``pos(1):3 > 0``). Every error of the DDC system (a bad program file, an
unknown distribution, invalid parameters, impossible evidence, a query that does not parse)
raises :class:`DDCError` whose message is the DDC system's, naming file:line and the cause.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from pathlib import Path

from bridge import prolog
from bridge.errors import DDCError
from bridge.prolog import OUT

DDC_FILE: Path = prolog.PROLOG_DIR / "ddc.pl"
DEFAULT_SAMPLES = 10_000

_lock = threading.Lock()



@dataclass(frozen=True)
class QueryResult:
    """A probability estimated by likelihood weighting.

    ``stderr`` is the standard error of the self-normalised estimate, ``ess`` the effective
    sample size (sum w)^2 / sum w^2 of the samples that count, ``samples`` the number drawn.
    """

    probability: float
    stderr: float
    ess: float
    samples: int


def _load_ddc() -> None:
    prolog.ensure_loaded(DDC_FILE)


def _call(predicate: str, **arguments: object) -> dict[str, object]:
    """Call the DDC system's ``predicate`` once through :func:`bridge.prolog.call` (one static
    call at a time, from any thread); a Prolog error, loading the DDC system's included, is a
    :class:`DDCError` (the subclass of its cause)."""
    _load_ddc()
    with _lock:
        return prolog.call(predicate, **arguments)


@dataclass(frozen=True)
class Program:
    """A DC program compiled into its own Prolog module (named by its absolute path)."""

    path: Path
    module: str

    def query(
        self,
        query: str,
        evidence: str | None = None,
        samples: int = DEFAULT_SAMPLES,
        seed: int | None = None,
    ) -> QueryResult:
        """P(query | evidence) from ``samples`` sampled worlds (same seed, same answer)."""
        if samples < 1:
            raise ValueError("samples must be positive")
        result = _call("ddc:ddc_query_text", M=self.module, Q=query, E=evidence or "",
                       N=int(samples), S="none" if seed is None else int(seed), R=OUT)
        probability, stderr, ess, n = result["R"]  # type: ignore[misc]
        return QueryResult(float(probability), float(stderr), float(ess), int(n))

    def expectation(
        self,
        value: str,
        query: str,
        evidence: str | None = None,
        samples: int = DEFAULT_SAMPLES,
        seed: int | None = None,
    ) -> QueryResult:
        """E[value | evidence, query]; ``value`` shares variables with ``query``.

        The estimate is in ``probability`` (the field name is shared with :meth:`query`).
        """
        result = _call("ddc:ddc_expectation_text", M=self.module, X=value, Q=query,
                       E=evidence or "", N=int(samples), S="none" if seed is None else int(seed),
                       R=OUT)
        mean, stderr, ess, n = result["R"]  # type: ignore[misc]
        return QueryResult(float(mean), float(stderr), float(ess), int(n))

    def distribution(
        self,
        value: str,
        query: str,
        evidence: str | None = None,
        samples: int = DEFAULT_SAMPLES,
        seed: int | None = None,
    ) -> list[tuple[float, str]]:
        """[(p, value as Prolog text), ...]: the distribution of ``value`` given the query."""
        result = _call("ddc:ddc_distribution_text", M=self.module, X=value, Q=query,
                       E=evidence or "", N=int(samples), S="none" if seed is None else int(seed),
                       R=OUT)
        return [(float(p), str(v)) for p, v in result["R"]]  # type: ignore[union-attr]

    def sample(self, template: str, goal: str, seed: int) -> list[str]:
        """The solutions of ``findall(template, goal, L)`` in ONE sampled world of the program.

        ``goal`` is a DC goal (``between(1, 100, I), a(I) ~= A, y(I) ~= Y``) read together with
        ``template`` (``I-A-Y``): they share variables. Every random variable the goal reads is
        drawn once in the world (by the DDC system's backward sampler, ``ddc_sample_world/4``), so
        the solutions are one joint sample of the program; the same seed gives the same world.
        Each solution is returned as Prolog term text (``term_string/2``: atoms quoted when
        needed, floats in full precision), e.g. ``"1-p-0.25"``.
        """
        result = _call("ddc:ddc_sample_text", M=self.module, TT=template, GT=goal,
                       S=int(seed), L=OUT)
        return [str(s) for s in result["L"]]  # type: ignore[union-attr]

    def reload(self) -> Program:
        """Compile the file again (the previous program stays if the new text has an error)."""
        return load(self.path)


def load(path: str | Path) -> Program:
    """Compile the DC program at ``path`` into its own module and return its handle."""
    resolved = Path(path).resolve()
    if not resolved.exists():
        raise DDCError(f"{resolved}: no such file")
    result = _call("ddc:ddc_load", F=str(resolved), M=OUT)
    return Program(resolved, str(result["M"]))
