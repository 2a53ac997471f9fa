"""The DDC system's errors in Python: one base class (bridge.errors.DDCError, also known as
bridge.FilterError and by its earlier name bridge.EngineError), a subclass per cause picked
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

ROOT = Path(__file__).resolve().parents[1]
PIT_WORLD = ROOT / "prolog" / "examples" / "filter" / "pit_world.pl"


def test_the_old_names_are_the_base_class() -> None:
    assert bridge.FilterError is DDCError and bridge.EngineError is DDCError
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
        assert caught.value.cause == "bad_input"
        with pytest.raises(BadArgumentError, match="query"):
            f.probability("maze(1,1):t ~=")
        with pytest.raises(DDCError, match="rename"):
            f.rename({"wall": "free"})
    with pytest.raises(UnknownObjectError, match="does not exist") as unknown:
        call_helper("bridge_time(K, T)", {"K": "no_such_filter"})
    assert unknown.value.cause == "existence_error"
    broken = tmp_path / "broken.pl"
    broken.write_text("x:0 ~ val(1).\ny:t+1 ~ gaussian(0, 1 := true.\n")
    with pytest.raises(ProgramError, match=r"broken\.pl:2"):
        Filter(broken, particles=10)


def test_static_program_and_learning_errors(tmp_path: Path) -> None:
    bad = tmp_path / "bad.pl"
    bad.write_text("coin ~ finite([0.5:true, 0.5:false]).\nx ~ val(1) := coin ~= .\n")
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
