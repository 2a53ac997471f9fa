"""``anchoring collect``: play episodes through perception and anchoring and write the learner's
input, before/after facts of occlusions (:mod:`probanchor.learning.occlusion_data`).

Episodes are scenario files (the shipped ones, or any) and generated occlusion games
(:func:`probanchor.tabletop.generate.occlusion_game`). Each is perceived once (the percept stream is
cached, as ``anchoring evaluate`` caches its streams) and anchored with anchoring alone; the
episodes are independent jobs (:mod:`probanchor.jobs`): on worker processes (spawned: a forked child
of a process that has janus loaded can hang) or on a Ray cluster, combined in the order of the
episodes whichever finished first. The data file is written only once every episode is done
(atomically), and an empty collection (no occlusion happened) is an error that writes nothing.
Beside the data file, ``DATA.motion.json`` holds the samples the theory's motion and carrying
parameters are fitted from (:mod:`probanchor.learning.motion_samples`), and ``DATA.release.pl``
the data of when a hand lets go of what it carries (:mod:`probanchor.learning.release_data`).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from probanchor.ddclearn.files import write_atomically
from probanchor.jobs import Job, parse_cluster, raise_failures, run_jobs
from probanchor.learning.motion_hindsight import hindsight_samples
from probanchor.learning.motion_samples import MotionSamples, episode_samples, samples_path
from probanchor.learning.occlusion_data import Collection, LabelOptions, data_text, episode_facts
from probanchor.learning.occlusion_data import hindsight_agreement as _agreement
from probanchor.learning.release_data import release_path, release_text
from probanchor.loop.naming import symbol_atom

__all__ = ["CollectError", "CollectOptions", "CollectReport", "collect", "game_files"]


class CollectError(ValueError):
    """A collection that cannot be written (names the cause)."""


@dataclass
class CollectOptions:
    """What to collect and where.

    Parameters
    ----------
    out : Path
        The data file to write.
    scenarios : sequence of Path
        Scenario files to play.
    games : int, default=0
        Generated occlusion games to play, seeds ``seed``, ``seed+1``, ...
    seed : int, default=0
        The first game's seed; also the sensor-noise seed of every episode.
    labels : LabelOptions
        Ground truth or hindsight labels.
    cache : Path
        Where percept streams and generated games are kept.
    jobs : int, default=1
        Worker processes (or the CPUs of a local Ray).
    cluster : str, optional
        Where the episodes run: None or ``"local"``, ``"ray"``, ``"auto"``,
        ``"ray://HOST:PORT"`` (:func:`probanchor.jobs.parse_cluster`).
    command : str, optional
        The command line, recorded in the data file.
    progress : bool, default=False
        Draw one progress bar over the episodes.
    """

    out: Path
    scenarios: Sequence[Path] = ()
    games: int = 0
    seed: int = 0
    labels: LabelOptions = field(default_factory=LabelOptions)
    cache: Path = Path("out/collect")
    jobs: int = 1
    cluster: str | None = None
    command: str | None = None
    progress: bool = False


@dataclass
class CollectReport:
    """What a collection did: counts, seconds per stage, agreement of hindsight with truth."""

    episodes: int
    pairs: int
    positive: float
    seconds_perception: float
    seconds_facts: float
    seconds_total: float
    agreement: float | None
    agreement_pairs: int
    per_episode: dict[str, int]
    out: Path


def game_files(folder: Path, games: int, first_seed: int) -> list[Path]:
    """``games`` occlusion games (YAML in ``folder``), seeds ``first_seed`` on.

    A game file that is not the game the generator makes now (written by an earlier version)
    is written again, and the percept streams cached beside ``folder`` (``../percepts``) for
    it are removed: they are of the old game."""
    from probanchor.tabletop.generate import occlusion_game

    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for seed in range(first_seed, first_seed + games):
        path = folder / f"occlusion_game_{seed:03d}.yaml"
        text = occlusion_game(seed).to_yaml()
        if not path.exists() or path.read_text(encoding="utf-8") != text:
            for stale in (folder.parent / "percepts").glob(f"{path.stem}_seed*.jsonl"):
                stale.unlink()
            path.write_text(text, encoding="utf-8")
        paths.append(path)
    return paths


def _episode(scenario: Path, seed: int, cache: Path, number: int,
             labels: LabelOptions, collection: str
             ) -> tuple[Collection, float, float, float, int, MotionSamples]:
    """One episode (``number`` of the collection named ``collection``) in a worker: its
    facts, seconds (perception, facts), hindsight agreement, the samples of the motion
    parameters."""
    from probanchor.learning.experience import play
    from probanchor.loop.sources import percept_stream
    from probanchor.percepts import read_percepts

    started = time.perf_counter()
    stream = percept_stream(scenario, seed, cache)
    perceived = time.perf_counter()
    episode = play(read_percepts(stream), scenario.stem)
    part = Collection()
    episode_facts(episode, number, labels, part, collection)
    agree, n = _agreement(episode, labels)
    # (collected in hindsight, the samples read no simulator truth either)
    samples = (hindsight_samples(episode) if labels.source == "hindsight"
               else episode_samples(episode))
    done = time.perf_counter()
    return part, perceived - started, done - perceived, agree, n, samples


def collect(options: CollectOptions,
            progress: Callable[[str], None] | None = None) -> CollectReport:
    """Play every episode, write the data file, return the report.

    Parameters
    ----------
    options : CollectOptions
        What to collect, where to run it and where to write it.
    progress : callable, optional
        Called with one line per episode, in the order of the episodes, once all are done.

    Returns
    -------
    CollectReport

    Raises
    ------
    CollectError
        No episode given, or no data point (no occlusion happened in any episode).
    jobs.JobsFailed
        Some episodes failed (each named with its cause); nothing is written, and the percept
        streams of the finished ones stay cached for the next try.
    """
    started = time.perf_counter()
    cluster = parse_cluster(options.cluster, options.jobs)
    scenarios = [Path(p) for p in options.scenarios]
    for p in scenarios:
        if not p.is_file():
            raise CollectError(f"{p}: no such scenario file")
    if options.games:
        scenarios += game_files(options.cache / "games", options.games, options.seed)
    if not scenarios:
        raise CollectError("nothing to collect: give scenario files or --games K")
    streams = options.cache / "percepts"
    # (the data's constants carry the collection's name: data files collected apart can be
    # learned from together)
    name = symbol_atom(options.out.stem)
    work = [Job(s.stem, _episode, (s, options.seed, streams, i, options.labels, name))
            for i, s in enumerate(scenarios)]
    outcomes = {o.job.args[3]: o
                for o in run_jobs(work, cluster, desc="collect", bar=options.progress)}
    raise_failures(list(outcomes.values()), "nothing written; the finished episodes' percept "
                   "streams are cached for the next try")
    results = [outcomes[i].value for i in range(len(scenarios))]
    total = Collection()
    seconds_p = seconds_f = agree = 0.0
    n_agree = 0
    motion = MotionSamples()
    for scenario, (part, sp, sf, a, n, samples) in zip(scenarios, results, strict=True):
        motion.extend(samples)
        total.lines += part.lines
        total.pairs += part.pairs
        total.weight += part.weight
        total.positive += part.positive
        total.episodes += 1
        total.categories |= part.categories
        total.per_episode[scenario.stem] = part.pairs
        seconds_p += sp
        seconds_f += sf
        agree += a
        n_agree += n
        if progress is not None:
            progress(f"{scenario.stem}: {part.pairs} pairs")
    if total.pairs == 0:
        raise CollectError(f"no occlusion happened in {len(scenarios)} episodes: no anchor was "
                           "hidden while another was perceived; nothing written")
    text = data_text(total, [s.stem for s in scenarios], options.labels, options.command)
    write_atomically(samples_path(options.out), motion.to_json())
    write_atomically(release_path(options.out), release_text(
        motion.rows["carries"], options.command, name="held_" + name))
    write_atomically(options.out, text)
    return CollectReport(
        episodes=total.episodes, pairs=total.pairs, positive=total.positive,
        seconds_perception=seconds_p, seconds_facts=seconds_f,
        seconds_total=time.perf_counter() - started,
        agreement=agree / n_agree if n_agree else None, agreement_pairs=n_agree,
        per_episode=total.per_episode, out=options.out)


