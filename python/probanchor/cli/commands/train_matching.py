"""`anchoring train-matching`: learn the anchor matching function from labelled percept streams.

Pairs (anchor state, new percept) are labelled same / different object from the streams'
``truth_id`` (see ``anchoring.training``). Streams are split into training and held-out
streams; an RBF SVM is chosen by a small grid search (scikit-learn's ``GridSearchCV``, its
folds whole training streams: ``GroupKFold``), refitted, scored on the held-out streams,
compared with the original ProbAnch model on the same similarity vectors, and written as JSON
(plus a report JSON with every figure).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # imported where used: `anchoring --help` imports no numpy, scipy, anchoring
    import numpy as np
    from sklearn.svm import SVC

    from anchoring import training
    from anchoring.matcher import RbfSvm
    from probanchor.percepts import PerceptFrame

#: The authors' original model, beside the repository (not shipped; run from the repository)
ORIGINAL = Path("..") / "shared" / "probanch" / "matching_svm.yml"
#: The grid of the SVM's C and gamma searched
GRID = {"C": [1.0, 10.0, 100.0], "gamma": [0.5, 2.0, 8.0]}
#: Folds of the grid search (fewer when there are fewer training streams)
FOLDS = 3
#: Models within this much of the best validation balanced accuracy count as equally good
TOLERANCE = 1e-3


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("train-matching", help="train the anchor matching function (SVM)",
                       description=__doc__)
    p.add_argument("streams", nargs="*", type=Path, help="percept streams (JSONL) with truth_id")
    p.add_argument("--scenario", type=Path, action="append", default=[],
                   help="a scenario file to simulate and perceive (repeatable)")
    p.add_argument("--random-scenes", type=int, default=0, metavar="N",
                   help="also simulate and perceive N random table scenes (tabletop)")
    p.add_argument("--save-streams", type=Path, default=None, metavar="DIR",
                   help="write the perceived streams there (JSONL), to train again without "
                        "simulating")
    p.add_argument("--synthetic", type=int, default=0, metavar="N",
                   help="also use N synthetic streams (anchoring.synthetic; no simulator)")
    p.add_argument("--out", type=Path, default=None,
                   help="model file (JSON; default: the shipped model, "
                        "python/anchoring/models/matching_svm.json)")
    p.add_argument("--report", type=Path, default=None,
                   help="figures as JSON (default: OUT with .report.json)")
    p.add_argument("--original", type=Path, default=ORIGINAL,
                   help="the original ProbAnch matching_svm.yml to compare with")
    p.add_argument("--evaluate", type=Path, action="append", default=[], metavar="PATH",
                   help="a stream (.jsonl) or scenario (.yaml) used only for testing, reported "
                        "on its own (repeatable; e.g. the shipped scenarios)")
    p.add_argument("--test-fraction", type=float, default=0.3)
    p.add_argument("--max-pairs", type=int, default=6000, help="training pairs after balancing")
    p.add_argument("--lookalikes", type=float, default=0.5, metavar="FRACTION",
                   help="hard negatives: look-alikes of this fraction of the same-object pairs, "
                        "placed --radius to 0.6 m away (0 for none)")
    p.add_argument("--radius", type=float, default=0.12,
                   help="nearest look-alike distance (m): the matching radius taught")
    p.add_argument("--stale", type=float, default=0.3, metavar="FRACTION",
                   help="copies of this fraction of the same-object pairs seen again after "
                        "1-30 s, still the same object (0 for none)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--show-report", type=Path, default=None, metavar="REPORT",
                   help="print the figures of a saved report (.report.json) as a Markdown "
                        "table and exit")
    p.add_argument("--calibrate", type=Path, default=None, metavar="MODEL",
                   help="only fit the appearance calibration of MODEL (its likelihood ratio "
                        "for the association, docs/anchoring.md) on the streams and scenes "
                        "given, and write it into MODEL's file")
    p.add_argument("--debug", action="store_true")
    p.set_defaults(func=run)


def _streams(args: argparse.Namespace) -> list[tuple[str, list[PerceptFrame]]]:
    import numpy as np

    from probanchor.percepts import read_percepts

    out: list[tuple[str, list[PerceptFrame]]] = []
    for path in args.streams:
        frames = list(read_percepts(path))
        if not any(p.truth_id is not None for f in frames for p in f.percepts):
            raise ValueError(f"{path}: no percept carries truth_id: cannot label pairs")
        alone = len(args.streams) == 1 and not (args.synthetic or scenes_wanted(args))
        if alone:  # one stream: split it in halves
            half = len(frames) // 2
            out += [(f"{path}[:{half}]", frames[:half]), (f"{path}[{half}:]", frames[half:])]
        else:
            out.append((str(path), frames))
    scenes = [(str(path), path) for path in args.scenario]
    scenes += [(f"random-scene-{args.seed}-{k}", k) for k in range(args.random_scenes)]
    for name, what in scenes:
        frames = _perceive(what, args.seed)
        if args.save_streams:
            from probanchor.percepts import write_percepts

            args.save_streams.mkdir(parents=True, exist_ok=True)
            stem = Path(name).stem if isinstance(what, Path) else name
            write_percepts(args.save_streams / f"{stem}.jsonl", frames)
        print(f"  perceived {name}: {len(frames)} frames")
        out.append((name, frames))
    if args.synthetic:
        from anchoring import synthetic

        rng = np.random.default_rng(args.seed)
        for k in range(args.synthetic):
            seed = 1000 * args.seed + k
            out.append((f"synthetic:{seed}", synthetic.stream(
                seed, n_objects=int(rng.integers(3, 8)), seconds=20.0,
                occlusion_rate=float(rng.choice([0.0, 0.05, 0.1])))))
    if len(out) < 2:
        raise ValueError("need at least two streams (or one to split, or --synthetic N)")
    return out


def report_table(report: dict) -> str:
    """The figures of a training report as a Markdown table (ours vs the original)."""
    orig = report.get("original", {})
    rows = [("| pairs | ours | original ProbAnch SVM |"), ("|---|---|---|")]

    def fmt(d: dict | None, key: str) -> str:
        return f"{d[key]:.4f}" if d and key in d else "-"

    held, oh = report["held_out"], orig.get("held_out")
    rows.append(f"| held-out streams ({report['test_pairs']} pairs, "
                f"{report['test_positives']} same-object): accuracy | "
                f"{fmt(held, 'accuracy')} | {fmt(oh, 'accuracy')} |")
    rows.append(f"| same-object recall | {fmt(held, 'same_recall')} | {fmt(oh, 'same_recall')} |")
    rows.append(f"| different-object recall | {fmt(held, 'different_recall')} | "
                f"{fmt(oh, 'different_recall')} |")
    if "held_out_lookalikes" in report:
        look = report["held_out_lookalikes"]
        rows.append(f"| look-alikes 0.12-0.6 m away ({look['pairs']}) rejected | "
                    f"{look['rejected']:.4f} | "
                    f"{fmt(orig, 'held_out_lookalikes_rejected')} |")
    if "held_out_stale" in report:
        stale = report["held_out_stale"]
        rows.append(f"| same object seen again after 1-30 s ({stale['pairs']}) accepted | "
                    f"{stale['accepted']:.4f} | {fmt(orig, 'held_out_stale_accepted')} |")
    if "agreement" in orig:
        rows.append(f"| agreement ours / original (held-out pairs) | {orig['agreement']:.4f} | |")
    ev = report.get("evaluate")
    if ev:
        names = ", ".join(Path(p).stem for p in ev["paths"])
        rows.append(f"| {names}: accuracy | {fmt(ev['ours'], 'accuracy')} | "
                    f"{fmt(ev.get('original'), 'accuracy')} |")
        rows.append(f"| same-object recall | {fmt(ev['ours'], 'same_recall')} | "
                    f"{fmt(ev.get('original'), 'same_recall')} |")
        rows.append(f"| different-object recall | {fmt(ev['ours'], 'different_recall')} | "
                    f"{fmt(ev.get('original'), 'different_recall')} |")
        if "agreement" in ev:
            rows.append(f"| agreement ours / original | {ev['agreement']:.4f} | |")
    rows.append(f"\nTraining pairs: {report['train_pairs']} ({report['train_positives']} "
                f"same-object; stale and look-alike copies included) of "
                f"{len(report['streams']) - len(report['test_streams'])} streams, a balanced "
                f"sample of which fits the SVM; C = {report['C']:g}, gamma = "
                f"{report['gamma']:g}, {report['support_vectors']} support vectors.")
    return "\n".join(rows)


def run(args: argparse.Namespace) -> int:
    if args.show_report:
        try:
            report = json.loads(args.show_report.read_text(encoding="utf-8"))
        except (OSError, json.JSONDecodeError) as exc:
            raise ValueError(f"{args.show_report}: cannot read report: {exc}") from exc
        print(report_table(report))
        return 0
    import numpy as np

    from anchoring import training
    from anchoring.matcher import DEFAULT_MODEL, RbfSvm

    if args.out is None:
        args.out = DEFAULT_MODEL
    rng = np.random.default_rng(args.seed)
    if args.calibrate is not None:
        return _calibrate_only(args)
    streams = _streams(args)
    pairs = [training.labelled_pairs(frames, group=g) for g, (_, frames) in enumerate(streams)]
    order = rng.permutation(len(streams))
    n_test = max(1, int(round(args.test_fraction * len(streams))))
    test_ids, train_ids = sorted(order[:n_test]), sorted(order[n_test:])
    # hard negatives, per stream (so they split with their stream), kept apart for the report
    looks = []
    for p in pairs:  # stale copies first, so that look-alikes also come with long gaps
        extra = [training.stale_positives(p, rng, args.stale)] \
            if args.stale > 0 and p.y.any() else []
        both = training.PairSet.concat([p, *extra])
        if args.lookalikes > 0 and p.y.any():
            extra.append(training.lookalike_negatives(both, rng, args.lookalikes, args.radius))
        looks.append(training.PairSet.concat(extra))
    train = training.PairSet.concat([pairs[i] for i in train_ids] + [looks[i] for i in train_ids])
    test = training.PairSet.concat(pairs[i] for i in test_ids)
    test_looks = training.PairSet.concat(looks[i] for i in test_ids)
    if train.y.min(initial=1) == 1 or train.y.max(initial=0) == 0:
        raise ValueError("training pairs have only one label")

    c, g = choose_parameters(train, args.max_pairs, rng)
    model = training.fit_svm(training.balanced_subsample(train, args.max_pairs, rng), c, g)
    held = training.scores(model, test)
    report: dict = {
        "streams": [name for name, _ in streams],
        "test_streams": [streams[i][0] for i in test_ids],
        "train_pairs": len(train), "train_positives": int(train.y.sum()),
        "test_pairs": len(test), "test_positives": int(test.y.sum()),
        "C": c, "gamma": g, "support_vectors": int(model.coefficients.size),
        "held_out": held,
    }
    if len(test_looks):
        neg, pos = test_looks.y == 0, test_looks.y == 1
        pred = model.predict(test_looks.x)
        report["held_out_lookalikes"] = {"pairs": int(neg.sum()),
                                         "rejected": float((pred[neg] == 0).mean())}
        if pos.any():
            report["held_out_stale"] = {"pairs": int(pos.sum()),
                                        "accepted": float((pred[pos] == 1).mean())}
    print(f"trained on {len(train)} pairs from {len(train_ids)} streams "
          f"(C={c:g}, gamma={g:g}, {model.coefficients.size} support vectors)")
    print(f"held-out ({len(test)} pairs, {len(test_ids)} streams): "
          f"accuracy {held['accuracy']:.4f}, "
          f"same-object recall {held['same_recall']:.4f}, "
          f"different-object recall {held['different_recall']:.4f}")
    if len(test_looks):
        print(f"held-out look-alikes ({report['held_out_lookalikes']['pairs']}: a same-object "
              f"pair moved {args.radius:g}-0.6 m away) rejected: "
              f"{report['held_out_lookalikes']['rejected']:.4f}")
    if "held_out_stale" in report:
        print(f"held-out stale same-object pairs ({report['held_out_stale']['pairs']}: seen "
              f"again after 1-30 s) accepted: {report['held_out_stale']['accepted']:.4f}")
    if args.original and Path(args.original).exists():
        original = RbfSvm.from_opencv_yaml(args.original)
        orig = training.scores(original, test)
        agree = float((original.predict(test.x) == model.predict(test.x)).mean())
        report["original"] = {"path": str(args.original), "held_out": orig, "agreement": agree}
        print(f"original ProbAnch matching_svm.yml on the same pairs: accuracy "
              f"{orig['accuracy']:.4f} (same {orig['same_recall']:.4f}, "
              f"different {orig['different_recall']:.4f}); agreement with ours {agree:.4f}")
        if len(test_looks):
            opred = original.predict(test_looks.x)
            neg, pos = test_looks.y == 0, test_looks.y == 1
            report["original"]["held_out_lookalikes_rejected"] = float((opred[neg] == 0).mean())
            print(f"original on the look-alikes: rejected "
                  f"{report['original']['held_out_lookalikes_rejected']:.4f}")
            if pos.any():
                report["original"]["held_out_stale_accepted"] = float((opred[pos] == 1).mean())
                print(f"original on the stale pairs: accepted "
                      f"{report['original']['held_out_stale_accepted']:.4f}")
    else:
        print(f"(original model {args.original} not found: no comparison)")
    # the appearance decision's likelihood ratio, fitted on the held-out streams' pairs
    model.info["appearance_calibration"] = training.appearance_calibration(model, test)
    model.info.update({"held_out": held, "streams": len(streams)})
    args.out.parent.mkdir(parents=True, exist_ok=True)
    model.save(args.out)
    report_path = args.report or args.out.with_suffix(".report.json")
    report_path.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {args.out} and {report_path}")
    if args.evaluate:
        report["evaluate"] = _evaluate(args, model)
        report_path.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    return 0


def choose_parameters(train: training.PairSet, max_pairs: int,
                      rng: np.random.Generator) -> tuple[float, float]:
    """C and gamma of the RBF SVM, by a grid search over :data:`GRID` (``GridSearchCV``).

    The folds are whole streams (``GroupKFold`` on the pairs' ``group``, :data:`FOLDS` of them
    or one per training stream when there are fewer): each candidate is fitted on a balanced
    sample of at most ``max_pairs`` pairs of the other folds, as the final model is, and scored
    by its balanced accuracy on every pair of the held-out fold. Of the candidates within
    :data:`TOLERANCE` of the best mean score, the one with the fewest support vectors (the cost
    of a frame) is taken; ties go to the better score, then to the earlier in the grid.

    Raises
    ------
    ValueError
        Fewer than two training streams: no fold to validate on.
    """
    import numpy as np
    from sklearn.model_selection import GridSearchCV, GroupKFold
    from sklearn.svm import SVC

    from anchoring import training

    streams = np.unique(train.group)
    if streams.size < 2:
        raise ValueError("the grid search needs at least two training streams")
    folds = []
    for fit, held in GroupKFold(n_splits=min(FOLDS, streams.size)).split(
            train.x, train.y, train.group):
        part = training.PairSet(train.x[fit], train.y[fit], fit)   # group: the pair's index
        folds.append((training.balanced_subsample(part, max_pairs, rng).group, held))
    search = GridSearchCV(
        SVC(kernel="rbf", class_weight="balanced"), GRID, cv=folds,
        scoring={"balanced": "balanced_accuracy", "support_vectors": _support_vectors},
        refit=_fewest_support_vectors, n_jobs=1)
    search.fit(train.x, train.y)
    results = search.cv_results_
    for k, params in enumerate(results["params"]):
        print(f"  C={params['C']:<6g} gamma={params['gamma']:<4g} validation balanced "
              f"accuracy {results['mean_test_balanced'][k]:.4f}, "
              f"{results['mean_test_support_vectors'][k]:.0f} support vectors")
    best = results["params"][search.best_index_]
    return float(best["C"]), float(best["gamma"])


def _support_vectors(estimator: SVC, x: np.ndarray, y: np.ndarray) -> float:
    """A scorer of ``GridSearchCV`` that reports the fitted SVM's number of support vectors."""
    return float(estimator.n_support_.sum())


def _fewest_support_vectors(results: dict) -> int:
    """``GridSearchCV``'s ``refit`` rule: the index of the candidate with the fewest support
    vectors among those within :data:`TOLERANCE` of the best mean balanced accuracy."""
    import numpy as np

    score = np.asarray(results["mean_test_balanced"])
    vectors = np.asarray(results["mean_test_support_vectors"])
    good = np.flatnonzero(score >= score.max() - TOLERANCE)
    return int(min(good, key=lambda k: (vectors[k], -score[k], k)))


def _calibrate_only(args: argparse.Namespace) -> int:
    """--calibrate MODEL: the appearance calibration of an existing model, on the pairs of
    the streams and scenes given (none of them used to train it, preferably)."""
    from anchoring import training
    from anchoring.matcher import RbfSvm

    model = RbfSvm.load(args.calibrate)
    args.streams = list(args.streams)
    streams = _streams(args)
    pairs = training.PairSet.concat(training.labelled_pairs(frames, group=g)
                                    for g, (_, frames) in enumerate(streams))
    calibration = training.appearance_calibration(model, pairs)
    model.info["appearance_calibration"] = calibration
    model.save(args.calibrate)
    rho = calibration["lookalike"]
    bound = f"A at most {1.0 / rho:.1f}" if rho >= 1e-6 else "A without bound"
    print(f"appearance calibration of {args.calibrate} on {calibration['pairs']} pairs from "
          f"{len(streams)} streams: log A0 = {calibration['scale']:.3f} d "
          f"{calibration['offset']:+.3f} against a distinct-looking object, a share "
          f"{rho:.4g} of look-alikes: {bound}")
    return 0


def _evaluate(args: argparse.Namespace, model: RbfSvm) -> dict:
    from anchoring import training
    from anchoring.matcher import RbfSvm
    from probanchor.percepts import read_percepts

    original = RbfSvm.from_opencv_yaml(args.original) if args.original and \
        Path(args.original).exists() else None
    sets = []
    for path in args.evaluate:
        if path.suffix in (".yaml", ".yml"):
            frames = _perceive(path, args.seed)
        else:
            frames = list(read_percepts(path))
        sets.append(training.labelled_pairs(frames, group=len(sets)))
    pairs = training.PairSet.concat(sets)
    out: dict = {"paths": [str(p) for p in args.evaluate], "ours": training.scores(model, pairs)}
    print(f"evaluation streams ({len(pairs)} pairs): ours accuracy {out['ours']['accuracy']:.4f} "
          f"(same {out['ours']['same_recall']:.4f}, "
          f"different {out['ours']['different_recall']:.4f})")
    if original is not None:
        out["original"] = training.scores(original, pairs)
        out["agreement"] = float((original.predict(pairs.x) == model.predict(pairs.x)).mean())
        print(f"  original accuracy {out['original']['accuracy']:.4f} "
              f"(same {out['original']['same_recall']:.4f}, "
              f"different {out['original']['different_recall']:.4f}); "
              f"agreement {out['agreement']:.4f}")
    return out


def scenes_wanted(args: argparse.Namespace) -> bool:
    return bool(args.scenario or args.random_scenes)


def _perceive(what: Path | int, seed: int) -> list[PerceptFrame]:
    """Simulate and perceive a scenario file, or random scene number ``what``."""
    from probanchor.loop.sources import perceive_scenario
    from probanchor.tabletop.generate import random_scene

    scenario = what if isinstance(what, Path) else random_scene(1000 * seed + what)
    return list(perceive_scenario(scenario, seed=seed))
