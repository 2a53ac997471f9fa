"""Filter.samples reads a variable's values as rows of floats: with the batched engine's column
library, straight from its columns into a numpy array (no conversion of each float), else from
a list of floats; both give the rows that Filter.values gives, NaN where a particle has none."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bridge import Filter

PROGRAM = """
s:0 ~ uniform([a, b]).
s:t+1 ~ val(S) := s:t ~= S.
x:0 ~ gaussian(0.0, 1.0).
x:t+1 ~ gaussian(X, 0.1) := x:t ~= X.
p:t ~ val((X, 1.5, 0.25)) := s:t ~= a, x:t ~= X.
q:t ~ val((1, 2)) := true.
"""


def rows_of_values(values: list) -> np.ndarray:
    width = len(next(v for v in values if v is not None)) if any(
        isinstance(v, tuple) for v in values) else 1
    out = np.full((len(values), width), np.nan)
    for i, v in enumerate(values):
        if v is not None:
            out[i] = v if isinstance(v, tuple) else [v]
    return out if width > 1 else out[:, 0]


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.parametrize("engine", ["batched", "per_particle"])
def test_samples_are_the_values_as_rows(tmp_path: Path, threads: int, engine: str) -> None:
    program = tmp_path / "rows.pl"
    program.write_text(PROGRAM)
    with Filter(program, particles=50, seed=4, threads=threads, engine=engine) as f:
        for _ in range(3):
            f.step([])
            for term in ("p:t", "x:t", "q:t"):
                rows, weights = f.samples(term)
                expected = rows_of_values(f.values("V", f"{term} ~= V"))
                assert rows.shape == expected.shape and weights.shape == (50,)
                assert np.array_equal(rows, expected, equal_nan=True), term
                rows[0] = 7.0  # (the caller's own array)
            undefined = np.isnan(f.samples("p:t")[0]).all(axis=1)
            assert 0 < undefined.sum() < 50  # (some particles hold s = b: no p there)
            pairs, _ = f.samples("(X, Y)", "p:t ~= (X, Y, _)")
            assert np.array_equal(pairs, f.samples("p:t")[0][:, :2], equal_nan=True)


def recorded_replies(monkeypatch: pytest.MonkeyPatch, helper: str, output: str) -> list:
    """What the bridge's Prolog helper ``helper`` gives back as ``output``, call by call, from
    here on."""
    from bridge import filter as bridge_filter

    replies = []
    call = bridge_filter._call

    def recording(name: str, /, **arguments: object) -> dict:
        result = call(name, **arguments)
        if name == helper:
            replies.append(result[output])
        return result

    monkeypatch.setattr(bridge_filter, "_call", recording)
    return replies


def test_the_column_library_copies_the_rows_into_the_array(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from bridge import prolog as bridge_prolog

    program = tmp_path / "rows.pl"
    program.write_text(PROGRAM)
    replies = recorded_replies(monkeypatch, "bridge_rows_into", "F")
    with Filter(program, particles=50, seed=4, threads=2, engine="batched") as f:
        f.step([])
        backend = bridge_prolog.query_once("ddc_batch_col:col_backend(B)")["B"]
        f.samples("p:t")
        f.samples("q:t")  # (integers: a list of floats)
    assert replies[1] == [1.0, 2.0] * 50
    assert replies[0] == 150 if backend == "foreign" else isinstance(replies[0], list)


INDEX_PROGRAM = """
h:0 ~ uniform([a, b, c, d]).
h:t+1 ~ val(H) := h:t ~= H.
under(O):t := h:t ~= O, O \\== d.
"""


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.parametrize("engine", ["batched", "per_particle"])
def test_indices_are_the_positions_of_the_values_in_the_list(
        tmp_path: Path, threads: int, engine: str) -> None:
    program = tmp_path / "indices.pl"
    program.write_text(INDEX_PROGRAM)
    atoms = ["c", "a"]  # b is not listed; d has no solution
    with Filter(program, particles=60, seed=2, threads=threads, engine=engine) as f:
        f.step([])
        values = f.values("O", "under(O):t")
        expected = np.array([atoms.index(v) if v in atoms else -1 for v in values])
        got = f.indices("O", "under(O):t", atoms)
        assert got.dtype == np.int64 and got.shape == (60,)
        assert np.array_equal(got, expected)
        assert set(got) == {-1, 0, 1}  # (each case occurs among 60 particles)
        assert np.array_equal(f.indices("O", "under(O):t", []), np.full(60, -1))


def test_the_column_library_copies_the_indices_into_the_array(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from bridge import prolog as bridge_prolog

    program = tmp_path / "indices.pl"
    program.write_text(INDEX_PROGRAM)
    replies = recorded_replies(monkeypatch, "bridge_indices_into", "I")
    with Filter(program, particles=50, seed=4, threads=2, engine="batched") as f:
        f.step([])
        backend = bridge_prolog.query_once("ddc_batch_col:col_backend(B)")["B"]
        f.indices("O", "under(O):t", ["a", "b"])
    assert replies[0] == 50 if backend == "foreign" else isinstance(replies[0], list)
