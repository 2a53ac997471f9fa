"""The DDC particle filter seen from Python.

Prolog (``prolog/ddc.pl``) owns the semantics: the particles live there between steps and one
call per step samples the transition, weights every particle and, by the rules of
``prolog/ddc/filter/ddc_weights.pl`` (the same as the swipl belief's, ``ddc_belief.pl``),
normalises the weights, adds the step's likelihood to the running log-likelihood, computes the
effective sample size and says whether to resample; the ancestors are picked there too. Python
holds the normalised log weights between steps (a numpy array it hands back at each step), the
numpy ``Generator`` seeded from ``seed`` whose uniforms the resampling takes, the running
log-likelihood, and timing.

Example::

    from bridge import Filter, terms
    f = Filter("prolog/examples/filter/wumpus.pl", particles=2000, seed=7)
    f.step(["observation(up) ~= wall", terms.observation("right", "free")],
           actions=[terms.action("null")])
    f.probability("maze(0,1):t ~= wall")          # ~0.857
    f.distribution("maze(0,1):t")                 # [(0.857, 'wall'), (0.143, 'free')]

Inputs go to Prolog as text (see :mod:`bridge.terms` for the Python -> Prolog mapping); each
text is parsed on the Prolog side with ``term_string/3`` in the operator context of module
``ddc`` and must be ground. Values read back from particles (``values``, ``distribution``,
``samples``, ``mean``) map Prolog -> Python as: numbers -> ``int``/``float``; atoms and strings
-> ``str``; comma terms ``(A,B,C)`` -> ``tuple``; lists -> ``list``; any other compound -> its
text (``"pos(ball_1)"``); a particle in which the goal has no solution -> ``None`` (the atom
``none`` is the string ``"none"``, a value like any other).

Zero-weight frames: if every particle's weight becomes 0 (log weight -inf or NaN) the filter does
not die. It warns (:class:`ZeroWeightWarning` and ``logging``), counts the event in
``zero_weight_events``, undoes the step in Prolog (``filter_undo``) and keeps the pre-step
particles with uniform weights. The frame is consumed (``frames`` counts it, the next ``step``
takes the next frame) but the filter's ``time`` does not advance, because the particles kept are
those of time t; ``log_likelihood`` does not include the frame (it would be -inf).

Bad input (a term that does not parse, a non-ground observation, an observation no clause
applies to, any other Prolog error in a step) raises :class:`FilterError` naming the step, the
item and the cause; if the engine had already advanced, the step is undone, so the filter stays
usable with everything it held.

Renaming and reweighting: ``rename`` renames constants inside chosen particles (their worlds go
on as if the names had always been so: data association per particle), ``reweight`` multiplies
the weights by factors the caller computed (an importance correction), and ``particle_data``
holds arrays of N rows that follow the particles through every resampling.

Threads: a filter may be made, stepped, queried and closed in any thread (its particles live in
a Prolog engine of their own that the calling thread runs for each call); calls on one filter
are taken one at a time. Its program is compiled into a module of its own: loading the file
again (:func:`bridge.load`, another filter) does not change a live filter. Every Prolog error
raised in any thread is a :class:`FilterError`.
"""

from __future__ import annotations

import logging
import math
import os
import threading
import time as _time
import warnings
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import wraps
from pathlib import Path
from typing import Any, Concatenate, Literal, ParamSpec, TypeVar

import numpy as np

from bridge import prolog
from bridge.engines import ENGINES, Engine
from bridge.errors import DDCError, prefixed
from bridge.particle_data import ParticleData
from bridge.prolog import OUT
from bridge.terms import Compound, Text, item_text, to_term
from bridge.threads import DEFAULT_THREADS

logger = logging.getLogger(__name__)

_TEMPLATE_VAR = "DdcBridgeValue__"
# The widest row the batched engine's column library holds (MAX_K in
# prolog/ddc/batch/c/ddc_columns.c): samples() lends it a buffer of this many floats per particle.
_MAX_ROW_WIDTH = 16


#: A step or query the filter could not carry out (the filter itself is unchanged): the base
#: class of the DDC system's errors, :class:`bridge.errors.DDCError`, whose subclasses say why
FilterError = DDCError


class ZeroWeightWarning(RuntimeWarning):
    """Every particle got weight 0 in a step; the pre-step particles were kept."""


#: The resampling schemes (``resample_indices/4`` in prolog/ddc/filter/ddc_weights.pl)
Resampling = Literal["systematic", "multinomial", "residual"]
SCHEMES: tuple[str, ...] = ("multinomial", "residual", "systematic")
#: The rules of the weights and resampling (called through the adapter, as the helper's)
_WEIGHTS_MODULE = "ddc_weights"


# --------------------------------------------------------------------------------------------
# The Prolog side of the bridge: prolog/ddc/filter/ddc_bridge.pl, loaded once, parses the texts,
# turns errors into messages and particle values into janus-friendly data; its predicates are
# called through the one adapter, bridge.prolog.

#: The engine file loaded before the first filter is made (tests may point it elsewhere).
ENGINE: Path = prolog.PROLOG_DIR / "ddc.pl"
#: The bridge's Prolog helper module (its predicates are called module-qualified).
HELPER: Path = prolog.PROLOG_DIR / "ddc/filter/ddc_bridge.pl"
_HELPER_MODULE = "ddc_bridge"

_helper_lock = threading.Lock()
_helper_loaded = False


def _ensure_engine() -> None:
    global _helper_loaded
    with _helper_lock:
        if _helper_loaded:
            return
        engine = ENGINE
        if not engine.exists():
            raise FilterError(f"{engine}: the DDC engine is missing")
        prolog.ensure_loaded(engine)
        # (no imports: the helper's predicates stay out of user)
        prolog.ensure_loaded(HELPER, imports=False)
        _helper_loaded = True


def call_helper(name: str, /, **arguments: Any) -> dict[str, Any]:
    """Call the predicate ``name`` of prolog/ddc/filter/ddc_bridge.pl once (the engine and the
    helper are loaded first) through :func:`bridge.prolog.call`: ``arguments`` by name, in
    order, :data:`bridge.prolog.OUT` for an output; a Prolog error or failure is a
    :class:`FilterError` (the subclass of its cause)."""
    _ensure_engine()
    return _call(name, **arguments)


def _call(name: str, /, **arguments: Any) -> dict[str, Any]:
    """Call the helper's predicate ``name`` once, in whatever thread calls (the particles live
    in a Prolog engine of their own, which any thread may run: ``filter_new/5``)."""
    return prolog.call(f"{_HELPER_MODULE}:{name}", **arguments)


# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class StepResult:
    """What one :meth:`Filter.step` did."""

    time: int  #: the filter's time after the step
    frame: int  #: 1-based number of the frame consumed
    ess: float  #: effective sample size after weighting, before any resampling
    resampled: bool
    log_likelihood: float  #: log of the weighted mean likelihood of this frame (-inf if zero)
    zero_weight: bool  #: every particle got weight 0; the pre-step particles were kept
    seconds: float  #: wall time of the whole step
    prolog_seconds: float  #: of which in the Prolog call (sampling and weighting)


_P = ParamSpec("_P")
_R = TypeVar("_R")


def _locked(method: Callable[Concatenate[Filter, _P], _R]) -> Callable[Concatenate[Filter, _P], _R]:
    """``method`` under the filter's lock: a filter used from several threads runs one step or
    query at a time, each whole (a step is several calls into Prolog and numpy updates)."""

    @wraps(method)
    def call(self: Filter, *args: _P.args, **kwargs: _P.kwargs) -> _R:
        with self._lock:
            return method(self, *args, **kwargs)

    return call


def _a(name: str) -> str:
    """``a list``, ``an int``."""
    return f"{'an' if name[:1] in 'aeiou' else 'a'} {name}"


def _as_term_text(value: Any) -> str:
    return item_text(value) if isinstance(value, str) else to_term(value)


class Filter:
    """A DDC particle filter: particles in Prolog, weights by the rules of ddc_weights.pl."""

    def __init__(
        self,
        program_path: str | os.PathLike[str],
        particles: int = 1000,
        seed: int | None = None,
        resample_threshold: float = 0.9,
        resampling: Resampling = "systematic",
        share: bool = True,
        threads: int = DEFAULT_THREADS,
        engine: Engine = "auto",
    ) -> None:
        """``share=False`` computes every value in every particle (see "Shared values" in
        ``prolog/ddc.pl``): the same particles, bit for bit, only slower; for comparison.

        ``threads``: a step's particles (after the first) are split into that many groups,
        stepped at the same time by Prolog threads, each with its own random stream seeded from
        the filter's (``filter_new/5``'s ``threads`` option). The particles depend on ``seed``
        and ``threads``, not on the machine; ``threads=1`` steps them one after the other.
        The worker threads stay for the life of the process, and SWI-Prolog does not survive a
        ``fork`` of a process with Prolog threads: after stepping with ``threads > 1``, start
        subprocesses with multiprocessing's ``"spawn"`` or ``"forkserver"`` method (a forked
        child hangs in its first Prolog call).

        ``engine``: ``"per_particle"`` proves each particle's clauses one particle at a time;
        ``"batched"`` evaluates each clause once for a batch of particles
        (``prolog/ddc/batch/ddc_batch.pl``; a program outside its fragment raises
        :class:`FilterError` naming the clause); ``"auto"`` takes the batched engine when the
        program is in its fragment. The two give other particles from the same seed (the draws
        come in another order); the batched one ignores ``share``. After construction ``engine``
        is the one that steps the particles (auto resolved)."""
        for name, value in (("particles", particles), ("threads", threads)):
            # an integer, not a bool, float or string that int() would quietly convert
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
                raise TypeError(f"{name} must be an integer, got {value!r}")
            if value < 1:
                raise ValueError(f"{name} must be >= 1, got {value}")
        if seed is not None and (isinstance(seed, bool) or not isinstance(seed, (int, np.integer))):
            raise TypeError(f"seed must be an integer or None, got {seed!r}")
        if not 0.0 <= float(resample_threshold) <= 1.0:
            raise ValueError(f"resample_threshold must be in [0, 1], got {resample_threshold}")
        if engine not in ENGINES:
            raise ValueError(f"unknown engine {engine!r}; use one of {list(ENGINES)}")
        if resampling not in SCHEMES:
            raise ValueError(
                f"unknown resampling scheme {resampling!r}; use one of {list(SCHEMES)}"
            )
        path = Path(program_path)
        if not path.is_file():
            raise FileNotFoundError(f"{path}: no such DDC program")
        self.program_path = path.resolve()
        self.particles = int(particles)
        self.seed = int(seed) if seed is not None else int(np.random.SeedSequence().entropy % 2**31)
        self.resample_threshold = float(resample_threshold)
        self.resampling: Resampling = resampling
        self.share = bool(share)
        self.threads = int(threads)
        self.engine: str = engine
        #: the uniforms of the resampling come from this stream (``resample_draws/3`` says how
        #: many each resampling takes)
        self._rng = np.random.default_rng(self.seed)
        self._log_weights = np.empty(0)  # (uniform once the particles are made)
        self._uniform = True
        self._ess = math.nan
        self.log_likelihood = 0.0
        self.zero_weight_events = 0
        self.frames = 0
        self.resample_count = 0
        self.step_seconds: list[float] = []  #: wall time of every step
        self.step_prolog_seconds: list[float] = []  #: of which in the Prolog step call
        self.last_step: StepResult | None = None
        #: name -> array with first dimension N, resampled with the particles (see
        #: :class:`bridge.particle_data.ParticleData`)
        self.particle_data = ParticleData(self.particles)
        self._key: str | None = None
        #: one call on the filter at a time (a step is several Prolog calls)
        self._lock = threading.RLock()
        _ensure_engine()
        try:
            result = _call("bridge_new", P=str(self.program_path), N=self.particles,
                           S=self.seed, Sh="true" if self.share else "false", Th=self.threads,
                           E=engine, K=OUT, Used=OUT)
        except DDCError as error:  # (usually "file:line: cause" already)
            text = str(error)
            if str(path) not in text and str(self.program_path) not in text:
                raise prefixed(error, f"{self.program_path}: ") from None
            raise
        self._key = str(result["K"])
        #: the engine that steps the particles: "batched" or "per_particle" (``auto`` resolved)
        self.engine = str(result["Used"])
        #: the log weights 1/N (``weights_uniform/2``), held while the weights are uniform
        self._uniform_log_weights = np.asarray(
            prolog.call(f"{_WEIGHTS_MODULE}:weights_uniform", N=self.particles, LW=OUT)["LW"],
            dtype=float)
        self._set_weights([])

    # -- life cycle ---------------------------------------------------------------------------
    def close(self) -> None:
        """Free the particles held in Prolog (also done when the object is collected)."""
        with self._lock:
            if self._key is not None:
                key, self._key = self._key, None
                _call("bridge_free", K=key)

    def __enter__(self) -> Filter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __del__(self) -> None:  # pragma: no cover - best effort at garbage collection
        try:
            self.close()
        except Exception:
            pass

    @property
    def handle(self) -> str:
        """The engine's name of the filter (the text of the atom ``filter_new/5`` gave), for
        calling the Prolog filter predicates on it directly; valid in every thread."""
        return self._handle()

    def _handle(self) -> str:
        if self._key is None:
            raise FilterError("this filter was closed")
        return self._key

    # -- state --------------------------------------------------------------------------------
    @property
    @_locked
    def time(self) -> int:
        """The time step of the particles (0 after construction, +1 per non-zero-weight step)."""
        return int(_call("bridge_time", K=self._handle(), T=OUT)["T"])

    @property
    def log_weights(self) -> np.ndarray:
        """Normalised log weights (a copy)."""
        return self._log_weights.copy()

    @property
    def weights(self) -> np.ndarray:
        """Normalised weights (a copy; they sum to 1)."""
        return np.exp(self._log_weights)

    @property
    def ess(self) -> float:
        """Effective sample size of the current weights (N right after resampling)."""
        return self._ess

    def _set_weights(self, log_weights: list[float], ess: float | None = None) -> None:
        """The normalised log weights Prolog gave (``[]``: uniform) and their ESS (N for
        uniform weights)."""
        self._uniform = not log_weights
        if self._uniform:
            self._log_weights = self._uniform_log_weights
            self._ess = float(self.particles)
        else:
            self._log_weights = np.asarray(log_weights, dtype=float)
            if ess is not None:
                self._ess = float(ess)

    # -- stepping -----------------------------------------------------------------------------
    @_locked
    def step(
        self, observations: Iterable[Any] = (), actions: Iterable[Any] = (),
        strata: np.ndarray | None = None, keep: int = 1,
    ) -> StepResult:
        """Advance t -> t+1 with the frame's observations and actions; weight; maybe resample.

        ``strata`` (one integer per particle, or None): a resampling in this step resamples
        each stratum on its own, keeping its mass with at least ``keep`` particles
        (``resample_preserving/6`` in prolog/ddc/filter/ddc_weights.pl: mixture resampling,
        for hypotheses of small weight that later evidence may confirm); the weights after it
        are then not uniform."""
        if strata is not None:
            strata = np.asarray(strata)
            if strata.shape != (self.particles,) or not np.issubdtype(strata.dtype, np.integer):
                raise ValueError(f"strata must be {self.particles} integers, one per particle")
        if isinstance(keep, bool) or not isinstance(keep, (int, np.integer)) or keep < 1:
            raise ValueError(f"keep must be a positive integer, got {keep!r}")
        started = _time.perf_counter()
        key = self._handle()
        obs_texts = self._texts("observation", observations)
        act_texts = self._texts("action", actions)
        time_before = self.time
        call_started = _time.perf_counter()
        # The uniforms a resampling may take (1 for systematic, N for the other schemes) are
        # drawn before the call; the stream then moves on by those it took only.
        stream = self._rng.bit_generator.state
        uniforms = self._rng.random(1 if self.resampling == "systematic" else self.particles)
        self._rng.bit_generator.state = stream
        try:
            result = _call("bridge_weighted_step", K=key, O=obs_texts, A=act_texts,
                           LW0=[] if self._uniform else self._log_weights.tolist(),
                           Th=self.resample_threshold, Sch=self.resampling,
                           St=[] if strata is None else strata.tolist(), Kp=int(keep),
                           Us=uniforms.tolist(), LW=OUT, Inc=OUT, ESS=OUT, Inf=OUT,
                           Drawn=OUT, Is=OUT)
        except Exception as exc:  # (a DDCError, or a value janus could not convert)
            self._restore(time_before)
            raise prefixed(exc, f"{self.program_path.name}: step {self.frames + 1}: ") from None
        prolog_seconds = _time.perf_counter() - call_started
        frame = self.frames + 1
        self.frames = frame
        if result["Inf"] in (True, "true"):
            logger.warning("step %d: infinite likelihoods; keeping only those particles", frame)
        increment = float(result["Inc"])
        self._set_weights(result["LW"])
        if not math.isfinite(increment):  # (the step was undone, the weights made uniform)
            return self._zero_weight(frame, started, prolog_seconds)
        self.log_likelihood += increment
        ess = float(result["ESS"])
        resampled = result["Is"] != "none"
        if resampled:
            self._rng.random(int(result["Drawn"]))
            self.particle_data.resample(np.asarray(result["Is"], dtype=np.int64))
            self.resample_count += 1
            if not self._uniform:  # (a preserving resampling: its weights' own ESS)
                self._ess = float(1.0 / np.sum(np.exp(2.0 * self._log_weights)))
        else:
            self._ess = ess
        return self._finish(
            StepResult(self.time, frame, ess, resampled, increment, False, 0.0, prolog_seconds),
            started,
        )

    # -- renaming and reweighting -------------------------------------------------------------
    @_locked
    def rename(
        self,
        mapping: Mapping[str, str],
        particles: np.ndarray | Sequence[int] | None = None,
    ) -> None:
        """In the given particles, the constants ``old`` of ``mapping`` are named ``mapping[old]``.

        ``mapping`` maps names (atoms) to names and must be a permutation of its keys
        (``{"mug_1": "mug_2", "mug_2": "mug_1"}``; a name mapped to itself is allowed).
        ``particles``: 0-based indices (repeats ignored), a boolean mask of N, or None for every
        particle. In each of them every value it holds (of t, of t-1 for the next step's ``:t``
        reads, and untimed) has each old name replaced by its new one, in the variable's
        arguments (``pos(mug_1)``) and in the value (``mug_1``); the next step goes on as if the
        names had always been so in those particles. The program and the step's facts are not
        renamed; the other particles and the weights are unchanged (see ``filter_rename/3`` in
        ``prolog/ddc/filter/ddc_filter.pl``, and "Renaming constants in particles" in
        docs/filter.md). A bad mapping or index raises :class:`FilterError` naming it; the filter
        is unchanged.
        """
        key = self._handle()
        if not isinstance(mapping, Mapping):
            raise FilterError(f"rename: the mapping must map old names to new names, "
                              f"got {mapping!r}")
        olds, news = list(mapping.keys()), list(mapping.values())
        for name in olds + news:
            if not isinstance(name, str):
                raise FilterError(f"rename: names are strings, got {name!r}")
        if len(set(news)) != len(news) or set(news) != set(olds):
            raise FilterError(f"rename: the new names {sorted(news)} are not a permutation of "
                              f"the old names {sorted(olds)}")
        indices = self._particle_indices("rename", particles)
        if not olds or indices.size == 0:
            return
        try:
            _call("bridge_rename", K=key, O=olds, N=news, I=(indices + 1).tolist())
        except DDCError as error:
            raise prefixed(error, "rename: ") from None

    def _particle_indices(
        self, what: str, particles: np.ndarray | Sequence[int] | None
    ) -> np.ndarray:
        """0-based particle indices (int64) of ``particles``: indices, a boolean mask of N, or
        None for all; a FilterError names a bad one."""
        if particles is None:
            return np.arange(self.particles, dtype=np.int64)
        array = np.asarray(particles)
        if array.dtype == bool:
            if array.shape != (self.particles,):
                raise FilterError(f"{what}: a particle mask must have shape "
                                  f"({self.particles},), got {array.shape}")
            return np.flatnonzero(array).astype(np.int64)
        if array.size == 0:
            return np.empty(0, dtype=np.int64)
        if array.ndim != 1 or array.dtype.kind not in "iu":
            raise FilterError(f"{what}: particles must be a 1-D sequence of integer indices, "
                              f"got {particles!r}")
        outside = array[(array < 0) | (array >= self.particles)]
        if outside.size:
            raise FilterError(f"{what}: particle index {int(outside[0])} is outside "
                              f"0..{self.particles - 1}")
        return array.astype(np.int64)

    @_locked
    def reweight(self, log_factors: np.ndarray) -> None:
        """Multiply each particle's weight by ``exp(log_factors[i])`` and renormalise.

        For an importance correction a caller computes itself (prior / proposal of a choice it
        made per particle, e.g. the hypothesis behind a :meth:`rename`). ``log_factors``: shape
        (N,), each finite or -inf, not all -inf. The log of the weighted mean factor is added to
        :attr:`log_likelihood` (0 in expectation for a prior / proposal ratio). The ESS
        (:attr:`ess`) sees the new weights at once; whether to resample is decided only in
        :meth:`step`, after the step's own weighting, so a reweighted filter is resampled (if
        its ESS is then below the threshold) at the next step. A bad array, or factors that
        leave no particle with weight, raise :class:`FilterError` and change nothing.
        """
        self._handle()
        try:
            factors = np.asarray(log_factors, dtype=float)
        except (TypeError, ValueError) as exc:
            raise FilterError(f"reweight: log factors must be numbers: {exc}") from None
        if factors.shape != (self.particles,):
            raise FilterError(f"reweight: log factors must have shape ({self.particles},), "
                              f"got {factors.shape}")
        bad = np.flatnonzero(np.isnan(factors) | np.isposinf(factors))
        if bad.size:
            raise FilterError(f"reweight: log factor {int(bad[0])} is {factors[bad[0]]}; "
                              "each must be finite or -inf")
        if np.isneginf(factors).all():
            raise FilterError("reweight: every log factor is -inf")
        found = prolog.call(f"{_WEIGHTS_MODULE}:weights_reweight",
                            LW0=self._log_weights.tolist(), F=factors.tolist(), LW=OUT,
                            Inc=OUT, ESS=OUT)
        increment = float(found["Inc"])
        if not math.isfinite(increment):
            raise FilterError("reweight: the factors give weight 0 to every particle that "
                              "has weight")
        self._set_weights(found["LW"], found["ESS"])
        self.log_likelihood += increment

    def _texts(self, kind: str, items: Iterable[Any]) -> list[str]:
        """The Prolog texts of a step's observations or actions: one term (Prolog text, a
        ``Compound`` or ``Text``) or a list of them; anything else is a FilterError naming the
        item (a number or a list is no fact, a dict's keys are not meant as facts)."""
        if isinstance(items, str | Compound | Text):
            items = [items]
        if isinstance(items, Mapping | set | frozenset | bytes | bytearray) or not isinstance(
                items, Iterable):
            raise FilterError(f"{kind}s: {items!r} is {_a(type(items).__name__)}; give a list of "
                              "terms (Prolog text such as 'observed(ball_1)', or bridge.terms "
                              "values such as terms.observation(...))")
        texts = []
        for i, item in enumerate(items, start=1):
            if not isinstance(item, str | Compound | Text):
                raise FilterError(f"{kind} {i} ({item!r}): {_a(type(item).__name__)} is not a "
                                  "term; give Prolog text or a bridge.terms value (fact, "
                                  "observation, action)")
            try:
                texts.append(_as_term_text(item))
            except (TypeError, ValueError) as exc:
                raise FilterError(f"{kind} {i} ({item!r}): {exc}") from None
        return texts

    def _restore(self, time_before: int) -> None:
        try:
            if self.time != time_before:
                _call("bridge_undo", K=self._handle())
        except Exception as exc:  # pragma: no cover - the engine refused to undo
            logger.error("could not undo a failed step: %s", exc)

    def _zero_weight(self, frame: int, started: float, prolog_seconds: float) -> StepResult:
        self.zero_weight_events += 1
        message = (
            f"{self.program_path.name}: step {frame}: every particle got weight 0; "
            f"kept the {self.particles} pre-step particles with uniform weights "
            f"(event {self.zero_weight_events})"
        )
        logger.warning(message)
        warnings.warn(message, ZeroWeightWarning, stacklevel=4)  # the caller of step
        # (the step was undone and the weights made uniform by bridge_weighted_step/15)
        return self._finish(
            StepResult(self.time, frame, 0.0, False, -math.inf, True, 0.0, prolog_seconds),
            started,
        )

    def _finish(self, result: StepResult, started: float) -> StepResult:
        seconds = _time.perf_counter() - started
        result = StepResult(**{**result.__dict__, "seconds": seconds})
        self.step_seconds.append(seconds)
        self.step_prolog_seconds.append(result.prolog_seconds)
        self.last_step = result
        return result

    # -- queries ------------------------------------------------------------------------------
    @_locked
    def holds(self, goal: Any) -> np.ndarray:
        """Per particle, 1 if ``goal`` holds in it, else 0 (int8 array of N)."""
        key = self._handle()
        try:
            result = _call("bridge_holds", K=key, G=_as_term_text(goal), F=OUT)
        except DDCError as error:
            raise prefixed(error, "query: ") from None
        return np.asarray(result["F"], dtype=np.int8)

    @_locked
    def probability(self, goal: Any) -> float:
        """Weighted fraction of particles in which ``goal`` holds."""
        return float(np.dot(self.weights, self.holds(goal)))

    @_locked
    def values(self, template: Any, goal: Any) -> list[Any]:
        """Per particle, ``template`` at the first solution of ``goal`` (None: no solution)."""
        return list(self._query("bridge_values", template, goal, V=OUT)["V"])

    def _query(self, name: str, template: Any, goal: Any, **rest: Any) -> dict[str, Any]:
        """One bridge query ``name`` over the particles: the filter as ``K``, ``template`` at
        the first solution of ``goal`` (as a pair, ``P``), then the arguments ``rest``; an
        error names the query."""
        template_text = _as_term_text(template)
        goal_text = _as_term_text(goal)
        key = self._handle()
        try:
            return _call(name, K=key, P=f"ddc_bridge_pair(({template_text}),({goal_text}))",
                         **rest)
        except DDCError as error:
            raise prefixed(error, f"query {template_text!r} for {goal_text!r}: ") from None

    @staticmethod
    def _template_goal(term: Any, goal: Any | None) -> tuple[Any, Any]:
        """A random variable's values (``goal`` None) or a template over a goal."""
        if goal is None:
            return _TEMPLATE_VAR, f"({_as_term_text(term)}) ~= {_TEMPLATE_VAR}"
        return term, goal

    def _term_values(self, term: Any, goal: Any | None) -> list[Any]:
        return self.values(*self._template_goal(term, goal))

    @_locked
    def distribution(self, term: Any, goal: Any | None = None) -> list[tuple[float, Any]]:
        """``[(p, value), ...]`` most probable first.

        With ``goal`` None, ``term`` is a random variable (``"maze(0,1):t"``) and the values are
        those of ``term ~= V``; otherwise ``term`` is a template over the first solution of
        ``goal``. Particles in which the variable is undefined (the goal has no solution) count
        for no value, so the probabilities then sum to less than 1.
        """
        values = self._term_values(term, goal)
        weights = self.weights
        index: dict[Any, int] = {}
        keys: list[Any] = []
        codes = np.empty(self.particles, dtype=np.int64)
        for i, value in enumerate(values):
            key = _hashable(value)
            if key not in index:
                index[key] = len(keys)
                keys.append(value)
            codes[i] = index[key]
        mass = np.bincount(codes, weights=weights, minlength=len(keys))
        pairs = [(float(mass[j]), keys[j]) for j in range(len(keys)) if keys[j] is not None]
        return sorted(pairs, key=lambda pv: (-pv[0], repr(pv[1])))

    @_locked
    def samples(self, term: Any, goal: Any | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(values, weights): N rows of values (float, NaN where undefined, when numeric)."""
        # numbers or k-tuples of numbers come flattened from Prolog (no per-particle Python
        # work); other values as values() gives them
        # (the floats copied into `buffer` by the column library where it is loaded: no
        # conversion of each float by janus; else a list.  The buffer's address and size are
        # _-named: janus gives back no such binding.)
        buffer = np.empty(self.particles * _MAX_ROW_WIDTH, dtype=float)
        result = self._query("bridge_rows_into", *self._template_goal(term, goal),
                             _A=buffer.ctypes.data, _C=buffer.size, W=OUT, F=OUT, V=OUT)
        width = int(result["W"])
        if width == 0:
            return _as_array(result["V"]), self.weights
        floats = result["F"]
        flat = (buffer[:floats].copy() if isinstance(floats, int)
                else np.asarray(floats, dtype=float))
        return (flat if width == 1 else flat.reshape(self.particles, width)), self.weights

    @_locked
    def indices(self, template: Any, goal: Any, atoms: Sequence[str]) -> np.ndarray:
        """Per particle, the position in ``atoms`` of ``template`` at the first solution of
        ``goal`` whose ``template`` is one of ``atoms``; -1 where there is none (int64 array
        of N). Which of a few constants each particle answers, e.g. which occluder hides an
        object: ``indices("O", "occluded_by(ball_1, O):t", ["mug_1", "mug_2"])``."""
        # (copied as doubles into `buffer` by the column library where it is loaded, NaN
        # for none: no conversion of a value per particle; else a list of integers)
        buffer = np.empty(self.particles, dtype=float)
        result = self._query("bridge_indices_into", template, goal,
                             L=[str(a) for a in atoms], _A=buffer.ctypes.data, _C=buffer.size,
                             I=OUT)
        found = result["I"]
        if isinstance(found, int):
            values = buffer[:found]
            out = np.full(self.particles, -1, dtype=np.int64)
            known = ~np.isnan(values)
            out[known] = values[known].astype(np.int64)
            return out
        return np.asarray(found, dtype=np.int64).reshape(self.particles)

    @_locked
    def mean(self, term: Any, goal: Any | None = None) -> tuple[Any, Any]:
        """Weighted (mean, covariance) of a numeric or tuple variable over the particles where
        it is defined: floats for a number, a (k,) and a (k, k) array for a k-tuple."""
        values, weights = self.samples(term, goal)
        if values.dtype == object:
            raise FilterError(f"mean of {_as_term_text(term)!r}: the values are not numeric")
        matrix = values.reshape(self.particles, -1)
        defined = ~np.isnan(matrix).any(axis=1)
        total = float(weights[defined].sum())
        if not defined.any() or total <= 0.0:
            raise FilterError(f"mean of {_as_term_text(term)!r}: undefined in every particle")
        w = weights[defined] / total
        x = matrix[defined]
        mean = w @ x
        centred = x - mean
        cov = (centred * w[:, None]).T @ centred
        if values.ndim == 1:
            return float(mean[0]), float(cov[0, 0])
        return mean, cov

    def __repr__(self) -> str:
        state = "closed" if self._key is None else f"t={self.time}"
        return (
            f"Filter({self.program_path.name!r}, particles={self.particles}, seed={self.seed}, "
            f"{state}, ess={self.ess:.1f})"
        )


def _hashable(value: Any) -> Any:
    if isinstance(value, list):
        return ("__list__", tuple(_hashable(v) for v in value))
    if isinstance(value, tuple):
        return tuple(_hashable(v) for v in value)
    return value


def _is_number(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _as_array(values: Sequence[Any]) -> np.ndarray:
    present = [v for v in values if v is not None]
    if present and all(_is_number(v) for v in present):
        return np.array([np.nan if v is None else float(v) for v in values], dtype=float)
    if present and all(isinstance(v, tuple) for v in present):
        width = len(present[0])
        if all(len(v) == width and all(_is_number(x) for x in v) for v in present):
            out = np.full((len(values), width), np.nan)
            for i, v in enumerate(values):
                if v is not None:
                    out[i] = v
            return out
    out = np.empty(len(values), dtype=object)
    out[:] = list(values)
    return out
