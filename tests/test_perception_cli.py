"""`anchoring render` and `anchoring perceive` on a short scenario."""

from __future__ import annotations

from pathlib import Path

from probanchor.cli.anchoring_cli import main
from probanchor.percepts import read_percepts

ROOT = Path(__file__).resolve().parents[1]
STATIC = str(ROOT / "scenarios" / "static.yaml")


def test_render_writes_pngs_and_a_gif(tmp_path):
    out = tmp_path / "r"
    assert main(["render", STATIC, "--out", str(out), "--fps", "2", "--depth",
                 "--overlay"]) == 0
    assert len(list(out.glob("frame_*.png"))) == 3
    assert len(list(out.glob("depth_*.png"))) == 3
    assert len(list(out.glob("overlay_*.png"))) == 3
    assert (out / "static.gif").stat().st_size > 1000


def test_perceive_writes_a_stream_with_truth(tmp_path):
    path = tmp_path / "p.jsonl"
    assert main(["perceive", STATIC, "--out", str(path), "--fps", "2"]) == 0
    frames = list(read_percepts(path))
    assert len(frames) == 3
    for fr in frames:
        assert not fr.rejected
        assert sorted(p.truth_id for p in fr.percepts) == sorted(fr.truth["objects"])


def test_bad_scenario_is_a_clear_error(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text("objects:\n  - {id: x_1, category: spaceship, colour: red, "
                   "position: [0, 0]}\n", encoding="utf-8")
    assert main(["perceive", str(bad), "--out", str(tmp_path / "o.jsonl")]) == 1
    err = capsys.readouterr().err
    assert f"{bad}:2" in err and "unknown category 'spaceship'" in err
