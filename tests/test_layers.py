"""The layers of docs/architecture.md hold: which package may import which (import-linter's
contracts in pyproject.toml), no module reads or writes another's objects' underscore
attributes (ruff's SLF001 over python/), and no package imports another's private names."""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PYTHON = ROOT / "python"


def test_packages_import_only_the_layers_below_them() -> None:
    pytest.importorskip("importlinter", reason="import-linter is in the dev extra "
                        "(pyproject.toml; scripts/setup.sh installs it)")
    # in a process of its own: the contracts are read from the repository's pyproject.toml,
    # the packages from its python/ (not an installed copy)
    done = subprocess.run(
        [sys.executable, "-c", "import sys; from importlinter.cli import lint_imports; "
         "sys.exit(lint_imports(no_cache=True, no_logo=True))"],
        cwd=ROOT, env={**os.environ, "PYTHONPATH": os.pathsep.join(
            [str(PYTHON), *filter(None, [os.environ.get("PYTHONPATH")])])},
        capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr


def test_no_module_reaches_into_another_modules_objects() -> None:
    """``obj._name`` where obj is not self or cls (ruff's SLF001, selected in pyproject.toml
    for python/); the few uses within one class family say why in their ``noqa``."""
    ruff = Path(sys.executable).with_name("ruff")
    done = subprocess.run([str(ruff), "check", "--no-cache", "--select", "SLF001",
                           "--output-format", "concise", str(PYTHON)],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr


def _package(dotted: list[str]) -> str:
    """The package a module belongs to: ``probanchor.loop`` for probanchor.loop.store,
    ``anchoring`` for anchoring.manager."""
    return ".".join(dotted[:2]) if dotted[0] == "probanchor" else dotted[0]


def private_imports(root: Path = PYTHON) -> list[str]:
    """Every ``from A import _name`` where A is in another package than the importing
    module's, as ``file:line: A._name``."""
    found = []
    for path in sorted(root.rglob("*.py")):
        mine = _package(list(path.relative_to(root).with_suffix("").parts))
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if not isinstance(node, ast.ImportFrom) or node.level or not node.module:
                continue
            if _package(node.module.split(".")) == mine:
                continue
            found.extend(f"{path.relative_to(root)}:{node.lineno}: {node.module}.{a.name}"
                         for a in node.names
                         if a.name.startswith("_") and not a.name.startswith("__"))
    return found


def test_no_package_imports_another_packages_private_names() -> None:
    assert private_imports() == []


def test_a_private_import_across_packages_is_found(tmp_path: Path) -> None:
    """The scan finds what it looks for (a tree with one such import, one within a package)."""
    loop = tmp_path / "probanchor" / "loop"
    learning = tmp_path / "probanchor" / "learning"
    loop.mkdir(parents=True)
    learning.mkdir(parents=True)
    (loop / "store.py").write_text("from probanchor.loop.naming import _helper\n")
    (learning / "collect.py").write_text("import os\n\nfrom probanchor.loop.store import _snap\n")
    assert private_imports(tmp_path) == [
        "probanchor/learning/collect.py:3: probanchor.loop.store._snap"]
