"""The Prolog files are laid out as a SWI-Prolog pack: ``pack.pl`` at the root, ``prolog/`` its
library with the facade (``library(ddc)``) and the theories at the top, the engine's modules a
folder per subsystem below ``prolog/ddc/``, each with its module documentation."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from plunit_runner import ROOT, swipl_executable

PROLOG = ROOT / "prolog"
SUBSYSTEMS = ("lang", "runtime", "filter", "batch", "learn", "compat")


def modules() -> list[Path]:
    """Every module file of the engine and the application (the examples are programs)."""
    return sorted(path for path in PROLOG.rglob("*.pl")
                  if "examples" not in path.relative_to(PROLOG).parts
                  and path.read_text(encoding="utf-8").lstrip().find(":- module(") >= 0)


def test_few_files_at_the_top_of_prolog() -> None:
    top = sorted(path.name for path in PROLOG.glob("*.pl"))
    assert len(top) <= 8, top
    assert "ddc.pl" in top and "too.pl" in top


def test_engine_modules_are_in_their_subsystem_folders() -> None:
    engine = [path for path in (PROLOG / "ddc").rglob("*.pl")]
    folders = {path.relative_to(PROLOG / "ddc").parts[0] for path in engine
               if path.parent != PROLOG / "ddc"}
    assert folders == set(SUBSYSTEMS)
    for path in engine:          # module names keep their prefix; the file names are theirs
        name = re.search(r":- module\((\w+)", path.read_text(encoding="utf-8")).group(1)
        assert name.startswith(("ddc_", "dc_")), (path, name)
        assert name == path.stem or (name, path.name) == ("ddc_learn", "learn.pl"), (path, name)


def test_pack_file_names_the_pack() -> None:
    text = (ROOT / "pack.pl").read_text(encoding="utf-8")
    assert re.search(r"^name\(ddc\)\.", text, re.M)


@pytest.mark.parametrize("library", ["ddc", "ddc/learn"])
def test_the_engine_loads_from_the_library(library: str) -> None:
    result = subprocess.run(
        [swipl_executable(), "-q", "--on-error=status", "--on-warning=status", "-p",
         "library=prolog", "-g", f"use_module(library({library})), halt", "-t", "halt(1)"],
        cwd=ROOT, capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 0, result.stdout + result.stderr


def test_every_module_has_a_module_documentation_block() -> None:
    missing = [str(path.relative_to(ROOT)) for path in modules()
               if "/** <module>" not in path.read_text(encoding="utf-8")]
    assert missing == []
