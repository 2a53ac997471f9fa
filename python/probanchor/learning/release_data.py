"""Data for learning when a hand lets go of what it carries (``released(A):t+1``).

A carrier (a hand) that has taken an object holds it, in the theory of occlusion, until the
particle draws ``released(A):t+1 ~= true``; the object then stays where it is and the hand
leaves. When that happens is learned by the structure learner (:func:`probanchor.ddclearn.learn`)
from the carries ``anchoring collect`` keeps among its motion samples
(:mod:`probanchor.learning.motion_samples`: for every frame a hand held an object, how high the
object was above where it stood when taken, and whether the hand let go after the last one).

One data point per frame a hand held the object (t) and the next (t+1): the object's state at t
as a particle of the theory holds it (``pos(A):t``, its height above ``rest_z(A):t``, where it
stood, and ``top(A):t``, the highest it has been above it since it was taken), and the label,
whether the hand let go of it at t+1 (the object no longer held). A carry that runs to the end
of its episode gives no data point for its last frame (censored). Each data point has constants
of its own (``held_data_truth_3_f12``), so that data points are independent worlds.

The background knowledge the learned clauses read (``FEATURES``) is written into the data file
and the learned theory carries the same text; ``prolog/too/too_learned_glue.pl`` defines the
example predicate ``carried/1`` and keeps ``top/1`` in the filter.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

__all__ = ["BIAS", "FEATURES", "release_points", "release_path", "release_text"]

#: Background knowledge of the learned release, in the data and in the learned theory.
FEATURES = """\
% Features of a carried object A from t to t+1: how high above where it stood it was at t,
% and the highest it had been since the hand took it.
height(A):t+1 ~ val(H) :=
    pos(A):t ~= (_, _, Z), rest_z(A):t ~= R, H is Z - R.
highest(A):t+1 ~ val(H) :=
    top(A):t ~= H.
"""

#: The declarative bias: the target, its examples and the literals its clauses may test.
BIAS = """\
type(released(obj):t+1).
type(carried(obj):t+1).
type(height(obj):t+1).
type(highest(obj):t+1).
rv(released(_):t+1, boolean).
rv(height(_):t+1, continuous).
rv(highest(_):t+1, continuous).
learn(released(Held):t+1).
examples(released(A):t+1, carried(A):t+1).
mode(released(_):t+1, height(+):t+1).
mode(released(_):t+1, highest(+):t+1).
"""


def release_path(data: str | Path) -> Path:
    """Where the release data of data file ``data`` are: ``DATA.release.pl`` beside it."""
    p = Path(data)
    return p.with_name(p.stem + ".release.pl")


def release_text(carries: Sequence[dict[str, Any]], command: str | None = None,
                 name: str = "held") -> str:
    """The data file of the release (see the module docstring) from the motion samples'
    ``carries`` rows (``heights`` above where the object stood, one per frame held;
    ``released``, whether the hand let go after the last). Without carries it has no data
    points (:func:`release_points` is 0): no hand carried anything, there is no release to
    learn. ``name`` begins every constant (``NAME_3_f12``): data files of several collections
    learned from together need names of their own (`anchoring collect` gives each the name of
    its data file)."""
    lines: list[str] = []
    points = releases = 0
    for n, carry in enumerate(carries):
        heights = [float(h) for h in carry["heights"]]
        top = -float("inf")
        for i, h in enumerate(heights):
            top = max(top, h)
            last = i == len(heights) - 1
            if last and not carry["released"]:
                break                                  # the episode ended: censored
            c = f"{name}_{n}_f{i}"
            lines += [f"pos({c}):t ~= (0.0, 0.0, {h:.5f}).", f"rest_z({c}):t ~= 0.0.",
                      f"top({c}):t ~= {top:.5f}.", f"carried({c}):t+1."]
            if last:
                lines.append(f"released({c}):t+1.")
                releases += 1
            points += 1
    header = ["% When a hand lets go of what it carries: data written by `anchoring collect` from",
              "% the carries among its motion samples, for the structure learner (`ddc learn`,",
              "% `anchoring learn-theory`); heights in metres above where the object stood."]
    if command:
        header.append(f"% Command: {command}")
    header.append(f"% {len(carries)} carries, {points} frames held, {releases} releases.")
    return "\n".join(header) + "\n\n" + FEATURES + "\n" + BIAS + "\n" + "\n".join(lines) + "\n"


def release_points(path: str | Path) -> int:
    """The number of data points (frames a hand held an object) in release data file ``path``."""
    with open(path, encoding="utf-8") as f:
        return sum(1 for line in f if line.startswith("carried("))
