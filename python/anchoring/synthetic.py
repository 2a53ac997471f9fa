"""Synthetic labelled percept streams: objects on a table seen by a noisy perception.

Not the simulator (that is ``tabletop`` + ``perception``): a cheap stand-in for tests and for
training the matching function before (or besides) recorded streams, with realistic noise: 3-D
centroid jitter, partial segmentations (shrunken boxes, shifted centroids), colour histograms
sampled from a finite number of pixels with background leakage, category confusions between
look-alike classes, missed detections, one-frame spurious percepts, objects pushed around, and
(optionally) occlusions during which an object may be carried a little. Each percept carries
``truth_id``; spurious ones get ids ``spurious-<k>`` that never repeat.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from probanchor.percepts import Percept, PerceptFrame

HIST_SHAPE = (8, 4, 4)  # H x S x V bins
TABLE = np.array([[0.05, 1.15], [0.05, 0.6]])  # x and y ranges in metres

SIZES = {
    "ball": (0.065, 0.065, 0.065),
    "mug": (0.11, 0.085, 0.095),
    "cup": (0.08, 0.08, 0.09),
    "box": (0.16, 0.11, 0.09),
    "block": (0.05, 0.05, 0.05),
    "can": (0.066, 0.066, 0.12),
    "bowl": (0.15, 0.15, 0.07),
    "bottle": (0.07, 0.07, 0.2),
}
CONFUSERS = {
    "ball": ["orange", "apple"],
    "mug": ["cup", "jar"],
    "cup": ["mug", "glass"],
    "box": ["block", "book"],
    "block": ["box", "toy"],
    "can": ["bottle", "cup"],
    "bowl": ["mixing_bowl", "plate"],
    "bottle": ["can", "jar"],
}
HUE_NAMES = ["red", "orange", "yellow", "green", "cyan", "blue", "purple", "magenta"]


@dataclass
class TrueObject:
    ident: str
    category: str
    hue: float  # in hue bins, [0, 8)
    saturation: float  # in saturation bins, [0, 4)
    value: float
    size: np.ndarray
    position: np.ndarray
    confidence: float  # mean probability the classifier gives the true category
    target: np.ndarray | None = None
    speed: float = 0.0
    hidden_until: float = -1.0


def true_histogram(obj: TrueObject) -> np.ndarray:
    h, s, v = np.meshgrid(*(np.arange(n) + 0.5 for n in HIST_SHAPE), indexing="ij")
    dh = np.minimum(np.abs(h - obj.hue), HIST_SHAPE[0] - np.abs(h - obj.hue))
    w = np.exp(-0.5 * (dh / 0.6) ** 2 - 0.5 * ((s - obj.saturation) / 0.7) ** 2
               - 0.5 * ((v - obj.value) / 0.9) ** 2)
    return (w / w.sum()).reshape(-1)


BACKGROUND = None


def _background() -> np.ndarray:
    global BACKGROUND
    if BACKGROUND is None:
        grey = TrueObject("", "", 0.0, 0.3, 2.5, np.zeros(3), np.zeros(3), 1.0)
        BACKGROUND = true_histogram(grey)
    return BACKGROUND


def random_object(rng: np.random.Generator, ident: str, category: str | None = None,
                  hue: float | None = None) -> TrueObject:
    category = category or str(rng.choice(list(SIZES)))
    size = np.array(SIZES[category]) * rng.uniform(0.85, 1.15, 3)
    return TrueObject(
        ident=ident,
        category=category,
        hue=float(rng.uniform(0, 8) if hue is None else hue),
        saturation=float(rng.uniform(1.8, 3.6)),
        value=float(rng.uniform(1.5, 3.5)),
        size=size,
        position=np.array([0.0, 0.0, size[2] / 2]),
        confidence=float(rng.uniform(0.55, 0.95)),
    )


def observe(obj: TrueObject, time: float, rng: np.random.Generator) -> Percept:
    """One noisy percept of ``obj``."""
    size = obj.size * rng.normal(1.0, 0.04, 3)
    position = obj.position + rng.normal(0.0, [0.004, 0.003, 0.003])
    if rng.random() < 0.06:  # partial segmentation: a clipped box and a shifted centroid
        axis = int(rng.integers(0, 2))
        f = rng.uniform(0.55, 0.9)
        position[axis] += (1 - f) * size[axis] / 2 * rng.choice([-1, 1])
        size[axis] *= f
    size = np.abs(size)
    pixels = int(rng.integers(250, 2500))
    leak = rng.uniform(0.0, 0.12)
    mix = (1 - leak) * true_histogram(obj) + leak * _background()
    hist = rng.multinomial(pixels, mix / mix.sum()).astype(float)
    hist /= hist.sum()
    category = _classify(obj, rng)
    names = [HUE_NAMES[int(round(obj.hue)) % 8]]
    return Percept(time=time, position=position, size=size, colour_histogram=hist,
                   category=category, colour_names=names, truth_id=obj.ident)


def _classify(obj: TrueObject, rng: np.random.Generator) -> dict[str, float]:
    p_true = float(np.clip(rng.normal(obj.confidence, 0.12), 0.2, 0.99))
    confusers = CONFUSERS.get(obj.category, ["toy", "box"])
    rest = 1 - p_true
    split = rng.dirichlet([3.0, 1.5, 0.7])
    others = [confusers[0], confusers[1], str(rng.choice(list(SIZES)))]
    probs: dict[str, float] = {obj.category: p_true}
    for name, share in zip(others, split, strict=True):
        if name != obj.category:
            probs[name] = probs.get(name, 0.0) + rest * float(share)
    top = sorted(probs.items(), key=lambda kv: -kv[1])[:3]
    return {k: round(v, 4) for k, v in top}


def spurious(time: float, rng: np.random.Generator, ident: str) -> Percept:
    obj = random_object(rng, ident)
    obj.size *= rng.uniform(0.3, 1.0, 3)
    obj.position = np.array([rng.uniform(*TABLE[0]), rng.uniform(*TABLE[1]), obj.size[2] / 2])
    return observe(obj, time, rng)


def _free_spot(rng: np.random.Generator, others: list[np.ndarray], min_gap: float) -> np.ndarray:
    for _ in range(200):
        xy = np.array([rng.uniform(*TABLE[0]), rng.uniform(*TABLE[1])])
        if all(np.linalg.norm(xy - o[:2]) >= min_gap for o in others):
            return xy
    return xy


def stream(
    seed: int,
    n_objects: int = 5,
    seconds: float = 20.0,
    fps: float = 15.0,
    occlusion_rate: float = 0.0,
    miss_rate: float = 0.03,
    spurious_rate: float = 0.01,
    move_rate: float = 0.15,
    twins: bool = True,
) -> list[PerceptFrame]:
    """A labelled stream. ``occlusion_rate``: chance per object per second of being hidden
    (1-4 s, sometimes carried up to 8 cm); ``move_rate``: chance per object per second of being
    pushed to a new spot (0.05-0.25 m/s). ``twins`` adds a look-alike of the first object."""
    rng = np.random.default_rng(seed)
    objects: list[TrueObject] = []
    for k in range(n_objects):
        if twins and k == 1 and objects:
            first = objects[0]
            obj = random_object(rng, f"obj-{k}", first.category, first.hue)
            obj.saturation, obj.value = first.saturation, first.value
        else:
            obj = random_object(rng, f"obj-{k}")
        xy = _free_spot(rng, [o.position for o in objects], 0.14)
        obj.position = np.array([xy[0], xy[1], obj.size[2] / 2])
        objects.append(obj)
    dt = 1.0 / fps
    frames: list[PerceptFrame] = []
    n_spurious = 0
    for f in range(int(round(seconds * fps))):
        t = round(f * dt, 6)
        percepts: list[Percept] = []
        for obj in objects:
            _move(obj, objects, t, dt, rng, move_rate, occlusion_rate)
            if t < obj.hidden_until or rng.random() < miss_rate:
                continue
            percepts.append(observe(obj, t, rng))
        if rng.random() < spurious_rate:
            n_spurious += 1
            percepts.append(spurious(t, rng, f"spurious-{n_spurious}"))
        order = rng.permutation(len(percepts))
        truth = {o.ident: {"position": o.position.round(5).tolist(),
                           "visible": bool(t >= o.hidden_until)} for o in objects}
        frames.append(PerceptFrame(f, t, [percepts[i] for i in order], {"objects": truth}))
    return frames


def _move(obj: TrueObject, objects: list[TrueObject], t: float, dt: float,
          rng: np.random.Generator, move_rate: float, occlusion_rate: float) -> None:
    if obj.target is None and t >= obj.hidden_until and rng.random() < move_rate * dt:
        others = [o.position for o in objects if o is not obj]
        obj.target = _free_spot(rng, others, 0.14)
        obj.speed = float(rng.uniform(0.05, 0.25))
    if occlusion_rate and t >= obj.hidden_until and rng.random() < occlusion_rate * dt:
        obj.hidden_until = t + float(rng.uniform(1.0, 4.0))
        if rng.random() < 0.3:  # carried a little while hidden
            shift = rng.normal(0.0, 0.04, 2)
            obj.position[:2] = np.clip(obj.position[:2] + shift, TABLE[:, 0], TABLE[:, 1])
    if obj.target is not None:
        d = obj.target - obj.position[:2]
        dist = float(np.linalg.norm(d))
        step = obj.speed * dt
        if dist <= step:
            obj.position[:2] = obj.target
            obj.target = None
        else:
            obj.position[:2] += d / dist * step
