"""A generated university: students, courses and professors, as relational learning data.

A data set in the style of the University data of relational learning (Ravkic, Ramon and
Davis's hybrid relational dependency networks; DreaML's experiments): each *world* holds
``students`` students, ``courses`` courses and ``professors`` professors; every course is taught
by one professor, every student takes ``takes`` courses and has ``friends`` friends. The
attributes and what they depend on:

==================  =============================  ==============================================
attribute           values                         depends on
==================  =============================  ==============================================
intelligence(S)     continuous                     nothing (standard normal)
ability(P)          continuous                     nothing (standard normal)
difficulty(C)       easy, medium, hard             nothing
nrhours(C)          continuous                     difficulty(C)
grade(S, C)         low, mid, high                 intelligence(S), difficulty(C), nrhours(C),
                                                   the ability of C's professor, the mean
                                                   intelligence of S's friends and of C's
                                                   students (an ordinal logit: a sum of
                                                   effects of three entities and two
                                                   aggregates)
satisfaction(S, C)  low, mid, high                 grade(S, C), the ability of C's professor, and
                                                   difficulty(C) together with intelligence(S)
hours(S, C)         continuous                     nrhours(C), intelligence(S), the mean grade
                                                   of C's students, difficulty(C)
==================  =============================  ==============================================

The effects' sizes are drawn from ``effects_seed`` (the same for every world of one data set);
the worlds themselves from ``seed``. Learning on one world and scoring on another world of the
same effects is the held-out setting of the original's University experiments (each split an
independent interpretation). :func:`university_data` writes a world in the learner's own
dialect (``docs/learning.md``) with its declarative bias; the targets are ``grade``,
``satisfaction`` and ``hours``::

    from probanchor.ddclearn.university import university_data
    Path("train.pl").write_text(university_data(seed=1, effects_seed=7))
    Path("test.pl").write_text(university_data(seed=2, effects_seed=7))
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["BIAS", "Effects", "university_data"]

LEVELS: tuple[str, ...] = ("low", "mid", "high")
DIFFICULTY: tuple[str, ...] = ("easy", "medium", "hard")

#: The declarative bias of the generated data (own dialect).
BIAS = """\
type(intelligence(s)).
type(ability(p)).
type(difficulty(c)).
type(nrhours(c)).
type(teaches(p, c)).
type(takes(s, c)).
type(friend(s, s)).
type(grade(s, c)).
type(satisfaction(s, c)).
type(hours(s, c)).
rv(intelligence(_), continuous).
rv(ability(_), continuous).
rv(difficulty(_), discrete([easy, medium, hard])).
rv(nrhours(_), continuous).
rv(grade(_, _), discrete([low, mid, high])).
rv(satisfaction(_, _), discrete([low, mid, high])).
rv(hours(_, _), continuous).
rank([intelligence, ability, difficulty, nrhours, teaches, takes, friend, grade,
      satisfaction, hours]).
learn(grade(S, C)).
learn(satisfaction(S, C)).
learn(hours(S, C)).
mode(grade(_, _), intelligence(+)).
mode(grade(_, _), difficulty(+)).
mode(grade(_, _), nrhours(+)).
mode(grade(_, _), mean, (teaches(-, +), ability(+))).
mode(grade(_, _), mean, (friend(+, -), intelligence(+))).
mode(grade(_, _), mean, (takes(-, +), intelligence(+))).
mode(grade(_, _), count, takes(+, -)).
mode(satisfaction(_, _), grade(+, +)).
mode(satisfaction(_, _), intelligence(+)).
mode(satisfaction(_, _), difficulty(+)).
mode(satisfaction(_, _), mean, (teaches(-, +), ability(+))).
mode(satisfaction(_, _), mean, (friend(+, -), intelligence(+))).
mode(hours(_, _), intelligence(+)).
mode(hours(_, _), difficulty(+)).
mode(hours(_, _), nrhours(+)).
mode(hours(_, _), grade(+, +)).
mode(hours(_, _), mean, (teaches(-, +), ability(+))).
mode(hours(_, _), mode, (takes(-, +), grade(+, +))).
mode(hours(_, _), count, takes(-, +)).
"""


@dataclass(frozen=True)
class Effects:
    """The effect sizes of one data set (drawn by :meth:`draw`)."""

    grade: np.ndarray          # intelligence, difficulty, ability, friends, classmates, nrhours
    grade_cuts: np.ndarray
    satisfaction: np.ndarray   # grade (per level), ability, the interaction
    satisfaction_cuts: np.ndarray
    hours: np.ndarray          # nrhours, intelligence, mean grade, difficulty (per level)
    hours_sd: float

    @classmethod
    def draw(cls, seed: int) -> Effects:
        r = np.random.default_rng(seed)
        return cls(
            grade=np.array([r.uniform(0.8, 1.6), -r.uniform(0.6, 1.2), r.uniform(0.4, 1.0),
                            r.uniform(0.3, 0.8), r.uniform(1.0, 2.0), r.uniform(0.1, 0.3)]),
            grade_cuts=np.sort(r.uniform(-1.0, 1.0, 2)) + np.array([-0.5, 0.5]),
            satisfaction=np.array([r.uniform(0.6, 1.2), r.uniform(0.5, 1.0),
                                   r.uniform(1.0, 2.0)]),
            satisfaction_cuts=np.sort(r.uniform(-0.5, 1.5, 2)) + np.array([-0.4, 0.4]),
            hours=np.array([r.uniform(0.3, 0.7), -r.uniform(1.0, 2.0), -r.uniform(0.5, 1.5),
                            r.uniform(0.5, 1.5)]),
            hours_sd=float(r.uniform(1.0, 2.0)),
        )


def _ordinal(r: np.random.Generator, z: np.ndarray, cuts: np.ndarray) -> np.ndarray:
    """Levels 0, 1, 2 of an ordinal logit: z plus logistic noise against two cut points."""
    u = z + r.logistic(size=len(z))
    return (u > cuts[0]).astype(int) + (u > cuts[1]).astype(int)


def university_data(seed: int, effects_seed: int = 0, students: int = 400, courses: int = 60,
                    professors: int = 30, takes: int = 5, friends: int = 3) -> str:
    """One generated world as a learning data file (own dialect, with :data:`BIAS`).

    Parameters
    ----------
    seed : int
        Seeds the world (who takes what, the attributes' values).
    effects_seed : int, default=0
        Seeds the effect sizes (:class:`Effects`): worlds of one data set share them.
    students, courses, professors : int
        How many of each.
    takes : int, default=5
        Courses per student (distinct, at random).
    friends : int, default=3
        Friends per student (at random; friendship is not symmetric).

    Returns
    -------
    str
        The file's text: a header, the facts, the bias.
    """
    for name, v in (("students", students), ("courses", courses), ("professors", professors),
                    ("takes", takes), ("friends", friends)):
        if isinstance(v, bool) or not isinstance(v, int) or v < 1:
            raise ValueError(f"{name} must be a positive integer, got {v!r}")
    if takes > courses or friends >= students:
        raise ValueError("a student takes at most every course and befriends the others")
    e = Effects.draw(effects_seed)
    r = np.random.default_rng([seed, effects_seed])
    iq = r.normal(size=students)
    ability = r.normal(size=professors)
    diff = r.integers(0, 3, size=courses)
    nrhours = 3.0 + 2.0 * diff + r.normal(scale=0.8, size=courses)
    prof = r.integers(0, professors, size=courses)
    taken = np.array([r.choice(courses, size=takes, replace=False) for _ in range(students)])
    friend = np.array([r.choice(np.delete(np.arange(students), s), size=friends, replace=False)
                       for s in range(students)])
    s_idx = np.repeat(np.arange(students), takes)
    c_idx = taken.ravel()
    friend_iq = iq[friend].mean(axis=1)
    class_iq = np.bincount(c_idx, weights=iq[s_idx], minlength=courses) / np.maximum(
        np.bincount(c_idx, minlength=courses), 1)
    z = (e.grade[0] * iq[s_idx] + e.grade[1] * (diff[c_idx] - 1) + e.grade[2] * ability[prof[c_idx]]
         + e.grade[3] * friend_iq[s_idx] + e.grade[4] * class_iq[c_idx]
         + e.grade[5] * (nrhours[c_idx] - 5.0))
    grade = _ordinal(r, z, e.grade_cuts)
    # satisfied by a good grade and a good teacher; a hard course satisfies the clever
    z = (e.satisfaction[0] * (grade - 1) + e.satisfaction[1] * ability[prof[c_idx]]
         + e.satisfaction[2] * (diff[c_idx] == 2) * np.tanh(iq[s_idx]))
    satisfaction = _ordinal(r, z, e.satisfaction_cuts)
    mean_grade = np.bincount(c_idx, weights=grade, minlength=courses) / np.maximum(
        np.bincount(c_idx, minlength=courses), 1)
    hours = (5.0 + e.hours[0] * nrhours[c_idx] + e.hours[1] * iq[s_idx]
             + e.hours[2] * (mean_grade[c_idx] - 1) + e.hours[3] * (diff[c_idx] - 1)
             + r.normal(scale=e.hours_sd, size=len(s_idx)))
    lines = [f"% A generated university (probanchor.ddclearn.university): seed {seed}, "
             f"effects {effects_seed},",
             f"% {students} students, {courses} courses, {professors} professors, "
             f"{len(s_idx)} enrolments."]
    lines += [f"intelligence(s{i}) ~= {v:.4f}." for i, v in enumerate(iq)]
    lines += [f"ability(p{i}) ~= {v:.4f}." for i, v in enumerate(ability)]
    lines += [f"difficulty(c{i}) ~= {DIFFICULTY[d]}." for i, d in enumerate(diff)]
    lines += [f"nrhours(c{i}) ~= {v:.3f}." for i, v in enumerate(nrhours)]
    lines += [f"teaches(p{p}, c{i})." for i, p in enumerate(prof)]
    lines += [f"friend(s{s}, s{f})." for s in range(students) for f in friend[s]]
    for s, c, g, sa, h in zip(s_idx, c_idx, grade, satisfaction, hours, strict=True):
        lines += [f"takes(s{s}, c{c}).", f"grade(s{s}, c{c}) ~= {LEVELS[g]}.",
                  f"satisfaction(s{s}, c{c}) ~= {LEVELS[sa]}.", f"hours(s{s}, c{c}) ~= {h:.3f}."]
    return "\n".join(lines) + "\n\n% Declarative bias.\n" + BIAS
