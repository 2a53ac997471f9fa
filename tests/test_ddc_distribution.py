"""The DDC system stands on its own: the distribution's own requirements (no extra) are the
system's (janus, numpy, scipy, scikit-learn), and a wheel of this tree installed into a fresh
virtual environment that holds only those (and what they require) answers ``ddc query``,
``ddc filter`` and ``ddc learn`` while pybullet and open3d cannot be imported.

The fresh environment gets no download: its dependencies are this environment's installed
distributions, only those the wheel requires, linked into a folder of their own.
"""

from __future__ import annotations

import importlib.metadata as metadata
import os
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

from test_package_resources import _source_copy

ROOT = Path(__file__).resolve().parents[1]
DDC_REQUIREMENTS = {"janus-swi", "numpy", "scipy", "scikit-learn", "threadpoolctl"}
APPLICATION_ONLY = ("pybullet", "open3d", "cv2", "rosbags", "matplotlib", "yaml")


def base_requirements(lines: list[str]) -> set[str]:
    """The names of the requirements without an extra (what ``pip install`` alone brings)."""
    return {canonicalize_name(r.name) for r in map(Requirement, lines)
            if not r.marker or r.marker.evaluate({"extra": ""})}


def test_the_distribution_requires_only_the_ddc_systems_dependencies() -> None:
    with (ROOT / "pyproject.toml").open("rb") as handle:
        project = tomllib.load(handle)["project"]
    assert base_requirements(project["dependencies"]) == DDC_REQUIREMENTS
    assert "app" in project["optional-dependencies"]


def closure(names: set[str]) -> dict[str, metadata.Distribution]:
    """The installed distributions ``names`` require, transitively (no extras), by name."""
    found: dict[str, metadata.Distribution] = {}
    todo = list(names)
    while todo:
        name = canonicalize_name(todo.pop())
        if name not in found:
            found[name] = metadata.distribution(name)
            todo += base_requirements(found[name].requires or [])
    return found


def link_distributions(distributions: dict[str, metadata.Distribution], folder: Path) -> None:
    """A site folder holding just these distributions (links to their installed files)."""
    folder.mkdir()
    for dist in distributions.values():
        for top in {f.parts[0] for f in dist.files or []} - {"..", "__pycache__"}:
            source = Path(str(dist.locate_file(top)))
            if source.exists() and not (folder / top).exists():
                (folder / top).symlink_to(source)


def test_the_ddc_system_alone_in_a_fresh_environment(tmp_path: Path) -> None:
    source = _source_copy(tmp_path / "source")
    built = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w",
                            str(tmp_path / "wheel"), str(source)],
                           capture_output=True, text=True, timeout=300, check=False)
    if built.returncode != 0 and "No matching distribution" in built.stderr:
        pytest.skip(f"no build back end to be had (offline?): {built.stderr[-300:]}")
    assert built.returncode == 0, built.stderr[-3000:]
    wheel = next((tmp_path / "wheel").glob("*.whl"))
    with zipfile.ZipFile(wheel) as archive:
        meta = next(n for n in archive.namelist() if n.endswith(".dist-info/METADATA"))
        requires = [line.split(":", 1)[1].strip()
                    for line in archive.read(meta).decode().splitlines()
                    if line.startswith("Requires-Dist:")]
    wanted = base_requirements(requires)
    assert wanted == DDC_REQUIREMENTS
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    python = venv / "bin" / "python"
    site = Path(subprocess.run([str(python), "-c",
                                "import sysconfig; print(sysconfig.get_path('purelib'))"],
                               capture_output=True, text=True, check=True).stdout.strip())
    link_distributions(closure(wanted), tmp_path / "dependencies")
    (site / "zz_dependencies.pth").write_text(str(tmp_path / "dependencies") + "\n")
    subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "-q",
                    "--no-deps", str(wheel)],
                   capture_output=True, text=True, timeout=300, check=True)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    work = tmp_path / "elsewhere"
    work.mkdir()

    def run(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(list(args), cwd=work, env=env, capture_output=True, text=True,
                              timeout=600, check=False)

    for module in APPLICATION_ONLY:
        assert run(str(python), "-c", f"import {module}").returncode != 0, module
    examples = ROOT / "prolog" / "examples"
    ddc = str(venv / "bin" / "ddc")
    query = run(ddc, "query", str(examples / "tutorial.pl"), "true")
    assert query.returncode == 0, query.stderr[-3000:]
    filtered = run(ddc, "filter", str(examples / "filter" / "pit_world.pl"),
                   str(examples / "filter" / "pit_world.jsonl"), "--particles", "100")
    assert filtered.returncode == 0, filtered.stderr[-3000:]
    assert "4 steps, 100 particles" in filtered.stdout + filtered.stderr
    learned = run(ddc, "learn", str(examples / "learn" / "occluder.pl"), "--out",
                  str(work / "learned.pl"), "--quiet")
    assert learned.returncode == 0, learned.stderr[-3000:]
    assert "occluder" in (work / "learned.pl").read_text()
