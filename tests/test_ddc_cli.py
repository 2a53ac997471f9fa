"""The `ddc` command: `ddc filter` over JSONL frames and `ddc query`, through main(argv) and
once through the installed console script."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from probanchor.cli.ddc_cli import main

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "prolog" / "examples" / "filter"
WUMPUS = EXAMPLES / "wumpus.pl"
PIT_WORLD = EXAMPLES / "pit_world.pl"
QUERY_WALL = "maze(0,1):t ~= wall"


@pytest.mark.parametrize("engine", ["auto", "per_particle"])
def test_filter_table_prints_the_queried_probability_per_step(
    capsys: pytest.CaptureFixture[str], engine: str
) -> None:
    status = main(["filter", str(WUMPUS), str(EXAMPLES / "wumpus.jsonl"), "--particles", "800",
                   "--seed", "3", "--engine", engine,
                   "--query", QUERY_WALL, "--query", "position:t ~= (0,0)"])
    out, err = capsys.readouterr()
    assert status == 0, err
    lines = out.strip().splitlines()
    assert lines[0].split()[:5] == ["step", "time", "ess", "resampled", "loglik"]
    assert QUERY_WALL in lines[0]
    prior, after = lines[1].split(), lines[2].split()
    assert prior[0] == "0" and after[0] == "1" and after[1] == "1"
    assert float(prior[-2]) == pytest.approx(0.4, abs=5 * (0.24 / 800) ** 0.5)
    assert float(after[-2]) == pytest.approx(0.857143, abs=0.08)
    assert float(after[-1]) == 1.0  # null keeps the agent at (0,0)
    assert "1 steps, 800 particles" in err


@pytest.mark.parametrize("threads", ["1", "3"])
def test_filter_json_lines_with_structured_observations(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], threads: str
) -> None:
    frames = tmp_path / "pits.jsonl"
    lines = [
        {"actions": ["action(null)"], "observations": [{"observation": "breeze",
                                                        "value": "false"}]},
        {"actions": ["action(up)"], "observations": ["observation(breeze) ~= true"],
         "comment": "a breeze north of the start"},
        {"actions": ["action(down)"], "observations": ["observation(breeze) ~= false"]},
        {"actions": ["action(right)"], "observations": ["observation(breeze) ~= true"]},
    ]
    frames.write_text("\n".join(json.dumps(line) for line in lines) + "\n\n")
    status = main(["filter", str(PIT_WORLD), str(frames), "--particles", "1000", "--seed", "1",
                   "--threads", threads,
                   "--query", "maze(1,1):t ~= free", "--distribution", "maze(2,0):t", "--json"])
    out, err = capsys.readouterr()
    assert status == 0, err
    rows = [json.loads(line) for line in out.strip().splitlines()]
    assert [r["step"] for r in rows] == [0, 1, 2, 3, 4]
    assert [r["time"] for r in rows] == [0, 1, 2, 3, 4]
    assert rows[0]["probabilities"]["maze(1,1):t ~= free"] == pytest.approx(0.8, abs=0.07)
    assert rows[-1]["probabilities"]["maze(1,1):t ~= free"] == pytest.approx(4 / 29, abs=0.09)
    free_20 = dict((v, p) for p, v in rows[-1]["distributions"]["maze(2,0):t"])["free"]
    assert free_20 == pytest.approx(20 / 29, abs=0.1)
    assert all(r["zero_weight"] is False for r in rows)


@pytest.mark.parametrize(
    ("line", "message"),
    [
        ("{not json", "invalid JSON"),
        ('["observation(up) ~= wall"]', "must be a JSON object"),
        ('{"observation": []}', "unknown key"),
        ('{"observations": [3]}', "observations[1]"),
        ('{"observations": ["observation(up ~= wall"]}', "observations[1]: syntax error in"),
        ('{"observations": ["observation(up) ~= V"]}', "observations[1]: not ground"),
        ('{"observations": [" "]}', "observations[1]: empty term text"),
        ('{"observations": [{"observation": "up", "value": []}]}', "observations[1]: cannot use"),
        ('{"observations": [{"observation": "up"}]}', "observations[1]: an observation is"),
        ('{"actions": ["action(null)", 7]}', "actions[2]: not term text"),
        ('{"actions": "action(null)"}', "actions must be a list"),
        ('{"observations": ["observation(smell) ~= yes"], "actions": ["action(null)"]}', "smell"),
    ],
)
def test_filter_bad_line_exits_1_naming_file_and_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], line: str, message: str
) -> None:
    frames = tmp_path / "frames.jsonl"
    good = '{"observations": ["observation(up) ~= wall"], "actions": ["action(null)"]}'
    frames.write_text(good + "\n" + line + "\n")
    status = main(["filter", str(WUMPUS), str(frames), "--particles", "50"])
    _, err = capsys.readouterr()
    assert status == 1
    assert f"{frames}:2:" in err and message in err


def test_filter_bad_query_and_missing_files_exit_1(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    jsonl = str(EXAMPLES / "wumpus.jsonl")
    bad_query = ["--particles", "20", "--query", "maze(0,1):t ~="]
    assert main(["filter", str(WUMPUS), jsonl, *bad_query]) == 1
    assert "--query" in capsys.readouterr().err
    assert main(["filter", str(tmp_path / "nope.pl"), jsonl]) == 1
    assert "nope.pl: no such file" in capsys.readouterr().err
    broken = tmp_path / "broken.pl"
    broken.write_text("position:0 ~ val((0,0)).\nmaze(X, Y):0 ~ finite([0.6:free 0.4:wall]).\n")
    assert main(["filter", str(broken), jsonl, "--particles", "20"]) == 1
    assert "broken.pl:2" in capsys.readouterr().err


def test_query_prints_probability_and_json(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    program = tmp_path / "coins.pl"
    program.write_text("coin ~ finite([0.2:true, 0.8:false]).\n"
                       "second ~ finite([0.5:true, 0.5:false]).\n"
                       "both := coin ~= true, second ~= true.\n")
    n = 4000
    assert main(["query", str(program), "coin ~= true", "--samples", str(n), "--seed", "1"]) == 0
    out = capsys.readouterr().out
    assert float(out.split()[0]) == pytest.approx(0.2, abs=5 * (0.16 / n) ** 0.5)
    assert main(["query", str(program), "both", "--evidence", "second ~= true",
                 "--samples", str(n), "--seed", "2", "--json"]) == 0
    record = json.loads(capsys.readouterr().out)
    assert set(record) == {"probability", "stderr", "samples"}
    assert record["probability"] == pytest.approx(0.2, abs=5 * (0.16 / n) ** 0.5)
    assert record["samples"] == n
    assert main(["query", str(program), "coin ~="]) == 1
    assert "error" in capsys.readouterr().err


def test_installed_console_script_runs_a_filter() -> None:
    ddc = Path(sys.executable).with_name("ddc")
    assert ddc.exists(), "pyproject declares the ddc console script; make setup installs it"
    out = subprocess.run(
        [str(ddc), "filter", str(WUMPUS), str(EXAMPLES / "wumpus.jsonl"), "--particles", "300",
         "--query", QUERY_WALL, "--json"],
        capture_output=True, text=True, timeout=120, cwd=ROOT,
    )
    assert out.returncode == 0, out.stderr
    last = json.loads(out.stdout.strip().splitlines()[-1])
    assert last["time"] == 1 and 0.6 < last["probabilities"][QUERY_WALL] < 1.0


def test_the_commands_default_to_the_bridge_thread_count() -> None:
    from bridge import DEFAULT_THREADS
    from probanchor.cli.anchoring_cli import build_parser as anchoring_parser
    from probanchor.cli.ddc_cli import build_parser

    assert build_parser().parse_args(["filter", "p.pl", "o.jsonl"]).threads == DEFAULT_THREADS
    for command in (["run", "s.yaml"], ["evaluate"]):
        assert anchoring_parser().parse_args(command).threads == DEFAULT_THREADS


@pytest.mark.parametrize("engine", ["batched", "per_particle"])
def test_a_head_its_body_leaves_non_ground_is_an_error_on_both_engines(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], engine: str) -> None:
    """The batched engine used to skip such a clause silently and run to the end."""
    program = tmp_path / "flag.pl"
    program.write_text("x:t+1 ~ val(1) := true.\nflag(W):t+1 ~ val(1) := true.\n")
    frames = tmp_path / "frames.jsonl"
    frames.write_text('{"observations": [], "actions": []}\n' * 2)
    code = main(["filter", str(program), str(frames), "--engine", engine, "--particles", "10"])
    err = capsys.readouterr().err
    assert code != 0
    assert f"{program}:2: the head flag(" in err and "is not ground after its body" in err
