"""Test files of facts only (DreaML's held-out files): ``ddc evaluate`` reads them as the program's
training data were read.

DreaML keeps its declarative bias in the training file; its held-out files hold facts only, and a
file without declarations is read in the project's own dialect, where ``loanStatus(l1, a)`` is an
atom, not the value of ``loanStatus(l1)``. A learned program records the dialect, files, targets
and declarations of its data (``learned_from/4``), so that such files are read in the training
data's dialect; ``--bias TRAIN.pl`` gives the declarations of any program; without either, the
error names the cause and the option. The held-out split is FinancialData.pl split by district
(``ddc split``), its test part stripped of everything but facts, as DreaML's own held-out files
are; and the same in the project's own dialect, whose Boolean target is given as atoms with
``examples/2``.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

import bridge
from bridge import DDCError
from bridge.learning import split_files
from ddc_cli_helpers import ddc
from probanchor.ddclearn import evaluate, learn
from probanchor.ddclearn.datasets import financial
from probanchor.ddclearn.search import SearchOptions

sys.path.insert(0, str(Path(__file__).resolve().parent))

from test_learn_cli import occlusion_data  # noqa: E402

TARGETS = ["loanStatus", "age"]
#: A line of FinancialData.pl that is a fact (not a declaration, a rule or a directive).
_FACT = re.compile(r"^[a-z][A-Za-z0-9_]*\([^:]*\)\.\s*$")
_DECLARATIONS = ("base(", "thres(", "mode(", "learn(", "rank(", "randomVariableNames(")


def facts_only(src: Path, dst: Path, drop_true: bool = False) -> Path:
    """The facts of a DreaML file, as DreaML's held-out files hold them (``drop_true``: a
    relation's facts without their ``true``, as its PKDD fold files write them)."""
    lines = [ln for ln in src.read_text().splitlines()
             if _FACT.match(ln) and not ln.startswith(_DECLARATIONS)]
    if drop_true:
        lines = [re.sub(r", true\)\.$", ").", ln) for ln in lines]
    dst.write_text("\n".join(lines) + "\n")
    return dst


@pytest.fixture(scope="module")
def split(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    d = tmp_path_factory.mktemp("dialect")
    train, test = d / "train.pl", d / "test.pl"
    split_files([financial()], train, test, fraction=0.2, seed=0, unit="d")
    result = learn([train], TARGETS, seed=0, options=SearchOptions(root_model="never"))
    program = result.write(d / "learned.pl")
    text = program.read_text()
    bare = d / "learned_without_record.pl"
    bare.write_text(re.sub(r"learned_from\(.*?\]\)\.\n", "", text, flags=re.S))
    return {"train": train, "test": test, "facts": facts_only(test, d / "test_facts.pl"),
            "program": program, "bare": bare, "folder": d}


def _same(a: dict, b: dict) -> None:
    assert a.keys() == b.keys()
    for k in a:
        assert a[k]["n"] == b[k]["n"] > 0, k
        assert a[k]["mean_log_likelihood"] == pytest.approx(b[k]["mean_log_likelihood"],
                                                            rel=1e-9), k


def test_the_program_records_its_data(split: dict[str, Path]) -> None:
    text = split["program"].read_text()
    m = re.search(r"^learned_from\(dreaml, \['[^']*train\.pl'\],\n\s+\[loanStatus\(_\), age\(_\)\]",
                  text, flags=re.M)
    assert m, text[:2000]
    for decl in ("base(loanStatus(l, ls))", "thres(loanStatus, 2, discrete, [a, b, c, d])",
                 "randomVariableNames(["):
        assert decl in text
    assert "mode(" not in text.split("learned_from(")[1].split("]).")[0]
    # an ordinary clause of the program: the engine loads it
    bridge.load(str(split["program"]))


def test_facts_only_are_read_in_the_training_data_dialect(split: dict[str, Path]) -> None:
    with_bias = evaluate(split["program"], [split["test"]])
    facts = evaluate(split["program"], [split["facts"]])
    assert set(with_bias) == {"loanStatus", "age"}
    _same(facts, with_bias)


def test_relations_without_true_as_in_the_pkdd_folds(split: dict[str, Path]) -> None:
    folds = facts_only(split["test"], split["folder"] / "fold.pl", drop_true=True)
    assert "hasLoan(" in folds.read_text() and ", true)." not in folds.read_text()
    _same(evaluate(split["program"], [folds]), evaluate(split["program"], [split["test"]]))


def test_without_a_record_the_error_says_which_file_to_pass(split: dict[str, Path]) -> None:
    with pytest.raises(DDCError) as info:
        evaluate(split["bare"], [split["facts"]])
    msg = str(info.value)
    assert str(split["facts"]) in msg
    assert "no declarations" in msg and "--bias TRAIN.pl" in msg
    assert "loanStatus(_)" in msg and "loanStatus/2" in msg     # what it found instead
    with pytest.raises(DDCError, match="--bias TRAIN.pl"):
        evaluate(split["bare"], [split["facts"]], ["loanStatus"])


def test_bias_gives_the_declarations(split: dict[str, Path]) -> None:
    _same(evaluate(split["bare"], [split["facts"]], bias=[split["train"]]),
          evaluate(split["program"], [split["test"]]))


def test_the_command_line(split: dict[str, Path]) -> None:
    run = ddc("evaluate", split["bare"], split["facts"], check=False)
    assert run.returncode != 0 and "--bias TRAIN.pl" in run.stderr
    run = ddc("evaluate", split["bare"], split["facts"], "--bias", split["train"], check=True)
    assert "loanStatus" in run.stdout and "age" in run.stdout
    run = ddc("evaluate", split["bare"], split["facts"], "--bias",
              split["folder"] / "missing.pl", check=False)
    assert run.returncode != 0 and "missing.pl: no such file" in run.stderr


def test_own_dialect_targets_given_as_atoms(tmp_path: Path) -> None:
    """A Boolean target given as atoms with examples/2: a test file of facts only scores as the
    same file with its declarations (before the record, none of its atoms was a grounding)."""
    train = occlusion_data(tmp_path / "train.pl", 400, seed=1)
    test = occlusion_data(tmp_path / "test.pl", 200, seed=2)
    facts = tmp_path / "facts.pl"
    facts.write_text("\n".join(ln for ln in test.read_text().splitlines()
                               if not ln.startswith(("type(", "rv(", "learn(", "examples(",
                                                     "mode("))) + "\n")
    program = learn([train], seed=0).write(tmp_path / "learned.pl")
    assert "examples(occluder(A, B):t+1, pair(A, B))" in program.read_text()
    _same(evaluate(program, [facts]), evaluate(program, [test]))
