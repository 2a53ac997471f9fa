"""`anchoring train-matching`: learn the anchor matching function from labelled percept streams.

Pairs (anchor state, new percept) are labelled same / different object from the streams'
``truth_id`` (see ``anchoring.training``). Streams are split into training and held-out
streams; an RBF SVM is chosen by a small grid search (validated on held-out training streams),
refitted, scored on the held-out streams, compared with the original ProbAnch model on the same
similarity vectors, and written as JSON (plus a report JSON with every figure).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from anchoring import training
from anchoring.matcher import DEFAULT_MODEL, RbfSvm
from percepts import PerceptFrame, read_percepts

ORIGINAL = Path(__file__).resolve().parents[3].parent / "shared" / "probanch" / "matching_svm.yml"
GRID = [(c, g) for c in (1.0, 10.0, 100.0) for g in (0.5, 2.0, 8.0)]


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("train-matching", help="train the anchor matching function (SVM)",
                       description=__doc__)
    p.add_argument("streams", nargs="*", type=Path, help="percept streams (JSONL) with truth_id")
    p.add_argument("--synthetic", type=int, default=0, metavar="N",
                   help="also use N synthetic streams (anchoring.synthetic)")
    p.add_argument("--out", type=Path, default=DEFAULT_MODEL, help="model file (JSON)")
    p.add_argument("--report", type=Path, default=None,
                   help="figures as JSON (default: OUT with .report.json)")
    p.add_argument("--original", type=Path, default=ORIGINAL,
                   help="the original ProbAnch matching_svm.yml to compare with")
    p.add_argument("--test-fraction", type=float, default=0.3)
    p.add_argument("--max-pairs", type=int, default=6000, help="training pairs after balancing")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--debug", action="store_true")
    p.set_defaults(func=run)


def _streams(args: argparse.Namespace) -> list[tuple[str, list[PerceptFrame]]]:
    out: list[tuple[str, list[PerceptFrame]]] = []
    for path in args.streams:
        frames = list(read_percepts(path))
        if not any(p.truth_id is not None for f in frames for p in f.percepts):
            raise ValueError(f"{path}: no percept carries truth_id: cannot label pairs")
        if len(args.streams) == 1 and not args.synthetic:  # one stream: split it in halves
            half = len(frames) // 2
            out += [(f"{path}[:{half}]", frames[:half]), (f"{path}[{half}:]", frames[half:])]
        else:
            out.append((str(path), frames))
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


def run(args: argparse.Namespace) -> int:
    rng = np.random.default_rng(args.seed)
    streams = _streams(args)
    pairs = [training.labelled_pairs(frames, group=g) for g, (_, frames) in enumerate(streams)]
    order = rng.permutation(len(streams))
    n_test = max(1, int(round(args.test_fraction * len(streams))))
    test_ids, train_ids = sorted(order[:n_test]), sorted(order[n_test:])
    train = training.PairSet.concat(pairs[i] for i in train_ids)
    test = training.PairSet.concat(pairs[i] for i in test_ids)
    if train.y.min(initial=1) == 1 or train.y.max(initial=0) == 0:
        raise ValueError("training pairs have only one label")

    # model selection: validate on a third of the training streams
    val_ids = set(train_ids[:: 3])
    fit_part = training.PairSet.concat(pairs[i] for i in train_ids if i not in val_ids)
    val_part = training.PairSet.concat(pairs[i] for i in train_ids if i in val_ids)
    fit_sub = training.balanced_subsample(fit_part, args.max_pairs, rng)
    tried = []
    for c, g in GRID:
        m = training.fit_svm(fit_sub, c, g)
        s = training.scores(m, val_part)
        balanced = (s["same_recall"] + s["different_recall"]) / 2
        n_sv = int(m.coefficients.size)
        print(f"  C={c:<6g} gamma={g:<4g} validation balanced accuracy {balanced:.4f}, "
              f"{n_sv} support vectors")
        tried.append((balanced, n_sv, c, g))
    # the fewest support vectors (the cost of a frame) among the models within 0.001 of the best
    top = max(t[0] for t in tried)
    _, _, c, g = min((t for t in tried if t[0] >= top - 1e-3), key=lambda t: (t[1], -t[0]))
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
    print(f"trained on {len(train)} pairs from {len(train_ids)} streams "
          f"(C={c:g}, gamma={g:g}, {model.coefficients.size} support vectors)")
    print(f"held-out ({len(test)} pairs, {len(test_ids)} streams): "
          f"accuracy {held['accuracy']:.4f}, "
          f"same-object recall {held['same_recall']:.4f}, "
          f"different-object recall {held['different_recall']:.4f}")
    if args.original and Path(args.original).exists():
        original = RbfSvm.from_opencv_yaml(args.original)
        orig = training.scores(original, test)
        agree = float((original.predict(test.x) == model.predict(test.x)).mean())
        report["original"] = {"path": str(args.original), "held_out": orig, "agreement": agree}
        print(f"original ProbAnch matching_svm.yml on the same pairs: accuracy "
              f"{orig['accuracy']:.4f} (same {orig['same_recall']:.4f}, "
              f"different {orig['different_recall']:.4f}); agreement with ours {agree:.4f}")
    else:
        print(f"(original model {args.original} not found: no comparison)")
    model.info.update({"held_out": held, "streams": len(streams)})
    args.out.parent.mkdir(parents=True, exist_ok=True)
    model.save(args.out)
    report_path = args.report or args.out.with_suffix(".report.json")
    report_path.write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {args.out} and {report_path}")
    return 0
