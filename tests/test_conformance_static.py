"""Conformance of the DDC system with the original DC system's static examples.

The programs in ``prolog/examples/`` restate, in our own words, the original's tutorial,
example1, church-dc, indian-gpa and probabilistic-graph examples (see
``../shared/dc-reference.md`` section 4) and the paper's section 2.2 example. Each answer is
asserted within 5 standard errors of the estimate (the engine's own delta-method standard
error, plus that of the independent simulation where there is one), with fixed seeds.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy import stats

from bridge import load

EXAMPLES = Path(__file__).resolve().parents[1] / "prolog" / "examples"
H10 = sum(1.0 / k for k in range(1, 11))


def assert_close(result, exact: float, extra_se: float = 0.0) -> None:
    tolerance = 5.0 * (result.stderr + extra_se) + 1e-9
    assert abs(result.probability - exact) <= tolerance, (result, exact, tolerance)


@pytest.fixture(scope="module")
def tutorial():
    return load(EXAMPLES / "tutorial.pl")


@pytest.mark.parametrize(
    ("query", "exact"),
    [
        ("coin ~= true", 0.2),
        ("color ~= black", 0.1),
        ("nballs ~= 4", 0.1),
        ("nballs ~= N, N > 5", 0.5),
        ("drawn(1) ~= X, color(X) ~= black", 0.7 / 3 + 0.3 / 2),
    ],
)
def test_tutorial(tutorial, query: str, exact: float) -> None:
    assert_close(tutorial.query(query, samples=4000, seed=1), exact)


@pytest.fixture(scope="module")
def example1():
    return load(EXAMPLES / "example1.pl")


@pytest.mark.parametrize(
    ("query", "evidence", "exact"),
    [
        ("drawn(1) ~= 1", None, 0.1 * H10),
        ("drawn(1) ~= 2", None, 0.1 * (H10 - 1)),
        ("drawn(1) ~= 3", None, 0.1 * (H10 - 1.5)),
        ("g ~= A, A < 0", None, 0.5),
        ("g ~= A, A > 0, A < 0.1", None, stats.norm.cdf(1) - 0.5),
        ("g ~= A, A < 0.1", "g ~= B, B > 0", (stats.norm.cdf(1) - 0.5) / 0.5),
        ("n3 ~= 4", None, math.exp(-4) * 4**4 / 24),
        ("n3", None, 0.9 * 0.5),
        ("n3_1", None, 0.9 * 0.5),
    ],
)
def test_example1_probabilities(example1, query, evidence, exact) -> None:
    assert_close(example1.query(query, evidence=evidence, samples=6000, seed=2), exact)


def test_example1_expectation_of_g(example1) -> None:
    result = example1.expectation("X", "g ~= X", samples=6000, seed=3)
    assert_close(result, 0.0)


@pytest.mark.parametrize(
    ("query", "evidence", "exact"),
    [
        # a ground query value of a continuous variable gives its density
        ("g ~= 0.0", None, stats.norm.pdf(0.0, 0.0, math.sqrt(0.01))),
        ("g2 ~= 0.0", None, stats.norm.pdf(0.0, 0.0, math.sqrt(0.02))),
        ("g2 ~= 0.1", "g ~= 0.1", stats.norm.pdf(0.1, 0.1, math.sqrt(0.01))),
    ],
)
def test_example1_densities(example1, query, evidence, exact) -> None:
    result = example1.query(query, evidence=evidence, samples=6000, seed=4)
    assert_close(result, exact)
    assert math.isclose(exact, {"g ~= 0.0": 3.98942280401433, "g2 ~= 0.0": 2.82094791773878,
                                "g2 ~= 0.1": 3.98942280401433}[query], rel_tol=1e-9)


@pytest.fixture(scope="module")
def church():
    return load(EXAMPLES / "church.pl")


@pytest.mark.parametrize(
    ("query", "evidence", "exact"),
    [
        ("coin ~= true", None, 0.5),
        ("true(0.5)", None, 0.5),
        ("trickcoin ~= h", None, 0.95),
        ("bent-coin ~= h", None, 0.4),
        ("cough(bob)", None, 1 - 0.99 * 0.8),
        ("breast_cancer ~= true", "positive_mammogram ~= true", 0.008 / (0.008 + 0.99 * 0.096)),
        ("a ~= 1", "d ~= D, D >= 2", 0.678571),
        ("a ~= 0", "d ~= D, D >= 2", 0.321429),
    ],
)
def test_church(church, query, evidence, exact) -> None:
    assert_close(church.query(query, evidence=evidence, samples=6000, seed=5), exact)


def test_church_conditional_distribution(church) -> None:
    dist = dict((v, p) for p, v in church.distribution("A", "a ~= A", evidence="d ~= D, D >= 2",
                                                        samples=6000, seed=6))
    assert set(dist) == {"0", "1"}
    assert abs(dist["1"] - 0.678571) < 0.05


def medical_exact() -> dict[tuple[int, int], float]:
    """Noisy-or diagnosis with all four symptoms observed, by enumeration."""
    prior = {"lc": 0.01, "tb": 0.005, "cold": 0.2, "sf": 0.1, "other": 0.1}
    symptoms = [
        {"cold": 0.5, "lc": 0.3, "tb": 0.7, "other": 0.01},
        {"cold": 0.3, "sf": 0.5, "tb": 0.2, "other": 0.01},
        {"lc": 0.4, "tb": 0.5, "other": 0.01},
        {"lc": 0.4, "tb": 0.5, "other": 0.01},
    ]
    joint: dict[tuple[int, int], float] = {}
    for bits in np.ndindex(*(2,) * 5):
        d = dict(zip(prior, bits, strict=True))
        p = math.prod(prior[k] if b else 1 - prior[k] for k, b in d.items())
        for s in symptoms:
            p *= 1 - math.prod(1 - w for c, w in s.items() if d[c])
        joint[(d["lc"], d["tb"])] = joint.get((d["lc"], d["tb"]), 0.0) + p
    z = sum(joint.values())
    return {k: v / z for k, v in joint.items()}


def test_church_medical_noisy_or(church) -> None:
    exact = medical_exact()
    assert math.isclose(exact[(1, 0)] + exact[(1, 1)], 0.263076, abs_tol=1e-6)
    assert math.isclose(exact[(1, 1)], 0.016014, abs_tol=1e-6)
    # all four symptoms together have probability 3.6e-4: rejection needs many samples
    result = church.query("lung_cancer", evidence="cough, fever, chest_pain, shortness_of_breath",
                          samples=250_000, seed=7)
    assert result.ess > 40
    assert_close(result, exact[(1, 0)] + exact[(1, 1)])


@pytest.fixture(scope="module")
def gpa():
    return load(EXAMPLES / "indian_gpa.pl")


def gpa_exact(g: float) -> float:
    """P(nation = a | gpa = g) for 0 < g < 4, with the change-of-variable Jacobians."""
    american = 0.25 * 0.95 * stats.beta.pdf(g / 4.0, 8, 2) / 4.0
    indian = 0.75 * 0.99 * stats.beta.pdf(g / 10.0, 5, 5) / 10.0
    return american / (american + indian)


def gpa_original(g: float) -> float:
    """The original system's answer: the same without the Jacobians 1/4 and 1/10."""
    american = 0.25 * 0.95 * stats.beta.pdf(g / 4.0, 8, 2)
    indian = 0.75 * 0.99 * stats.beta.pdf(g / 10.0, 5, 5)
    return american / (american + indian)


@pytest.mark.parametrize("g", [3.0, 3.9])
def test_indian_gpa_with_jacobian(gpa, g: float) -> None:
    # the original's numbers (file comments) are the no-Jacobian formula ...
    assert math.isclose(gpa_original(3.0), 0.3854718517966607, rel_tol=1e-5)
    assert math.isclose(gpa_original(3.9), 0.1928808855689747, rel_tol=1e-5)
    # ... we assert the correct ones, which differ
    result = gpa.query("nation ~= a", evidence=f"student_gpa ~= {g}", samples=6000, seed=8)
    assert_close(result, gpa_exact(g))
    assert abs(result.probability - gpa_original(g)) > 10 * result.stderr


def test_indian_gpa_point_mass(gpa) -> None:
    # gpa = 4 is a point mass of the American scale: it beats any density
    result = gpa.query("nation ~= a", evidence="student_gpa ~= 4.0", samples=3000, seed=9)
    assert result.probability == pytest.approx(1.0, abs=1e-12)


@pytest.fixture(scope="module")
def graph():
    return load(EXAMPLES / "graph.pl")


@pytest.mark.parametrize(("query", "exact"), [("p(1,4)", 0.125), ("p(1,5)", 0.25),
                                               ("p(1,3)", 0.25), ("path(1,5)", 1.0)])
def test_probabilistic_graph(graph, query: str, exact: float) -> None:
    assert_close(graph.query(query, samples=4000, seed=10), exact)


def simulate_paper_example(t: int, threshold: float, n: int = 1_000_000) -> tuple[float, float]:
    """numpy simulation of P(left(1,2):t ~= true, pos(1):t > threshold) (paper, section 2.2)."""
    rng = np.random.default_rng(12345)
    count = rng.poisson(6, n)
    p1 = rng.uniform(0, 100, n)
    p2 = rng.uniform(0, 100, n)
    for _ in range(t):
        p1 = p1 + 3 + rng.normal(0, 1, n)
        p2 = p2 + 3 + rng.normal(0, 1, n)
    hit = (count >= 2) & (p1 < p2) & (p1 > threshold)
    values = np.where(hit, 0.99, 0.0)
    return float(values.mean()), float(values.std() / math.sqrt(n))


@pytest.mark.parametrize(("t", "threshold"), [(0, 0.0), (2, 0.0), (2, 50.0)])
def test_paper_example(t: int, threshold: float) -> None:
    program = load(EXAMPLES / "paper_objects.pl")
    exact, se = simulate_paper_example(t, threshold)
    result = program.query(f"left(1,2):{t} ~= true, pos(1):{t} > {threshold}",
                           samples=4000, seed=11)
    assert_close(result, exact, extra_se=se)
