"""The DDC system's errors in Python: one base class (bridge.errors.DDCError, also known as
bridge.FilterError and by its earlier name bridge.DDCError), a subclass per cause picked
from the Prolog error term, the message the DDC system's (file:line where there is one)."""

from __future__ import annotations

from pathlib import Path

import pytest

import bridge
from bridge.errors import (
    BadArgumentError,
    DDCError,
    FrameFileError,
    LearningDataError,
    NotPermittedError,
    ProgramError,
    UnknownObjectError,
    error_class,
)
from bridge.filter import Filter, call_helper
from bridge.frames import read_frames
from bridge.learning import LearningData
from bridge.prolog import OUT

ROOT = Path(__file__).resolve().parents[1]
PIT_WORLD = ROOT / "prolog" / "examples" / "filter" / "pit_world.pl"


def test_the_old_names_are_the_base_class() -> None:
    assert bridge.FilterError is DDCError and bridge.DDCError is DDCError
    assert bridge.DDCError is DDCError and DDCError.__name__ == "DDCError"
    for cls in (ProgramError, LearningDataError, FrameFileError, UnknownObjectError,
                BadArgumentError, NotPermittedError):
        assert issubclass(cls, DDCError)
    assert issubclass(FrameFileError, ValueError) and issubclass(BadArgumentError, ValueError)


def test_causes_pick_the_class() -> None:
    assert error_class("ddc") is ProgramError
    assert error_class("existence_error") is UnknownObjectError
    assert error_class("instantiation_error") is BadArgumentError
    assert error_class("permission_error") is NotPermittedError
    assert error_class("resource_error") is DDCError


def test_filter_errors_by_cause(tmp_path: Path) -> None:
    with Filter(PIT_WORLD, particles=50, seed=1) as f:
        with pytest.raises(BadArgumentError, match="not ground") as caught:
            f.step(["observation(breeze) ~= X"], actions=["action(up)"])
        assert caught.value.cause == "instantiation_error"
        with pytest.raises(BadArgumentError, match="query"):
            f.probability("maze(1,1):t ~=")
        with pytest.raises(DDCError, match="rename"):
            f.rename({"wall": "free"})
    with pytest.raises(UnknownObjectError, match="does not exist") as unknown:
        call_helper("bridge_time", K="no_such_filter", T=OUT)
    assert unknown.value.cause == "existence_error"
    broken = tmp_path / "broken.pl"
    broken.write_text("x:0 ~ val(1).\ny:t+1 ~ gaussian(0, 1 := true.\n")
    with pytest.raises(BadArgumentError, match=r"broken\.pl:2: syntax error") as syntax:
        Filter(broken, particles=10)  # a file that does not parse: the reader's syntax_error
    assert syntax.value.cause == "syntax_error"
    bad = tmp_path / "bad.pl"
    bad.write_text("x:0 ~ val(1).\ny:t+1 ~ nosuch(1) := true.\n")
    with pytest.raises(ProgramError, match=r"bad\.pl:2"):
        Filter(bad, particles=10)  # a program that says something wrong: ddc(Cause, Where)


def test_static_program_and_learning_errors(tmp_path: Path) -> None:
    bad = tmp_path / "bad.pl"
    bad.write_text("coin ~ finite([0.5:true, 0.5:false]).\nx ~ val(1) := coin ~= .\n")
    with pytest.raises(BadArgumentError, match=r"bad\.pl:2: syntax error"):
        bridge.load(bad)
    bad.write_text("coin ~ finite([0.5:true, 0.5:false]).\nx ~ nosuch(1) := coin ~= true.\n")
    with pytest.raises(ProgramError, match=r"bad\.pl:2"):
        bridge.load(bad)
    data = tmp_path / "data.pl"
    data.write_text("age(ann) ~= high.\ntype(age(person, number)).\n")
    with pytest.raises(LearningDataError, match=r"data\.pl"):
        LearningData([data])


def test_frame_file_errors(tmp_path: Path) -> None:
    frames = tmp_path / "frames.jsonl"
    frames.write_text('{"observations": ["ok"]}\n{"bad": 1}\n')
    with pytest.raises(FrameFileError, match=r"frames\.jsonl:2"):
        read_frames(frames)


def test_learner_errors_arrive_by_cause_naming_file_and_line(tmp_path: Path) -> None:
    """The learner is called through the same adapter as the filter (bridge.prolog): its
    Prolog errors arrive as the DDCError subclass of their cause, the message the data's
    file:line."""
    bad = tmp_path / "bad.pl"
    bad.write_text("p(a) ~= 1.\nq(a ~= 2.\n")
    with pytest.raises(BadArgumentError, match=r"bad\.pl:2: syntax error") as syntax:
        LearningData([bad])  # (the one reader of DC files: its ISO syntax_error)
    assert syntax.value.cause == "syntax_error"
    head = ["type(y(e)).", "type(d(e)).", "rv(y(_), boolean).", "rv(d(_), continuous).",
            "learn(y(X)).", "mode(y(_), d(+)).", "d(1) ~= 0.5.", "y(1) ~= true."]
    unknown = tmp_path / "unknown.pl"
    unknown.write_text("\n".join([*head, "learn(z(X)).", ""]))
    with pytest.raises(LearningDataError, match=r"unknown\.pl:9: target z/1 has no facts"):
        LearningData([unknown])
    good = tmp_path / "good.pl"
    good.write_text("\n".join([*head, ""]))
    with LearningData([good]) as data:
        assert [t["predicate"] for t in data.targets()] == ["y"]
        with pytest.raises(UnknownObjectError, match="ddc_learn_target `z' does not exist"):
            data.root("z")
        root = data.root("y")
        assert root.y.tolist() == [0.0]
    with pytest.raises(UnknownObjectError, match="no such file"):
        LearningData([tmp_path / "missing.pl"])


def test_the_adapter_calls_named_predicates_with_data() -> None:
    """bridge.prolog.call: arguments by name and in order, OUT for outputs; a failing goal is
    the base class naming the predicate; anything but a module-qualified name is refused."""
    from bridge import prolog

    assert prolog.call("lists:sum_list", Xs=[1, 2, 3.5], S=OUT)["S"] == 6.5
    with pytest.raises(DDCError, match="lists:member/2 failed") as failed:
        prolog.call("lists:member", X=4, L=[1, 2])
    assert type(failed.value) is DDCError
    with pytest.raises(BadArgumentError) as bad:
        prolog.call("error:must_be", T="positive_integer", X=-1)
    assert bad.value.cause == "type_error"
    for name in ("sum_list", "lists:sum_list(X)", "lists:sum_list, halt"):
        with pytest.raises(ValueError, match="module-qualified"):
            prolog.call(name, S=OUT)
    with pytest.raises(ValueError, match="variable"):
        prolog.call("lists:sum_list", xs=[1], S=OUT)
