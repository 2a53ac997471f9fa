"""The benchmark's occlusion model twice: as a generated DDC program, and vectorised in numpy.

The model (a theory of occlusion of the paper's shape, section 2.3), for M objects:

* time 0: every object at its start position plus N(0, PROCESS_VAR I); all seen; none hidden.
* an object seen at t+1 does a random walk: pos' ~ N(pos, PROCESS_VAR I);
* an object seen at t and not at t+1 picks its occluder uniformly among the objects seen at
  t+1 that are above it (z) and within OCCLUDER_RADIUS of it in the table plane (its position
  at t, theirs at t+1); with no candidate it is hidden under nothing;
* a hidden object keeps its offset to its occluder (moves with it), or stays put if it has none;
* every observed position y weights the particle by N(y; pos', SENSOR_VAR I).

:func:`ddc_program` writes the DDC text for M objects; :class:`NumpyOcclusionFilter` is the
same model with particles as arrays (N, M, 3); :func:`scenario` makes a reproducible frame
sequence (boxes that move, small objects that get hidden under them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

PROCESS_VAR = 0.000025  # (0.5 cm)^2 per step and axis
SENSOR_VAR = 0.0004  # (2 cm)^2 per axis
OCCLUDER_RADIUS = 0.3

_PROGRAM_BODY = """
process_cov([{q}, 0, 0, 0, {q}, 0, 0, 0, {q}]) := true.
sensor_cov([{r}, 0, 0, 0, {r}, 0, 0, 0, {r}]) := true.

pos(O):0 ~ gaussian([X, Y, Z], C) := start(O, (X, Y, Z)), process_cov(C).
seen(O):0 ~ val(true) := object(O).
hidden_under(O):0 ~ val(none) := object(O).

seen(O):t+1 ~ val(true) := object(O), observed(O).
seen(O):t+1 ~ val(false) := object(O), \\+ observed(O).

occluder(O, H):t+1 :=
    seen(O):t ~= true, seen(O):t+1 ~= false,
    object(H), H \\== O, seen(H):t+1 ~= true,
    pos(O):t ~= (X, Y, Z), pos(H):t+1 ~= (XH, YH, ZH),
    D is sqrt((X - XH)**2 + (Y - YH)**2), Z < ZH, D < {radius}.

hidden_under(O):t+1 ~ uniform(Hs) :=
    object(O), seen(O):t ~= true, seen(O):t+1 ~= false,
    findall_forward(H, occluder(O, H):t+1, Hs), Hs \\== [].
hidden_under(O):t+1 ~ val(none) :=
    object(O), seen(O):t ~= true, seen(O):t+1 ~= false,
    findall_forward(H, occluder(O, H):t+1, []).
hidden_under(O):t+1 ~ val(H) :=
    object(O), seen(O):t ~= false, seen(O):t+1 ~= false, hidden_under(O):t ~= H.
hidden_under(O):t+1 ~ val(none) := object(O), seen(O):t+1 ~= true.

occluded_by(O, H):t := hidden_under(O):t ~= H, H \\== none.

pos(O):t+1 ~ gaussian([X, Y, Z], C) :=
    object(O), seen(O):t+1 ~= true, pos(O):t ~= (X, Y, Z), process_cov(C).
pos(O):t+1 ~ val((X1, Y1, Z1)) :=
    object(O), seen(O):t+1 ~= false, hidden_under(O):t+1 ~= H, H \\== none,
    pos(O):t ~= (X, Y, Z), pos(H):t ~= (HX, HY, HZ), pos(H):t+1 ~= (HX1, HY1, HZ1),
    X1 is X + HX1 - HX, Y1 is Y + HY1 - HY, Z1 is Z + HZ1 - HZ.
pos(O):t+1 ~ val(P) :=
    object(O), seen(O):t+1 ~= false, hidden_under(O):t+1 ~= none, pos(O):t ~= P.

observation(pos(O)):t+1 ~ gaussian([X, Y, Z], C) := pos(O):t+1 ~= (X, Y, Z), sensor_cov(C).
"""


def object_names(m: int) -> list[str]:
    return [f"o{k}" for k in range(1, m + 1)]


def start_positions(m: int) -> np.ndarray:
    """(M, 3): boxes (every third object, z = 0.05) 0.25 m apart on a line, each followed by
    two small objects (z = 0.02) a few centimetres from it."""
    out = np.zeros((m, 3))
    for k in range(m):
        box, role = divmod(k, 3)
        x = 0.25 * box
        if role == 0:
            out[k] = (x, 0.0, 0.05)
        else:
            out[k] = (x + (0.03 if role == 1 else -0.03), 0.04 * (1 if role == 1 else -1), 0.02)
    return out


def is_box(k: int) -> bool:
    return k % 3 == 0


def ddc_program(m: int) -> str:
    """The DDC text of the model for ``m`` objects."""
    names = object_names(m)
    starts = start_positions(m)
    lines = [f"% Benchmark occlusion model, {m} objects (bench/filter_numpy_reference.py)"]
    lines += [f"object({n}) := true." for n in names]
    lines += [
        f"start({n}, ({float(x)!r}, {float(y)!r}, {float(z)!r})) := true."
        for n, (x, y, z) in zip(names, starts,
                                                                              strict=True)
    ]
    body = _PROGRAM_BODY.format(q=PROCESS_VAR, r=SENSOR_VAR, radius=OCCLUDER_RADIUS)
    return "\n".join(lines) + "\n" + body


@dataclass(frozen=True)
class Frame:
    """One time step of the scenario: which objects are seen and where (metres)."""

    seen: np.ndarray  # (M,) bool
    positions: np.ndarray  # (M, 3) observed positions (rows of unseen objects unused)

    def terms(self, names: list[str]) -> list[str]:
        out = []
        for k in np.flatnonzero(self.seen):
            x, y, z = (float(v) for v in self.positions[k])
            out.append(f"observed({names[k]})")
            out.append(f"observation(pos({names[k]})) ~= ({x!r},{y!r},{z!r})")
        return out


def scenario(m: int, steps: int, seed: int = 0) -> list[Frame]:
    """Boxes drift 1 cm per step in x; from step 3 on the first small object next to every box
    is hidden (under it), and from step 6 the second too; positions observed with noise."""
    rng = np.random.default_rng(seed)
    truth = start_positions(m).copy()
    frames = []
    for t in range(1, steps + 1):
        seen = np.ones(m, dtype=bool)
        for k in range(m):
            role = k % 3
            if (role == 1 and t >= 3) or (role == 2 and t >= 6):
                seen[k] = False
        for k in range(m):
            if is_box(k) or not seen[k]:  # a hidden object is carried by the box it is under
                truth[k, 0] += 0.01
        observed = truth + rng.normal(0.0, math.sqrt(SENSOR_VAR), truth.shape)
        frames.append(Frame(seen, observed))
    return frames


def systematic_indices(weights: np.ndarray, offset: float) -> np.ndarray:
    """Systematic resampling: positions (offset + k) / N, each taking the first particle
    whose cumulative weight exceeds it (the last counting as 1)."""
    n = len(weights)
    cumulative = np.cumsum(weights)
    cumulative[-1] = 1.0
    return np.minimum(np.searchsorted(cumulative, (offset + np.arange(n)) / n, side="right"),
                      n - 1)


class NumpyOcclusionFilter:
    """The same model, particles as numpy arrays; bootstrap filter with systematic resampling
    (the DDC filter's scheme, here in numpy: the reference is numpy alone) when the ESS falls
    below ``threshold`` * N."""

    def __init__(self, m: int, particles: int, seed: int = 0, threshold: float = 0.9) -> None:
        self.m, self.n, self.threshold = m, particles, threshold
        self.rng = np.random.default_rng(seed)
        sd = math.sqrt(PROCESS_VAR)
        self.pos = start_positions(m)[None] + self.rng.normal(0.0, sd, (particles, m, 3))
        self.seen = np.ones(m, dtype=bool)
        self.hidden_under = np.full((particles, m), -1, dtype=np.int64)
        self.log_weights = np.full(particles, -math.log(particles))
        self.log_likelihood = 0.0

    def step(self, frame: Frame) -> None:
        n, m = self.n, self.m
        seen_new = frame.seen
        old = self.pos
        new = old.copy()
        # seen objects: random walk
        walk = self.rng.normal(0.0, math.sqrt(PROCESS_VAR), (n, m, 3))
        new[:, seen_new] += walk[:, seen_new]
        # newly hidden objects: pick an occluder uniformly among the candidates
        hidden_under = self.hidden_under.copy()
        hidden_under[:, seen_new] = -1
        for o in np.flatnonzero(self.seen & ~seen_new):
            xy = old[:, o, :2][:, None, :]
            dist = np.sqrt(((new[:, :, :2] - xy) ** 2).sum(axis=2))  # (N, M)
            candidate = (dist < OCCLUDER_RADIUS) & (old[:, o, 2][:, None] < new[:, :, 2])
            candidate &= seen_new[None, :]
            candidate[:, o] = False
            count = candidate.sum(axis=1)
            pick = np.floor(self.rng.random(n) * count).astype(np.int64)
            chosen = np.argmax(np.cumsum(candidate, axis=1) > pick[:, None], axis=1)
            hidden_under[:, o] = np.where(count > 0, chosen, -1)
        # hidden objects follow their occluder's displacement (chains resolved in turn)
        hidden = np.flatnonzero(~seen_new)
        moved = np.zeros((n, m), dtype=bool)
        moved[:, seen_new] = True
        for _ in range(len(hidden)):
            for o in hidden:
                h = hidden_under[:, o]
                has = h >= 0
                rows = np.arange(n)
                ready = has & moved[rows, np.maximum(h, 0)] & ~moved[:, o]
                delta = new[rows, np.maximum(h, 0)] - old[rows, np.maximum(h, 0)]
                new[ready, o] = old[ready, o] + delta[ready]
                moved[ready, o] = True
                moved[~has, o] = True
        # weights
        diff = new[:, seen_new] - frame.positions[seen_new][None]
        k = 3 * int(seen_new.sum())
        step_lw = -0.5 * (diff**2).sum(axis=(1, 2)) / SENSOR_VAR - 0.5 * k * math.log(
            2 * math.pi * SENSOR_VAR
        )
        combined = self.log_weights + step_lw
        top = combined.max()
        increment = top + math.log(np.exp(combined - top).sum())
        self.log_likelihood += increment
        self.log_weights = combined - increment
        self.pos, self.seen, self.hidden_under = new, seen_new.copy(), hidden_under
        w = np.exp(self.log_weights)
        if 1.0 / np.dot(w, w) < self.threshold * n:
            idx = systematic_indices(w, self.rng.random())
            self.pos, self.hidden_under = self.pos[idx], self.hidden_under[idx]
            self.log_weights = np.full(n, -math.log(n))

    def occluded_by(self, o: int, h: int) -> float:
        return float(np.exp(self.log_weights)[self.hidden_under[:, o] == h].sum())

    def mean_position(self, o: int) -> np.ndarray:
        return np.exp(self.log_weights) @ self.pos[:, o]
