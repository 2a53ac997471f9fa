"""A run's limits and promises at its end: an impossible particle count refused before it is
tried; world.pl written even when the particles cannot be read; every record's total time
recorded, the last one's too."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest

from bridge.filter import FilterError
from probanchor.cli.anchoring_cli import main as anchoring
from probanchor.loop import reasoning, world_file
from probanchor.loop.runner import MAX_PARTICLES, RunOptions, run
from scenario_helpers import scenario_file


@pytest.fixture(scope="module")
def scenario(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return scenario_file(tmp_path_factory)


def test_an_impossible_particle_count_is_refused_before_it_is_tried(
        scenario: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    made: list[int] = []
    original = reasoning.OcclusionReasoner.__init__

    def counted(self, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003
        made.append(1)
        original(self, *args, **kwargs)

    monkeypatch.setattr(reasoning.OcclusionReasoner, "__init__", counted)
    started = time.monotonic()
    with pytest.raises(ValueError, match=r"--particles 10,000,000: more than the 1,000,000 a "
                                         r"run's filter takes"):
        run(RunOptions(scenario=scenario, particles=10_000_000, progress=False,
                       out=tmp_path / "out"))
    for bad in (0, -5, 2.5, True):
        with pytest.raises(ValueError, match="not a positive whole number"):
            run(RunOptions(scenario=scenario, particles=bad, progress=False))  # type: ignore
    assert anchoring(["run", str(scenario), "--particles", str(MAX_PARTICLES + 1),
                      "--quiet"]) == 1
    assert "more than the 1,000,000" in capsys.readouterr().err
    assert made == [] and time.monotonic() - started < 30  # no filter was made
    assert not (tmp_path / "out").exists()


def test_the_world_file_is_written_when_the_particles_cannot_be_read(
        scenario: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    def overflow(loop):  # noqa: ANN001
        raise FilterError("too.pl: Stack limit (1.0Gb) exceeded")

    monkeypatch.setattr(world_file, "particle_rows", overflow)
    out = tmp_path / "out"
    output = run(RunOptions(scenario=scenario, particles=30, progress=False, out=out,
                            picture_every=1000))
    text = (out / "world.pl").read_text()
    assert "% the particles could not be read from the filter: DDCError: too.pl: Stack" \
        in text
    assert text.count("anchor(") == len(output.records[-1].hypotheses)
    assert f"world_frame({output.records[-1].frame}, " in text and "particle(" not in text


@pytest.mark.parametrize("overlap", [True, False])
def test_every_record_has_its_total_time(scenario: Path, tmp_path: Path,
                                         overlap: bool) -> None:
    out = tmp_path / "out"
    run(RunOptions(scenario=scenario, particles=30, progress=False, out=out, overlap=overlap,
                   picture_every=1000))
    totals = [json.loads(line)["timings"]["total"]
              for line in (out / "records.jsonl").read_text().splitlines()]
    assert len(totals) == 46 and all(t is not None and t > 0 for t in totals)
