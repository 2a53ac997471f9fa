"""Programs written for the original DC/DCPF system run unmodified.

The files in ``prolog/examples/dc/`` are written as the original's users wrote them (its header
``use_module('../distributionalclause.pl')`` or ``'../dcpf.pl'``, ``set_options/1`` and the other
option setters, ``:- initialization(...)``, test predicates that call the original's entry
points). Each is run in ``swipl`` through ``prolog/ddc/compat/dc_compat.pl``, its test predicates
print their answers, and the answers are asserted within 3 standard errors of the exact ones of
``../shared/dc-reference.md`` section 4 (fixed seeds). The same files load with ``ddc query``.
"""

from __future__ import annotations

import math
import re
import subprocess
from pathlib import Path

import pytest
from scipy import stats

from ddc_cli_helpers import ddc
from plunit_runner import ROOT, swipl_executable

DC = ROOT / "prolog" / "examples" / "dc"
COMPAT = ROOT / "prolog" / "ddc" / "compat" / "dc_compat.pl"
H10 = sum(1.0 / k for k in range(1, 11))


def run_old(program: str | Path, goal: str, seed: int = 1) -> subprocess.CompletedProcess[str]:
    """``swipl prolog/ddc/compat/dc_compat.pl FILE`` (a name in ``prolog/examples/dc`` or a path)
    with ``goal``; the seed is fixed before FILE is consulted (its initialization/1 goals run then)
    and the run must succeed."""
    path = str(DC / program).replace("'", "\\'")
    result = subprocess.run(
        [swipl_executable(), "-q", "-g", f"set_random(seed({seed})), consult('{path}'), {goal}",
         "-t", "halt", str(COMPAT)],
        cwd=ROOT, capture_output=True, text=True, timeout=300,
    )
    assert result.returncode == 0, result.stderr
    return result


def variant(tmp_path: Path, program: str, name: str, old: str, new: str) -> Path:
    """A copy of ``prolog/examples/dc/PROGRAM`` named ``name`` with one directive changed."""
    text = (DC / program).read_text()
    assert old in text
    path = tmp_path / name
    path.write_text(text.replace(old, new))
    return path


def printed(text: str, label: str) -> float:
    """The number printed after ``label`` (a line ``label N`` or a term ``label(N)``)."""
    match = re.search(re.escape(label) + r"[:( ]\s*([-0-9.eE]+)", text)
    assert match, (label, text)
    return float(match.group(1))


def binomial_se(p: float, n: float) -> float:
    return math.sqrt(p * (1.0 - p) / n)


def test_tutorial_prints_the_exact_answers() -> None:
    n = 10000
    out = run_old("tutorial.pl", f"test_coin({n}), test_color({n}), test_balls({n}), "
                                 f"test_balls2({n})").stdout
    assert printed(out, "probability coin=true") == pytest.approx(0.2)      # weighted: exact
    assert printed(out, "probability color=black") == pytest.approx(0.1)
    assert printed(out, "probability nballs=4") == pytest.approx(0.1)
    assert abs(printed(out, "probability nballs>5") - 0.5) <= 3 * binomial_se(0.5, n)
    exact = 0.7 / 3 + 0.3 / 2
    assert abs(printed(out, "probability first drawn ball is black") - exact) \
        <= 3 * binomial_se(exact, n)


def test_example1_runs_its_test_on_load_and_its_other_tests() -> None:
    n = 10000
    result = run_old("example1.pl", f"testpoisson({n}), test_random({n}), test2({n})")
    out = result.stdout
    # test(10000), run by the file's own initialization/1, prints absolute errors
    for k, label in ((1, "drawn(1) ~= 1"), (2, "drawn(1) ~= 2"), (3, "drawn(1) ~= 3")):
        exact = 0.1 * (H10 - sum(1.0 / j for j in range(1, k)))
        assert printed(out, f"Absolute error {label}") <= 3 * binomial_se(exact, n)
    assert printed(out, "Absolute error average g") <= 3 * 0.1 / math.sqrt(n)
    # test_query/6 prints the estimate and the program goes on (the original halted)
    poisson = stats.poisson.pmf(4, 4)
    assert abs(printed(out, "lw") - poisson) <= 3 * binomial_se(poisson, n)
    for label in ("n3", "n3_2"):     # n3_2 draws with the original's `X is random`
        assert abs(printed(out, label) - 0.45) <= 3 * binomial_se(0.45, n)
    assert abs(printed(out, "g<0.0") - 0.5) <= 3 * binomial_se(0.5, n)
    assert abs(printed(out, "0.0<g<0.1") - 0.341345) <= 3 * binomial_se(0.341345, n)
    assert abs(printed(out, "g<0.1 | g>0.0") - 0.68269) <= 3 * binomial_se(0.68269, n / 2)
    assert printed(out, "density g=0.0") == pytest.approx(3.98942280401433, rel=1e-9)
    # g2 = 0 is weighted by N(0; g, v) at g ~ N(0, v), v = 0.01: the mean is the N(0, 2v)
    # density, the second moment 1 / (2 pi v sqrt(3))
    v, mean = 0.01, 2.82094791773878
    sd = math.sqrt(1 / (2 * math.pi * v * math.sqrt(3)) - mean ** 2)
    assert abs(printed(out, "density g2=0.0") - mean) <= 3 * sd / math.sqrt(n)
    assert printed(out, "density g2=0.1|g=0.1") == pytest.approx(3.98942280401433, rel=1e-9)


def test_example1_with_query_propagation_is_the_original_test_pl(tmp_path: Path) -> None:
    # the original's test.pl: example1 with set_query_propagation(true), test(10000) on load
    program = variant(tmp_path, "example1.pl", "test.pl", "set_inference(backward(lw)).",
                      "set_inference(backward(lw)),set_query_propagation(true).")
    n = 10000
    result = run_old(program, "true")
    assert "set_query_propagation(true)" in result.stderr
    for k in (1, 2, 3):
        exact = 0.1 * (H10 - sum(1.0 / j for j in range(1, k)))
        error = printed(result.stdout, f"Absolute error drawn(1) ~= {k}")
        assert error <= 3 * binomial_se(exact, n)


def test_church_examples() -> None:
    n = 10000
    out = run_old("church.pl", f"test_all({n})").stdout
    for label, exact in (("coin", 0.5), ("flip", 0.5), ("trickcoin", 0.95), ("bent_coin", 0.4),
                         ("cough", 0.208)):
        assert abs(printed(out, label) - exact) <= 3 * binomial_se(exact, n) + 1e-9, label
    # weighted by the mammogram: about n * 0.103 samples' worth of information
    assert abs(printed(out, "breast_cancer") - 0.077640) <= 3 * binomial_se(0.07764, 0.103 * n)
    # eval_query_distribution/8 with evidence d >= 2 by rejection (P = 0.028)
    pairs = dict(re.findall(r"([0-9.]+):([01])", out.split("a_given_d")[1]))
    by_value = {int(v): float(p) for p, v in pairs.items()}
    assert abs(by_value[1] - 0.678571) <= 3 * binomial_se(0.678571, 0.028 * n)
    assert by_value[0] + by_value[1] == pytest.approx(1.0)


def gpa_exact(g: float) -> float:
    """P(nation = a | gpa = g), with the Jacobians of V is A*4.0 and V is A*10.0."""
    american = 0.25 * 0.95 * stats.beta.pdf(g / 4.0, 8, 2) / 4.0
    indian = 0.75 * 0.99 * stats.beta.pdf(g / 10.0, 5, 5) / 10.0
    return american / (american + indian)


def test_indian_gpa_warns_about_query_propagation_and_is_right() -> None:
    n = 10000
    result = run_old("indian_gpa.pl", f"test_gpa({n})")
    assert re.search(r"indian_gpa\.pl:13: set_query_propagation\(true\): .*Jacobian", result.stderr)
    assert result.stderr.count("set_query_propagation") == 1
    for g in (3.0, 3.9):
        p = printed(result.stdout, f"p(nation=a|student_gpa={g})")
        assert abs(p - gpa_exact(g)) <= 3 * binomial_se(gpa_exact(g), n / 4), g
    assert printed(result.stdout, "p(nation=a|student_gpa=4.0)") == pytest.approx(1.0)


def test_dcpf_wumpus_step_particle_and_eval_query_particle() -> None:
    n = 2000
    out = run_old("dcpfwumpus.pl", f"test1({n}), plotdata(1), get_loglikelihood(L), "
                                   "format('loglikelihood ~w~n', [L])").stdout
    exact = 0.4 * 0.9 / (0.4 * 0.9 + 0.6 * 0.1)
    assert abs(printed(out, "P(maze(0,1)=wall)") - exact) <= 3 * binomial_se(exact, n)
    assert "AA" in out                          # plotdata/1 found the agent in particle 1
    # P(up = wall, right = free) = 0.42 * 0.58
    assert abs(printed(out, "loglikelihood") - math.log(0.42 * 0.58)) < 0.05


def test_probabilistic_graph_and_generate_backward() -> None:
    n = 10000
    out = run_old("exampleproblog.pl", f"test({n})").stdout
    assert abs(printed(out, "p(1,4)") - 0.125) <= 3 * binomial_se(0.125, n)
    assert abs(printed(out, "p(1,5)") - 0.25) <= 3 * binomial_se(0.25, n)
    assert printed(out, "path(1,5)") == pytest.approx(1.0)
    world = out.split("one world:")[1]
    assert "e(1,6)~=true" in world and "e(6,5)~=true" in world and "$undef" not in world


def test_generatesamples_generate_backward_from_a_given_world() -> None:
    n = 2000
    out = run_old("generatesamples.pl", f"test_coin(10000), test_coin2(10000), test_prod, test, "
                                        f"test_object({n})").stdout
    assert printed(out, "probability coin=true (exact 0.5)") == pytest.approx(0.5)
    assert abs(printed(out, "probability fair coin=true (exact 0.5)") - 0.5) <= 3 * binomial_se(
        0.5, 10000)
    world = re.search(r"^\[prod~= ?([^,]+),g2~= ?([^,]+),g~= ?([^\]]+)\]$", out, re.M)
    assert world, out
    prod, g2, g = (float(v) for v in world.groups())
    assert prod == pytest.approx(g * g2)
    # the given values are in the world listed, the drawn one at time 1
    assert "object(1):0~=(0,0,0)" in out and "object(1):1~=(" in out
    means = re.search(r"mean \(([-0-9.]+),([-0-9.]+),([-0-9.]+)\), standard deviation "
                      r"\(([-0-9.]+),([-0-9.]+),([-0-9.]+)\)", out)
    assert means, out
    values = [float(v) for v in means.groups()]
    sd = 0.02
    for got, exact in zip(values[:3], (1.0, 0.0, 0.0), strict=True):
        assert abs(got - exact) <= 3 * sd / math.sqrt(n)
    for got in values[3:]:          # the sample sd's standard error is about sd / sqrt(2n)
        assert abs(got - sd) <= 3 * sd / math.sqrt(2 * n)


RECORDED_PROGRAM = """\
:- use_module('../dcpf.pl').
:- use_module('../random/sampling.pl').
:- use_module(library(lists)).
:- set_options(default).

position:0 ~ finite([1:(0,0)]) := true.
position:t+1 ~ finite([1:(X,Y)]) := position:t ~= (X0,Y), action(right), X is X0+1.
speed:0 ~ gaussian(2.0,1.0) := true.
speed:t+1 ~ gaussian(S,0.01) := speed:t ~= S.

plotdata(N) :-
\tdcpf:bb_get(offset,Offset),
\topen('DATA','write',S),
\t(
\t\tbetween(1,N,Pos),
\t\tI is Offset+Pos,
\t\trecorded(I,current(position) ~= (X,Y),_),
\t\twrite(S,X),write(S,' '),write(S,Y),nl(S),
\t\tfail;
\t\ttrue
\t),
\tclose(S).

averagespeed(N,Mean) :-
\tbb_put(sum,0.0),
\t(
\t\tbetween(1,N,I),
\t\trecorded(I,current(speed) ~= V,_),
\t\tbb_get(sum,Old), New is Old+V, bb_put(sum,New),
\t\tfail;
\t\ttrue
\t),
\tbb_delete(sum,T),
\tMean is T/N.

run(N) :-
\tinit_particle(N),
\tstep_particle([action(right)],[],N),
\tplotdata(N),
\taveragespeed(N,M),
\twrite('mean speed '),writeln(M),
\tprintp(1).
"""


def test_plot_predicates_read_particles_with_recorded_and_printp(tmp_path: Path) -> None:
    data = tmp_path / "data.txt"
    program = tmp_path / "recorded.pl"
    program.write_text(RECORDED_PROGRAM.replace("DATA", str(data)))
    n = 500
    out = run_old(program, f"run({n})").stdout
    assert data.read_text().splitlines() == ["1 0"] * n
    # speed ~ N(2, 1) at time 0, then N(S, 0.01): the mean of n particles
    assert abs(printed(out, "mean speed") - 2.0) <= 3 * math.sqrt(1.01 / n)
    assert "current(position)~=(1,0)" in out
    assert re.search(r"^current\(speed\)~= ?[-0-9.]+$", out, re.M), out


def test_forward_inference_is_accepted_with_a_warning_and_answers_the_same(tmp_path: Path) -> None:
    # the original's forwarddcpfwumpus.pl: the wumpus maze with forward inference
    forward = variant(tmp_path, "dcpfwumpus.pl", "forwarddcpfwumpus.pl",
                      ":- set_options(default).", ":- set_options(default),set_inference(false).")
    n = 2000
    result = run_old(forward, f"test1({n})")
    assert re.search(r"forwarddcpfwumpus\.pl:\d+: set_inference\(false\): forward sampling is "
                     r"not implemented", result.stderr)
    exact = 0.4 * 0.9 / (0.4 * 0.9 + 0.6 * 0.1)
    assert abs(printed(result.stdout, "P(maze(0,1)=wall)") - exact) <= 3 * binomial_se(exact, n)


def test_dcpf_pit_world_unittest() -> None:
    out = run_old("dcpfwumpus2.pl", "unittest").stdout
    n = 10000
    # five joint entries over 10,000 particles, resampled at each of four steps: allow for
    # an effective sample size of a quarter of the particles
    assert printed(out, "total absolute difference") <= 5 * 3 * binomial_se(0.5, n / 4)
    got = out.split("Got:")[1]
    marginals = {(int(x), int(y)): float(p)
                 for p, x, y in re.findall(r"([0-9.]+):\((\d),(\d)\)", got)}
    for cell, exact in (((1, 1), 0.137931), ((2, 0), 0.689655), ((0, 2), 0.689655),
                        ((0, 0), 1.0), ((1, 0), 1.0), ((0, 1), 1.0)):
        assert abs(marginals[cell] - exact) <= 3 * binomial_se(exact, n / 4) + 1e-9, cell


def tracked(out: str, label: str) -> tuple[float, float, float]:
    """The position ``X,Y,Z`` printed after ``label`` by tracking.pl's test_tracking/1."""
    line = next(ln for ln in out.splitlines() if ln.startswith(label))
    x, y, z = (float(v) for v in line.rsplit(": ", 1)[1].split(","))
    return x, y, z


def test_tracking_births_the_object_and_follows_it_with_the_kalman_proposal(
        tmp_path: Path) -> None:
    n = 1000
    program = tmp_path / "tracking.pl"      # plotdata/1 writes data.txt where it runs
    program.write_text((DC / "tracking.pl").read_text())
    path = str(program).replace("'", "\\'")
    run = subprocess.run(
        [swipl_executable(), "-q", "-g", f"set_random(seed(4)), consult('{path}'), "
         f"test_tracking({n})", "-t", "halt", str(COMPAT)],
        cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    # birth at the first observation (0.6,1,0): each coordinate ~ N(obs, varQ deltaT^2)
    var_birth = 0.005 * 0.2 ** 2
    for got, obs in zip(tracked(run.stdout, "after the first"), (0.6, 1.0, 0.0), strict=True):
        assert abs(got - obs) <= 3 * math.sqrt(var_birth / n)
    # second observation (0.7,1,0): prior N(0.6, 2 var_birth) in x, measurement variance
    # 0.001, Kalman posterior mean and variance; the particles are weighed by the
    # predictive density N(0.7; x_t, var_birth + 0.001), which costs N / N_eff =
    # E[w^2] / E[w]^2 of the sample size
    prior, r, d = 2 * var_birth, 0.001, 0.1
    mean = 0.6 + prior / (prior + r) * d
    var_post = prior * r / (prior + r)
    s = var_birth + r
    ratio = (math.sqrt(math.pi * s) * stats.norm.pdf(d, 0, math.sqrt(s / 2 + var_birth))
             / (2 * math.pi * s * stats.norm.pdf(d, 0, math.sqrt(s + var_birth)) ** 2))
    x, y, z = tracked(run.stdout, "after the second")
    assert abs(x - mean) <= 3 * math.sqrt(var_post * ratio / n), (x, mean)
    for got, obs in ((y, 1.0), (z, 0.0)):
        assert abs(got - obs) <= 3 * math.sqrt(var_birth * 2 * r / (var_birth * 2 + r) * ratio / n)
    rows = (tmp_path / "data.txt").read_text().split("\n")
    assert len([ln for ln in rows if ln.startswith("1 ")]) == n     # "ID X Y Z R G B"


@pytest.mark.parametrize(("goal", "lines"), [
    ("t2", ["anchor2 anchor2"]),                    # anchor3 arrives when an object exists
    ("t3", ["anchor1 anchor1", "anchor2 anchor2"]),  # anchor2 associated with its own object
    ("t1", ["anchor1 anchor1", "anchor2 anchor2"]),
])
def test_minimalexample_associates_anchors_with_one_particle(tmp_path: Path, goal: str,
                                                            lines: list[str]) -> None:
    """Its plotdata/1 reads the particle through the original's internals (eraseall/1,
    proof_query_backward_lazy/3) and writes one "Anchor Object" line per object."""
    program = tmp_path / "minimalexample.pl"        # plotdata/1 writes data.txt where it runs
    program.write_text((DC / "minimalexample.pl").read_text())
    path = str(program).replace("'", "\\'")
    run = subprocess.run(
        [swipl_executable(), "-q", "-g", f"consult('{path}'), {goal}", "-t", "halt", str(COMPAT)],
        cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert "[anchor2]" in run.stdout                 # writeln/1 in the association clause's body
    written = [ln for ln in (tmp_path / "data.txt").read_text().splitlines() if ln]
    assert sorted(written) == lines


@pytest.mark.parametrize(("program", "query", "evidence", "exact"), [
    ("tutorial.pl", "drawn(1) ~= X, color(X) ~= black", None, 0.7 / 3 + 0.3 / 2),
    ("example1.pl", "drawn(1) ~= 1", None, 0.1 * H10),
    ("church.pl", "cough(bob)", None, 0.208),
    ("indian_gpa.pl", "nation ~= a", "student_gpa ~= 3.0", gpa_exact(3.0)),
    ("dcpfwumpus.pl", "position:0 ~= (0,0)", None, 1.0),
    ("generatesamples.pl", "prod ~= P, P > 0", None, 0.5),
    ("tracking.pl", "deltaT(D), D =:= 0.2", None, 1.0),
    ("minimalexample.pl", "associate:0 ~= _", None, 0.0),
])
def test_the_same_files_load_with_ddc_query(program: str, query: str, evidence: str | None,
                                           exact: float) -> None:
    args = [DC / program, query, "--samples", "4000", "--seed", "3", "--json"]
    if evidence:
        args += ["--evidence", evidence]
    run = ddc("query", *args, check=True)
    p = float(re.search(r'"probability": ([-0-9.eE]+)', run.stdout).group(1))
    se = float(re.search(r'"stderr": ([-0-9.eE]+)', run.stdout).group(1))
    assert abs(p - exact) <= 3 * se + 1e-9, (p, se, exact)


def test_an_option_value_the_original_did_not_know_names_file_and_line(tmp_path: Path) -> None:
    program = tmp_path / "bad.pl"
    program.write_text(":- use_module('../distributionalclause.pl').\n"
                       ":- set_options(default), set_inference(backward(magic)).\n"
                       "coin ~ finite([0.5:true,0.5:false]).\n")
    run = ddc("query", program, "coin ~= true")
    assert run.returncode != 0
    assert f"{program}:2: unknown directive set_inference(backward(magic))" in run.stderr
