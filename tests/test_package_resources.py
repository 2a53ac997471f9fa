"""The data files the code reads (the Prolog engine and theories, world.pl, the examples, the
shipped scenarios, the trained models) are package resources, found through importlib.resources
relative to the imported packages, never through the layout of a checkout: an installed
distribution (not editable) runs from any folder.

The last test builds the wheel of this tree, installs it into a fresh virtual environment (its
dependencies reused from this one) and plays the shell game from a folder of its own.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import sysconfig
from importlib import resources
from pathlib import Path

import pytest

import bridge.resources
import probanchor.resources
from probanchor.loop.theories import DEFAULT_THEORY, THEORIES

ROOT = Path(__file__).resolve().parents[1]


def inside(path: Path, package: str, *parts: str) -> bool:
    folder = Path(resources.files(package).joinpath(*parts)).resolve()
    return path.resolve().is_relative_to(folder) and path.exists()


def test_prolog_files_are_resources_of_the_bridge() -> None:
    import bridge.prolog

    engine = bridge.resources.prolog_dir()
    assert inside(engine, "bridge", "engine")
    assert bridge.prolog.PROLOG_DIR == engine
    for name in ("ddc.pl", "too.pl", "too_learned.pl", "too_learned_hindsight.pl", "shell/world.pl",
                 "examples/filter/wumpus.pl"):
        assert inside(bridge.resources.prolog_file(name), "bridge", "engine"), name
    assert all(inside(path, "bridge", "engine") for path in THEORIES.values())
    assert DEFAULT_THEORY == THEORIES["hand"]


def test_scenarios_and_models_are_resources_of_their_packages() -> None:
    from anchoring.matcher import DEFAULT_MODEL as MATCHING
    from probanchor.perception.classifier import DEFAULT_MODEL as CLASSIFIER

    assert inside(probanchor.resources.scenario_file("shell_game"), "probanchor", "scenarios")
    assert inside(probanchor.resources.scenarios_dir() / "SCHEMA.md", "probanchor", "scenarios")
    assert inside(CLASSIFIER, "probanchor.perception", "models")
    assert inside(MATCHING, "anchoring", "models")


def test_in_the_source_tree_the_resource_folders_are_the_repository_folders() -> None:
    assert bridge.resources.prolog_dir() == (ROOT / "prolog").resolve()
    assert probanchor.resources.scenarios_dir() == (ROOT / "scenarios").resolve()


def test_no_module_finds_files_through_the_checkout_layout() -> None:
    found = [f"{path.relative_to(ROOT)}:{n}"
             for path in sorted((ROOT / "python").rglob("*.py"))
             if "engine" not in path.parts and "scenarios" not in path.parts
             for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
             if re.search(r"__file__.*(\.parents\[|\.parent\.parent)", line)]
    assert found == []


def _source_copy(to: Path) -> Path:
    """The files a wheel is built from (this tree as it is, uncommitted changes included)."""
    ignore = shutil.ignore_patterns("__pycache__", "*.egg-info", "build")
    to.mkdir()
    shutil.copy2(ROOT / "pyproject.toml", to / "pyproject.toml")
    for folder in ("python", "prolog", "scenarios"):
        shutil.copytree(ROOT / folder, to / folder, symlinks=True, ignore=ignore)
    return to


def test_an_installed_wheel_plays_a_scenario_from_another_folder(tmp_path: Path) -> None:
    source = _source_copy(tmp_path / "source")
    (tmp_path / "wheel").mkdir()
    built = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w",
                            str(tmp_path / "wheel"), str(source)],
                           capture_output=True, text=True, timeout=300, check=False)
    if built.returncode != 0 and "No matching distribution" in built.stderr:
        pytest.skip(f"no build back end to be had (offline?): {built.stderr[-300:]}")
    assert built.returncode == 0, built.stderr[-3000:]
    wheel = next((tmp_path / "wheel").glob("*.whl"))
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    site = Path(subprocess.run([str(venv / "bin" / "python"), "-c",
                                "import sysconfig; print(sysconfig.get_path('purelib'))"],
                               capture_output=True, text=True, check=True).stdout.strip())
    # the dependencies are this environment's (a plain path line: its own .pth files, among
    # them an editable install of the project, are not read)
    (site / "zz_dependencies.pth").write_text(sysconfig.get_path("purelib") + "\n")
    subprocess.run([sys.executable, "-m", "pip", "--python", str(venv / "bin" / "python"),
                    "install", "-q", "--no-deps", str(wheel)],
                   capture_output=True, text=True, timeout=300, check=True)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    shutil.copy2(ROOT / "scenarios" / "shell_game.yaml", elsewhere)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    where = subprocess.run(
        [str(venv / "bin" / "python"), "-c", "import bridge.resources, probanchor.resources; "
         "print(bridge.resources.prolog_dir()); print(probanchor.resources.scenarios_dir())"],
        cwd=elsewhere, env=env, capture_output=True, text=True, check=True).stdout.split()
    assert [Path(w).is_relative_to(site) for w in where] == [True, True], where
    run = subprocess.run([str(venv / "bin" / "anchoring"), "run", "shell_game.yaml",
                          "--particles", "50", "--quiet"],
                         cwd=elsewhere, env=env, capture_output=True, text=True, timeout=600,
                         check=False)
    assert run.returncode == 0, run.stderr[-3000:]
    assert "ID switches 0" in run.stdout, run.stdout
