"""Python -> Prolog -> Python round trips through janus, as the bridge uses them."""

from __future__ import annotations

import subprocess
import sys

from bridge import prolog


def test_round_trip_arithmetic_and_terms() -> None:
    result = prolog.query_once("X is A * 2, atom_length(N, L)", {"A": 21, "N": "ball_1"})
    assert result["truth"] is True
    assert result["X"] == 42
    assert result["L"] == 6


def test_janus_uses_the_projects_swipl_version() -> None:
    result = prolog.query_once("current_prolog_flag(version, V)")
    assert result["V"] >= 90112  # janus-swi needs SWI-Prolog 9.1.12 or newer


def test_import_works_in_a_fresh_interpreter_with_a_clean_environment() -> None:
    # No SWI_HOME_DIR exported by the caller: the venv sets it up itself.
    env = {"PATH": "/usr/bin:/bin", "HOME": "/tmp"}
    out = subprocess.run(
        [sys.executable, "-c", "import janus_swi as j; print(j.query_once('X = ok')['X'])"],
        env=env, capture_output=True, text=True, timeout=120,
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"
